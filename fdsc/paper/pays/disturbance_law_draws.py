"""The draws, candidates and runs of chapter 'disturbance_law' (see
:mod:`fdsc.paper.pays.disturbance_law`, which re-exports every name here): the seeded non-stationary
disturbances, the Pareto front and the law's candidates, one draw under every controller, and one
draw under a chosen law for the chapter's figure. The runs under errors of the estimate are in
:mod:`fdsc.paper.pays.disturbance_law_robust`.
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
from fdsc.paper.shared.comparators import comparators

__all__ = ["SEED", "LAMBDAS", "HYSTERESES", "DECIDE_EVERY", "RESTART", "NOISE_SHARE", "NOISE_TONES",
           "IDEAL_PAIR", "FRONT_FRACTIONS", "FRONT_MAXITER", "Draw", "draw", "front", "candidates",
           "lqr", "certificate", "draw_result", "fixed_gain", "LawRun", "law_run", "direct_realization",
           "law_supervisor", "seeded_draw"]

SEED = 32
#: The tuning grid (on the training half).
LAMBDAS, HYSTERESES = (0.05, 0.2, 1.0), (0.1, 0.3)
#: The law's decision interval and restart period (s).
DECIDE_EVERY, RESTART = 0.1, 20.0
#: Probability that a segment is band-limited noise, and its tones per band.
NOISE_SHARE, NOISE_TONES = 0.25, 6
#: The fixed gains the ideal segment law holds on LF- and HF-dominated pieces.
IDEAL_PAIR = ("PassC-LF", "PassC-HF")
#: Bounds on the LF peak of the Pareto front, as fractions of the way (in log) from the LF
#: design's LF peak to the H∞ design's.
FRONT_FRACTIONS = (0.0, 0.5, 1.0)
#: Nelder–Mead iterations per start of the front's search (the peaks agree with 400 to 4 digits).
FRONT_MAXITER = 200


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


def draw(example, rng: np.random.Generator) -> Draw:
    """One seeded non-stationary disturbance of the module docstring's distribution.

    Parameters
    ----------
    example : Example
    rng : numpy.random.Generator

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
    lengths = np.round((20.0 + rng.exponential(80.0, k)) * 100.0) / 100.0
    parts, dom, noise = [], [], []
    for _ in range(k):
        lf = bool(rng.random() < 0.5)
        alpha = rng.uniform(0.8, 1.0)
        is_noise = bool(rng.random() < NOISE_SHARE)
        m = NOISE_TONES if is_noise else 3
        sums = []
        for (lo, hi), share in ((example.lf_tones, alpha if lf else 1 - alpha),
                                (example.hf_tones, 1 - alpha if lf else alpha)):
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


@functools.cache
@cached
def front(example: str = "aircraft") -> fdsc.ParetoFront:
    """The multi-band Pareto front of the example: least HF peak with the LF peak at most β, β
    from the LF design's LF peak to the H∞ design's (:data:`FRONT_FRACTIONS`, in log).

    Parameters
    ----------
    example : {"aircraft", "generic"}

    Returns
    -------
    fdsc.ParetoFront
    """
    ex = _example(example)
    lo = fdsc.band_peak(ex.closed_loop("PassC-LF"), ex.bands["LF"]).gamma
    hi = fdsc.band_peak(ex.closed_loop("PassC-EF"), ex.bands["LF"]).gamma
    lo, hi = min(lo, hi) * 1.02, max(lo, hi)
    betas = [lo * (hi / lo) ** f for f in FRONT_FRACTIONS]
    return fdsc.pareto_front(ex.plant, ex.bands["HF"], ex.bands["LF"], betas, maxiter=FRONT_MAXITER)


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


