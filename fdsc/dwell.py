"""A certified dwell-time bound for switched linear systems, and the periodic-switching margin.

For Hurwitz modes A_1, …, A_I (I ≥ 2) and a decay rate λ > 0, mode-wise Lyapunov matrices
P_i ≻ 0 with

    A_iᵀ P_i + P_i A_i ⪯ −2λ P_i                                  (decay)
    P_j ⪯ μ P_i   for every i ≠ j                                  (jump)

make V_i(x) = xᵀ P_i x decay like e^{−2λt} along mode i, and V_j ≤ μ V_i at a switch from i to j.
Along any switching signal with N(t) switches in (0, t] therefore

    V_σ(t)(x(t)) ≤ μ^{N(t)} e^{−2λt} V_σ(0)(x(0)),

and if consecutive switches are at least τ_d > τ* = ln μ / (2λ) apart, the switched system with
d = 0 is globally exponentially stable (the classical dwell-time theorem, Liberzon 2003, Ch. 3;
Hespanha & Morse 1999 for the average dwell time). μ is the tight generalized-eigenvalue form
μ = max_{i≠j} λ_max(P_i^{−1/2} P_j P_i^{−1/2}); the cruder form max_i λ_max(P_i) / min_j λ_min(P_j)
is reported beside it.

For fixed λ the smallest μ is a generalized-eigenvalue problem (quasi-convex): it is found by
bisection on ln μ over LMI feasibility problems, started from the convex crude problem
(I ⪯ P_i ⪯ κI), which also yields the crude μ. τ* is then minimized over a grid of
λ ∈ (0, min_i λ_i^max), λ_i^max = −max Re eig(A_i). Every certificate is verified after the solve
by the eigenvalues of the decay matrices, and μ is recomputed from the P_i found, so the
reported (λ, μ, τ*) is a property of the returned P_i, not of the solver's tolerances.

:func:`periodic_dwell_margin` gives the other side: a periodic switching signal whose
monodromy matrix has spectral radius > 1 diverges, so the longest such dwell is a lower bound on
any valid dwell-time bound. :func:`switched_states`, :func:`random_dwell_signal` and
:func:`check_dwell_bound` realise given switching signals exactly (d = 0, matrix exponentials)
and test the bound on them.
"""

from __future__ import annotations

from dataclasses import dataclass

import cvxpy as cp
import numpy as np
from scipy.linalg import eigh, expm

from ._validation import (
    as_count,
    as_matrix,
    as_nonnegative,
    as_positive,
    as_vector,
    check_hurwitz,
    check_type,
    frozen_array,
)
from .exceptions import InfeasibleError, IterationLimitError, SolverError, VerificationError
from .lmi import DEFAULT_MARGIN, _sym, solve_checked
from .plant import LTISystem

__all__ = [
    "DwellTimeBound",
    "dwell_time_bound",
    "PeriodicDwellMargin",
    "periodic_dwell_margin",
    "LyapunovDwell",
    "lyapunov_dwell",
    "DwellCheck",
    "switched_states",
    "random_dwell_signal",
    "check_dwell_bound",
    "DEFAULT_N_DECAYS",
    "DEFAULT_TAU_RTOL",
    "DEFAULT_MAX_BISECTIONS",
]

#: Points of the coarse λ grid (the refinement around its best point has as many again).
DEFAULT_N_DECAYS = 16
#: Relative tolerance on ln μ (hence on τ* at fixed λ) at which the bisection stops.
DEFAULT_TAU_RTOL = 1e-3
#: Absolute tolerance on ln μ (stops the bisection when μ is 1 up to the margin).
_LOG_MU_ATOL = 1e-9
#: Iteration cap of the bisection on ln μ (the initial bracket is at most a few dozen wide).
DEFAULT_MAX_BISECTIONS = 60


def _mode_matrices(modes):
    if isinstance(modes, np.ndarray) and modes.ndim == 3:
        modes = list(modes)
    if not isinstance(modes, list | tuple):
        raise TypeError(f"modes must be a list of square matrices or LTISystem's, but found "
                        f"{type(modes).__name__}")
    if len(modes) < 2:
        raise ValueError(f"modes must hold at least two modes, found {len(modes)}")
    A = [m.A if isinstance(m, LTISystem) else as_matrix(f"modes[{k}]", m, square=True)
         for k, m in enumerate(modes)]
    n = A[0].shape[0]
    for k, a in enumerate(A):
        if a.shape != (n, n):
            raise ValueError(f"modes must share the state dimension: modes[0] is {(n, n)}, "
                             f"modes[{k}] is {a.shape}")
        check_hurwitz(f"modes[{k}]", a, "a dwell-time bound")
    return A


def _decay_limits(A):
    return np.array([-float(np.linalg.eigvals(a).real.max()) for a in A])


def _mu_tight(P):
    """max over i ≠ j of λ_max(P_i^{-1/2} P_j P_i^{-1/2}) (generalized eigenvalues of (P_j, P_i))."""
    return max(float(eigh(P[j], P[i], eigvals_only=True).max())
               for i in range(len(P)) for j in range(len(P)) if i != j)


