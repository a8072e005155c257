"""Chapter 'passive_controllers', continued: the LMIs against a direct search.

On seeded random plants and bands, the γ certified by the synthesis LMIs set against the
smallest band peak a direct minimization over the gain finds.
"""

import math
from dataclasses import dataclass

import numpy as np

from fdsc._validation import as_choice
from fdsc.bands import Band
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.prose import count, num
from fdsc.paper.shared.results import RecordPart, entry
from fdsc.random_systems import random_plant
from fdsc.synthesis import optimize_gain, synthesize

__all__ = ["CrosscheckCase", "DirectCrosscheck", "direct_crosscheck"]


#: Bands of the random plants of :func:`direct_crosscheck` (not the paper's: the plants are random).
_CROSSCHECK_BANDS = {"LF": Band.lf(1.0), "MF": Band.mf(1.0, 5.0)}


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
        """One row per case with every field (for :func:`fdsc.paper.shared.report.html_table`).

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
        """The numbers the chapter quotes (:mod:`fdsc.paper.shared.prose`).

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
