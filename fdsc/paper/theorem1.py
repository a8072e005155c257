"""Chapter 'theorem1': Theorem 1 (paper eqs. (33), (34)) on the aircraft, the paper's and our Q's,
statement (1) by simulation and the Lyapunov jumps, statements (2) and (3) (paper eqs. (35),
(36)) against simulated energy ratios.
"""

from dataclasses import dataclass

import numpy as np

from .._validation import as_count, as_positive, check_type, frozen_array
from ..bands import Band
from ..frequency import band_peak
from ..signals import Sinusoids
from ..simulate import SimResult, simulate, time_grid
from ..switching import DEFAULT_GAMMA_TOL, Theorem1Result, certify_q, design_q
from .cache import cached
from .data import (
    STATIONARY_DT,
    our_q,
    paper_data,
    paper_disturbance,
    paper_modes,
    run_controller,
)
from .prose import count, matrix_text, num, pct
from .results import RecordPart, entry, pick

__all__ = [
    "record_part",
    "Theorem1Row",
    "Theorem1Table",
    "theorem1_table",
    "AutonomousRuns",
    "autonomous_stability",
    "LyapunovJumps",
    "lyapunov_jumps",
    "autonomous_lyapunov_jumps",
    "Statement1Check",
    "statement1",
    "window_ratios",
    "WindowCheck",
    "Statement2Check",
    "statement2",
    "AsymptoticCheck",
    "Statement3Check",
    "statement3",
    "matrix_text",
]


#: How the two sets of Q's are labelled in the results.
_Q_LABELS = ("paper", "ours")


def _whole(x):
    """A count or a length as the prose prints it: whole numbers without decimals."""
    x = float(x)
    return count(int(x)) if x.is_integer() else num(x)


@dataclass(frozen=True)
class Theorem1Row:
    """The γ's that Theorem 1 certifies for one pair of Q's.

    Parameters
    ----------
    source : str
        ``"paper's Q's (certified)"`` or ``"paper Remark 4 design"``.
    gamma_tol : float
        γ_tol of the design (NaN for the paper's Q's).
    gamma_1, gamma_2 : float
        γ_1 (mode 1, PassC-LF) and γ_2 (mode 2, PassC-HF) of (T1-2).
    Q_1, Q_2 : (2, 2) ndarray
        The law's Q's.
    max_eig : float
        Largest eigenvalue of all LMI matrices at the solution (< 0).
    """

    source: str
    gamma_tol: float
    gamma_1: float
    gamma_2: float
    Q_1: np.ndarray
    Q_2: np.ndarray
    max_eig: float

    @property
    def gammas(self) -> np.ndarray:
        """``[γ_1, γ_2]``."""
        return np.array([self.gamma_1, self.gamma_2])


