"""Chapter 'passive_controllers': the gains of Sec. IV recomputed by synthesis, paper Fig. 3, ε and
σ, the best HF design, paper Remark 3's gap, LMIs against a direct search. The bounds printed
beside the gains are judged in the appendix :mod:`fdsc.paper.printed_bounds`.
"""

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from .._validation import as_choice, as_vector
from ..bands import Band
from ..frequency import band_peak, sigma_max
from ..plant import Plant
from ..random_systems import random_plant
from ..synthesis import DEFAULT_EPSILON, SynthesisResult, optimize_gain, synthesize, synthesize_hinf
from .cache import cached
from .data import (
    aircraft,
    paper_bands,
    paper_data,
    paper_gains,
)
from .names import FDSC_IN_BAND, FIGURE_IDS, GAIN_BANDS, GAIN_ORDER
from .prose import count, num
from .results import RecordPart, entry, pick
from .verdict import verdict

__all__ = [
    "record_part",
    "EPSILON_GRID",
    "HF_SIGMA_GRID",
    "controller_label",
    "GainDesigns",
    "recompute_gains",
    "GainRow",
    "GainComparison",
    "gain_comparison",
    "SigmaCurves",
    "sigma_curves",
    "GapCurves",
    "gap_curves",
    "remark3_gap",
    "EpsilonScan",
    "epsilon_sensitivity",
    "SigmaScan",
    "sigma_sensitivity",
    "HFBest",
    "hf_best",
    "CrosscheckCase",
    "DirectCrosscheck",
    "direct_crosscheck",
]


#: ε of the stability LMI scanned by :func:`epsilon_sensitivity`.
EPSILON_GRID = (1e-3, 1e-2, 1e-1, 1.0, 10.0)


#: σ of the HF slack scanned by :func:`hf_best`: 0 and 17 log-spaced values in [10⁻², 10²].
HF_SIGMA_GRID = (0.0, *(float(s) for s in np.geomspace(1e-2, 1e2, 17)))


#: Bands of the random plants of :func:`direct_crosscheck` (not the paper's: the plants are random).
_CROSSCHECK_BANDS = {"LF": Band.lf(1.0), "MF": Band.mf(1.0, 5.0)}


def _default_omega():
    return np.geomspace(1e-3, 1e4, 1200)


def _band_limits():
    """The finite limits of the paper's ranges, ϖ_l and ϖ_h (paper eq. (55)), in rad/s."""
    bands = paper_bands()
    return tuple(sorted({bands["LF"].upper, bands["MF"].lower, bands["MF"].upper, bands["HF"].lower}))


def controller_label(gain: str) -> str:
    """The gain with the name of its passive controller, e.g. ``"K_f1 (PassC-LF)"``.

    Parameters
    ----------
    gain : str
        One of :data:`fdsc.paper.names.GAIN_ORDER`.

    Returns
    -------
    str

    Examples
    --------
    >>> controller_label("K_e")
    'K_e (PassC-EF)'
    """
    as_choice("gain", gain, GAIN_ORDER)
    return f"{gain} (PassC-{GAIN_BANDS[gain]})"


def _exact(x):
    """A chosen parameter printed with just the digits it has (0.01, not 0.0100)."""
    digits = f"{x:g}".replace(".", "").replace("-", "").lstrip("0")
    return num(float(x), max(1, len(digits)))


def _fmt_K(K):
    # four decimals, as the paper prints its gains (rows separated by semicolons, no raw array)
    rows = np.atleast_2d(np.asarray(K, dtype=float))
    return "[" + "; ".join(", ".join(f"{v:.4f}".replace("-", "−") for v in r) for r in rows) + "]"


# -- the gains recomputed ------------------------------------------------------------------------

@dataclass(frozen=True)
class GainDesigns:
    """The four gains of Sec. IV designed by the synthesis LMIs (see :func:`recompute_gains`).

    Parameters
    ----------
    designs : dict
        ``{"K_f1": SynthesisResult, "K_f2": ..., "K_f3": ..., "K_e": ...}``.
    """

    designs: dict

    def __post_init__(self):
        if set(self.designs) != set(GAIN_ORDER):
            raise ValueError(f"designs must hold the gains {GAIN_ORDER}, but found {tuple(self.designs)}")
        if not all(isinstance(r, SynthesisResult) for r in self.designs.values()):
            raise TypeError("designs must hold SynthesisResult values")

    def __getitem__(self, name: str) -> SynthesisResult:
        """The design of one gain.

        Parameters
        ----------
        name : str
            One of :data:`fdsc.paper.names.GAIN_ORDER`.

        Returns
        -------
        SynthesisResult
        """
        return self.designs[name]

    @property
    def gains(self) -> dict:
        """``{name: K}`` of the designed gains."""
        return {k: r.K for k, r in self.designs.items()}


