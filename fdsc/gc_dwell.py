"""The Geromel–Colaneri dwell-time certificate for switched linear systems, by LMIs.

For Hurwitz modes A_1, …, A_I (I ≥ 2) and a dwell time T > 0, the minimum dwell-time theorem of
Geromel and Colaneri (2006) asks for matrices P_i ≻ 0 with

    A_iᵀ P_i + P_i A_i ≺ 0                          for every i            (flow)
    e^{A_iᵀ T} P_j e^{A_i T} − P_i ≺ 0              for every i ≠ j        (jump)

If they exist, ẋ = A_σ x (no disturbance, d = 0) is globally asymptotically stable for every
switching signal σ whose consecutive switches are at least T apart. V_i(x) = xᵀ P_i x is not
required to decrease at the switch itself: the jump condition compares V_j just after a switch
with V_i at the start of the interval of mode i that preceded it, at least T earlier, and the
flow condition keeps V_i from growing inside an interval. The certificate is a statement about
stability only; it gives no L2-gain bound from a disturbance.

If the P_i certify T, they certify every T' ≥ T (see :func:`geromel_colaneri_dwell`), so the
dwell times certified form an interval (T_min, ∞), and :func:`geromel_colaneri_dwell` finds
its left end by geometric bisection on T, one LMI feasibility problem per step.

Comparison with :func:`fdsc.dwell.dwell_time_bound`. That function certifies
τ* = ln μ / (2λ) from P_i with A_iᵀP_i + P_iA_i ⪯ −2λP_i and P_j ⪯ μP_i. Those same P_i satisfy
the jump condition above for every T > τ* (e^{A_iᵀT} P_j e^{A_iT} ⪯ μ e^{−2λT} P_i ≺ P_i), so
in exact arithmetic the Geromel–Colaneri T_min is never above the τ* of any such certificate.
The returned numbers are computed to tolerances (a λ grid and a bisection on ln μ there, a
bisection on T with relative tolerance ``rtol`` here), so the returned ``tau`` may exceed the
returned τ* when the two are within those tolerances of each other. Both are upper bounds on
the smallest dwell time that makes every switching signal stable;
:func:`fdsc.dwell.periodic_dwell_margin` gives a lower bound (a periodic signal that diverges).

Reference: J. C. Geromel and P. Colaneri, "Stability and stabilization of continuous-time
switched linear systems", SIAM J. Control Optim. 45(5), 2006.
"""

from __future__ import annotations

from dataclasses import dataclass

import cvxpy as cp
import numpy as np
from scipy.linalg import expm

from ._dwell_lmi import _mode_matrices
from ._validation import as_count, as_positive, as_vector, frozen_array
from .exceptions import InfeasibleError, IterationLimitError, SolverError, VerificationError
from .lmi import DEFAULT_MARGIN, _sym, solve_checked

__all__ = [
    "DwellCertificate",
    "geromel_colaneri_dwell",
    "DEFAULT_TAU_MAX",
    "DEFAULT_RTOL",
    "DEFAULT_MAX_BISECTIONS",
    "LOWER_FRACTION",
]

#: Largest dwell time tried by default, in s.
DEFAULT_TAU_MAX = 1e3
#: Relative tolerance of the bisection on T: it stops when hi / lo − 1 ≤ rtol.
DEFAULT_RTOL = 1e-3
#: Iteration cap of the bisection (a bracket of ratio 1e6 needs 14 steps at rtol = 1e-3).
DEFAULT_MAX_BISECTIONS = 60
#: The lower end of the bracket is ``tau_max * LOWER_FRACTION``: a T certified there is reported
#: as it is, without searching below it.
LOWER_FRACTION = 1e-6


