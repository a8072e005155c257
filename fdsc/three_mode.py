"""Theorem 1 for laws with second-order scores (on ``[ẍ; ẋ; x]``), any number of modes.

The law picks ``σ = argmax_k vᵀW_k v`` with ``v = [ẍ; ẋ; x]`` and ``W_k = m_k ⊗ Q_k``
(:mod:`fdsc.scores`). In mode i, ``ẋ = A_i x + B d`` and ``ẍ = A_i² x + A_i B d + B ḋ``, so

    v = G_i [x; d; ḋ],   G_i = [[A_i², A_iB, B], [A_i, B, 0], [I, 0, 0]],

and the proof of paper Theorem 1 goes through with ḋ as a second input:

* (T1-1') for d = 0, ``v = N_i x`` with ``N_i = [A_i²; A_i; I]``, and
  ``A_iᵀP^s_i + P^s_iA_i + N_iᵀ(W_i − W_j)N_i ≺ 0``, ``P^s_i ≻ 0``, for all j ≠ i;
* (T1-2') with ``F_i = [[A_i, B, 0], [I, 0, 0]]`` and ``H_i = [C_i, D, 0]``,

      F_iᵀ(Φ⊗P_i)F_i + G_iᵀ(W_i − W_j)G_i + H_iᵀH_i − diag(0, γ_i² I, η_i² I) ≺ 0,  j ≠ i.

Multiplying (T1-2') by ``[x; d; ḋ]`` and integrating over a window where mode i is active and
therefore ``vᵀW_iv ≥ vᵀW_jv``, as in the paper's proof of statement (2):
``∫zᵀz < γ_i²∫dᵀd + η_i²∫ḋᵀḋ + (terms of V at the window ends)``. For a tone at ω,
``∫ḋ² = ω²∫d²``: the bound is ``γ_i² + η_i²ω²``. Where no score has an ẍ block (order 1), ḋ does not
enter and η_i is only the margin.

**(T1-1') holds for any Q's** when every A_i is Hurwitz: with
``A_iᵀP^s_i + P^s_iA_i = −β_i I`` and ``β_i > max_j λ_max(N_iᵀ(W_i − W_j)N_i)``, P^s_i ≻ 0 and every
(T1-1') matrix is ``−β_i I + N_iᵀ(W_i − W_j)N_i ≺ 0``. This module builds P^s_i so (no solve), and
only (T1-2') constrains the Q's. The same holds for the printed (T1-1) of paper eq. (33).

**Numerics.** A fast mode (eigenvalue −784 for the aircraft's K_f2) puts A_i² ~ 6·10⁵ into G_i,
and the LMI as written stops Clarabel (NumericalError). Each (T1-2') matrix is therefore posed
after the congruence ``[x; d; ḋ] = T_i[ξ; d; ḋ]`` with ``x = V_i D_i ξ − A_i⁻¹B d`` (V_i the real
eigenvector basis of A_i, ``D_i = diag(1/max(1, |λ_k|)²)``): then ``ẋ = A_iV_iD_i ξ`` and
``ẍ = A_i²V_iD_i ξ + B ḋ`` have entries of order one. A congruence preserves definiteness, so the
certificate is the same; it is verified at the solution and, independently, by a frequency sweep
of the steady-state inequality that (T1-2') implies (KYP lemma).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import cvxpy as cp
import numpy as np
from scipy.linalg import cdf2rdf, solve_continuous_lyapunov

from ._validation import as_count, as_matrix, as_nonnegative, as_positive, check_hurwitz
from .bands import PHI
from .energy import check_weight
from .exceptions import VerificationError
from .lmi import DEFAULT_MARGIN, _sym, solve_checked
from .plant import LTISystem, as_system

__all__ = ["ScoreCertificate", "score_lmi_blocks", "certify_scores", "design_scores",
           "pair_sweep", "DEFAULT_ETA_TOL"]

#: Cap on every η_i (the ḋ gain of (T1-2')) in :func:`design_scores`: with γ_tol = 10 the ḋ
#: term ``η²ω²`` of a tone at 10 rad/s adds at most the γ_tol² term again.
DEFAULT_ETA_TOL = 1.0
#: Eigenvector bases less well conditioned than this are not used for the congruence.
_MAX_COND = 1e8


@dataclass(frozen=True)
class ScoreCertificate:
    """Certificate of (T1-1') and (T1-2') for a law with scores ``W_k = m_k ⊗ Q_k``.

    Parameters
    ----------
    gammas : (I,) ndarray
        γ_i of (T1-2') (the d gain).
    etas : (I,) ndarray
        η_i of (T1-2') (the ḋ gain).
    Q : list of (n, n) ndarray
        The Q_k.
    factors : list of (3, 3) ndarray
        The score factors m_k (:func:`fdsc.scores.score_matrix`).
    P, Ps : list of (n, n) ndarray
        P_i of (T1-2') and P^s_i of (T1-1').
    max_eigs : dict
        Largest eigenvalue of every (T1-1') and (T1-2') matrix at the solution, keyed
        ``("T1-1", i, j)`` / ``("T1-2", i, j)`` ((T1-2') in the scaled coordinates); all < 0.
    sweep_max : float
        Largest eigenvalue over a frequency sweep of the steady-state inequalities implied by
        (T1-2') (each normalized by its data); < 0.
    status : str
        cvxpy status of the solve.
    solve_time : float
        Wall-clock seconds of the solve.
    """

    gammas: np.ndarray
    etas: np.ndarray
    Q: list
    factors: list
    P: list
    Ps: list
    max_eigs: dict
    sweep_max: float
    status: str
    solve_time: float

    @property
    def weights(self) -> list:
        """The law's weights ``W_k = m_k ⊗ Q_k`` (3n × 3n), for ``law_weights`` of the simulators."""
        return [np.kron(m, q) for m, q in zip(self.factors, self.Q, strict=True)]

    def bound(self, i: int, omega: float) -> float:
        """The energy-ratio bound ``γ_i² + η_i²ω²`` of mode i for a tone at ω.

        Parameters
        ----------
        i : int
            Mode index (0-based).
        omega : float
            Frequency of the tone in rad/s.

        Returns
        -------
        float
        """
        return float(self.gammas[i] ** 2 + self.etas[i] ** 2 * omega**2)


def _congruence(A, B):
    """T with x = V D ξ − A⁻¹B d (see the module docstring); identity on d and ḋ."""
    n, m = B.shape
    lam, V = np.linalg.eig(A)
    if np.iscomplexobj(lam) and np.any(lam.imag != 0):
        lam_r, V = cdf2rdf(lam, V)
        mag = np.abs(np.linalg.eigvals(lam_r))
    else:
        V, mag = V.real, np.abs(lam.real)
    if np.linalg.cond(V) > _MAX_COND:
        V, mag = np.eye(n), np.ones(n)
    T = np.eye(n + 2 * m)
    T[:n, :n] = V @ np.diag(1.0 / np.maximum(1.0, mag) ** 2)
    T[:n, n:n + m] = -np.linalg.solve(A, B)
    return T


def score_lmi_blocks(mode: LTISystem) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The constant blocks of (T1-2') for one mode, already multiplied by the congruence T_i.

    Parameters
    ----------
    mode : LTISystem
        Closed loop ``(A_i, B, C_i, D)`` (A_i Hurwitz).

    Returns
    -------
    G : (3n, n + 2m) ndarray
        ``G_i T_i``: maps ``[ξ; d; ḋ]`` to ``v = [ẍ; ẋ; x]``.
    F : (2n, n + 2m) ndarray
        ``F_i T_i``: maps to ``[ẋ; x]`` (the storage term Φ⊗P_i).
    H : (p, n + 2m) ndarray
        ``H_i T_i``: maps to z.
    T : (n + 2m, n + 2m) ndarray
        The congruence.

    Raises
    ------
    UnstableError
        If A_i is not Hurwitz.

    Examples
    --------
    >>> mode = LTISystem([[-2.0]], [[1.0]], [[1.0]], [[0.0]])
    >>> G, F, H, T = score_lmi_blocks(mode)
    >>> G          # x = ξ/4 + d/2: ẍ = ξ + ḋ, ẋ = −ξ/2, x = ξ/4 + d/2
    array([[ 1.  ,  0.  ,  1.  ],
           [-0.5 ,  0.  ,  0.  ],
           [ 0.25,  0.5 ,  0.  ]])
    """
    mode = as_system(mode, "mode")
    A, B, C, D = mode.A, mode.B, mode.C, mode.D
    check_hurwitz("mode", A, "the score certificate")
    n, m = B.shape
    Z = np.zeros((n, m))
    G = np.block([[A @ A, A @ B, B], [A, B, Z], [np.eye(n), Z, Z]])
    F = np.block([[A, B, Z], [np.eye(n), Z, Z]])
    H = np.hstack([C, D, np.zeros((C.shape[0], m))])
    T = _congruence(A, B)
    return G @ T, F @ T, H @ T, T


def _validate(modes, factors):
    modes = list(modes)
    if len(modes) < 2:
        raise ValueError(f"modes must hold at least two closed loops, found {len(modes)}")
    modes = [as_system(m, f"modes[{k}]") for k, m in enumerate(modes)]
    if not isinstance(factors, list | tuple) or len(factors) != len(modes):
        raise ValueError(f"factors must list one (3, 3) score factor per mode ({len(modes)})")
    out = []
    for k, m in enumerate(factors):
        m = np.asarray(as_matrix(f"factors[{k}]", m, (3, 3)))
        if not np.allclose(m, m.T, rtol=1e-12, atol=1e-12 * max(1.0, float(np.abs(m).max()))):
            raise ValueError(f"factors[{k}] must be symmetric")
        out.append(m)
    n = modes[0].n_states
    for k, md in enumerate(modes):
        if md.A.shape != (n, n) or not np.array_equal(md.B, modes[0].B) or not np.array_equal(
                md.D, modes[0].D) or md.C.shape != modes[0].C.shape:
            raise ValueError(f"modes must share B, D and the state and output dimensions; mode {k} "
                             "differs from mode 0")
        check_hurwitz(f"modes[{k}]", md.A, "the score certificate")
    return modes, out


def _lmi(blocks, Wd, P, g, h, n, m, backend):
    G, F, H, T = blocks
    kron = cp.kron if backend == "cvxpy" else np.kron
    dd = np.zeros(n + 2 * m)
    dd[n:n + m] = 1.0
    ee = np.zeros(n + 2 * m)
    ee[n + m:] = 1.0
    # the supply −diag(0, g I, h I) in the scaled coordinates: Tᵀ diag(·) T
    Eg, Eh = T.T @ np.diag(dd) @ T, T.T @ np.diag(ee) @ T
    return F.T @ kron(PHI, P) @ F + G.T @ Wd @ G + H.T @ H - g * Eg - h * Eh


def _lyapunov_ps(modes, factors, Q):
    """P^s_i closing (T1-1') for every j (module docstring) and the largest eigenvalues."""
    Ps, eigs = [], {}
    for i, md in enumerate(modes):
        A = md.A
        N = np.vstack([A @ A, A, np.eye(A.shape[0])])
        S = {j: _sym(N.T @ (np.kron(factors[i], Q[i]) - np.kron(factors[j], Q[j])) @ N)
             for j in range(len(modes)) if j != i}
        top = max(float(np.linalg.eigvalsh(s).max()) for s in S.values())
        scale = max(1.0, max(float(np.abs(s).max()) for s in S.values()))
        beta = max(top, 0.0) + 1e-3 * scale
        P = _sym(solve_continuous_lyapunov(A.T, -beta * np.eye(A.shape[0])))
        Ps.append(P)
        for j, s in S.items():
            eigs[("T1-1", i, j)] = float(np.linalg.eigvalsh(_sym(A.T @ P + P @ A) + s).max())
    return Ps, eigs


def pair_sweep(mode_i: LTISystem, m_i, m_j, Q_i, Q_j, gamma_i: float, eta_i: float,
               omega) -> np.ndarray:
    """Largest eigenvalue of the steady-state form of (T1-2') for the pair (i, j) over ω.

    At a frequency ω with mode i frozen, ``[x; d; ḋ] = [X_i(ω)d; d; ḋ]`` with
    ``X_i = (jωI − A_i)⁻¹B`` and d, ḋ independent; (T1-2') implies (KYP lemma) that the
    2m × 2m Hermitian matrix M(ω) of this quadratic form is negative definite. M is normalized by
    its diagonal, ``D^{-1/2} M D^{-1/2}`` with ``D = |diag M|`` (a congruence: the sign of every
    eigenvalue is kept, and values are O(1) whatever the scales of d and ḋ).

    Parameters
    ----------
    mode_i : LTISystem
        Closed loop of mode i.
    m_i, m_j : (3, 3) array_like
        Score factors.
    Q_i, Q_j : (n, n) array_like
        The Q's.
    gamma_i, eta_i : float
        The gains of (T1-2').
    omega : (K,) array_like
        Frequencies in rad/s (≥ 0; ``inf`` allowed).

    Returns
    -------
    (K,) ndarray
        Largest eigenvalue of the normalized M(ω) at each ω.

    Examples
    --------
    >>> from fdsc import Band
    >>> from fdsc.scores import score_matrix
    >>> mode = LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]])
    >>> lf, hf = score_matrix(Band.lf(1.0)), score_matrix(Band.hf(10.0))
    >>> bool(np.all(pair_sweep(mode, lf, hf, [[0.01]], [[0.01]], 2.0, 0.1, [0, 1, 10, np.inf]) < 0))
    True
    """
    mode_i = as_system(mode_i, "mode_i")
    Wd = np.kron(np.asarray(m_i), np.asarray(Q_i)) - np.kron(np.asarray(m_j), np.asarray(Q_j))
    return _sweep(mode_i, Wd, gamma_i, eta_i, omega)


def _sweep(mode_i, Wd, gamma_i, eta_i, omega):
    A, B, C, D = mode_i.A, mode_i.B, mode_i.C, mode_i.D
    n, m = B.shape
    out = []
    for w in np.atleast_1d(np.asarray(omega, dtype=float)):
        X = np.zeros((n, m), complex) if np.isinf(w) else np.linalg.solve(1j * w * np.eye(n) - A, B)
        xd = A @ X + B
        Zm = np.zeros((n, m))
        V = np.block([[A @ xd, B], [xd, Zm], [X, Zm]])
        Z = np.hstack([C @ X + D, np.zeros((C.shape[0], m))])
        M = V.conj().T @ Wd @ V + Z.conj().T @ Z
        M -= np.diag(np.r_[np.full(m, gamma_i**2), np.full(m, eta_i**2)])
        M = 0.5 * (M + M.conj().T)
        r = 1.0 / np.sqrt(np.maximum(np.abs(np.diag(M).real), np.finfo(float).tiny))
        out.append(float(np.linalg.eigvalsh(r[:, None] * M * r[None, :]).max()))
    return np.array(out)


#: Sweep of the a-posteriori check: 0, a log grid and ∞.
_SWEEP = np.r_[0.0, np.logspace(-4, 5, 721), np.inf]


def _differences(factors, Q, i, backend):
    """The law terms ``W_i − W_j`` of mode i's (T1-2'), one per j ≠ i, in the order of j."""
    kron = cp.kron if backend == "cvxpy" else np.kron
    return [kron(factors[i], Q[i]) - kron(factors[j], Q[j]) for j in range(len(Q)) if j != i]


def _solve(modes, factors, Q, g, h, P, cons, objective, margin, what):
    n, m = modes[0].n_states, modes[0].B.shape[1]
    blocks = [score_lmi_blocks(md) for md in modes]
    I = len(modes)  # noqa: E741  (the paper's symbol)
    for i in range(I):
        for Wd in _differences(factors, Q, i, "cvxpy"):
            M = _lmi(blocks[i], Wd, P[i], g[i], h[i], n, m, "cvxpy")
            cons.append(_sym(M) << -margin * np.eye(n + 2 * m))
    prob = cp.Problem(cp.Minimize(objective), cons)
    t0 = time.perf_counter()
    status = solve_checked(prob, what)
    elapsed = time.perf_counter() - t0
    Qv = [_sym(q.value if isinstance(q, cp.Variable) else np.asarray(q)) for q in Q]
    Pv = [_sym(p.value) for p in P]
    gv = np.array([max(float(x.value), 0.0) for x in g])
    hv = np.array([max(float(x.value), 0.0) for x in h])
    if min(float(np.linalg.eigvalsh(q).min()) for q in Qv) <= 0:
        raise VerificationError(f"{what}: a Q is not positive definite at the solution", status)
    eigs, sweep = {}, -np.inf
    for i in range(I):
        others = [j for j in range(I) if j != i]
        for k, Wd in enumerate(_differences(factors, Qv, i, "numpy")):
            key = ("T1-2", i, others[k])
            M = _lmi(blocks[i], Wd, Pv[i], gv[i], hv[i], n, m, "numpy")
            eigs[key] = float(np.linalg.eigvalsh(_sym(M)).max())
            sweep = max(sweep, float(_sweep(modes[i], Wd, np.sqrt(gv[i]), np.sqrt(hv[i]),
                                            _SWEEP).max()))
    Ps, e1 = _lyapunov_ps(modes, factors, Qv)
    eigs.update(e1)
    bad = {k: v for k, v in eigs.items() if not v < 0}
    if bad:
        raise VerificationError(f"{what}: LMIs not negative definite at the solution: {bad}", status)
    if not sweep < 0:
        raise VerificationError(f"{what}: the frequency sweep of (T1-2') finds a non-negative "
                                f"eigenvalue ({sweep:.3g})", status)
    return ScoreCertificate(np.sqrt(gv), np.sqrt(hv), Qv, [np.array(f) for f in factors], Pv, Ps,
                            eigs, sweep, status, elapsed)


def _variables(modes):
    n = modes[0].n_states
    I = len(modes)  # noqa: E741
    P = [cp.Variable((n, n), symmetric=True, name=f"P_{i}") for i in range(I)]
    g = [cp.Variable(name=f"gamma_sq_{i}", nonneg=True) for i in range(I)]
    h = [cp.Variable(name=f"eta_sq_{i}", nonneg=True) for i in range(I)]
    return P, g, h


def certify_scores(modes: list[LTISystem], factors: list, Q: list, *, rate_weight: float,
                   margin: float = DEFAULT_MARGIN) -> ScoreCertificate:
    """The smallest ``Σ_i (γ_i² + rate_weight·η_i²)`` that (T1-2') certifies for given Q's.

    Parameters
    ----------
    modes : list of LTISystem
        Closed loops (I ≥ 2, Hurwitz, sharing B and D).
    factors : list of (3, 3) array_like
        Score factors m_k (:func:`fdsc.scores.score_matrix`).
    Q : list of (n, n) array_like
        The Q_k (symmetric positive definite).
    rate_weight : float
        Weight (≥ 0, rad²/s²) of the η_i² in the objective (e.g. the square of the highest
        frequency of interest: the objective is then the sum of the bounds ``γ_i² + η_i²ω²``
        there).
    margin : float, optional
        Strictness margin of every LMI.

    Returns
    -------
    ScoreCertificate

    Raises
    ------
    ValueError
        On inconsistent lists, modes that do not share B and D, a Q that is not symmetric
        positive definite, or a non-symmetric factor.
    UnstableError
        If a mode is not Hurwitz.
    InfeasibleError, SolverError, VerificationError
        On solver failure or a certificate that fails its checks.

    Notes
    -----
    (T1-1') and (T1-2') of the module docstring: paper eqs. (33) and (34) with the law's scores
    on ``[ẍ; ẋ; x]`` and ḋ as a second input.

    Unlike the law, the certificate depends on the Q's common scale: small Q's leave each mode's
    own H∞ norm, large ones weigh the law's terms.

    Examples
    --------
    >>> from fdsc import Band
    >>> from fdsc.scores import score_matrix
    >>> modes = [LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]]),
    ...          LTISystem([[-3.0]], [[1.0]], [[1.0]], [[0.0]])]
    >>> cert = certify_scores(modes, [score_matrix(Band.lf(1.0)),
    ...                               score_matrix(Band.mf(1.0, 10.0), order=2)],
    ...                       [0.01 * np.eye(1), 1e-4 * np.eye(1)], rate_weight=100.0)
    >>> bool(cert.sweep_max < 0), all(v < 0 for v in cert.max_eigs.values())
    (True, True)
    """
    modes, factors = _validate(modes, factors)
    n = modes[0].n_states
    if not isinstance(Q, list | tuple) or len(Q) != len(modes):
        raise ValueError(f"Q must list one matrix per mode ({len(modes)})")
    Q = [check_weight(q, n) for q in Q]
    rate_weight = as_nonnegative("rate_weight", rate_weight)
    margin = as_positive("margin", margin)
    P, g, h = _variables(modes)
    obj = cp.sum(cp.hstack(g)) + rate_weight * cp.sum(cp.hstack(h))
    return _solve(modes, factors, Q, g, h, P, [], obj, margin, "score certificate with given Q's")


def design_scores(modes: list[LTISystem], factors: list, in_band: int, *, rate_weight: float,
                  gamma_tol: float = 10.0, eta_tol: float = DEFAULT_ETA_TOL,
                  q_floor: float | None = None,
                  margin: float = DEFAULT_MARGIN) -> ScoreCertificate:
    """Q design in the spirit of paper Remark 4 for scores on ``[ẍ; ẋ; x]``.

    Minimize ``γ_in² + rate_weight·η_in²`` subject to (T1-2') for every ordered pair, ``γ_j = γ_tol``
    for j ≠ in_band and ``η_k ≤ η_tol`` for every k.

    Parameters
    ----------
    modes : list of LTISystem
        Closed loops (I ≥ 2, Hurwitz, sharing B and D).
    factors : list of (3, 3) array_like
        Score factors m_k (:func:`fdsc.scores.score_matrix`).
    in_band : int
        Index (0-based) of the in-band mode.
    gamma_tol : float, optional
        γ_tol of paper Remark 4 (> 0).
    eta_tol : float, optional
        Cap on every η_k (> 0).
    rate_weight : float
        Weight (≥ 0, rad²/s²) of η_in² in the objective. A disturbance confined to the in-band
        range below ω_top has ``∫ḋ² ≤ ω_top²∫d²``; with ``rate_weight = ω_top²`` the objective is
        its energy-ratio bound ``γ_in² + η_in²ω_top²``. (With 0 the design may trade all of γ_in
        for η_in, which bounds nothing useful.)
    q_floor : float, optional
        If given, ``Q_in ⪰ q_floor·I`` (the design otherwise drives Q_in to the margin, and the
        in-band score to zero).
    margin : float, optional
        Strictness margin of every LMI (and the lower bound of every Q).

    Returns
    -------
    ScoreCertificate

    Raises
    ------
    ValueError
        On inconsistent lists, an invalid ``in_band``, or non-positive tolerances.
    UnstableError
        If a mode is not Hurwitz.
    InfeasibleError, SolverError, VerificationError
        On solver failure or a certificate that fails its checks.

    Notes
    -----
    Paper Remark 4 (paper eq. (53)) with paper eqs. (33) and (34) replaced by (T1-1') and (T1-2')
    of the module docstring.

    Examples
    --------
    >>> from fdsc import Band
    >>> from fdsc.scores import score_matrix
    >>> modes = [LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]]),
    ...          LTISystem([[-3.0]], [[1.0]], [[1.0]], [[0.0]])]
    >>> f = [score_matrix(Band.lf(1.0)), score_matrix(Band.mf(1.0, 10.0), order=2)]
    >>> cert = design_scores(modes, f, 1, rate_weight=100.0, gamma_tol=2.0)
    >>> round(cert.bound(1, 10.0), 4)       # the MF peak of |1/(jω + 3)|², at ω = 1
    0.1
    """
    modes, factors = _validate(modes, factors)
    in_band = as_count("in_band", in_band, 0)
    if in_band >= len(modes):
        raise ValueError(f"in_band must be a mode index in [0, {len(modes)}), found {in_band}")
    gamma_tol = as_positive("gamma_tol", gamma_tol)
    eta_tol = as_positive("eta_tol", eta_tol)
    rate_weight = as_nonnegative("rate_weight", rate_weight)
    margin = as_positive("margin", margin)
    n = modes[0].n_states
    P, g, h = _variables(modes)
    Q = [cp.Variable((n, n), symmetric=True, name=f"Q_{i}") for i in range(len(modes))]
    cons = [q >> margin * np.eye(n) for q in Q]
    if q_floor is not None:
        cons.append(Q[in_band] >> as_positive("q_floor", q_floor) * np.eye(n))
    cons += [g[j] == gamma_tol**2 for j in range(len(modes)) if j != in_band]
    cons += [x <= eta_tol**2 for x in h]
    return _solve(modes, factors, Q, g, h, P, cons, g[in_band] + rate_weight * h[in_band], margin,
                  f"score Q design (gamma_tol={gamma_tol:g}, in-band mode {in_band})")