@dataclass(frozen=True)
class Theorem1Table:
    """What Theorem 1 certifies with the paper's Q's and with the paper Remark 4 design.

    Parameters
    ----------
    certified : tuple of Theorem1Row
        The paper's Q's first, then one design per γ_tol.
    hinf : (2,) ndarray
        H∞ norm of each mode's closed loop (PassC-LF, PassC-HF) over all frequencies.
    band_peaks : (2,) ndarray
        Peak of σ_max of each mode's closed loop over its own range (Ω_1, Ω_3): the Lemma 1
        bound of the mode alone.
    """

    certified: tuple
    hinf: np.ndarray
    band_peaks: np.ndarray

    def __post_init__(self):
        for name in ("hinf", "band_peaks"):
            object.__setattr__(self, name, frozen_array(np.asarray(getattr(self, name), dtype=float)))

    @property
    def paper(self) -> Theorem1Row:
        """The row of the paper's Q's."""
        return self.certified[0]

    @property
    def designs(self) -> tuple:
        """The rows of the paper Remark 4 design, one per γ_tol."""
        return self.certified[1:]

    def rows(self) -> list:
        """One row per pair of Q's (for :func:`fdsc.paper.report.html_table`).

        Returns
        -------
        list of dict
            ``source, gamma_tol, gamma_1, gamma_2, Q_1, Q_2, max_eig``.
        """
        keys = ("source", "gamma_tol", "gamma_1", "gamma_2", "Q_1", "Q_2", "max_eig")
        return [{k: getattr(r, k) for k in keys} for r in self.certified]

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``paper_g1``, ``paper_g2`` (the γ's the printed Q's certify),
            ``hinf_mode1``, ``hinf_mode2`` (H∞ norms of the modes), ``hf_mode2`` (PassC-HF's
            in-band peak), ``gamma_tol`` (the default γ_tol of our Q's), ``gamma_tols`` (those
            tried).
        """
        return {"paper_g1": num(float(self.paper.gamma_1), 4), "paper_g2": num(float(self.paper.gamma_2), 4),
                "hinf_mode1": num(float(self.hinf[0])), "hinf_mode2": num(float(self.hinf[1]), 4),
                "hf_mode2": num(float(self.band_peaks[1]), 5), "gamma_tol": _whole(DEFAULT_GAMMA_TOL),
                "gamma_tols": ", ".join(_whole(r.gamma_tol) for r in self.designs)}

    def table_rows(self) -> list:
        """:meth:`rows` as the book prints them (γ's, Q's and eigenvalues formatted).

        Returns
        -------
        list of dict
        """
        def tol(x):
            return "—" if x is None or not np.isfinite(x) else _whole(x)

        return [{**r, "gamma_tol": tol(r["gamma_tol"]),
                 "gamma_1": num(float(r["gamma_1"]), 5), "gamma_2": num(float(r["gamma_2"]), 5),
                 "Q_1": matrix_text(r["Q_1"]), "Q_2": matrix_text(r["Q_2"]),
                 "max_eig": num(float(r["max_eig"]), 2)} for r in self.rows()]

    def to_record(self) -> RecordPart:
        """Record entries ``thm1_gammas`` and ``thm1_mode_reference`` (new).

        Returns
        -------
        RecordPart
        """
        p = self.paper
        design_g2 = [r.gamma_2 for r in self.designs]
        above = bool(np.all(p.gammas > self.hinf))
        return RecordPart((
            entry("thm1_gammas", "Theorem 1, paper Remark 4 (gammas not printed)", None,
                  {"paper_Q": [p.gamma_1, p.gamma_2],
                   "ours": {f"gamma_tol={r.gamma_tol:g}": [r.gamma_1, r.gamma_2] for r in self.designs}},
                  "new", "the paper prints no gammas; these are the values Theorem 1 certifies."),
            entry("thm1_mode_reference", "Theorem 1 against Lemma 1 for each mode alone", None,
                  {"hinf": {"PassC-LF": self.hinf[0], "PassC-HF": self.hinf[1]},
                   "own_band_peak": {"PassC-LF": self.band_peaks[0], "PassC-HF": self.band_peaks[1]},
                   "paper_Q_gammas": [p.gamma_1, p.gamma_2], "paper_Q_gammas_above_hinf": above,
                   "design_gamma_2_range": [min(design_g2), max(design_g2)]},
                  "new",
                  "reference gains of each FDSC loop alone: its H-infinity norm and its peak over "
                  "its own range (the best in-band bound Lemma 1 gives). "
                  + ("Each gamma_i the printed Q's certify exceeds the H-infinity norm of its own "
                     "loop (no useful attenuation). " if above else "")
                  + "The Remark 4 design attains PassC-HF's Omega_3 peak as gamma_2 for every "
                  "gamma_tol tried."),
        ))


@cached
def theorem1_table(gamma_tols: tuple = (1.0, 10.0, 100.0, 1000.0)) -> Theorem1Table:
    """γ's certified by Theorem 1 with the paper's Q's and with the paper Remark 4 design over γ_tol.

    Parameters
    ----------
    gamma_tols : sequence of float, optional
        The γ_tol's of the design.

    Returns
    -------
    Theorem1Table

    Notes
    -----
    The LMIs are (T1-1) and (T1-2), paper eqs. (33) and (34); the design fixes γ_j = γ_tol for
    the out-of-band mode and minimizes γ_i of the in-band mode (paper Remark 4, paper eq. (53)).
    """
    pm = paper_modes()
    paper = certify_q(pm["modes"], pm["bands"], pm["Q"])
    rows = [Theorem1Row("paper's Q's (certified)", np.nan, paper.gammas[0], paper.gammas[1],
                        paper.Q[0], paper.Q[1], max(paper.max_eigs.values()))]
    for gt in gamma_tols:
        r = design_q(pm["modes"], pm["bands"], 1, gamma_tol=gt)
        rows.append(Theorem1Row("paper Remark 4 design", gt, r.gammas[0], r.gammas[1], r.Q[0],
                                r.Q[1], max(r.max_eigs.values())))
    return Theorem1Table(tuple(rows), [band_peak(m, Band.entire()).gamma for m in pm["modes"]],
                         [band_peak(m, b).gamma for m, b in zip(pm["modes"], pm["bands"], strict=True)])


@dataclass(frozen=True)
class AutonomousRuns:
    """Runs of the autonomous switched loop (d = 0) from random initial states.

    Parameters
    ----------
    final_ratio : (k,) ndarray
        ‖x(T)‖/‖x(0)‖ per run.
    max_growth : (k,) ndarray
        max over t of ‖x(t)‖/‖x(0)‖ per run.
    switches : (k,) int ndarray
        Number of switches per run.
    horizon : float
        Length of each run in s.
    """

    final_ratio: np.ndarray
    max_growth: np.ndarray
    switches: np.ndarray
    horizon: float

    def __post_init__(self):
        for name in ("final_ratio", "max_growth", "switches"):
            object.__setattr__(self, name, frozen_array(getattr(self, name)))
        if not self.final_ratio.shape == self.max_growth.shape == self.switches.shape:
            raise ValueError("final_ratio, max_growth and switches must have one shape (one value "
                             f"per run), but found {self.final_ratio.shape}, "
                             f"{self.max_growth.shape}, {self.switches.shape}")

    @property
    def n_runs(self) -> int:
        """Number of runs."""
        return int(self.final_ratio.size)

    def summary(self) -> dict:
        """``{"max_final_ratio", "max_growth", "median_switches"}`` over the runs.

        Returns
        -------
        dict
        """
        return {"max_final_ratio": float(self.final_ratio.max()),
                "max_growth": float(self.max_growth.max()),
                "median_switches": float(np.median(self.switches))}


_ZERO = Sinusoids([0.0], [1.0])


def autonomous_stability(n_initial: int = 40, *, horizon: float = 60.0, dt: float = 1e-3,
                         seed: int = 3, Q=None) -> AutonomousRuns:
    """Statement (1) of Theorem 1: the autonomous switched loop (d = 0) from random initial states.

    Parameters
    ----------
    n_initial : int, optional
        Number of initial states (standard normal).
    horizon, dt : float, optional
        Length and step of each run in s.
    seed : int, optional
        Seed of the initial states.
    Q : list of (2, 2) array_like, optional
        Q's of the switching law (default the paper's).

    Returns
    -------
    AutonomousRuns

    Examples
    --------
    >>> runs = autonomous_stability(2, horizon=5.0)
    >>> runs.n_runs, bool(np.all(runs.final_ratio < 1))
    (2, True)
    """
    n_initial = as_count("n_initial", n_initial)
    rng = np.random.default_rng(seed)
    pm = paper_modes()
    Q = pm["Q"] if Q is None else Q
    t = time_grid(horizon, dt)
    ratios, growth, switches = [], [], []
    for _ in range(n_initial):
        x0 = rng.standard_normal(2)
        sim = simulate(pm["modes"], _ZERO, t, x0=x0, law_bands=pm["bands"], law_Q=Q)
        nrm = np.linalg.norm(sim.x, axis=1) / np.linalg.norm(x0)
        ratios.append(float(nrm[-1]))
        growth.append(float(nrm.max()))
        switches.append(int(sim.switch_times.size))
    return AutonomousRuns(np.array(ratios), np.array(growth), np.array(switches), float(horizon))


@dataclass(frozen=True)
class LyapunovJumps:
    """Jumps of ``V = xᵀ P^s_σ x`` (paper eq. (37)) at the switching instants of some runs.

    Parameters
    ----------
    ratios : (k,) ndarray
        V(t⁺)/V(t⁻) at every switch of every run.
    n_runs : int
        Number of runs.
    horizon : float
        Length of each run in s.
    final_ratio : (n_runs,) ndarray
        ‖x(T)‖/‖x(0)‖ per run (empty for runs from rest).
    """

    ratios: np.ndarray
    n_runs: int
    horizon: float
    final_ratio: np.ndarray

    def __post_init__(self):
        object.__setattr__(self, "ratios", frozen_array(np.asarray(self.ratios, dtype=float)))
        object.__setattr__(self, "final_ratio",
                           frozen_array(np.asarray(self.final_ratio, dtype=float)))

    @property
    def n_switches(self) -> int:
        """Number of switches of all runs."""
        return int(self.ratios.size)

    @property
    def max_ratio(self) -> float:
        """Largest jump ratio (1 when nothing switches)."""
        return float(self.ratios.max()) if self.ratios.size else 1.0

    @property
    def frac_up(self) -> float:
        """Share of the switches at which V increases."""
        return float(np.mean(self.ratios > 1)) if self.ratios.size else 0.0


def _jump_ratios(sim, Ps):
    k = np.flatnonzero(np.diff(sim.sigma)) + 1
    x = sim.x[k]
    before = np.einsum("ki,kij,kj->k", x, Ps[sim.sigma[k - 1]], x)
    after = np.einsum("ki,kij,kj->k", x, Ps[sim.sigma[k]], x)
    return after / before


def lyapunov_jumps(result: Theorem1Result, *, kind: str = "HF", horizon: float = 20.0,
                   dt: float = STATIONARY_DT, Q=None) -> LyapunovJumps:
    """Jumps of V = xᵀ P^s_σ x at the switching instants of an FDSC run from rest.

    Parameters
    ----------
    result : Theorem1Result
        Supplies P^s_1, P^s_2 (and, unless ``Q`` is given, the law's Q's).
    kind : {"LF", "HF"}, optional
        The paper's disturbance (paper eqs. (56), (57)).
    horizon, dt : float, optional
        Length and step of the run in s.
    Q : list of (2, 2) array_like, optional
        Q's of the switching law.

    Returns
    -------
    LyapunovJumps
        One run (``final_ratio`` empty: the run starts from rest).
    """
    check_type("result", result, Theorem1Result)
    pm = paper_modes()
    d = paper_disturbance(kind)
    t = time_grid(horizon, dt)
    sim = simulate(pm["modes"], d, t, law_bands=pm["bands"], law_Q=result.Q if Q is None else Q)
    return LyapunovJumps(_jump_ratios(sim, np.array(result.Ps)), 1, float(horizon), np.empty(0))


def autonomous_lyapunov_jumps(result: Theorem1Result, n_initial: int = 40, *,
                              horizon: float = 60.0, dt: float = 1e-3, seed: int = 3,
                              Q=None) -> LyapunovJumps:
    """Jumps of ``V = xᵀ P^s_σ x`` at the switches of the autonomous switched loop (d = 0).

    Theorem 1 statement (1) is about d = 0; its proof differentiates V (paper eq. (37)) between
    switches and never compares V across a switch. The runs start from the same random initial
    states as :func:`autonomous_stability` (same ``seed``).

    Parameters
    ----------
    result : Theorem1Result
        Supplies P^s_1, P^s_2 and (unless ``Q`` is given) the law's Q's.
    n_initial : int, optional
        Number of initial states (standard normal).
    horizon, dt : float, optional
        Length and step of each run in s.
    seed : int, optional
        Seed of the initial states.
    Q : list of (n, n) array_like, optional
        Q's of the switching law.

    Returns
    -------
    LyapunovJumps

    Examples
    --------
    >>> from fdsc.paper.data import our_q
    >>> j = autonomous_lyapunov_jumps(our_q(), 3, horizon=5.0)
    >>> j.n_runs, bool(j.max_ratio > 1)
    (3, True)
    """
    check_type("result", result, Theorem1Result)
    n_initial = as_count("n_initial", n_initial)
    pm = paper_modes()
    Q = result.Q if Q is None else Q
    Ps = np.array(result.Ps)
    rng = np.random.default_rng(seed)
    t = time_grid(horizon, dt)
    ratios, final = [], []
    for _ in range(n_initial):
        x0 = rng.standard_normal(Ps.shape[1])
        sim = simulate(pm["modes"], _ZERO, t, x0=x0, law_bands=pm["bands"], law_Q=Q)
        ratios.append(_jump_ratios(sim, Ps))
        final.append(float(np.linalg.norm(sim.x[-1]) / np.linalg.norm(x0)))
    return LyapunovJumps(np.concatenate(ratios), n_initial, float(horizon), np.array(final))


@dataclass(frozen=True)
class Statement1Check:
    """Statement (1) of Theorem 1 by simulation, with the paper's and our Q's, and the jumps of V.

    Parameters
    ----------
    paper, ours : AutonomousRuns
        The autonomous runs with the paper's and with our Q's (same initial states).
    jumps : LyapunovJumps
        The jumps of V on the runs with our Q's (whose certificate supplies P^s).

    Raises
    ------
    ValueError
        If the jumps were not measured on the runs of ``ours``.
    """

    paper: AutonomousRuns
    ours: AutonomousRuns
    jumps: LyapunovJumps

    def __post_init__(self):
        if self.jumps.final_ratio.shape != self.ours.final_ratio.shape or not np.allclose(
                self.jumps.final_ratio, self.ours.final_ratio, rtol=1e-12, atol=0.0):
            raise ValueError("jumps must be measured on the runs of ours (same initial states, "
                             "same final states)")

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``stab_n``, ``stab_T``; for ``paper`` and ``ours``
            ``stab_<q>_final`` (largest ‖x(T)‖/‖x(0)‖), ``stab_<q>_growth``,
            ``stab_<q>_switches`` (median); ``jump_max``, ``jump_n``, ``jump_runs``, ``jump_up``.
        """
        out = {"stab_n": count(self.paper.n_runs), "stab_T": _whole(self.paper.horizon)}
        for key, runs in (("paper", self.paper), ("ours", self.ours)):
            sm = runs.summary()
            out.update({f"stab_{key}_final": num(sm["max_final_ratio"], 2),
                        f"stab_{key}_growth": num(sm["max_growth"], 4),
                        f"stab_{key}_switches": _whole(sm["median_switches"])})
        j = self.jumps
        return {**out, "jump_max": num(j.max_ratio), "jump_n": count(j.n_switches),
                "jump_runs": count(j.n_runs), "jump_up": pct(j.frac_up)}

    def to_record(self) -> RecordPart:
        """Record entries ``thm1_statement1`` and ``thm1_lyapunov_jumps`` (both new).

        Returns
        -------
        RecordPart
        """
        return RecordPart((
            entry("thm1_statement1", "Theorem 1, statement (1) (d = 0; nothing printed)", None,
                  {"paper_Q": self.paper.summary(), "ours": self.ours.summary(),
                   "n_runs": self.paper.n_runs, "horizon": self.paper.horizon},
                  "new",
                  "autonomous switched loop from random initial states: every run decays (max "
                  "final ratio ||x(T)||/||x(0)|| < 1) with the paper's Q's and with ours; a "
                  "numerical check, not a proof."),
            entry("thm1_lyapunov_jumps", "Theorem 1, proof of statement (1), paper eq. (37)", None,
                  {"max_ratio": self.jumps.max_ratio, "frac_up": self.jumps.frac_up,
                   "n_switches": self.jumps.n_switches, "n_runs": self.jumps.n_runs},
                  "new",
                  "V = x' P^s_sigma x at the switches of the autonomous runs with our Q's: V jumps "
                  "up at a share frac_up of the switches, by up to max_ratio; the printed proof "
                  "does not cover the jumps."),
        ))