def _mu_crude(P):
    return max(float(np.linalg.eigvalsh(p).max()) for p in P) / min(
        float(np.linalg.eigvalsh(p).min()) for p in P)


def _decay_eigs(A, P, decay):
    """Largest eigenvalue of A_iᵀP_i + P_iA_i + 2λP_i, one per mode (negative at a certificate)."""
    return np.array([float(np.linalg.eigvalsh(_sym(a.T @ p + p @ a + 2 * decay * p)).max())
                     for a, p in zip(A, P, strict=True)])


def _verify(A, P, decay, status, what):
    eigs = _decay_eigs(A, P, decay)
    pmin = np.array([float(np.linalg.eigvalsh(p).min()) for p in P])
    if not (np.all(eigs < 0) and np.all(pmin > 0)):
        raise VerificationError(f"{what}: the certificate fails its check (largest eigenvalues of "
                                f"A_i'P_i + P_iA_i + 2*decay*P_i: {eigs}, smallest of P_i: {pmin})",
                                status)
    return eigs, pmin


#: Multipliers of the margin tried when a solve returns a point that fails its eigenvalue check
#: (an 'optimal_inaccurate' point near the boundary, e.g. for λ close to the slowest mode's rate).
MARGIN_RETRIES = (1.0, 1e2, 1e4)


class _Problems:
    """The three parametrized LMI problems (compiled once; λ, μ and the margin are Parameters).

    Every decay constraint is divided by ‖A_i‖₂ so that the solver sees O(1) data whatever the
    time scale of each mode; the LMIs are homogeneous in P, normalized by P_i ⪰ I.
    """

    def __init__(self, A, margin):
        n, I = A[0].shape[0], len(A)  # noqa: E741  (the usual symbol for the number of modes)
        eye = np.eye(n)
        self.margin = margin
        self.lam = cp.Parameter(nonneg=True, name="decay")
        self.mu = cp.Parameter(nonneg=True, name="mu")
        self.eps = cp.Parameter(nonneg=True, name="margin")

        def decay(a, p):
            return _sym(a.T @ p + p @ a + 2 * self.lam * p) / np.linalg.norm(a, 2) << -self.eps * eye

        Pc = cp.Variable((n, n), symmetric=True, name="P_common")
        self.common = cp.Problem(cp.Minimize(0), [Pc >> eye] + [decay(a, Pc) for a in A])
        self.P_common = Pc
        P = [cp.Variable((n, n), symmetric=True, name=f"P_{i}") for i in range(I)]
        kappa = cp.Variable(name="kappa")
        self.crude = cp.Problem(cp.Minimize(kappa), [decay(a, p) for a, p in zip(A, P, strict=True)]
                                + [p >> eye for p in P] + [p << kappa * eye for p in P])
        self.P_crude = P
        Q = [cp.Variable((n, n), symmetric=True, name=f"P_{i}") for i in range(I)]
        cons = [decay(a, q) for a, q in zip(A, Q, strict=True)] + [q >> eye for q in Q]
        cons += [Q[j] << self.mu * Q[i] for i in range(I) for j in range(I) if i != j]
        self.bisect = cp.Problem(cp.Minimize(0), cons)
        self.P_bisect = Q
        self.n_solves = 0
        self.n_failed = 0

    def solve(self, prob, variables, A, decay, what):
        """Solve and verify; an inaccurate point failing its check is solved again, larger margin."""
        for k, factor in enumerate(MARGIN_RETRIES):
            self.eps.value = self.margin * factor
            self.n_solves += 1
            status = solve_checked(prob, what)
            P = [_sym(v.value) for v in variables]
            if len(P) == 1:
                P = P * len(A)
            try:
                _verify(A, P, decay, status, what)
                return P
            except VerificationError:
                if status != cp.OPTIMAL_INACCURATE or k == len(MARGIN_RETRIES) - 1:
                    raise


def _certify_at(probs, A, decay, tau_rtol, max_bisections):
    """(μ, μ_crude, P) at one decay rate: a common P if one exists, else bisection on ln μ.

    Returns ``(inf, inf, None)`` if the crude problem yields no verified certificate (which
    happens only for λ very close to the slowest mode's rate, where the LMIs are ill-posed).
    """
    probs.lam.value = decay
    what = f"dwell-time LMI at decay={decay:.6g}"
    try:
        P = probs.solve(probs.crude, probs.P_crude, A, decay, what + " (crude mu)")
    except SolverError:
        probs.n_failed += 1
        return np.inf, np.inf, None
    mu_crude = _mu_crude(P)
    try:
        return 1.0, mu_crude, probs.solve(probs.common, [probs.P_common], A, decay,
                                          what + " (common P)")
    except SolverError as exc:
        probs.n_failed += not isinstance(exc, InfeasibleError)
    lo, hi = 0.0, np.log(_mu_tight(P))
    for _ in range(max_bisections):
        if hi - lo <= tau_rtol * hi + _LOG_MU_ATOL:
            break
        mid = 0.5 * (lo + hi)
        probs.mu.value = float(np.exp(mid))
        try:
            Pm = probs.solve(probs.bisect, probs.P_bisect, A, decay, what + f" at mu={np.exp(mid):.6g}")
        except SolverError as exc:
            # no verified certificate at this μ (infeasible, failed check, or a solver stop near
            # the boundary of the feasible set): move up. The returned μ always belongs to a
            # verified certificate, so this can only make it larger, never invalid.
            if not isinstance(exc, InfeasibleError):
                probs.n_failed += 1
            lo = mid
            continue
        m = np.log(_mu_tight(Pm))
        if m < hi:
            hi, P = m, Pm
        else:
            # only by rounding (the LMI asks μ ≤ e^mid < e^hi): end the step like an infeasible one
            lo = mid
    else:
        if hi - lo > tau_rtol * hi + _LOG_MU_ATOL:
            raise IterationLimitError(f"{what}: the bisection on ln(mu) did not reach the tolerance "
                                      f"{tau_rtol:g} in {max_bisections} steps (bracket [{lo:.3g}, "
                                      f"{hi:.3g}])")
    return float(np.exp(hi)), mu_crude, P


