"""What a law on the disturbance estimate is guaranteed, computed for the candidates as run.

Realized through copies (``u = K0 x + (u_σ − K0 x̂_σ)``, :mod:`fdsc.supervisor`) from rest, with
the exact estimate ŵ = d and switches only at the decision points ``kΔ``, the plant's output is

    z = z_σ + C0 e,        C0 = C + D2 K0,        e = x − x̂_σ,

where ``z_i`` is copy i's own output (candidate i's closed loop driven by d), and e obeys
``ė = A0 e`` (``A0 = A + B2 K0``) between switches and jumps by ``x̂_q − x̂_p`` (the copies' plant
states) at a switch from q to p. So the argument needs: A0 Hurwitz, every candidate's loop
Hurwitz, the estimate exact, and the decision grid. Then an L2 gain bound follows for *every*
switching signal on the grid (:func:`copies_l2_bound`):

* ``∫‖z_σ‖² ≤ Σ_i ∫‖z_i‖² ≤ Σ_i γ_i² ‖d‖²`` (γ_i the H∞ norm of loop i);
* with ``h_i(τ) = ‖S_i e^{A_i τ} B_i‖`` (S_i picks copy i's plant state) and the weighted
  Cauchy–Schwarz inequality, the copies' states sampled at the grid satisfy
  ``Σ_k ‖x̂_i(kΔ)‖² ≤ ‖h_i‖₁ H_i ‖d‖²``, ``H_i = Σ_j sup_{[jΔ,(j+1)Δ]} h_i``; a jump is at most
  ``‖x̂_q‖ + ‖x̂_p‖``, so ``Σ_k ‖Δe_k‖² ≤ 2 Σ_i ‖h_i‖₁ H_i ‖d‖²``;
* with ``m(τ) = ‖C0 e^{A0 τ}‖`` the same argument gives ``∫‖C0 e‖² ≤ M ‖m‖₁ Σ_k ‖Δe_k‖²``,
  ``M = Σ_j sup_{[jΔ,(j+1)Δ]} m``.

Every sup over an interval is bounded rigorously: ``sup_{s≤Δ} ‖S e^{As}‖`` from a grid fine enough
that ``e^{‖A‖δ} ≤ 2`` between its points (for a stiff loop by ``‖S V‖ ‖V⁻¹‖``, V its
eigenvectors), and the sum over j by the first J with
``‖e^{AJΔ}‖ ≤ ½`` (a geometric tail). The bound holds for any law on that grid, so it is
conservative; it is finite, which the dwell-free direct realization cannot claim.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.linalg import expm

from ._validation import as_positive

__all__ = ["LawCertificate", "copies_l2_bound", "MAX_STEPS"]

#: Cap on the decision intervals summed before the geometric tail (a loop slower than this many
#: intervals gets no finite bound: None).
MAX_STEPS = 200_000
#: Above this many grid points per decision interval, the sup over an interval is bounded through
#: the eigenvectors instead (a stiff loop).
MAX_GRID = 2000


@dataclass(frozen=True)
class LawCertificate:
    """What the law is guaranteed (see :meth:`fdsc.Supervisor.certificate`).

    Parameters
    ----------
    realization : str
        ``"copies"`` or ``"direct"``.
    checks : dict
        ``{what the argument needs: bool}`` as computed.
    assumptions : tuple of str
        What is assumed, not computed (the exact estimate, the decision grid).
    stable : bool
        All checks pass: bounded for bounded d, decaying for d = 0, for any switching on the grid.
    l2_bound : float or None
        An L2 gain bound for any switching on the grid (:func:`copies_l2_bound`), or None where
        the argument gives none (the direct realization; a check that fails).
    """

    realization: str
    checks: dict
    assumptions: tuple
    stable: bool
    l2_bound: float | None


def _interval_sums(A, L, R, step):
    """``(Σ_j sup_{τ∈[jΔ,(j+1)Δ]} ‖L e^{Aτ} R‖, ∫₀^∞ ‖L e^{Aτ} R‖ dτ)`` bounded from above, or
    None if the loop does not decay within :data:`MAX_STEPS` intervals."""
    n = A.shape[0]
    norm_A = float(np.linalg.norm(A, 2))
    k = max(1, math.ceil(norm_A * step / math.log(2.0)))
    if k <= MAX_GRID:
        delta = step / k
        Ed = expm(A * delta)
        P = np.eye(n)
        E_L = 0.0
        for _ in range(k + 1):              # sup_{s ≤ Δ} ‖L e^{As}‖ ≤ 2 max over the grid
            E_L = max(E_L, float(np.linalg.norm(L @ P, 2)))
            P = P @ Ed
        E_L *= 2.0
    else:                                   # a stiff loop: ‖L e^{As}‖ ≤ ‖L V‖ ‖V⁻¹‖ for s ≥ 0
        lam, V = np.linalg.eig(A)
        if np.linalg.cond(V) > 1e12:
            return None
        E_L = float(np.linalg.norm(L @ V, 2) * np.linalg.norm(np.linalg.inv(V), 2))
    Estep = expm(A * step)
    P, total, j = np.eye(n), 0.0, 0
    while float(np.linalg.norm(P, 2)) > 0.5 or j == 0:
        total += float(np.linalg.norm(P @ R, 2))
        P = P @ Estep
        j += 1
        if j > MAX_STEPS:
            return None
    s = E_L * total / (1.0 - float(np.linalg.norm(P, 2)))
    return s, step * s


def copies_l2_bound(plant, controllers, K0, decide_every: float) -> float | None:
    """An L2 gain bound of the realization through copies under any switching on the grid
    (module docstring).

    Parameters
    ----------
    plant : Plant
    controllers : sequence of Controller
    K0 : (m_u, n) ndarray
    decide_every : float
        Δ (s).

    Returns
    -------
    float or None
        None if a loop is not Hurwitz or decays too slowly to sum.

    Examples
    --------
    >>> from fdsc import Controller, Plant, band_peak, Band
    >>> p = Plant([[-1.0]], [[1.0]], [[1.0]], [[1.0], [0.0]], [[0.0], [0.0]], [[0.0], [0.1]])
    >>> cs = [Controller.static([[-1.0]]), Controller.static([[-3.0]])]
    >>> rho = copies_l2_bound(p, cs, np.array([[-2.0]]), 0.1)
    >>> gmax = max(band_peak(c.closed_loop(p), Band.entire()).gamma for c in cs)
    >>> bool(gmax < rho < 100 * gmax)
    True
    """
    from .bands import Band
    from .frequency import band_peak

    step = as_positive("decide_every", decide_every)
    n = plant.n_states
    A0 = plant.A + plant.B2 @ K0
    C0 = plant.C + plant.D2 @ K0
    if np.max(np.linalg.eigvals(A0).real) >= 0:
        return None
    gam2, jump = 0.0, 0.0
    for c in controllers:
        loop = c.closed_loop(plant)
        if not loop.is_hurwitz():
            return None
        gam2 += band_peak(loop, Band.entire()).gamma ** 2
        S = np.zeros((n, loop.n_states))
        S[:, :n] = np.eye(n)
        sums = _interval_sums(loop.A, S, loop.B, step)
        if sums is None:
            return None
        H, l1 = sums
        jump += 2.0 * H * l1
    sums = _interval_sums(A0, C0, np.eye(n), step)
    if sums is None:
        return None
    M, m1 = sums
    return float(math.sqrt(gam2) + math.sqrt(M * m1 * jump))
