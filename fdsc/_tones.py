"""ESPRIT over a window of samples: the identification of tones shared by
:func:`fdsc.predictive.identify_tones` and :class:`fdsc.predictive.PredictiveLaw` (internal).

ESPRIT (Roy and Kailath 1989) on the second differences of the samples: the signal subspace of
their lag matrix, the frequencies from its shift invariance, then the amplitudes by least
squares with a polynomial trend. :func:`_esprit` is the law's (the rank set by ``rank_tol``);
:func:`_below_rank_tol` is the second pass of :func:`~fdsc.predictive.identify_tones`.
"""

from __future__ import annotations

import functools
import math
import warnings

import numpy as np

from .exceptions import ResolutionWarning

__all__ = []


def _hankel_gram(y, L):
    """``H.T @ H`` of the lag matrix ``H[r, i] = y[r + i]`` (``N − L + 1`` rows, L columns) in
    O(N L + L²) operations instead of O(N L²): its first row by one product, the rest along each
    diagonal by the recurrence ``G[i+1, j+1] = G[i, j] + y[R+i] y[R+j] − y[i] y[j]`` (R rows)."""
    y = np.asarray(y, dtype=float)
    R = y.size - L + 1
    first = np.lib.stride_tricks.sliding_window_view(y, R)[:L] @ y[:R]      # G[0, k], k < L
    if L == 1:
        return first.reshape(1, 1)
    pad = np.concatenate([y, np.zeros(L)])
    hi = np.lib.stride_tricks.sliding_window_view(pad[R:], L)[:L - 1]       # y[R+m+k]
    lo = np.lib.stride_tricks.sliding_window_view(y, L)[:L - 1]             # y[m+k]
    steps = y[R:R + L - 1, None] * hi - y[:L - 1, None] * lo                 # (L−1, L): m, k
    diag = np.empty((L, L))                                                   # diag[i, k] = G[i, i+k]
    diag[0] = first
    np.cumsum(steps, axis=0, out=diag[1:])
    diag[1:] += first[None, :]
    i, k = _upper(L)
    G = np.empty((L, L))
    G[i, i + k] = diag[i, k]
    G[i + k, i] = diag[i, k]
    return G


@functools.cache
def _upper(L):
    """Row and diagonal offset of every entry on and above the diagonal of an L × L matrix."""
    i, j = np.triu_indices(L)
    return i, j - i


