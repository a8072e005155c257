"""Chapter 'theorem1_counterexamples': Theorem 1 put to the test.

(a) A seeded search for mode pairs and Q's for which Theorem 1's LMIs (paper eqs. (33), (34))
are feasible but the autonomous switched loop (d = 0) under the printed law (paper eq. (31))
does not converge, with the cause of each failure measured. (b) The gap-closing certificates of
:mod:`fdsc.lyapunov_jumps` on the paper's example and on the search's cases. (c) The residues
ε_T and ε_∞ of statements (2) and (3) (paper eqs. (35), (36)) measured on FDSC runs from the
jumps of ``xᵀ P_σ x``, and β weighted by time against β weighted by disturbance energy.

Every case of the search is a pure function of ``(family, seed)`` (:func:`search_case`), so a
divergent case is rebuilt from its seed.
"""

import warnings
from dataclasses import dataclass

import numpy as np
from scipy.linalg import solve_continuous_lyapunov

from ..bands import Band
from ..exceptions import InfeasibleError, SolverError, UnstableError, UnstableRunWarning
from ..lyapunov_jumps import certify_switching, certify_switching_gain
from ..plant import LTISystem
from ..random_systems import random_hurwitz, random_spd
from ..signals import Sinusoids
from ..simulate import simulate, time_grid
from ..stream import Case, simulate_batch
from ..switching import DEFAULT_GAMMA_TOL, certify_q, design_q
from .cache import cached
from .data import aircraft, our_q, paper_disturbance, paper_gains, paper_modes
from .prose import count, matrix_text, num, pct
from .results import RecordPart, entry

