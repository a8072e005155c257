"""Chapter 'theorem1', continued: the cases of the seeded search and their runs.

The families of mode pairs and Q's, each case a pure function of ``(family, seed)``
(:func:`search_case`), the runs of the autonomous switched loop (d = 0) under both readings of
ẋ from seeded initial states, and the diagnosis of each divergent run.
"""

import warnings
from dataclasses import dataclass

import numpy as np

from fdsc.bands import Band
from fdsc.exceptions import InfeasibleError, SolverError, UnstableError, UnstableRunWarning
from fdsc.paper.shared.data import aircraft, paper_gains, paper_modes
from fdsc.plant import LTISystem
from fdsc.random_systems import random_hurwitz, random_spd
from fdsc.signals import Sinusoids
from fdsc.simulate import simulate, time_grid
from fdsc.stream import Case, simulate_batch
from fdsc.switching import DEFAULT_GAMMA_TOL, certify_q, design_q

__all__ = [
    "CAUSES", "CLEAN_LIMIT", "CaseOutcome", "Diagnosis", "FAMILIES", "Q_SCALING_FACTORS",
    "SearchCase", "diagnose", "search_case",
]


#: Families of the search, with the number of seeds of each in the default search.
FAMILIES = {"random-2": 40, "random-3": 40, "spiral-2": 80, "aircraft": 20}


_FAMILY_CODE = {"random-2": 2, "random-3": 3, "spiral-2": 12, "aircraft": 7}


#: Causes a divergent run is classified into (see :class:`Diagnosis`).
CAUSES = ("chattering", "V jumps up at switches", "V grows during flows", "other")


#: Initial states per case, and the limit on the steps of one run.
N_INITIAL = 2


MAX_STEPS = 30_000


#: The step is this fraction of 1/max_i ‖A_i‖ (the law sees the fastest flow at this resolution)
#: unless the horizon needs more than :data:`MAX_STEPS` steps.
DT_FRACTION = 0.05


#: The horizon in slowest time constants ``1/min |Re λ|``.
SLOW_CONSTANTS = 10.0


#: A divergent run is confirmed on a grid this many times finer.
REFINE = 4


#: :func:`diagnose` keeps a divergent trace up to this growth of ‖x‖.
GROWTH_LIMIT = 1e12


_ZERO = Sinusoids([0.0], [1.0])


_LAWS = ("previous", "candidate")


#: Reader-facing names of the two readings of ẋ.
_READING = {"previous": "measured ẋ", "candidate": "candidate ẋ"}


#: A divergent run is "clean" (does not chatter) if at most this share of its samples lie in
#: one-sample dwells.
CLEAN_LIMIT = 0.05


#: Common factors of the Q's tried on the smallest counterexample (2²⁷ scales exactly).
Q_SCALING_FACTORS = (2.0**27, 1e8)


@dataclass(frozen=True)
class SearchCase:
    """One case of the search: modes, law ranges, Q's and the solution of Theorem 1's LMIs (if feasible).

    Parameters
    ----------
    family : str
        One of :data:`FAMILIES`.
    seed : int
        Seed of the case (with the family, it fixes everything).
    modes : list of LTISystem
        The two closed loops (mode 0 on the LF range, mode 1 on the HF range).
    bands : list of Band
        LF and HF ranges of the law.
    Q : list of (n, n) ndarray or None
        The law's Q's (None if Theorem 1 is infeasible or a mode is not Hurwitz).
    q_source : {"design", "random"}
        Q's by paper Remark 4 (:func:`fdsc.design_q`) or random SPD (:func:`fdsc.certify_q`).
    status : str
        ``"feasible"``, ``"infeasible"`` (no Q's / the given Q's fail), ``"not Hurwitz"``
        (refused by Theorem 1 up front) or ``"solver"`` (numerical failure).
    gammas : (2,) ndarray
        The least γ's for which Theorem 1's LMIs are feasible (NaN unless feasible).
    Ps : list of (n, n) ndarray or None
        P^s_i of (T1-1) (None unless feasible).
    """

    family: str
    seed: int
    modes: list
    bands: list
    Q: list | None
    q_source: str
    status: str
    gammas: np.ndarray
    Ps: list | None

    @property
    def n(self) -> int:
        """Number of states."""
        return self.modes[0].n_states

    def grid(self) -> tuple[float, float]:
        """Step and horizon (s) of the d = 0 runs.

        T = :data:`SLOW_CONSTANTS` / ``min |Re λ|`` over both modes; dt = :data:`DT_FRACTION` /
        max ‖A_i‖₂, enlarged if needed so that T takes at most :data:`MAX_STEPS` (even) steps.

        Returns
        -------
        (float, float)
        """
        ev = np.concatenate([np.linalg.eigvals(m.A) for m in self.modes])
        T = SLOW_CONSTANTS / float(np.abs(ev.real).min())
        dt = max(DT_FRACTION / max(float(np.linalg.norm(m.A, 2)) for m in self.modes),
                 T / MAX_STEPS)
        steps = int(np.ceil(T / dt))
        return dt, (steps + steps % 2) * dt


