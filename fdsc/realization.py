"""What a law on the disturbance estimate is built from: the gentle stabilizing gain of the
realization through copies (:func:`lqr_gain`), the switched loops of that realization, and the
band-power law's monitoring filters (:func:`band_filter`).
"""

from __future__ import annotations

import math

import numpy as np

from ._validation import check_type

__all__ = ["lqr_gain", "band_filter", "control_maps", "MAX_FILTER_EDGE"]

#: The band edges (rad/s) a monitoring filter resolves: [1 / MAX_FILTER_EDGE, MAX_FILTER_EDGE].
MAX_FILTER_EDGE = 1e6


def lqr_gain(plant) -> np.ndarray:
    """The LQR gain of ``(A, B2)`` for the cost ``∫ ‖C x + D2 u‖² dt`` (a gentle stabilizing
    gain for :func:`supervise`'s ``K0``; ``D2ᵀD2`` is regularized by 1e-9 of its norm if
    singular).

    Parameters
    ----------
    plant : Plant

    Returns
    -------
    (m_u, n) ndarray
        ``u = K x``.

    Raises
    ------
    ValueError
        If the Riccati equation has no stabilizing solution, or its gain does not stabilize
        A + B2 K (a mode the cost does not see).

    Examples
    --------
    >>> from fdsc import Plant
    >>> K = lqr_gain(Plant([[1.0]], [[1.0]], [[1.0]], [[1.0], [0.0]], [[0.0], [0.0]], [[0.0], [1.0]]))
    >>> bool(np.isclose(K[0, 0], -1.0 - np.sqrt(2.0)))      # ẋ = x + u, cost ∫ x² + u²
    True
    """
    from scipy.linalg import solve_continuous_are

    from .plant import as_plant

    plant = as_plant(plant)
    C, D2 = plant.C, plant.D2
    R = D2.T @ D2
    if np.linalg.matrix_rank(R) < R.shape[0]:
        R = R + 1e-9 * max(1.0, float(np.linalg.norm(R))) * np.eye(R.shape[0])
    S = C.T @ D2
    try:
        P = solve_continuous_are(plant.A, plant.B2, C.T @ C, R, s=S)
    except (np.linalg.LinAlgError, ValueError) as exc:
        raise ValueError(f"plant: the LQR problem of (A, B2, C, D2) has no stabilizing solution "
                         f"((A, B2) not stabilizable or (A, C) not detectable on the imaginary "
                         f"axis): {exc}") from exc
    K = -np.linalg.solve(R, plant.B2.T @ P + S.T)
    worst = float(np.max(np.linalg.eigvals(plant.A + plant.B2 @ K).real))
    if not worst < 0:
        raise ValueError(f"plant: the LQR gain of (A, B2, C, D2) does not stabilize A + B2 K (an "
                         f"eigenvalue has real part {worst:.3g}): the cost ∫‖C x + D2 u‖² does not "
                         f"see every unstable mode; choose K0 yourself")
    return K


def copies_loop(plant, controllers, K0, m, *, estimate_input: bool = False):
    """The loop with candidate m active in the realization through copies (Hespanha and Morse,
    Automatica 2002): state ``[x; c_0; …; c_{I−1}]`` with ``c_i = [x̂_i; x̂_k,i]`` a copy of
    candidate i's closed loop (its controller's states included) driven by ŵ, and
    ``u = K0 x + (u_m − K0 x̂_m)`` with ``u_m`` the control copy m applies; output
    ``z = C x + D1 d + D2 u``. For gains ``c_i = x̂_i`` and ``u = K0 x + (K_m − K0) x̂_m``.

    Parameters
    ----------
    plant : Plant
    controllers : sequence of Controller
    K0 : (m_u, n) ndarray
    m : int
        The active candidate.
    estimate_input : bool, optional
        False: one input d (the copies run on ŵ = d). True: inputs ``[d; ŵ]``, the plant on d,
        the copies (and the active controller's direct ŵ term) on ŵ.

    Returns
    -------
    LTISystem
    """
    from .plant import LTISystem

    A, B1, B2, C, D1, D2 = plant.A, plant.B1, plant.B2, plant.C, plant.D1, plant.D2
    n = A.shape[0]
    loops = [c.closed_loop(plant) for c in controllers]         # each copy runs on ŵ alone
    sizes = [lp.n_states for lp in loops]
    offs = np.cumsum([n, *sizes])
    N = int(offs[-1])
    Cu, Du = controllers[m].control_map(plant)
    S = np.zeros((n, sizes[m]))
    S[:, :n] = np.eye(n)
    o, k = offs[m], sizes[m]
    Aa = np.zeros((N, N))
    Aa[:n, :n] = A + B2 @ K0
    Aa[:n, o:o + k] = B2 @ (Cu - K0 @ S)
    Ca = np.zeros((C.shape[0], N))
    Ca[:, :n] = C + D2 @ K0
    Ca[:, o:o + k] = D2 @ (Cu - K0 @ S)
    for lp, oi, ki in zip(loops, offs[:-1], sizes, strict=True):
        Aa[oi:oi + ki, oi:oi + ki] = lp.A
    if estimate_input:
        Bd = np.zeros((N, B1.shape[1]))
        Bd[:n] = B1
        Bw = np.zeros((N, B1.shape[1]))
        Bw[:n] = B2 @ Du
        for lp, oi, ki in zip(loops, offs[:-1], sizes, strict=True):
            Bw[oi:oi + ki] = lp.B
        return LTISystem(Aa, np.hstack([Bd, Bw]), Ca, np.hstack([D1, D2 @ Du]))
    Ba = np.vstack([B1 + B2 @ Du, *[lp.B for lp in loops]])
    return LTISystem(Aa, Ba, Ca, D1 + D2 @ Du)