@dataclass(frozen=True)
class DwellTimeBound:
    """A certified dwell-time bound τ* = ln μ / (2λ) with its Lyapunov matrices.

    Parameters
    ----------
    tau : float
        τ* = ln μ / (2λ) in s: every switching signal whose switches are at least τ_d > τ* apart
        makes the switched system (d = 0) globally exponentially stable.
    decay : float
        λ in 1/s: A_iᵀP_i + P_iA_i ⪯ −2λP_i for every mode (V decays like e^{−2λt}).
    mu : float
        μ = max_{i≠j} λ_max(P_i^{−1/2} P_j P_i^{−1/2}) ≥ 1 of the returned P_i (V_j ≤ μ V_i).
    mu_crude : float
        The crude form max_i λ_max(P_i) / min_j λ_min(P_j), minimized over the P_i at this λ.
    tau_crude : float
        ln(mu_crude) / (2λ) in s.
    P : tuple of (n, n) ndarray
        The Lyapunov matrices P_i (symmetric positive definite), one per mode.
    decay_limits : (I,) ndarray
        λ_i^max = −max Re eig(A_i) of each mode; λ < min_i λ_i^max.
    decays : (k,) ndarray
        The decay rates tried (sorted); one entry if ``decay`` was given.
    mus, mus_crude, taus, taus_crude : (k,) ndarray
        μ, crude μ, τ* and crude τ* at each decay rate tried (inf where no certificate was found,
        which happens only for λ very close to min_i λ_i^max).
    max_eigs : (I,) ndarray
        Largest eigenvalue of A_iᵀP_i + P_iA_i + 2λP_i at the certificate (all < 0).
    min_eig_P : (I,) ndarray
        Smallest eigenvalue of each P_i (all > 0).
    n_solves : int
        Number of LMI solves.
    n_failed : int
        Solves that ended without a verified certificate other than by infeasibility (a solver
        stop or a failed eigenvalue check near the boundary of the feasible set); each counts as
        "not certified" there, which can only make μ larger, never invalid.

    Notes
    -----
    The dwell-time theorem (Liberzon 2003, Ch. 3, stability under slow switching; Hespanha & Morse 1999).
    """

    tau: float
    decay: float
    mu: float
    mu_crude: float
    tau_crude: float
    P: tuple
    decay_limits: np.ndarray
    decays: np.ndarray
    mus: np.ndarray
    mus_crude: np.ndarray
    taus: np.ndarray
    taus_crude: np.ndarray
    max_eigs: np.ndarray
    min_eig_P: np.ndarray
    n_solves: int
    n_failed: int

    def __post_init__(self):
        object.__setattr__(self, "P", tuple(frozen_array(p) for p in self.P))
        for name in ("decay_limits", "decays", "mus", "mus_crude", "taus", "taus_crude",
                     "max_eigs", "min_eig_P"):
            object.__setattr__(self, name, frozen_array(np.asarray(getattr(self, name), dtype=float)))

    def rate(self, dwell: float) -> float:
        """Guaranteed exponential decay rate of V under switches at least ``dwell`` apart.

        Parameters
        ----------
        dwell : float
            The minimum dwell time τ_d in s (> 0).

        Returns
        -------
        float
            2λ − ln μ / τ_d in 1/s (positive exactly when ``dwell`` > τ*): with the first switch
            at least τ_d after 0, V(t) ≤ e^{−(2λ − ln μ/τ_d) t} V(0).

        Raises
        ------
        ValueError
            If ``dwell`` is not positive.
        """
        dwell = as_positive("dwell", dwell)
        return 2 * self.decay - np.log(self.mu) / dwell

    def envelope(self, t: np.ndarray, n_switches: np.ndarray) -> np.ndarray:
        """The bound μ^{N(t)} e^{−2λt} on V(t)/V(0).

        Parameters
        ----------
        t : (k,) array_like
            Times in s (≥ 0).
        n_switches : (k,) array_like
            N(t), the number of switches in (0, t].

        Returns
        -------
        (k,) ndarray
        """
        t = np.asarray(t, dtype=float)
        return np.exp(np.asarray(n_switches, dtype=float) * np.log(self.mu) - 2 * self.decay * t)


