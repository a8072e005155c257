"""Theorem 1: the LMIs (T1-1), (T1-2) for I modes, the Q design of paper Remark 4, and the least
γ's for which the LMIs are feasible with given Q's.

For closed-loop modes ``(A_i, B, C_i, D)`` with ranges Ω_i (matrices Ψ_i, real for LF/HF) and
every ordered pair i ≠ j::

    (T1-1)  [A_i; I]ᵀ (Φ⊗P_i^s + Ψ_i⊗Q_i − Ψ_j⊗Q_j) [A_i; I] < 0,              P_i^s > 0,
    (T1-2)  [A_i B; I 0]ᵀ (Φ⊗P_i + Ψ_i⊗Q_i − Ψ_j⊗Q_j) [A_i B; I 0]
            + [C_i D; 0 I]ᵀ diag(I, −γ_i² I) [C_i D; 0 I] < 0,                  Q_i > 0,

paper eqs. (33) and (34). The Q_i are those of the switching law, paper eq. (31). (Q enters only
through differences, so its overall scale is free up to the margins.) The matrices are built by
:mod:`fdsc.kyp`, the builder shared with Lemma 1.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import cvxpy as cp
import numpy as np

from . import _defaults
from ._validation import as_count, as_positive, check_hurwitz
from .bands import Band
from .energy import check_weight
from .exceptions import VerificationError
from .kyp import Matrix, kyp_matrix, kyp_outer, kyp_weight
from .lmi import DEFAULT_MARGIN, _sym, solve_checked
from .plant import LTISystem, as_system

__all__ = ["Theorem1Result", "theorem1_matrices", "certify_q", "design_q", "DEFAULT_GAMMA_TOL"]

#: γ_tol of paper Remark 4 used by default (not printed in the paper; the book shows the sensitivity).
DEFAULT_GAMMA_TOL = _defaults.DEFAULT_GAMMA_TOL


@dataclass(frozen=True)
class Theorem1Result:
    """A solution of Theorem 1's LMIs (paper eqs. (33), (34)), called the design's certificate for
    short (the paper has no such word): it shows only that the LMIs are feasible.

    The LMIs are feasible for every pair of Hurwitz modes with large enough γ_i, and the
    theorem's statement (1) does not follow from them (the book's chapter on Theorem 1 gives an
    exact counterexample), so a solution bounds nothing on its own.

    Parameters
    ----------
    gammas : (I,) ndarray
        γ_i of (T1-2), one per mode.
    Q : list of (n, n) ndarray
        Q_i of the switching law (symmetric positive definite), one per mode.
    P : list of (n, n) ndarray
        P_i of (T1-2) (symmetric), one per mode.
    Ps : list of (n, n) ndarray
        P_i^s of (T1-1) (symmetric positive definite), one per mode.
    max_eigs : dict
        Largest eigenvalue of each (T1-1) and (T1-2) matrix at the solution, keyed
        ``("T1-1", i, j)`` / ``("T1-2", i, j)``; all < 0.
    status : str
        cvxpy status of the solve.
    solve_time : float
        Wall-clock seconds of the solve.

    Notes
    -----
    Theorem 1 of the paper, LMIs (T1-1) and (T1-2) = paper eqs. (33) and (34).
    """

    gammas: np.ndarray
    Q: list
    P: list
    Ps: list
    max_eigs: dict
    status: str
    solve_time: float


def _validate(modes, bands):
    modes = list(modes)
    bands = list(bands)
    if len(modes) < 2:
        raise ValueError(f"modes must hold at least two closed loops, found {len(modes)}")
    if len(bands) != len(modes):
        raise ValueError(f"bands must list one range per mode: {len(modes)} modes, "
                         f"{len(bands)} bands")
    modes = [as_system(m, f"modes[{k}]") for k, m in enumerate(modes)]
    if not all(isinstance(b, Band) for b in bands):
        raise TypeError("bands must be fdsc.Band")
    if any(b.is_complex for b in bands):
        raise ValueError("bands: Theorem 1 is implemented for real Ψ (LF, HF, entire); the "
                         "switching law sees only Re Ψ of an MF range")
    n = modes[0].n_states
    for k, m in enumerate(modes):
        if m.A.shape != (n, n) or not np.array_equal(m.B, modes[0].B) or not np.array_equal(
                m.D, modes[0].D) or m.C.shape != modes[0].C.shape:
            raise ValueError(f"modes must share B, D and the state and output dimensions; mode {k} "
                             "differs from mode 0")
        # (T1-1) mixes the law's Ψ terms into the Lyapunov inequality, so it can hold for a mode
        # that is not Hurwitz; the γ's bound energy only if every mode is stable on its own
        check_hurwitz(f"modes[{k}]", m.A, "Theorem 1's LMIs")
    return modes, bands


def theorem1_matrices(mode_i: LTISystem, band_i: Band, band_j: Band, Ps_i: Matrix, P_i: Matrix,
                      Q_i: Matrix, Q_j: Matrix, gamma_i: float | cp.Expression,
                      backend: str = "numpy") -> tuple[Matrix, Matrix]:
    """The (T1-1) and (T1-2) matrices for one ordered pair (i, j) (NumPy values or cvxpy expressions).

    Parameters
    ----------
    mode_i : LTISystem
        Closed loop ``(A_i, B, C_i, D)`` of mode i, with n states and m inputs.
    band_i : Band
        Range Ω_i of mode i (its Ψ_i; real for LF, HF and the entire range).
    band_j : Band
        Range Ω_j of the other mode j.
    Ps_i : (n, n) array_like or cvxpy.Expression
        P_i^s of (T1-1).
    P_i : (n, n) array_like or cvxpy.Expression
        P_i of (T1-2).
    Q_i : (n, n) array_like or cvxpy.Expression
        Q_i of the switching law for mode i.
    Q_j : (n, n) array_like or cvxpy.Expression
        Q_j of the switching law for mode j.
    gamma_i : float or cvxpy.Expression
        With ``backend="numpy"`` the gain γ_i (squared here); with ``backend="cvxpy"`` the
        variable g = γ_i² itself, so that the LMI stays affine.
    backend : {"numpy", "cvxpy"}, optional
        Build values or cvxpy expressions (see :func:`fdsc.kyp.kyp_weight`).

    Returns
    -------
    M1 : (n, n) ndarray or cvxpy.Expression
        ``[A_i; I]ᵀ (Φ⊗P_i^s + Ψ_i⊗Q_i − Ψ_j⊗Q_j) [A_i; I]``.
    M2 : (n + m, n + m) ndarray or cvxpy.Expression
        ``[A_i B; I 0]ᵀ (Φ⊗P_i + Ψ_i⊗Q_i − Ψ_j⊗Q_j) [A_i B; I 0]
        + [C_i D; 0 I]ᵀ diag(I, −γ_i² I) [C_i D; 0 I]``.

    Raises
    ------
    ValueError
        If ``backend`` is not ``"numpy"`` or ``"cvxpy"``.
    DimensionError
        If a matrix does not match the mode's number of states.

    Notes
    -----
    Theorem 1's (T1-1) and (T1-2), paper eqs. (33) and (34); Theorem 1 asks both to be negative
    definite. Only the real part of Ψ is used (the function is meant for real Ψ).

    Examples
    --------
    ``[A; I]ᵀ W [A; I]`` with A = −1 and W = [[−0.11, 1], [1, 1.1]]:

    >>> from fdsc import LTISystem, Band
    >>> mode = LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]])
    >>> M1, M2 = theorem1_matrices(mode, Band.lf(1.0), Band.hf(10.0), [[1.0]], [[1.0]],
    ...                            [[0.1]], [[0.01]], 2.0)
    >>> M1.round(12)
    array([[-1.01]])
    >>> M2.round(12)
    array([[-0.01,  1.11],
           [ 1.11, -4.11]])
    """
    terms = [(band_i.psi, Q_i, 1), (band_j.psi, Q_j, -1)]
    W1, _ = kyp_weight(Ps_i, terms, backend=backend)
    M1 = kyp_outer(W1, mode_i.A)
    g = gamma_i if backend == "cvxpy" else gamma_i**2
    M2, _ = kyp_matrix(mode_i.A, mode_i.B, mode_i.C, mode_i.D, P_i, terms, g, backend=backend)
    return M1, M2


def _problem(modes, bands, margin, Q_fixed=None):
    n = modes[0].n_states
    I = len(modes)  # noqa: E741  (the paper's symbol)
    Ps = [cp.Variable((n, n), symmetric=True, name=f"Ps_{i}") for i in range(I)]
    P = [cp.Variable((n, n), symmetric=True, name=f"P_{i}") for i in range(I)]
    g = [cp.Variable(name=f"gamma_sq_{i}", nonneg=True) for i in range(I)]
    Q = ([cp.Variable((n, n), symmetric=True, name=f"Q_{i}") for i in range(I)]
         if Q_fixed is None else [np.asarray(q) for q in Q_fixed])
    cons = [Ps[i] >> margin * np.eye(n) for i in range(I)]
    if Q_fixed is None:
        cons += [q >> margin * np.eye(n) for q in Q]
    for i in range(I):
        for j in range(I):
            if i == j:
                continue
            M1, M2 = theorem1_matrices(modes[i], bands[i], bands[j], Ps[i], P[i], Q[i], Q[j], g[i],
                                       backend="cvxpy")
            cons += [_sym(M1) << -margin * np.eye(n), _sym(M2) << -margin * np.eye(M2.shape[0])]
    return Ps, P, Q, g, cons


def _verify(modes, bands, Ps, P, Q, gammas, status, what, scale=1.0):
    """Evaluate every LMI at the solution; eigenvalues are reported divided by ``scale``."""
    eigs = {}
    for i in range(len(modes)):
        for j in range(len(modes)):
            if i == j:
                continue
            M1, M2 = theorem1_matrices(modes[i], bands[i], bands[j], Ps[i], P[i], Q[i], Q[j],
                                       gammas[i])
            eigs[("T1-1", i, j)] = float(np.linalg.eigvalsh(_sym(M1)).max()) / scale
            eigs[("T1-2", i, j)] = float(np.linalg.eigvalsh(_sym(M2)).max()) / scale
    bad = {k: v for k, v in eigs.items() if not v < 0}
    if bad:
        raise VerificationError(f"{what}: LMIs not negative definite at the solution: {bad}", status)
    if min(float(np.linalg.eigvalsh(p).min()) for p in Ps) <= 0:
        raise VerificationError(f"{what}: P^s is not positive definite", status)
    return eigs


def _result(modes, bands, Ps, P, Q, g, prob, what, scale=1.0):
    """Solve, undo the data scaling (P, P^s and γ² scale with ``scale``) and verify unscaled."""
    t0 = time.perf_counter()
    status = solve_checked(prob, what)
    elapsed = time.perf_counter() - t0
    Psv = [scale * v.value for v in Ps]
    Pv = [scale * v.value for v in P]
    Qv = [scale * q.value if isinstance(q, cp.Variable) else scale * q for q in Q]
    gam = np.sqrt(scale * np.array([max(float(v.value), 0.0) for v in g]))
    eigs = _verify(modes, bands, Psv, Pv, Qv, gam, status, what, scale=scale)
    return Theorem1Result(gam, Qv, Pv, Psv, eigs, status, elapsed)


def certify_q(modes: list[LTISystem], bands: list[Band], Q: list[np.ndarray], *,
              margin: float = DEFAULT_MARGIN) -> Theorem1Result:
    """The smallest γ_i for which Theorem 1's LMIs are feasible with *given* Q_i (the sum of the
    γ_i² minimized).

    Parameters
    ----------
    modes : list of LTISystem
        Closed loops of the modes (I ≥ 2), sharing B and D.
    bands : list of Band
        Range Ω_i of each mode's law term (real Ψ).
    Q : list of (n, n) array_like
        The Q_i of the switching law (symmetric positive definite).
    margin : float, optional
        Strictness margin of every LMI (in the problem scaled to O(1) data); default
        :data:`~fdsc.lmi.DEFAULT_MARGIN`.

    Returns
    -------
    Theorem1Result
        The γ_i, the given Q_i and the certificate.

    Raises
    ------
    ValueError
        If fewer than two modes are given, the lists differ in length, the modes do not share
        B and D, a band is complex (MF), a Q_i is not symmetric positive definite, or
        ``margin`` is not positive.
    TypeError
        If a band is not a :class:`~fdsc.Band`.
    UnstableError
        If a mode is not Hurwitz (named with its eigenvalue).
    InfeasibleError
        If (T1-1) or (T1-2) cannot hold for these Q's whatever the γ's.
    SolverError
        On any other solver failure.
    VerificationError
        If an LMI is not negative definite at the returned solution.

    Notes
    -----
    Theorem 1, paper eqs. (33) and (34), for every ordered pair i ≠ j, with the Q_i of the
    switching law (paper eq. (31)) fixed. The LMIs are homogeneous, so they are solved with the
    Q_i and CᵀC scaled to O(1) and the certificate is scaled back.

    Examples
    --------
    >>> from fdsc import LTISystem, Band
    >>> modes = [LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]]),
    ...          LTISystem([[-3.0]], [[1.0]], [[1.0]], [[0.0]])]
    >>> res = certify_q(modes, [Band.lf(1.0), Band.hf(10.0)], [np.eye(1), 0.01 * np.eye(1)])
    >>> bool(np.all(res.gammas > 0)), all(v < 0 for v in res.max_eigs.values())
    (True, True)
    """
    modes, bands = _validate(modes, bands)
    n = modes[0].n_states
    if not isinstance(Q, list | tuple) or len(Q) != len(modes):
        raise ValueError(f"Q must list one matrix per mode ({len(modes)}), found "
                         f"{len(Q) if isinstance(Q, list | tuple) else type(Q).__name__}")
    Q = [check_weight(q, n) for q in Q]
    margin = as_positive("margin", margin)
    # the LMIs are homogeneous in (P^s, P, Q, γ², CᵀC): solve with Q/s and C/√s so that the
    # solver sees O(1) data even for the paper's Q_1 ~ 1e6, then scale the certificate back
    s = max(float(np.abs(q).max()) for q in Q)
    smodes = [LTISystem(m.A, m.B, m.C / np.sqrt(s), m.D / np.sqrt(s)) for m in modes]
    Ps, P, Qs, g, cons = _problem(smodes, bands, margin, Q_fixed=[q / s for q in Q])
    prob = cp.Problem(cp.Minimize(cp.sum(cp.hstack(g))), cons)
    return _result(modes, bands, Ps, P, Qs, g, prob, "Theorem 1 with given Q's", scale=s)


def design_q(modes: list[LTISystem], bands: list[Band], in_band: int, *,
             gamma_tol: float = DEFAULT_GAMMA_TOL,
             margin: float = DEFAULT_MARGIN) -> Theorem1Result:
    """The Q design of paper Remark 4: fix γ_j = γ_tol for every j ≠ in_band, minimize γ_in_band.

    Parameters
    ----------
    modes : list of LTISystem
        Closed loops of the modes (I ≥ 2), sharing B and D.
    bands : list of Band
        Range Ω_i of each mode's law term (real Ψ).
    in_band : int
        Index of the in-band mode i (0-based).
    gamma_tol : float, optional
        γ_tol of paper Remark 4 (> 0); default :data:`DEFAULT_GAMMA_TOL` (the paper prints none).
    margin : float, optional
        Strictness margin of every LMI; default :data:`~fdsc.lmi.DEFAULT_MARGIN`.

    Returns
    -------
    Theorem1Result
        The designed Q_i (for the switching law, paper eq. (31)), the γ_i and the certificate.

    Raises
    ------
    ValueError
        If fewer than two modes are given, the lists differ in length, the modes do not share
        B and D, a band is complex (MF), ``in_band`` is not a mode index, or ``gamma_tol`` or
        ``margin`` is not positive.
    TypeError
        If a band is not a :class:`~fdsc.Band`.
    UnstableError
        If a mode is not Hurwitz.
    InfeasibleError
        If no Q's satisfy Theorem 1 with this γ_tol.
    SolverError
        On any other solver failure.
    VerificationError
        If an LMI is not negative definite at the returned solution.

    Notes
    -----
    Paper Remark 4: minimize γ_i subject to Theorem 1's (T1-1) and (T1-2), paper eqs. (33) and
    (34), with γ_j = γ_tol for j ≠ i, over P_i^s, P_i, Q_i.

    Examples
    --------
    Mode 1 (``1/(s + 3)``) is in band on HF [10, ∞); its γ reaches the HF peak ``1/√109``:

    >>> from fdsc import LTISystem, Band
    >>> modes = [LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]]),
    ...          LTISystem([[-3.0]], [[1.0]], [[1.0]], [[0.0]])]
    >>> res = design_q(modes, [Band.lf(1.0), Band.hf(10.0)], 1, gamma_tol=2.0)
    >>> round(float(res.gammas[0]), 6), round(float(res.gammas[1]), 4), round(1 / 109**0.5, 4)
    (2.0, 0.0958, 0.0958)
    """
    modes, bands = _validate(modes, bands)
    in_band = as_count("in_band", in_band, 0)
    if in_band >= len(modes):
        raise ValueError(f"in_band must be a mode index in [0, {len(modes)}), found {in_band}")
    gamma_tol = as_positive("gamma_tol", gamma_tol)
    margin = as_positive("margin", margin)
    Ps, P, Q, g, cons = _problem(modes, bands, margin)
    cons += [g[j] == gamma_tol**2 for j in range(len(modes)) if j != in_band]
    prob = cp.Problem(cp.Minimize(g[in_band]), cons)
    return _result(modes, bands, Ps, P, Q, g, prob, f"paper Remark 4 design (gamma_tol={gamma_tol:g})")