def candidates(example: str = "aircraft") -> tuple:
    """The law's candidates: the fixed gains of the comparator set whose copies can predict their
    cost, and the Pareto front's points.

    A copy restarted every :data:`RESTART` seconds cannot see the cost of a loop whose slowest
    mode has a longer time constant (its response is still building up when the copy restarts),
    so such a loop looks cheap while it is quiet: it is left out (the generic example's open loop,
    with a resonance of time constant about 50 s, and the aircraft's PassC-HF, with a pole at
    −0.0165 /s). Every gain stays a fixed baseline.

    Parameters
    ----------
    example : {"aircraft", "generic"}

    Returns
    -------
    names : tuple of str
        ``"front 1"`` … in increasing order of the LF bound after the comparator set.
    gains : tuple of ndarray
    """
    ex = _example(example)
    names = [n for n in comparators(example) if _time_constant(ex.closed_loop(n)) <= RESTART]
    gains = [ex.gains[n] for n in names]
    for j, K in enumerate(front(example).gains()):
        names.append(f"front {j + 1}")
        gains.append(K)
    return tuple(names), tuple(gains)


def _time_constant(loop):
    """1 / (the least |Re λ| of the loop's poles), in s."""
    return 1.0 / float(np.min(np.abs(np.linalg.eigvals(loop.A).real)))


def fixed_gain(example: str, name: str) -> np.ndarray:
    """A fixed gain of the study by name: a member of the comparator set or a front point.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    name : str

    Returns
    -------
    (m_u, n) ndarray
    """
    ex = _example(example)
    if name in ex.gains:
        return ex.gains[name]
    names, gains = candidates(example)
    return gains[names.index(name)]


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


def _configs(example):
    """The tuning grid: (law, realization, λ, h). Every law is realized through copies (with
    K0 the LQR gain), which is stable for any switching on the decision grid; the direct
    realization turns a switch to a high gain into a spike of u (the chapter shows one)."""
    return [(law, "copies", lam, h) for law in ("cost", "band_power") for lam in LAMBDAS
            for h in HYSTERESES]


def draw_result(example: str, index: int, seed: int = SEED) -> dict:
    """Every controller on draw ``index`` of the seeded sequence.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    index : int
        The draw (its generator is seeded by ``[seed, index]``, so draws do not depend on which
        others are computed, nor where).
    seed : int, optional

    Returns
    -------
    dict
        Plain and picklable: ``fixed`` (energy of each candidate held throughout), ``oracle``
        (the clairvoyant per-segment oracle), ``ideal`` (the ideal segment law), ``runs``
        (``{"law/realization/λ/h": (energy, switches, diverged)}``), ``changes``,
        ``segments``, ``horizon``, ``input_energy``.
    """
    ex, dr = seeded_draw(example, index, seed)
    names, gains = candidates(example)
    K0 = lqr(example)
    sup = fdsc.Supervisor(ex.plant, gains, decide_every=DECIDE_EVERY, restart=RESTART)
    prep = sup.prepare(dr.d, dr.horizon)
    fixed = {n: prep.fixed(i) for i, n in enumerate(names)}
    for n in comparators(example):
        if n not in fixed:                     # a baseline the law does not switch to
            fixed[n] = prep.energy_of(ex.closed_loop(n))
    oracle, _choice = prep.clairvoyant()
    pair_gains = [fixed_gain(example, n) for n in IDEAL_PAIR]
    dom = {}
    for (t0, _t1, *_r), k in zip(prep.grid.pieces, range(len(prep.grid.pieces)), strict=True):
        j = int(np.searchsorted(dr.d.breaks, t0 + 1e-9, side="right") - 1)
        dom[k] = dr.dominant[j] if 0 <= j < len(dr.dominant) else "LF"
    pair = fdsc.Supervisor(ex.plant, pair_gains, law="band_power",
                           bands=[ex.bands["LF"], ex.bands["HF"]], decide_every=DECIDE_EVERY,
                           restart=RESTART).prepare(dr.d, dr.horizon)
    # the ideal segment law: PassC-LF on LF-dominated pieces, PassC-HF on HF ones (the pair's loops)
    ideal = pair.segment_law([0 if dom[k] == "LF" else 1 for k in range(len(pair.grid.pieces))])
    preps = {("cost", "copies"): prep.with_K0(K0), ("band_power", "copies"): pair.with_K0(K0)}
    runs = {}
    for law, real, lam, h in _configs(example):
        r = preps[(law, real)].run(forgetting=lam, hysteresis=h)
        runs[f"{law}/{real}/{lam:g}/{h:g}"] = (r.energy, r.switches, r.diverged_at is not None)
    return {"index": index, "horizon": dr.horizon, "changes": dr.changes, "segments": len(dr.dominant),
            "fixed": fixed, "oracle": oracle, "ideal": ideal, "runs": runs,
            "input_energy": prep.input_energy}