def control_maps(plant, controllers, K0, *, estimate_input: bool = False) -> list:
    """``[(Ku_m, Du_m)]``: the control input ``u = Ku_m ξ + Du_m w`` of each switched loop on its
    state ξ (:meth:`fdsc.Supervisor.switched_loops`), w its input (d, or ``[d; ŵ]``).

    Parameters
    ----------
    plant : Plant
    controllers : sequence of Controller
    K0 : (m_u, n) ndarray or None
        None: the direct realization; else the realization through copies.
    estimate_input : bool, optional
        As the switched loops.

    Returns
    -------
    list of (ndarray, ndarray)
    """
    n, m, nd = plant.n_states, plant.n_controls, plant.B1.shape[1]
    maps = [c.control_map(plant) for c in controllers]
    if K0 is None:
        sizes = [c.n_states for c in controllers]
        N = n + sum(sizes)
        offs = np.cumsum([n, *sizes])
        out = []
        for (Cu, Du), o, k in zip(maps, offs[:-1], sizes, strict=True):
            Ku = np.zeros((m, N))
            Ku[:, :n] = Cu[:, :n]
            Ku[:, o:o + k] = Cu[:, n:]
            out.append((Ku, np.hstack([np.zeros((m, nd)), Du]) if estimate_input else Du))
        return out
    sizes = [n + c.n_states for c in controllers]
    offs = np.cumsum([n, *sizes])
    N = int(offs[-1])
    out = []
    for (Cu, Du), o, k in zip(maps, offs[:-1], sizes, strict=True):
        S = np.zeros((n, k))
        S[:, :n] = np.eye(n)
        Ku = np.zeros((m, N))
        Ku[:, :n] = K0
        Ku[:, o:o + k] = Cu - K0 @ S
        out.append((Ku, np.hstack([np.zeros((m, nd)), Du]) if estimate_input else Du))
    return out


def band_filter(band):
    """The monitoring filter of a band for the band-power law: a second-order Butterworth
    low-pass at ϖ_l (LF band), high-pass at ϖ_h (HF), their cascade (MF), or the identity (EF);
    unit gain in the pass band.

    Parameters
    ----------
    band : Band

    Returns
    -------
    LTISystem
        Input ŵ, output the filtered ŵ.

    Raises
    ------
    TypeError
        If ``band`` is not a Band.
    ValueError
        If an edge lies outside [1e-6, 1e6] rad/s, where the filter's output is lost to
        rounding (its pass band is then a vanishing part of what it is fed).

    Examples
    --------
    >>> from fdsc import Band, freqresp
    >>> f = band_filter(Band.hf(10.0))
    >>> g = np.abs(freqresp(f, [1.0, 10.0, 1000.0])[:, 0, 0])
    >>> [round(float(v), 4) for v in g]                 # −3 dB at the edge
    [0.01, 0.7071, 1.0]
    """
    from .bands import Band
    from .plant import LTISystem

    check_type("band", band, Band, "an fdsc.Band")
    edges = [w for w in (band.lower, band.upper) if 0 < w < math.inf]
    if any(w > MAX_FILTER_EDGE or w < 1.0 / MAX_FILTER_EDGE for w in edges):
        raise ValueError(f"band: the monitoring filter resolves band edges in [1e-6, 1e6] rad/s, "
                         f"but {band.label} has edges {edges}")

    def section(w, high):
        A = np.array([[0.0, 1.0], [-w * w, -math.sqrt(2.0) * w]])
        B = np.array([[0.0], [1.0]])
        if high:                        # s² / (s² + √2 ω s + ω²) = 1 − (√2 ω s + ω²) / (…)
            return A, B, np.array([[-w * w, -math.sqrt(2.0) * w]]), np.array([[1.0]])
        return A, B, np.array([[w * w, 0.0]]), np.array([[0.0]])

    parts = []
    if band.lower > 0:
        parts.append(section(band.lower, True))
    if math.isfinite(band.upper):
        parts.append(section(band.upper, False))
    if not parts:
        return LTISystem(np.array([[-1.0]]), np.zeros((1, 1)), np.zeros((1, 1)), np.array([[1.0]]))
    A, B, C, D = parts[0]
    for A2, B2, C2, D2 in parts[1:]:                # the second driven by the first's output
        A = np.block([[A, np.zeros((A.shape[0], A2.shape[0]))], [B2 @ C, A2]])
        B = np.vstack([B, B2 @ D])
        C = np.hstack([D2 @ C, C2])
        D = D2 @ D
    return LTISystem(A, B, C, D)
