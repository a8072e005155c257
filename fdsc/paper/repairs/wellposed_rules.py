"""Chapter 'switching_law', continued: the three well-posed laws against their parameter.

Energies and switch counts of the laws with hysteresis (relative and absolute margin), a minimum
dwell time and a moving window over each law's parameter (:data:`LAW_GRIDS`), at dt and dt/2;
the paper's FDSC under a dwell time just above the certified one with d = 0; and each law set
against the comparator set.
"""

from dataclasses import dataclass

import numpy as np

from fdsc._validation import as_count, as_positive
from fdsc.paper.repairs.wellposed_regions import _case_disturbance, _cell, _pair, _param
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.data import STATIONARY_DT, aircraft, paper_fdsc, paper_gains, piecewise_disturbance
from fdsc.paper.shared.dwell_time import dwell_certificate
from fdsc.paper.shared.names import CONTROLLER_GAINS
from fdsc.paper.shared.prose import count, num, times
from fdsc.rules import SwitchRule
from fdsc.signals import Sinusoids
from fdsc.stream import Case, simulate_batch

__all__ = [
    "DwellLawCheck", "LAW_CASES", "LAW_GRIDS", "LAW_TITLES", "LawStudy", "against_comparators",
    "comparator_energies", "comparator_table", "dwell_law_check", "law_study",
]


#: Parameter grids of the well-posed laws: hysteresis with a relative margin h
#: (``s_j − s_a > h(|s_j| + |s_a|)``), hysteresis with an absolute margin h (s_j − s_a > h, in the
#: units of the printed Q's scores), minimum dwell time and moving window (seconds).
LAW_GRIDS = {"hysteresis": (0.1, 0.5, 0.9, 0.99),
             "hysteresis_abs": (1e3, 1e4, 1e5, 1e6, 1e8),
             "dwell": (0.002, 0.01, 0.1, 1.0, 10.0),
             "window": (0.01, 0.1, 1.0, 10.0)}


#: Reader-facing names of the laws of :data:`LAW_GRIDS` and of their parameters.
LAW_TITLES = {"hysteresis": ("hysteresis, relative margin", "relative margin h"),
              "hysteresis_abs": ("hysteresis, absolute margin", "absolute margin h"),
              "dwell": ("minimum dwell time", "dwell time τ_d (s)"),
              "window": ("moving window (FD-EEF)", "window T_w (s)")}


#: The paper's simulation cases of the law study: stationary LF and HF (500 s), mixed with
#: ρ_p = 0.1 (500 s), piecewise with T = 500 s, ρ_t = 0.2, ρ*_p = 0.1.
LAW_CASES = ("LF", "HF", "mixed", "piecewise")


_FIXED = ("PassC-EF", "PassC-LF", "PassC-HF")


def _law_case(case):
    if case == "piecewise":
        d = piecewise_disturbance(500.0, 0.2, 0.1)
        return d, float(d.breaks[-1])
    return _case_disturbance(case), 500.0


def _rule(law, p):
    if law == "hysteresis_abs":
        return SwitchRule.hysteresis(p, relative=False)
    return {"hysteresis": SwitchRule.hysteresis, "dwell": SwitchRule.dwell_time,
            "window": SwitchRule.moving_window}[law](p)


