"""The disturbance class of Part II (chapters 'fixed_controllers' and 'disturbance_law'): seeded
non-stationary draws, the law's decision grid and tuning grid, the gentle gain K0 of the
realization through copies, and the dwell certificate of the paper's FDSC pair. The runs are in
:mod:`fdsc.paper.pays.disturbance_law_runs`, the designs in :mod:`fdsc.paper.pays.fixed_designs`.
"""

import functools
import math
from dataclasses import dataclass

import numpy as np

import fdsc
from fdsc._validation import as_choice
from fdsc.paper.pays.generic_example import generic_example
from fdsc.paper.reproduced.paper_cases import aircraft_example
from fdsc.paper.shared.cache import cached

__all__ = ["SEED", "LAMBDAS", "HYSTERESES", "DECIDE_EVERY", "RESTART", "NOISE_SHARE", "NOISE_TONES",
           "IDEAL_PAIR", "MIN_LENGTH", "MEAN_EXTRA", "Draw", "draw", "lqr", "certificate", "seeded_draw",
           "segment_class"]

SEED = 32
#: The tuning grid of the laws (on the training half): forgetting λ (1/s) and hysteresis h.
LAMBDAS, HYSTERESES = (0.05, 0.2, 1.0), (0.1, 0.3, 1.0)
#: The law's decision interval and restart period (s).
DECIDE_EVERY, RESTART = 0.1, 20.0
#: Probability that a segment is band-limited noise, and its tones per band.
NOISE_SHARE, NOISE_TONES = 0.25, 6
#: A segment's length: this many seconds plus an exponential time of mean :data:`MEAN_EXTRA`.
MIN_LENGTH, MEAN_EXTRA = 20.0, 80.0
#: The fixed gains the ideal segment law holds on LF- and HF-dominated pieces.
IDEAL_PAIR = ("PassC-LF", "PassC-HF")


@functools.cache
def _example(name):
    as_choice("example", name, ("aircraft", "generic"))
    return aircraft_example() if name == "aircraft" else generic_example()


@dataclass(frozen=True)
class Draw:
    """One non-stationary disturbance (see :func:`draw`).

    Parameters
    ----------
    d : fdsc.Piecewise
    horizon : float
        Run length (s): the end of the last segment, up to the next decision point.
    dominant : tuple of str
        "LF" or "HF" per segment.
    noise : tuple of bool
        Whether each segment is band-limited noise.
    """

    d: fdsc.Piecewise
    horizon: float
    dominant: tuple
    noise: tuple

    @property
    def changes(self) -> int:
        """Changes of the dominating band between consecutive segments."""
        return int(sum(a != b for a, b in zip(self.dominant[:-1], self.dominant[1:], strict=True)))


