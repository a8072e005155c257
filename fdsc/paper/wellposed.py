"""Chapter 'wellposed_laws': what the printed law does in continuous time, and three well-posed laws.

1. **The conflict region.** With the measured ẋ = A_a x + B d (a the active mode), mode a
   *holds itself* at (x, d) if its own score wins there: ``argmax_j s_j^(a)(x, d) = a``. For two
   modes every point of the state space is of one of four kinds: only mode 1 holds itself (the
   law settles in 1), only mode 2 does, both do (the mode active on arrival stays: the law has
   memory), or neither does. In the last set the sampled law switches at every sample (1, 2, 1,
   …), so as dt → 0 the loop follows the *implicit* dynamics ``ẋ = ½(A_1 + A_2) x + B d`` with the
   input ``u = ½(K_1 + K_2) x`` on average, and every sample spent there is a switch. (The
   Filippov inclusion ``ẋ ∈ co{A_1 x + B d, A_2 x + B d}`` admits any mix there; sampling picks
   ½.) For d = 0 the scores are quadratic forms in x, so the four sets are cones; a disturbance
   moves them.
2. **Convergence.** Runs at dt, dt/2, …, dt/16: energy, time shares, switch count × dt (→ the
   time spent in the chattering set), the share of mode 1 inside that set (→ ½) and the
   actuator rate |Δu|/dt at the switches (which grows like 1/dt).
3. **Well-posed laws** (:class:`fdsc.SwitchRule`): hysteresis (relative margin), minimum dwell
   time and a moving-window FD-EEF law (paper Remark 6), each against its parameter on the
   paper's stationary, mixed and piecewise cases, at dt and dt/2.
"""

from dataclasses import dataclass
from numbers import Integral, Real

import numpy as np

from .._validation import as_count, as_positive
from ..rules import SwitchRule
from ..signals import Sinusoids
from ..simulate import time_grid
from ..stream import Case, simulate_batch
from .cache import cached
from .data import (
    STATIONARY_DT,
    aircraft,
    mixed_disturbance,
    our_q,
    paper_disturbance,
    paper_fdsc,
    paper_gains,
    paper_modes,
    piecewise_disturbance,
)
from .dwell_time import dwell_certificate
from .names import CONTROLLER_GAINS
from .prose import count, num, pct, times
from .results import RecordPart, entry

__all__ = [
    "REGION_KINDS",
    "holds_itself",
    "region_codes",
    "LawRegions",
    "law_regions",
    "ConvergenceRow",
    "ConvergenceStudy",
    "convergence_study",
    "LAW_GRIDS",
    "LAW_CASES",
    "LawStudy",
    "law_study",
    "DwellLawCheck",
    "dwell_law_check",
    "comparator_energies",
    "against_comparators",
    "comparator_table",
    "LAW_TITLES",
    "record_part",
]

#: The four kinds of points (codes 0-3) for two modes.
REGION_KINDS = ("only mode 1 holds itself", "only mode 2 holds itself",
                "both hold themselves (memory)", "neither: chatters")

#: The d value (besides 0) at which the regions are drawn: one tone's amplitude.
D_REF = 1.0


def _cell(value):
    """A table cell as the book prints it (:mod:`fdsc.paper.prose`): yes/no, counts, numbers."""
    if isinstance(value, bool | np.bool_):
        return "yes" if value else "no"
    if isinstance(value, Integral):
        return count(value)
    if isinstance(value, Real):
        return num(float(value))
    return str(value)


def _share(value, digits=1):
    """A share as a percentage, a dash where there is none (NaN)."""
    return "—" if np.isnan(value) else pct(float(value), digits)


def _param(p):
    """A parameter of a grid with the digits that print it exactly (``0.002``, ``1 × 10⁸``)."""
    p = float(p)
    digits = next((d for d in range(1, 7) if float(f"{p:.{d - 1}e}") == p), 7)
    return num(p, digits)


def _pair(a, b):
    """Switch counts at dt and dt/2."""
    return f"{count(a)} → {count(b)}"


def _law_weights(Q):
    pm = paper_modes()
    return [np.kron(b.psi.real, np.asarray(q, dtype=float)) for b, q in zip(pm["bands"], Q, strict=True)]


