"""The LMIs of :func:`fdsc.dwell.dwell_time_bound`: mode matrices, the tight and crude jump
factor μ, the verification of a certificate, and the bisection on ln μ at one decay rate.
Internal (see the docstring of :mod:`fdsc.dwell`).
"""

from __future__ import annotations

import cvxpy as cp
import numpy as np
from scipy.linalg import eigh

from ._validation import (
    as_matrix,
    check_hurwitz,
)
from .exceptions import InfeasibleError, IterationLimitError, SolverError, VerificationError
from .lmi import _sym, solve_checked
from .plant import LTISystem

__all__ = []

#: Absolute tolerance on ln μ (stops the bisection when μ is 1 up to the margin).
_LOG_MU_ATOL = 1e-9


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