def dwell_time_bound(modes, *, decay: float | None = None, n_decays: int = DEFAULT_N_DECAYS,
                     tau_rtol: float = DEFAULT_TAU_RTOL,
                     max_bisections: int = DEFAULT_MAX_BISECTIONS,
                     margin: float = DEFAULT_MARGIN) -> DwellTimeBound:
    """The dwell-time bound τ* = ln μ / (2λ) from mode-wise quadratic Lyapunov functions, by LMIs.

    Parameters
    ----------
    modes : list of (n, n) array_like or LTISystem
        The modes' state matrices A_i (I ≥ 2), or closed loops whose ``A`` is used.
    decay : float, optional
        A fixed decay rate λ in (0, min_i λ_i^max) in 1/s. By default τ* is minimized over
        ``n_decays`` equally spaced λ in that interval and as many again between the neighbours
        of the best one.
    n_decays : int, optional
        Points of the coarse λ grid (≥ 1).
    tau_rtol : float, optional
        Relative tolerance on ln μ at which the bisection stops (in (0, 1)).
    max_bisections : int, optional
        Iteration cap of the bisection.
    margin : float, optional
        Strictness margin of the decay LMIs (each divided by ‖A_i‖₂, with P_i ⪰ I).

    Returns
    -------
    DwellTimeBound

    Raises
    ------
    TypeError
        If ``modes`` is not a list or tuple.
    ValueError
        If fewer than two modes are given, they differ in size, or ``decay``, ``n_decays``,
        ``tau_rtol``, ``max_bisections`` or ``margin`` is out of range.
    DimensionError
        If a mode is not a square matrix.
    UnstableError
        If a mode is not Hurwitz.
    SolverError
        If no decay rate tried yields a verified certificate (at a single given ``decay``: if
        its crude problem, feasible in exact arithmetic for every λ below the limit, fails).
    IterationLimitError
        If the bisection does not converge within ``max_bisections`` steps.

    Notes
    -----
    With P_i ≻ 0, A_iᵀP_i + P_iA_i ⪯ −2λP_i and P_j ⪯ μP_i (i ≠ j), V = xᵀP_σx satisfies
    V(t) ≤ μ^{N(t)} e^{−2λt} V(0) along any switching signal with N(t) switches in (0, t].
    If the switches are at least τ_d apart and the first one is at least τ_d after t = 0,
    N(t) ≤ t/τ_d and V(t) ≤ e^{−(2λ − ln μ/τ_d)t} V(0): global exponential stability for
    τ_d > τ* = ln μ/(2λ) (if the first switch may come earlier, one more factor μ). This is the
    dwell-time theorem (Liberzon 2003, Ch. 3); the same bound on the *average* dwell time
    (N(t) ≤ N_0 + t/τ_a) is Hespanha & Morse 1999.

    With a disturbance, if moreover every mode satisfies the λ-weighted bounded-real inequality
    V̇_i ≤ −2λV_i − zᵀz + γ²dᵀd, then from x(0) = 0 the same argument gives
    ∫ μ^{N(s,t)} e^{−2λ(t−s)} zᵀz ds ≤ γ² ∫ μ^{N(s,t)} e^{−2λ(t−s)} dᵀd ds for all t;
    integrating over t and bounding N(s, t) ≤ 1 + (t − s)/τ_d gives the L2 gain
    ‖z‖² ≤ γ² μ · 2λτ_d / (2λτ_d − ln μ) · ‖d‖² for τ_d > τ* (a weighted version is due to Zhai
    et al. 2001). This function certifies the d = 0 statement only.

    Examples
    --------
    Two modes with the common Lyapunov function P = I (μ = 1, τ* = 0):

    >>> A1 = [[-1.0, 2.0], [-2.0, -1.0]]
    >>> A2 = [[-2.0, 0.0], [0.0, -3.0]]
    >>> b = dwell_time_bound([A1, A2], decay=0.5)
    >>> b.mu, b.tau
    (1.0, 0.0)
    >>> bool(np.all(b.max_eigs < 0))
    True
    """
    A = _mode_matrices(modes)
    limits = _decay_limits(A)
    lam_max = float(limits.min())
    n_decays = as_count("n_decays", n_decays)
    tau_rtol = as_positive("tau_rtol", tau_rtol)
    if tau_rtol >= 1:
        raise ValueError(f"tau_rtol must be in (0, 1), but found {tau_rtol}")
    max_bisections = as_count("max_bisections", max_bisections)
    margin = as_positive("margin", margin)
    if decay is not None:
        decay = as_positive("decay", decay)
        if decay >= lam_max:
            raise ValueError(f"decay must be below the slowest mode's decay rate "
                             f"-max Re eig(A_i) = {lam_max:.6g}, but found {decay:g}")
    probs = _Problems(A, margin)
    found = {}

    def evaluate(lams):
        for lam in lams:
            found[float(lam)] = _certify_at(probs, A, float(lam), tau_rtol, max_bisections)

    def tau_of(lam):
        return np.log(found[lam][0]) / (2 * lam)

    if decay is not None:
        evaluate([decay])
    else:
        coarse = lam_max * np.arange(1, n_decays + 1) / (n_decays + 1)
        evaluate(coarse)
        k = min(range(n_decays), key=lambda q: (tau_of(float(coarse[q])), -coarse[q]))
        if not np.isfinite(tau_of(float(coarse[k]))):
            raise SolverError(f"dwell-time LMIs: no verified certificate at any decay rate of the "
                              f"grid ({coarse})", "no certificate")
        lo = coarse[k - 1] if k > 0 else 0.0
        hi = coarse[k + 1] if k < n_decays - 1 else lam_max
        fine = np.linspace(lo, hi, n_decays + 2)[1:-1]
        evaluate([lam for lam in fine if float(lam) not in found])
    lams = np.array(sorted(found))
    mus = np.array([found[lam][0] for lam in lams])
    mus_crude = np.array([found[lam][1] for lam in lams])
    taus = np.log(mus) / (2 * lams)
    taus_crude = np.log(mus_crude) / (2 * lams)
    if not np.any(np.isfinite(taus)):
        raise SolverError(f"dwell-time LMIs: no verified certificate at any decay rate tried "
                          f"({lams})", "no certificate")
    # smallest τ*; among equal ones (μ = 1) the fastest decay
    best = min(range(lams.size), key=lambda q: (taus[q], -lams[q]))
    lam = float(lams[best])
    mu, mu_crude, P = found[lam]
    max_eigs, pmin = _verify(A, P, lam, "optimal", "dwell-time certificate")
    return DwellTimeBound(float(taus[best]), lam, mu, mu_crude, float(taus_crude[best]), tuple(P),
                          limits, lams, mus, mus_crude, taus, taus_crude, max_eigs, pmin,
                          probs.n_solves, probs.n_failed)