def holds_itself(modes, weights, x, d):
    """Whether each mode, when active, prefers itself under the law with the measured ẋ.

    Parameters
    ----------
    modes : list of LTISystem
        The closed loops (I modes, n states).
    weights : list of (2n, 2n) ndarray
        The law's forms ``Re Ψ_i ⊗ Q_i`` on ``[ẋ; x]``.
    x : (k, n) ndarray
        States.
    d : float or (k,) ndarray
        Disturbance values.

    Returns
    -------
    (I, k) bool ndarray
        ``[a, k]``: mode a's own scores (ẋ = A_a x + B d) are largest for a at point k.
    """
    x = np.atleast_2d(x)
    d = np.broadcast_to(np.asarray(d, dtype=float), (x.shape[0],))
    out = np.empty((len(modes), x.shape[0]), dtype=bool)
    for a, m in enumerate(modes):
        v = np.hstack([x @ m.A.T + np.outer(d, m.B[:, 0]), x])
        s = np.array([np.einsum("kr,rc,kc->k", v, W, v) for W in weights])
        out[a] = s.argmax(axis=0) == a
    return out


def region_codes(holds):
    """Codes of :data:`REGION_KINDS` from :func:`holds_itself` (two modes).

    Parameters
    ----------
    holds : (2, k) bool ndarray

    Returns
    -------
    (k,) int ndarray
    """
    h0, h1 = holds
    return np.where(h0 & h1, 2, np.where(h0, 0, np.where(h1, 1, 3)))


@dataclass(frozen=True)
class LawRegions:
    """The four kinds of points in the (x₁, x₂) plane for the paper's and our Q's, d = 0 and
    d = :data:`D_REF`, with a trajectory on top.

    Parameters
    ----------
    x1, x2 : (g,) ndarray
        Grid axes.
    codes : dict
        ``{(q_label, d): (g, g) int ndarray}`` of :data:`REGION_KINDS` codes (rows x₂, columns x₁).
    angular_share : dict
        ``{q_label: (4,) ndarray}``: share of the directions of the plane of each kind at d = 0
        (the sets are cones there).
    traj_x : (k, 2) ndarray
        States of a run of the paper's FDSC under the LF disturbance (every sample).
    traj_sigma : (k,) ndarray
        Its active modes.
    traj_codes : (k,) ndarray
        The kind of each of its samples (with the sample's own d).
    dt : float, optional
        Step of the run in s.
    """

    x1: np.ndarray
    x2: np.ndarray
    codes: dict
    angular_share: dict
    traj_x: np.ndarray
    traj_sigma: np.ndarray
    traj_codes: np.ndarray
    dt: float = STATIONARY_DT

    def prose(self) -> dict:
        """The numbers the chapter quotes, as text (:mod:`fdsc.paper.prose`).

        Returns
        -------
        dict of str
            ``ang_p_*`` and ``ang_o_*`` (share of the directions of each kind at d = 0 with the
            printed and with our Q's: ``only1``, ``only2``, ``both``, ``neither``), ``traj_*``
            (share of the run's samples of each kind, and its length ``traj_horizon`` in s),
            ``d_ref``, and the poles that explain the regions: ``eig_fast`` (the fastest of the
            K_f1 loop) and ``eig_slow`` (the slowest of the K_f3 loop), in 1/s.
        """
        modes = paper_modes()["modes"]
        kinds = ("only1", "only2", "both", "neither")
        traj = np.bincount(self.traj_codes, minlength=4) / self.traj_codes.size
        out = {f"ang_{q[0]}_{k}": pct(float(v), 1)
               for q, shares in (("p", self.angular_share["paper Q"]),
                                 ("o", self.angular_share["our Q"]))
               for k, v in zip(kinds, shares, strict=True)}
        out |= {f"traj_{k}": pct(float(v), 1) for k, v in zip(kinds, traj, strict=True)}
        out["traj_horizon"] = _param(round((self.traj_x.shape[0] - 1) * self.dt, 9))
        out["d_ref"] = _param(D_REF)
        out["eig_fast"] = num(float(np.linalg.eigvals(modes[0].A).real.min()))
        out["eig_slow"] = num(float(np.linalg.eigvals(modes[1].A).real.max()))
        return out


