"""The paper's simulation cases run with every controller of the book: the aircraft as an
:class:`~fdsc.paper.shared.examples.Example` (the comparator set and three FDSC variants) in the
stationary LF and HF cases and along the ρ_p and ρ_t families of paper Figs. 7 and 8.

Chapter 'stationary' and chapter 'nonstationary' set FDSC beside the best fixed controller of
these runs; chapter 'baselines' (Part II) says who wins where. The paper's four controllers reuse
the runs of :mod:`fdsc.paper.reproduced.nonstationary_sweeps` (the same cases, computed once per
build); the others run here, through the library's public API.
"""

from dataclasses import dataclass

import numpy as np

import fdsc
from fdsc.paper.reproduced.nonstationary_sweeps import family_signal, mixed_sweep, piecewise_sweep
from fdsc.paper.reproduced.passive_sensitivity import hf_best
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.comparators import HF_BEST, comparators
from fdsc.paper.shared.data import (
    STATIONARY_DT,
    STATIONARY_HORIZON,
    aircraft,
    paper_bands,
    paper_disturbance,
    paper_fdsc,
    paper_gains,
)
from fdsc.paper.shared.examples import OPEN_LOOP, Example, beats
from fdsc.paper.shared.results import RecordPart, entry

__all__ = [
    "HF_BEST",
    "FDSC_DWELL",
    "FDSC_HF_BEST",
    "FIXED",
    "SWITCHED",
    "DWELL_TAU",
    "aircraft_example",
    "Scenario",
    "Baselines",
    "baselines",
    "chosen_runs",
]

#: FDSC as printed but with a minimum dwell time (chapter 'wellposed_laws').
FDSC_DWELL = "FDSC (dwell)"
#: FDSC with K_f1 on Ω_1 and the best HF design on Ω_3, Q's by paper Remark 4.
FDSC_HF_BEST = "FDSC (HF best)"

#: The fixed gains compared, in order: the comparator set of the aircraft
#: (:data:`fdsc.paper.shared.comparators.COMPARATORS`).
FIXED = comparators("aircraft")
#: The switched controllers compared, in order.
SWITCHED = ("FDSC", FDSC_DWELL, FDSC_HF_BEST)

#: Minimum dwell time (s) of :data:`FDSC_DWELL`: the default that the law study of chapter
#: 'wellposed_laws' picks (least mean log energy ratio over its grid; checked by its tests).
DWELL_TAU = 0.01

# the controllers that chapter 'nonstationary' has already run on both families
_SWEPT = ("PassC-EF", "PassC-LF", "PassC-HF", "FDSC")


@cached
def aircraft_example() -> Example:
    """The paper's aircraft (paper eq. (10)) as an :class:`~fdsc.paper.shared.examples.Example`.

    Fixed gains :data:`FIXED` (the open loop, K_e, K_f1, K_f3 and the best certified HF design),
    switched controllers :data:`SWITCHED`. Random tones are drawn in [0.1, 1] rad/s (LF; the
    slowest printed tone is 0.1 rad/s) and [10, 300] rad/s (HF; up to the fastest printed tone);
    runs of 200 s at 1 ms (three periods of the slowest tone).

    Returns
    -------
    Example

    Examples
    --------
    >>> ex = aircraft_example()
    >>> ex.names[:3], ex.names[-1]
    (('open loop', 'PassC-EF', 'PassC-LF'), 'FDSC (HF best)')
    """
    plant, gains, bands = aircraft(), paper_gains(), paper_bands()
    best = hf_best()
    printed = paper_fdsc("paper")
    with_best = fdsc.FDSC.from_gains(plant, [gains["K_f1"], best.K], [bands["LF"], bands["HF"]], 1)
    return Example(
        "aircraft", plant, {"LF": bands["LF"], "HF": bands["HF"]},
        {OPEN_LOOP: np.zeros_like(best.K), "PassC-EF": gains["K_e"], "PassC-LF": gains["K_f1"],
         "PassC-HF": gains["K_f3"], HF_BEST: best.K},
        {"FDSC": (printed, fdsc.PRINTED), FDSC_DWELL: (printed, fdsc.SwitchRule.dwell_time(DWELL_TAU)),
         FDSC_HF_BEST: (with_best, fdsc.PRINTED)},
        (0.1, 1.0), (10.0, 300.0), 200.0, STATIONARY_DT)


