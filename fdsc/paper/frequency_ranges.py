"""Chapter 'frequency_ranges': Sec. II-A, Definitions 1-3 (Ψ of the three ranges, the weight's
sign, Paley–Wiener, dominance degrees) and the factorizations printed in Proposition 1's proof.
"""

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from .._validation import as_positive, as_vector, check_type, frozen_array
from ..bands import Band
from ..signals import Sinusoids, dominance_degree, localized_dominance
from .cache import cached
from .data import (
    hf_disturbance,
    lf_disturbance,
    mixed_disturbance,
    paper_bands,
    paper_data,
    piecewise_disturbance,
)
from .names import BAND_ORDER
from .prose import count, num
from .results import RecordPart, entry

__all__ = [
    "record_part",
    "RANGES",
    "PsiEntry",
    "PsiTable",
    "psi_table",
    "BandWeight",
    "PsiWeights",
    "psi_weights",
    "DominanceVsRho",
    "dominance_vs_rho",
    "PiecewiseDominance",
    "localized_dominance_piecewise",
    "Factorization",
    "Prop1WeightCheck",
    "prop1_weight_check",
    "truncated_spectrum",
    "truncated_energy",
    "out_of_band_fraction",
    "PALEY_WIENER_HORIZONS",
    "PaleyWienerCase",
    "PaleyWienerTable",
    "paley_wiener_table",
]


def _length(x):
    """A length or duration as the prose prints it: whole numbers without decimals."""
    x = float(x)
    return count(int(x)) if x.is_integer() else num(x)


#: The ranges of Lemma 1 that carry a Ψ (the entire range Ω_e has Ψ = 0).
RANGES = tuple(k for k in BAND_ORDER if k != "EF")


# -- Ψ and its weight ---------------------------------------------------------------------------

@dataclass(frozen=True)
class PsiEntry:
    """Ψ of one of the paper's ranges (Lemma 1, paper eq. (7)).

    Parameters
    ----------
    kind : {"LF", "MF", "HF"}
        The range.
    label : str
        The range with its limits, e.g. ``"LF [0, 1] rad/s"``.
    psi : (2, 2) ndarray
        Ψ (complex for MF).
    is_complex : bool
        Ψ has a nonzero imaginary part.
    """

    kind: str
    label: str
    psi: np.ndarray
    is_complex: bool


@dataclass(frozen=True)
class PsiTable:
    """Ψ of the paper's three ranges Ω_1, Ω_2, Ω_3 (paper eq. (55)).

    Parameters
    ----------
    ranges : tuple of PsiEntry
        One per range, in the order LF, MF, HF.
    """

    ranges: tuple

    def rows(self) -> list:
        """One row per range: ``band, range, Psi`` (printed to 3 decimals), ``complex``.

        Returns
        -------
        list of dict
            For :func:`fdsc.paper.report.html_table`.
        """
        return [{"band": r.kind, "range": r.label, "Psi": _matrix_text(r.psi),
                 "complex": "yes" if r.is_complex else "no"} for r in self.ranges]


def _entry_text(z):
    z = complex(z)
    re_, im = z.real, z.imag
    if im == 0:
        return num(re_) if not float(re_).is_integer() else count(int(re_))
    mag = num(abs(im)) if not float(im).is_integer() else count(int(abs(im)))
    return ("−" if im < 0 else "") + f"{mag}j" if re_ == 0 else f"{num(re_)} {'−' if im < 0 else '+'} {mag}j"


def _matrix_text(m):
    """A small matrix as the prose prints it, rows separated by a semicolon: ``[−1, 0; 0, 1]``."""
    return "[" + "; ".join(", ".join(_entry_text(z) for z in row) for row in np.asarray(m)) + "]"


def psi_table() -> PsiTable:
    """Ψ of each of the paper's bands (Ω_1, Ω_2, Ω_3 of paper eq. (55)).

    Returns
    -------
    PsiTable

    Examples
    --------
    >>> [(r.kind, r.is_complex) for r in psi_table().ranges]
    [('LF', False), ('MF', True), ('HF', False)]
    """
    bands = paper_bands()
    return PsiTable(tuple(PsiEntry(k, bands[k].label, bands[k].psi, bands[k].is_complex)
                          for k in RANGES))


