"""Chapter 'frequency_ranges', continued: the dominance degrees of Definitions 2 and 3.

The dominance degree of each range for the paper's disturbances as the range's parameter ρ
varies, and the localized dominance (Definition 3) of the piecewise disturbance over time.
"""

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from fdsc._validation import as_positive, as_vector, frozen_array
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.data import mixed_disturbance, paper_bands, paper_data, piecewise_disturbance
from fdsc.paper.shared.prose import count, num
from fdsc.paper.shared.results import RecordPart, entry
from fdsc.signals import dominance_degree, localized_dominance

__all__ = [
    "DominanceVsRho", "PiecewiseDominance", "dominance_vs_rho", "localized_dominance_piecewise",
]


def _length(x):
    """A length or duration as the prose prints it: whole numbers without decimals."""
    x = float(x)
    return count(int(x)) if x.is_integer() else num(x)


# -- dominance degrees (Definitions 2 and 3) ----------------------------------------------------

@dataclass(frozen=True)
class DominanceVsRho:
    """α(Ω_3) of the mixed disturbance ``d_h + ρ_p d_l`` over ρ_p (see :func:`dominance_vs_rho`).

    Parameters
    ----------
    rho_p : (k,) ndarray
        Values of ρ_p.
    exact : (k,) ndarray
        Closed form from the mean powers of the tones.
    fft : (k,) ndarray
        Estimate from the FFT of a sampled record (Hann taper).
    horizon, dt : float
        Record length and sampling step of the FFT estimate in s.
    """

    rho_p: np.ndarray
    exact: np.ndarray
    fft: np.ndarray
    horizon: float
    dt: float

    @property
    def max_fft_error(self) -> float:
        """Largest ``|fft − exact|`` over ρ_p."""
        return float(np.max(np.abs(self.fft - self.exact)))

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``alpha_fft_err`` (largest FFT error), ``alpha_at_half`` (α(Ω_3)
            at the largest ρ_p), ``horizon``.
        """
        return {"alpha_fft_err": num(self.max_fft_error, 2), "alpha_at_half": num(float(self.exact[-1])),
                "horizon": _length(self.horizon)}

    def to_record(self) -> RecordPart:
        """Record entry ``alpha_mixed`` (new): α(Ω_3) over the ρ_p range of paper Fig. 7.

        Returns
        -------
        RecordPart
        """
        return RecordPart((entry(
            "alpha_mixed", "Definition 2 on the mixed disturbance d_h + rho_p d_l of paper Fig. 7",
            None, {"rho_p": self.rho_p, "exact": self.exact, "fft": self.fft},
            "new",
            f"dominance degree of Ω_3, exact from the mean powers (1/(1 + ρ_p²)) and by "
            f"the FFT of a {self.horizon:g} s record (Hann), which agrees within "
            f"{self.max_fft_error:.1e}; at rho_p = {self.rho_p[-1]:g} the disturbance is still "
            f"HF-dominated (alpha = {self.exact[-1]:.3f}).", horizon=self.horizon, dt=self.dt),))


@cached
def dominance_vs_rho(rhos: ArrayLike | None = None, *, horizon: float | None = None,
                     dt: float = 2e-3) -> DominanceVsRho:
    """α(Ω_3) of the mixed disturbance ``d_h + ρ_p d_l`` (paper Fig. 7): exact and by FFT.

    Parameters
    ----------
    rhos : (k,) array_like, optional
        Values of ρ_p (default: 11 points over the paper's range [0, 0.5]).
    horizon : float, optional
        Record length of the FFT estimate in s (default the paper's t ∈ [0, 500]).
    dt : float, optional
        Sampling step of the record in s.

    Returns
    -------
    DominanceVsRho

    Examples
    --------
    >>> r = dominance_vs_rho((0.0, 0.5))
    >>> [round(float(a), 6) for a in r.exact], r.max_fft_error < 1e-4
    ([1.0, 0.8], True)
    """
    sim = paper_data("simulation")
    rhos = np.linspace(*sim["rho_p_range"]["value"], 11) if rhos is None else rhos
    rhos = as_vector("rhos", rhos)
    horizon = sim["mixed_horizon"]["value"] if horizon is None else as_positive("horizon", horizon)
    dt = as_positive("dt", dt)
    hf = paper_bands()["HF"]
    t = np.arange(0.0, horizon, dt)
    exact, fft = [], []
    for rho in rhos:
        d = mixed_disturbance(rho)
        exact.append(d.dominance(hf))
        fft.append(dominance_degree(d(t), dt, hf))
    return DominanceVsRho(rhos, np.array(exact), np.array(fft), horizon, dt)


@dataclass(frozen=True)
class PiecewiseDominance:
    """α(Ω_1, T_l) and α(Ω_3, T_l) along the piecewise disturbance (paper eq. (58), paper Fig. 8).

    Parameters
    ----------
    breaks : (4,) ndarray
        Segment limits in s: HF on ``[b0, b1)``, LF on ``[b1, b2)``, HF on ``[b2, b3)``.
    rho_t : float
        Relative length of the LF segment.
    T : float
        Length of the first HF segment in s.
    rho_p_star : float
        Amplitude factor of the LF segment.
    window_length, hop, dt : float
        STFT window length, hop and sampling step in s.
    t : (L,) ndarray
        Window centres in s.
    alpha : dict
        ``{"LF": (L,) ndarray, "HF": (L,) ndarray}``: in-band share of each window's energy.
    """

    breaks: np.ndarray
    rho_t: float
    T: float
    rho_p_star: float
    window_length: float
    hop: float
    dt: float
    t: np.ndarray
    alpha: dict

    def __post_init__(self):
        if len(self.breaks) != 4:
            raise ValueError(f"breaks must hold 4 segment limits, but found {len(self.breaks)}")
        for kind, a in self.alpha.items():
            if np.shape(a) != np.shape(self.t):
                raise ValueError(f"alpha: {kind} must have the shape of t {np.shape(self.t)}, "
                                 f"but found {np.shape(a)}")

    def inside(self, segment: str) -> np.ndarray:
        """Mask of the windows lying wholly inside the LF segment or wholly inside an HF segment.

        Parameters
        ----------
        segment : {"LF", "HF"}
            Which segments.

        Returns
        -------
        (L,) ndarray of bool

        Raises
        ------
        ValueError
            If ``segment`` is neither.
        """
        half = self.window_length / 2
        b = self.breaks
        if segment == "LF":
            return (self.t - half >= b[1]) & (self.t + half <= b[2])
        if segment == "HF":
            return (self.t + half <= b[1]) | (self.t - half >= b[2])
        raise ValueError(f"segment must be 'LF' or 'HF', but found {segment!r}")

    @property
    def alpha_lf_in_lf(self) -> float:
        """Smallest α(Ω_1, T_l) over windows wholly in the LF segment (NaN if there is none)."""
        a = self.alpha["LF"][self.inside("LF")]
        return float(a.min()) if a.size else math.nan

    @property
    def alpha_lf_in_hf(self) -> float:
        """Largest α(Ω_1, T_l) over windows wholly in an HF segment (NaN if there is none)."""
        a = self.alpha["LF"][self.inside("HF")]
        return float(a.max()) if a.size else math.nan

    @property
    def resolution(self) -> float:
        """Frequency resolution ``2π / window_length`` of the windows in rad/s."""
        return 2 * np.pi / self.window_length

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.shared.prose`).

        The smallest in-LF share is printed with as many digits as it takes to tell it from 1
        (a share never exceeds 1, and rounded to three decimals it would print as 1.000).

        Returns
        -------
        dict
            ``{name: text}``: ``alpha_lf_in_lf``, ``alpha_lf_in_hf``, ``stft_window``,
            ``stft_resolution``.

        Examples
        --------
        >>> localized_dominance_piecewise().prose()["alpha_lf_in_lf"]
        '0.9999983'
        """
        lf = self.alpha_lf_in_lf
        gap = 1.0 - lf
        digits = 3 if not gap > 0 else max(3, 1 - math.floor(math.log10(gap)))
        return {"alpha_lf_in_lf": num(lf, digits), "alpha_lf_in_hf": num(self.alpha_lf_in_hf, 2),
                "stft_window": _length(self.window_length), "stft_resolution": num(self.resolution, 2)}

    def to_record(self) -> RecordPart:
        """Record entry ``alpha_localized`` (new): α(Ω_1, T_l) inside the segments.

        Returns
        -------
        RecordPart
        """
        return RecordPart((entry(
            "alpha_localized", "Definition 3 on the piecewise disturbance of paper eq. (58)",
            None, {"alpha_lf_min_in_lf_segment": self.alpha_lf_in_lf,
                   "alpha_lf_max_in_hf_segments": self.alpha_lf_in_hf},
            "new",
            f"time-localized dominance by STFT (Hann windows of {self.window_length:g} s, hop "
            f"{self.hop:g} s) along the piecewise disturbance with T = {self.T:g} s, rho_t = "
            f"{self.rho_t:g}, rho_p* = {self.rho_p_star:g}: windows wholly in a segment identify "
            f"it; windows across a switching instant mix the two, over a zone set by the window "
            f"length.", window_length=self.window_length, hop=self.hop, T=self.T,
            rho_t=self.rho_t),))


@cached
def localized_dominance_piecewise(rho_t: float = 0.2, *, T: float | None = None,
                                  window_length: float = 60.0, hop: float = 5.0,
                                  dt: float = 2e-3) -> PiecewiseDominance:
    """α(Ω_1, T_l) and α(Ω_3, T_l) along the piecewise disturbance of paper Fig. 8 (eq. (58)).

    Parameters
    ----------
    rho_t : float
        Relative length of the LF segment.
    T : float, optional
        Length of the first HF segment in s (default the paper's T = 500); pass the T of the run
        the result is drawn beside.
    window_length, hop, dt : float
        STFT window, hop and sampling step in s.

    Returns
    -------
    PiecewiseDominance

    Notes
    -----
    Definition 3 of the paper asks for a "pseudo spectrum" per window T_l; this is the short-time
    Fourier transform (:func:`fdsc.signals.localized_dominance`).

    Examples
    --------
    >>> r = localized_dominance_piecewise(0.5, T=100.0, window_length=20.0, hop=2.0)
    >>> [float(b) for b in r.breaks], r.alpha_lf_in_lf > 0.99, r.alpha_lf_in_hf < 1e-3
    ([0.0, 100.0, 150.0, 250.0], True, True)
    """
    sim = paper_data("simulation")
    T = sim["piecewise_T"]["value"] if T is None else T
    rho_p_star = sim["piecewise_rho_p_star"]["value"]
    d = piecewise_disturbance(T, rho_t, rho_p_star)
    t = np.arange(0.0, d.breaks[-1], dt)
    x = d(t)
    bands = paper_bands()
    loc = {k: localized_dominance(x, dt, bands[k], window_length=window_length, hop=hop)
           for k in ("LF", "HF")}
    return PiecewiseDominance(frozen_array(d.breaks), float(rho_t), float(T), float(rho_p_star),
                              float(window_length), float(hop), float(dt), loc["LF"].t,
                              {k: v.alpha for k, v in loc.items()})
