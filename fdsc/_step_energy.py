"""Exact energies of sampled runs, step by step: the quadratic forms of one step and ``∫ d²``.

Internal: used by :mod:`fdsc.stream` (the compiled loop and the closed form of LTI runs) and by
:func:`fdsc.simulate.simulate`.

Within a step from ``t_k`` to ``t_k + h`` the active mode (or the held input) is fixed and the
disturbance is known in closed form, so ``∫ zᵀz`` over the step is an exact quadratic form of
the state at ``t_k`` augmented with what drives the step:

* under tones ``d = Σ a_j sin(ω_j t + φ_j)``: ``η = [R x_k; a∘c; a∘s]`` with ``c_j, s_j`` the
  cos and sin of ``ω_j t_k + φ_j`` (the oscillators of :mod:`fdsc._blocks`);
* under a held input ``u`` (zero- or first-order hold of samples): ``η = [R x_k; u_k;
  u_{k+1} − u_k]`` (the slope's entry is unused for a zero-order hold).

The form ``Q = ∫₀^h e^{Fᵀs} GᵀG e^{Fs} ds`` of the augmented system ``(F, G)`` comes from
:func:`fdsc._blocks._gram` (Taylor series and doublings, no Van Loan block with ``e^{−Aᵀh}``,
which overflows for a stiff loop). ``R`` is the change of coordinates that separates the fast and
slow parts of a stiff mode (:func:`fdsc._blocks._coordinates`; None where there is none): the
energy is formed in the coordinates where its terms are of its own size.

A switched run's output jumps at a switch (``C + D2 K_σ`` changes), so a quadrature of its samples
(Simpson's rule, the trapezoid) is wrong by up to a step's energy at every switch: for a law that
switches at almost every sample that is the whole energy's order (9 % on the paper's FDSC under its
LF disturbance). These forms make every energy the exact integral of the simulated run.
"""

import math

import numpy as np
from numba import njit

from ._blocks import _coordinates, _gram, _step

__all__ = []


def mode_coordinates(modes):
    """The coordinates of :func:`fdsc._blocks._coordinates` for each closed loop of ``modes``
    (LTISystem with one disturbance input), computed once per distinct A."""
    out, seen = [], {}
    for m in modes:
        key = (m.A.tobytes(), m.C.tobytes(), m.B.tobytes(), m.D.tobytes())
        if key not in seen:
            seen[key] = _coordinates(m.A, m.B[:, :1], m.C, m.D[:, :1])
        out.append(seen[key])
    return out


def sine_forms(coords, frequencies, h):
    """The step forms of every mode under tones of unit amplitude at ``frequencies``.

    Returns ``(Q, R)``: Q ``(I, n + 2T, n + 2T)`` on ``η = [R x; a∘c; a∘s]`` (so the caller
    multiplies the oscillators by the amplitudes), R ``(I, n, n)`` (the identity where a mode is
    not split) and ``split`` ``(I,)`` bool."""
    w = np.asarray(frequencies, dtype=float)
    n = coords[0][0].shape[0]
    W = n + 2 * w.size
    Q = np.zeros((len(coords), W, W))
    R = np.tile(np.eye(n), (len(coords), 1, 1))
    split = np.zeros(len(coords), dtype=np.bool_)
    for i, co in enumerate(coords):
        _, q, r = _step(co, w, h)
        Q[i] = q
        if r is not None:
            R[i], split[i] = r, True
    return Q, R, split


def held_forms(coords, h, hold):
    """The step forms of every mode under a held input: Q ``(I, n + 2, n + 2)`` on
    ``η = [R x; u_k; u_{k+1} − u_k]`` (zero-order hold: the last entry's rows are zero), R and
    ``split`` as in :func:`sine_forms`."""
    n = coords[0][0].shape[0]
    Q = np.zeros((len(coords), n + 2, n + 2))
    R = np.tile(np.eye(n), (len(coords), 1, 1))
    split = np.zeros(len(coords), dtype=np.bool_)
    for i, (A, B, C, D, _S, Si) in enumerate(coords):
        F = np.zeros((n + 2, n + 2))
        F[:n, :n] = A
        F[:n, n] = B[:, 0]
        if hold == "foh":
            F[n, n + 1] = 1.0 / h            # u(t_k + s) = u_k + (s / h) (u_{k+1} − u_k)
        G = np.zeros((C.shape[0], n + 2))
        G[:, :n] = C
        G[:, n] = D[:, 0]
        _, Q[i] = _gram(F, G.T @ G, h)
        if Si is not None:
            R[i], split[i] = Si, True
    return Q, R, split