@cached
def recompute_gains(plant: Plant | None = None, *, epsilon: float = DEFAULT_EPSILON,
                    sigma: float = 0.0) -> GainDesigns:
    """Synthesize LF, MF, HF (fictitious pole σ) and H∞ gains for the aircraft.

    Parameters
    ----------
    plant : Plant, optional
        Default the aircraft of Sec. IV.
    epsilon : float, optional
        ε of the stability LMI (LF, MF, HF).
    sigma : float, optional
        σ of the HF slack (the fictitious pole at −σ).

    Returns
    -------
    GainDesigns
    """
    plant = aircraft() if plant is None else plant
    bands = paper_bands()
    return GainDesigns({"K_f1": synthesize(plant, bands["LF"], epsilon=epsilon),
                        "K_f2": synthesize(plant, bands["MF"], epsilon=epsilon),
                        "K_f3": synthesize(plant, bands["HF"], epsilon=epsilon, sigma=sigma),
                        "K_e": synthesize_hinf(plant)})


@dataclass(frozen=True)
class GainRow:
    """A printed gain beside the recomputed one (see :func:`gain_comparison`).

    Parameters
    ----------
    name : str
        Name of the gain.
    band : str
        The band it is designed for.
    paper_K, ours_K : (2, 2) ndarray
        Printed and recomputed gain.
    rel_diff : float
        ``‖ours − paper‖_F / ‖paper‖_F``.
    gamma_paper_gain : float
        In-band peak of σ_max for the printed gain.
    gamma_lmi : float
        γ certified by our synthesis LMI.
    gamma_sweep : float
        In-band peak of σ_max for our gain.
    poles_paper, poles_ours : (2,) ndarray
        Closed-loop poles with either gain.
    status : str
        cvxpy status of our design.
    verdict : str
        Of our gain against the printed one.
    epsilon, sigma : float
        Parameters of our design (``sigma`` NaN except for HF).
    """

    name: str
    band: str
    paper_K: np.ndarray
    ours_K: np.ndarray
    rel_diff: float
    gamma_paper_gain: float
    gamma_lmi: float
    gamma_sweep: float
    poles_paper: np.ndarray
    poles_ours: np.ndarray
    status: str
    verdict: str
    epsilon: float
    sigma: float

    @property
    def fastest_pole(self) -> float:
        """Smallest real part of the poles with our gain."""
        return float(np.min(np.real(self.poles_ours)))

    def to_entry(self) -> dict:
        """The record entry of this gain (id: the gain's name).

        Returns
        -------
        dict
        """
        band = self.band
        how = "H-infinity state-feedback LMI" if band == "EF" else f"{band} synthesis LMI"
        return entry(
            self.name, f"Sec. IV, {self.name}", self.paper_K, self.ours_K, self.verdict,
            f"{how} (derived in the passive-controller chapter"
            + ("" if band == "EF" else f"; stability LMI with epsilon = {self.epsilon:g}")
            + ("; sigma = 0" if band == "HF" else "") + f"); relative difference "
            f"{self.rel_diff:.2e}; in-band gain of the printed gain "
            f"{self.gamma_paper_gain:.4f}, of ours {self.gamma_sweep:.4f} "
            f"(LMI bound {self.gamma_lmi:.4f}). "
            + ("The HF LMI is only sufficient and depends on sigma: see the best HF design."
               if band == "HF" else
               "The optimal gains are high-gain and gamma is flat along the gain's size, "
               "so only a few digits are determined."))


