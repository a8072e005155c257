"""Chapter 'simulations': paper Figs. 4, 5 and 6 (stationary LF and HF disturbances, four
controllers), energies, the paper's sentences about these figures, and step halving.
"""

from dataclasses import dataclass

from fdsc.paper.reproduced.stationary_claims import (
    Claim,
    HFOutputClaims,
    L2Claims,
    LFOutputClaims,
    hf_l2_claims,
    hf_output_claims,
    lf_output_claims,
)
from fdsc.paper.reproduced.stationary_figures import OUR_Q_NAME, StationaryRuns, _whole, stationary_runs
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.data import STATIONARY_DT, paper_disturbance, run_controller
from fdsc.paper.shared.names import CONTROLLERS
from fdsc.paper.shared.prose import count, num, times
from fdsc.paper.shared.results import RecordPart, entry
from fdsc.simulate import time_grid

__all__ = [
    "record_part",
    "OUR_Q_NAME",
    "StationaryRuns",
    "stationary_runs",
    "Claim",
    "LFOutputClaims",
    "lf_output_claims",
    "HFOutputClaims",
    "hf_output_claims",
    "L2Claims",
    "hf_l2_claims",
    "HalvingRow",
    "StepHalving",
    "step_halving",
    "StationaryComparison",
    "against_comparators",
]


@dataclass(frozen=True)
class HalvingRow:
    """Energy and switch count of one controller with the step dt and dt/2.

    Parameters
    ----------
    controller : str
        One of the paper's four controllers.
    energy_dt, energy_dt2 : float
        ∫zᵀz with dt and with dt/2.
    switches_dt, switches_dt2 : int
        Number of switches with dt and with dt/2.
    """

    controller: str
    energy_dt: float
    energy_dt2: float
    switches_dt: int
    switches_dt2: int

    @property
    def rel_change(self) -> float:
        """``|E(dt/2) − E(dt)| / |E(dt)|``."""
        return abs(self.energy_dt2 - self.energy_dt) / abs(self.energy_dt)