@dataclass(frozen=True)
class LyapunovDwell:
    """What *given* Lyapunov matrices P_i certify: decay rates, μ and the dwell time.

    Parameters
    ----------
    rates : (I,) ndarray
        λ_i = −½ λ_max(P_i^{−1/2}(A_iᵀP_i + P_iA_i)P_i^{−1/2}) in 1/s: V_i decays like
        e^{−2λ_i t} along mode i (negative: V_i can grow).
    decay : float
        λ = min_i λ_i.
    mu : float
        max_{i≠j} λ_max(P_i^{−1/2} P_j P_i^{−1/2}).
    mu_crude : float
        max_i λ_max(P_i) / min_j λ_min(P_j).
    tau : float
        ln μ / (2λ) in s; inf if λ ≤ 0 (the P_i certify no dwell time).
    """

    rates: np.ndarray
    decay: float
    mu: float
    mu_crude: float
    tau: float

    def __post_init__(self):
        object.__setattr__(self, "rates", frozen_array(np.asarray(self.rates, dtype=float)))


def lyapunov_dwell(modes, P) -> LyapunovDwell:
    """The decay rates, μ and dwell time that given matrices P_i ≻ 0 certify (no optimization).

    Parameters
    ----------
    modes : list of (n, n) array_like or LTISystem
        The modes' state matrices A_i (I ≥ 2, Hurwitz).
    P : list of (n, n) array_like
        Symmetric positive definite P_i, one per mode (e.g. the P^s_i of Theorem 1).

    Returns
    -------
    LyapunovDwell

    Raises
    ------
    ValueError
        If ``P`` does not hold one symmetric positive definite matrix per mode.
    DimensionError
        If a P_i is not (n, n).

    Notes
    -----
    The quantities of :func:`dwell_time_bound` evaluated at fixed P_i: the largest λ with
    A_iᵀP_i + P_iA_i ⪯ −2λP_i for all i, and the tight μ.

    Examples
    --------
    >>> r = lyapunov_dwell([[[-1.0]], [[-3.0]]], [[[1.0]], [[2.0]]])
    >>> r.rates.round(12).tolist(), r.mu, round(r.tau, 6)
    ([1.0, 3.0], 2.0, 0.346574)
    """
    A = _mode_matrices(modes)
    n = A[0].shape[0]
    if not isinstance(P, list | tuple) or len(P) != len(A):
        raise ValueError(f"P must list one matrix per mode ({len(A)})")
    P = [as_matrix(f"P[{k}]", p, (n, n)) for k, p in enumerate(P)]
    for k, p in enumerate(P):
        if not np.allclose(p, p.T, rtol=1e-12, atol=0) or np.linalg.eigvalsh(_sym(p)).min() <= 0:
            raise ValueError(f"P[{k}] must be symmetric positive definite")
    P = [_sym(p) for p in P]
    rates = np.array([-0.5 * float(eigh(_sym(a.T @ p + p @ a), p, eigvals_only=True).max())
                      for a, p in zip(A, P, strict=True)])
    decay = float(rates.min())
    mu = _mu_tight(P)
    tau = float(np.log(mu) / (2 * decay)) if decay > 0 else np.inf
    return LyapunovDwell(rates, decay, mu, _mu_crude(P), tau)