@dataclass(frozen=True)
class Scenario:
    """Every controller under one disturbance of the paper's simulation section.

    Parameters
    ----------
    label : str
        "LF", "HF", "ρ_p = 0.1", "ρ_t = 0.2", ...
    family : {"stationary", "mixed", "piecewise"}
    param : float
        ρ_p or ρ_t (NaN for the stationary cases).
    energy : dict
        ``{controller: ∫zᵀz}`` over the run.
    input_energy : float
        ∫d² over the run.
    """

    label: str
    family: str
    param: float
    energy: dict
    input_energy: float

    def winner(self, among=None) -> str:
        """The controller of least energy.

        Parameters
        ----------
        among : sequence of str, optional
            The controllers compared (default all).

        Returns
        -------
        str
        """
        among = tuple(self.energy) if among is None else tuple(among)
        return min(among, key=lambda n: self.energy[n])

    def factor(self, name: str, among=None) -> float:
        """Energy of a controller over the least energy (1 for the winner).

        Parameters
        ----------
        name : str
            The controller.
        among : sequence of str, optional
            The controllers whose least energy is the reference (default all).

        Returns
        -------
        float
        """
        return float(self.energy[name] / self.energy[self.winner(among)])


@dataclass(frozen=True)
class Baselines:
    """The paper's simulation cases with every baseline (see :func:`baselines`).

    Parameters
    ----------
    names : tuple of str
        :data:`FIXED` + :data:`SWITCHED`.
    scenarios : tuple of Scenario
        Stationary LF, stationary HF, the ρ_p family (paper Fig. 7), the ρ_t family (paper Fig. 8).
    steady : dict
        ``{fixed controller: {"LF": γ, "HF": γ}}``: steady-state L2 gain on the printed LF and HF
        tones (closed form, :func:`fdsc.steady_state_gain`).
    peaks : dict
        ``{fixed controller: {"LF": peak, "HF": peak}}``: σ_max peak over each band.
    gammas : dict
        ``{switched controller: (2,) ndarray}``: γ_i for which Theorem 1's LMIs are feasible with its Q's.
    switches : dict
        ``{switched controller: (k,) ndarray}``: switch count in each scenario.
    ideal_piecewise : (r,) ndarray
        ∫zᵀz of the ideal segment law over the ρ_t family (PassC-HF on the HF pieces, PassC-LF
        on the LF piece, :meth:`~fdsc.paper.shared.examples.Example.segment_ideal`).
    """

    names: tuple
    scenarios: tuple
    steady: dict
    peaks: dict
    gammas: dict
    switches: dict
    ideal_piecewise: np.ndarray

    def ideal_ratio(self) -> np.ndarray:
        """The ideal segment law's energy over the least energy of the fixed gains, along ρ_t."""
        return np.array([e / s.energy[s.winner(FIXED)]
                         for e, s in zip(self.ideal_piecewise, self.family("piecewise"), strict=True)])

    def family(self, family: str) -> tuple:
        """The scenarios of one family.

        Parameters
        ----------
        family : {"stationary", "mixed", "piecewise"}

        Returns
        -------
        tuple of Scenario
        """
        return tuple(s for s in self.scenarios if s.family == family)

    def energies(self, family: str) -> tuple:
        """The parameters and energies of one family.

        Parameters
        ----------
        family : {"stationary", "mixed", "piecewise"}

        Returns
        -------
        param : (m,) ndarray
            ρ_p or ρ_t (NaN for the stationary cases).
        energy : dict
            ``{controller: (m,) ndarray}``.
        """
        sc = self.family(family)
        return (np.array([s.param for s in sc]),
                {n: np.array([s.energy[n] for s in sc]) for n in self.names})

    def wins(self, among=None) -> dict:
        """How many scenarios each controller wins.

        Parameters
        ----------
        among : sequence of str, optional
            The controllers compared (default all).

        Returns
        -------
        dict
            ``{controller: number of scenarios of least energy}``.
        """
        among = self.names if among is None else tuple(among)
        out = dict.fromkeys(among, 0)
        for s in self.scenarios:
            out[s.winner(among)] += 1
        return out

    def winner_table(self) -> list:
        """One row per stretch of scenarios with the same winner: which controller wins where, and
        by how much (over the runner-up), with FDSC's and FDSC (HF best)'s factors to the winner.

        Returns
        -------
        list of dict
        """
        rows, current = [], None
        for s in self.scenarios:
            w = s.winner()
            if current is None or current["family"] != s.family or current["winner"] != w:
                current = {"family": s.family, "from": s.label, "to": s.label, "winner": w,
                           "margins": [], "fdsc": [], "fdsc_best": []}
                rows.append(current)
            current["to"] = s.label
            current["margins"].append(s.factor(min((n for n in self.names if n != w),
                                                   key=lambda n: s.energy[n])))
            current["fdsc"].append(s.factor("FDSC"))
            current["fdsc_best"].append(s.factor(FDSC_HF_BEST))
        return [{"family": r["family"],
                 "scenarios": r["from"] if r["from"] == r["to"] else f"{r['from']} … {r['to']}",
                 "winner": r["winner"], "runner-up factor": (min(r["margins"]), max(r["margins"])),
                 "FDSC / winner": (min(r["fdsc"]), max(r["fdsc"])),
                 f"{FDSC_HF_BEST} / winner": (min(r["fdsc_best"]), max(r["fdsc_best"]))}
                for r in rows]

    def switched_ratio(self, name: str) -> np.ndarray:
        """Energy of a switched controller over the least energy of the fixed ones, per case.

        Parameters
        ----------
        name : str
            One of :data:`SWITCHED`.

        Returns
        -------
        (k,) ndarray
        """
        return np.array([s.energy[name] / s.energy[s.winner(FIXED)] for s in self.scenarios])

    def pays(self) -> str:
        """One sentence: whether FDSC (any of its variants) pays in the paper's cases, with numbers."""
        n = len(self.scenarios)
        ratios = {k: self.switched_ratio(k) for k in SWITCHED}
        best = max(SWITCHED, key=lambda k: (int(np.sum(beats(ratios[k]))), -np.median(ratios[k])))
        fixed = {k: v for k, v in self.wins(FIXED).items() if v}
        r = ratios[best]
        any_win = int(np.sum(beats(np.min([ratios[k] for k in SWITCHED], axis=0))))
        return (f"A switched controller has less energy than every fixed one in {any_win} of the {n} "
                f"cases; the best variant, {best}, has "
                f"{r.min():.3g} to {r.max():.3g} times the energy of the best comparator of the case "
                f"(median {np.median(r):.3g}), and the best comparator is "
                + ", ".join(f"{k} in {v}" for k, v in fixed.items()) + " of the cases. "
                f"The ideal segment law (PassC-LF on the LF piece, PassC-HF on the HF pieces of the "
                f"ρ_t family) has {self.ideal_ratio().min():.3g} to {self.ideal_ratio().max():.3g} "
                f"times the energy of the best comparator of the case: it beats it at "
                f"{int(np.sum(beats(self.ideal_ratio())))} of {self.ideal_ratio().size} values of ρ_t.")

    def hf_best_gain(self) -> dict:
        """``{family: (min, max)}`` of FDSC (HF best)'s energy over the printed FDSC's."""
        out = {}
        for fam in ("stationary", "mixed", "piecewise"):
            r = [s.energy[FDSC_HF_BEST] / s.energy["FDSC"] for s in self.family(fam)]
            out[fam] = (float(min(r)), float(max(r)))
        return out

    def to_record(self) -> RecordPart:
        """Record entries ``baselines`` and ``hf_good_in_band`` (new).

        Returns
        -------
        RecordPart
        """
        wins = self.wins()
        stat = {s.label: {n: s.energy[n] for n in self.names} for s in self.family("stationary")}
        table = [{k: list(v) if isinstance(v, tuple) else v for k, v in r.items()}
                 for r in self.winner_table()]
        lf, hf = self.family("stationary")
        note = (f"not printed by the paper: over the {len(self.scenarios)} simulation cases of the paper "
                f"(stationary LF and HF, {len(self.family('mixed'))} values of rho_p, "
                f"{len(self.family('piecewise'))} of rho_t), the wins are "
                + ", ".join(f"{n} {k}" for n, k in wins.items() if k)
                + f"; under the HF tones the open loop has {hf.factor(OPEN_LOOP):.3g} "
                f"times the least energy, under the LF tones {lf.factor(OPEN_LOOP):.3g} times.")
        g = self.hf_best_gain()
        hb = hf_best()
        note_best = (f"not printed by the paper: FDSC with the best certified HF design (in-band peak "
                     f"{hb.in_band:.4f}, out of band {hb.out_of_band:.3f}) in place of K_f3 (in band "
                     f"{hb.K_f3_in_band:.4f}, out of band {hb.K_f3_out_of_band:.1f}) has "
                     + "; ".join(f"{a:.3g} to {b:.3g} times the printed FDSC's energy ({fam})"
                                 for fam, (a, b) in g.items()) + ".")
        return RecordPart((
            entry("baselines", "Sec. IV, paper Figs. 4-8 (all simulation cases) with baselines", None,
                  {"stationary": stat, "wins": wins, "winner_table": table,
                   "ideal_segment_law_rho_t": {"rho_t": [s.param for s in self.family("piecewise")],
                                               "energy": self.ideal_piecewise.tolist(),
                                               "ratio_to_best_fixed": self.ideal_ratio().tolist()},
                   "steady_gain": self.steady, "band_peak": self.peaks}, "new", note),
            entry("hf_good_in_band", "Sec. IV, FDSC with K_f3 replaced by the best certified HF design",
                  None, {"energy_ratio_to_printed_fdsc": {k: list(v) for k, v in g.items()},
                         "theorem1_gammas": {n: self.gammas[n].tolist() for n in (FDSC_HF_BEST, "FDSC")},
                         "stationary": {s.label: {n: s.energy[n] for n in ("FDSC", FDSC_HF_BEST)}
                                        for s in self.family("stationary")}},
                  "new", note_best)))


