"""Chapter 'passive_controllers': the gains of Sec. IV recomputed by synthesis, paper Fig. 3, ε and
σ, the best HF design, paper Remark 3's gap, LMIs against a direct search. The bounds printed
beside the gains are judged in the appendix :mod:`fdsc.paper.reproduced.printed_bounds`.
"""

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from fdsc._validation import as_choice, as_vector
from fdsc.frequency import sigma_max
from fdsc.paper.reproduced.passive_crosscheck import CrosscheckCase, DirectCrosscheck, direct_crosscheck
from fdsc.paper.reproduced.passive_gains import (
    GainComparison,
    GainDesigns,
    GainRow,
    gain_comparison,
    recompute_gains,
)
from fdsc.paper.reproduced.passive_sensitivity import (
    EPSILON_GRID,
    HF_SIGMA_GRID,
    EpsilonScan,
    HFBest,
    SigmaScan,
    epsilon_sensitivity,
    hf_best,
    sigma_sensitivity,
)
from fdsc.paper.shared.data import aircraft, paper_bands, paper_data, paper_gains
from fdsc.paper.shared.names import FDSC_IN_BAND, FIGURE_IDS, GAIN_BANDS, GAIN_ORDER
from fdsc.paper.shared.prose import num
from fdsc.paper.shared.results import RecordPart, entry

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
        One of :data:`fdsc.paper.shared.names.GAIN_ORDER`.

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
        """The numbers the chapter quotes (:mod:`fdsc.paper.shared.prose`).

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


def record_part() -> RecordPart:
    """Record entries K_f1..K_e (gains), bound_f1..bound_e (the printed bounds, one verdict each
    with every reading tried: :mod:`fdsc.paper.reproduced.printed_bounds`), hf_best, the ε scans, paper
    Remark 3's gap, the direct-search cross-check, and the figure ``sigma_max`` (paper Fig. 3).

    Returns
    -------
    RecordPart
    """
    # the appendix on the printed bounds builds on this chapter's designs (it imports this
    # module), so it is imported here, when the record asks for its entries
    from fdsc.paper.reproduced.printed_bounds import printed_bound_entries

    return (gain_comparison().to_record() + printed_bound_entries() + hf_best().to_record()
            + epsilon_sensitivity("LF").to_record() + epsilon_sensitivity("MF").to_record()
            + remark3_gap().to_record()
            + direct_crosscheck().to_record()
            + sigma_curves(paper_gains()).to_record())