@dataclass(frozen=True)
class GainComparison:
    """The printed gains beside the recomputed ones.

    Parameters
    ----------
    gains : tuple of GainRow
        In the order of :data:`fdsc.paper.names.GAIN_ORDER`.
    """

    gains: tuple

    def __getitem__(self, name: str) -> GainRow:
        """The row of one gain.

        Parameters
        ----------
        name : str
            Name of the gain.

        Returns
        -------
        GainRow
        """
        return pick(self.gains, "name", name)

    def rows(self) -> list:
        """One row per gain, gains printed to 4 decimals (for
        :func:`fdsc.paper.report.html_table`).

        Returns
        -------
        list of dict
        """
        return [{**vars(g), "paper_K": _fmt_K(g.paper_K), "ours_K": _fmt_K(g.ours_K)}
                for g in self.gains]

    def display_rows(self) -> list:
        """One row per gain, formatted for the book: ``name, band, paper_K, ours_K, rel_diff,
        gamma_paper_gain, gamma_lmi, gamma_sweep, verdict``.

        Returns
        -------
        list of dict
        """
        return [{"name": g.name, "band": g.band, "paper_K": _fmt_K(g.paper_K), "ours_K": _fmt_K(g.ours_K),
                 "rel_diff": num(g.rel_diff, 2), "gamma_paper_gain": num(g.gamma_paper_gain, 5),
                 "gamma_lmi": num(g.gamma_lmi, 5), "gamma_sweep": num(g.gamma_sweep, 5),
                 "verdict": g.verdict} for g in self.gains]

    def prose(self) -> dict:
        """The numbers the chapter quotes (:mod:`fdsc.paper.prose`).

        Returns
        -------
        dict
            ``{name: text}``: per gain ``rel_<gain>`` (relative difference to the printed gain),
            ``verdict_<gain>``, ``gpaper_<gain>``, ``glmi_<gain>``, ``gsweep_<gain>`` (in-band
            peak of the printed gain, LMI γ and in-band peak of ours); ``fast_pole_lo`` and
            ``fast_pole_hi`` (fastest poles of our LF, MF and H∞ designs).
        """
        fast = [g.fastest_pole for g in self.gains if g.band != "HF"]
        out = {"fast_pole_lo": num(min(fast)), "fast_pole_hi": num(max(fast))}
        for g in self.gains:
            out |= {f"rel_{g.name}": num(g.rel_diff, 2), f"verdict_{g.name}": g.verdict,
                    f"gpaper_{g.name}": num(g.gamma_paper_gain, 4), f"glmi_{g.name}": num(g.gamma_lmi, 4),
                    f"gsweep_{g.name}": num(g.gamma_sweep, 4)}
        return out

    def to_record(self) -> RecordPart:
        """Record entries ``K_f1``, ``K_f2``, ``K_f3``, ``K_e``.

        Returns
        -------
        RecordPart
        """
        return RecordPart(tuple(g.to_entry() for g in self.gains))


@cached
def gain_comparison(results: GainDesigns | None = None) -> GainComparison:
    """Printed against recomputed gains, with in-band gains of both.

    Parameters
    ----------
    results : GainDesigns, optional
        Output of :func:`recompute_gains` (default: computed).

    Returns
    -------
    GainComparison

    Notes
    -----
    The gains are printed in Sec. IV; paper Fig. 3 draws their σ_max.
    """
    results = recompute_gains() if results is None else results
    plant, printed, bands = aircraft(), paper_gains(), paper_bands()
    rows = []
    for name in GAIN_ORDER:
        res, Kp = results[name], printed[name]
        band = bands[GAIN_BANDS[name]]
        cl = plant.closed_loop(Kp)
        rows.append(GainRow(
            name, band.kind, Kp, res.K, float(np.linalg.norm(res.K - Kp) / np.linalg.norm(Kp)),
            band_peak(cl, band).gamma, res.gamma_lmi, res.gamma_sweep, cl.poles(), res.poles,
            res.status, verdict(Kp, res.K), res.epsilon, res.sigma))
    return GainComparison(tuple(rows))


# -- σ_max curves (paper Fig. 3) and the gap of paper Remark 3 ----------------------------------

@dataclass(frozen=True)
class SigmaCurves:
    """σ_max(G(jω)) of the aircraft closed loop for several gains (the curves of paper Fig. 3).

    Parameters
    ----------
    omega : (k,) ndarray
        Frequencies in rad/s.
    sigma : dict
        ``{gain name: (k,) ndarray}``.
    band_limits : tuple of float
        The limits of the paper's ranges in rad/s (paper eq. (55)).
    """

    omega: np.ndarray
    sigma: dict
    band_limits: tuple

    def __post_init__(self):
        for name, s in self.sigma.items():
            if np.shape(s) != np.shape(self.omega):
                raise ValueError(f"sigma: {name} must have the shape of omega "
                                 f"{np.shape(self.omega)}, but found {np.shape(s)}")

    def to_record(self) -> RecordPart:
        """The figure ``sigma_max`` (paper Fig. 3): meant for the curves of the printed gains.

        Returns
        -------
        RecordPart

        Raises
        ------
        ValueError
            If the curves are not those of the four gains of Sec. IV.
        """
        if tuple(self.sigma) != GAIN_ORDER:
            raise ValueError(f"sigma must hold the curves of {GAIN_ORDER}, but found {tuple(self.sigma)}")
        return RecordPart(figures={"sigma_max": {
            "paper_figure": FIGURE_IDS["sigma_max"], "omega": self.omega, "sigma_max": self.sigma,
            "band_limits": list(self.band_limits),
            "units": {"omega": "rad/s", "sigma_max": "1 (largest singular value of G(jw))"}}})


def sigma_curves(gains: dict, omega: ArrayLike | None = None) -> SigmaCurves:
    """σ_max(G(jω)) of the aircraft closed loop for each gain (the curves of paper Fig. 3).

    Parameters
    ----------
    gains : dict
        ``{name: K}``.
    omega : (k,) array_like, optional
        Frequencies in rad/s (default 1200 log-spaced points over [10⁻³, 10⁴]).

    Returns
    -------
    SigmaCurves
    """
    omega = _default_omega() if omega is None else as_vector("omega", omega)
    plant = aircraft()
    return SigmaCurves(omega, {name: sigma_max(plant.closed_loop(K), omega)
                               for name, K in gains.items()}, _band_limits())