@dataclass(frozen=True)
class LawStudy:
    """Energies and switch counts of the well-posed laws against their parameter.

    Parameters
    ----------
    dt : float
        The step; every run is repeated at dt/2.
    energy : dict
        ``{(law, param, case): ∫zᵀz at dt}``; law "printed" (param 0) and the fixed gains
        ("PassC-…", param 0) included.
    energy_half : dict
        The same at dt/2.
    switches, switches_half : dict
        Switch counts at dt and dt/2 (switched runs only).
    """

    dt: float
    energy: dict
    energy_half: dict
    switches: dict
    switches_half: dict

    def well_posed(self, law: str, p: float, *, tol: float = 0.5) -> bool:
        """Whether the switch count grows by at most ``tol`` (relative, or 2 switches) from dt
        to dt/2 in every case.

        Parameters
        ----------
        law : str
            A key of :data:`LAW_GRIDS` or "printed".
        p : float
            The law's parameter (0 for "printed").
        tol : float, optional
            Allowed relative growth.

        Returns
        -------
        bool
        """
        return all(self.switches_half[(law, p, c)] <= max((1 + tol) * self.switches[(law, p, c)],
                                                           self.switches[(law, p, c)] + 2)
                   for c in LAW_CASES)

    def relative_energy(self, law: str, p: float) -> np.ndarray:
        """Energy over the printed law's, per case of :data:`LAW_CASES`.

        Parameters
        ----------
        law : str
            A key of :data:`LAW_GRIDS`.
        p : float
            The law's parameter.

        Returns
        -------
        (4,) ndarray
        """
        return np.array([self.energy[(law, p, c)] / self.energy[("printed", 0.0, c)] for c in LAW_CASES])

    def best_fixed(self, case: str) -> tuple[str, float]:
        """The fixed gain with the lowest energy in a case, and its energy.

        Parameters
        ----------
        case : str
            One of :data:`LAW_CASES`.

        Returns
        -------
        name : str
        energy : float
        """
        name = min(_FIXED, key=lambda f: self.energy[(f, 0.0, case)])
        return name, self.energy[(name, 0.0, case)]

    def default(self, law: str) -> float | None:
        """The chosen parameter: among the well-posed ones, the smallest geometric mean of
        :meth:`relative_energy`; None if no parameter of the grid is well-posed.

        Parameters
        ----------
        law : str
            A key of :data:`LAW_GRIDS`.

        Returns
        -------
        float or None
        """
        ok = [p for p in LAW_GRIDS[law] if self.well_posed(law, p)]
        if not ok:
            return None
        return min(ok, key=lambda p: float(np.mean(np.log(self.relative_energy(law, p)))))

    def table(self, law: str) -> list:
        """One row per parameter, every cell text (:mod:`fdsc.paper.shared.prose`), for
        :func:`fdsc.paper.shared.report.html_table` (a table may show a subset of the columns).

        Parameters
        ----------
        law : str
            A key of :data:`LAW_GRIDS`.

        Returns
        -------
        list of dict
            Keys ``law`` (its :data:`LAW_TITLES` name), ``parameter``, per case ``c`` of
            :data:`LAW_CASES` the energy ``c`` (∫zᵀz at dt), the energy relative to the printed
            law's ``c ÷ printed`` and the switch counts at dt and dt/2 ``c switches``, and
            ``well-posed`` (yes/no).
        """
        rows = []
        for p in LAW_GRIDS[law]:
            row = {"law": LAW_TITLES[law][0], "parameter": _param(p)}
            for c, rel in zip(LAW_CASES, self.relative_energy(law, p), strict=True):
                row[c] = num(self.energy[(law, p, c)])
                row[f"{c} ÷ printed"] = num(float(rel))
                row[f"{c} switches"] = _pair(self.switches[(law, p, c)],
                                             self.switches_half[(law, p, c)])
            row["well-posed"] = _cell(self.well_posed(law, p))
            rows.append(row)
        return rows

    def reference_table(self) -> list:
        """The printed law and the fixed gains in the same cases, every cell text: one row of
        energies (∫zᵀz at dt) per controller, then the printed law's switch counts at dt and dt/2.

        Returns
        -------
        list of dict
            Keys ``controller`` and the cases of :data:`LAW_CASES`.
        """
        rows = [{"controller": "FDSC, printed law" if name == "printed" else name,
                 **{c: num(self.energy[(name, 0.0, c)]) for c in LAW_CASES}}
                for name in ("printed", *_FIXED)]
        rows.append({"controller": "FDSC, printed law: switches at dt → dt/2",
                     **{c: _pair(self.switches[("printed", 0.0, c)],
                                 self.switches_half[("printed", 0.0, c)]) for c in LAW_CASES}})
        return rows

    def prose(self, extra: dict) -> dict:
        """The numbers the chapter quotes, as text (:mod:`fdsc.paper.shared.prose`).

        Parameters
        ----------
        extra : dict
            :func:`comparator_energies` at the study's step (the comparator set's members the
            study does not run).

        Returns
        -------
        dict of str
            Per case ``c``: the printed law's energy ``ref_c`` and switch counts
            ``refsw_c``/``refsw2_c`` (dt, dt/2); the best of the paper's three fixed gains
            ``bestfixed_c`` and its energy ``bestfixed_e_c``; the chosen dwell-time law's energy
            relative to the printed law ``dw_rel_c``, to the best of the three fixed gains
            ``dw_vs_fixed_c``, its switch counts ``dw_sw_c``/``dw_sw2_c``; against the
            comparator set (:func:`against_comparators`) the best member ``cmp_best_c``, the
            factor ``cmp_ratio_c`` and all four as ``cmp_summary``. Per law ``l`` of
            :data:`LAW_GRIDS`: ``default_l`` (the chosen parameter or "none"), ``nwell_l``,
            ``ngrid_l``. The relative hysteresis at its largest margin (``hy_top``,
            ``hy_sw_LF``, ``hy_sw2_LF``), the absolute one (``hya_grid``, ``hya_nwell``,
            ``hya_only``: where it is well-posed; ``hya_big`` and ``hya_big_sw``: the largest
            margin that is not, mixed case; ``hya_mid_sw``: the smallest margin, LF), the
            window values that are well-posed ``win_ok`` and the 1 s window (``win1_*``), and
            the step ``law_dt_ms``.
        """
        out = {"law_dt_ms": _param(self.dt * 1e3)}
        tau = self.default("dwell")
        for c in LAW_CASES:
            ref = self.energy[("printed", 0.0, c)]
            name, e = self.best_fixed(c)
            out |= {f"ref_{c}": num(ref), f"refsw_{c}": count(self.switches[("printed", 0.0, c)]),
                    f"refsw2_{c}": count(self.switches_half[("printed", 0.0, c)]),
                    f"bestfixed_{c}": name, f"bestfixed_e_{c}": num(e)}
            if tau is not None:
                out |= {f"dw_rel_{c}": num(self.energy[("dwell", tau, c)] / ref),
                        f"dw_vs_fixed_{c}": num(self.energy[("dwell", tau, c)] / e),
                        f"dw_sw_{c}": count(self.switches[("dwell", tau, c)]),
                        f"dw_sw2_{c}": count(self.switches_half[("dwell", tau, c)])}
        cmp_rows = against_comparators(self, extra)
        for r in cmp_rows:
            out[f"cmp_best_{r['case']}"] = r["best fixed"]
            out[f"cmp_ratio_{r['case']}"] = times(r["ratio"])
        out["cmp_summary"] = ", ".join(f"{r['case']} {times(r['ratio'])}" for r in cmp_rows)
        for law, grid in LAW_GRIDS.items():
            d = self.default(law)
            out |= {f"default_{law}": "none" if d is None else _param(d),
                    f"nwell_{law}": count(sum(self.well_posed(law, q) for q in grid)),
                    f"ngrid_{law}": count(len(grid))}
        h_top = LAW_GRIDS["hysteresis"][-1]
        out |= {"hy_top": _param(h_top), "hy_sw_LF": count(self.switches[("hysteresis", h_top, "LF")]),
                "hy_sw2_LF": count(self.switches_half[("hysteresis", h_top, "LF")])}
        grid = LAW_GRIDS["hysteresis_abs"]
        ok = [q for q in grid if self.well_posed("hysteresis_abs", q)]
        quiet = all(self.switches[("hysteresis_abs", q, c)] == 0 for q in ok for c in LAW_CASES)
        out["hya_only"] = ("at none of the margins" if not ok else
                           f"h ≥ {_param(min(ok))}" + (", where the law never leaves its initial mode"
                                                    if quiet else ""))
        out["hya_grid"] = "; ".join(_param(q) for q in grid)
        out["hya_nwell"] = count(len(ok))
        bad = [q for q in grid if q not in ok]
        if bad:
            h_big = max(bad)
            out["hya_big"] = _param(h_big)
            out["hya_big_sw"] = _pair(self.switches[("hysteresis_abs", h_big, "mixed")],
                                      self.switches_half[("hysteresis_abs", h_big, "mixed")])
        out["hya_mid_sw"] = _pair(self.switches[("hysteresis_abs", grid[0], "LF")],
                                  self.switches_half[("hysteresis_abs", grid[0], "LF")])
        w_ok = [q for q in LAW_GRIDS["window"] if self.well_posed("window", q)]
        w_words = [_param(q) for q in w_ok]
        out["win_ok"] = (" and ".join([", ".join(w_words[:-1]), w_words[-1]] if len(w_words) > 1 else w_words)
                         if w_ok else "none")
        w1 = 1.0
        out |= {"win1": _param(w1),
                "win1_rel_LF": num(self.energy[("window", w1, "LF")] / self.energy[("printed", 0.0, "LF")]),
                "win1_rel_mixed": num(self.energy[("window", w1, "mixed")]
                                      / self.energy[("printed", 0.0, "mixed")]),
                "win1_sw_LF": count(self.switches[("window", w1, "LF")]),
                "win1_sw2_LF": count(self.switches_half[("window", w1, "LF")])}
        return out