@cached
def statement1(n_initial: int = 40, *, horizon: float = 60.0, dt: float = 1e-3,
               seed: int = 3) -> Statement1Check:
    """Statement (1) of Theorem 1 with the paper's and our Q's, and the jumps of V on our runs.

    Parameters
    ----------
    n_initial : int, optional
        Number of initial states.
    horizon, dt : float, optional
        Length and step of each run in s.
    seed : int, optional
        Seed of the initial states.

    Returns
    -------
    Statement1Check

    Notes
    -----
    Statement (1) claims stability of the autonomous loop; its proof uses the multiple
    Lyapunov function of paper eq. (37).
    """
    ours = our_q()
    return Statement1Check(
        autonomous_stability(n_initial, horizon=horizon, dt=dt, seed=seed),
        autonomous_stability(n_initial, horizon=horizon, dt=dt, seed=seed, Q=ours.Q),
        autonomous_lyapunov_jumps(ours, n_initial, horizon=horizon, dt=dt, seed=seed))


def window_ratios(run_sim: SimResult, window: float) -> np.ndarray:
    """Energy ratio ∫zᵀz/∫d² over consecutive windows of a run (Theorem 1 statement (2)).

    Parameters
    ----------
    run_sim : SimResult
        A run on a uniform grid.
    window : float
        Window length in s (at least two steps, at most the run).

    Returns
    -------
    (k,) ndarray

    Raises
    ------
    ValueError
        If the window spans fewer than two steps or more than the run.
    """
    t = run_sim.t
    window = as_positive("window", window)
    n = round(window / (t[1] - t[0]))
    if n < 2 or n > t.size - 1:
        raise ValueError(f"window must span between 2 steps ({2 * (t[1] - t[0]):g} s) and the run "
                         f"({t[-1] - t[0]:g} s), but found {window:g} s")
    zz = np.sum(run_sim.z**2, axis=1)
    out = []
    for k0 in range(0, t.size - n, n):
        sl = slice(k0, k0 + n + 1)
        out.append(float(np.trapezoid(zz[sl], t[sl]) / np.trapezoid(run_sim.d[sl] ** 2, t[sl])))
    return np.array(out)


