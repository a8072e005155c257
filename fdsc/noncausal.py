"""The non-causal limit: the least output energy any controller can reach on one disturbance.

A controller that knew the whole disturbance d on [0, H] in advance could do no better than the
finite-horizon LQ optimum with a known exogenous input::

    J* = min_u ∫₀ᴴ ‖C x + D1 d + D2 u‖² dt,     ẋ = A x + B1 d + B2 u,  x(0) = x0,

so no causal controller — fixed, switched, adaptive or predictive, on whatever measurements —
reaches less on that draw: J* is a **bound**, not a reference. It needs u penalized in z
(R = D2ᵀD2 > 0). With u = −R⁻¹D2ᵀ(C x + D1 d) + v the cost splits into
``‖Π(C x + D1 d)‖² + vᵀR v`` (Π = I − D2 R⁻¹ D2ᵀ), and the optimum is

    v* = −R⁻¹ B2ᵀ (P x + ξ),      ẋ = A_c x − S ξ + B̃1 d,      ξ̇ = −A_cᵀ ξ − F d,

with P the stabilizing solution of the Riccati equation of (Ã, B2, CᵀΠC, R), A_c = Ã − S P
Hurwitz, S = B2 R⁻¹ B2ᵀ, F = P B̃1 + CᵀΠD1, Ã = A − B2R⁻¹D2ᵀC, B̃1 = B1 − B2R⁻¹D2ᵀD1. The
adjoint ξ is the anti-causal filter of the future disturbance; the end condition
``P x(H) + ξ(H) = 0`` is met exactly by superposition (the end value c = ξ(H) solves
``(I − P G_H) c = −P x⁰(H)``, G_H the finite-horizon Gramian of (A_c, S)). ξ is integrated
backward and x forward, each along its stable direction, piece by piece of d in closed form
(:mod:`fdsc._modal`): exact between the breaks of d, no step, whatever the horizon.

For any control u, ``J(u) − J* = ∫ ‖v − v*(t, x)‖²_R dt``: the best causal law is the LQ gain
plus the best prediction of ξ from the past, and it beats a fixed controller only by
predicting the future disturbance better than a linear filter can.

:func:`tone_limit` is the same bound per frequency for a long single tone: the squared distance
of ``G_zd(jω)`` from the range of ``G_zu(jω)``.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from ._modal import Modal, tone_terms
from ._validation import as_positive, as_vector, check_type
from .decisions import _scale_exponent, _scaled
from .exceptions import EnergyOverflowError, EnergyUnderflowWarning
from .plant import as_plant
from .signals import Piecewise, Sinusoids

__all__ = ["LQData", "lq_data", "NoncausalLimit", "noncausal_limit", "tone_limit"]

#: The largest relative residual of the Riccati equation :func:`lq_data` accepts.
RICCATI_RTOL = 1e-8
#: :func:`lq_data` takes D2 to lack full column rank where its smallest singular value is at most
#: this share of the size of z's map ``‖[C D1 D2]‖₂`` (a test that does not depend on z's units).
RANK_RTOL = 1e-12
#: :func:`noncausal_limit` warns when its run meets the end condition ``P x(H) + ξ(H) = 0`` only to
#: a relative error above this.
END_RTOL = 1e-8
#: :func:`noncausal_limit` warns when the rounding of the closed-form terms it sums (eps times
#: their size) may exceed this share of its energy.
CANCEL_RTOL = 1e-6


@dataclass(frozen=True)
class LQData:
    """The LQ quantities of a plant for the cost ``∫ ‖C x + D1 d + D2 u‖²`` (:func:`lq_data`).

    Parameters
    ----------
    P : (n, n) ndarray
        The stabilizing solution of the Riccati equation.
    K : (m_u, n) ndarray
        The LQ gain: ``u = K x + K_d d − R⁻¹B2ᵀ ξ`` is the optimum (K = −R⁻¹(D2ᵀC + B2ᵀP)).
    K_d : (m_u, n_d) ndarray
        The direct term of d, ``−R⁻¹D2ᵀD1`` (0 when D1 = 0).
    A_c : (n, n) ndarray
        The closed loop ``A + B2 K`` (Hurwitz).
    R_inv_B2T : (m_u, n) ndarray
        ``R⁻¹B2ᵀ``: how the adjoint ξ enters u.
    F : (n, n_d) ndarray
        How d drives the adjoint: ``ξ̇ = −A_cᵀξ − F d``.
    S : (n, n) ndarray
        ``B2 R⁻¹ B2ᵀ``.
    B1t : (n, n_d) ndarray
        ``B̃1 = B1 − B2R⁻¹D2ᵀD1``.
    Cz, Dz_xi, Dz_d : ndarray
        ``z = Cz x + Dz_xi ξ + Dz_d d`` along the optimum.
    """

    P: np.ndarray
    K: np.ndarray
    K_d: np.ndarray
    A_c: np.ndarray
    R_inv_B2T: np.ndarray
    F: np.ndarray
    S: np.ndarray
    B1t: np.ndarray
    Cz: np.ndarray
    Dz_xi: np.ndarray
    Dz_d: np.ndarray

    def psi_gain(self, omega: ArrayLike) -> np.ndarray:
        """``−(jω I + A_cᵀ)⁻¹ F`` per frequency: the adjoint of a tone continued forever,
        ``ξ(t) = Re(ψ(ω) c e^{jωt})`` for ``d(t) = Re(c e^{jωt})`` (n, n_d) per ω.

        Parameters
        ----------
        omega : (N,) array_like
            rad/s, any sign.

        Returns
        -------
        (N, n, n_d) complex ndarray

        Raises
        ------
        ValueError
            If ω is not a finite real vector.
        """
        w = as_vector("omega", omega)
        n = self.A_c.shape[0]
        M = 1j * w[:, None, None] * np.eye(n)[None] + self.A_c.T[None]
        return -np.linalg.solve(M, np.broadcast_to(self.F, (w.size, *self.F.shape)))


def lq_data(plant) -> LQData:
    """The LQ optimum's quantities of a plant (module docstring).

    Parameters
    ----------
    plant : Plant, control.StateSpace or tuple

    Returns
    -------
    LQData

    Raises
    ------
    ValueError
        If D2 does not have full column rank (its smallest singular value at most
        :data:`RANK_RTOL` of ``‖[C D1 D2]‖₂``: u is not penalized in z, the limit is not
        finite), the Riccati equation has no stabilizing solution or is solved inaccurately
        (relative residual above :data:`RICCATI_RTOL`), or P leaves the float range in z's units.

    Notes
    -----
    The problem is solved with z in units where ``‖[C D1 D2]‖₂`` lies in [1/2, 1) (a power of
    two, exact) and brought back: the rank test and the solve do not depend on z's units.

    Examples
    --------
    >>> from fdsc import Plant
    >>> lq = lq_data(Plant([[1.0]], [[1.0]], [[1.0]], [[1.0], [0.0]], [[0.0], [0.0]], [[0.0], [1.0]]))
    >>> round(float(lq.K[0, 0]), 6), round(float(lq.A_c[0, 0]), 6)      # ẋ = x + u, ∫ x² + u²
    (-2.414214, -1.414214)
    """
    from scipy.linalg import solve_continuous_are

    plant = as_plant(plant)
    A, B1, B2, C, D1, D2 = plant.A, plant.B1, plant.B2, plant.C, plant.D1, plant.D2
    # solved with z in units where its map [C D1 D2] has a norm in [1/2, 1) (a power of two,
    # exact): P, F and the cost scale with z's units squared and the gains not at all, so neither
    # the rank test nor the Riccati solve depends on them (z × 1e-13 or × 1e60 is the same problem)
    size = float(np.linalg.norm(np.hstack([C, D1, D2]), 2))
    ez = math.frexp(size)[1] if size > 0 else 0
    C, D1, D2 = (np.ldexp(M, -ez) for M in (C, D1, D2))
    s = np.linalg.svd(D2, compute_uv=False)
    smallest = float(np.ldexp(s.min(), ez)) if s.size == D2.shape[1] else 0.0
    if not smallest > RANK_RTOL * size:
        raise ValueError(f"plant: D2 must have full column rank (every control penalized in z), so that the "
                         f"least energy is finite, but its smallest singular value is {smallest:.3g}, "
                         f"{smallest / size if size else 0.0:.3g} of the size of z's map ‖[C D1 D2]‖ = "
                         f"{size:.3g} (at most {RANK_RTOL:g} of it counts as 0); add a penalty ρ u to z")
    R = D2.T @ D2
    Ri = np.linalg.inv(R)
    G = Ri @ D2.T                                      # R⁻¹D2ᵀ
    At = A - B2 @ G @ C
    B1t = B1 - B2 @ G @ D1
    Pi = np.eye(C.shape[0]) - D2 @ G
    Q = C.T @ Pi @ C
    Q = 0.5 * (Q + Q.T)
    # solved in the units u = L⁻ᵀ ũ (R = L Lᵀ), where the penalty is I: a small penalty (R near
    # 1e-16) otherwise makes the solver return P = 0 without a word
    Bu = B2 @ np.linalg.inv(np.linalg.cholesky(R)).T
    try:
        P = solve_continuous_are(At, Bu, Q, np.eye(R.shape[0]))
    except (np.linalg.LinAlgError, ValueError) as exc:
        raise ValueError(f"plant: the LQ problem has no stabilizing solution ({exc})") from None
    P = 0.5 * (P + P.T)
    RiB = Ri @ B2.T
    S = B2 @ RiB
    terms = (At.T @ P, P @ S @ P, Q)
    res = np.linalg.norm(terms[0] + terms[0].T - terms[1] + Q)
    if not res <= RICCATI_RTOL * sum(np.linalg.norm(t) for t in terms):
        raise ValueError(f"plant: the Riccati equation of the LQ problem is solved inaccurately (relative "
                         f"residual {res / max(sum(np.linalg.norm(t) for t in terms), 1e-300):.2g} > "
                         f"{RICCATI_RTOL:g}): rescale the plant's states, controls or outputs")
    A_c = At - S @ P
    lam = np.linalg.eigvals(A_c)
    if np.max(lam.real) >= 0:
        raise ValueError(f"plant: the LQ closed loop is not Hurwitz (an eigenvalue at "
                         f"{complex(lam[np.argmax(lam.real)]):.4g}): a mode the cost does not see")
    N = C.T @ Pi @ D1
    K = -(G @ C + RiB @ P)
    # back to z's units: P, F as z², Cz, Dz_d as z, R⁻¹B2ᵀ, S as z⁻², Dz_xi as z⁻¹ (ξ is as z²)
    scaled = {"P": (P, 2), "R_inv_B2T": (RiB, -2), "F": (P @ B1t + N, 2), "S": (S, -2),
              "Cz": (Pi @ C - D2 @ RiB @ P, 1), "Dz_xi": (-D2 @ RiB, -1), "Dz_d": (Pi @ D1, 1)}
    tiny = np.finfo(float).tiny
    back = {}
    for name, (M, power) in scaled.items():
        with np.errstate(over="ignore", under="ignore"):
            back[name] = np.ldexp(M, power * ez)
        if not np.all(np.isfinite(back[name])) or np.any((np.abs(M) >= tiny) & (np.abs(back[name]) < tiny)):
            raise ValueError(f"plant: the LQ quantity {name} leaves the float range in z's units (the size "
                             f"of z's map ‖[C D1 D2]‖ is {size:.3g}): rescale z")
    return LQData(back["P"], K, -G @ D1, A_c, back["R_inv_B2T"], back["F"], back["S"], B1t, back["Cz"],
                  back["Dz_xi"], back["Dz_d"])


def _pieces(d, horizon):
    from ._blocks import pieces

    return pieces(d, horizon)


@dataclass(frozen=True)
class NoncausalLimit:
    """The least output energy on one disturbance (see :func:`noncausal_limit`).

    Parameters
    ----------
    energy : float
        J* = min ∫₀ᴴ ‖z‖² dt over every control knowing d on [0, H].
    horizon : float
    breaks : (P + 1,) ndarray
        The pieces' bounds (the breaks of d and 0, H).
    piece_energies : (P,) ndarray
        J* split by piece.
    lq : LQData
    _x_terms, _xi_terms, _d_terms : tuple
        Per piece, the closed-form terms of x, ξ and d (what :meth:`trajectory` evaluates).
    _scale : int
        The terms are those of the run with d and x0 times 2^−_scale (see :func:`noncausal_limit`).
    _state_scale : (n,) ndarray
        The terms are in the balanced state ``x̃ = x / _state_scale`` (powers of two; the
        adjoint ``ξ̃ = ξ · _state_scale``), see :func:`noncausal_limit`.
    """

    energy: float
    horizon: float
    breaks: np.ndarray
    piece_energies: np.ndarray
    lq: LQData = field(repr=False)
    _x_terms: tuple = field(repr=False, default=())
    _xi_terms: tuple = field(repr=False, default=())
    _d_terms: tuple = field(repr=False, default=())
    _scale: int = field(repr=False, default=0)
    _state_scale: np.ndarray | None = field(repr=False, default=None)

    def trajectory(self, t: ArrayLike) -> dict:
        """The optimal trajectory at times t (closed forms, no simulation).

        Parameters
        ----------
        t : (N,) array_like
            Times in [0, horizon].

        Returns
        -------
        dict
            ``x`` (N, n), ``u`` (N, m_u), ``z`` (N, p), ``xi`` (N, n).

        Raises
        ------
        ValueError
            If t is not a finite real vector or leaves [0, horizon].
        """
        t = as_vector("t", t)
        if np.any((t < 0) | (t > self.horizon)):
            raise ValueError(f"t must lie in [0, {self.horizon}]")
        k = np.clip(np.searchsorted(self.breaks, t, side="right") - 1, 0, self.piece_energies.size - 1)
        lq = self.lq
        x = np.zeros((t.size, lq.A_c.shape[0]))
        xi = np.zeros_like(x)
        dd = np.zeros((t.size, lq.F.shape[1]))
        for j in np.unique(k):
            sel = k == j
            L = self.breaks[j + 1] - self.breaks[j]
            tau = t[sel] - self.breaks[j]
            for out, terms in ((x, self._x_terms[j]), (xi, self._xi_terms[j]), (dd, self._d_terms[j])):
                e, an, g = terms
                if e.size:
                    ex = np.exp(e[None, :] * (tau[:, None] - an[None, :] * L))
                    out[sel] = (ex @ g).real
        if self._state_scale is not None:          # from the balanced state to the plant's own
            x, xi = x * self._state_scale[None, :], xi / self._state_scale[None, :]
        u = x @ lq.K.T + dd @ lq.K_d.T - xi @ lq.R_inv_B2T.T
        z = x @ lq.Cz.T + xi @ lq.Dz_xi.T + dd @ lq.Dz_d.T
        out = {"x": x, "u": u, "z": z, "xi": xi}
        if self._scale:                             # back to the caller's units (states: power 1)
            with np.errstate(over="ignore", under="ignore"):
                out = {k: np.ldexp(v, self._scale) for k, v in out.items()}
            for k, v in out.items():
                if not np.all(np.isfinite(v)):
                    raise EnergyOverflowError(f"trajectory: {k} exceeds the float range (about 1.8e308) "
                                              "in the disturbance's units")
        return out


def noncausal_limit(plant, d, horizon: float, *, x0=None) -> NoncausalLimit:
    """The least ∫₀ᴴ ‖z‖² any controller reaches on the disturbance d, knowing it in advance
    (module docstring): a lower bound for every causal controller on this draw.

    Parameters
    ----------
    plant : Plant, control.StateSpace or tuple
        D2 of full column rank.
    d : Sinusoids or Piecewise
        The disturbance (one input per column of B1; sums of tones, piece by piece).
    horizon : float
        H > 0 (s).
    x0 : (n,) array_like, optional
        The plant's initial state (default rest).

    Returns
    -------
    NoncausalLimit

    Raises
    ------
    TypeError
        If d is not a Sinusoids or Piecewise.
    ValueError
        If the plant has more than one disturbance input, D2 lacks full column rank, the LQ
        problem has no stabilizing solution, ``horizon`` is not positive, or x0 has the wrong
        size or non-finite entries.
    EnergyOverflowError
        If the energy exceeds the float range.

    Warns
    -----
    EnergyUnderflowWarning
        If the energy is below the smallest normal float (the run itself is made at a scale
        where it keeps its digits).
    RuntimeWarning
        If the closed-form terms it sums cancel so much that their rounding may exceed
        :data:`CANCEL_RTOL` of the energy (a horizon short against every time scale of the loop
        and of d); the message gives the bound. Also if the run meets its end condition
        ``P x(H) + ξ(H) = 0`` only to a relative error above :data:`END_RTOL`.

    Notes
    -----
    The run is made in balanced states (``x = T x̃``, T diagonal of powers of two that balances
    the LQ closed loop, exact), so that the bound does not depend on the units of the states;
    :attr:`NoncausalLimit.lq` and :meth:`NoncausalLimit.trajectory` are in the plant's own.

    Examples
    --------
    A long single tone reaches the per-frequency bound :func:`tone_limit` (its mean power):

    >>> from fdsc import Plant
    >>> p = Plant([[-1.0]], [[1.0]], [[1.0]], [[1.0], [0.0]], [[0.0], [0.0]], [[0.0], [0.5]])
    >>> lim = noncausal_limit(p, Sinusoids([1.0], [2.0]), 2000.0)
    >>> round(float(lim.energy / 2000.0 / (0.5 * tone_limit(p, [2.0])[0])), 3)
    1.0
    """
    plant = as_plant(plant)
    check_type("d", d, Sinusoids | Piecewise, "an fdsc.Sinusoids or fdsc.Piecewise")
    if plant.B1.shape[1] != 1:
        raise ValueError(f"plant must have one disturbance input (d is a scalar signal), but has "
                         f"{plant.B1.shape[1]}")
    H = as_positive("horizon", horizon)
    n = plant.n_states
    x0 = np.zeros(n) if x0 is None else as_vector("x0", x0, n)
    lq_plant = lq_data(plant)
    # run in a balanced state x = T x̃ (T diagonal, powers of two, exact), so that the bound does
    # not depend on the units of the states: written in scaled states, the Lyapunov solve of the
    # end condition perturbed its equation and the eigenbasis lost its conditioning
    sca = _state_scale(lq_plant.A_c)
    lq = _in_state_units(lq_plant, sca)
    # run at a scale (a power of two, exact) where the energies keep their digits: J(2^−e d,
    # 2^−e x0) = 2^−2e J(d, x0)
    e_scale = _scale_exponent(x0, d)
    x0 = np.ldexp(x0, -e_scale) / sca
    pcs = _pieces(_scaled(d, e_scale), H)
    back = Modal(lq.A_c.T, np.eye(n), "the LQ closed loop")
    fwd = Modal(lq.A_c, np.vstack([lq.Cz, np.eye(n)]), "the LQ closed loop")
    xi_at_H = np.zeros(n)
    for _attempt in range(2):                    # ξ(H) = 0, then the c that meets P x(H) + ξ(H) = 0
        xi_terms = _backward(back, pcs, lq, xi_at_H)
        energies, x_terms, d_terms, xH, sizes = _forward(fwd, pcs, lq, xi_terms, x0)
        if _attempt == 0:
            GH = _gramian_H(lq, H)
            c = np.linalg.solve(np.eye(n) - lq.P @ GH, -lq.P @ xH)
            if not np.all(np.isfinite(c)):
                raise EnergyOverflowError("noncausal_limit: the end condition is not finite")
            xi_at_H = c
    # the end condition, met by superposition, checked on the run itself: a Lyapunov or linear
    # solve that lost its digits shows here
    miss = float(np.max(np.abs(lq.P @ xH + xi_at_H), initial=0.0))      # largest entries: no squares
    ref = float(np.max(np.abs(lq.P @ xH), initial=0.0) + np.max(np.abs(xi_at_H), initial=0.0))
    if ref > 0 and not miss <= END_RTOL * ref:
        warnings.warn(f"noncausal_limit: the end condition P x(H) + ξ(H) = 0 is met only to a relative "
                      f"{miss / ref:.2g} (above {END_RTOL:g}), even in balanced states: the bound may be off "
                      "by about that share (a closed loop with nearly undamped or widely spread modes)",
                      RuntimeWarning, stacklevel=2)
    J = float(np.sum(energies))
    if not math.isfinite(J):
        raise EnergyOverflowError("noncausal_limit: the energy exceeds the float range (about 1.8e308)")
    size = float(np.sum(sizes))
    eps = np.finfo(float).eps
    if size > 0 and not abs(J) * CANCEL_RTOL > eps * size:
        ratio = size / abs(J) if J else math.inf
        warnings.warn(f"noncausal_limit: the energy is a sum of closed-form terms that cancel (their size "
                      f"is {ratio:.3g} times the energy's): its rounding error may reach {eps * ratio:.2g} "
                      f"of it (a horizon short against every time scale of the loop and of d)",
                      RuntimeWarning, stacklevel=2)
    J = _in_units(J, e_scale)
    with np.errstate(over="ignore", under="ignore"):
        piece_energies = np.ldexp(np.asarray(energies), 2 * e_scale)
    breaks = np.array([p[0] for p in pcs] + [H])
    return NoncausalLimit(J, H, breaks, piece_energies, lq_plant, tuple(x_terms),
                          tuple(xi_terms), tuple(d_terms), e_scale, sca)


def _in_units(J, e):
    """The energy J of the run scaled by 2^−e in the caller's units (2^2e J), refused above the
    float range and warned below its normal numbers."""
    with np.errstate(over="ignore", under="ignore"):
        out = float(np.ldexp(J, 2 * e))
    if not math.isfinite(out):
        raise EnergyOverflowError("noncausal_limit: the energy exceeds the float range (about 1.8e308) "
                                  "in the units of d and x0: scale them down")
    tiny = np.finfo(float).tiny
    if J != 0 and abs(out) < tiny:
        warnings.warn(f"noncausal_limit: the energy ({out:.3g}) is below the smallest normal float (about "
                      f"{tiny:.2g}) in the units of d and x0, where it keeps few digits or none (it was "
                      "computed at a scale where it keeps them): scale d and x0 up for its digits",
                      EnergyUnderflowWarning, stacklevel=3)
    return out


def _state_scale(A):
    """The diagonal state scaling (powers of two) that balances A: ``x = T x̃`` with
    ``T = diag(scale)`` and ``T⁻¹ A T`` of comparable row and column norms."""
    from scipy.linalg import matrix_balance

    if A.size == 0:
        return np.ones(0)
    _b, (scale, _perm) = matrix_balance(A, permute=False, separate=True)
    return np.asarray(scale, dtype=float)


def _in_state_units(lq, sca):
    """The LQ quantities in the state ``x̃ = x / sca`` (adjoint ``ξ̃ = ξ · sca``); exact."""
    r, c = sca[:, None], sca[None, :]
    return LQData(lq.P * r * c, lq.K * c, lq.K_d, lq.A_c / r * c, lq.R_inv_B2T / c, lq.F * r, lq.S / r / c,
                  lq.B1t / r, lq.Cz * c, lq.Dz_xi / c, lq.Dz_d)


def _gramian_H(lq, H):
    """``∫₀ᴴ e^{A_c s} S e^{A_cᵀ s} ds = M − e^{A_c H} M e^{A_cᵀ H}`` with A_c M + M A_cᵀ + S = 0."""
    from scipy.linalg import expm, solve_continuous_lyapunov

    M = solve_continuous_lyapunov(lq.A_c, -lq.S)
    slowest = float(np.min(np.abs(np.linalg.eigvals(lq.A_c).real)))
    if H * slowest > 60.0:                      # e^{A_c H} below 1e-26 of M: nothing to subtract
        return M
    E = expm(lq.A_c * H)
    return M - E @ M @ E.T


def _backward(back, pcs, lq, xi_end):
    """Per piece, the terms of ξ in forward time (exponent, anchor, coefficient (n,))."""
    n = lq.A_c.shape[0]
    out = [None] * len(pcs)
    xi = np.asarray(xi_end, dtype=float)
    for j in range(len(pcs) - 1, -1, -1):
        t0, t1, w, a, ph = pcs[j]
        L = t1 - t0
        # reversed time τ' = t1 − t: dξ/dτ' = A_cᵀ ξ + F d(t1 − τ'), d(t1 − τ') a sum of tones
        s, c = tone_terms(0.0, -w, a, w * t1 + ph)
        b = c[:, None] * lq.F[:, 0][None, :]
        e, an, g, xi0 = back.piece(xi, s, np.zeros(s.size, dtype=bool), b, np.zeros((s.size, n)), L)
        # back to forward time τ = L − τ': e^{e (L − τ)}; tones keep anchor 0 (coefficient
        # e^{eL}, unit modulus), modes (Re e < 0) become e^{−e (τ − L)} anchored at L
        tone = np.abs(e.real) == 0
        coef = np.where(tone[:, None], g * np.exp(np.where(tone, e, 0.0) * L)[:, None], g)
        out[j] = (-e, ~tone, coef)
        xi = xi0
    return out


def _forward(fwd, pcs, lq, xi_terms, x0):
    n = lq.A_c.shape[0]
    p = lq.Cz.shape[0]
    x = np.asarray(x0, dtype=float)
    energies, x_terms, d_terms, sizes = [], [], [], []
    for j, (t0, t1, w, a, ph) in enumerate(pcs):
        L = t1 - t0
        sd, cd = tone_terms(t0, w, a, ph)
        ex, ax, gx = xi_terms[j]
        s = np.r_[sd, ex]
        anchor = np.r_[np.zeros(sd.size, dtype=bool), ax]
        b = np.vstack([cd[:, None] * lq.B1t[:, 0][None, :], -(gx @ lq.S.T)])
        dz = np.vstack([cd[:, None] * lq.Dz_d[:, 0][None, :], gx @ lq.Dz_xi.T])
        dout = np.hstack([dz, np.zeros((s.size, n))])
        e, an, g, xL = fwd.piece(x, s, anchor, b, dout, L)
        G, size = Modal.gram(e, an, g[:, :p], L, bound=True)
        energies.append(float(np.trace(G)))
        sizes.append(size)
        x_terms.append((e, an, g[:, p:]))
        d_terms.append((sd, np.zeros(sd.size, dtype=bool), cd[:, None]))
        x = xL
    return energies, x_terms, d_terms, x, sizes


def tone_limit(plant, omega: ArrayLike) -> np.ndarray:
    """The least ``‖z‖²/|d|²`` per frequency: for ``d = Re(c e^{jωt})`` held forever, no control
    makes the mean of ‖z‖² less than ``|c|²/2`` times this (the squared distance of
    ``G_zd(jω)`` from the range of ``G_zu(jω)``).

    Parameters
    ----------
    plant : Plant, control.StateSpace or tuple
        One disturbance input; D2 of full column rank.
    omega : (N,) array_like
        Frequencies (rad/s), none on a pole of the plant.

    Returns
    -------
    (N,) ndarray

    Raises
    ------
    ValueError
        As :func:`lq_data`, or if ω lies on a pole of the plant.

    Examples
    --------
    >>> from fdsc import Plant
    >>> p = Plant([[-1.0]], [[1.0]], [[1.0]], [[1.0], [0.0]], [[0.0], [0.0]], [[0.0], [0.5]])
    >>> float(np.round(tone_limit(p, [0.0])[0], 6))     # min_u (1 + u)² + u²/4 = 0.2
    0.2
    """
    plant = as_plant(plant)
    if plant.B1.shape[1] != 1:
        raise ValueError(f"plant must have one disturbance input, but has {plant.B1.shape[1]}")
    lq_data(plant)
    w = as_vector("omega", omega)
    n = plant.n_states
    # in balanced states (diagonal, powers of two, exact): the bound and the test of a pole do
    # not depend on the units of the states
    sca = _state_scale(plant.A)
    A = plant.A / sca[:, None] * sca[None, :]
    B1, B2, C = plant.B1 / sca[:, None], plant.B2 / sca[:, None], plant.C * sca[None, :]
    out = np.empty(w.size)
    for k, wk in enumerate(w):
        M = 1j * wk * np.eye(n) - A
        if np.linalg.cond(M) > 1e14:
            raise ValueError(f"omega[{k}] = {wk} lies on a pole of the plant")
        G1 = C @ np.linalg.solve(M, B1) + plant.D1
        G2 = C @ np.linalg.solve(M, B2) + plant.D2
        U, _res, _rank, _sv = np.linalg.lstsq(G2, G1, rcond=None)
        r = G1 - G2 @ U
        out[k] = float(np.real(np.vdot(r, r)))
    return out
