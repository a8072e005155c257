"""Exact-discretization simulation of LTI and switched closed loops under the paper's disturbances.

Between two samples the active mode i is an LTI system driven by a sum of sinusoids, so the
step is exact: with the steady-state (particular) solution ``x_p`` of mode i for the sinusoids
active on ``[t_k, t_{k+1})``,

    x_{k+1} = x_p(t_{k+1}) + e^{A_i Δt} (x_k − x_p(t_k)).

No quadrature of the input is involved; the only approximation of a switched run is that the
switching law is evaluated on the sample grid. The hot loop runs in a
compiled numba kernel; :func:`_kernel_numpy` is the same method in plain Python/NumPy, kept for
the tests and the benchmark.
"""

from dataclasses import dataclass

import numpy as np
from numba import njit
from scipy.linalg import expm

from ._validation import as_positive
from .bands import Band
from .energy import check_weight
from .plant import LTISystem
from .signals import Piecewise, Sinusoids

__all__ = ["SimResult", "particular", "simulate", "time_grid", "LAWS"]

#: How ẋ enters the switching law: "previous" (default: ẋ = A_σ(t⁻) x + B d, the measured
#: derivative) or "candidate" (each candidate i is scored with its own ẋ = A_i x + B d).
LAWS = ("previous", "candidate")


@dataclass(frozen=True)
class SimResult:
    """A simulated run on the grid ``t``.

    Attributes
    ----------
    t : (N,) ndarray
    x, xdot : (N, n) ndarray
        State and its derivative under the mode active on ``[t_k, t_{k+1})``.
    z : (N, p) ndarray
        Regulated output.
    d : (N,) ndarray
        Disturbance samples.
    sigma : (N,) int ndarray
        Active mode index (0-based) on ``[t_k, t_{k+1})``.
    """

    t: np.ndarray
    x: np.ndarray
    xdot: np.ndarray
    z: np.ndarray
    d: np.ndarray
    sigma: np.ndarray

    @property
    def switch_times(self):
        """Instants at which the active mode changes."""
        return self.t[1:][np.diff(self.sigma) != 0]

    def energy(self):
        """∫ zᵀz dt over the run (composite Simpson's rule on the grid)."""
        from scipy.integrate import simpson

        return float(simpson(np.sum(self.z**2, axis=1), x=self.t))

    def input_energy(self):
        """∫ d² dt over the run (composite Simpson's rule on the grid)."""
        from scipy.integrate import simpson

        return float(simpson(self.d**2, x=self.t))

    def time_share(self):
        """Fraction of the horizon spent in each mode (β_i of Theorem 1(3))."""
        n_modes = int(self.sigma.max()) + 1
        dt = np.diff(self.t)
        return np.array([dt[self.sigma[:-1] == i].sum() for i in range(n_modes)]) / (
            self.t[-1] - self.t[0])


def time_grid(horizon, dt):
    """Uniform grid ``0, dt, …, horizon``; ``horizon`` must be a multiple of ``dt``.

    Raises
    ------
    ValueError
        If ``dt ≤ 0``, ``horizon ≤ 0`` or the horizon is not a multiple of dt.
    """
    horizon, dt = as_positive("horizon", horizon), as_positive("dt", dt)
    n = round(horizon / dt)
    if abs(n * dt - horizon) > 1e-9 * horizon:
        raise ValueError(f"horizon ({horizon:g}) must be a multiple of dt ({dt:g})")
    return np.linspace(0.0, horizon, n + 1)


def particular(A, B, d, t):
    """Steady-state response ``x_p`` and ``ẋ_p`` of ``dx/dt = A x + B d`` to ``d`` (Sinusoids).

    ``x_p(t) = Σ Im(X_k e^{j(ω_k t + φ_k)})`` with ``X_k = (jω_k I − A)⁻¹ B a_k``. Requires
    ``jω_k`` not to be an eigenvalue of A (A need not be Hurwitz).
    """
    (xp,), (xdp,) = _particular_many([np.asarray(A, float)], B, d, t, derivative=True)
    return xp, xdp


def _particular_many(As, B, d, t, derivative=False):
    """x_p (and ẋ_p) of several modes at once; cos and sin of each tone are computed once."""
    t = np.asarray(t, dtype=float)
    n = As[0].shape[0]
    xps = [np.zeros((t.size, n)) for _ in As]
    xdps = [np.zeros((t.size, n)) for _ in As] if derivative else None
    b = np.asarray(B, dtype=float).reshape(-1)
    for a, w, ph in zip(d.amplitudes, d.frequencies, d.phases, strict=True):
        theta = w * t + ph
        c, s = np.cos(theta), np.sin(theta)
        for m, A in enumerate(As):
            X = np.linalg.solve(1j * w * np.eye(n) - A, b * a)
            # Im(X e^{jθ}) = Im X cos θ + Re X sin θ
            xps[m] += np.outer(c, X.imag) + np.outer(s, X.real)
            if derivative:
                Xd = 1j * w * X
                xdps[m] += np.outer(c, Xd.imag) + np.outer(s, Xd.real)
    return xps, xdps


