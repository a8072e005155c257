"""Chapter 'simulations': paper Figs. 7 and 8 (the ρ_p and ρ_t sweeps), the crossover of
paper Fig. 7 bisected, and the paper's objectives (P.1) and (P.2) measured.

Every run goes through the library's streaming batch simulator (:func:`fdsc.simulate_batch`):
one batch per sweep, running integrals on a coarse grid for the windows of (P.2).
"""

from dataclasses import dataclass

import numpy as np

from fdsc.paper.reproduced.nonstationary_objectives import (
    PAPER_CROSSOVER,
    Crossover,
    P1Result,
    P1Row,
    P2Result,
    crossover,
    crossover_in,
    p1_global,
    p2_localized,
    scaled_crossing,
)
from fdsc.paper.reproduced.nonstationary_sweeps import (
    CANDIDATE_NAME,
    COARSE_STEP,
    P2_WINDOWS,
    RHO_T_EXTENDED,
    SWEEP_NAMES,
    SweepRuns,
    extended_piecewise,
    family_signal,
    fdsc_designs,
    mixed_sweep,
    piecewise_sweep,
    sweep_cases,
)
from fdsc.paper.reproduced.stationary import OUR_Q_NAME
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.data import (
    STATIONARY_DT,
    aircraft,
    mixed_disturbance,
    paper_bands,
    paper_data,
    paper_gains,
)
from fdsc.paper.shared.names import CONTROLLER_GAINS
from fdsc.paper.shared.prose import count, num, pct, span, times
from fdsc.paper.shared.results import RecordPart, entry
from fdsc.paper.shared.verdict import verdict

__all__ = [
    "CANDIDATE_NAME",
    "SWEEP_NAMES",
    "COARSE_STEP",
    "P2_WINDOWS",
    "fdsc_designs",
    "sweep_cases",
    "family_signal",
    "SweepRuns",
    "RHO_T_EXTENDED",
    "PAPER_CROSSOVER",
    "mixed_sweep",
    "piecewise_sweep",
    "extended_piecewise",
    "Crossover",
    "crossover",
    "crossover_in",
    "scaled_crossing",
    "P1Row",
    "P1Result",
    "p1_global",
    "P2Result",
    "p2_localized",
    "SweepStudy",
    "sweep_study",
    "ComparatorCheck",
    "against_comparators",
    "record_part",
]


# -- everything at dt and dt/2, and the record ------------------------------------------------------