def _random_modes(rng, n):
    A = [random_hurwitz(rng, n), random_hurwitz(rng, n)]
    # fast/slow separation (the aircraft's modes differ by a factor ~ 300): speed one mode up
    A[int(rng.integers(2))] *= 10.0 ** rng.uniform(0.0, 2.0)
    B = rng.standard_normal((n, 1))
    C = rng.standard_normal((1, n))
    return [LTISystem(a, B, C, np.zeros((1, 1))) for a in A]


def _spiral_modes(rng):
    A = []
    for _ in range(2):
        # a lightly damped spiral, stretched by k along a random direction θ: no common
        # quadratic Lyapunov function for two of them in different directions is the textbook
        # destabilizing pair (Liberzon 2003)
        w = 10.0 ** rng.uniform(0.0, 1.0)
        a = w * 10.0 ** rng.uniform(-1.5, -0.5)
        k = 10.0 ** rng.uniform(0.3, 1.0)
        th = rng.uniform(0.0, np.pi)
        R = np.array([[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]])
        A.append(-a * np.eye(2) + w * R @ np.array([[0.0, k], [-1.0 / k, 0.0]]) @ R.T)
    B = rng.standard_normal((2, 1))
    C = rng.standard_normal((1, 2))
    return [LTISystem(a, B, C, np.zeros((1, 1))) for a in A]


def _aircraft_modes(rng):
    plant, gains = aircraft(), paper_gains()
    Ks = [gains["K_f1"], gains["K_f3"]]
    return [plant.closed_loop(K * 10.0 ** rng.uniform(-1.0, 1.0)
                              * (1.0 + 0.3 * rng.standard_normal(K.shape))) for K in Ks]


def search_case(family: str, seed: int) -> SearchCase:
    """Build one case of the search from its family and seed, and solve Theorem 1's LMIs for it.

    Parameters
    ----------
    family : {"random-2", "random-3", "aircraft"}
        Random 2- or 3-state Hurwitz pairs sharing B (one mode sped up by a random factor up to
        100), or the aircraft with K_f1 and K_f3 scaled by 10^U(−1, 1) and perturbed by 30 %.
    seed : int
        Seed (≥ 0).

    Returns
    -------
    SearchCase

    Notes
    -----
    Random families draw LF and HF edges ϖ_l = 10^U(−1, 1), ϖ_h = ϖ_l·10^U(0, 1.5); the aircraft
    uses the paper's ranges. Half the cases (by a draw) get Q's by paper Remark 4 (γ_tol =
    :data:`fdsc.switching.DEFAULT_GAMMA_TOL`, a random in-band mode), the others random SPD Q's
    (condition up to 10³, relative scale 10^U(−3, 3)) for which :func:`fdsc.certify_q` finds
    Theorem 1's LMIs feasible.

    Examples
    --------
    >>> c = search_case("random-2", 0)
    >>> c.n, c.family, c.status in ("feasible", "infeasible", "solver")
    (2, 'random-2', True)
    """
    if family not in _FAMILY_CODE:
        raise ValueError(f"family must be one of {tuple(_FAMILY_CODE)}, but found {family!r}")
    rng = np.random.default_rng([_FAMILY_CODE[family], int(seed)])
    if family == "aircraft":
        modes = _aircraft_modes(rng)
        bands = paper_modes()["bands"]
    else:
        modes = (_spiral_modes(rng) if family == "spiral-2"
                 else _random_modes(rng, _FAMILY_CODE[family]))
        w_l = 10.0 ** rng.uniform(-1.0, 1.0)
        bands = [Band.lf(w_l), Band.hf(w_l * 10.0 ** rng.uniform(0.0, 1.5))]
    n = modes[0].n_states
    q_source = "design" if rng.random() < 0.5 else "random"
    in_band = int(rng.integers(2))
    Q = [random_spd(rng, n, condition=10.0 ** rng.uniform(0.0, 3.0)),
         random_spd(rng, n, condition=10.0 ** rng.uniform(0.0, 3.0)) * 10.0 ** rng.uniform(-3, 3)]
    nan = np.full(2, np.nan)
    if any(np.linalg.eigvals(m.A).real.max() >= 0 for m in modes):
        return SearchCase(family, int(seed), modes, bands, None, q_source, "not Hurwitz", nan, None)
    try:
        res = (design_q(modes, bands, in_band, gamma_tol=DEFAULT_GAMMA_TOL) if q_source == "design"
               else certify_q(modes, bands, Q))
    except SolverError as exc:
        status = "infeasible" if isinstance(exc, InfeasibleError) else "solver"
        return SearchCase(family, int(seed), modes, bands, None, q_source, status, nan, None)
    return SearchCase(family, int(seed), modes, bands, [np.asarray(q) for q in res.Q], q_source,
                      "feasible", np.asarray(res.gammas), [np.asarray(p) for p in res.Ps])