def _scenarios_of(example, family, sweep, names):
    """The scenarios of one swept family: the paper's four from ``sweep``, the others run here."""
    ds = [family_signal(family, p)[0] for p in sweep.param]
    extra = [n for n in names if n not in _SWEPT]
    comp = example.compare(ds, sweep.horizon, names=extra)
    sym = "ρ_p" if family == "mixed" else "ρ_t"
    out, switches = [], {n: [] for n in SWITCHED}
    for i, p in enumerate(sweep.param):
        e = {n: float(sweep.energy[n][i]) if n in _SWEPT else float(comp.energy[n][i]) for n in names}
        out.append(Scenario(f"{sym} = {p:.3g}", family, float(p), e, float(sweep.input_energy[i])))
        for n in SWITCHED:
            switches[n].append(int(sweep.switches[n][i]) if n in _SWEPT else int(comp.switches[n][i]))
    return out, switches


@cached
def baselines() -> Baselines:
    """Every controller of :func:`aircraft_example` in every simulation case of the paper.

    Stationary LF (paper eq. (56)) and HF (paper eq. (57)) over 500 s, the ρ_p family of paper
    Fig. 7 and the ρ_t family of paper Fig. 8 on the grids of chapter 'nonstationary', at 1 ms,
    from rest.

    Returns
    -------
    Baselines
    """
    ex = aircraft_example()
    names = FIXED + SWITCHED
    stat = ex.compare([paper_disturbance("LF"), paper_disturbance("HF")], [STATIONARY_HORIZON] * 2,
                      names=names)
    scen = [Scenario(k, "stationary", float("nan"), {n: float(stat.energy[n][i]) for n in names},
                     float(stat.input_energy[i])) for i, k in enumerate(("LF", "HF"))]
    switches = {n: [int(v) for v in stat.switches[n]] for n in SWITCHED}
    sweeps = {"mixed": mixed_sweep(), "piecewise": piecewise_sweep()}
    for family, sweep in sweeps.items():
        sc, sw = _scenarios_of(ex, family, sweep, names)
        scen += sc
        for n in SWITCHED:
            switches[n] += sw[n]
    lf, hf = paper_disturbance("LF"), paper_disturbance("HF")
    steady, peaks = {}, {}
    for n in FIXED:
        cl = ex.closed_loop(n)
        steady[n] = {"LF": fdsc.steady_state_gain(cl, lf.frequencies, lf.amplitudes),
                     "HF": fdsc.steady_state_gain(cl, hf.frequencies, hf.amplitudes)}
        peaks[n] = {k: fdsc.band_peak(cl, ex.bands[k]).gamma for k in ("LF", "HF")}
    gammas = {n: np.asarray(ex.designs[n][0].gammas) for n in SWITCHED}
    sweep = sweeps["piecewise"]
    ideal = np.array([ex.segment_ideal(family_signal("piecewise", p)[0], h, ("PassC-LF", "PassC-HF"))
                      for p, h in zip(sweep.param, sweep.horizon, strict=True)])
    return Baselines(names, tuple(scen), steady, peaks, gammas,
                     {n: np.array(v) for n, v in switches.items()}, ideal)