def _segments(d, t):
    """Split the grid into segments with one Sinusoids each: list of (k0, k1, Sinusoids|None)."""
    if isinstance(d, Sinusoids):
        return [(0, t.size - 1, d)]
    if not isinstance(d, Piecewise):
        raise TypeError(f"d must be Sinusoids or Piecewise, found {type(d).__name__}")
    dt = t[1] - t[0]
    out = []
    idx = []
    for b in d.breaks:
        k = round((b - t[0]) / dt)
        if abs(t[0] + k * dt - b) > 1e-9 * max(1.0, abs(b)):
            raise ValueError(f"the disturbance switches at t = {b:g}, which is not on the grid "
                             f"(dt = {dt:g}); choose dt dividing every break")
        idx.append(min(max(k, 0), t.size - 1))
    if idx[0] > 0:
        out.append((0, idx[0], None))
    for j, part in enumerate(d.parts):
        if idx[j + 1] > idx[j]:
            out.append((idx[j], idx[j + 1], part))
    if idx[-1] < t.size - 1:
        out.append((idx[-1], t.size - 1, None))
    return out


def _particular_steps(As, B, d, t):
    """x_p of every mode at the left and right end of every step [t_k, t_{k+1}), using the
    sinusoids of the segment that owns the step. Returns two (I, N − 1, n) arrays."""
    n, N = As[0].shape[0], t.size
    left = np.zeros((len(As), N - 1, n))
    right = np.zeros((len(As), N - 1, n))
    for k0, k1, part in _segments(d, t):
        if part is None or k1 <= k0:
            continue
        xps, _ = _particular_many(As, B, part, t[k0:k1 + 1])
        for m, xp in enumerate(xps):
            left[m, k0:k1] = xp[:-1]
            right[m, k0:k1] = xp[1:]
    return left, right


def _law_matrices(psis, Qs):
    """Stack the quadratic forms of the switching law: W_i = [[ψ11 Q, ψ12 Q], [ψ21 Q, ψ22 Q]]."""
    return np.array([np.kron(p, Q) for p, Q in zip(psis, Qs, strict=True)])


@njit(cache=True)
def _kernel_numba(Phi, left, right, A, B, d, W, x0, sigma0, candidate):
    n_modes, n = A.shape[0], A.shape[1]
    N = d.shape[0]
    x = np.empty((N, n))
    sigma = np.empty(N, np.int64)
    x[0] = x0
    prev = sigma0
    v = np.empty(2 * n)
    for k in range(N):
        xk = x[k]
        if n_modes > 1:
            best = -np.inf
            choice = prev
            for i in range(n_modes):
                if candidate or i == 0:
                    # the measured ẋ (default law) is the same for every candidate: build v once
                    m = i if candidate else prev
                    for r in range(n):
                        acc = B[r] * d[k]
                        for c in range(n):
                            acc += A[m, r, c] * xk[c]
                        v[r] = acc
                        v[n + r] = xk[r]
                score = 0.0
                for r in range(2 * n):
                    row = 0.0
                    for c in range(2 * n):
                        row += W[i, r, c] * v[c]
                    score += v[r] * row
                if score > best:
                    best = score
                    choice = i
            prev = choice
        sigma[k] = prev
        if k + 1 < N:
            for r in range(n):
                acc = right[prev, k, r]
                for c in range(n):
                    acc += Phi[prev, r, c] * (xk[c] - left[prev, k, c])
                x[k + 1, r] = acc
    return x, sigma


def _kernel_numpy(Phi, left, right, A, B, d, W, x0, sigma0, candidate):
    """Reference implementation of :func:`_kernel_numba` (same arithmetic, plain Python loop)."""
    n_modes, n = A.shape[0], A.shape[1]
    N = d.shape[0]
    x = np.empty((N, n))
    sigma = np.empty(N, np.int64)
    x[0] = x0
    prev = sigma0
    for k in range(N):
        xk = x[k]
        if n_modes > 1:
            if candidate:
                v = np.concatenate([A @ xk + B * d[k], np.broadcast_to(xk, (n_modes, n))], axis=1)
            else:
                v = np.broadcast_to(np.concatenate([A[prev] @ xk + B * d[k], xk]), (n_modes, 2 * n))
            scores = np.einsum("ir,irc,ic->i", v, W, v)
            prev = int(np.argmax(scores))
        sigma[k] = prev
        if k + 1 < N:
            x[k + 1] = right[prev, k] + Phi[prev] @ (xk - left[prev, k])
    return x, sigma