@cached
def law_study(*, dt: float = STATIONARY_DT) -> LawStudy:
    """Every law of :data:`LAW_GRIDS` (paper's Q's, measured ẋ) on :data:`LAW_CASES` at dt and dt/2.

    Parameters
    ----------
    dt : float, optional
        Step in s.

    Returns
    -------
    LawStudy
    """
    dt = as_positive("dt", dt)
    ctrl = paper_fdsc("paper")
    plant, gains = aircraft(), paper_gains()
    cases, keys = [], []
    for h in (dt, dt / 2):
        for c in LAW_CASES:
            d, horizon = _law_case(c)
            cases.append(ctrl.case(d, horizon, h))
            keys.append(("printed", 0.0, c, h))
            for law, grid in LAW_GRIDS.items():
                for p in grid:
                    cases.append(ctrl.case(d, horizon, h, rule=_rule(law, p)))
                    keys.append((law, p, c, h))
            for name in _FIXED:
                cases.append(Case(plant.closed_loop(gains[CONTROLLER_GAINS[name]]), d, horizon, h))
                keys.append((name, 0.0, c, h))
    runs = simulate_batch(cases)
    out = ({}, {}, {}, {})
    for (law, p, c, h), e, s in zip(keys, runs.energy, runs.switches, strict=True):
        half = h != dt
        out[1 if half else 0][(law, p, c)] = float(e)
        if law not in _FIXED:
            out[3 if half else 2][(law, p, c)] = int(s)
    return LawStudy(float(dt), *out)


