"""The H2-optimal fixed controller for a disturbance spectrum.

When the disturbance is not arbitrary but drawn from a class with a known mean spectrum, the
fixed controller that minimizes the expected output energy is the H2-optimal one for a shaping
filter F whose output has that spectrum when driven by white noise: ``d = F ν``. Augmenting the
plant with F (state ``[x; x_F]``) makes the problem standard:

* with x and the disturbance estimate ŵ (the paper's premise: x and ẋ measured, so ŵ = d),
  the optimal control is ``u = K_x x + K_F x̂_F`` with ``[K_x, K_F]`` the LQR gain of the
  augmented plant and x̂_F a Kalman filter of F driven by ŵ: the LQR gain on x is the plant's
  own (F is not controllable from u), the rest is feedforward from the predicted disturbance;
* with x alone, a Kalman filter of the augmented plant from the measured x estimates x_F
  (what d has been doing shows in how x moves), and ``u = K_x x + K_F x̂_F``.

Either is a :class:`fdsc.Controller`. :func:`shaping_filter` builds F from band-pass sections,
:func:`fit_shaping_filter` fits one to sampled tones (the tones of training disturbances).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.linalg import solve_continuous_are, solve_continuous_lyapunov

from ._validation import as_choice, as_positive, as_vector
from .controller import Controller
from .plant import LTISystem, as_plant

__all__ = ["shaping_filter", "fit_shaping_filter", "h2_controller", "READS"]

#: What an H2 controller reads: the state alone, or the state and the estimate ŵ.
READS = ("x", "x+w")
#: The measurement noise of the Kalman filters, relative to the signal it measures (the state's
#: or the disturbance's RMS under the design): a filter for exact measurements would be singular.
DEFAULT_NOISE = 1e-2


def shaping_filter(centres, dampings, powers) -> LTISystem:
    """A sum of second-order band-pass sections ``g 2ζω s / (s² + 2ζω s + ω²)``, section j with
    output variance ``powers[j]`` when driven by unit white noise (``g² ζ ω = P``).

    Parameters
    ----------
    centres : (k,) array_like
        ω_j > 0 (rad/s).
    dampings : (k,) array_like
        ζ_j > 0.
    powers : (k,) array_like
        P_j ≥ 0.

    Returns
    -------
    LTISystem
        2k states, one input ν, one output d.

    Raises
    ------
    ValueError
        If the lengths differ or an entry is out of range.

    Examples
    --------
    >>> F = shaping_filter([2.0], [0.5], [3.0])
    >>> X = solve_continuous_lyapunov(F.A, -F.B @ F.B.T)
    >>> round(float((F.C @ X @ F.C.T)[0, 0]), 10)          # the output's variance
    3.0
    """
    w, z, P = (as_vector(nm, v) for nm, v in (("centres", centres), ("dampings", dampings),
                                                 ("powers", powers)))
    if not (w.size == z.size == P.size) or w.size == 0:
        raise ValueError(f"centres, dampings and powers must have one equal length ≥ 1, but found "
                         f"{w.size}, {z.size}, {P.size}")
    if np.any(w <= 0) or np.any(z <= 0) or np.any(P < 0) or not np.all(np.isfinite(np.r_[w, z, P])):
        raise ValueError("centres and dampings must be positive and powers non-negative, all finite")
    k = w.size
    A = np.zeros((2 * k, 2 * k))
    B = np.zeros((2 * k, 1))
    C = np.zeros((1, 2 * k))
    for j in range(k):
        A[2 * j:2 * j + 2, 2 * j:2 * j + 2] = [[0.0, 1.0], [-w[j] ** 2, -2 * z[j] * w[j]]]
        B[2 * j + 1, 0] = 1.0
        C[0, 2 * j + 1] = math.sqrt(P[j] / (z[j] * w[j])) * 2 * z[j] * w[j]
    return LTISystem(A, B, C, np.zeros((1, 1)))


def fit_shaping_filter(frequencies, powers, edges) -> LTISystem:
    """A shaping filter fitted to tones: one band-pass section per group of tones.

    Tones are grouped by the ``edges`` between groups (e.g. one edge between an LF and an HF
    band). Each group's section is centred at the power-weighted mean of log ω, its half-power
    points lie ``√3`` log-standard deviations on either side (those of a log-uniform spread, so
    ``ζ = sinh(√3 s)``), and its power is the group's.

    Parameters
    ----------
    frequencies : (N,) array_like
        The tones' frequencies (rad/s, > 0).
    powers : (N,) array_like
        Their mean powers (a²/2 times the share of time they are on).
    edges : sequence of float
        Frequencies between the groups (rad/s, positive and finite; taken in increasing order).

    Returns
    -------
    LTISystem

    Raises
    ------
    ValueError
        If a group holds no tone, or the input is out of range (an edge that is not a positive
        finite frequency is named as ``edges``).

    Examples
    --------
    >>> w = np.geomspace(10.0, 100.0, 401)                 # log-uniform from 10 to 100 rad/s
    >>> F = fit_shaping_filter(w, np.full(401, 1 / 401), [])
    >>> round(float(np.sqrt(-F.A[1, 0])), 2)                    # centred at √(10 · 100)
    31.62
    """
    w, P = as_vector("frequencies", frequencies), as_vector("powers", powers)
    e = np.sort(as_vector("edges", edges))
    if np.any(e <= 0):
        raise ValueError(f"edges must be positive frequencies (rad/s), but found {e.tolist()}")
    if w.size != P.size or w.size == 0 or np.any(w <= 0) or np.any(P < 0):
        raise ValueError("frequencies must be positive, powers non-negative, of one length ≥ 1")
    group = np.searchsorted(e, w)
    centres, damps, pows = [], [], []
    for g in range(e.size + 1):
        sel = group == g
        if not np.any(sel) or P[sel].sum() == 0:
            raise ValueError(f"group {g} (between the edges {e.tolist()}) holds no tone with power")
        lw, p = np.log(w[sel]), P[sel]
        mu = float(np.sum(p * lw) / p.sum())
        s = float(np.sqrt(np.sum(p * (lw - mu) ** 2) / p.sum()))
        centres.append(math.exp(mu))
        damps.append(max(0.05, math.sinh(math.sqrt(3.0) * s)))
        pows.append(float(p.sum()))
    return shaping_filter(centres, damps, pows)


def _lqr(A, B, Q, R, S):
    P = solve_continuous_are(A, B, Q, R, s=S)
    return -np.linalg.solve(R, B.T @ P + S.T)


def _kalman(A, C, W, V):
    P = solve_continuous_are(A.T, C.T, W, V)
    return P @ C.T @ np.linalg.inv(V)


def h2_controller(plant, shaping, *, reads: str = "x", noise: float = DEFAULT_NOISE,
                  name: str = "") -> Controller:
    """The H2-optimal fixed controller for disturbances ``d = F ν`` (module docstring).

    Parameters
    ----------
    plant : Plant, control.StateSpace or tuple
        One disturbance input (:func:`fdsc.as_plant`: a StateSpace's first input is it).
    shaping : LTISystem
        F: one input (white noise), one output (d), stable, strictly proper (D = 0).
    reads : {"x", "x+w"}, optional
        What the controller reads: the state alone (a Kalman filter of the augmented plant from
        x), or the state and the estimate ŵ (a Kalman filter of F from ŵ).
    noise : float, optional
        The Kalman filters' measurement noise, relative to the RMS of what they measure.
    name : str, optional

    Returns
    -------
    Controller
        ``u = K_x x + K_F x̂_F``; its states are the filter's (x̂_F, or ``[x̂; x̂_F]``).

    Raises
    ------
    ValueError
        If the plant has several disturbances, F is not stable, not strictly proper or not of
        one input and one output, ``reads`` is unknown or ``noise`` is not positive, or the
        Riccati equations have no stabilizing solution.

    Examples
    --------
    >>> from fdsc import Band, Plant, band_peak
    >>> plant = Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
    ...               [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.1]])
    >>> F = shaping_filter([12.0], [0.1], [1.0])
    >>> c = h2_controller(plant, F)
    >>> c.n_states, bool(plant.closed_loop(c).is_hurwitz())     # x̂ and the filter's x̂_F
    (4, True)
    """
    plant = as_plant(plant)
    if plant.B1.shape[1] != 1:
        raise ValueError(f"plant must have one disturbance input, but has {plant.B1.shape[1]}")
    if not isinstance(shaping, LTISystem) or shaping.B.shape[1] != 1 or shaping.C.shape[0] != 1:
        raise ValueError("shaping must be an fdsc.LTISystem with one input and one output")
    if np.any(shaping.D) or not shaping.is_hurwitz():
        raise ValueError("shaping must be stable and strictly proper (D = 0)")
    reads = as_choice("reads", reads, READS)
    noise = as_positive("noise", noise)
    A, B1, B2, C, D1, D2 = plant.A, plant.B1, plant.B2, plant.C, plant.D1, plant.D2
    n, m, nf = plant.n_states, plant.n_controls, shaping.n_states
    Af, Bf, Cf = shaping.A, shaping.B, shaping.C
    Aa = np.block([[A, B1 @ Cf], [np.zeros((nf, n)), Af]])
    B2a = np.vstack([B2, np.zeros((nf, m))])
    Ca = np.hstack([C, D1 @ Cf])
    R = D2.T @ D2
    if np.linalg.matrix_rank(R) < m:
        R = R + 1e-9 * max(1.0, float(np.linalg.norm(R))) * np.eye(m)
    try:
        K = _lqr(Aa, B2a, Ca.T @ Ca, R, Ca.T @ D2)       # its block on x is the plant's LQR gain
        Kx, KF = K[:, :n], K[:, n:]
    except (np.linalg.LinAlgError, ValueError) as exc:
        raise ValueError(f"plant: the augmented LQR problem has no stabilizing solution: {exc}") from exc
    d_var = float((Cf @ solve_continuous_lyapunov(Af, -Bf @ Bf.T) @ Cf.T)[0, 0])
    if reads == "x+w":
        V = np.array([[(noise ** 2) * max(d_var, 1e-300)]])
        L = _kalman(Af, Cf, Bf @ Bf.T, V)
        return Controller(Af - L @ Cf, np.zeros((nf, n)), KF, Kx, E=L, F=np.zeros((m, 1)), name=name)
    # x alone: the state's spread under the design sets the filter's noise
    G = np.vstack([np.zeros((n, 1)), Bf])
    Acl = Aa + B2a @ np.hstack([Kx, KF])
    X = solve_continuous_lyapunov(Acl, -G @ G.T)
    sx = np.sqrt(np.maximum(np.diag(X)[:n], 1e-300))
    V = np.diag((noise * sx) ** 2)
    S = np.hstack([np.eye(n), np.zeros((n, nf))])
    try:
        L = _kalman(Aa, S, G @ G.T, V)
    except (np.linalg.LinAlgError, ValueError) as exc:
        raise ValueError(f"shaping: the Kalman filter from x has no stabilizing solution: {exc}") from exc
    Ak = Aa - L @ S + B2a @ np.hstack([np.zeros((m, n)), KF])
    Bk = L + B2a @ Kx
    Ck = np.hstack([np.zeros((m, n)), KF])
    return Controller(Ak, Bk, Ck, Kx, name=name)