__all__ = [
    "FAMILIES",
    "CAUSES",
    "SearchCase",
    "search_case",
    "CaseOutcome",
    "Diagnosis",
    "diagnose",
    "SearchResult",
    "counterexample_search",
    "GapClosing",
    "gap_closing",
    "ResidueRun",
    "residues",
    "smallest_case",
    "smallest_table",
    "LMIWitness",
    "lmi_witness",
    "QScaling",
    "q_scaling",
    "CLEAN_LIMIT",
    "Q_SCALING_FACTORS",
    "record_part",
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
#: The horizon in slowest time constants 1/min |Re λ|.
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
    """One case of the search: modes, law ranges, Q's and the Theorem 1 certificate (if any).

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
        γ's of the certificate (NaN unless feasible).
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

        T = :data:`SLOW_CONSTANTS` / min |Re λ| over both modes; dt = :data:`DT_FRACTION` /
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
    """Build one case of the search from its family and seed, and certify it by Theorem 1.

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
    (condition up to 10³, relative scale 10^U(−3, 3)) certified by :func:`fdsc.certify_q`.

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


@dataclass(frozen=True)
class SearchResult:
    """The counterexample search (see :func:`counterexample_search`).

    Parameters
    ----------
    cases : tuple of SearchCase
        Every case tried.
    outcomes : tuple of CaseOutcome
        One per feasible case and law.
    diagnoses : tuple of Diagnosis
        One per divergent outcome.
    """

    cases: tuple
    outcomes: tuple
    diagnoses: tuple

    def counts(self) -> dict:
        """Cases tried, refused (not Hurwitz), solver failures, Theorem 1 feasible, and per law
        the diverging runs and the sampling artefacts (growing on dt only).

        Returns
        -------
        dict
        """
        out = {"tried": len(self.cases),
               "not_hurwitz": sum(c.status == "not Hurwitz" for c in self.cases),
               "solver_failures": sum(c.status == "solver" for c in self.cases),
               "feasible": sum(c.status == "feasible" for c in self.cases)}
        for law in _LAWS:
            oc = [o for o in self.outcomes if o.law == law]
            out[f"diverging_{law}"] = sum(o.diverging for o in oc)
            out[f"sampling_artefacts_{law}"] = sum(o.grew_coarse and not o.diverging for o in oc)
        return out

    def by_family(self) -> list:
        """One row per family: tried, feasible, diverging under each law.

        Returns
        -------
        list of dict
        """
        rows = []
        for fam in FAMILIES:
            cs = [c for c in self.cases if c.family == fam]
            oc = [o for o in self.outcomes if o.family == fam]
            rows.append({"family": fam, "tried": len(cs),
                         "feasible": sum(c.status == "feasible" for c in cs),
                         **{f"diverging ({law})": sum(o.diverging and o.law == law for o in oc)
                            for law in _LAWS},
                         **{f"sampling artefacts ({law})": sum(
                             o.grew_coarse and not o.diverging and o.law == law for o in oc)
                            for law in _LAWS}})
        return rows

    def family_table(self) -> list:
        """:meth:`by_family` as text with reader-facing column names (the readings of ẋ by name).

        Returns
        -------
        list of dict
        """
        names = {f"{kind} ({law})": f"{kind} ({_READING[law]})"
                 for kind in ("diverging", "sampling artefacts") for law in _LAWS}
        return [{names.get(k, k): (v if isinstance(v, str) else count(v)) for k, v in r.items()}
                for r in self.by_family()]

    def diagnosis_table(self) -> list:
        """One row per divergent run, every cell text (:mod:`fdsc.paper.prose`).

        Returns
        -------
        list of dict
            Family, seed, reading of ẋ, the log growth of V over the jumps and over the flows,
            the share of switches at which V increases and of samples in one-sample dwells, the
            spectral abscissa of ½(A₀ + A₁) and the cause.
        """
        return [{"family": d.family, "seed": str(d.seed), "reading of ẋ": _READING[d.law],
                 "log growth, jumps": num(d.log_growth_jumps),
                 "log growth, flows": num(d.log_growth_flows),
                 "switches with V up": pct(d.frac_up), "one-sample dwells": pct(d.chatter, 1),
                 "abscissa of (A₀+A₁)/2": num(d.average_abscissa), "cause": d.cause}
                for d in self.diagnoses]

    def divergent(self) -> list:
        """The divergent outcomes, smallest first (fewest states, then family order, then seed).

        Returns
        -------
        list of CaseOutcome
        """
        order = {f: k for k, f in enumerate(FAMILIES)}
        cases = {(c.family, c.seed): c for c in self.cases}
        return sorted((o for o in self.outcomes if o.diverging),
                      key=lambda o: (cases[o.family, o.seed].n, order[o.family], o.seed, o.law))

    def case(self, family: str, seed: int) -> SearchCase:
        """The case of a family and seed.

        Parameters
        ----------
        family : str
        seed : int

        Returns
        -------
        SearchCase
        """
        for c in self.cases:
            if (c.family, c.seed) == (family, seed):
                return c
        raise KeyError(f"no case {family!r}/{seed}")

    def clean(self, limit: float = CLEAN_LIMIT) -> list:
        """The divergent runs under the printed law (measured ẋ) with at most ``limit`` of their
        samples in one-sample dwells: runs that do not chatter, inside Theorem 1's no-sliding
        assumption.

        Parameters
        ----------
        limit : float
            Largest share of samples in one-sample dwells.

        Returns
        -------
        list of Diagnosis
        """
        return [d for d in self.diagnoses if d.law == "previous" and d.chatter <= limit]

    def dwell_rows(self, limit: float = CLEAN_LIMIT) -> list:
        """One row per divergent run, clean runs under the measured ẋ first: family, seed, reading
        of ẋ (reader-facing), share of samples in one-sample dwells, and whether it is clean.

        Parameters
        ----------
        limit : float
            Largest one-sample-dwell share of a clean run.

        Returns
        -------
        list of dict
            Every cell text (:mod:`fdsc.paper.prose`).
        """
        clean = {(d.family, d.seed) for d in self.clean(limit)}
        rows = [({"family": d.family, "seed": str(d.seed), "reading of ẋ": _READING[d.law],
                  "one-sample dwells": pct(d.chatter, 1),
                  "clean": ("n/a" if d.law != "previous"
                            else "yes" if (d.family, d.seed) in clean else "no (chatters)")},
                 (d.law != "previous", (d.family, d.seed) not in clean, d.chatter, d.seed))
                for d in self.diagnoses]
        return [r for r, _ in sorted(rows, key=lambda rk: rk[1])]

    def prose(self) -> dict:
        """The search's numbers as text for the chapter (:mod:`fdsc.paper.prose`).

        Returns
        -------
        dict of str
            Counts of cases and runs (``tried``, ``feasible``, ``not_hurwitz``,
            ``solver_failures``, ``diverging_measured``, ``diverging_candidate``,
            ``artefacts_measured``, ``artefacts_candidate``), the clean runs (``n_clean``,
            ``clean_limit``, ``clean_max``, ``chatter_min``, ``chatter_max`` over the measured
            runs that are not clean), the divergent runs by family (``div_spiral``, the stretched
            spirals; ``div_other``, the other families), the diagnoses (``n_diag``;
            ``n_flows_down``, runs whose flows decrease V; ``n_avg_unstable``, runs whose average
            dynamics is unstable; ``cause_<reading>_<cause>`` per reading ``measured`` or
            ``candidate`` and cause ``chattering``, ``V``, ``flows``, ``other``), and the grid
            constants.
        """
        cnt = self.counts()
        clean = self.clean()
        dirty = [d.chatter for d in self.diagnoses if d.law == "previous" and d.chatter > CLEAN_LIMIT]
        return {"tried": count(cnt["tried"]), "feasible": count(cnt["feasible"]),
                "not_hurwitz": count(cnt["not_hurwitz"]),
                "solver_failures": count(cnt["solver_failures"]),
                "diverging_measured": count(cnt["diverging_previous"]),
                "diverging_candidate": count(cnt["diverging_candidate"]),
                "artefacts_measured": count(cnt["sampling_artefacts_previous"]),
                "artefacts_candidate": count(cnt["sampling_artefacts_candidate"]),
                "n_clean": count(len(clean)), "clean_limit": pct(CLEAN_LIMIT),
                "clean_max": pct(max((d.chatter for d in clean), default=0.0), 1),
                "n_dirty": count(len(dirty)),
                "chatter_min": pct(min(dirty, default=0.0)), "chatter_max": pct(max(dirty, default=0.0)),
                "n_initial": count(N_INITIAL), "slow": num(SLOW_CONSTANTS, 2),
                "dtf": num(DT_FRACTION, 1), "maxsteps": count(MAX_STEPS), "refine": count(REFINE),
                **self._diagnosis_prose()}

    def _diagnosis_prose(self):
        rows = self.by_family()
        n_div = {r["family"]: sum(r[f"diverging ({law})"] for law in _LAWS) for r in rows}
        cause_key = {"chattering": "chattering", "V jumps up at switches": "V",
                     "V grows during flows": "flows", "other": "other"}
        reading = {"previous": "measured", "candidate": "candidate"}
        return {"div_spiral": count(n_div["spiral-2"]),
                "div_other": count(sum(v for f, v in n_div.items() if f != "spiral-2")),
                "n_diag": count(len(self.diagnoses)),
                "n_flows_down": count(sum(d.log_growth_flows < 0 for d in self.diagnoses)),
                "n_avg_unstable": count(sum(d.average_abscissa >= 0 for d in self.diagnoses)),
                **{f"cause_{reading[law]}_{cause_key[cause]}": count(n)
                   for law, c in self.causes().items() for cause, n in c.items()}}

    def causes(self) -> dict:
        """Number of divergent runs per cause and law.

        Returns
        -------
        dict
        """
        return {law: {cause: sum(d.cause == cause and d.law == law for d in self.diagnoses)
                      for cause in CAUSES} for law in _LAWS}


@cached
def counterexample_search(families: tuple = tuple(FAMILIES.items())) -> SearchResult:
    """The seeded search for Theorem 1 counterexamples.

    Parameters
    ----------
    families : tuple of (str, int)
        ``(family, number of seeds)``; seeds run from 0.

    Returns
    -------
    SearchResult

    Notes
    -----
    Theorem 1 (paper eqs. (33), (34)) with d = 0 claims convergence (statement (1)) under the law
    of paper eq. (31); a run grows if ``‖x(T)‖ > ‖x(0)‖`` and ``‖x(T)‖ > ‖x(T/2)‖`` for one of
    :data:`N_INITIAL` initial states after T = :data:`SLOW_CONSTANTS` slowest time constants, or
    if it overflows; a case is divergent if it grows on the grid dt and on dt / :data:`REFINE`.
    """
    cases = tuple(search_case(fam, s) for fam, count in families for s in range(count))
    outcomes = tuple(_outcomes([c for c in cases if c.status == "feasible"]))
    by_key = {(c.family, c.seed): c for c in cases}
    diagnoses = tuple(diagnose(by_key[o.family, o.seed], o) for o in outcomes if o.diverging)
    return SearchResult(cases, outcomes, diagnoses)


# ---------------------------------------------------------------------------------------------
# (b) the gap-closing certificates
# ---------------------------------------------------------------------------------------------

def _try_certificate(modes, bands, Q, law, condition, gain=False):
    """``{"certified": bool, ...}``: the decay rate (or γ's) if it holds, the reason if not."""
    fn = certify_switching_gain if gain else certify_switching
    try:
        cert = fn(modes, bands, Q, law=law, condition=condition)
    except InfeasibleError as exc:
        return {"certified": False, "why": str(exc.status)}
    except SolverError as exc:
        return {"certified": False, "why": f"solver failure: {exc.status}"}
    out = {"certified": True, "decay": float(cert.decay)}
    if gain:
        out["gammas"] = [float(g) for g in cert.gammas]
    return out


@dataclass(frozen=True)
class GapClosing:
    """The gap-closing certificates on the paper's example and on the search's cases.

    Parameters
    ----------
    paper : dict
        ``{(q_label, law, condition, kind): result}`` for the paper's FDSC, q_label in
        {"paper", "ours"}, kind "stability" (:func:`~fdsc.lyapunov_jumps.certify_switching`) or
        "gain" (:func:`~fdsc.lyapunov_jumps.certify_switching_gain`); a result is
        ``{"certified": bool, "decay" | "why", "gammas"?}``.
    divergent : tuple of (str, int, str, bool)
        ``(family, seed, law, certified)`` for every divergent run of the search (jump
        condition, the run's law); a certified divergent run would contradict the certificate.
    convergent : tuple of (str, int, str, bool)
        The same for the first :data:`N_CONVERGENT_SAMPLE` convergent feasible cases of each
        family: how much of what converges the certificate proves.
    """

    paper: dict
    divergent: tuple
    convergent: tuple

    def summary(self) -> dict:
        """Counts of certified runs among the divergent and the sampled convergent ones.

        Returns
        -------
        dict
        """
        return {"divergent": len(self.divergent),
                "divergent_certified": sum(d[3] for d in self.divergent),
                "convergent_sampled": len(self.convergent),
                "convergent_certified": sum(d[3] for d in self.convergent)}

    def paper_rows(self) -> list:
        """One row per (Q's, reading of ẋ, condition, kind) on the paper's example, every cell
        text with reader-facing names (:mod:`fdsc.paper.prose`).

        Returns
        -------
        list of dict
        """
        qname = {"paper": "printed Q", "ours": "our Q"}
        cname = {"jump": "jump and switch-in", "common": "common P"}
        kname = {"stability": "stability (d = 0)", "gain": "L₂ gain"}
        rows = []
        for (q, law, cond, kind), r in self.paper.items():
            rows.append({"Q's": qname[q], "reading of ẋ": _READING[law], "condition": cname[cond],
                         "kind": kname[kind], "certified": "yes" if r["certified"] else "no",
                         "result": (f"decay {num(r['decay'])} 1/s" if kind == "stability" else
                                    "γ = " + ", ".join(num(g) for g in r["gammas"]))
                         if r["certified"] else "no certificate"})
        return rows


#: Convergent feasible cases per family on which the gap-closing certificate is tried.
N_CONVERGENT_SAMPLE = 5


@cached
def gap_closing() -> GapClosing:
    """The gap-closing certificates on the paper's example and on the search's cases.

    Returns
    -------
    GapClosing

    Notes
    -----
    The conditions are those of :mod:`fdsc.lyapunov_jumps`: Theorem 1's (T1-1)/(T1-2) (paper
    eqs. (33), (34)) with free multipliers, plus the jump condition on the switching set and the
    flow condition on the switch-in set of the law (paper eq. (31)), or a common P.
    """
    pm = paper_modes()
    paper = {}
    for q_label, Q in (("paper", pm["Q"]), ("ours", our_q().Q)):
        for law in _LAWS:
            for cond in ("jump", "common"):
                for kind in ("stability", "gain"):
                    paper[q_label, law, cond, kind] = _try_certificate(
                        pm["modes"], pm["bands"], Q, law, cond, gain=kind == "gain")
    search = counterexample_search()
    div = tuple((o.family, o.seed, o.law, _try_certificate(
        (c := search.case(o.family, o.seed)).modes, c.bands, c.Q, o.law, "jump")["certified"])
        for o in search.divergent())
    conv = []
    for fam in FAMILIES:
        ok = [o for o in search.outcomes if o.family == fam and not o.grew_coarse
              and o.law == "previous"]
        for o in ok[:N_CONVERGENT_SAMPLE]:
            c = search.case(o.family, o.seed)
            for law in _LAWS:
                conv.append((o.family, o.seed, law,
                             _try_certificate(c.modes, c.bands, c.Q, law, "jump")["certified"]))
    return GapClosing(paper, div, tuple(conv))


# ---------------------------------------------------------------------------------------------
# (c) the residues ε_T and ε_∞ and the two β's
# ---------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class ResidueRun:
    """The terms of the proof of statements (2) and (3) measured on one FDSC run from rest.

    All energies are left Riemann sums on the samples (sample k carries mode σ_k on
    ``[t_k, t_{k+1})``) and are divided by ``E_d = ∫ dᵀd``.

    Parameters
    ----------
    q_label : {"paper", "ours"}
        Whose Q's the law uses (and whose (T1-2) certificate supplies P_i, γ_i).
    disturbance : {"LF", "HF"}
        The paper's disturbance (paper eqs. (56), (57)).
    horizon, dt, window : float
        Run length, step and window of statement (2) (s).
    ratio : float
        ``∫zᵀz / ∫dᵀd`` over the run.
    gammas : (2,) ndarray
        γ_i of (T1-2) for these Q's.
    beta_time, beta_energy : (2,) ndarray
        Share of the time, and of ``∫dᵀd``, spent in each mode.
    jumps : float
        J / E_d: the jumps of ``xᵀ P_σ x`` at the switches, summed.
    jumps_up : float
        The upward jumps only, summed, / E_d.
    boundary : float
        −ΔV / E_d with ΔV = V at the end − V at the start.
    law_term : float
        −∫(s_σ − s_other) / E_d (the law's own term of the proof; ≤ 0 where the active mode
        scores best).
    switches : int
        Number of switches.
    window_excess : float
        Largest excess of a window's ratio over ``max γ_i²`` (statement (2) without ε_T).
    window_eps : float
        Largest ε_T of the proof over the same windows.
    """

    q_label: str
    disturbance: str
    horizon: float
    dt: float
    window: float
    ratio: float
    gammas: np.ndarray
    beta_time: np.ndarray
    beta_energy: np.ndarray
    jumps: float
    jumps_up: float
    boundary: float
    law_term: float
    switches: int
    window_excess: float
    window_eps: float

    @property
    def eps(self) -> float:
        """ε of the proof, ``max(0, J − ΔV − ∫Δs) / E_d`` (ε_T over the run, ε_∞ as T grows)."""
        return max(0.0, self.jumps + self.boundary + self.law_term)

    @property
    def bound_max(self) -> float:
        """max γ_i² (statement (2))."""
        return float(np.max(self.gammas**2))

    @property
    def bound_time(self) -> float:
        """Σ β_i γ_i² with β by time (statement (3) as printed)."""
        return float(self.beta_time @ self.gammas**2)

    @property
    def bound_energy(self) -> float:
        """Σ β_i γ_i² with β by disturbance energy (what the proof integrates)."""
        return float(self.beta_energy @ self.gammas**2)

    def row(self) -> dict:
        """The run as a table row.

        Returns
        -------
        dict
        """
        return {"Q's": self.q_label, "d": self.disturbance, "switches": self.switches,
                "ratio": self.ratio, "max γ²": self.bound_max, "Σβγ² (time)": self.bound_time,
                "Σβγ² (energy)": self.bound_energy, "J/E_d": self.jumps,
                "−ΔV/E_d": self.boundary, "−∫Δs/E_d": self.law_term, "ε (proof)": self.eps,
                "ratio − Σβγ² (energy)": self.ratio - self.bound_energy}


    def table_row(self) -> dict:
        """:meth:`row` as text (:mod:`fdsc.paper.prose`), the Q's by their reader-facing name.

        Returns
        -------
        dict
        """
        q = {"paper": "printed Q", "ours": "our Q"}[self.q_label]
        return {k: (q if k == "Q's" else v if isinstance(v, str) else
                    count(v) if isinstance(v, int) else num(float(v)))
                for k, v in self.row().items()}

    def prose(self) -> dict:
        """The numbers the chapter quotes of this run, as text (:mod:`fdsc.paper.prose`).

        Returns
        -------
        dict of str
            ``T`` and ``window`` (s), ``ratio``, ``eps``, ``bound_time`` and ``bound_energy``
            (Σβγ² by time and by energy), ``beta_t`` and ``beta_e`` (mode 1's share of the time
            and of the disturbance energy).
        """
        return {"T": num(self.horizon), "window": num(self.window), "ratio": num(self.ratio),
                "eps": num(self.eps), "bound_time": num(self.bound_time),
                "bound_energy": num(self.bound_energy), "beta_t": pct(float(self.beta_time[0]), 1),
                "beta_e": pct(float(self.beta_energy[0]), 2)}


def _residue_run(q_label, kind, horizon, dt, window):
    pm = paper_modes()
    cert = our_q() if q_label == "ours" else certify_q(pm["modes"], pm["bands"], pm["Q"])
    sim = simulate(pm["modes"], paper_disturbance(kind), time_grid(horizon, dt),
                   law_bands=pm["bands"], law_Q=cert.Q)
    P = np.array(cert.P)
    g2 = np.asarray(cert.gammas) ** 2
    s, x, d = sim.sigma[:-1], sim.x, sim.d[:-1]
    ed = d**2 * dt
    ez = np.sum(sim.z[:-1] ** 2, axis=1) * dt
    v_start = np.einsum("ki,kij,kj->k", x[:-1], P[s], x[:-1])
    v_end = np.einsum("ki,kij,kj->k", x[1:], P[s], x[1:])
    jump = np.concatenate([[0.0], v_start[1:] - v_end[:-1]])
    v = np.hstack([sim.xdot, sim.x])[:-1]
    W = [np.kron(b.psi.real, q) for b, q in zip(pm["bands"], cert.Q, strict=True)]
    score = np.array([np.einsum("kr,rc,kc->k", v, w, v) for w in W])
    k = np.arange(s.size)
    law = (score[s, k] - score[1 - s, k]) * dt
    Ed = ed.sum()
    beta_t = np.array([np.mean(s == i) for i in range(2)])
    beta_e = np.array([ed[s == i].sum() for i in range(2)]) / Ed
    # windows of statement (2): consecutive, of `window` seconds
    n = round(window / dt)
    w_exc, w_eps = -np.inf, 0.0
    for k0 in range(0, s.size - n + 1, n):
        sl = slice(k0, k0 + n)
        e = ed[sl].sum()
        w_exc = max(w_exc, ez[sl].sum() / e - g2.max())
        w_eps = max(w_eps, (jump[k0 + 1:k0 + n].sum() - (v_end[k0 + n - 1] - v_start[k0])
                            - law[sl].sum()) / e)
    return ResidueRun(q_label, kind, float(horizon), float(dt), float(window), float(ez.sum() / Ed),
                      np.sqrt(g2), beta_t, beta_e, float(jump.sum() / Ed),
                      float(jump[jump > 0].sum() / Ed), float(-(v_end[-1] - v_start[0]) / Ed),
                      float(-law.sum() / Ed), int(np.count_nonzero(np.diff(sim.sigma))),
                      float(w_exc), float(w_eps))


@cached
def residues(*, horizon: float = 50.0, dt: float = 1e-3, window: float = 10.0) -> tuple:
    """ε_T, ε_∞ and the two β's on FDSC runs from rest (paper's modes and law, both Q's).

    Parameters
    ----------
    horizon, dt, window : float, optional
        Run length, step and the window of statement (2) in s.

    Returns
    -------
    tuple of ResidueRun
        Paper's and our Q's under the LF and the HF disturbance.

    Notes
    -----
    Integrating (T1-2) (paper eq. (34)) along a run, with the jumps of ``xᵀ P_σ x`` written out,
    gives ``ratio ≤ Σ_i β^E_i γ_i² + (J − ΔV − ∫Δs)/E_d`` with β^E_i the share of the
    disturbance energy in mode i; the paper's ε_T and ε_∞ (paper eqs. (35), (36)) are this
    residue with the jumps hidden in ``x*P_i x|``.
    """
    return tuple(_residue_run(q, kind, horizon, dt, window) for q in ("paper", "ours")
                 for kind in ("LF", "HF"))


# ---------------------------------------------------------------------------------------------
# the record
# ---------------------------------------------------------------------------------------------

def _matrix(a):
    # 7 significant digits: the designed Q's can sit at the LMI margin (~1e-8)
    return [[float(f"{v:.7g}") for v in row] for row in np.atleast_2d(np.asarray(a, dtype=float))]


def smallest_case(search: SearchResult) -> dict:
    """The smallest divergent case written out (matrices to 7 significant digits).

    Parameters
    ----------
    search : SearchResult

    Returns
    -------
    dict
        Family, seed, law, A_0, A_1, B, C, the LF and HF edges, Q_0, Q_1, the γ's, the initial
        state, the final ratio and the eigenvalues of both modes (empty dict if none diverges).
    """
    div = search.divergent()
    if not div:
        return {}
    o = div[0]
    c = search.case(o.family, o.seed)
    return {"family": o.family, "seed": o.seed, "law": o.law, "A_0": _matrix(c.modes[0].A),
            "A_1": _matrix(c.modes[1].A), "B": _matrix(c.modes[0].B), "C": _matrix(c.modes[0].C),
            "w_l": float(c.bands[0].upper), "w_h": float(c.bands[1].lower),
            "Q_0": _matrix(c.Q[0]), "Q_1": _matrix(c.Q[1]), "q_source": c.q_source,
            "gammas": [float(g) for g in c.gammas], "x0": _matrix(o.worst_x0),
            "final_ratio": o.final_ratio, "horizon": o.horizon, "dt": o.dt,
            "eig_A_0": [str(np.round(e, 4)) for e in np.linalg.eigvals(c.modes[0].A)],
            "eig_A_1": [str(np.round(e, 4)) for e in np.linalg.eigvals(c.modes[1].A)]}


def _eigenvalues_text(a):
    def one(e):
        if abs(e.imag) < 1e-12 * max(abs(e.real), 1.0):
            return num(float(e.real), 4)
        return f"{num(float(e.real), 4)} {'+' if e.imag > 0 else '−'} {num(abs(float(e.imag)), 4)}i"
    ev = np.linalg.eigvals(np.asarray(a, dtype=float))
    return ", ".join(one(e) for e in ev[np.lexsort((ev.imag, ev.real))])


def smallest_table(search: SearchResult) -> list:
    """The smallest divergent case (:func:`smallest_case`) as a table, every cell text
    (matrices through :func:`fdsc.paper.prose.matrix_text`).

    Parameters
    ----------
    search : SearchResult

    Returns
    -------
    list of dict
        ``quantity``, ``value``; empty if no case diverges.
    """
    small = smallest_case(search)
    if not small:
        return []
    names = {"A_0": "A₀", "A_1": "A₁", "B": "B", "C": "C", "Q_0": "Q₀", "Q_1": "Q₁", "x0": "initial state"}
    rows = [{"quantity": v, "value": matrix_text(small[k])} for k, v in names.items()]
    rows += [{"quantity": f"eigenvalues of {names[k]}", "value": _eigenvalues_text(small[k])}
             for k in ("A_0", "A_1")]
    rows.append({"quantity": "Q's from",
                 "value": {"design": "paper Remark 4", "random": "random, certified"}[small["q_source"]]})
    return rows


@dataclass(frozen=True)
class QScaling:
    """The printed law's switching signal with the Q's scaled by a common factor (see :func:`q_scaling`).

    Parameters
    ----------
    factor : float
        c > 0 multiplying both Q's.
    n_samples : int
        Samples of the run.
    n_switches : int
        Switches of the run with the original Q's.
    mismatches : int
        Samples at which the scaled run's mode differs from the original's.
    max_state_difference : float
        max_k ‖x_scaled(t_k) − x(t_k)‖ / ‖x(0)‖.
    """

    factor: float
    n_samples: int
    n_switches: int
    mismatches: int
    max_state_difference: float


def q_scaling(case: SearchCase, outcome: CaseOutcome, factor: float, *,
              horizon: float | None = None) -> QScaling:
    """Re-run a case with both Q's multiplied by ``factor`` and compare the switching signals.

    Every score s_k = [ẋ; x]*(Ψ_k⊗Q_k)[ẋ; x] is linear in Q_k, so a common factor c > 0 scales
    every score by c and leaves the argmax, hence the law, unchanged: Q's at the solver's
    margin are not an artefact of their size. (A power of two scales exactly in floating point.)

    Parameters
    ----------
    case : SearchCase
        A feasible case.
    outcome : CaseOutcome
        Its outcome (law, grid, worst initial state); run on the grid ``outcome.dt / REFINE``.
    factor : float
        c > 0.
    horizon : float, optional
        Horizon in s (default: the outcome's).

    Returns
    -------
    QScaling
    """
    if not factor > 0:
        raise ValueError(f"factor must be positive, but found {factor!r}")
    grid = time_grid(outcome.horizon if horizon is None else horizon, outcome.dt / REFINE)
    runs = [simulate(case.modes, _ZERO, grid, x0=outcome.worst_x0, law_bands=case.bands,
                     law_Q=[c * np.asarray(q) for q in case.Q], law=outcome.law)
            for c in (1.0, factor)]
    a, b = runs
    n0 = np.linalg.norm(outcome.worst_x0)
    return QScaling(float(factor), int(a.sigma.size), int(np.count_nonzero(np.diff(a.sigma))),
                    int(np.count_nonzero(a.sigma != b.sigma)),
                    float(np.max(np.linalg.norm(a.x - b.x, axis=1)) / n0))


@dataclass(frozen=True)
class LMIWitness:
    """A point that makes Theorem 1's LMIs (T1-1) and (T1-2) hold, built without a solver.

    Parameters
    ----------
    t_s : (2,) ndarray
        P^s_i = t_s[i]·L_i, where A_iᵀL_i + L_iA_i = −I.
    t : (2,) ndarray
        P_i = t[i]·L_i in (T1-2).
    gammas : (2,) ndarray
        γ_i of (T1-2).
    max_eig_1, max_eig_2 : (2,) ndarray
        Largest eigenvalue of the left-hand side of (T1-1) and of (T1-2) at this point, per mode.
    """

    t_s: np.ndarray
    t: np.ndarray
    gammas: np.ndarray
    max_eig_1: np.ndarray
    max_eig_2: np.ndarray

    def holds(self) -> bool:
        """True if both LMIs hold strictly for both modes (all largest eigenvalues < 0)."""
        return bool(np.all(self.max_eig_1 < 0) and np.all(self.max_eig_2 < 0))

    def prose(self) -> dict:
        """The point as text (:mod:`fdsc.paper.prose`), both modes joined by "and".

        Returns
        -------
        dict of str
            ``t`` (the t_s of P^s_i), ``g`` (γ_i), ``e1`` and ``e2`` (largest eigenvalues of
            (T1-1) and (T1-2)), and mode 0's alone: ``t_0``, ``e1_0``.
        """
        def both(v):
            return " and ".join(num(float(x)) for x in v)

        return {"t": both(self.t_s), "g": both(self.gammas), "e1": both(self.max_eig_1),
                "e2": both(self.max_eig_2), "t_0": num(float(self.t_s[0])),
                "e1_0": num(float(self.max_eig_1[0]))}


_PHI = np.array([[0.0, 1.0], [1.0, 0.0]])


def _hermitian_max(m):
    return float(np.linalg.eigvalsh(0.5 * (m + m.conj().T)).max())


def lmi_witness(modes, bands, Q) -> LMIWitness:
    """Make Theorem 1's LMIs (paper eqs. (33), (34)) hold for any two Hurwitz modes and any Q's.

    With L_i the solution of A_iᵀL_i + L_iA_i = −I (positive definite since A_i is Hurwitz), the
    choice P^s_i = t·L_i turns (T1-1) into −tI + M_i with the fixed
    M_i = [A_i; I]*(Ψ_i⊗Q_i − Ψ_j⊗Q_j)[A_i; I], negative definite for t > λ_max(M_i); here
    t_s = 2·max(λ_max(M_i), 0) + 1. In (T1-2), P_i = t·L_i makes the left-hand side

        [[−tI + W₁₁, tL_iB_i + W₁₂], [(…)*, W₂₂ − γ_i²I]],

    with W = [A_i B_i; I 0]*(Ψ_i⊗Q_i − Ψ_j⊗Q_j)[A_i B_i; I 0] + [C_i D_i]*[C_i D_i] fixed. With
    a = max(λ_max(W₁₁), 0), t = 2a + 1, b = ‖L_iB_i‖, e = ‖W₁₂‖ and
    γ_i² = max(λ_max(W₂₂), 0) + r, r = 2(tb + e)²/t + 1, the lower-right block is ⪯ −rI and the
    Schur complement is ⪯ (−(t − a) + (tb + e)²/r)·I; since t − a ≥ t/2 + 1/2 and
    (tb + e)²/r < t/2, it is ≺ −½I. Both LMIs therefore hold for every Hurwitz pair and every Q;
    the returned point is checked by eigenvalues, not assumed.

    Parameters
    ----------
    modes : sequence of two LTISystem
        Hurwitz closed loops (A_i, B_i, C_i, D_i).
    bands : sequence of two Band
        The law's ranges (their Ψ's).
    Q : sequence of two (n, n) array_like
        The Q's (any; Theorem 1 asks them positive definite).

    Returns
    -------
    LMIWitness

    Raises
    ------
    ValueError
        If a mode is not Hurwitz.

    Examples
    --------
    >>> from fdsc.plant import LTISystem
    >>> m = [LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]]),
    ...      LTISystem([[-2.0]], [[1.0]], [[1.0]], [[0.0]])]
    >>> w = lmi_witness(m, [Band.lf(1.0), Band.hf(10.0)], [[[1.0]], [[1.0]]])
    >>> w.holds(), float(w.t_s[0]), float(w.max_eig_1[0])
    (True, 199.0, -100.0)
    """
    out = {"t_s": [], "t": [], "gammas": [], "max_eig_1": [], "max_eig_2": []}
    for i, j in ((0, 1), (1, 0)):
        A = np.asarray(modes[i].A, dtype=float)
        B = np.asarray(modes[i].B, dtype=float)
        C = np.asarray(modes[i].C, dtype=float)
        D = np.asarray(modes[i].D, dtype=float)
        if np.linalg.eigvals(A).real.max() >= 0:
            raise ValueError(f"mode {i} must be Hurwitz")
        n, m = A.shape[0], B.shape[1]
        S = (np.kron(bands[i].psi, np.asarray(Q[i], dtype=float))
             - np.kron(bands[j].psi, np.asarray(Q[j], dtype=float)))
        L = solve_continuous_lyapunov(A.T, -np.eye(n))
        L = 0.5 * (L + L.T)
        F1 = np.vstack([A, np.eye(n)])
        M = F1.conj().T @ S @ F1
        t_s = 2.0 * max(_hermitian_max(M), 0.0) + 1.0
        lhs1 = F1.T @ np.kron(_PHI, t_s * L) @ F1 + M
        F2 = np.block([[A, B], [np.eye(n), np.zeros((n, m))]])
        CD = np.hstack([C, D])
        W = (F2.conj().T @ S @ F2 + CD.T @ CD).astype(complex)
        a = max(_hermitian_max(W[:n, :n]), 0.0)
        t = 2.0 * a + 1.0
        r = 2.0 * (t * np.linalg.norm(L @ B, 2) + np.linalg.norm(W[:n, n:], 2)) ** 2 / t + 1.0
        g2 = max(_hermitian_max(W[n:, n:]), 0.0) + r
        lhs2 = F2.T @ np.kron(_PHI, t * L) @ F2 + W
        lhs2[n:, n:] -= g2 * np.eye(m)
        for k, v in zip(out, (t_s, t, np.sqrt(g2), _hermitian_max(lhs1), _hermitian_max(lhs2)),
                        strict=True):
            out[k].append(float(v))
    return LMIWitness(**{k: np.array(v) for k, v in out.items()})


def record_part() -> RecordPart:
    """Record entry ``theorem1_counterexamples`` (new).

    Returns
    -------
    RecordPart
    """
    search = counterexample_search()
    gap = gap_closing()
    res = residues()
    rec = {"counts": search.counts(), "by_family": search.by_family(),
           "smallest": smallest_case(search), "causes": search.causes(),
           "divergent_seeds": [[o.family, o.seed, o.law] for o in search.divergent()],
           "gap_closing": {"paper_example": {" / ".join(k): v for k, v in gap.paper.items()},
                           **gap.summary()},
           "residues": [{k: (float(v) if isinstance(v, float | np.floating) else v)
                         for k, v in r.row().items()}
                        | {"beta_time": r.beta_time.tolist(), "beta_energy": r.beta_energy.tolist(),
                           "window_excess": r.window_excess, "window_eps": r.window_eps}
                        for r in res]}
    o = search.divergent()[0]
    small = search.case(o.family, o.seed)
    wit = lmi_witness(small.modes, small.bands, small.Q)
    rec["clean"] = {"limit": CLEAN_LIMIT, "n_clean": len(search.clean()),
                    "n_diverging_measured": search.counts()["diverging_previous"],
                    "runs": [{"family": d.family, "seed": d.seed, "law": d.law,
                              "one_sample_dwells": d.chatter} for d in search.diagnoses]}
    rec["lmi_witness_smallest"] = {k: getattr(wit, k).tolist() for k in
                                   ("t_s", "t", "gammas", "max_eig_1", "max_eig_2")}
    rec["q_scaling_smallest"] = [dict(vars(q)) for q in
                                 (q_scaling(small, o, c) for c in Q_SCALING_FACTORS)]
    cnt = search.counts()
    gs = gap.summary()
    return RecordPart((entry(
        "theorem1_counterexamples", "Theorem 1, statements (1)-(3), paper eqs. (33)-(37)", None,
        rec, "new",
        "Theorem 1's LMIs hold for every pair of Hurwitz modes and every Q (P = t L with "
        "A'L + LA = -I, t and gamma large; checked by eigenvalues on the smallest case). "
        f"Seeded search with d = 0: {cnt['tried']} cases, {cnt['feasible']} with Theorem 1 "
        f"feasible (Hurwitz modes only), {cnt['diverging_previous']} diverging under the printed "
        f"law (measured xdot), {len(search.clean())} of them clean (at most "
        f"{CLEAN_LIMIT:.0%} of the samples in one-sample dwells), and "
        f"{cnt['diverging_candidate']} under the candidate xdot (each confirmed on a {REFINE}x "
        f"finer grid); scaling both Q's of the smallest case by {Q_SCALING_FACTORS} changes the "
        f"switching signal at {max(q['mismatches'] for q in rec['q_scaling_smallest'])} samples. Every "
        "divergent case is rebuilt from its family and seed. The gap-closing certificate (jumps of "
        "V, the law's switch-in "
        f"set) certifies {gs['divergent_certified']} of the {gs['divergent']} divergent runs and "
        f"{gs['convergent_certified']} of {gs['convergent_sampled']} sampled convergent ones; "
        "epsilon_T, epsilon_inf measured from the jumps of x'P_sigma x."),))
