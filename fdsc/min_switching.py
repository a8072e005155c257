"""Geromel–Colaneri min-switching: a state-feedback switching law with an L2-gain certificate.

For closed loops ``ẋ = A_i x + B d, z = C_i x + D d`` (i = 1 … I, shared B and D) the
min-switching law picks ``σ(x) = argmin_i xᵀ P_i x``. Geromel and Colaneri (SIAM J. Control
Optim. 2006) show that it is stabilizing if the P_i ≻ 0 satisfy the Lyapunov–Metzler inequalities
``A_iᵀ P_i + P_i A_i + Σ_j π_ji P_j ≺ 0`` for a Metzler matrix Π (off-diagonal entries ≥ 0,
columns summing to 0). With the output and the disturbance added,

    [A_iᵀP_i + P_iA_i + Σ_j π_ji P_j + C_iᵀC_i,   P_iB + C_iᵀD ]
    [BᵀP_i + DᵀC_i,                               DᵀD − ρ² I   ]  ≺ 0     for every i,

the law also bounds the L2 gain: along the active mode i (the minimizer),
``V(x) = min_j xᵀP_j x`` obeys ``V̇ + ‖z‖² − ρ² d² ≤ −Σ_{j≠i} π_ji (xᵀP_j x − xᵀP_i x) ≤ 0``,
so from x(0) = 0, ``∫‖z‖² ≤ ρ² ∫d²`` for every disturbance. The inequalities are bilinear in
(P, Π); :func:`min_switching` fixes Π = γ (11ᵀ − I) / (I − 1) − γ I, solves the LMIs in
(P, ρ²) for each γ of a grid, and keeps the least ρ.

The law decides on the state, not on the disturbance, so it cannot anticipate what a band will
need; it is the book's certified negative control for the laws of :mod:`fdsc.supervisor`.
:meth:`MinSwitchingCertificate.law_weights` gives the quadratic forms with which
:func:`fdsc.simulate_stream` runs it (its law picks the largest ``[ẋ; x]ᵀ W_i [ẋ; x]``, so
``W_i = diag(0, −P_i)``), sampled at the simulator's step.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import cvxpy as cp
import numpy as np

from ._validation import as_positive, as_vector, frozen_array
from .exceptions import InfeasibleError, SolverError, VerificationError
from .lmi import _sym, solve_checked
from .plant import LTISystem

__all__ = ["MinSwitchingCertificate", "min_switching", "DEFAULT_RATES"]

#: The rates γ of the Metzler matrix tried by default (1/s).
DEFAULT_RATES = tuple(float(g) for g in np.logspace(-3, 3, 13))


@dataclass(frozen=True)
class MinSwitchingCertificate:
    """An L2-gain certificate of the min-switching law (see :func:`min_switching`).

    Parameters
    ----------
    P : tuple of (n, n) ndarray
        The P_i of the law ``σ = argmin_i xᵀ P_i x``.
    rate : float
        γ of the Metzler matrix Π used.
    l2_bound : float
        ρ: from x(0) = 0, ``∫‖z‖² ≤ ρ² ∫d²`` under the law, for every disturbance.
    max_eigs : (I,) ndarray
        The largest eigenvalue of each LMI block at the returned P_i (all negative).
    """

    P: tuple
    rate: float
    l2_bound: float
    max_eigs: np.ndarray

    def __post_init__(self):
        object.__setattr__(self, "P", tuple(frozen_array(p) for p in self.P))
        object.__setattr__(self, "max_eigs", frozen_array(self.max_eigs))

    def law_weights(self) -> list:
        """``W_i = diag(0, −P_i) / 2^k`` on ``[ẋ; x]``: the law as ``law_weights`` of
        :func:`fdsc.simulate_stream` (whose law picks the largest score).

        The P_i are divided by one power of two 2^k that brings their largest entry into
        [½, 1): the law does not change (it compares the forms with each other), and the
        simulator's scores stay far from the float range's ends whatever the P_i's scale.

        Returns
        -------
        list of (2n, 2n) ndarray
        """
        n = self.P[0].shape[0]
        k = _exponent(max(float(np.max(np.abs(p))) for p in self.P))
        out = []
        for p in self.P:
            W = np.zeros((2 * n, 2 * n))
            W[n:, n:] = -np.ldexp(p, -k)
            out.append(W)
        return out

    def choose(self, x) -> int:
        """The mode the law picks at the state x (the lowest index on ties).

        Parameters
        ----------
        x : (n,) array_like

        Returns
        -------
        int

        Raises
        ------
        ValueError
            If x is not a finite vector of the loops' size.
        """
        x = np.array(as_vector("x", x, self.P[0].shape[0]))
        # the law does not depend on the norm of x nor on a common scale of the P_i: both are
        # normalized by powers of two (exact), so that the forms neither overflow nor underflow
        x = np.ldexp(x, -_exponent(float(np.max(np.abs(x)))))
        k = _exponent(max(float(np.max(np.abs(p))) for p in self.P))
        return int(np.argmin([x @ np.ldexp(p, -k) @ x for p in self.P]))


def _exponent(largest: float) -> int:
    """The power of two that brings ``largest`` into [½, 1) (0 for 0)."""
    return math.frexp(largest)[1] if largest > 0 else 0


def _blocks(loops, P, Pi, rho2):
    """The LMI blocks at given P_i (NumPy)."""
    out = []
    for i, lp in enumerate(loops):
        top = lp.A.T @ P[i] + P[i] @ lp.A + sum(Pi[j, i] * P[j] for j in range(len(loops))) + lp.C.T @ lp.C
        off = P[i] @ lp.B + lp.C.T @ lp.D
        out.append(_sym(np.block([[top, off], [off.T, lp.D.T @ lp.D - rho2 * np.eye(lp.B.shape[1])]])))
    return out


def _solve(loops, gamma, margin):
    """(P, ρ², Π) at the rate γ, or the SolverError that says why there are none."""
    nI, n = len(loops), loops[0].n_states
    m = loops[0].B.shape[1]
    Pi = gamma * (np.ones((nI, nI)) - np.eye(nI)) / (nI - 1) - gamma * np.eye(nI)
    P = [cp.Variable((n, n), symmetric=True) for _ in range(nI)]
    rho2 = cp.Variable(nonneg=True)
    cons = [p >> margin * np.eye(n) for p in P]
    for i, lp in enumerate(loops):
        top = lp.A.T @ P[i] + P[i] @ lp.A + sum(Pi[j, i] * P[j] for j in range(nI)) + lp.C.T @ lp.C
        off = P[i] @ lp.B + lp.C.T @ lp.D
        blk = cp.bmat([[top, off], [off.T, lp.D.T @ lp.D - rho2 * np.eye(m)]])
        cons.append(_sym(blk) << -margin * np.eye(n + m))
    try:
        solve_checked(cp.Problem(cp.Minimize(rho2), cons), f"min-switching LMIs at rate {gamma:.3g}")
    except SolverError as exc:
        return exc
    return [_sym(p.value) for p in P], float(rho2.value), Pi


def min_switching(loops, *, rates=DEFAULT_RATES, margin: float = 1e-6) -> MinSwitchingCertificate:
    """The min-switching law of closed loops with the least certified L2-gain bound.

    Parameters
    ----------
    loops : sequence of LTISystem
        Two or more Hurwitz closed loops sharing B (one disturbance input) and D, of one size.
    rates : sequence of float, optional
        The rates γ > 0 of the Metzler matrix tried (module docstring).
    margin : float, optional
        Strictness of the LMIs (blocks ⪯ −margin I, P_i ⪰ margin I).

    Returns
    -------
    MinSwitchingCertificate
        At the rate with the least ρ among those whose solution passes its check (every block's
        eigenvalues negative at the returned P_i and ρ).

    Raises
    ------
    TypeError
        If ``loops`` is not a sequence of LTISystem.
    ValueError
        If fewer than two loops are given, they differ in size, B or D, ``rates`` is not a
        non-empty sequence of positive finite numbers, or ``margin`` is not one.
    InfeasibleError
        If no rate gives a certificate (the message names the last solver status).

    Examples
    --------
    Two loops of one scalar plant ``ẋ = −x + d + u, z = x`` (gains −1 and −3): the law picks the
    faster loop, and the bound is at least the better loop's H∞ norm, 1/4 for ``ẋ = −4x + d``:

    >>> from fdsc import LTISystem
    >>> loops = [LTISystem([[-2.0]], [[1.0]], [[1.0]], [[0.0]]),
    ...          LTISystem([[-4.0]], [[1.0]], [[1.0]], [[0.0]])]
    >>> c = min_switching(loops)
    >>> 0.25 - 1e-3 <= c.l2_bound <= 0.5 + 1e-3, c.choose([1.0])
    (True, 1)
    """
    if not isinstance(loops, list | tuple) or not all(isinstance(lp, LTISystem) for lp in loops):
        raise TypeError("loops must be a list or tuple of fdsc.LTISystem")
    if len(loops) < 2:
        raise ValueError(f"loops must hold at least two closed loops, but found {len(loops)}")
    for k, lp in enumerate(loops[1:], start=1):
        if lp.A.shape != loops[0].A.shape or not np.array_equal(lp.B, loops[0].B) \
                or not np.array_equal(lp.D, loops[0].D) or lp.C.shape != loops[0].C.shape:
            raise ValueError(f"loops must share B, D and their sizes; loops[{k}] differs from loops[0]")
    for k, lp in enumerate(loops):
        worst = float(np.max(np.linalg.eigvals(lp.A).real))
        if worst >= 0:
            raise ValueError(f"loops[{k}] must be Hurwitz, but has an eigenvalue with real part {worst:.4g}")
    if isinstance(rates, str | bytes) or not hasattr(rates, "__len__") or np.ndim(rates) != 1 \
            or not len(rates):
        raise ValueError(f"rates must be a non-empty sequence of positive rates, but found {rates!r}")
    rates = [as_positive(f"rates[{k}]", g) for k, g in enumerate(rates)]
    margin = as_positive("margin", margin)
    best, last = None, None
    for g in rates:
        found = _solve(loops, g, margin)
        if isinstance(found, SolverError):
            last = found
            continue
        P, rho2, Pi = found
        eigs = np.array([float(np.linalg.eigvalsh(b).max()) for b in _blocks(loops, P, Pi, rho2)])
        if not (np.all(eigs < 0) and min(float(np.linalg.eigvalsh(p).min()) for p in P) > 0):
            last = VerificationError(f"min-switching LMIs at rate {g:.3g}: the solution fails its check "
                                     f"(largest block eigenvalues {eigs})", "verification")
            continue
        if best is None or rho2 < best.l2_bound ** 2:
            best = MinSwitchingCertificate(tuple(P), g, float(np.sqrt(rho2)), eigs)
    if best is None:
        status = getattr(last, "status", "unknown")
        why = str(last).removesuffix(f" (status: {status})")
        raise InfeasibleError(f"min_switching: no rate among {len(rates)} gives a certificate (last: {why})",
                              status, getattr(last, "solver_status", None))
    return best