@dataclass(frozen=True)
class GapCurves:
    """paper Remark 3's gap ``σ_max(G, K_in) − σ_max(G, K_out)`` for candidate out-of-band gains.

    Parameters
    ----------
    omega : (k,) ndarray
        Frequencies in rad/s.
    gap : dict
        ``{candidate label: (k,) ndarray}``.
    band_limits : tuple of float
        The limits of the paper's ranges in rad/s.
    name_in : str
        Name of the in-band gain.
    """

    omega: np.ndarray
    gap: dict
    band_limits: tuple
    name_in: str = "K_in"

    def first_crossing(self, label: str) -> float:
        """Lowest grid frequency after which the gap of one candidate changes sign.

        Parameters
        ----------
        label : str
            A key of :attr:`gap`.

        Returns
        -------
        float
            In rad/s; NaN if the gap keeps its sign on the grid.
        """
        idx = np.nonzero(np.diff(np.sign(self.gap[label])))[0]
        return float(self.omega[idx[0]]) if idx.size else math.nan

    def prose(self) -> dict:
        """The numbers the chapter quotes (:mod:`fdsc.paper.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``cross_lo``, ``cross_hi`` (where the candidates' gaps first change
            sign, rad/s), ``name_in``.
        """
        cross = [self.first_crossing(k) for k in self.gap]
        return {"cross_lo": num(min(cross)), "cross_hi": num(max(cross)), "name_in": self.name_in}

    def to_record(self) -> RecordPart:
        """Record entry ``remark3_gap`` (new): where the gap of each candidate changes sign.

        Returns
        -------
        RecordPart
        """
        cross = {k: self.first_crossing(k) for k in self.gap}
        low = {k: float(g[0]) for k, g in self.gap.items()}
        reading = ("so the in-band controller is better only above the crossing. Remark 3 asks "
                   "the gap to be positive in band and negative out of band: read literally, "
                   "the reverse of what the curves show."
                   if all(v > 0 for v in low.values()) else "")
        return RecordPart((entry(
            "remark3_gap", "paper Remark 3, gap function (paper eq. (52))", None,
            {"first_sign_change_rad_s": cross, "gap_at_lowest_omega": low}, "new",
            f"gap sigma_max(G, {self.name_in}) - sigma_max(G, K_out) with the in-band gain "
            f"{self.name_in} and the other printed gains as K_out, on {self.omega.size} "
            f"log-spaced frequencies over [{self.omega[0]:g}, {self.omega[-1]:g}] rad/s: at the "
            f"lowest frequency it is {min(low.values()):.4g} or more, and it first changes sign "
            f"between {min(cross.values()):.3g} and {max(cross.values()):.3g} rad/s; " + reading,
            name_in=self.name_in),))


def gap_curves(K_in: ArrayLike, candidates: dict, omega: ArrayLike | None = None, *,
               name_in: str = "K_in") -> GapCurves:
    """paper Remark 3's gap ``σ_max(G, K_in) − σ_max(G, K_out)`` for each candidate out-of-band gain.

    Parameters
    ----------
    K_in : (2, 2) array_like
        The in-band gain.
    candidates : dict
        ``{label: K_out}``.
    omega : (k,) array_like, optional
        Frequencies in rad/s (default 1200 log-spaced points over [10⁻³, 10⁴]).
    name_in : str, optional
        Name of the in-band gain (for the record's note).

    Returns
    -------
    GapCurves

    Notes
    -----
    The gap function is paper eq. (52).
    """
    omega = _default_omega() if omega is None else as_vector("omega", omega)
    plant = aircraft()
    s_in = sigma_max(plant.closed_loop(K_in), omega)
    return GapCurves(omega, {n: s_in - sigma_max(plant.closed_loop(K), omega)
                             for n, K in candidates.items()}, _band_limits(), name_in)


def remark3_gap() -> GapCurves:
    """The gap of paper Remark 3 with the paper's in-band gain and the other printed gains.

    The in-band mode of the paper's FDSC is PassC-HF (K_f3 on Ω_3); the candidates are K_f1,
    K_f2 and K_e, labelled ``"K_out = K_f1"`` and so on.

    Returns
    -------
    GapCurves

    Examples
    --------
    >>> g = remark3_gap()
    >>> g.name_in, list(g.gap)
    ('K_f3', ['K_out = K_f1', 'K_out = K_f2', 'K_out = K_e'])
    """
    printed = paper_gains()
    name_in = paper_data("switching")["modes"]["value"][FDSC_IN_BAND]
    return gap_curves(printed[name_in], {f"K_out = {k}": printed[k] for k in GAIN_ORDER
                                         if k != name_in}, name_in=name_in)


# -- the free parameters ε and σ ------------------------------------------------------------------

