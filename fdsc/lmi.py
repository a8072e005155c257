"""Lemma 1 (the generalized KYP lemma): the smallest gain certified on a band.

For ``G(s) = C (sI − A)⁻¹ B + D`` and a band with matrices Φ, Ψ, the gKYP lemma
(Iwasaki & Hara 2005) states that ``σ_max(G(jω)) < γ`` for all ω in the band if
and only if there are Hermitian P and Q ⪰ 0 with

    [A B; I 0]* (Φ⊗P + Ψ⊗Q) [A B; I 0] + [C D; 0 I]* diag(I, −γ² I) [C D; 0 I] < 0.

The paper's Lemma 1 carries −γ² in this LMI but writes the energy ratio bound (2)
with γ; the LMI bounds the *gain* by γ and therefore the energy ratio by γ².

Numerics. The LMI is solved by cvxpy with Clarabel, minimizing g = γ², with the
strictness margin ``LMI ⪯ −margin·I``. Complex Hermitian LMIs (MF) are posed
through the real embedding ``M ≺ 0 ⇔ [[Re M, −Im M], [Im M, Re M]] ≺ 0``.
Before solving, the state is balanced (diagonal similarity) and the output is
divided by a sweep estimate of the peak, so that the solver sees γ ≈ 1; the
certificate is mapped back and its LMI matrix is evaluated in the original
coordinates, where its largest eigenvalue must be negative.

The matrix itself is assembled by :func:`fdsc.kyp.kyp_matrix`, the builder shared with
Theorem 1 and the synthesis LMIs.
"""

from __future__ import annotations

import time
import warnings
from dataclasses import dataclass

import cvxpy as cp
import numpy as np
from scipy.linalg import cholesky, matrix_balance, solve_continuous_lyapunov

from ._validation import as_positive, check_hurwitz, check_type
from .bands import Band
from .exceptions import DimensionError, InfeasibleError, SolverError, VerificationError
from .frequency import band_peak
from .kyp import kyp_matrix
from .plant import LTISystem, as_system

__all__ = [
    "GKYPResult",
    "gkyp_gamma",
    "gkyp_certify",
    "gkyp_matrix",
    "real_embedding",
    "real_embedding_parts",
    "solve_checked",
    "DEFAULT_MARGIN",
    "SOLVER_OPTIONS",
]

#: Strictness margin of every LMI (in the normalized problem, where γ ≈ 1).
DEFAULT_MARGIN = 1e-8
#: Clarabel settings used for every LMI of fdsc (tolerances well below DEFAULT_MARGIN's effect).
SOLVER_OPTIONS = {"tol_gap_abs": 1e-10, "tol_gap_rel": 1e-10, "tol_feas": 1e-10,
                  "tol_ktratio": 1e-8, "max_iter": 300}


@dataclass(frozen=True)
class GKYPResult:
    """Certificate of Lemma 1 for one system and one band.

    Parameters
    ----------
    gamma : float
        Certified gain bound: σ_max(G(jω)) < gamma on the band.
    P : (n, n) ndarray
        The certificate's P (Hermitian; complex for MF).
    Q : (n, n) ndarray
        The certificate's Q ⪰ 0 (Hermitian; complex for MF; zero for the entire range).
    band : Band
        The band the certificate holds on.
    status : str
        cvxpy status of the solve.
    max_eig : float
        Largest eigenvalue of the LMI matrix at the certificate (original coordinates); < 0.
    solve_time : float
        Wall-clock seconds of the solve (setup included).
    iterations : int
        Interior-point iterations.
    margin : float
        Strictness margin used in the normalized problem (larger than requested if
        an inaccurate solve had to be repeated).

    Notes
    -----
    Lemma 1 of the paper, paper eq. (7).
    """

    gamma: float
    P: np.ndarray
    Q: np.ndarray
    band: Band
    status: str
    max_eig: float
    solve_time: float
    iterations: int
    margin: float