@dataclass(frozen=True)
class DwellCertificate:
    """A dwell time T certified by the Geromel–Colaneri LMIs, with its Lyapunov matrices.

    Parameters
    ----------
    tau : float
        The certified dwell time T in s: ẋ = A_σ x is globally asymptotically stable for every
        switching signal whose consecutive switches are at least ``tau`` apart.
    P : tuple of (n, n) ndarray
        The matrices P_i ≻ 0, one per mode, that satisfy the LMIs at ``tau``.
    A : tuple of (n, n) ndarray
        The modes' state matrices A_i.
    max_eigs : (I²,) ndarray
        Largest eigenvalue of each LMI block at the certificate, all < 0: first the I flow
        blocks A_iᵀP_i + P_iA_i, then the I(I − 1) jump blocks e^{A_iᵀT}P_je^{A_iT} − P_i in
        the order (i, j) = (0, 1), (0, 2), …, (I − 1, I − 2).
    n_solves : int
        Number of LMI solves.
    bracket : tuple of float
        ``(lo, hi)`` in s: the last T at which no certificate was found (0.0 if the lower end
        of the bracket was certified) and ``hi = tau``.
    n_failed : int, optional
        Solves that ended without a verified certificate other than by infeasibility (a solver
        stop or a failed eigenvalue check near the boundary of the feasible set); each counts as
        "not certified" at its T, which can only make ``tau`` larger, never invalid.

    Raises
    ------
    ValueError
        If ``tau`` is not positive, or ``P``, ``A`` and ``max_eigs`` do not describe the same
        number of modes.

    Notes
    -----
    Geromel & Colaneri (2006), the minimum dwell-time theorem (continuous time).
    """

    tau: float
    P: tuple
    A: tuple
    max_eigs: np.ndarray
    n_solves: int
    bracket: tuple
    n_failed: int = 0

    def __post_init__(self):
        object.__setattr__(self, "tau", as_positive("tau", self.tau))
        object.__setattr__(self, "P", tuple(frozen_array(np.asarray(p, dtype=float)) for p in self.P))
        object.__setattr__(self, "A", tuple(frozen_array(np.asarray(a, dtype=float)) for a in self.A))
        object.__setattr__(self, "max_eigs", frozen_array(np.asarray(self.max_eigs, dtype=float)))
        object.__setattr__(self, "bracket", tuple(float(b) for b in self.bracket))
        n_modes = len(self.A)
        if len(self.P) != n_modes or self.max_eigs.shape != (n_modes**2,):
            raise ValueError(f"P and max_eigs must describe the {n_modes} modes of A: expected "
                             f"{n_modes} matrices P_i and {n_modes**2} eigenvalues, but found "
                             f"{len(self.P)} and shape {self.max_eigs.shape}")

    def admits(self, switch_times, horizon: float | None = None) -> bool:
        """Whether a switching signal keeps its switches at least ``tau`` apart.

        Parameters
        ----------
        switch_times : (m,) array_like
            Switching instants t_1 < … < t_m in s (> 0); may be empty.
        horizon : float, optional
            End in s of the window [0, horizon] on which the signal is judged: switches after it
            are ignored. Default: every switch counts.

        Returns
        -------
        bool
            True if t_{k+1} − t_k ≥ ``tau`` for every pair of consecutive switches (in the
            window). The time before the first switch and after the last one is not a dwell
            between switches and is not checked.

        Raises
        ------
        ValueError
            If ``switch_times`` is not positive and strictly increasing, or ``horizon`` is not
            positive.

        Notes
        -----
        A signal the certificate admits is one the theorem covers: the first interval
        [0, t_1) may be shorter than ``tau``, since it multiplies V by a bounded factor only.

        Examples
        --------
        >>> c = geromel_colaneri_dwell([[[-1.0]], [[-2.0]]])
        >>> c.admits([1.0, 2.0, 3.0]), c.admits([1.0, 1.0 + c.tau / 2])
        (True, False)
        """
        st = as_vector("switch_times", switch_times) if np.size(switch_times) else np.zeros(0)
        if st.size and (st[0] <= 0 or np.any(np.diff(st) <= 0)):
            raise ValueError(f"switch_times must be positive and strictly increasing, but found {st}")
        if horizon is not None:
            st = st[st <= as_positive("horizon", horizon)]
        # switch instants computed as k·Δ round off a few ulps: a gap equal to tau up to that
        # rounding is tau
        return bool(np.all(np.diff(st) >= self.tau * (1.0 - 1e-12)))