def _lag_matrix(y, lags):
    """The lag matrix of the second differences of y (None if it has fewer than 3 columns)."""
    yd = np.diff(y, 2)
    L = min(lags, yd.size // 2)
    if L < 3:
        return None
    return np.lib.stride_tricks.sliding_window_view(yd, L)


def _frequencies(V, step, lo, hi, T, edge_share):
    """The frequencies in the band of the signal subspace V (shift invariance), one per tone.

    A frequency within ``edge_share`` of the resolution 2π/T outside the band is kept."""
    Phi = np.linalg.lstsq(V[:-1], V[1:], rcond=None)[0]
    w = np.abs(np.angle(np.linalg.eigvals(Phi))) / step
    tol = edge_share * 2 * math.pi / T
    w = np.sort(w[(w >= lo - tol) & (w <= hi + tol)])
    if w.size:                           # the two roots of a real tone give one frequency
        w = w[np.r_[True, np.diff(w) > 1e-6 * np.maximum(1.0, w[1:])]]
    return w


def _esprit(y, step, lo, hi, max_tones, lags, rank_tol, edge_share):
    """The frequencies in [lo, hi] of the tones in y (module docstring), with the band's edges
    widened by ``edge_share`` of the window's resolution."""
    yd = np.diff(y, 2)
    L = min(lags, yd.size // 2)
    if L < 3:
        return np.zeros(0)
    ev, vec = np.linalg.eigh(_hankel_gram(yd, L))
    ev, vec = ev[::-1], vec[:, ::-1]
    if not ev[0] > 0:
        return np.zeros(0)
    r = int(min(2 * max_tones, np.sum(ev > rank_tol ** 2 * ev[0]), L - 1))
    if r < 1:
        return np.zeros(0)
    return _frequencies(vec[:, :r], step, lo, hi, step * (y.size - 1), edge_share)


def _below_rank_tol(y, step, lo, hi, max_tones, lags, rank_tol, trend, edge_share, floor_factor):
    """The tones of y identified again with the directions of the lag matrix that lie below
    ``rank_tol`` but stand ``floor_factor`` times above its noise floor (None if there are
    none): a slow part that the second differences leave, or the split of two tones closer than
    the window resolves. ESPRIT without them is biased by them; with them it finds the tones of
    the window, and those whose share of the lag matrix is below ``rank_tol`` are dropped."""
    H = _lag_matrix(y, lags)
    if H is None:
        return None
    L = H.shape[1]
    _u, sv, vt = np.linalg.svd(H, full_matrices=False)
    if not sv[0] > 0:
        return None
    r = int(min(2 * max_tones, np.sum(sv > rank_tol * sv[0]), L - 1))
    if r >= L - 1:
        return None
    floor = max(float(np.median(sv[r:])), np.finfo(float).eps * sv[0] * math.sqrt(H.size))
    r2 = int(min(np.sum(sv > floor_factor * floor), L - 1))
    if r2 <= r:
        return None
    w = _frequencies(vt[:r2].T, step, lo, hi, step * (y.size - 1), edge_share)
    if not w.size:
        return w
    tau = step * (np.arange(y.size) - (y.size - 1))
    c, _res = _fit(tau, y, w, trend)
    # a tone's share of the lag matrix: its amplitude times the gain of the second difference
    share = np.abs(c) * (2 * np.sin(w * step / 2)) ** 2
    keep = share >= rank_tol * share.max()
    keep &= share >= np.sort(share)[::-1][min(max_tones, share.size) - 1]
    return w[keep]


def _fit(tau, y, w, trend):
    """Least-squares amplitudes of tones w with a polynomial trend; (c, residual)."""
    w = np.asarray(w, dtype=float)
    s = tau / max(-float(tau[0]), 1e-300)
    B = np.empty((tau.size, trend + 1 + 2 * w.size))
    for k in range(trend + 1):
        B[:, k] = s ** k
    phase = tau[:, None] * w[None, :]
    np.cos(phase, out=B[:, trend + 1::2])
    np.sin(phase, out=B[:, trend + 2::2])
    coef, *_ = np.linalg.lstsq(B, y, rcond=None)
    a, b = coef[trend + 1::2], coef[trend + 2::2]
    res = y - B @ coef
    return a - 1j * b, float(np.mean(res ** 2))


def _warn_unresolved(w, step, n):
    """Warn (:class:`ResolutionWarning`) of tones closer than the window of n samples resolves."""
    T = step * (n - 1)
    res = 2 * math.pi / T
    close = np.flatnonzero(np.diff(w) < res)
    if close.size:
        k = int(close[0])
        warnings.warn(f"identify_tones: the tones at {w[k]:.6g} and {w[k + 1]:.6g} rad/s are closer than the "
                      f"window resolves (2π/T = {res:.4g} rad/s for a window of T = {T:.4g} s): their "
                      "amplitudes and phases are ill-conditioned (a small error in the samples moves them "
                      "much, and below the noise they come back as one tone); lengthen the window",
                      ResolutionWarning, stacklevel=3)
    nyquist = math.pi / step
    near = w[nyquist - w < res / 2]
    if near.size:
        warnings.warn(f"identify_tones: the tone at {near[-1]:.6g} rad/s lies within π/T = "
                      f"{res / 2:.4g} rad/s of the Nyquist frequency π/step = {nyquist:.6g} rad/s, where its "
                      "samples barely tell it from its alias at 2π/step − ω: its amplitude and phase are not "
                      "determined (at π/step only a·sin φ of a·sin(ωt + φ) is seen); sample faster, or keep "
                      f"the band's top below {nyquist - res / 2:.6g} rad/s", ResolutionWarning, stacklevel=3)