def real_embedding(M: np.ndarray) -> np.ndarray:
    """Real symmetric embedding ``[[Re M, −Im M], [Im M, Re M]]`` of a Hermitian matrix.

    The embedding is negative definite if and only if M is; its eigenvalues are
    those of M, each twice.

    Parameters
    ----------
    M : (k, k) array_like
        Hermitian matrix (real or complex).

    Returns
    -------
    (2k, 2k) ndarray
        The real symmetric embedding.

    Raises
    ------
    DimensionError
        If M is not a square 2-D array.

    Notes
    -----
    How the complex Hermitian LMI of Lemma 1 on the MF band (paper eq. (7)) is posed over real
    variables.

    Examples
    --------
    >>> M = np.array([[-2, 1j], [-1j, -2]])
    >>> np.round(np.linalg.eigvalsh(real_embedding(M)), 12)
    array([-3., -3., -1., -1.])
    """
    M = np.asarray(M)
    if M.ndim != 2 or M.shape[0] != M.shape[1]:
        raise DimensionError(f"M must be a square 2-D array, but found shape {M.shape}")
    return real_embedding_parts(M.real, M.imag)


def real_embedding_parts(re: np.ndarray | cp.Expression,
                         im: np.ndarray | cp.Expression) -> np.ndarray | cp.Expression:
    """The real embedding ``[[re, −im], [im, re]]`` from real and imaginary parts.

    Parameters
    ----------
    re : (k, k) ndarray or cvxpy.Expression
        Real part (symmetric).
    im : (k, k) ndarray or cvxpy.Expression
        Imaginary part (skew-symmetric).

    Returns
    -------
    (2k, 2k) ndarray or cvxpy.Expression
        A cvxpy expression if either part is one, else an ndarray.

    Raises
    ------
    ValueError
        If the parts do not have one shape (raised by :func:`numpy.block` or
        :func:`cvxpy.bmat`).

    Notes
    -----
    ``M = re + j·im`` is negative definite if and only if its embedding is; this is how the MF
    band's complex LMI of Lemma 1 (paper eq. (7)) reaches a real solver.

    Examples
    --------
    >>> real_embedding_parts(np.eye(1), np.array([[0.5]]))
    array([[ 1. , -0.5],
           [ 0.5,  1. ]])
    """
    if isinstance(re, cp.Expression) or isinstance(im, cp.Expression):
        return cp.bmat([[re, -im], [im, re]])
    return np.block([[re, -im], [im, re]])


def _sym(E):
    return 0.5 * (E + E.T)


def _value(pair):
    re, im = pair
    return re.value if im is None else re.value + 1j * im.value


def _lmi_parts(sys, band, P, Q, g, backend):
    """``(re, im)`` of the Lemma 1 matrix; P and Q are pairs (re, im), ``im`` None for real bands."""
    terms = [] if band.kind == "EF" else [(band.psi, Q, 1)]
    return kyp_matrix(sys.A, sys.B, sys.C, sys.D, P, terms, g, backend=backend)


def gkyp_matrix(sys: LTISystem, band: Band, P: np.ndarray, Q: np.ndarray | None,
                gamma: float) -> np.ndarray:
    """Evaluate the Lemma 1 matrix at given ``P``, ``Q`` and ``gamma`` (NumPy).

    Parameters
    ----------
    sys : LTISystem
        The system ``(A, B, C, D)`` with n states and m inputs.
    band : Band
        The band (its Φ and Ψ); Ψ is not used for the entire range.
    P : (n, n) array_like
        Hermitian multiplier of Φ (complex for MF).
    Q : (n, n) array_like or None
        Hermitian multiplier of Ψ (complex for MF); ignored for the entire range, where None
        is accepted.
    gamma : float
        The gain bound; the matrix carries −γ².

    Returns
    -------
    (n + m, n + m) complex ndarray
        The Hermitian part of
        ``[A B; I 0]* (Φ⊗P + Ψ⊗Q) [A B; I 0] + [C D; 0 I]* diag(I, −γ² I) [C D; 0 I]``;
        negative definite at a certificate.

    Raises
    ------
    DimensionError
        If P or Q is not (n, n).

    Notes
    -----
    The LMI of Lemma 1, paper eq. (7), built by :func:`fdsc.kyp.kyp_matrix`; for a real band
    only the real parts of P and Q are used.

    Examples
    --------
    ``G(s) = 1/(s + 1)`` on the entire range, P = 1, γ = √2:

    >>> gkyp_matrix(LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]]), Band.entire(), [[1.0]],
    ...             None, np.sqrt(2)).real.round(12)
    array([[-1.,  1.],
           [ 1., -2.]])
    """
    P = np.asarray(P)
    Q = np.zeros_like(P) if Q is None else np.asarray(Q)
    cplx = band.is_complex
    re, im = _lmi_parts(sys, band, (P.real, P.imag if cplx else None),
                        (Q.real, Q.imag if cplx else None), float(gamma) ** 2, "numpy")
    M = re + 1j * im if cplx else re.astype(complex)
    return 0.5 * (M + M.conj().T)