def _blocks(A, E, P):
    """The LMI matrices at given P_i (NumPy): flow blocks, then jump blocks in (i, j) order."""
    flow = [_sym(a.T @ p + p @ a) for a, p in zip(A, P, strict=True)]
    jump = [_sym(E[i].T @ P[j] @ E[i] - P[i]) for i in range(len(A)) for j in range(len(A)) if i != j]
    return flow + jump


def _certify_at(A, T, margin, counts):
    """Verified P_i at the dwell time T, or the exception that says why there are none.

    The flow LMIs are divided by ‖A_i‖₂ and the jump LMIs by min(1, T‖A_i‖₂), so that the
    solver sees O(1) blocks: for small T the jump block is about T(A_iᵀP + PA_i) when P_j ≈ P_i.
    The LMIs are homogeneous in P, normalized by P_i ⪰ I.
    """
    n, n_modes = A[0].shape[0], len(A)
    eye = np.eye(n)
    norms = [float(np.linalg.norm(a, 2)) for a in A]
    E = [expm(a * T) for a in A]
    P = [cp.Variable((n, n), symmetric=True, name=f"P_{i}") for i in range(n_modes)]
    cons = [p >> eye for p in P]
    cons += [_sym(a.T @ p + p @ a) / s << -margin * eye for a, p, s in zip(A, P, norms, strict=True)]
    cons += [_sym(E[i].T @ P[j] @ E[i] - P[i]) / min(1.0, T * norms[i]) << -margin * eye
             for i in range(n_modes) for j in range(n_modes) if i != j]
    what = f"Geromel-Colaneri dwell-time LMIs at T={T:.6g} s"
    counts["solves"] += 1
    try:
        status = solve_checked(cp.Problem(cp.Minimize(0), cons), what)
    except SolverError as exc:
        counts["failed"] += not isinstance(exc, InfeasibleError)
        return exc
    Pv = [_sym(p.value) for p in P]
    eigs = np.array([float(np.linalg.eigvalsh(b).max()) for b in _blocks(A, E, Pv)])
    pmin = min(float(np.linalg.eigvalsh(p).min()) for p in Pv)
    if not (np.all(eigs < 0) and pmin > 0):
        counts["failed"] += 1
        return VerificationError(f"{what}: the certificate fails its check (largest eigenvalues of the "
                           f"blocks: {eigs}, smallest of the P_i: {pmin:.3g})", status)
    return Pv, eigs