def _certified_gammas():
    """γ's certified for the paper's Q's and for ours: ``{"paper": (2,), "ours": (2,)}``."""
    pm = paper_modes()
    return {"paper": np.asarray(certify_q(pm["modes"], pm["bands"], pm["Q"]).gammas),
            "ours": np.asarray(our_q().gammas)}


def _law_q(label):
    return paper_modes()["Q"] if label == "paper" else our_q().Q


@dataclass(frozen=True)
class WindowCheck:
    """Energy ratios over windows of one FDSC run against the bound max γ_i² of statement (2).

    Parameters
    ----------
    disturbance : {"LF", "HF"}
        The paper's disturbance.
    q_label : {"paper", "ours"}
        Whose Q's the law uses.
    ratios : (k,) ndarray
        ∫zᵀz/∫d² over each window.
    bound : float
        max_i γ_i² certified for these Q's.
    """

    disturbance: str
    q_label: str
    ratios: np.ndarray
    bound: float

    @property
    def max_ratio(self) -> float:
        """Largest window ratio."""
        return float(self.ratios.max())

    @property
    def mean_ratio(self) -> float:
        """Mean window ratio."""
        return float(self.ratios.mean())

    @property
    def holds(self) -> bool:
        """Every window ratio is below the bound (without the residue ε_T)."""
        return bool(self.max_ratio <= self.bound)