def simulate(modes, d, t, *, x0=None, law_bands=None, law_Q=None, law="previous", sigma0=0,
             kernel="numba"):
    """Simulate an LTI (one mode) or switched (several modes) closed loop exactly on a grid.

    Parameters
    ----------
    modes : LTISystem or list of LTISystem
        Closed loops ``(A_i, B, C_i, D)``; all share B and D (state feedback).
    d : Sinusoids or Piecewise
        Scalar disturbance; Piecewise breaks must lie on the grid.
    t : (N,) array_like
        Uniform grid (see :func:`time_grid`).
    x0 : (n,) array_like, optional
        Initial state (default 0).
    law_bands : list of Band, optional
        Ω_i of the switching law (required for several modes).
    law_Q : list of (n, n) array_like, optional
        Q_i of the switching law (symmetric positive definite).
    law : {"previous", "candidate"}
        How ẋ enters the law (see :data:`LAWS`).
    sigma0 : int
        Mode assumed active before t = 0 (used for ẋ at t = 0).
    kernel : {"numba", "numpy"}

    Returns
    -------
    SimResult

    Raises
    ------
    ValueError
        On mismatched mode/law counts, a non-uniform grid, non-PD Q, unknown law or kernel.
    """
    modes = [modes] if isinstance(modes, LTISystem) else list(modes)
    if not modes or not all(isinstance(m, LTISystem) for m in modes):
        raise TypeError("modes must be an LTISystem or a non-empty list of LTISystem")
    n = modes[0].n_states
    B, D = modes[0].B, modes[0].D
    for m in modes[1:]:
        if m.A.shape != (n, n) or not np.array_equal(m.B, B) or m.C.shape != modes[0].C.shape:
            raise ValueError("modes must share B, D and the state and output dimensions")
    if B.shape[1] != 1:
        raise ValueError(f"the disturbance must be scalar (B of shape (n, 1)), found {B.shape}")
    if law not in LAWS:
        raise ValueError(f"law must be one of {LAWS}, found {law!r}")
    if kernel not in ("numba", "numpy"):
        raise ValueError(f"kernel must be 'numba' or 'numpy', found {kernel!r}")
    n_modes = len(modes)
    if n_modes > 1:
        if law_bands is None or law_Q is None or len(law_bands) != n_modes or len(law_Q) != n_modes:
            raise ValueError(f"law_bands and law_Q must each list one entry per mode ({n_modes} modes)")
        if not all(isinstance(b, Band) for b in law_bands):
            raise TypeError("law_bands must be a list of fdsc.Band")
        Qs = [check_weight(Q, n) for Q in law_Q]
        W = _law_matrices([b.psi.real for b in law_bands], Qs)
    else:
        W = np.zeros((1, 2 * n, 2 * n))
    if not 0 <= int(sigma0) < n_modes:
        raise ValueError(f"sigma0 must be a mode index in [0, {n_modes}), found {sigma0}")
    t = np.asarray(t, dtype=float)
    if t.ndim != 1 or t.size < 2:
        raise ValueError("t must be a 1-D grid of at least 2 points")
    dt = t[1] - t[0]
    if dt <= 0 or not np.allclose(np.diff(t), dt, rtol=1e-9, atol=0):
        raise ValueError("t must be a uniform increasing grid (dt > 0)")
    x0 = np.zeros(n) if x0 is None else np.asarray(x0, dtype=float).reshape(-1)
    if x0.size != n:
        raise ValueError(f"x0 must have {n} entries, found {x0.size}")
    dvals = d(t)
    Phi = np.array([expm(m.A * dt) for m in modes])
    A = np.array([m.A for m in modes])
    left, right = _particular_steps(list(A), B, d, t)
    run = _kernel_numba if kernel == "numba" else _kernel_numpy
    x, sigma = run(Phi, left, right, A, np.ascontiguousarray(B[:, 0]), dvals, W, x0,
                   int(sigma0), law == "candidate")
    xdot = np.einsum("krc,kc->kr", A[sigma], x) + np.outer(dvals, B[:, 0])
    Cs = np.array([m.C for m in modes])
    z = np.einsum("krc,kc->kr", Cs[sigma], x) + np.outer(dvals, D[:, 0])
    return SimResult(t, x, xdot, z, dvals, sigma)