def _sign_violations(band, omega, weight):
    """Grid points where the weight has the wrong sign: < 0 in the band or > 0 outside.

    For MF only ω ≥ 0 counts as in band: on the mirror interval [−ϖ_2, −ϖ_1] the weight is
    negative by construction (the rule the proof needs holds for ω > 0 only, see
    :func:`prop1_weight_check`).
    """
    inside = band.contains(omega)
    rule_inside = inside & ((omega >= 0) | (band.kind != "MF"))
    return int(np.sum(weight[rule_inside] < 0) + np.sum(weight[~inside] > 0))


@dataclass(frozen=True)
class BandWeight:
    """The weight of Ψ of one range over ω (see :func:`psi_weights`).

    Parameters
    ----------
    kind : {"LF", "MF", "HF"}
        The range.
    label : str
        The range with its limits.
    lower, upper : float
        Band limits in rad/s (``upper`` is inf for HF).
    weight : (k,) ndarray
        ``[jω; 1]* Ψ [jω; 1]``.
    real_weight : (k,) ndarray
        The same with Re Ψ (what a quadratic form in a real signal sees).
    n_sign_violations : int
        Grid points where ``weight`` is < 0 in the band (MF: for ω ≥ 0) or > 0 outside.
    """

    kind: str
    label: str
    lower: float
    upper: float
    weight: np.ndarray
    real_weight: np.ndarray
    n_sign_violations: int