def draw(example, rng: np.random.Generator, *, length_scale: float = 1.0, alpha=(0.8, 1.0),
         noise_share: float = NOISE_SHARE, noise_tones: int = NOISE_TONES) -> Draw:
    """One seeded non-stationary disturbance of the module docstring's distribution.

    Six to ten segments of 20 s plus an exponential time of mean 80 s (both times
    ``length_scale``), each LF- or HF-dominated with even odds, its dominating band carrying a
    share α of its power drawn uniformly in ``alpha``; a segment is three tones per band, or
    with probability ``noise_share`` band-limited noise (``noise_tones`` tones per band with
    Rayleigh amplitudes and random phases).

    Parameters
    ----------
    example : Example
    rng : numpy.random.Generator
    length_scale : float, optional
        The segments' lengths times this (the class's variants: 4× shorter or longer).
    alpha : (float, float), optional
        The range of the dominating band's share of the power.
    noise_share : float, optional
        The probability that a segment is band-limited noise.
    noise_tones : int, optional
        Tones per band of a noise segment.

    Returns
    -------
    Draw

    Examples
    --------
    >>> dr = draw(aircraft_example(), np.random.default_rng(0))
    >>> 6 <= len(dr.dominant) <= 10, [round(p.power(), 12) for p in dr.d.parts][:2]
    (True, [1.0, 1.0])
    """
    k = int(rng.integers(6, 11))
    lengths = np.round(length_scale * (MIN_LENGTH + rng.exponential(MEAN_EXTRA, k)) * 100.0) / 100.0
    parts, dom, noise = [], [], []
    for _ in range(k):
        lf = bool(rng.random() < 0.5)
        share_dom = rng.uniform(alpha[0], alpha[1])
        is_noise = bool(rng.random() < noise_share)
        m = noise_tones if is_noise else 3
        sums = []
        for (lo, hi), share in ((example.lf_tones, share_dom if lf else 1 - share_dom),
                                (example.hf_tones, 1 - share_dom if lf else share_dom)):
            w = np.exp(rng.uniform(np.log(lo), np.log(hi), m))
            a = rng.rayleigh(1.0, m) if is_noise else rng.uniform(0.5, 1.5, m)
            a = a * np.sqrt(share / (0.5 * np.sum(a**2)))
            sums.append(fdsc.Sinusoids(a, w, rng.uniform(0.0, 2 * np.pi, m)))
        parts.append(sums[0] + sums[1])
        dom.append("LF" if lf else "HF")
        noise.append(is_noise)
    breaks = np.round(np.r_[0.0, np.cumsum(lengths)] * 100.0) / 100.0
    horizon = math.ceil(breaks[-1] / DECIDE_EVERY - 1e-9) * DECIDE_EVERY
    return Draw(fdsc.Piecewise(breaks, parts), round(horizon, 6), tuple(dom), tuple(noise))


def segment_class(example: str, length_scale: float = 1.0) -> fdsc.SegmentClass:
    """The class of :func:`draw` as its second-order statistics see it (:class:`fdsc.SegmentClass`).

    A segment's tones are log-uniform in the example's LF and HF tone ranges, each band with a
    mean half of the power (LF-dominated segments, with a share α of it, and HF-dominated ones,
    with 1 − α, are equally likely), and the tones of a noise segment have the same law of
    frequency and the same expected share each; a segment's power is 1 and its length
    ``length_scale · (20 + Exp(80))`` s.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    length_scale : float, optional

    Returns
    -------
    fdsc.SegmentClass
    """
    ex = _example(example)
    return fdsc.SegmentClass([ex.lf_tones, ex.hf_tones], [0.5, 0.5], power=1.0,
                             min_length=length_scale * MIN_LENGTH, mean_extra=length_scale * MEAN_EXTRA)


def seeded_draw(example: str, index: int, seed: int = SEED) -> tuple:
    """``(Example, Draw)``: draw ``index`` of the seeded sequence of an example.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    index : int
    seed : int, optional

    Returns
    -------
    (Example, Draw)
    """
    ex = _example(example)
    return ex, draw(ex, np.random.default_rng([seed, index]))


def lqr(example: str = "aircraft") -> np.ndarray:
    """K0 of the realization through copies: the LQR gain of (A, B2, C, D2).

    Parameters
    ----------
    example : {"aircraft", "generic"}

    Returns
    -------
    (m_u, n) ndarray
    """
    return fdsc.lqr_gain(_example(example).plant)


@functools.cache
@cached
def certificate(example: str = "aircraft"):
    """The Geromel–Colaneri dwell time of the FDSC pair's closed loops (PassC-LF, PassC-HF):
    what the direct realization of a law switching between them would have to enforce.

    Parameters
    ----------
    example : {"aircraft", "generic"}

    Returns
    -------
    fdsc.DwellCertificate or None
        None if no dwell time up to 10⁴ s is certified.
    """
    ex = _example(example)
    loops = [ex.closed_loop(n) for n in IDEAL_PAIR]
    try:
        return fdsc.geromel_colaneri_dwell(loops, tau_max=1e4)
    except fdsc.SolverError:
        return None


