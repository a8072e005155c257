"""Chapter 'passive_controllers', continued: the gains of Sec. IV recomputed by synthesis.

The LF, MF, HF (fictitious pole σ) and H∞ gains of Sec. IV synthesized by the library's LMIs
for the aircraft, each printed gain beside the recomputed one, with the in-band gains of both.
"""

from dataclasses import dataclass

import numpy as np

from fdsc.frequency import band_peak
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.data import aircraft, paper_bands, paper_gains
from fdsc.paper.shared.names import GAIN_BANDS, GAIN_ORDER
from fdsc.paper.shared.prose import num
from fdsc.paper.shared.results import RecordPart, entry, pick
from fdsc.paper.shared.verdict import verdict
from fdsc.plant import Plant
from fdsc.synthesis import DEFAULT_EPSILON, SynthesisResult, synthesize, synthesize_hinf

__all__ = ["GainComparison", "GainDesigns", "GainRow", "UNPRINTED", "gain_comparison", "recompute_gains"]

#: The parameters of each band's synthesis that Sec. IV does not print: ε of the stability LMI
#: (LF, MF, HF) and the fictitious pole σ of the HF slack; the H∞ design needs none. A printed
#: gain that our design does not recompute within 1 % is therefore not reproducible (the
#: verdict rules of :mod:`fdsc.paper.shared.verdict`), not a gain that differs.
UNPRINTED = {"LF": ("ε",), "MF": ("ε",), "HF": ("σ", "ε"), "EF": ()}


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
            One of :data:`fdsc.paper.shared.names.GAIN_ORDER`.

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
        how = "H∞ state-feedback LMI" if band == "EF" else f"{band} synthesis LMI"
        missing = " or ".join(UNPRINTED[band])
        why = (f"Not reproducible: the paper does not print {missing}, which the design needs, and "
               "the HF LMI is only sufficient, its gain moving with σ (see the best HF design). "
               if self.verdict == "not reproducible" else "")
        return entry(
            self.name, f"Sec. IV, {self.name}", self.paper_K, self.ours_K, self.verdict,
            why + f"{how} (derived in the passive-controller chapter"
            + ("" if band == "EF" else f"; stability LMI with ε = {self.epsilon:g}")
            + ("; σ = 0" if band == "HF" else "") + f"); relative difference "
            f"{self.rel_diff:.2e}; in-band gain of the printed gain "
            f"{self.gamma_paper_gain:.4f}, of ours {self.gamma_sweep:.4f} "
            f"(LMI bound {self.gamma_lmi:.4f})."
            + ("" if band == "HF" else
               " The optimal gains are high-gain and γ is flat along the gain's size, "
               "so only a few digits are determined."))


@dataclass(frozen=True)
class GainComparison:
    """The printed gains beside the recomputed ones.

    Parameters
    ----------
    gains : tuple of GainRow
        In the order of :data:`fdsc.paper.shared.names.GAIN_ORDER`.
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
        :func:`fdsc.paper.shared.report.html_table`).

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
        """The numbers the chapter quotes (:mod:`fdsc.paper.shared.prose`).

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
            res.status, verdict(Kp, res.K, unprinted=UNPRINTED[band.kind]), res.epsilon, res.sigma))
    return GainComparison(tuple(rows))