@dataclass(frozen=True)
class EpsilonScan:
    """Designs of one band over ε of the stability LMI (see :func:`epsilon_sensitivity`).

    Parameters
    ----------
    kind : {"LF", "MF"}
        The band.
    epsilon : (k,) ndarray
        The values of ε.
    gamma_lmi, gamma_sweep : (k,) ndarray
        Certified γ and in-band peak of the designed closed loop.
    fast_pole : (k,) ndarray
        Smallest real part of the closed-loop poles.
    K : (k, m, n) ndarray
        The gains.
    status : tuple of str
        cvxpy statuses.
    """

    kind: str
    epsilon: np.ndarray
    gamma_lmi: np.ndarray
    gamma_sweep: np.ndarray
    fast_pole: np.ndarray
    K: np.ndarray
    status: tuple

    @property
    def spread(self) -> float:
        """``max / min − 1`` of the in-band peak over ε."""
        return float(self.gamma_sweep.max() / self.gamma_sweep.min() - 1)

    def spread_over(self, lo: float, hi: float) -> float:
        """``max / min − 1`` of the in-band peak over the values of ε in ``[lo, hi]``.

        Parameters
        ----------
        lo, hi : float
            The ends of the range of ε.

        Returns
        -------
        float

        Raises
        ------
        ValueError
            If no ε of the scan lies in ``[lo, hi]``.
        """
        inside = (self.epsilon >= lo) & (self.epsilon <= hi)
        if not inside.any():
            raise ValueError(f"lo, hi must enclose an epsilon of the scan {self.epsilon.tolist()}, "
                             f"but found [{lo}, {hi}]")
        g = self.gamma_sweep[inside]
        return float(g.max() / g.min() - 1)

    def prose(self, lo: float = 1e-2, hi: float = 1.0) -> dict:
        """The numbers the chapter quotes (:mod:`fdsc.paper.prose`).

        Parameters
        ----------
        lo, hi : float, optional
            A sub-range of ε whose spread is quoted beside that of the whole grid.

        Returns
        -------
        dict
            ``{name: text}``: ``spread`` and ``grid_lo``, ``grid_hi`` (the in-band peak's
            relative spread over the whole grid of ε and its ends); ``spread_mid`` over
            ``[mid_lo, mid_hi]``.
        """
        return {"spread": num(self.spread, 2), "grid_lo": _exact(self.epsilon.min()),
                "grid_hi": _exact(self.epsilon.max()), "spread_mid": num(self.spread_over(lo, hi), 2),
                "mid_lo": _exact(lo), "mid_hi": _exact(hi)}

    def display_rows(self) -> list:
        """One row per ε, formatted for the book: ``kind, epsilon, gamma_lmi, gamma_sweep,
        fast_pole, K``.

        Returns
        -------
        list of dict
        """
        return [{"kind": self.kind, "epsilon": _exact(e), "gamma_lmi": num(float(g), 5),
                 "gamma_sweep": num(float(w), 5), "fast_pole": num(float(p)), "K": _fmt_K(K)}
                for e, g, w, p, K in zip(self.epsilon, self.gamma_lmi, self.gamma_sweep,
                                         self.fast_pole, self.K, strict=True)]

    def rows(self) -> list:
        """One row per ε: ``kind, epsilon, gamma_lmi, gamma_sweep, fast_pole, K`` (K printed).

        Returns
        -------
        list of dict
        """
        return [{"kind": self.kind, "epsilon": float(e), "gamma_lmi": float(g),
                 "gamma_sweep": float(s), "fast_pole": float(p), "K": _fmt_K(K), "status": st}
                for e, g, s, p, K, st in zip(self.epsilon, self.gamma_lmi, self.gamma_sweep,
                                              self.fast_pole, self.K, self.status, strict=True)]

    def to_record(self) -> RecordPart:
        """Record entry ``epsilon_scan_<kind>`` (new): the designs over ε.

        Returns
        -------
        RecordPart
        """
        return RecordPart((entry(
            f"epsilon_scan_{self.kind.lower()}",
            f"Sec. IV, {self.kind} design (epsilon of the stability LMI, not printed)", None,
            {"epsilon": self.epsilon, "gamma_lmi": self.gamma_lmi, "gamma_sweep": self.gamma_sweep,
             "fast_pole": self.fast_pole}, "new",
            f"the paper prints no synthesis method; our {self.kind} design shares X and Y with a "
            f"stability LMI whose epsilon is free: its in-band peak varies by "
            f"{self.spread:.1%} over epsilon in [{self.epsilon.min():g}, {self.epsilon.max():g}] "
            f"(we use {DEFAULT_EPSILON:g})."),))