@dataclass(frozen=True)
class PeriodicDwellMargin:
    """Spectral radii of periodic switching 1 → 2 → … → I → 1 against the dwell time.

    Parameters
    ----------
    taus : (k,) ndarray
        Dwell times τ in s (positive, increasing).
    rho : (k,) ndarray
        Spectral radius of e^{A_I τ} ⋯ e^{A_1 τ} (every dwell = τ).
    growth : (k,) ndarray
        ln(rho) / (I τ) in 1/s: the exponential rate of the periodic solution (> 0: unstable).
    rho_worst : (k,) ndarray
        Two modes: the largest spectral radius of e^{A_2 τ_2} e^{A_1 τ_1} over the pairs
        (τ_1, τ_2) of ``taus`` with both ≥ τ; NaN for more than two modes.
    growth_worst : (k,) ndarray
        Two modes: the largest ln(ρ) / (τ_1 + τ_2) over the same pairs; NaN otherwise.
    n_modes : int
        Number of modes I.
    """

    taus: np.ndarray
    rho: np.ndarray
    growth: np.ndarray
    rho_worst: np.ndarray
    growth_worst: np.ndarray
    n_modes: int

    def __post_init__(self):
        for name in ("taus", "rho", "growth", "rho_worst", "growth_worst"):
            object.__setattr__(self, name, frozen_array(np.asarray(getattr(self, name), dtype=float)))

    @property
    def lower_bound(self) -> float:
        """The longest dwell τ of ``taus`` at which some periodic switching diverges (ρ > 1).

        Every valid dwell-time bound exceeds it; 0.0 if no periodic switching on the grid
        diverges.

        Returns
        -------
        float
        """
        worst = self.rho if self.n_modes > 2 else self.rho_worst
        bad = np.flatnonzero(worst > 1.0)
        return float(self.taus[bad[-1]]) if bad.size else 0.0


def _spectral_radius(M):
    return np.abs(np.linalg.eigvals(M)).max(axis=-1)


def _suffix_max(R):
    """S[a, b] = max of R[a:, b:]."""
    S = np.maximum.accumulate(np.maximum.accumulate(R[::-1, ::-1], axis=0), axis=1)
    return S[::-1, ::-1]


def periodic_dwell_margin(modes, taus) -> PeriodicDwellMargin:
    """Spectral radius of the periodic switching 1 → 2 → … → I → 1 with dwell τ, over a grid of τ.

    Parameters
    ----------
    modes : list of (n, n) array_like or LTISystem
        The modes' state matrices A_i (I ≥ 2, Hurwitz).
    taus : (k,) array_like
        Dwell times in s, positive and strictly increasing. For two modes the unequal pairs
        (τ_1, τ_2) are taken from this grid (k² products).

    Returns
    -------
    PeriodicDwellMargin

    Raises
    ------
    TypeError
        If ``modes`` is not a list or tuple.
    ValueError
        If fewer than two modes are given, they differ in size, or ``taus`` is not positive and
        strictly increasing.
    DimensionError
        If a mode is not square or ``taus`` is not 1-D.
    UnstableError
        If a mode is not Hurwitz.

    Notes
    -----
    With d = 0 the state after one period is Φ x with Φ = e^{A_I τ_I} ⋯ e^{A_1 τ_1}; if
    ρ(Φ) > 1 the periodic switching diverges, so any dwell-time bound valid for all switching
    signals must exceed min_i τ_i. This measures how conservative τ* of
    :func:`dwell_time_bound` is.

    Examples
    --------
    Two modes whose average [[-1, 2], [2, -1]] is unstable: fast periodic switching diverges.

    >>> A1 = [[-1.0, 4.0], [0.0, -1.0]]
    >>> A2 = [[-1.0, 0.0], [4.0, -1.0]]
    >>> m = periodic_dwell_margin([A1, A2], [0.01, 0.1, 1.0, 5.0])
    >>> bool(m.rho[0] > 1), bool(m.rho[-1] < 1), m.lower_bound >= 0.1
    (True, True, True)
    """
    A = _mode_matrices(modes)
    taus = as_vector("taus", taus)
    if taus.size == 0 or taus[0] <= 0 or np.any(np.diff(taus) <= 0):
        raise ValueError(f"taus must be positive and strictly increasing, but found {taus}")
    # one call per matrix: scipy's batched expm is slow for the large ‖Aτ‖ of stiff modes
    E = [np.array([expm(a * tau) for tau in taus]) for a in A]
    M = E[0]
    for e in E[1:]:
        M = e @ M
    rho = _spectral_radius(M)
    growth = np.log(rho) / (len(A) * taus)
    if len(A) == 2:
        R = _spectral_radius(np.einsum("bij,ajk->abik", E[1], E[0]))
        G = np.log(R) / (taus[:, None] + taus[None, :])
        rho_worst = np.diagonal(_suffix_max(R)).copy()
        growth_worst = np.diagonal(_suffix_max(G)).copy()
    else:
        rho_worst = growth_worst = np.full(taus.shape, np.nan)
    return PeriodicDwellMargin(taus, rho, growth, rho_worst, growth_worst, len(A))