def pack(Q):
    """The upper triangles of symmetric forms ``(..., W, W)``, row by row, off-diagonal entries
    doubled: ``ηᵀQη = Σ_a η_a Σ_{b≥a} packed[a, b] η_b``."""
    W = Q.shape[-1]
    iu = np.triu_indices(W)
    full = Q + np.swapaxes(Q, -1, -2) - Q * np.eye(W)
    return np.ascontiguousarray(full[..., iu[0], iu[1]])


def _cos_integral(nu, psi, ta, tb):
    """``∫_{ta}^{tb} cos(ν t + ψ) dt`` for arrays of ν and ψ, without cancellation at small ν:
    ``L cos(ν t_m + ψ) sinc(ν L / 2)`` (L = tb − ta, t_m the middle)."""
    L = tb - ta
    tm = 0.5 * (ta + tb)
    return L * np.cos(nu * tm + psi) * np.sinc(nu * L / (2.0 * np.pi))


def sines_input_energy(parts, seg_start, dt, ends):
    """``∫₀^{t_K} d²`` for every K of ``ends``, where the steps ``seg_start[s] … seg_start[s+1] − 1``
    carry the tones ``parts[s]`` (a Sinusoids, or None for d = 0) at the times ``t_k = k dt``.

    Exact: ``sin θ_j sin θ_l = ½ (cos(θ_j − θ_l) − cos(θ_j + θ_l))`` integrated over each piece."""
    ends = np.asarray(ends, dtype=np.int64)
    total = np.zeros(ends.size)
    for s, part in enumerate(parts):
        if part is None or part.frequencies.size == 0:
            continue
        k0, k1 = int(seg_start[s]), int(seg_start[s + 1])
        kb = np.clip(ends, k0, k1)
        has = kb > k0
        if not np.any(has):
            continue
        a, w, ph = part.amplitudes, part.frequencies, part.phases
        aa = np.outer(a, a)
        ta, tb = k0 * dt, kb[has] * dt
        dw, dp = w[:, None] - w[None, :], ph[:, None] - ph[None, :]
        sw, sp = w[:, None] + w[None, :], ph[:, None] + ph[None, :]
        val = 0.5 * np.einsum("jl,jlb->b", aa,
                              _cos_integral(dw[..., None], dp[..., None], ta, tb[None, None, :])
                              - _cos_integral(sw[..., None], sp[..., None], ta, tb[None, None, :]))
        total[has] += val
    return total


def held_input_energy(u, dt, hold, ends):
    """``∫₀^{t_K} u²`` of the held samples ``u`` for every K of ``ends``: ``dt u_k²`` per step
    (zero-order hold) or ``dt (u_k² + u_k u_{k+1} + u_{k+1}²) / 3`` (first-order)."""
    u = np.asarray(u, dtype=float)
    if hold == "foh":
        step = dt * (u[:-1] ** 2 + u[:-1] * u[1:] + u[1:] ** 2) / 3.0
    else:
        step = dt * u[:-1] ** 2
    cum = np.concatenate([[0.0], np.cumsum(step)])
    return cum[np.asarray(ends, dtype=np.int64)]


def _oscillator_form(frequencies, h):
    """The form of ``∫ d²`` over a step on ``[a∘c; a∘s]`` (``d = Σ a_j s_j``), (2T, 2T)."""
    w = np.asarray(frequencies, dtype=float)
    T = w.size
    F = np.zeros((2 * T, 2 * T))
    F[:T, T:] = -np.diag(w)
    F[T:, :T] = np.diag(w)
    g = np.zeros((1, 2 * T))
    g[0, T:] = 1.0
    return _gram(F, g.T @ g, h)[1]