@cached
def epsilon_sensitivity(kind: str, epsilons: ArrayLike = EPSILON_GRID) -> EpsilonScan:
    """LMI and sweep γ of the ``kind`` design (LF or MF) over ε of the stability LMI.

    Parameters
    ----------
    kind : {"LF", "MF"}
        The band.
    epsilons : (k,) array_like, optional
        Values of ε (> 0).

    Returns
    -------
    EpsilonScan

    Raises
    ------
    ValueError
        If ``kind`` is neither LF nor MF.
    """
    as_choice("kind", kind, ("LF", "MF"))
    plant, band = aircraft(), paper_bands()[kind]
    designs = [synthesize(plant, band, epsilon=eps) for eps in as_vector("epsilons", epsilons)]
    return EpsilonScan(kind, np.array([r.epsilon for r in designs]),
                       np.array([r.gamma_lmi for r in designs]),
                       np.array([r.gamma_sweep for r in designs]),
                       np.array([float(r.poles.real.min()) for r in designs]),
                       np.array([r.K for r in designs]), tuple(r.status for r in designs))


def _out_of_band_peak(cl, band):
    """Peak of σ_max outside an HF band, i.e. over |ω| ≤ ϖ_h."""
    return band_peak(cl, Band.lf(band.lower)).gamma


@dataclass(frozen=True)
class SigmaScan:
    """HF designs over the fictitious-pole parameter σ (see :func:`sigma_sensitivity`).

    Parameters
    ----------
    sigma : (k,) ndarray
        The values of σ.
    gamma_lmi, gamma_sweep : (k,) ndarray
        Certified γ and in-band peak of the designed closed loop.
    out_of_band : (k,) ndarray
        Peak of σ_max outside the band, over |ω| ≤ ϖ_h.
    K : (k, m, n) ndarray
        The gains.
    status : tuple of str
        cvxpy statuses.
    band_edge : float
        ϖ_h in rad/s.
    """

    sigma: np.ndarray
    gamma_lmi: np.ndarray
    gamma_sweep: np.ndarray
    out_of_band: np.ndarray
    K: np.ndarray
    status: tuple
    band_edge: float

    def rows(self) -> list:
        """One row per σ: ``sigma, gamma_lmi, gamma_sweep, out_of_band, K`` (K printed).

        Returns
        -------
        list of dict
        """
        return [{"sigma": float(s), "gamma_lmi": float(g), "gamma_sweep": float(w),
                 "out_of_band": float(o), "K": _fmt_K(K)}
                for s, g, w, o, K in zip(self.sigma, self.gamma_lmi, self.gamma_sweep,
                                         self.out_of_band, self.K, strict=True)]


def sigma_sensitivity(sigmas: ArrayLike, *, epsilon: float = DEFAULT_EPSILON) -> SigmaScan:
    """HF designs over the fictitious-pole parameter σ: LMI γ, in-band sweep, out-of-band peak.

    Parameters
    ----------
    sigmas : (k,) array_like
        Values of σ (≥ 0).
    epsilon : float, optional
        ε of the stability LMI.

    Returns
    -------
    SigmaScan
    """
    plant, band = aircraft(), paper_bands()["HF"]
    sigmas = as_vector("sigmas", sigmas)
    designs, oob = [], []
    for s in sigmas:
        r = synthesize(plant, band, epsilon=epsilon, sigma=s)
        designs.append(r)
        oob.append(_out_of_band_peak(plant.closed_loop(r.K), band))
    return SigmaScan(np.array(sigmas),
                     np.array([r.gamma_lmi for r in designs]),
                     np.array([r.gamma_sweep for r in designs]), np.array(oob),
                     np.array([r.K for r in designs]), tuple(r.status for r in designs), band.lower)