@dataclass(frozen=True)
class SweepStudy:
    """Both sweeps, the crossovers, (P.1), (P.2), each with the step dt and, for the verdicts,
    dt/2 (see :func:`sweep_study`).

    Parameters
    ----------
    mixed, piecewise : SweepRuns
        The sweeps of paper Figs. 7 and 8 with dt.
    crossover : dict
        ``{"PassC-LF": Crossover, "PassC-EF": Crossover}`` along ρ_p with dt.
    extended : SweepRuns
        :func:`extended_piecewise` with dt.
    extended_crossover : dict
        ``{"PassC-LF": Crossover, "PassC-EF": Crossover}`` along the extended ρ_t grid.
    p1 : P1Result
    p2 : P2Result
    mixed_half, piecewise_half : SweepRuns
        The sweeps with dt/2.
    crossover_half : dict
        The crossovers along ρ_p with dt/2.
    p1_half, p2_half : P1Result, P2Result
        (P.1) and (P.2) with dt/2.
    """

    mixed: SweepRuns
    piecewise: SweepRuns
    crossover: dict
    extended: SweepRuns
    extended_crossover: dict
    p1: P1Result
    p2: P2Result
    mixed_half: SweepRuns
    piecewise_half: SweepRuns
    crossover_half: dict
    p1_half: P1Result
    p2_half: P2Result

    @property
    def dt(self) -> float:
        """The step of the main runs in s."""
        return self.mixed.dt

    def max_rel_change(self) -> dict:
        """``{family: {controller: largest |E(dt/2) − E(dt)| / E(dt) over the grid}}``.

        Returns
        -------
        dict
        """
        return {a.family: {n: float(np.max(np.abs(b.energy[n] - a.energy[n]) / a.energy[n]))
                           for n in a.names}
                for a, b in ((self.mixed, self.mixed_half), (self.piecewise, self.piecewise_half))}

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        dict
            ``{name: text}``: the choices (``dt_ms``, ``dt2_ms``, ``n_rho_p``, ``n_rho_t``,
            ``n_runs``, ``coarse_step``, ``scale7``, ``scale8``), paper Fig. 7 (dominance,
            crossovers, PassC-HF's growth, the variants, switches), paper Fig. 8 (``pw_*``),
            (P.1) (``gamma_in``, ``p1_*``), (P.2) (``gamma_tol``, ``p2_*``) and the step halving
            (``halving_*``; ``halving_same`` needs the claims and is glued by the chapter).
        """
        mixed, pw, p1, p2 = self.mixed, self.piecewise, self.p1, self.p2
        sim = paper_data("simulation")
        scale7, scale8 = sim["mixed_passc_hf_scale"]["value"], sim["piecewise_passc_hf_scale"]["value"]
        hf = paper_bands()["HF"]
        e, ep = mixed.energy, pw.energy
        cross = {r: c.value for r, c in self.crossover.items()}
        half = self.crossover_half["PassC-LF"].value
        i02 = int(np.argmin(np.abs(mixed.param - 0.2)))
        hf_loop = aircraft().closed_loop(paper_gains()[CONTROLLER_GAINS["PassC-HF"]])
        chg = self.max_rel_change()
        out = {
            "dt_ms": _whole(round(self.dt * 1e3, 9)), "dt2_ms": num(self.dt * 1e3 / 2, 2),
            "n_rho_p": count(mixed.param.size), "n_rho_t": count(pw.param.size),
            "n_runs": count((mixed.param.size + pw.param.size) * len(SWEEP_NAMES)),
            "coarse_step": num(COARSE_STEP, 1), "scale7": _whole(1 / scale7), "scale8": _whole(1 / scale8),
            "alpha_02": num(mixed_disturbance(0.2).dominance(hf), 4),
            "alpha_05": num(mixed_disturbance(0.5).dominance(hf), 2),
            "cross_lf": num(cross["PassC-LF"]), "cross_lf_approx": num(cross["PassC-LF"], 2),
            "cross_lf_fine": num(cross["PassC-LF"], 4), "cross_ef": num(cross["PassC-EF"]),
            "cross_width": num(self.crossover["PassC-LF"].width, 2),
            "cross_lf_half": num(half), "cross_lf_half_fine": num(half, 4),
            "cross_scaled": num(scaled_crossing(mixed, scale7), 4), "cross_paper": num(PAPER_CROSSOVER, 1),
            "cross_changes": count(self.crossover["PassC-LF"].sign_changes),
            "hf_slow_pole": num(float(hf_loop.poles().real.max())),
            "hf_at0": num(float(e["PassC-HF"][0])), "hf_max": num(float(e["PassC-HF"].max())),
            "hf_1e6_from": _grid(mixed.param[np.argmax(e["PassC-HF"] >= 1e6)]),
            "alpha_cross": _pct(mixed_disturbance(cross["PassC-LF"]).dominance(hf), 1),
            "fdsc_over_lf_02": times(float(e["FDSC"][i02] / e["PassC-LF"][i02])),
            "hf_over_fdsc_02": times(float(e["PassC-HF"][i02] / e["FDSC"][i02])),
            "ours_over_lf_max": times(float(np.max(e[OUR_Q_NAME] / e["PassC-LF"]))),
            "halving_ours_early": _pct(max(v[OUR_Q_NAME] for v in chg.values())),
            "cand_over_hf_max": _pct(float(np.max(np.abs(e[CANDIDATE_NAME] / e["PassC-HF"] - 1))), 1),
            "sw_mixed_min": count(int(mixed.switches["FDSC"][1:].min())),
            "sw_mixed_max": count(int(mixed.switches["FDSC"].max())),
        }
        T = sim["piecewise_T"]["value"]
        xc = {r: c.value for r, c in self.extended_crossover.items()}
        first_loss = crossover_in(pw, "PassC-LF")
        out.update({
            "pw_hf_0": num(float(ep["PassC-HF"][0])), "pw_hf_1": num(float(ep["PassC-HF"][1])),
            "pw_window_1": _whole(round(float(pw.param[1] * T), 9)),
            "pw_fdsc_over_lf_max": times(float(np.max(ep["FDSC"] / ep["PassC-LF"]))),
            "pw_in_range_text": ("Within the paper's range PassC-LF never beats FDSC." if first_loss is None
                                 else f"Within the paper's range PassC-LF beats FDSC from ρ_t = "
                                      f"{num(first_loss, 2)} on."),
            "pw_ext_lf": num(xc["PassC-LF"], 2), "pw_ext_ef": num(xc["PassC-EF"], 2),
            "pw_ext_lf_s": _whole(round(xc["PassC-LF"] * T)),
            "pw_ours_over_lf": times(float(np.max(ep[OUR_Q_NAME] / ep["PassC-LF"]))),
            "pw_hf_max": num(float(ep["PassC-HF"].max())),
        })
        hf_row = next(r for r in p1.rows if r.alpha_in == 1.0)
        first = p1.rows[2]  # the smallest ρ_p > 0 of the grid
        out.update({
            "gamma_in": num(p1.gamma_in, 4), "gamma_in_printed": num(p1.gamma_in_printed),
            "p1_inherit": times(float(np.sqrt(hf_row.tail_ratio["FDSC"] / hf_row.tail_ratio["PassC-HF"])), 4),
            "p1_max_over_gamma": _pct(float(p1.sqrt_tail("FDSC")[1:].max() / p1.gamma_in), 1),
            "p1_lf_fdsc": num(float(np.sqrt(p1.rows[0].tail_ratio["FDSC"]))),
            "p1_lf_lf": num(float(np.sqrt(p1.rows[0].tail_ratio["PassC-LF"]))),
            "p1_in_band": num(float(np.sqrt(hf_row.tail_ratio["PassC-HF"])), 4),
            "p1_first_rho": _grid(first.rho_p), "p1_first_alpha": num(first.alpha_in, 4),
            "p1_first_ratio": times(float(np.sqrt(first.tail_ratio["FDSC"] / hf_row.tail_ratio["PassC-HF"]))),
            "p1_over_printed": _grid(min(r.rho_p for r in p1.rows[1:]
                                       if np.sqrt(r.tail_ratio["FDSC"]) > p1.gamma_in_printed)),
        })
        starts = np.array([[pw.worst_window_start[w]["FDSC"][i] for w in P2_WINDOWS]
                           for i in range(1, pw.param.size)])
        inside = (starts >= T) & (starts < T + pw.param[1:, None] * T)
        longest = min([w for w, ok in p2.meets("FDSC").items() if ok], default=None)
        out.update({
            "gamma_tol": _whole(p2.gamma_tol), "gamma_out_in": num(p2.gamma_out_in, 4),
            "windows": ", ".join(_whole(w) for w in P2_WINDOWS),
            **{f"p2_fdsc_{w:g}": num(p2.worst[w]["FDSC"]) for w in P2_WINDOWS},
            "p2_lf_max": num(max(p2.worst[w][n] for w in P2_WINDOWS for n in ("PassC-EF", "PassC-LF"))),
            "p2_fdsc_max": num(max(p2.worst[w]["FDSC"] for w in P2_WINDOWS)),
            "p2_in_lf": count(int(inside.sum())), "p2_n_worst": count(int(inside.size)),
            "p2_longest": "none" if longest is None else _whole(longest),
            "halving_fdsc_mixed": _pct(chg["mixed"]["FDSC"], 1),
            "halving_fdsc_pw": _pct(chg["piecewise"]["FDSC"], 1),
            "halving_ours": _pct(max(chg[f][OUR_Q_NAME] for f in chg)),
            "halving_fixed": num(max(chg[f][n] for f in chg
                                     for n in ("PassC-EF", "PassC-LF", "PassC-HF")), 2),
        })
        return out

    def to_record(self) -> RecordPart:
        """Figures ``mixed_sweep`` and ``piecewise_sweep``; entries ``mixed_crossover``,
        ``piecewise_crossover``, ``p1_global``, ``p2_localized``, ``sweep_step_halving``.

        Returns
        -------
        RecordPart
        """
        paper = PAPER_CROSSOVER
        lf = self.crossover["PassC-LF"]
        fig7 = self.mixed.to_figure()
        fig7["crossover"] = {"PassC-LF": lf.value, "PassC-EF": self.crossover["PassC-EF"].value,
                             "tolerance": lf.width, "paper": paper}
        in_range = {r: crossover_in(self.piecewise, r) for r in ("PassC-LF", "PassC-EF")}
        entries = (
            entry("mixed_crossover", "Sec. IV, text on paper Fig. 7: 'rho_p <= 0.2'", paper,
                  {r: c.value for r, c in self.crossover.items()},
                  "not reproducible" if lf.value is None else verdict(paper, lf.value, decimals=1),
                  "rho_p at which FDSC's energy over [0, 500] reaches PassC-LF's (PassC-LF has the "
                  "smaller energy of PassC-EF and PassC-LF at every rho_p), bisected by full runs to "
                  "a bracket of width <= 1e-3; compared with the printed 0.2 to its one decimal.",
                  brackets={r: list(c.bracket) if c.bracket else None for r, c in self.crossover.items()},
                  with_half_step={r: c.value for r, c in self.crossover_half.items()},
                  passc_hf_scaled_crossing=scaled_crossing(
                      self.mixed, paper_data("simulation")["mixed_passc_hf_scale"]["value"]),
                  grid_sign_changes={r: c.sign_changes for r, c in self.crossover.items()}),
            entry("piecewise_crossover", "Sec. IV, text on paper Fig. 8: 'with the increase of the "
                  "ratio ... EF or LF may be a better option'", None,
                  {"in_paper_range": in_range,
                   "extended": {r: c.value for r, c in self.extended_crossover.items()},
                   "extended_grid": self.extended.param.tolist()}, "new",
                  "rho_t at which FDSC's energy reaches PassC-LF's or PassC-EF's: on the paper's "
                  "grid of [0, 0.5] (none if FDSC is better at every point) and, beyond it, bisected "
                  "to a bracket of width <= 1e-2."),
            entry("sweep_step_halving", "our check (both sweeps with dt and dt/2; nothing printed)",
                  None, {"dt": self.dt, "max_rel_change": self.max_rel_change(),
                         "crossover": {r: [self.crossover[r].value, self.crossover_half[r].value]
                                       for r in self.crossover}}, "new",
                  "the sweeps of paper Figs. 7 and 8 and the bisected crossover repeated with half "
                  "the step: the fixed gains change by their quadrature error only, FDSC by its "
                  "sampled law."),
        )
        return (RecordPart(entries, {"mixed_sweep": fig7, "piecewise_sweep": self.piecewise.to_figure()})
                + self.p1.to_record() + self.p2.to_record())


@cached
def sweep_study(*, dt: float = STATIONARY_DT) -> SweepStudy:
    """Everything of the chapter: both sweeps, the crossovers (bisected to 1e-3 along ρ_p, 1e-2
    along the extended ρ_t grid), (P.1), (P.2), and the sweeps and crossovers again with dt/2.

    Parameters
    ----------
    dt : float, optional
        Step in s.

    Returns
    -------
    SweepStudy
    """
    rivals = ("PassC-LF", "PassC-EF")
    mixed, piecewise, ext = mixed_sweep(dt=dt), piecewise_sweep(dt=dt), extended_piecewise(dt=dt)
    mixed_half, piecewise_half = mixed_sweep(dt=dt / 2), piecewise_sweep(dt=dt / 2)
    return SweepStudy(mixed, piecewise, {r: crossover(mixed, r) for r in rivals}, ext,
                      {r: crossover(ext, r, tol=1e-2) for r in rivals}, p1_global(mixed),
                      p2_localized(piecewise), mixed_half, piecewise_half,
                      {r: crossover(mixed_half, r) for r in rivals}, p1_global(mixed_half),
                      p2_localized(piecewise_half))


def _whole(x):
    """A count or a length as the prose prints it: whole numbers without decimals."""
    x = float(x)
    return count(int(x)) if x.is_integer() else num(x)


def _grid(x):
    """A point of a sweep's grid as it was chosen (0.025, 0.3), without trailing zeros."""
    return f"{round(float(x), 9):g}".replace("-", "−")


def _pct(x, digits=0):
    """A relative change or share as a percentage (changes may exceed 100 %)."""
    x = float(x)
    return pct(x, digits) if 0.0 <= x <= 1.0 else f"{num(100 * x)} %"


@dataclass(frozen=True)
class ComparatorCheck:
    """FDSC against the comparator set (:mod:`fdsc.paper.shared.comparators`) along one sweep.

    Parameters
    ----------
    family : {"mixed", "piecewise"}
        The sweep (paper Fig. 7 or 8).
    param : (m,) ndarray
        ρ_p or ρ_t.
    best : tuple of str
        The best fixed controller at each point: the member of the comparator set of least
        energy.
    best_energy, fdsc, open_loop : (m,) ndarray
        ∫zᵀz of the best fixed controller, of FDSC (paper's gains and Q's) and of the open loop
        at each point.
    chosen : str
        The fixed controller chosen in advance (:mod:`fdsc.paper.shared.fixed_choice`).
    chosen_energy : (m,) ndarray
        Its ∫zᵀz at each point.
    """

    family: str
    param: np.ndarray
    best: tuple
    best_energy: np.ndarray
    fdsc: np.ndarray
    open_loop: np.ndarray
    chosen: str = ""
    chosen_energy: np.ndarray | None = None

    @property
    def n_fdsc_better(self) -> int:
        """Number of points at which FDSC has less energy than the best fixed controller."""
        return int(np.sum(self.fdsc < self.best_energy))

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``n_better``, ``n`` (points), ``winners`` (which member is best how
            often, in words), ``ratio`` (FDSC's energy over the best fixed one's, as a range of
            factors), ``open_loop_better`` (points at which the open loop alone has less energy
            than FDSC), ``chosen``, ``chosen_better`` (points at which FDSC has less energy than
            the fixed controller chosen in advance), ``chosen_ratio`` (FDSC's over its, a range).
        """
        names, counts = np.unique(np.asarray(self.best), return_counts=True)
        order = np.argsort(-counts, kind="stable")
        ratio = self.fdsc / self.best_energy
        lo, hi = float(ratio.min()), float(ratio.max())
        out = {"n_better": count(self.n_fdsc_better), "n": count(len(self.best)),
               "winners": ", ".join(f"{names[k]} at {count(int(counts[k]))}" for k in order),
               "ratio": times(lo) if times(lo) == times(hi) else f"{times(lo)} to {times(hi)}",
               "open_loop_better": count(int(np.sum(self.open_loop < self.fdsc)))}
        if self.chosen_energy is not None:
            rc = self.fdsc / self.chosen_energy
            out |= {"chosen": self.chosen, "chosen_better": count(int(np.sum(rc < 1))),
                    "chosen_ratio": span(float(rc.min()), float(rc.max()), fmt=times)}
        return out


def against_comparators() -> dict:
    """FDSC against the best comparator of each point of both sweeps.

    The energies come from :func:`fdsc.paper.reproduced.paper_cases.baselines`, whose mixed and piecewise
    scenarios are the points of paper Figs. 7 and 8 with every controller of the comparator set
    (the open loop and the best certified HF design included).

    Returns
    -------
    dict
        ``{"mixed": ComparatorCheck, "piecewise": ComparatorCheck}``.
    """
    from fdsc.paper.reproduced.chosen_cases import chosen_energies
    from fdsc.paper.reproduced.paper_cases import baselines
    from fdsc.paper.shared.comparators import best_fixed

    base, chosen = baselines(), chosen_energies()
    out = {}
    for family in ("mixed", "piecewise"):
        scen = base.family(family)
        best = [best_fixed(s.energy, "aircraft") for s in scen]
        out[family] = ComparatorCheck(family, np.array([s.param for s in scen]), tuple(b[0] for b in best),
                                      np.array([b[1] for b in best]),
                                      np.array([s.energy["FDSC"] for s in scen]),
                                      np.array([s.energy["open loop"] for s in scen]), chosen["name"],
                                      np.array(chosen[family]))
    return out


def record_part() -> RecordPart:
    """Record figures and entries of the chapter (see :meth:`SweepStudy.to_record`).

    Returns
    -------
    RecordPart
    """
    return sweep_study().to_record()