def _signal(switch_times, sequence, n_modes):
    st = as_vector("switch_times", switch_times) if np.size(switch_times) else np.zeros(0)
    if st.size and (st[0] <= 0 or np.any(np.diff(st) <= 0)):
        raise ValueError(f"switch_times must be positive and strictly increasing, but found {st}")
    seq = np.asarray(sequence)
    if seq.ndim != 1 or seq.size != st.size + 1 or seq.dtype.kind not in "iu":
        raise ValueError(f"sequence must be a 1-D integer array with one mode per interval "
                         f"({st.size + 1}), but found {seq!r}")
    if seq.min() < 0 or seq.max() >= n_modes:
        raise ValueError(f"sequence must hold mode indices in [0, {n_modes}), but found {seq}")
    if np.any(seq[1:] == seq[:-1]):
        raise ValueError("sequence must change mode at every switch (consecutive entries differ)")
    return st, seq


def switched_states(modes, x0, switch_times, sequence, t) -> np.ndarray:
    """Exact states of ẋ = A_σ(t) x (d = 0) along a given switching signal.

    Parameters
    ----------
    modes : list of (n, n) array_like or LTISystem
        The modes' state matrices A_i (I ≥ 2, Hurwitz).
    x0 : (n,) array_like
        Initial state.
    switch_times : (m,) array_like
        Switching instants t_1 < … < t_m in s (> 0); may be empty.
    sequence : (m + 1,) int array_like
        Active mode on [0, t_1), [t_1, t_2), …, [t_m, ∞); consecutive entries differ.
    t : (k,) array_like
        Sample times in s (≥ 0).

    Returns
    -------
    (k, n) ndarray
        x(t) at the samples (e^{A_i (t − t_l)} x(t_l) on each interval: exact up to rounding).

    Raises
    ------
    ValueError
        If the signal is malformed, or a sample time is negative.
    DimensionError
        If ``x0`` does not have n entries.

    Examples
    --------
    >>> x = switched_states([[[-1.0]], [[-2.0]]], [1.0], [1.0], [0, 1], [0.0, 1.0, 2.0])
    >>> np.allclose(x[:, 0], [1.0, np.exp(-1), np.exp(-3)])
    True
    """
    A = _mode_matrices(modes)
    x0 = as_vector("x0", x0, A[0].shape[0])
    st, seq = _signal(switch_times, sequence, len(A))
    t = as_vector("t", t)
    if t.size and t.min() < 0:
        raise ValueError(f"t must be >= 0, but found {t.min()}")
    cache = {}

    def transition(i, h):
        # one matrix exponential per (mode, step); a uniform sample grid has few distinct steps
        if (i, h) not in cache:
            cache[i, h] = expm(A[i] * h)
        return cache[i, h]

    starts = np.concatenate([[0.0], st])
    xb = [x0]
    for m in range(st.size):
        xb.append(transition(seq[m], starts[m + 1] - starts[m]) @ xb[-1])
    idx = np.searchsorted(st, t, side="right")
    x = np.empty((t.size, x0.size))
    m, tc, xc = -1, 0.0, x0
    for q in np.argsort(t, kind="stable"):
        if idx[q] != m:
            m, tc, xc = idx[q], starts[idx[q]], xb[idx[q]]
        xc = transition(seq[m], t[q] - tc) @ xc
        tc = t[q]
        x[q] = xc
    return x


