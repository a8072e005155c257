"""The NumPy reference of the compiled kernel of :func:`fdsc.simulate` (``kernel="numpy"``),
kept for the tests and the benchmark. Internal.

It evaluates the particular solution ``x_p`` of every mode at both ends of every step
beforehand, from NumPy's cos and sin of ``ω_j t_k + φ_j`` on the whole grid, and then takes the
same exact step ``x_{k+1} = x_p(t_{k+1}) + Φ_i (x_k − x_p(t_k))`` in a plain Python loop, the
switching rule run by the interpreter. The compiled kernel (:mod:`fdsc._simulate_kernel`)
rotates phasors instead; the two agree to rounding.
"""

import numpy as np
from numba import njit

from .frequency import check_no_pole_at
from .rules import apply_rule

__all__ = []


def _particular_many(As, B, d, t, derivative=False):
    """x_p (and ẋ_p) of several modes at once; cos and sin of each tone are computed once."""
    t = np.asarray(t, dtype=float)
    n = As[0].shape[0]
    for m, A in enumerate(As):
        check_no_pole_at(A, d.frequencies, what=f"the forced response of mode {m} to the disturbance")
    xps = [np.zeros((t.size, n)) for _ in As]
    xdps = [np.zeros((t.size, n)) for _ in As] if derivative else None
    b = np.asarray(B, dtype=float).reshape(-1)
    for a, w, ph in zip(d.amplitudes, d.frequencies, d.phases, strict=True):
        theta = w * t + ph
        c, s = np.cos(theta), np.sin(theta)
        for m, A in enumerate(As):
            X = np.linalg.solve(1j * w * np.eye(n) - A, b * a)
            # Im(X e^{jθ}) = Im X cos θ + Re X sin θ
            _add_tone(xps[m], c, s, np.ascontiguousarray(X.imag), np.ascontiguousarray(X.real))
            if derivative:
                Xd = 1j * w * X
                _add_tone(xdps[m], c, s, np.ascontiguousarray(Xd.imag),
                          np.ascontiguousarray(Xd.real))
    return xps, xdps


@njit(cache=True)
def _add_tone(xp, c, s, Xi, Xr):
    """xp += outer(c, Xi) + outer(s, Xr) in one pass (the same operations in the same order as
    NumPy's, so the same numbers)."""
    for k in range(xp.shape[0]):
        for r in range(xp.shape[1]):
            xp[k, r] += c[k] * Xi[r] + s[k] * Xr[r]


def _particular_steps(As, B, pieces, t):
    """x_p of every mode at the left and right end of every step [t_k, t_{k+1}), using the
    sinusoids of the piece that owns the step (``pieces``: :func:`_segments`). Returns two
    (I, N − 1, n) arrays."""
    n, N = As[0].shape[0], t.size
    left = np.zeros((len(As), N - 1, n))
    right = np.zeros((len(As), N - 1, n))
    for k0, k1, part in pieces:
        if part is None or k1 <= k0:
            continue
        xps, _ = _particular_many(As, B, part, t[k0:k1 + 1])
        for m, xp in enumerate(xps):
            left[m, k0:k1] = xp[:-1]
            right[m, k0:k1] = xp[1:]
    return left, right


def _kernel_numpy(Phi, left, right, A, B, d, dd, W, x0, sigma0, candidate, rparams, ring, ring_sum,
                  istate):
    """Reference implementation of the compiled kernel (:func:`fdsc._simulate_kernel.kernel`) in
    NumPy arithmetic and a plain Python loop, with ``x_p`` at both ends of every step evaluated
    beforehand from NumPy's cos and sin (``left``, ``right``); the rule is the same function run
    by the interpreter."""
    n_modes, n = A.shape[0], A.shape[1]
    second = W.shape[1] == 3 * n
    N = d.shape[0]
    x = np.empty((N, n))
    sigma = np.empty(N, np.int64)
    x[0] = x0
    prev = sigma0
    eff = np.empty(n_modes)
    for k in range(N):
        xk = x[k]
        if n_modes > 1:
            Am = A if candidate else np.broadcast_to(A[prev], A.shape)
            xd = Am @ xk + B * d[k]
            parts = [xd, np.broadcast_to(xk, (n_modes, n))]
            if second:
                parts.insert(0, np.einsum("irc,ic->ir", Am, xd) + B * dd[k])
            v = np.concatenate(parts, axis=1)
            scores = np.einsum("ir,irc,ic->i", v, W, v)
            prev = apply_rule.py_func(scores, scores.shape[0], prev, k, rparams, ring, ring_sum, istate, eff)
        sigma[k] = prev
        if k + 1 < N:
            x[k + 1] = right[prev, k] + Phi[prev] @ (xk - left[prev, k])
    return x, sigma