def geromel_colaneri_dwell(modes, *, tau_max: float = DEFAULT_TAU_MAX, rtol: float = DEFAULT_RTOL,
                           margin: float = DEFAULT_MARGIN,
                           max_bisections: int = DEFAULT_MAX_BISECTIONS) -> DwellCertificate:
    """The smallest dwell time certified by the Geromel–Colaneri LMIs, by bisection on T.

    Parameters
    ----------
    modes : list of (n, n) array_like or LTISystem
        The modes' state matrices A_i (I ≥ 2, Hurwitz), or closed loops whose ``A`` is used.
    tau_max : float, optional
        Largest dwell time tried, in s (> 0); the upper end of the bracket. The lower end is
        ``tau_max *`` :data:`LOWER_FRACTION`.
    rtol : float, optional
        Relative tolerance of the bisection (in (0, 1)): it stops when hi / lo − 1 ≤ rtol.
    margin : float, optional
        Strictness margin of the LMIs (each block ⪯ −margin·I after its scaling, with P_i ⪰ I).
    max_bisections : int, optional
        Iteration cap of the bisection (≥ 1).

    Returns
    -------
    DwellCertificate
        ``tau`` is the smallest T of the bisection with a verified certificate; the bisection
        ends with ``bracket[1] / bracket[0] − 1 ≤ rtol``, or returns the lower end
        ``tau_max * LOWER_FRACTION`` (with ``bracket[0] = 0.0``) if that is certified.

    Raises
    ------
    TypeError
        If ``modes`` is not a list or tuple.
    ValueError
        If fewer than two modes are given, they differ in size, or ``tau_max``, ``rtol``,
        ``margin`` or ``max_bisections`` is out of range.
    DimensionError
        If a mode is not a square matrix.
    UnstableError
        If a mode is not Hurwitz (the message names the mode and its eigenvalue with the largest
        real part).
    InfeasibleError
        If no dwell time up to ``tau_max`` is certified (the LMIs at ``tau_max`` are infeasible,
        or their solve fails or yields a point that fails its eigenvalue check).
    IterationLimitError
        If the bisection does not reach ``rtol`` within ``max_bisections`` steps.

    Notes
    -----
    Geromel & Colaneri (2006), minimum dwell-time theorem: if P_i ≻ 0 satisfy A_iᵀP_i + P_iA_i ≺ 0 for every i
    and e^{A_iᵀT}P_je^{A_iT} − P_i ≺ 0 for every i ≠ j, then ẋ = A_σ x is globally
    asymptotically stable for every switching signal whose consecutive switches are at least
    T apart. The same P_i satisfy the jump condition at every T' > T:

        e^{A_iᵀT'}P_je^{A_iT'} = e^{A_iᵀ(T'−T)} (e^{A_iᵀT}P_je^{A_iT}) e^{A_i(T'−T)}
                               ≺ e^{A_iᵀ(T'−T)} P_i e^{A_i(T'−T)} ⪯ P_i,

    the last step by the flow condition. In exact arithmetic the certified dwell times therefore
    form an interval and bisection on T is sound; it is geometric (mid = √(lo·hi)) because the bracket spans
    several decades. Every point the solver returns is verified by the eigenvalues of all blocks
    and of the P_i, evaluated with the same matrix exponentials, before T counts as certified;
    a point that fails the check counts as "not certified" there. The result certifies
    stability with d = 0 only; it is not an L2-gain bound.

    Examples
    --------
    Commuting modes have the common Lyapunov function P = I, certified at every T > 0; the
    lower end of the bracket is returned:

    >>> c = geromel_colaneri_dwell([np.diag([-1.0, -2.0]), np.diag([-3.0, -0.5])])
    >>> c.tau, c.bracket, bool(np.all(c.max_eigs < 0))
    (0.001, (0.0, 0.001), True)

    Two modes whose fast periodic switching diverges need a positive dwell time:

    >>> A1 = [[-1.0, 4.0], [0.0, -1.0]]
    >>> A2 = [[-1.0, 0.0], [4.0, -1.0]]
    >>> c = geromel_colaneri_dwell([A1, A2], rtol=0.01)
    >>> bool(2.0 < c.tau < 2.7), c.bracket[1] / c.bracket[0] - 1 <= 0.01
    (True, True)
    """
    A = _mode_matrices(modes)
    tau_max = as_positive("tau_max", tau_max)
    rtol = as_positive("rtol", rtol)
    if rtol >= 1:
        raise ValueError(f"rtol must be in (0, 1), but found {rtol}")
    margin = as_positive("margin", margin)
    max_bisections = as_count("max_bisections", max_bisections)
    counts = {"solves": 0, "failed": 0}

    def certificate(found, T, lo):
        P, eigs = found
        return DwellCertificate(T, tuple(P), tuple(A), eigs, counts["solves"], (lo, T),
                                counts["failed"])

    best = _certify_at(A, tau_max, margin, counts)
    if isinstance(best, SolverError):
        why = str(best).removesuffix(f" (status: {best.status})")
        raise InfeasibleError(f"no dwell time up to tau_max = {tau_max:g} s could be certified: {why}",
                              best.status, best.solver_status) from best
    lo, hi = tau_max * LOWER_FRACTION, tau_max
    at_lo = _certify_at(A, lo, margin, counts)
    if not isinstance(at_lo, SolverError):
        return certificate(at_lo, lo, 0.0)
    for _ in range(max_bisections):
        if hi / lo - 1 <= rtol:
            break
        mid = float(np.sqrt(lo * hi))
        found = _certify_at(A, mid, margin, counts)
        if isinstance(found, SolverError):
            lo = mid
        else:
            hi, best = mid, found
    else:
        if hi / lo - 1 > rtol:
            raise IterationLimitError(f"Geromel-Colaneri dwell time: the bisection on T did not reach "
                                      f"rtol = {rtol:g} in max_bisections = {max_bisections} steps "
                                      f"(bracket [{lo:.6g}, {hi:.6g}] s)")
    return certificate(best, hi, lo)