def random_dwell_signal(rng: np.random.Generator, n_modes: int, min_dwell: float, horizon: float,
                        *, max_dwell: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """A random switching signal on [0, horizon] whose dwells all lie in [min_dwell, max_dwell].

    Draws the initial mode, then alternately a dwell (uniform) and the next mode (uniform among
    the others). The first switch is at least ``min_dwell`` after 0.

    Parameters
    ----------
    rng : numpy.random.Generator
        Source of randomness.
    n_modes : int
        Number of modes (≥ 2).
    min_dwell : float
        Shortest dwell in s (> 0).
    horizon : float
        Length of the signal in s (> 0).
    max_dwell : float, optional
        Longest dwell in s (≥ ``min_dwell``); default 2 ``min_dwell``.

    Returns
    -------
    switch_times : (m,) ndarray
        Switching instants in (0, horizon).
    sequence : (m + 1,) int ndarray
        Active mode on each interval.

    Raises
    ------
    TypeError
        If ``rng`` is not a ``numpy.random.Generator``.
    ValueError
        If an argument is out of range.

    Examples
    --------
    >>> st, seq = random_dwell_signal(np.random.default_rng(0), 2, 1.0, 10.0)
    >>> bool(np.all(np.diff(np.concatenate([[0.0], st])) >= 1.0)), seq.size == st.size + 1
    (True, True)
    """
    check_type("rng", rng, np.random.Generator, "a numpy.random.Generator")
    n_modes = as_count("n_modes", n_modes, 2)
    min_dwell = as_positive("min_dwell", min_dwell)
    horizon = as_positive("horizon", horizon)
    max_dwell = 2 * min_dwell if max_dwell is None else as_positive("max_dwell", max_dwell)
    if max_dwell < min_dwell:
        raise ValueError(f"max_dwell must be >= min_dwell = {min_dwell:g}, but found {max_dwell:g}")
    seq = [int(rng.integers(n_modes))]
    times = []
    t = float(rng.uniform(min_dwell, max_dwell))
    # every step advances t by at least min_dwell > 0: at most horizon/min_dwell iterations
    while t < horizon:
        times.append(t)
        seq.append(int((seq[-1] + rng.integers(1, n_modes)) % n_modes))
        t += float(rng.uniform(min_dwell, max_dwell))
    return np.array(times), np.array(seq, dtype=int)


@dataclass(frozen=True)
class DwellCheck:
    """The bound V(t) ≤ μ^{N(t)} e^{−2λt} V(0) checked along one switching signal (d = 0).

    Parameters
    ----------
    max_ratio : float
        max over the samples t > 0 of V(t) / (μ^{N(t)} e^{−2λt} V(0)); ≤ 1 by the certificate
        (1.0 if there is no sample after 0).
    final_v_ratio : float
        V(T)/V(0) at the last sample.
    final_norm_ratio : float
        ‖x(T)‖/‖x(0)‖.
    rate_bound : float
        The guaranteed rate 2λ − ln μ/τ_d with τ_d the signal's shortest dwell (the first from
        t = 0 included); V(T)/V(0) ≤ e^{−rate_bound·T}.
    n_switches : int
        Number of switches.
    min_dwell : float
        Shortest dwell of the signal in s (the horizon if it never switches).
    horizon : float
        Last sample time T in s.
    """

    max_ratio: float
    final_v_ratio: float
    final_norm_ratio: float
    rate_bound: float
    n_switches: int
    min_dwell: float
    horizon: float

    def holds(self, rtol: float = 1e-9) -> bool:
        """Whether the envelope and the decay bound hold up to the relative tolerance ``rtol``.

        Parameters
        ----------
        rtol : float, optional
            Relative slack for rounding (≥ 0).

        Returns
        -------
        bool
        """
        rtol = as_nonnegative("rtol", rtol)
        decay_ok = self.final_v_ratio <= np.exp(-self.rate_bound * self.horizon) * (1 + rtol)
        return bool(self.max_ratio <= 1 + rtol and decay_ok)


def check_dwell_bound(bound: DwellTimeBound, modes, x0, switch_times, sequence, t) -> DwellCheck:
    """Check the Lyapunov envelope of a dwell-time certificate along a switching signal (d = 0).

    Parameters
    ----------
    bound : DwellTimeBound
        The certificate (its P_i, λ and μ).
    modes : list of (n, n) array_like or LTISystem
        The modes the certificate was computed for.
    x0 : (n,) array_like
        Initial state (nonzero).
    switch_times, sequence : array_like
        The switching signal (see :func:`switched_states`).
    t : (k,) array_like
        Sample times in s, starting at 0; the switching instants are added to them.

    Returns
    -------
    DwellCheck

    Raises
    ------
    TypeError
        If ``bound`` is not a :class:`DwellTimeBound`.
    ValueError
        If the modes do not match the certificate, ``x0`` is zero, ``t`` does not start at 0,
        or the signal is malformed.

    Notes
    -----
    The envelope V(t) ≤ μ^{N(t)} e^{−2λt} V(0) holds for *every* switching signal; the dwell
    time is what makes it decay (see :func:`dwell_time_bound`).

    Examples
    --------
    >>> A = [[[-1.0, 2.0], [-2.0, -1.0]], [[-2.0, 0.0], [0.0, -3.0]]]
    >>> b = dwell_time_bound(A, decay=0.5)
    >>> c = check_dwell_bound(b, A, [1.0, 0.0], [1.0, 2.0], [0, 1, 0], np.linspace(0, 3, 31))
    >>> c.holds(), c.n_switches
    (True, 2)
    """
    check_type("bound", bound, DwellTimeBound, "an fdsc.dwell.DwellTimeBound")
    A = _mode_matrices(modes)
    if len(A) != len(bound.P) or A[0].shape != bound.P[0].shape:
        raise ValueError(f"modes must be the {len(bound.P)} modes of the certificate, but found "
                         f"{len(A)} of size {A[0].shape}")
    x0 = as_vector("x0", x0, A[0].shape[0])
    if not np.any(x0):
        raise ValueError("x0 must be nonzero")
    st, seq = _signal(switch_times, sequence, len(A))
    t = as_vector("t", t)
    if t.size == 0 or t.min() != 0:
        raise ValueError(f"t must start at 0, but found {t.min() if t.size else 'no samples'}")
    t = np.union1d(t, st)
    x = switched_states(A, x0, st, seq, t)
    idx = np.searchsorted(st, t, side="right")
    P = np.array(bound.P)[seq[idx]]
    V = np.einsum("ki,kij,kj->k", x, P, x)
    with np.errstate(divide="ignore"):
        log_ratio = np.log(V) - np.log(V[0]) - idx * np.log(bound.mu) + 2 * bound.decay * t
    min_dwell = float(np.diff(np.concatenate([[0.0], st])).min()) if st.size else float(t[-1])
    rate = 2 * bound.decay - np.log(bound.mu) / min_dwell if min_dwell > 0 else -np.inf
    later = log_ratio[t > 0]
    return DwellCheck(float(np.exp(later.max())) if later.size else 1.0, float(V[-1] / V[0]),
                      float(np.linalg.norm(x[-1]) / np.linalg.norm(x[0])), float(rate),
                      int(st.size), min_dwell, float(t[-1]))