@cached
def law_regions(*, grid: int = 301, horizon: float = 60.0, dt: float = STATIONARY_DT) -> LawRegions:
    """The regions of the printed law (measured ẋ) and a trajectory of the paper's FDSC.

    Parameters
    ----------
    grid : int, optional
        Points per axis.
    horizon, dt : float, optional
        The run under the LF disturbance (paper eq. (56)) drawn on top.

    Returns
    -------
    LawRegions
    """
    grid = as_count("grid", grid, 11)
    pm = paper_modes()
    Qs = {"paper Q": pm["Q"], "our Q": our_q().Q}
    run = paper_fdsc("paper").simulate(paper_disturbance("LF"), time_grid(horizon, dt))
    span = 1.15 * np.abs(run.x).max(axis=0)
    x1 = np.linspace(-span[0], span[0], grid)
    x2 = np.linspace(-span[1], span[1], grid)
    X = np.stack(np.meshgrid(x1, x2), axis=-1).reshape(-1, 2)
    theta = np.linspace(0.0, np.pi, 3600, endpoint=False)
    dirs = np.stack([np.cos(theta), np.sin(theta)], axis=1)
    codes, shares = {}, {}
    for label, Q in Qs.items():
        W = _law_weights(Q)
        for d in (0.0, D_REF):
            codes[(label, d)] = region_codes(holds_itself(pm["modes"], W, X, d)).reshape(grid, grid)
        c = region_codes(holds_itself(pm["modes"], W, dirs, 0.0))
        shares[label] = np.bincount(c, minlength=4) / c.size
    traj_codes = region_codes(holds_itself(pm["modes"], _law_weights(pm["Q"]), run.x, run.d))
    return LawRegions(x1, x2, codes, shares, run.x, run.sigma, traj_codes, float(dt))


@dataclass(frozen=True)
class ConvergenceRow:
    """One run of the convergence study.

    Parameters
    ----------
    case : str
        The disturbance ("LF", "HF", "mixed").
    dt : float
        Step in s.
    energy : float
        ∫ zᵀz over the horizon.
    share_hf : float
        Time share of mode 2 (PassC-HF).
    switches : int
        Number of switches.
    chatter_time : float
        Time (s) spent at samples of the chattering set (neither mode holds itself).
    share_lf_in_chatter : float
        Share of those samples spent in mode 1 (→ ½ as dt → 0); nan if there are none.
    du_max, du_median : float
        Largest and median ‖Δu‖ = ‖(K_2 − K_1) x‖ at the switches.
    """

    case: str
    dt: float
    energy: float
    share_hf: float
    switches: int
    chatter_time: float
    share_lf_in_chatter: float
    du_max: float
    du_median: float

    @property
    def switch_time(self) -> float:
        """Switch count × dt (s)."""
        return self.switches * self.dt

    @property
    def rate_max(self) -> float:
        """The actuator rate the largest switch asks for, ‖Δu‖/dt."""
        return self.du_max / self.dt


@dataclass(frozen=True)
class ConvergenceStudy:
    """Runs of the paper's FDSC (printed law) at dt, dt/2, …: see :func:`convergence_study`.

    Parameters
    ----------
    horizon : float
        Length of every run in s.
    rows : tuple of ConvergenceRow
        One per (case, dt), dt decreasing within a case.
    """

    horizon: float
    rows: tuple

    def cases(self) -> list:
        """The disturbance cases, in order.

        Returns
        -------
        list of str
        """
        return list(dict.fromkeys(r.case for r in self.rows))

    def of(self, case: str) -> list:
        """The rows of one case (dt decreasing).

        Parameters
        ----------
        case : str
            One of :data:`CONVERGENCE_CASES`.

        Returns
        -------
        list of ConvergenceRow
        """
        return [r for r in self.rows if r.case == case]

    def energy_spread(self, case: str) -> float:
        """(max − min) / median of the energy over the steps of one case.

        Parameters
        ----------
        case : str
            One of :data:`CONVERGENCE_CASES`.

        Returns
        -------
        float
        """
        e = np.array([r.energy for r in self.of(case)])
        return float((e.max() - e.min()) / np.median(e))

    def table(self) -> list:
        """One row per run, every cell text (:mod:`fdsc.paper.prose`), for
        :func:`fdsc.paper.report.html_table` (a table may show a subset of the columns).

        Returns
        -------
        list of dict
            Keys ``case``, ``dt (ms)``, ``∫zᵀz``, ``HF mode``, ``switches``,
            ``switches × dt (s)``, ``in chattering region (s)``, ``mode 1 there``,
            ``largest ‖Δu‖/dt``.
        """
        return [{"case": r.case, "dt (ms)": _param(r.dt * 1e3), "∫zᵀz": num(r.energy),
                 "HF mode": _share(r.share_hf), "switches": count(r.switches),
                 "switches × dt (s)": num(r.switch_time),
                 "in chattering region (s)": num(r.chatter_time),
                 "mode 1 there": _share(r.share_lf_in_chatter), "largest ‖Δu‖/dt": num(r.rate_max)}
                for r in self.rows]

    def prose(self) -> dict:
        """The numbers the chapter quotes, as text (:mod:`fdsc.paper.prose`).

        Returns
        -------
        dict of str
            ``horizon`` (s), ``levels``, ``dt0_ms`` and ``dtN_us`` (the coarsest step in ms and
            the finest in µs) and per case ``c``: switch counts ``sw0_c``/``swN_c`` at the
            coarsest and the finest step, switch count × dt ``swdt0_c``/``swdtN_c`` (s), time in
            the chattering region ``ch0_c``/``chN_c`` (s), mode 1's share there
            ``m1_0_c``/``m1_N_c``, the energy's spread over the steps ``spread_c``, the
            actuator rate ``rate0_c``/``rateN_c`` and the largest input jump ``du_c``.
        """
        first = self.of(self.cases()[0])
        out = {"horizon": _param(self.horizon), "levels": count(len(first)),
               "dt0_ms": _param(first[0].dt * 1e3), "dtN_us": _param(first[-1].dt * 1e6)}
        for c in self.cases():
            r0, rN = self.of(c)[0], self.of(c)[-1]
            out |= {f"sw0_{c}": count(r0.switches), f"swN_{c}": count(rN.switches),
                    f"swdt0_{c}": num(r0.switch_time), f"swdtN_{c}": num(rN.switch_time),
                    f"ch0_{c}": num(r0.chatter_time), f"chN_{c}": num(rN.chatter_time),
                    f"m1_0_{c}": num(r0.share_lf_in_chatter),
                    f"m1_N_{c}": num(rN.share_lf_in_chatter),
                    f"spread_{c}": pct(self.energy_spread(c), 1),
                    f"rate0_{c}": num(r0.rate_max), f"rateN_{c}": num(rN.rate_max),
                    f"du_{c}": num(r0.du_max)}
        return out


