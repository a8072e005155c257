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

import numpy as np
from scipy.linalg import eigh

from ._dwell_bound import DwellTimeBound
from ._dwell_lmi import (
    _certify_at,
    _decay_limits,
    _mode_matrices,
    _mu_crude,
    _mu_tight,
    _Problems,
    _verify,
)
from ._dwell_signals import (
    MAX_SWITCHES,
    MODES_RTOL,
    DwellCheck,
    PeriodicDwellMargin,
    check_dwell_bound,
    periodic_dwell_margin,
    random_dwell_signal,
    switched_states,
)
from ._validation import (
    as_count,
    as_matrix,
    as_positive,
    frozen_array,
)
from .exceptions import SolverError
from .lmi import DEFAULT_MARGIN, _sym

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
    "MAX_SWITCHES",
    "MODES_RTOL",
]

#: Points of the coarse λ grid (the refinement around its best point has as many again).
DEFAULT_N_DECAYS = 16
#: Relative tolerance on ln μ (hence on τ* at fixed λ) at which the bisection stops.
DEFAULT_TAU_RTOL = 1e-3
#: Iteration cap of the bisection on ln μ (the initial bracket is at most a few dozen wide).
DEFAULT_MAX_BISECTIONS = 60


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
                          probs.n_solves, probs.n_failed, tuple(A))


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