def solve_checked(problem: cp.Problem, what: str) -> str:
    """Solve a cvxpy problem with Clarabel and raise on any failure, naming Clarabel's own status.

    The problem is compiled by cvxpy, solved by Clarabel directly and its result unpacked by
    cvxpy, so that Clarabel's status (``"Solved"``, ``"AlmostSolved"``,
    ``"InsufficientProgress"``, ``"PrimalInfeasible"``, …) reaches the message and the exception.

    Parameters
    ----------
    problem : cvxpy.Problem
        The problem to solve (its variables receive the solution).
    what : str
        Description used in error messages.

    Returns
    -------
    str
        The cvxpy status (``optimal`` or ``optimal_inaccurate``).

    Raises
    ------
    InfeasibleError
        If Clarabel reports (almost) primal infeasibility.
    SolverError
        On any other failure; ``exc.status`` is the cvxpy status and ``exc.solver_status``
        Clarabel's own.

    Notes
    -----
    The settings are :data:`SOLVER_OPTIONS`; they are passed to this solve only (no global
    solver options are changed).

    Examples
    --------
    >>> x = cp.Variable(name="x")
    >>> solve_checked(cp.Problem(cp.Minimize(x), [x >= 1]), "a toy LP")
    'optimal'
    >>> round(float(x.value), 6)
    1.0
    """
    opts = dict(SOLVER_OPTIONS)
    data, chain, inverse = problem.get_problem_data(cp.CLARABEL, solver_opts=opts)
    raw = chain.solver.solve_via_data(data, False, False, opts)
    raw_status = str(raw.status)
    iters = f"{int(raw.iterations)} iterations"
    try:
        with warnings.catch_warnings():
            # cvxpy warns on 'optimal_inaccurate'; that status is returned to the caller and
            # every certificate is verified independently afterwards, so the warning adds nothing
            warnings.filterwarnings("ignore", message="Solution may be inaccurate", category=UserWarning)
            problem.unpack_results(raw, chain, inverse)
    except cp.error.SolverError:
        raise SolverError(f"{what}: Clarabel stopped with status {raw_status} after {iters}",
                          cp.SOLVER_ERROR, raw_status) from None
    status = problem.status
    if status in (cp.INFEASIBLE, cp.INFEASIBLE_INACCURATE):
        raise InfeasibleError(f"{what}: the LMI is infeasible (Clarabel: {raw_status} after "
                              f"{iters})", status, raw_status)
    if status not in (cp.OPTIMAL, cp.OPTIMAL_INACCURATE):
        raise SolverError(f"{what}: no solution (Clarabel: {raw_status} after {iters})", status,
                          raw_status)
    return status


def _state_transform(sys):
    """A well-conditioned state basis: balanced realization if A is Hurwitz, else diagonal balancing.

    Returns ``T`` and ``T⁻¹`` with ``x = T x'``. The balanced realization equalizes the
    controllability and observability Gramians, which keeps the KYP certificate P near
    unit scale even for stiff closed loops (poles from −0.02 to −800 on the aircraft).
    """
    A, B, C = sys.A, sys.B, sys.C
    if sys.is_hurwitz():
        try:
            Wc = solve_continuous_lyapunov(A, -B @ B.T)
            Wo = solve_continuous_lyapunov(A.T, -C.T @ C)
            Lc = cholesky(0.5 * (Wc + Wc.T), lower=True)
            Lo = cholesky(0.5 * (Wo + Wo.T), lower=True)
            U, sv, Vt = np.linalg.svd(Lo.T @ Lc)
            if sv.min() > 1e-10 * sv.max():
                T = Lc @ Vt.T / np.sqrt(sv)[None, :]
                Tinv = (U / np.sqrt(sv)[None, :]).T @ Lo.T
                return T, Tinv
        except np.linalg.LinAlgError:
            pass
    _, (scale, _) = matrix_balance(A, permute=False, separate=True)
    return np.diag(scale), np.diag(1.0 / scale)