@dataclass(frozen=True)
class PsiWeights:
    """The weight of Ψ for the paper's three ranges over positive and negative ω.

    Parameters
    ----------
    omega : (k,) ndarray
        Frequencies in rad/s.
    bands : dict
        ``{kind: BandWeight}`` for LF, MF, HF.
    """

    omega: np.ndarray
    bands: dict

    def __post_init__(self):
        for kind, b in self.bands.items():
            if b.weight.shape != self.omega.shape or b.real_weight.shape != self.omega.shape:
                raise ValueError(f"bands: the weights of {kind} must have the shape of omega "
                                 f"{self.omega.shape}, but found {b.weight.shape}")

    def __getitem__(self, kind: str) -> BandWeight:
        """The weight of one range.

        Parameters
        ----------
        kind : {"LF", "MF", "HF"}
            The range.

        Returns
        -------
        BandWeight
        """
        return self.bands[kind]

    @property
    def n_sign_violations(self) -> int:
        """Sign violations summed over the three ranges."""
        return sum(b.n_sign_violations for b in self.bands.values())

    @property
    def mf_real_max(self) -> float:
        """Largest weight of Re Ψ_MF on the grid (−(ω² + ϖ_1ϖ_2) < 0 in closed form)."""
        return float(self.bands["MF"].real_weight.max())

    @property
    def mf_product(self) -> float:
        """ϖ_1ϖ_2 of the MF range in (rad/s)²."""
        return self.bands["MF"].lower * self.bands["MF"].upper

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``n_grid``, ``sign_violations``, ``mf_real_max``, ``mf_w1w2``.
        """
        return {"n_grid": count(self.omega.size), "sign_violations": count(self.n_sign_violations),
                "mf_real_max": num(self.mf_real_max, 4), "mf_w1w2": num(float(self.mf_product), 3)}

    def to_record(self) -> RecordPart:
        """Record entry ``psi_weight_sign``: the sign rule of the weight that the proof of
        Proposition 1 rests on, and the MF weight seen by real signals.

        Returns
        -------
        RecordPart
        """
        counts = {k: b.n_sign_violations for k, b in self.bands.items()}
        rng = f"±[{np.abs(self.omega).min():g}, {np.abs(self.omega).max():g}] rad/s"
        return RecordPart((entry(
            "psi_weight_sign",
            "Sec. III, proof of Proposition 1: sign of [(jw)* 1] Psi [(jw)* 1]*",
            "w >= 0 on Omega_i and w <= 0 outside",
            {"sign_violations": counts, "grid_points": int(self.omega.size),
             "mf_real_weight_max": self.mf_real_max},
            "match" if self.n_sign_violations == 0 else "differs",
            f"weight of Psi counted on {self.omega.size} grid points over {rng}: "
            f"{self.n_sign_violations} sign violations for LF and HF over all w and for MF over "
            f"w >= 0 (on the mirror interval [-w_2, -w_1] the MF weight is negative, see "
            f"prop1_factorizations). For real signals only Re Psi counts, and the MF weight of Re "
            f"Psi is -(w^2 + w_1 w_2), at most {num(self.mf_real_max, 4)} on the grid: the MF FD-EEF "
            f"of a real signal is never positive."),))


def psi_weights(omega: ArrayLike | None = None) -> PsiWeights:
    """The weight ``[jω;1]* Ψ [jω;1]`` and its real-signal part for the paper's three bands.

    Parameters
    ----------
    omega : (k,) array_like, optional
        Frequencies in rad/s (default: ±[10⁻², 10³], 600 log-spaced points per sign).

    Returns
    -------
    PsiWeights
        With the sign-rule count of each range.

    Notes
    -----
    The weight is written ``[(jω)* 1] Ψ [(jω)* 1]*`` in the proof of paper Proposition 1, which
    rests on its sign: ≥ 0 in the band, ≤ 0 outside.

    Examples
    --------
    >>> w = psi_weights()
    >>> w.n_sign_violations, w.mf_real_max < -w.mf_product
    (0, True)
    """
    if omega is None:
        pos = np.geomspace(1e-2, 1e3, 600)
        omega = np.concatenate([-pos[::-1], pos])
    omega = as_vector("omega", omega)
    bands = paper_bands()
    out = {}
    for kind in RANGES:
        band = bands[kind]
        weight = band.weight(omega)
        out[kind] = BandWeight(kind, band.label, band.lower, band.upper, weight,
                               band.real_weight(omega), _sign_violations(band, omega, weight))
    return PsiWeights(omega, out)


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
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.prose`).

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
            f"dominance degree of Omega_3, exact from the mean powers (1/(1 + rho_p^2)) and by "
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
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.prose`).

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


# -- the factorizations printed in the proof of Proposition 1 -----------------------------------

#: Truncation lengths T (s) of the paper's test signals in :func:`paley_wiener_table`.
PALEY_WIENER_HORIZONS = (50.0, 500.0, 5000.0)


#: Gauss–Legendre nodes per panel in :func:`out_of_band_fraction`.
_GL_NODES = 16


#: Panels per half period 2π/T of the spectrum's oscillation in ω.
_PANELS_PER_HALF_PERIOD = 2


#: The factorizations as the proof of Proposition 1 prints them (between paper eqs. (23), (24)).
_PRINTED = {"LF": "(w_l - jw)(w_l + jw) > 0", "MF": "(w - w_1)(w_2 - w) > 0",
            "HF": "(jw - w_h)(jw + w_h) > 0"}


def _default_grid():
    # 400 points per sign: the log step 5/399 puts no grid point on a band edge (1 or 10 rad/s),
    # where the weight is zero and its sign undefined.
    pos = np.geomspace(1e-2, 1e3, 400)
    return np.concatenate([-pos[::-1], pos])


@dataclass(frozen=True)
class Factorization:
    """One printed factorization of the weight against the weight (see :func:`prop1_weight_check`).

    Parameters
    ----------
    kind : {"LF", "MF", "HF"}
        The range.
    weight : (N,) ndarray
        The weight ``[jω; 1]* Ψ [jω; 1]`` (:meth:`fdsc.Band.weight`).
    printed : (N,) ndarray
        The product printed in the proof of Proposition 1.
    corrected : (N,) ndarray
        The real factorization of the weight.
    tau_diagonal : (N,) ndarray
        τ(Ψ_i, ω, ω) of the proof of Theorem 1.
    in_band : (N,) ndarray of bool
        Mask of the two-sided band.
    n_wrong_sign : int
        Points where printed product and weight have opposite signs.
    n_claim_fails : int
        In-band points where the printed product is not > 0 (the proof's claim).
    n_in_band_negative : int
        In-band points with ω < 0.
    max_abs_diff, max_abs_diff_corrected, max_abs_diff_tau : float
        Largest ``|printed − weight|``, ``|corrected − weight|``, ``|tau_diagonal − weight|``.
    """

    kind: str
    weight: np.ndarray
    printed: np.ndarray
    corrected: np.ndarray
    tau_diagonal: np.ndarray
    in_band: np.ndarray
    n_wrong_sign: int
    n_claim_fails: int
    n_in_band_negative: int
    max_abs_diff: float
    max_abs_diff_corrected: float
    max_abs_diff_tau: float

    @property
    def n_in_band(self) -> int:
        """Grid points in the (two-sided) band."""
        return int(self.in_band.sum())

    @property
    def n_out_of_band(self) -> int:
        """Grid points outside the band."""
        return int((~self.in_band).sum())

    @property
    def rel_diff_corrected(self) -> float:
        """``max_abs_diff_corrected`` relative to the largest ``|weight|`` on the grid."""
        return self.max_abs_diff_corrected / float(np.max(np.abs(self.weight)))

    @property
    def rel_diff_tau(self) -> float:
        """``max_abs_diff_tau`` relative to the largest ``|weight|`` on the grid."""
        return self.max_abs_diff_tau / float(np.max(np.abs(self.weight)))


@dataclass(frozen=True)
class Prop1WeightCheck:
    """The factorizations printed in the proof of Proposition 1, per range, on one grid.

    Parameters
    ----------
    omega : (N,) ndarray
        Frequencies in rad/s.
    bands : dict
        ``{kind: Factorization}`` for LF, MF, HF.
    """

    omega: np.ndarray
    bands: dict

    def __getitem__(self, kind: str) -> Factorization:
        """The check of one range.

        Parameters
        ----------
        kind : {"LF", "MF", "HF"}
            The range.

        Returns
        -------
        Factorization
        """
        return self.bands[kind]

    @property
    def max_printed_diff(self) -> float:
        """Largest ``|printed − weight|`` over LF and HF (MF prints the weight itself)."""
        return max(self.bands[k].max_abs_diff for k in ("LF", "HF"))

    @property
    def max_rel_diff_corrected(self) -> float:
        """Largest relative difference of the corrected factorizations over the three ranges."""
        return max(f.rel_diff_corrected for f in self.bands.values())

    @property
    def max_rel_diff_tau(self) -> float:
        """Largest relative difference of τ's diagonal over the three ranges."""
        return max(f.rel_diff_tau for f in self.bands.values())

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``n_grid``; per range ``{kind}_wrong``, ``{kind}_claim_fails``,
            ``{kind}_in_band``, ``{kind}_out_band``; ``max_diff``, ``corrected_rel``,
            ``tau_rel``, ``mf_negative``.
        """
        out = {"n_grid": count(self.omega.size)}
        for kind, f in self.bands.items():
            out.update({f"{kind}_wrong": count(f.n_wrong_sign), f"{kind}_claim_fails": count(f.n_claim_fails),
                        f"{kind}_in_band": count(f.n_in_band), f"{kind}_out_band": count(f.n_out_of_band)})
        return {**out, "max_diff": num(self.max_printed_diff),
                "corrected_rel": num(self.max_rel_diff_corrected, 2),
                "tau_rel": num(self.max_rel_diff_tau, 2),
                "mf_negative": count(self.bands["MF"].n_in_band_negative)}

    def to_record(self) -> RecordPart:
        """Record entry ``prop1_factorizations``: the printed products against the weight.

        Returns
        -------
        RecordPart
        """
        fails = any(f.n_wrong_sign or f.n_claim_fails for f in self.bands.values())
        mf = self.bands["MF"]
        return RecordPart((entry(
            "prop1_factorizations",
            "Sec. III, proof of Proposition 1, display between paper eqs. (23) and (24)",
            dict(_PRINTED),
            {"grid_points": int(self.omega.size),
             **{k: {"wrong_sign": f.n_wrong_sign, "claim_fails": f.n_claim_fails,
                    "in_band": f.n_in_band, "max_abs_diff": f.max_abs_diff}
                for k, f in self.bands.items()},
             "corrected_max_rel_diff": self.max_rel_diff_corrected},
            "differs" if fails else "match",
            f"multiplied out, the printed LF product is w_l^2 + w^2 > 0 and the HF product "
            f"-w^2 - w_h^2 < 0 at every w, while the weights are w_l^2 - w^2 and w^2 - w_h^2 "
            f"(wrong sign at {self.bands['LF'].n_wrong_sign} and {self.bands['HF'].n_wrong_sign} "
            f"of {self.omega.size} grid points); the real factorizations (w_l - w)(w_l + w) and "
            f"(w - w_h)(w + w_h), those of tau in the proof of Theorem 1, agree with the weight to "
            f"{self.max_rel_diff_corrected:.1e} relative. The MF product is the weight itself, "
            f"but its claim > 0 fails on the mirror interval [-w_2, -w_1] ({mf.n_claim_fails} of "
            f"{mf.n_in_band} in-band points)."),))


def prop1_weight_check(varpi_l: float = 1.0, varpi_1: float = 1.0, varpi_2: float = 10.0,
                       varpi_h: float = 10.0, omega: ArrayLike | None = None) -> Prop1WeightCheck:
    """The factorizations printed in the proof of Proposition 1, against the weight.

    The proof writes the weight ``w(ω) = [(jω)* 1] Ψ [(jω)* 1]*`` as
    ``(ϖ_l − jω)(ϖ_l + jω)`` (LF), ``(ω − ϖ_1)(ϖ_2 − ω)`` (MF) and ``(jω − ϖ_h)(jω + ϖ_h)``
    (HF), each claimed ``> 0`` when Ω_i lies in the band. The LF product equals
    ``ϖ_l² + ω² > 0`` and the HF product ``−ω² − ϖ_h² < 0`` for every ω, while the weights
    are ``ϖ_l² − ω²`` and ``ω² − ϖ_h²``. The correct real factorizations are
    ``(ϖ_l − ω)(ϖ_l + ω)`` and ``(ω − ϖ_h)(ω + ϖ_h)``; the MF product is the weight itself.
    The proof of Theorem 1 uses the correct forms in its function τ(Ψ_i, ω_k, ω_κ).

    Parameters
    ----------
    varpi_l, varpi_1, varpi_2, varpi_h : float
        Band limits in rad/s (the paper's: 1, 1, 10, 10).
    omega : (N,) array_like, optional
        Frequencies in rad/s (default: ±[10⁻², 10³], 400 log-spaced points per sign, none on
        a band edge).

    Returns
    -------
    Prop1WeightCheck

    Notes
    -----
    The printed display stands between paper eqs. (23) and (24).

    Examples
    --------
    >>> r = prop1_weight_check()
    >>> r["LF"].n_wrong_sign, r["HF"].n_wrong_sign, r["MF"].n_wrong_sign
    (480, 320, 0)
    >>> r["MF"].n_claim_fails, r["HF"].n_claim_fails == r["HF"].n_in_band
    (80, True)
    >>> r["HF"].max_abs_diff_corrected < 1e-9 * r["HF"].max_abs_diff
    True
    """
    w = _default_grid() if omega is None else as_vector("omega", omega)
    bands = {"LF": Band.lf(varpi_l), "MF": Band.mf(varpi_1, varpi_2), "HF": Band.hf(varpi_h)}
    jw = 1j * w
    lo, hi = bands["LF"].upper, bands["HF"].lower
    w1, w2 = bands["MF"].lower, bands["MF"].upper
    printed = {"LF": ((lo - jw) * (lo + jw)).real, "MF": (w - w1) * (w2 - w),
               "HF": ((jw - hi) * (jw + hi)).real}
    corrected = {"LF": (lo - w) * (lo + w), "MF": (w - w1) * (w2 - w), "HF": (w - hi) * (w + hi)}
    # τ(Ψ_i, ω_k, ω_κ) as printed in the proof of Theorem 1, at ω_k = ω_κ = ω.
    tau = {"LF": (lo - w) * (w + lo), "MF": (w2 - w) * (w - w1), "HF": (w - hi) * (w + hi)}
    out = {}
    for kind, band in bands.items():
        weight = band.weight(w)
        inside = band.contains(w)
        p = printed[kind]
        out[kind] = Factorization(
            kind, weight, p, corrected[kind], tau[kind], inside,
            n_wrong_sign=int(np.sum(np.sign(p) * np.sign(weight) < 0)),
            n_claim_fails=int(np.sum(inside & ~(p > 0))),
            n_in_band_negative=int(np.sum(inside & (w < 0))),
            max_abs_diff=float(np.max(np.abs(p - weight))),
            max_abs_diff_corrected=float(np.max(np.abs(corrected[kind] - weight))),
            max_abs_diff_tau=float(np.max(np.abs(tau[kind] - weight))))
    return Prop1WeightCheck(w, out)


# -- Definition 1 on [0, ∞): Paley–Wiener --------------------------------------------------------

def _check_sinusoids(d):
    check_type("d", d, Sinusoids)
    if np.any(d.phases != 0):
        raise ValueError("d must have zero phases (sums of sines, as in the paper), "
                         f"but found phases {d.phases.tolist()}")


def _window_integral(nu, T):
    # ∫_0^T exp(jνt) dt, written with sinc so that ν = 0 needs no special case.
    return T * np.exp(0.5j * nu * T) * np.sinc(nu * T / (2.0 * np.pi))


def truncated_spectrum(d: Sinusoids, T: float, omega: ArrayLike) -> np.ndarray:
    """Fourier transform of the causal truncation ``d(t)·1[0, T](t)`` of a sum of sines.

    ``D(ω) = ∫_0^T d(t) e^{−jωt} dt`` in closed form, for ``d = Σ a_k sin(ω_k t)``.

    Parameters
    ----------
    d : Sinusoids
        With zero phases.
    T : float
        Length of the record in s (> 0).
    omega : (N,) array_like
        Frequencies in rad/s.

    Returns
    -------
    (N,) complex ndarray

    Raises
    ------
    TypeError
        If ``d`` is not a :class:`fdsc.Sinusoids`.
    ValueError
        If ``d`` has a nonzero phase or ``T`` is not positive.

    Notes
    -----
    The transform of paper eq. (3) (Definition 1) applied to a finite record.

    Examples
    --------
    >>> D = truncated_spectrum(Sinusoids([1.0], [1.0]), 2 * np.pi, [1.0])
    >>> complex(np.round(D[0], 10))  # ∫_0^{2π} sin t e^{−jt} dt = −jπ
    -3.1415926536j
    """
    _check_sinusoids(d)
    T = as_positive("T", T)
    w = as_vector("omega", omega)
    D = np.zeros(w.shape, dtype=complex)
    for a, wk in zip(d.amplitudes, d.frequencies, strict=True):
        D += a / 2j * (_window_integral(wk - w, T) - _window_integral(-wk - w, T))
    return D


def truncated_energy(d: Sinusoids, T: float) -> float:
    """``∫_0^T d(t)² dt`` in closed form for a sum of sines ``d = Σ a_k sin(ω_k t)``.

    Parameters
    ----------
    d : Sinusoids
        With zero phases.
    T : float
        Length of the record in s (> 0).

    Returns
    -------
    float

    Raises
    ------
    TypeError
        If ``d`` is not a :class:`fdsc.Sinusoids`.
    ValueError
        If ``d`` has a nonzero phase or ``T`` is not positive.

    Examples
    --------
    >>> round(truncated_energy(Sinusoids([1.0], [1.0]), 2 * np.pi), 12)  # = π
    3.14159265359
    """
    _check_sinusoids(d)
    T = as_positive("T", T)
    a, w = d.amplitudes, d.frequencies

    def cos_integral(nu):  # ∫_0^T cos(νt) dt
        return T * np.sinc(nu * T / np.pi)

    diff = np.subtract.outer(w, w)
    summ = np.add.outer(w, w)
    return float(0.5 * a @ (cos_integral(diff) - cos_integral(summ)) @ a)


def _low_band_energy(d, T, upper):
    """``(1/π) ∫_0^upper |D(ω)|² dω`` (energy in |ω| ≤ upper) by panelled Gauss–Legendre."""
    n_panels = max(8, math.ceil(_PANELS_PER_HALF_PERIOD * upper * T / np.pi))
    x, wq = np.polynomial.legendre.leggauss(_GL_NODES)
    edges = np.linspace(0.0, upper, n_panels + 1)
    half = 0.5 * np.diff(edges)
    nodes = (edges[:-1, None] + half[:, None] * (x[None, :] + 1.0)).ravel()
    weights = (half[:, None] * wq[None, :]).ravel()
    return float(weights @ np.abs(truncated_spectrum(d, T, nodes)) ** 2 / np.pi)


def out_of_band_fraction(d: Sinusoids, T: float, band: Band) -> float:
    """Share of the energy of ``d·1[0, T]`` that lies outside ``band`` (two-sided spectrum).

    By Paley–Wiener the Fourier transform of a nonzero causal L2 signal cannot vanish on an
    interval, so this share is positive for every T; it is not zero for a finite record of
    in-band sinusoids either.

    Parameters
    ----------
    d : Sinusoids
        With zero phases.
    T : float
        Record length in s.
    band : Band
        An LF or HF band.

    Returns
    -------
    float
        ``E_out / E`` with ``E = ∫_0^T d² dt`` (closed form) and the in-band part by
        Parseval, ``(1/2π) ∫_{Ω} |D(ω)|² dω``, integrated by Gauss–Legendre on panels much
        shorter than the spectrum's oscillation period 2π/T.

    Raises
    ------
    TypeError
        If ``d`` or ``band`` has the wrong type.
    ValueError
        If ``band`` is not LF or HF, ``d`` has a nonzero phase or ``T`` is not positive.

    Notes
    -----
    Definition 1 (paper eq. (3)) asks this share to be zero.

    Examples
    --------
    >>> lf = Sinusoids([1.0, 1.0, 1.0], [0.1, 0.2, 0.3])
    >>> f = out_of_band_fraction(lf, 500.0, Band.lf(1.0))
    >>> 0 < f < 1e-2
    True
    """
    check_type("band", band, Band)
    if band.kind not in ("LF", "HF"):
        raise ValueError(f"band must be an LF or HF band, but found kind {band.kind!r}")
    total = truncated_energy(d, T)
    if band.kind == "LF":
        return (total - _low_band_energy(d, T, band.upper)) / total
    return _low_band_energy(d, T, band.lower) / total


@dataclass(frozen=True)
class PaleyWienerCase:
    """One of the paper's test signals cut to ``[0, T]``, and its energy outside its band.

    Parameters
    ----------
    kind : {"LF", "HF"}
        The signal (paper eq. (56) or (57)) and its band (Ω_1 or Ω_3).
    signal : str
        The signal as the table names it.
    band : str
        The band's label.
    T : float
        Record length in s.
    fraction_out : float
        Share of the record's energy outside the band (:func:`out_of_band_fraction`).
    """

    kind: str
    signal: str
    band: str
    T: float
    fraction_out: float


@dataclass(frozen=True)
class PaleyWienerTable:
    """Out-of-band energy shares of the paper's test signals over record lengths.

    Parameters
    ----------
    cases : tuple of PaleyWienerCase
        One per signal and record length.
    """

    cases: tuple

    def rows(self) -> list:
        """One row per case: ``signal, band, T, fraction_out``.

        Returns
        -------
        list of dict
            For :func:`fdsc.paper.report.html_table`.
        """
        return [{"signal": c.signal, "band": c.band, "T": c.T, "fraction_out": c.fraction_out}
                for c in self.cases]

    @property
    def horizons(self) -> tuple:
        """The record lengths, in order of first appearance."""
        return tuple(dict.fromkeys(c.T for c in self.cases))

    @property
    def n_positive(self) -> int:
        """Cases with a positive out-of-band share."""
        return sum(c.fraction_out > 0 for c in self.cases)

    def min_fraction(self, kind: str) -> float:
        """Smallest out-of-band share of one signal over the record lengths.

        Parameters
        ----------
        kind : {"LF", "HF"}
            The signal.

        Returns
        -------
        float
        """
        return min(c.fraction_out for c in self.cases if c.kind == kind)

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``T_list`` (the record lengths), ``lf_min``, ``hf_min`` (the
            smallest out-of-band shares), ``n_positive``, ``n_rows``.
        """
        return {"T_list": ", ".join(_length(T) for T in self.horizons),
                "lf_min": num(self.min_fraction("LF")), "hf_min": num(self.min_fraction("HF")),
                "n_positive": count(int(self.n_positive)), "n_rows": count(len(self.cases))}

    def to_record(self) -> RecordPart:
        """Record entry ``paley_wiener_share`` (new): Definition 1 on finite records.

        Returns
        -------
        RecordPart
        """
        shares = {c.kind: {} for c in self.cases}
        for c in self.cases:
            shares[c.kind][f"T={c.T:g}"] = c.fraction_out
        return RecordPart((entry(
            "paley_wiener_share", "Definition 1 (paper eq. (3)) on the signals of paper eqs. (56), (57)",
            None, shares, "new",
            f"share of the energy of the LF (eq. (56)) and HF (eq. (57)) signals cut to [0, T] "
            f"that lies outside Omega_1 and Omega_3, from the closed-form transform: positive in "
            f"{self.n_positive} of {len(self.cases)} cases, shrinking with T. By Paley-Wiener no "
            f"nonzero causal L2 signal is frequency-limited, so the class of Definition 1 is "
            f"empty and the statements that assume it are vacuous as printed."),))


@cached
def paley_wiener_table(horizons: tuple = PALEY_WIENER_HORIZONS) -> PaleyWienerTable:
    """Out-of-band energy share of the paper's test signals truncated to ``[0, T]``.

    The LF signal of paper eq. (56) against Ω_1 and the HF signal of paper eq. (57) against Ω_3.

    Parameters
    ----------
    horizons : tuple of float, optional
        Record lengths T in s.

    Returns
    -------
    PaleyWienerTable

    Examples
    --------
    >>> table = paley_wiener_table((100.0,))
    >>> [c.signal for c in table.cases], table.n_positive
    (['LF, eq. (56)', 'HF, eq. (57)'], 2)
    """
    bands = paper_bands()
    cases = []
    for kind, d in (("LF", lf_disturbance()), ("HF", hf_disturbance())):
        label = "LF, eq. (56)" if kind == "LF" else "HF, eq. (57)"
        for T in horizons:
            cases.append(PaleyWienerCase(kind, label, bands[kind].label, float(T),
                                         out_of_band_fraction(d, T, bands[kind])))
    return PaleyWienerTable(tuple(cases))


def record_part() -> RecordPart:
    """Record entries of the chapter: ``psi_weight_sign``, ``prop1_factorizations``,
    ``paley_wiener_share``, ``alpha_mixed`` and ``alpha_localized``.

    Returns
    -------
    RecordPart
    """
    return (psi_weights().to_record() + prop1_weight_check().to_record()
            + paley_wiener_table().to_record() + dominance_vs_rho().to_record()
            + localized_dominance_piecewise().to_record())
