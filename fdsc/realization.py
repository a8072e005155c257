"""What a law on the disturbance estimate is built from: the gentle stabilizing gain of the
realization through copies (:func:`lqr_gain`), the switched loops of that realization, and the
band-power law's monitoring filters (:func:`band_filter`).
"""

from __future__ import annotations

import math

import numpy as np

from ._validation import check_type

__all__ = ["lqr_gain", "band_filter", "MAX_FILTER_EDGE"]

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


def copies_loop(plant, gains, K0, m):
    """The loop with candidate m active in the realization through copies: state
    ``[x; x̂_0; …; x̂_{I−1}]``, ``u = K0 x + (K_m − K0) x̂_m``, each copy ``ẋ̂_i = (A + B2 K_i) x̂_i
    + B1 d``, output ``z = C x + D1 d + D2 u``."""
    from .plant import LTISystem

    A, B1, B2, C, D1, D2 = plant.A, plant.B1, plant.B2, plant.C, plant.D1, plant.D2
    n, nm = A.shape[0], len(gains)
    N = n * (nm + 1)
    Aa = np.zeros((N, N))
    Aa[:n, :n] = A + B2 @ K0
    Aa[:n, n * (m + 1):n * (m + 2)] = B2 @ (gains[m] - K0)
    Ca = np.zeros((C.shape[0], N))
    Ca[:, :n] = C + D2 @ K0
    Ca[:, n * (m + 1):n * (m + 2)] = D2 @ (gains[m] - K0)
    for i, K in enumerate(gains):
        Aa[n * (i + 1):n * (i + 2), n * (i + 1):n * (i + 2)] = A + B2 @ K
    return LTISystem(Aa, np.tile(B1, (nm + 1, 1)), Ca, D1)


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