def law_supervisor(example: str, law: str) -> tuple:
    """The supervisor of a setting ``law/realization/λ/h``.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    law : str

    Returns
    -------
    sup : fdsc.Supervisor
        The cost law over the candidates, or the band-power law over the ideal pair.
    names : tuple of str
        Its gains' names.
    forgetting, hysteresis : float
    """
    ex = _example(example)
    kind, real, lam, h = law.split("/")
    K0 = lqr(example) if real == "copies" else None
    if kind == "cost":
        names, gains = candidates(example)
        sup = fdsc.Supervisor(ex.plant, gains, decide_every=DECIDE_EVERY, restart=RESTART, K0=K0)
    else:
        names = IDEAL_PAIR
        sup = fdsc.Supervisor(ex.plant, [fixed_gain(example, n) for n in names], law="band_power",
                              bands=[ex.bands["LF"], ex.bands["HF"]], decide_every=DECIDE_EVERY,
                              restart=RESTART, K0=K0)
    return sup, tuple(names), float(lam), float(h)


@dataclass(frozen=True)
class LawRun:
    """One draw under the chosen law, for the chapter's figure (see :func:`law_run`).

    Parameters
    ----------
    draw : Draw
    names : tuple of str
        The candidates.
    run : fdsc.SupervisedRun
        With the monitoring signals.
    ratio : float
        Its energy over the fixed gain chosen in advance's.
    """

    draw: Draw
    names: tuple
    run: fdsc.SupervisedRun
    ratio: float


def law_run(example: str, index: int, law: str, fixed_in_advance: str, seed: int = SEED) -> LawRun:
    """Draw ``index`` of the seeded sequence under a law, with its monitoring signals.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    index : int
    law : str
        ``law/realization/λ/h``.
    fixed_in_advance : str
        The candidate whose energy the run is divided by.
    seed : int, optional

    Returns
    -------
    LawRun
    """
    ex, dr = seeded_draw(example, index, seed)
    sup, shown, lam, h = law_supervisor(example, law)
    prep = sup.prepare(dr.d, dr.horizon)
    r = prep.run(forgetting=lam, hysteresis=h)
    ref = prep.energy_of(ex.plant.closed_loop(fixed_gain(example, fixed_in_advance)))
    return LawRun(dr, tuple(shown), r, r.energy / ref)


def direct_realization(example: str, index: int, law: str, seed: int = SEED) -> dict:
    """The chosen cost law on draw ``index`` realized directly (u = K_σ x) with the
    Geromel–Colaneri dwell time of the candidates enforced, against its realization through
    copies.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    index : int
    law : str
        ``cost/realization/λ/h`` (the realization is replaced).
    seed : int, optional

    Returns
    -------
    dict
        ``dwell`` (s, None if none was certified up to 10³ s), ``direct`` and ``copies``
        (energies), ``direct_switches``, ``copies_switches``.
    """
    ex, dr = seeded_draw(example, index, seed)
    names, gains = candidates(example)
    _kind, _real, lam, h = law.split("/")
    loops = [ex.plant.closed_loop(K) for K in gains]
    try:
        tau = fdsc.geromel_colaneri_dwell(loops, tau_max=1e3).tau
    except fdsc.SolverError:
        tau = None
    prep = fdsc.Supervisor(ex.plant, gains, decide_every=DECIDE_EVERY, restart=RESTART).prepare(
        dr.d, dr.horizon)
    direct = prep.run(forgetting=float(lam), hysteresis=float(h), min_dwell=tau or 0.0)
    copies = prep.with_K0(lqr(example)).run(forgetting=float(lam), hysteresis=float(h))
    return {"dwell": tau, "direct": direct.energy, "copies": copies.energy,
            "direct_switches": direct.switches, "copies_switches": copies.switches}