#: Steps between two phasors of :func:`_trajectory_kernel` computed by cos and sin (in between,
#: each is the previous one times the exact rotation of one step: at most this many roundings).
_REBASE = 64


@njit(cache=True)
def _trajectory_kernel(x, sigma, t, k0, k1, w, a, ph, Q, R, split, out):
    """``ηᵀ Q[σ_k] η`` for the steps k0 … k1 − 1 of a stored run under one piece's tones, with
    ``η = [R x_k; a∘c; a∘s]`` (the oscillators at t_k)."""
    n = x.shape[1]
    T = w.size
    W = n + 2 * T
    eta = np.zeros(W)
    cr = np.cos(w * (t[1] - t[0]))
    sr = np.sin(w * (t[1] - t[0]))
    c = np.zeros(T)
    sn = np.zeros(T)
    for k in range(k0, k1):
        if (k - k0) % _REBASE == 0:
            for j in range(T):
                th = w[j] * t[k] + ph[j]
                c[j] = math.cos(th)
                sn[j] = math.sin(th)
        m = sigma[k]
        if split[m]:
            for r in range(n):
                acc = 0.0
                for q in range(n):
                    acc += R[m, r, q] * x[k, q]
                eta[r] = acc
        else:
            for r in range(n):
                eta[r] = x[k, r]
        for j in range(T):
            eta[n + j] = a[j] * c[j]
            eta[n + T + j] = a[j] * sn[j]
        e = 0.0
        for r in range(W):
            row = 0.0
            for q in range(W):
                row += Q[m, r, q] * eta[q]
            e += eta[r] * row
        out[k] = e
        for j in range(T):
            cj = c[j] * cr[j] - sn[j] * sr[j]
            sn[j] = c[j] * sr[j] + sn[j] * cr[j]
            c[j] = cj


def trajectory_quadratic(x, sigma, t, pieces, make_forms, scale=0):
    """A quadratic form of every step of a stored run: ``ηᵀ Q η`` per step, with the forms of each
    piece from ``make_forms(frequencies) -> (Q (I, W, W), R (I, n, n), split (I,))`` (as
    :func:`sine_forms`), x and σ at the grid points and the pieces ``(k0, k1, Sinusoids or
    None)`` of :func:`fdsc._simulate_kernel._segments`. Evaluated on the run scaled by
    ``2^−scale`` and scaled back by ``2^(2 scale)`` (exact: powers of two), so that no square
    overflows. Returns (N − 1,) ndarray."""
    out = np.zeros(t.size - 1)
    xs = np.ascontiguousarray(np.ldexp(x, -scale))
    sig = np.ascontiguousarray(sigma, dtype=np.int64)
    for k0, k1, part in pieces:
        w = np.zeros(0) if part is None else np.asarray(part.frequencies, dtype=float)
        a = np.zeros(0) if part is None else np.ldexp(part.amplitudes, -scale)
        ph = np.zeros(0) if part is None else np.asarray(part.phases, dtype=float)
        Q, R, split = make_forms(w)
        _trajectory_kernel(xs, sig, t, k0, k1, w, a, ph, np.ascontiguousarray(Q), R, split, out)
    with np.errstate(over="ignore"):
        return np.ldexp(out, 2 * scale)


def trajectory_step_energies(x, sigma, t, pieces, coords, h, scale=0):
    """``∫ zᵀz`` and ``∫ d²`` over every step ``[t_k, t_{k+1})`` of a stored run (see
    :func:`trajectory_quadratic`): two (N − 1,) ndarrays, each entry exact."""
    n, nm = x.shape[1], len(coords)

    def input_forms(w):
        W = n + 2 * w.size
        Q = np.zeros((nm, W, W))
        if w.size:
            Q[:, n:, n:] = _oscillator_form(w, h)
        return Q, np.tile(np.eye(n), (nm, 1, 1)), np.zeros(nm, dtype=np.bool_)

    return (trajectory_quadratic(x, sigma, t, pieces, lambda w: sine_forms(coords, w, h), scale),
            trajectory_quadratic(x, sigma, t, pieces, input_forms, scale))