@dataclass(frozen=True)
class DwellLawCheck:
    """The dwell-time law of the simulator at the certified τ* (d = 0, seeded initial states).

    Parameters
    ----------
    tau : float
        The dwell time used (1.01 τ*), s.
    horizon : float
        Length of each run in s.
    final_ratio : (k,) ndarray
        ‖x(T)‖/‖x(0)‖ per run.
    switches : (k,) int ndarray
        Switches per run.
    """

    tau: float
    horizon: float
    final_ratio: np.ndarray
    switches: np.ndarray

    def prose(self) -> dict:
        """The numbers the chapter quotes, as text (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        dict of str
            ``tau`` (s), ``n`` (runs), ``h`` (horizon, s), ``ratio`` (largest
            ‖x(T)‖/‖x(0)‖), ``sw`` (most switches of a run) and ``swbound`` (horizon/τ_d).
        """
        return {"tau": num(self.tau), "n": count(self.final_ratio.size), "h": _param(self.horizon),
                "ratio": num(float(self.final_ratio.max())), "sw": count(int(self.switches.max())),
                "swbound": count(int(self.horizon // self.tau))}


@cached
def dwell_law_check(*, n_initial: int = 10, horizon: float = 120.0, dt: float = 1e-2,
                    seed: int = 1) -> DwellLawCheck:
    """Run the paper's FDSC under ``SwitchRule.dwell_time(1.01 τ*)`` with d = 0.

    Parameters
    ----------
    n_initial : int, optional
        Number of standard-normal initial states.
    horizon, dt : float, optional
        Length and step of each run in s (the step is exact for d = 0).
    seed : int, optional
        Seed of the initial states.

    Returns
    -------
    DwellLawCheck
    """
    tau = 1.01 * dwell_certificate().bound.tau
    ctrl = paper_fdsc("paper")
    rng = np.random.default_rng(seed)
    x0s = rng.standard_normal((as_count("n_initial", n_initial), 2))
    zero = Sinusoids([0.0], [1.0])
    runs = simulate_batch([ctrl.case(zero, horizon, dt, x0=x0, rule=SwitchRule.dwell_time(tau))
                           for x0 in x0s])
    ratios = np.array([np.linalg.norm(runs[c].x_final) / np.linalg.norm(x0)
                       for c, x0 in enumerate(x0s)])
    return DwellLawCheck(float(tau), float(horizon), ratios, np.asarray(runs.switches))


@cached
def comparator_energies(*, dt: float = STATIONARY_DT) -> dict:
    """Energies of the comparator set's members that :func:`law_study` does not run (the open
    loop and the best HF design) on :data:`LAW_CASES` at ``dt``.

    Parameters
    ----------
    dt : float, optional
        Step in s (the law study's).

    Returns
    -------
    dict
        ``{(name, case): ∫zᵀz}``.
    """
    from fdsc.paper.reproduced.passive_controllers import hf_best
    from fdsc.paper.shared.comparators import HF_BEST
    from fdsc.paper.shared.examples import OPEN_LOOP

    dt = as_positive("dt", dt)
    plant = aircraft()
    best = hf_best()
    gains = {OPEN_LOOP: np.zeros_like(best.K), HF_BEST: best.K}
    cases, keys = [], []
    for c in LAW_CASES:
        d, horizon = _law_case(c)
        for name, K in gains.items():
            cases.append(Case(plant.closed_loop(K), d, horizon, dt))
            keys.append((name, c))
    runs = simulate_batch(cases)
    return {k: float(e) for k, e in zip(keys, runs.energy, strict=True)}


def against_comparators(study: LawStudy, extra: dict, law: str = "dwell",
                        p: float | None = None) -> list:
    """A law against the best comparator of each case (the comparator set of
    :mod:`fdsc.paper.shared.comparators`).

    Parameters
    ----------
    study : LawStudy
    extra : dict
        :func:`comparator_energies` (the members the study does not run).
    law : str, optional
        A key of :data:`LAW_GRIDS`.
    p : float, optional
        The law's parameter (default: :meth:`LawStudy.default`).

    Returns
    -------
    list of dict
        Per case: ``case``, ``best fixed`` (name), ``best fixed energy``, ``law energy``,
        ``ratio`` (law over best fixed), and the energy of every member of the set.
    """
    from fdsc.paper.shared.comparators import best_fixed, comparators

    p = study.default(law) if p is None else p
    rows = []
    for c in LAW_CASES:
        energy = {n: extra[(n, c)] if (n, c) in extra else study.energy[(n, 0.0, c)]
                  for n in comparators("aircraft")}
        name, e = best_fixed(energy, "aircraft")
        law_e = study.energy[(law, p, c)]
        rows.append({"case": c, "best fixed": str(name), "best fixed energy": float(e),
                     "law energy": law_e, "ratio": law_e / float(e),
                     **{f"energy {n}": v for n, v in energy.items()}})
    return rows


def comparator_table(rows: list) -> list:
    """:func:`against_comparators` as text (:mod:`fdsc.paper.shared.prose`), for
    :func:`fdsc.paper.shared.report.html_table` (a table may show a subset of the columns).

    Parameters
    ----------
    rows : list of dict
        :func:`against_comparators`.

    Returns
    -------
    list of dict
        Keys ``case``, ``best fixed``, ``best fixed energy``, ``law energy``, ``ratio`` (a
        factor) and every member's name (its energy).
    """
    return [{"case": r["case"], "best fixed": r["best fixed"],
             "best fixed energy": num(r["best fixed energy"]), "law energy": num(r["law energy"]),
             "ratio": times(r["ratio"]),
             **{k.removeprefix("energy "): num(v) for k, v in r.items() if k.startswith("energy ")}}
            for r in rows]