@dataclass(frozen=True)
class CaseOutcome:
    """The d = 0 runs of one feasible case under one reading of ẋ.

    Parameters
    ----------
    family : str
        Family of the case.
    seed : int
        Seed of the case.
    law : {"previous", "candidate"}
        Reading of ẋ.
    dt, horizon : float
        Step and length of the runs (s).
    final_ratio : float
        Largest ‖x(T)‖/‖x(0)‖ over the initial states (inf if a run overflowed).
    half_ratio : float
        ‖x(T/2)‖/‖x(0)‖ of the same initial state.
    worst_x0 : (n,) ndarray
        The initial state of the largest ratio.
    diverging : bool
        The run grows (it overflows, or ``final_ratio > 1`` and ``final_ratio > half_ratio``)
        on the grid dt and again on the grid dt / :data:`REFINE`.
    switches : int
        Switches of the worst run.
    grew_coarse : bool
        The run grows on the grid dt (re-run on the finer grid).
    fine_ratio : float
        Worst ‖x(T)‖/‖x(0)‖ on the finer grid (NaN if not re-run). A run that grows on dt but
        not on dt / REFINE is an artefact of sampling the law, not a counterexample.
    """

    family: str
    seed: int
    law: str
    dt: float
    horizon: float
    final_ratio: float
    half_ratio: float
    worst_x0: np.ndarray
    diverging: bool
    switches: int
    grew_coarse: bool
    fine_ratio: float


def _x0s(case):
    rng = np.random.default_rng([_FAMILY_CODE[case.family], case.seed, 1])
    return [rng.standard_normal(case.n) for _ in range(N_INITIAL)]


def _runs(cases, laws, refine=1):
    """Batch-run cases from their initial states to T and to T/2 on the grid dt/refine; per
    (case, law) the worst ``(ratio at T, ratio at T/2, x0, switches, overflowed)``."""
    runs = []
    for c, law in zip(cases, laws, strict=True):
        dt, T = c.grid()
        for x0 in _x0s(c):
            for h in (T, T / 2):
                runs.append(Case(c.modes, _ZERO, h, dt / refine, x0=x0, law_bands=c.bands,
                                 law_Q=c.Q, law=law))
    with warnings.catch_warnings():
        # divergent runs are what the search looks for; they are counted, not warned about
        warnings.simplefilter("ignore", UnstableRunWarning)
        batch = simulate_batch(runs)
    out, k = [], 0
    for c in cases:
        best = None
        for x0 in _x0s(c):
            full, half = batch[k], batch[k + 1]
            k += 2
            nx0 = np.linalg.norm(x0)
            with np.errstate(over="ignore"):
                r = np.inf if full.diverged_at is not None else float(
                    np.linalg.norm(full.x_final) / nx0)
                rh = np.inf if half.diverged_at is not None else float(
                    np.linalg.norm(half.x_final) / nx0)
            if best is None or r > best[0]:
                best = (r, rh, x0, full.switches, full.diverged_at is not None)
        out.append(best)
    return out


def _grows(r, rh, overflow):
    return bool(overflow or (r > 1 and r > rh))


def _outcomes(cases):
    """Every feasible case under both laws; a growing run is re-run on a finer grid."""
    pairs = [(c, law) for c in cases for law in _LAWS]
    first = _runs([p[0] for p in pairs], [p[1] for p in pairs])
    grow = [k for k, b in enumerate(first) if _grows(b[0], b[1], b[4])]
    fine = dict(zip(grow, _runs([pairs[k][0] for k in grow], [pairs[k][1] for k in grow],
                                REFINE), strict=True)) if grow else {}
    out = []
    for k, ((c, law), (r, rh, x0, sw, _)) in enumerate(zip(pairs, first, strict=True)):
        dt, T = c.grid()
        f = fine.get(k)
        out.append(CaseOutcome(c.family, c.seed, law, dt, T, float(r), float(rh), x0,
                               f is not None and _grows(f[0], f[1], f[4]), int(sw),
                               k in fine, float(f[0]) if f is not None else float("nan")))
    return out


