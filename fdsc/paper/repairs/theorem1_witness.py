"""Chapter 'theorem1', continued: why Theorem 1's LMIs always hold.

The explicit witness of their feasibility for any pair of Hurwitz modes and any Q (P = t L with
A'L + LA = -I, t and γ large, checked by eigenvalues) and the switching signal's invariance
under a scaling of both Q's.
"""

from dataclasses import dataclass

import numpy as np
from scipy.linalg import solve_continuous_lyapunov

from fdsc.paper.repairs.theorem1_cases import _ZERO, REFINE, CaseOutcome, SearchCase
from fdsc.paper.shared.prose import num
from fdsc.simulate import simulate, time_grid

__all__ = ["LMIWitness", "QScaling", "lmi_witness", "q_scaling"]


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
        """The point as text (:mod:`fdsc.paper.shared.prose`), both modes joined by "and".

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
    >>> from fdsc.bands import Band
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