@dataclass(frozen=True)
class Statement2Check:
    """Statement (2) of Theorem 1 (paper eq. (35)) over windows of FDSC runs (see
    :func:`statement2`).

    Parameters
    ----------
    horizon, window, dt : float
        Run length, window length and step in s.
    cases : tuple of WindowCheck
        One per (disturbance, Q's).
    """

    horizon: float
    window: float
    dt: float
    cases: tuple

    def case(self, disturbance: str, q_label: str) -> WindowCheck:
        """The check of one run.

        Parameters
        ----------
        disturbance : {"LF", "HF"}
            The disturbance.
        q_label : {"paper", "ours"}
            Whose Q's.

        Returns
        -------
        WindowCheck
        """
        for c in self.cases:
            if (c.disturbance, c.q_label) == (disturbance, q_label):
                return c
        raise KeyError(f"no run with disturbance {disturbance!r} and Q's {q_label!r}")

    def bound(self, q_label: str) -> float:
        """The bound max_i γ_i² of one set of Q's.

        Parameters
        ----------
        q_label : {"paper", "ours"}
            Whose Q's.

        Returns
        -------
        float
        """
        return pick(self.cases, "q_label", q_label).bound

    def rows(self) -> list:
        """One row per run: ``disturbance, Q's, max ratio, mean ratio, bound max γ²``.

        Returns
        -------
        list of dict
        """
        return [{"disturbance": c.disturbance, "Q's": c.q_label, "max ratio": c.max_ratio,
                 "mean ratio": c.mean_ratio, "bound max γ²": c.bound} for c in self.cases]

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``s2_horizon``, ``s2_window``, ``bound_paper``, ``bound_ours``,
            ``wr_max_lf_paper``.
        """
        return {"s2_horizon": _whole(self.horizon), "s2_window": _whole(self.window),
                "bound_paper": num(self.bound("paper")), "bound_ours": num(self.bound("ours"), 4),
                "wr_max_lf_paper": num(self.case("LF", "paper").max_ratio, 4)}

    def to_record(self) -> RecordPart:
        """Record entry ``thm1_statement2`` (new).

        Returns
        -------
        RecordPart
        """
        rec = {f"{c.disturbance}, {c.q_label} Q": {"max_ratio": c.max_ratio, "bound": c.bound,
                                                   "below_bound": c.holds} for c in self.cases}
        return RecordPart((entry(
            "thm1_statement2", "Theorem 1, statement (2), paper eq. (35) (nothing printed)", None,
            rec, "new",
            f"FDSC from rest, {self.horizon:g} s runs, energy ratio int z'z / int d^2 over "
            f"{self.window:g} s windows against max_i gamma_i^2 (the residue epsilon_T is not "
            "computable a priori and is left out).", window=self.window, horizon=self.horizon),))


@cached
def statement2(*, horizon: float = 100.0, window: float = 10.0, dt: float = 1e-3) -> Statement2Check:
    """Statement (2) of Theorem 1: windowed energy ratios of FDSC runs against max_i γ_i².

    FDSC runs from rest under the paper's LF and HF disturbances, with the paper's and with our
    Q's; each run's ratios over consecutive windows (:func:`window_ratios`) set against the
    largest γ_i² Theorem 1 certifies for its Q's.

    Parameters
    ----------
    horizon, window, dt : float, optional
        Run length, window length and step in s.

    Returns
    -------
    Statement2Check

    Notes
    -----
    Statement (2), paper eq. (35), bounds the ratio by ``max_i γ_i² + ε_T``; ε_T involves the
    law's own terms and V at the window ends and is not computable a priori.
    """
    t = time_grid(horizon, dt)
    gammas = _certified_gammas()
    cases = []
    for kind in ("LF", "HF"):
        d = paper_disturbance(kind)
        for label in _Q_LABELS:
            ratios = window_ratios(run_controller("FDSC", d, t, Q=_law_q(label)), window)
            cases.append(WindowCheck(kind, label, ratios, float(gammas[label].max() ** 2)))
    return Statement2Check(float(horizon), float(window), float(dt), tuple(cases))


@dataclass(frozen=True)
class AsymptoticCheck:
    """The long-run energy ratio of one FDSC run against Σ_i β_i γ_i² of statement (3).

    Parameters
    ----------
    disturbance : {"LF", "HF"}
        The paper's disturbance.
    q_label : {"paper", "ours"}
        Whose Q's the law uses.
    ratio : float
        ∫zᵀz/∫d² over the run.
    beta : (2,) ndarray
        Time share β_i of each mode.
    gammas : (2,) ndarray
        γ_i certified for these Q's.
    """

    disturbance: str
    q_label: str
    ratio: float
    beta: np.ndarray
    gammas: np.ndarray

    @property
    def bound(self) -> float:
        """Σ_i β_i γ_i²."""
        return float(self.beta @ self.gammas**2)

    @property
    def below(self) -> bool:
        """The ratio lies below Σ_i β_i γ_i² (without the residue ε_∞)."""
        return bool(self.ratio < self.bound)


@dataclass(frozen=True)
class Statement3Check:
    """Statement (3) of Theorem 1 (paper eq. (36)) on long FDSC runs (see :func:`statement3`).

    Parameters
    ----------
    horizon, dt : float
        Run length and step in s.
    cases : tuple of AsymptoticCheck
        One per (disturbance, Q's).
    """

    horizon: float
    dt: float
    cases: tuple

    @property
    def n_below(self) -> int:
        """Number of runs whose ratio lies below Σ_i β_i γ_i²."""
        return sum(c.below for c in self.cases)

    def case(self, disturbance: str, q_label: str) -> AsymptoticCheck:
        """The check of one run.

        Parameters
        ----------
        disturbance : {"LF", "HF"}
            The disturbance.
        q_label : {"paper", "ours"}
            Whose Q's.

        Returns
        -------
        AsymptoticCheck
        """
        for c in self.cases:
            if (c.disturbance, c.q_label) == (disturbance, q_label):
                return c
        raise KeyError(f"no run with disturbance {disturbance!r} and Q's {q_label!r}")

    @property
    def ratio_label(self) -> str:
        """Column header of the ratio in :meth:`rows`."""
        return f"ratio over {self.horizon:g} s"

    def rows(self) -> list:
        """One row per run: ``disturbance, Q's, ratio over T s, β₁, β₂, Σ βᵢγᵢ²``.

        Returns
        -------
        list of dict
        """
        return [{"disturbance": c.disturbance, "Q's": c.q_label, self.ratio_label: c.ratio,
                 "β₁": c.beta[0], "β₂": c.beta[1], "Σ βᵢγᵢ²": c.bound} for c in self.cases]

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``s3_horizon``, ``s3_ours_hf_ratio``, ``s3_ours_hf_bound``,
            ``s3_n_below``, ``s3_n``.
        """
        hf = self.case("HF", "ours")
        return {"s3_horizon": _whole(self.horizon), "s3_ours_hf_ratio": num(hf.ratio, 4),
                "s3_ours_hf_bound": num(hf.bound, 4), "s3_n_below": count(self.n_below),
                "s3_n": count(len(self.cases))}

    def to_record(self) -> RecordPart:
        """Record entry ``thm1_statement3`` (new).

        Returns
        -------
        RecordPart
        """
        rec = {f"{c.disturbance}, {c.q_label} Q": {"ratio": c.ratio, "beta": c.beta,
                                                   "sum_beta_gamma2": c.bound, "below": c.below}
               for c in self.cases}
        return RecordPart((entry(
            "thm1_statement3", "Theorem 1, statement (3), paper eq. (36) (nothing printed)", None,
            rec, "new",
            f"FDSC from rest over {self.horizon:g} s: the energy ratio lies below "
            f"sum_i beta_i gamma_i^2 (beta_i measured time shares) in {self.n_below} of "
            f"{len(self.cases)} runs without the residue epsilon_inf.", horizon=self.horizon),))


@cached
def statement3(*, horizon: float = 500.0, dt: float = 1e-3) -> Statement3Check:
    """Statement (3) of Theorem 1: the long-run energy ratio against Σ_i β_i γ_i².

    FDSC runs from rest under the paper's LF and HF disturbances, with the paper's and with our
    Q's; β_i is the measured time share of mode i and γ_i the value certified for the run's Q's.

    Parameters
    ----------
    horizon, dt : float, optional
        Run length and step in s.

    Returns
    -------
    Statement3Check

    Notes
    -----
    Statement (3), paper eq. (36), bounds the asymptotic ratio by ``Σ_i β_i γ_i² + ε_∞``.
    """
    t = time_grid(horizon, dt)
    gammas = _certified_gammas()
    cases = []
    for kind in ("LF", "HF"):
        d = paper_disturbance(kind)
        for label in _Q_LABELS:
            sim = run_controller("FDSC", d, t, Q=_law_q(label))
            cases.append(AsymptoticCheck(kind, label, sim.energy() / sim.input_energy(),
                                         np.asarray(sim.time_share()), gammas[label]))
    return Statement3Check(float(horizon), float(dt), tuple(cases))


def _q_entries(table):
    sw = paper_data("switching")
    ours = our_q()
    p = table.paper
    return RecordPart(tuple(entry(
        name, f"Sec. IV, {name}", sw[name]["value"], ours.Q[k], "not reproducible",
        "the paper prints the Q's but not gamma_tol nor the Q's scale, which the Remark 4 design "
        "needs (Q enters Theorem 1 only through differences); ours: Remark 4 design with "
        f"gamma_tol = {DEFAULT_GAMMA_TOL:g} (in-band mode PassC-HF): it reaches gamma_2 = "
        f"{ours.gammas[1]:.4f} by driving Q_1 to the margin; the printed Q's certify only "
        f"gamma = ({num(float(p.gamma_1), 4)}, {num(float(p.gamma_2), 4)}).")
        for k, name in enumerate(("Q_1", "Q_2"))))


def record_part() -> RecordPart:
    """Record entries of the chapter.

    ``Q_1``, ``Q_2`` (the law's Q's), ``thm1_gammas`` (what Theorem 1 certifies), and the new
    ``thm1_mode_reference``, ``thm1_statement1``, ``thm1_lyapunov_jumps``,
    ``thm1_statement2``, ``thm1_statement3``.

    Returns
    -------
    RecordPart
    """
    table = theorem1_table()
    return (_q_entries(table) + table.to_record() + statement1().to_record()
            + statement2().to_record() + statement3().to_record())