@dataclass(frozen=True)
class HFBest:
    """The HF design with the smallest certified γ over a grid of σ, beside K_f3.

    Parameters
    ----------
    sigma : float
        σ of the best design.
    K : (m, n) ndarray
        Its gain.
    gamma_lmi : float
        Its certified γ.
    in_band : float
        Its in-band peak (sweep).
    out_of_band : float
        Its peak over |ω| ≤ ϖ_h.
    K_f3_in_band, K_f3_out_of_band : float
        The same two peaks for the printed K_f3.
    scan : SigmaScan
        The whole σ scan.
    """

    sigma: float
    K: np.ndarray
    gamma_lmi: float
    in_band: float
    out_of_band: float
    K_f3_in_band: float
    K_f3_out_of_band: float
    scan: SigmaScan

    @property
    def gamma_lmi_smallest_sigma(self) -> float:
        """Certified γ at the smallest σ of the scan (σ = 0 on the default grid)."""
        return float(self.scan.gamma_lmi[np.argmin(self.scan.sigma)])

    def prose(self) -> dict:
        """The numbers the chapter quotes (:mod:`fdsc.paper.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``sigma``, ``gamma_lmi``, ``in_band``, ``out_of_band`` of the best
            design; ``K_f3_in_band``, ``K_f3_out_of_band``; ``lmi_sigma0`` (the certified γ at
            the smallest σ) and ``sigma_min`` (that σ); ``n_sigma``, ``sigma_lo``, ``sigma_hi``
            (the scan's positive grid).
        """
        pos = self.scan.sigma[self.scan.sigma > 0]
        return {"sigma": _exact(self.sigma), "gamma_lmi": num(self.gamma_lmi, 4),
                "in_band": num(self.in_band, 4), "out_of_band": num(self.out_of_band, 4),
                "K_f3_in_band": num(self.K_f3_in_band, 4), "K_f3_out_of_band": num(self.K_f3_out_of_band, 4),
                "lmi_sigma0": num(self.gamma_lmi_smallest_sigma, 4),
                "sigma_min": _exact(float(self.scan.sigma.min())), "n_sigma": count(self.scan.sigma.size),
                "sigma_lo": _exact(float(pos.min())), "sigma_hi": _exact(float(pos.max()))}

    def to_record(self) -> RecordPart:
        """Record entry ``hf_best`` (new).

        Returns
        -------
        RecordPart
        """
        return RecordPart((entry(
            "hf_best", "Sec. IV, K_f3 and paper Fig. 3 (HF design)",
            {"K": paper_data("controllers")["K_f3"]["value"], "in_band": self.K_f3_in_band,
             "out_of_band": self.K_f3_out_of_band},
            {"K": self.K, "sigma": self.sigma, "gamma_lmi": self.gamma_lmi,
             "in_band": self.in_band, "out_of_band": self.out_of_band},
            "new",
            f"not printed by the paper: best certified HF design over the sigma grid: "
            f"in-band gain {self.in_band:.4f} "
            f"(LMI {self.gamma_lmi:.4f}) and out-of-band peak {self.out_of_band:.4f}, "
            f"against {self.K_f3_in_band:.4f} and {self.K_f3_out_of_band:.1f} for the printed "
            f"K_f3 ('paper' holds K_f3's values recomputed from the printed gain)."),))


@cached
def hf_best(sigmas: ArrayLike | None = None, *, epsilon: float = DEFAULT_EPSILON) -> HFBest:
    """The HF design with the smallest certified γ over a grid of σ, beside K_f3.

    Parameters
    ----------
    sigmas : (k,) array_like, optional
        Values of σ (default :data:`HF_SIGMA_GRID`).
    epsilon : float, optional
        ε of the stability LMI.

    Returns
    -------
    HFBest
    """
    scan = sigma_sensitivity(HF_SIGMA_GRID if sigmas is None else sigmas, epsilon=epsilon)
    k = int(np.argmin(scan.gamma_lmi))
    plant, band = aircraft(), paper_bands()["HF"]
    cl3 = plant.closed_loop(paper_gains()["K_f3"])
    return HFBest(float(scan.sigma[k]), scan.K[k], float(scan.gamma_lmi[k]),
                  float(scan.gamma_sweep[k]), float(scan.out_of_band[k]), band_peak(cl3, band).gamma,
                  _out_of_band_peak(cl3, band), scan)


# -- LMIs against a direct search ----------------------------------------------------------------

@dataclass(frozen=True)
class CrosscheckCase:
    """LMI design against direct search for one random plant and band.

    Parameters
    ----------
    plant : int
        Index of the plant in the draw.
    open_loop_stable : bool
        The plant's A is Hurwitz.
    band : {"LF", "MF"}
        The band.
    gamma_lmi : float
        γ certified by the synthesis LMI.
    gamma_sweep : float
        In-band peak with the LMI gain.
    gamma_direct : float
        In-band peak with the gain of the direct search.
    lmi_excess : float
        ``(gamma_sweep − gamma_direct) / gamma_direct``.
    """

    plant: int
    open_loop_stable: bool
    band: str
    gamma_lmi: float
    gamma_sweep: float
    gamma_direct: float
    lmi_excess: float