def _normalize(sys, band, peak):
    """Copy of ``sys`` in a well-conditioned basis with output scaled so the band peak is ≈ 1."""
    s = peak if peak > 0 else 1.0
    # balance after scaling the output, so that B and C/s are of one size and the
    # states excited by a unit disturbance at the peak are O(1): the margin then
    # costs O(margin) in γ², not O(margin · |x|²)
    T, Tinv = _state_transform(LTISystem(sys.A, sys.B, sys.C / s, sys.D / s))
    nsys = LTISystem(Tinv @ sys.A @ T, Tinv @ sys.B, sys.C @ T / s, sys.D / s)
    return nsys, Tinv, s


#: Successive margin multipliers tried when an inaccurate solve fails its verification.
MARGIN_RETRIES = (1.0, 10.0, 100.0)


def _solve(sys, band, gamma, margin):
    sys = as_system(sys)
    check_type("band", band, Band)
    margin = as_positive("margin", margin)
    check_hurwitz("sys", sys.A, "Lemma 1 as an L2-gain certificate")
    pk = band_peak(sys, band)
    if gamma is not None:
        # the lemma is lossless: a γ at or below the swept peak has no certificate. Deciding
        # this before the solver keeps the answer independent of how the solver rounds.
        if gamma <= pk.gamma:
            raise InfeasibleError(
                f"Lemma 1 on the {band.label} band at gamma={gamma:g}: no certificate exists, "
                f"sigma_max(G(jw)) reaches {pk.gamma:.6g} >= gamma at w = {pk.omega:.6g} rad/s",
                "not solved (sweep)")
    nsys, Tinv, s = _normalize(sys, band, pk.gamma)
    for k, factor in enumerate(MARGIN_RETRIES):
        try:
            return _solve_once(sys, nsys, Tinv, s, band, gamma, margin * factor)
        except VerificationError as exc:
            # an 'optimal_inaccurate' point can sit just outside the cone; a larger
            # margin moves the optimum inward at a cost of O(margin) in γ²
            if exc.status != cp.OPTIMAL_INACCURATE or k == len(MARGIN_RETRIES) - 1:
                raise


def _solve_once(sys, nsys, Tinv, s, band, gamma, margin):
    n = sys.n_states
    cplx = band.is_complex
    P = (cp.Variable((n, n), symmetric=True, name="P_re"),
         cp.Variable((n, n), name="P_im") if cplx else None)
    Q = (cp.Variable((n, n), symmetric=True, name="Q_re"),
         cp.Variable((n, n), name="Q_im") if cplx else None) if band.kind != "EF" else None
    if gamma is None:
        g = cp.Variable(name="gamma_sq", nonneg=True)
        objective = cp.Minimize(g)
    else:
        g = (float(gamma) / s) ** 2
        objective = cp.Minimize(0)
    re, im = _lmi_parts(nsys, band, P, Q, g, "cvxpy")
    cons = [_sym(real_embedding_parts(re, im) if cplx else re) << -margin * np.eye(
        (2 if cplx else 1) * (n + sys.n_inputs))]
    if Q is not None:
        QE = real_embedding_parts(*Q) if cplx else Q[0]
        cons.append(_sym(QE) >> margin * np.eye(QE.shape[0]))
    if cplx:
        cons += [P[1] + P[1].T == 0, Q[1] + Q[1].T == 0]
    prob = cp.Problem(objective, cons)
    what = f"Lemma 1 on the {band.label} band" + ("" if gamma is None else f" at gamma={gamma:g}")
    t0 = time.perf_counter()
    status = solve_checked(prob, what)
    elapsed = time.perf_counter() - t0
    # map the certificate back: x' = T⁻¹ x and z' = z / s scale the quadratic forms
    P0 = s**2 * Tinv.T @ _value(P) @ Tinv
    Q0 = s**2 * Tinv.T @ _value(Q) @ Tinv if Q is not None else np.zeros((n, n))
    g0 = s**2 * float(g.value) if gamma is None else float(gamma) ** 2
    gam = float(np.sqrt(g0))
    max_eig = float(np.linalg.eigvalsh(gkyp_matrix(sys, band, P0, Q0, gam)).max())
    if not max_eig < 0:
        raise VerificationError(f"{what}: the LMI matrix at the returned certificate has "
                                f"eigenvalue {max_eig:.3e} >= 0", status)
    if Q is not None:
        qmin = float(np.linalg.eigvalsh(0.5 * (Q0 + Q0.conj().T)).min())
        if not qmin > 0:
            raise VerificationError(f"{what}: Q is not positive definite "
                                    f"(min eigenvalue {qmin:.3e})", status)
    iters = int(prob.solver_stats.num_iters or 0)
    return GKYPResult(gam, P0, Q0, band, status, max_eig, elapsed, iters, margin)