@dataclass(frozen=True)
class StepHalving:
    """Energies and switch counts with dt and dt/2 (see :func:`step_halving`).

    Parameters
    ----------
    kind : {"LF", "HF"}
        The disturbance.
    horizon, dt : float
        Run length and the coarser step in s.
    controllers : tuple of HalvingRow
        One per controller.
    """

    kind: str
    horizon: float
    dt: float
    controllers: tuple

    @property
    def max_rel_change(self) -> float:
        """Largest relative change of an energy."""
        return max(r.rel_change for r in self.controllers)

    def row(self, controller: str) -> HalvingRow:
        """The row of one controller.

        Parameters
        ----------
        controller : str
            One of the paper's four controllers.

        Returns
        -------
        HalvingRow
        """
        for r in self.controllers:
            if r.controller == controller:
                return r
        raise KeyError(f"controller must be one of {[r.controller for r in self.controllers]}, "
                       f"but found {controller!r}")

    def rows(self) -> list:
        """One row per controller (for :func:`fdsc.paper.shared.report.html_table`).

        Returns
        -------
        list of dict
            ``disturbance, controller, energy_dt, energy_dt2, rel_change, switches_dt,
            switches_dt2``.
        """
        return [{"disturbance": self.kind, "controller": r.controller, "energy_dt": r.energy_dt,
                 "energy_dt2": r.energy_dt2, "rel_change": r.rel_change,
                 "switches_dt": r.switches_dt, "switches_dt2": r.switches_dt2}
                for r in self.controllers]

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``horizon``, ``max`` (largest relative change), and FDSC's
            ``sw1`` and ``sw2`` (switches with dt and dt/2) and ``fdsc`` (relative change).
        """
        r = self.row("FDSC")
        return {"horizon": _whole(self.horizon), "max": num(self.max_rel_change, 2),
                "sw1": count(int(r.switches_dt)), "sw2": count(int(r.switches_dt2)),
                "fdsc": num(r.rel_change, 2)}

    def table_rows(self) -> list:
        """:meth:`rows` as the book prints them (energies to 7 digits, changes to 2).

        Returns
        -------
        list of dict
        """
        return [{**r, "energy_dt": num(r["energy_dt"], 7), "energy_dt2": num(r["energy_dt2"], 7),
                 "rel_change": num(r["rel_change"], 2), "switches_dt": count(int(r["switches_dt"])),
                 "switches_dt2": count(int(r["switches_dt2"]))} for r in self.rows()]

    def to_record(self) -> RecordPart:
        """Record entry ``step_halving_lf`` or ``step_halving_hf`` (new).

        Returns
        -------
        RecordPart
        """
        rec = {r.controller: {"rel_change": r.rel_change, "switches_dt": r.switches_dt,
                              "switches_dt2": r.switches_dt2} for r in self.controllers}
        return RecordPart((entry(
            f"step_halving_{self.kind.lower()}", f"our check (step dt and dt/2, {self.kind} "
            "disturbance; nothing printed)", None, rec, "new",
            f"{self.horizon:g} s runs with dt = {self.dt:g} s and dt/2: relative change of the "
            "energy (quadrature error for the fixed gains; the sampled law for FDSC) and the "
            "switch counts (a count that scales with the sampling rate is chattering).",
            max_rel_change=self.max_rel_change),))


@cached
def step_halving(kind: str, *, horizon: float = 100.0, dt: float = STATIONARY_DT) -> StepHalving:
    """Energies and switch counts with dt and dt/2 for every controller (the law is sampled).

    Parameters
    ----------
    kind : {"LF", "HF"}
        The paper's LF (paper eq. (56)) or HF (paper eq. (57)) disturbance.
    horizon, dt : float, optional
        Run length and the coarser step in s.

    Returns
    -------
    StepHalving
    """
    d = paper_disturbance(kind)
    rows = []
    for name in CONTROLLERS:
        s1 = run_controller(name, d, time_grid(horizon, dt))
        s2 = run_controller(name, d, time_grid(horizon, dt / 2))
        rows.append(HalvingRow(name, s1.energy(), s2.energy(), int(s1.switch_times.size),
                               int(s2.switch_times.size)))
    return StepHalving(kind, float(horizon), float(dt), tuple(rows))


@dataclass(frozen=True)
class StationaryComparison:
    """FDSC against the comparator set (:mod:`fdsc.paper.shared.comparators`) in one stationary case.

    Parameters
    ----------
    kind : {"LF", "HF"}
        The paper's disturbance.
    best : str
        The member of the comparator set of least energy in this case (known only after it).
    best_energy, fdsc : float
        ∫zᵀz of that member and of FDSC (paper's gains and Q's).
    chosen : str
        The fixed controller chosen in advance (:mod:`fdsc.paper.shared.fixed_choice`).
    chosen_energy : float
        Its ∫zᵀz.
    """

    kind: str
    best: str
    best_energy: float
    fdsc: float
    chosen: str = ""
    chosen_energy: float = float("nan")

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``best`` (its name), ``best_energy``, ``ratio`` (FDSC's energy
            over the best member's, as a factor), ``chosen``, ``chosen_energy``,
            ``chosen_ratio`` (FDSC's over the fixed controller chosen in advance's).

        Examples
        --------
        >>> StationaryComparison("HF", "open loop", 8.74, 9.05, "tuned", 4.525).prose()["chosen_ratio"]
        '×2.00'
        """
        return {"best": self.best, "best_energy": num(self.best_energy, 4),
                "ratio": times(self.fdsc / self.best_energy), "chosen": self.chosen,
                "chosen_energy": num(self.chosen_energy, 4),
                "chosen_ratio": times(self.fdsc / self.chosen_energy)}


def against_comparators() -> dict:
    """FDSC against the best fixed controller of the paper's two stationary cases.

    The energies come from :func:`fdsc.paper.reproduced.paper_cases.baselines`, which runs the stationary
    cases with every member of the comparator set (the open loop and the best certified HF design
    included).

    Returns
    -------
    dict
        ``{"LF": StationaryComparison, "HF": StationaryComparison}``.
    """
    from fdsc.paper.reproduced.chosen_cases import chosen_energies
    from fdsc.paper.reproduced.paper_cases import baselines
    from fdsc.paper.shared.comparators import best_fixed

    out = {}
    chosen = chosen_energies()
    for scen, e in zip(baselines().family("stationary"), chosen["stationary"], strict=True):
        name, energy = best_fixed(scen.energy, "aircraft")
        out[scen.label] = StationaryComparison(scen.label, name, float(energy), float(scen.energy["FDSC"]),
                                               chosen["name"], float(e))
    return out


def record_part() -> RecordPart:
    """Record figures and entries of the chapter.

    Figures ``lf_outputs``, ``hf_outputs`` (paper Figs. 4 and 5: energies and switch counts) and
    ``hf_l2`` (paper Fig. 6: the L2-induced norm); entries ``lf_outputs_claims``,
    ``hf_outputs_claims``, ``hf_l2_claims`` (the paper's sentences about these figures),
    ``step_halving_lf`` and ``step_halving_hf`` (new).

    Returns
    -------
    RecordPart
    """
    lf, hf = stationary_runs("LF"), stationary_runs("HF")
    return (lf.to_record() + hf.to_record() + lf_output_claims(lf).to_record()
            + hf_output_claims(hf).to_record() + hf_l2_claims(hf).to_record()
            + step_halving("LF").to_record() + step_halving("HF").to_record())