@dataclass(frozen=True)
class Diagnosis:
    """Why one divergent run diverges, measured on its trace (see :func:`diagnose`).

    Parameters
    ----------
    family, seed, law : str, int, str
        The case and the reading of ẋ.
    log_growth_jumps : float
        Σ log V(t⁺)/V(t⁻) over the switches, ``V = xᵀ P^s_σ x`` with the P^s_i of (T1-1).
    log_growth_flows : float
        Σ log of V's change over the steps without a switch.
    frac_up : float
        Share of the switches at which V increases.
    chatter : float
        Share of the samples that lie in one-sample dwells (σ alternating at the sampling rate).
    average_abscissa : float
        Largest real part of the eigenvalues of ½(A_0 + A_1), the dynamics of a run that
        alternates at every sample.
    cause : str
        One of :data:`CAUSES`.
    """

    family: str
    seed: int
    law: str
    log_growth_jumps: float
    log_growth_flows: float
    frac_up: float
    chatter: float
    average_abscissa: float
    cause: str


def diagnose(case: SearchCase, outcome: CaseOutcome) -> Diagnosis:
    """Re-run a divergent case with full traces and split the growth of V into jumps and flows.

    Parameters
    ----------
    case : SearchCase
        A feasible case (it supplies the P^s_i of (T1-1)).
    outcome : CaseOutcome
        Its outcome under one law (supplies the law, the grid and the worst initial state).

    Returns
    -------
    Diagnosis

    Notes
    -----
    ``log V(T)/V(0) = log_growth_jumps + log_growth_flows`` exactly on the samples. The cause is
    "chattering" if more than half the samples lie in one-sample dwells, else "V jumps up at
    switches" if the jumps grow V and the flows do not, else "V grows during flows" (a mode run
    where (T1-1) gives no decrease), else "other".
    """
    dt, T = outcome.dt / REFINE, outcome.horizon
    for _ in range(8):  # shorten until the trace stays finite
        try:
            with warnings.catch_warnings():
                # the run diagnosed is one the search found divergent: the monitor's warning
                # says what is already known
                warnings.simplefilter("ignore", UnstableRunWarning)
                sim = simulate(case.modes, _ZERO, time_grid(T, dt), x0=outcome.worst_x0,
                               law_bands=case.bands, law_Q=case.Q, law=outcome.law)
            break
        except UnstableError:
            T = dt * max(2, round(T / dt / 4))
    else:
        raise UnstableError(f"diagnose: case {case.family}/{case.seed} overflows within {T:g} s")
    # keep the trace up to a growth of 1e12, where V is still far from overflow
    nrm = np.linalg.norm(sim.x, axis=1) / np.linalg.norm(outcome.worst_x0)
    stop = int(np.argmax(nrm > GROWTH_LIMIT)) if np.any(nrm > GROWTH_LIMIT) else nrm.size
    sim = type(sim)(*(getattr(sim, f)[:max(stop, 2)] for f in ("t", "x", "xdot", "z", "d", "sigma")))
    Ps = np.array(case.Ps)
    s = sim.sigma
    x = sim.x
    V_prev = np.einsum("ki,kij,kj->k", x[1:], Ps[s[:-1]], x[1:])   # V of the old mode at t_{k+1}
    V_new = np.einsum("ki,kij,kj->k", x[1:], Ps[s[1:]], x[1:])
    V_start = np.einsum("ki,kij,kj->k", x[:-1], Ps[s[:-1]], x[:-1])
    flows = np.log(V_prev / V_start)
    jumps = np.log(V_new / V_prev)
    sw = s[1:] != s[:-1]
    edges = np.concatenate([[0], np.flatnonzero(sw) + 1, [s.size]])
    dwell = np.repeat(np.diff(edges), np.diff(edges))
    chatter = float(np.mean(dwell <= 1))
    lj, lf = float(jumps[sw].sum()), float(flows.sum())
    avg = 0.5 * (case.modes[0].A + case.modes[1].A)
    if chatter > 0.5:
        cause = CAUSES[0]
    elif lj > 0 >= lf:
        cause = CAUSES[1]
    elif lf > 0:
        cause = CAUSES[2]
    else:
        cause = CAUSES[3]
    return Diagnosis(case.family, case.seed, outcome.law, lj, lf,
                     float(np.mean(jumps[sw] > 0)) if sw.any() else 0.0, chatter,
                     float(np.linalg.eigvals(avg).real.max()), cause)