def gkyp_gamma(sys: LTISystem, band: Band, *, margin: float = DEFAULT_MARGIN) -> GKYPResult:
    """Smallest γ that Lemma 1 certifies for ``sys`` on ``band``.

    Parameters
    ----------
    sys : LTISystem
        The closed loop (d → z); a python-control ``StateSpace`` or an ``(A, B, C, D)`` tuple
        is accepted too.
    band : Band
        LF, MF, HF or the entire range (then Lemma 1 is the bounded real lemma).
    margin : float, optional
        Strictness margin of the LMI (normalized problem); default :data:`DEFAULT_MARGIN`.

    Returns
    -------
    GKYPResult
        The smallest certified γ, its certificate and the solve's diagnostics.

    Raises
    ------
    TypeError
        If ``sys`` is not a system or ``band`` not a :class:`Band`.
    ValueError
        If ``margin`` is not a positive finite number.
    UnstableError
        If A is not Hurwitz (Lemma 1's γ bounds energy only for a stable loop).
    SolverError
        On solver failure.
    VerificationError
        If the certificate fails its check (LMI matrix not negative definite, Q not positive
        definite) even after the margin retries.

    Notes
    -----
    Lemma 1 of the paper, paper eq. (7). The result equals the band peak of
    σ_max up to solver accuracy (the lemma is lossless).

    Examples
    --------
    >>> sys = LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]])
    >>> round(gkyp_gamma(sys, Band.lf(1.0)).gamma, 6)   # peak at ω = 0
    1.0
    """
    return _solve(sys, band, None, margin)


def gkyp_certify(sys: LTISystem, band: Band, gamma: float, *,
                 margin: float = DEFAULT_MARGIN) -> GKYPResult:
    """Find a Lemma 1 certificate for a *given* γ, or raise :class:`InfeasibleError`.

    Parameters
    ----------
    sys : LTISystem
        The closed loop (d → z); a python-control ``StateSpace`` or an ``(A, B, C, D)`` tuple
        is accepted too.
    band : Band
        LF, MF, HF or the entire range.
    gamma : float
        The bound to certify (> 0).
    margin : float, optional
        Strictness margin of the LMI (normalized problem); default :data:`DEFAULT_MARGIN`.

    Returns
    -------
    GKYPResult
        With ``gamma`` equal to the argument.

    Raises
    ------
    TypeError
        If ``sys`` is not a system or ``band`` not a :class:`Band`.
    ValueError
        If ``gamma`` or ``margin`` is not a positive finite number.
    InfeasibleError
        If ``gamma`` does not exceed the swept band peak (decided before the solver runs).
    UnstableError
        If A is not Hurwitz.
    SolverError
        On solver failure.
    VerificationError
        If the certificate fails its check.

    Notes
    -----
    Lemma 1, paper eq. (7), at a fixed γ (a feasibility problem).

    Examples
    --------
    >>> sys = LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]])
    >>> gkyp_certify(sys, Band.lf(1.0), 0.9)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    fdsc.exceptions.InfeasibleError: Lemma 1 on the LF [0, 1] rad/s band at gamma=0.9: no ...
    """
    gamma = as_positive("gamma", gamma)
    return _solve(sys, band, gamma, margin)
