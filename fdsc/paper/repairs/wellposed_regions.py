"""Chapter 'switching_law', continued: the conflict region of the printed law and its convergence.

Where each mode holds itself under the measured ẋ (:func:`holds_itself`), the four kinds of
points of the state space (:data:`REGION_KINDS`) with and without a disturbance, and the
printed law's runs as dt halves.
"""

from dataclasses import dataclass
from numbers import Integral, Real

import numpy as np

from fdsc._validation import as_count, as_positive
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.data import (
    STATIONARY_DT,
    mixed_disturbance,
    our_q,
    paper_disturbance,
    paper_fdsc,
    paper_modes,
)
from fdsc.paper.shared.prose import count, num, pct
from fdsc.simulate import time_grid

__all__ = [
    "ConvergenceRow", "ConvergenceStudy", "LawRegions", "REGION_KINDS", "convergence_study",
    "holds_itself", "law_regions", "region_codes",
]


#: The four kinds of points (codes 0-3) for two modes.
REGION_KINDS = ("only mode 1 holds itself", "only mode 2 holds itself",
                "both hold themselves (memory)", "neither: chatters")


#: The d value (besides 0) at which the regions are drawn: one tone's amplitude.
D_REF = 1.0


def _cell(value):
    """A table cell as the book prints it (:mod:`fdsc.paper.shared.prose`): yes/no, counts, numbers."""
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
        """The numbers the chapter quotes, as text (:mod:`fdsc.paper.shared.prose`).

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
        """One row per run, every cell text (:mod:`fdsc.paper.shared.prose`), for
        :func:`fdsc.paper.shared.report.html_table` (a table may show a subset of the columns).

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
        """The numbers the chapter quotes, as text (:mod:`fdsc.paper.shared.prose`).

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