@dataclass(frozen=True)
class DirectCrosscheck:
    """Synthesis LMIs against a direct search on seeded random plants (see
    :func:`direct_crosscheck`).

    Parameters
    ----------
    cases : tuple of CrosscheckCase
        One per plant and band.
    seed : int
        Seed of the draw.
    n_starts : int
        Starts of the direct search.
    """

    cases: tuple
    seed: int
    n_starts: int

    def rows(self) -> list:
        """One row per case with every field (for :func:`fdsc.paper.report.html_table`).

        Returns
        -------
        list of dict
        """
        return [vars(c).copy() for c in self.cases]

    def display_rows(self) -> list:
        """One row per case, formatted for the book.

        Returns
        -------
        list of dict
        """
        return [{"plant": count(c.plant + 1), "open_loop_stable": "yes" if c.open_loop_stable else "no",
                 "band": c.band, "gamma_lmi": num(c.gamma_lmi, 5), "gamma_sweep": num(c.gamma_sweep, 5),
                 "gamma_direct": num(c.gamma_direct, 5), "lmi_excess": num(c.lmi_excess, 2)}
                for c in self.cases]

    def prose(self) -> dict:
        """The numbers the chapter quotes (:mod:`fdsc.paper.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``n_plants``, ``seed``, ``n_starts``, ``lf_stable_max`` (largest
            LMI excess, LF, open-loop stable plants), ``worst`` (largest excess of all).
        """
        return {"n_plants": count(len({c.plant for c in self.cases})), "seed": count(self.seed),
                "n_starts": count(self.n_starts),
                "lf_stable_max": num(self.max_excess("LF", open_loop_stable=True), 2),
                "worst": num(max(abs(c.lmi_excess) for c in self.cases), 2)}

    def max_excess(self, band: str, *, open_loop_stable: bool) -> float:
        """Largest ``|lmi_excess|`` over the cases of one band and stability class.

        Parameters
        ----------
        band : {"LF", "MF"}
            The band.
        open_loop_stable : bool
            Which plants.

        Returns
        -------
        float
            NaN if there is no such case.
        """
        sel = [abs(c.lmi_excess) for c in self.cases
               if c.band == band and c.open_loop_stable == open_loop_stable]
        return max(sel) if sel else math.nan

    def to_record(self) -> RecordPart:
        """Record entry ``lmi_vs_direct`` (new): the LMI excess per case.

        Returns
        -------
        RecordPart
        """
        kinds = sorted({c.band for c in self.cases})
        excess = {f"{k}, {'stable' if s else 'unstable'}": self.max_excess(k, open_loop_stable=s)
                  for k in kinds for s in (True, False)}
        return RecordPart((entry(
            "lmi_vs_direct", "Sec. IV synthesis (method not printed): LMIs against a direct search",
            None, excess, "new",
            f"largest |LMI excess| = (peak with the LMI gain - peak with a Nelder-Mead gain) / "
            f"the latter, per band and open-loop stability, on {len({c.plant for c in self.cases})} "
            f"seeded random plants (seed {self.seed}, {self.n_starts} start(s) per search): "
            + ", ".join(f"{k} {v:.1e}" for k, v in excess.items())
            + ". Where it is positive beyond the sweep's tolerance the LMI design is not optimal.",
            lmi_excess=[c.lmi_excess for c in self.cases]),))


@cached
def direct_crosscheck(n_plants: int = 4, *, seed: int = 7, kinds: tuple = ("LF", "MF"),
                      n_starts: int = 1) -> DirectCrosscheck:
    """LMI synthesis against direct minimization of the band peak on seeded random plants.

    Half of the plants are open-loop stable, half are drawn unrestricted (mostly unstable).

    Parameters
    ----------
    n_plants : int, optional
        Number of random plants.
    seed : int, optional
        Seed of the draw and of the search's perturbations.
    kinds : tuple of {"LF", "MF"}, optional
        Bands to design for (LF [0, 1] and MF [1, 5] rad/s).
    n_starts : int, optional
        Starts of the direct search (:func:`fdsc.synthesis.optimize_gain`).

    Returns
    -------
    DirectCrosscheck
    """
    for kind in kinds:
        as_choice("kinds", kind, tuple(_CROSSCHECK_BANDS))
    rng = np.random.default_rng(seed)
    cases = []
    for i in range(n_plants):
        plant = random_plant(rng, stable=i % 2 == 0)
        for kind in kinds:
            band = _CROSSCHECK_BANDS[kind]
            r = synthesize(plant, band)
            d = optimize_gain(plant, band, r.K, n_starts=n_starts, rng=rng)
            cases.append(CrosscheckCase(
                i, bool(np.all(np.linalg.eigvals(plant.A).real < 0)), kind, r.gamma_lmi,
                r.gamma_sweep, d.gamma_sweep, (r.gamma_sweep - d.gamma_sweep) / d.gamma_sweep))
    return DirectCrosscheck(tuple(cases), seed, n_starts)


def record_part() -> RecordPart:
    """Record entries K_f1..K_e (gains), bound_f1..bound_e (the printed bounds, one verdict each
    with every reading tried: :mod:`fdsc.paper.printed_bounds`), hf_best, the ε scans, paper
    Remark 3's gap, the direct-search cross-check, and the figure ``sigma_max`` (paper Fig. 3).

    Returns
    -------
    RecordPart
    """
    # the appendix on the printed bounds builds on this chapter's designs (it imports this
    # module), so it is imported here, when the record asks for its entries
    from .printed_bounds import printed_bound_entries

    return (gain_comparison().to_record() + printed_bound_entries() + hf_best().to_record()
            + epsilon_sensitivity("LF").to_record() + epsilon_sensitivity("MF").to_record()
            + remark3_gap().to_record()
            + direct_crosscheck().to_record()
            + sigma_curves(paper_gains()).to_record())