@cached
def chosen_runs(example: str = "aircraft") -> dict:
    """The fixed controller chosen in advance (:mod:`fdsc.paper.shared.fixed_choice`) in every
    simulation case of the paper, by the library's simulator at the book's step (the method of
    the other controllers' runs), from rest.

    Parameters
    ----------
    example : {"aircraft"}
        The paper's cases are the aircraft's.

    Returns
    -------
    dict
        ``{"name": str, "stationary": [E_LF, E_HF], "mixed": [...], "piecewise": [...]}`` (∫zᵀz
        at the points of :func:`baselines`).
    """
    from fdsc.paper.shared.fixed_choice import fixed_in_advance

    name, c = fixed_in_advance(example)
    loop = aircraft().closed_loop(c)
    out = {"name": name, "stationary": [
        fdsc.simulate_stream(loop, paper_disturbance(k), STATIONARY_HORIZON, STATIONARY_DT).energy
        for k in ("LF", "HF")]}
    for family, sweep in (("mixed", mixed_sweep()), ("piecewise", piecewise_sweep())):
        out[family] = []
        for p, h in zip(sweep.param, sweep.horizon, strict=True):
            d, _h = family_signal(family, p)
            out[family].append(fdsc.simulate_stream(loop, d, float(h), STATIONARY_DT).energy)
    return out