#: Disturbances of the convergence study.
CONVERGENCE_CASES = ("LF", "HF", "mixed")


def _case_disturbance(case):
    if case == "mixed":
        return mixed_disturbance(0.1)
    return paper_disturbance(case)


@cached
def convergence_study(*, horizon: float = 50.0, dt: float = STATIONARY_DT,
                      levels: int = 5) -> ConvergenceStudy:
    """The printed law (paper's Q's, measured ẋ) at dt, dt/2, …, dt/2^(levels−1).

    Parameters
    ----------
    horizon : float, optional
        Length of each run in s.
    dt : float, optional
        The coarsest step in s.
    levels : int, optional
        Number of steps (≥ 3).

    Returns
    -------
    ConvergenceStudy
    """
    horizon, dt = as_positive("horizon", horizon), as_positive("dt", dt)
    levels = as_count("levels", levels, 3)
    ctrl = paper_fdsc("paper")
    pm = paper_modes()
    W = _law_weights(pm["Q"])
    dK = np.asarray(ctrl.gains[1]) - np.asarray(ctrl.gains[0])
    rows = []
    for case in CONVERGENCE_CASES:
        d = _case_disturbance(case)
        for level in range(levels):
            h = dt / 2**level
            run = ctrl.simulate(d, time_grid(horizon, h))
            codes = region_codes(holds_itself(pm["modes"], W, run.x, run.d))
            chatter = codes[:-1] == 3
            sw = np.flatnonzero(np.diff(run.sigma)) + 1
            du = np.linalg.norm(run.x[sw] @ dK.T, axis=1) if sw.size else np.zeros(1)
            rows.append(ConvergenceRow(
                case, h, run.energy(), float(run.time_share()[1]), int(sw.size),
                float(chatter.sum() * h),
                float(np.mean(run.sigma[:-1][chatter] == 0)) if chatter.any() else float("nan"),
                float(du.max()), float(np.median(du))))
    return ConvergenceStudy(float(horizon), tuple(rows))


#: Parameter grids of the well-posed laws: hysteresis with a relative margin h
#: (s_j − s_a > h(|s_j| + |s_a|)), hysteresis with an absolute margin h (s_j − s_a > h, in the
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
        """One row per parameter, every cell text (:mod:`fdsc.paper.prose`), for
        :func:`fdsc.paper.report.html_table` (a table may show a subset of the columns).

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
        """The numbers the chapter quotes, as text (:mod:`fdsc.paper.prose`).

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
        out["win_ok"] = ", ".join(_param(q) for q in w_ok) if w_ok else "none"
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
        """The numbers the chapter quotes, as text (:mod:`fdsc.paper.prose`).

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
    from .comparators import HF_BEST
    from .examples import OPEN_LOOP
    from .passive_controllers import hf_best

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
    """A law against the best fixed controller of each case (the comparator set of
    :mod:`fdsc.paper.comparators`).

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
    from .comparators import best_fixed, comparators

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
    """:func:`against_comparators` as text (:mod:`fdsc.paper.prose`), for
    :func:`fdsc.paper.report.html_table` (a table may show a subset of the columns).

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


def _sliding_entry(regions, conv):
    spread = {c: conv.energy_spread(c) for c in conv.cases()}
    rec = {"angular_share_d0": {q: dict(zip(REGION_KINDS, map(float, s), strict=True))
                                for q, s in regions.angular_share.items()},
           "trajectory_share_by_kind": dict(zip(REGION_KINDS, map(float, np.bincount(
               regions.traj_codes, minlength=4) / regions.traj_codes.size), strict=True)),
           "convergence": [{"case": r.case, "dt": r.dt, "energy": r.energy, "share_hf": r.share_hf,
                            "switches": r.switches, "switches_x_dt": r.switch_time,
                            "chatter_time": r.chatter_time,
                            "share_mode1_in_chatter": r.share_lf_in_chatter,
                            "du_max": r.du_max, "du_median": r.du_median, "rate_max": r.rate_max}
                           for r in conv.rows],
           "energy_spread": spread}
    return entry("sliding", "paper Remark 7 (sliding motion assumed absent; nothing printed)", None,
                 rec, "new",
                 "The printed law with the measured ẋ: inside the set where neither mode holds "
                 "itself (the chattering region) the sampled law switches at every sample (mode 1's "
                 "share there tends to ½), and on the border of that set it slides (mode 1 at every "
                 "other sample); time shares and switch count × dt converge as dt → 0 while the "
                 "energy scatters by a few per cent without a trend; the actuator rate ‖Δu‖/dt "
                 "grows like 1/dt.", horizon=conv.horizon)


def _law_record(study, law):
    return {"parameters": list(LAW_GRIDS[law]),
            "energy": {c: [study.energy[(law, p, c)] for p in LAW_GRIDS[law]] for c in LAW_CASES},
            "energy_half_dt": {c: [study.energy_half[(law, p, c)] for p in LAW_GRIDS[law]]
                               for c in LAW_CASES},
            "switches": {c: [study.switches[(law, p, c)] for p in LAW_GRIDS[law]] for c in LAW_CASES},
            "switches_half_dt": {c: [study.switches_half[(law, p, c)] for p in LAW_GRIDS[law]]
                                 for c in LAW_CASES},
            "well_posed": [study.well_posed(law, p) for p in LAW_GRIDS[law]],
            "default": study.default(law)}


def _reference_record(study):
    return {name: {c: study.energy[(name, 0.0, c)] for c in LAW_CASES} for name in ("printed", *_FIXED)} | {
        "printed_switches": {c: study.switches[("printed", 0.0, c)] for c in LAW_CASES},
        "printed_switches_half_dt": {c: study.switches_half[("printed", 0.0, c)] for c in LAW_CASES}}


def record_part() -> RecordPart:
    """Record entries ``sliding``, ``hysteresis_dwell`` (with the certified dwell time of
    :func:`fdsc.paper.dwell_time.dwell_certificate`) and ``eef_switching`` (all new).

    Returns
    -------
    RecordPart
    """
    regions, conv, study = law_regions(), convergence_study(), law_study()
    dwell = dwell_certificate().record_dict()
    check = dwell_law_check()
    dwell["dwell_law_check"] = {"tau": check.tau, "horizon": check.horizon,
                                "max_final_ratio": float(check.final_ratio.max()),
                                "switches": check.switches.tolist()}
    reference = _reference_record(study)
    hd = {"hysteresis": _law_record(study, "hysteresis"), "dwell": _law_record(study, "dwell"),
          "hysteresis_absolute": _law_record(study, "hysteresis_abs"),
          "reference": reference, "cases": list(LAW_CASES), "dt": study.dt,
          "against_comparators": against_comparators(study, comparator_energies(dt=study.dt))}
    hd["dwell_time_bound"] = dwell
    return RecordPart((
        _sliding_entry(regions, conv),
        entry("hysteresis_dwell", "paper Remark 7 (hysteresis, minimum dwell time; nothing printed)",
              None, hd, "new",
              "Energies and switch counts at dt and dt/2 of the hysteresis (relative and absolute "
              "margin) and minimum-dwell-time laws on the paper's stationary, mixed (ρ_p = 0.1) "
              "and piecewise (T = 500 s, ρ_t = 0.2) cases; a law is well-posed here if its "
              "switch count does not grow when dt halves."),
        entry("eef_switching", "paper Remark 6 (an FD-EEF-based law; nothing printed)", None,
              {"window": _law_record(study, "window"), "reference": reference,
               "cases": list(LAW_CASES), "dt": study.dt}, "new",
              "The law on the score averaged over the last T_w seconds (the FD-EEF of the recent "
              "past per unit time), with the measured ẋ, against T_w."),
    ))
