"""The compiled kernel of :func:`fdsc.simulate.simulate`, the tone tables it reads and the pieces of
the disturbance on the grid that both kernels step through. Internal.

The kernel does the whole run in one loop, with no per-step arrays built beforehand: the step
is that of :mod:`fdsc.simulate`, ``x_{k+1} = x_p(t_{k+1}) + Φ_i (x_k − x_p(t_k))``, with the
particular solution of the active mode written as ``x_p(t) = Σ_j Im(X_j p_j(t))`` over the tones
of the segment that owns the step, and ``p_j(t) = e^{j(ω_j t + φ_j)}`` the tone's phasor. The
phasors are rotated from sample to sample as in :mod:`fdsc.stream`: every
:data:`PHASOR_BLOCK` steps (and at each segment start) a phasor is computed by cos and sin of
``ω_j t_k + φ_j``; in between it is that first phasor times the exact rotation ``e^{jω_j m Δt}``
from a table, so each phasor is the product of two correctly rounded numbers (no error builds
up along the run). d, ḋ, ẋ and z are computed in the same loop.

The NumPy reference (:mod:`fdsc._simulate_reference`) evaluates ``x_p`` from NumPy's cos
and sin of ``ω_j t_k + φ_j`` on the whole grid instead; the two agree to rounding (the tests
compare them).
"""

import math

import numpy as np
from numba import njit

from .frequency import check_no_pole_at
from .rules import decide, window_scores
from .signals import Piecewise, Sinusoids

__all__ = []

#: Steps per block of phasor rotations (the first phasor of a block is computed by cos and sin).
PHASOR_BLOCK = 512


#: A break of a Piecewise lies on the grid if it is within this fraction of dt of a grid point
#: (plus the rounding of t); breaks outside the run need not lie on it.
BREAK_RTOL = 1e-6


def break_index(b, t0, dt, N, where=""):
    """The grid index of a break ``b`` of a Piecewise on the grid ``t0 + k dt``, k = 0 … N − 1 (not
    clipped to the grid).

    A break inside the run must lie on the grid within ``BREAK_RTOL · dt`` (plus the rounding of
    t): the run cuts the pieces there by index, so a t_k an ulp below a break still belongs to the
    piece that starts at the break, for the steps and the samples alike. A break outside the run
    need not: its index is that of the first grid point at or after it (≤ 0 before the run, ≥ N
    after it)."""
    b, t0, dt = float(b), float(t0), float(dt)
    x = (b - t0) / dt
    tol = BREAK_RTOL + 16 * np.finfo(float).eps * max(abs(b), abs(t0), dt) / dt
    k = round(x)
    if abs(x - k) <= tol:
        return k
    if x < 0 or x > N - 1:
        return math.ceil(x)
    raise ValueError(f"{where}the disturbance switches at t = {b!r} s, which is not on the grid "
                     f"(it lies {abs(x - k):.3g} steps of dt = {dt!r} s from the nearest point); "
                     "choose dt dividing every break")


def check_resolved(d, dt, where=""):
    """Refuse a disturbance with a tone at or above the Nyquist frequency π/dt of the grid: its
    samples are those of a slower tone (the states and energies stay exact, but d on the grid
    and the law's inputs would be of that slower tone)."""
    parts = d.parts if isinstance(d, Piecewise) else (d,)
    dt = float(dt)
    for j, part in enumerate(parts):
        if part.frequencies.size and part.frequencies.max() * dt >= math.pi:
            which = f"piece {j} of the disturbance" if isinstance(d, Piecewise) else "the disturbance"
            raise ValueError(f"{where}dt = {dt!r} s does not resolve {which}: its tone at "
                             f"{part.frequencies.max():g} rad/s is at or above the Nyquist frequency "
                             f"π/dt = {math.pi / dt:.6g} rad/s; choose dt < π/ω for every tone")


def _break_indices(d, t):
    """The grid index of every break of a Piecewise on the grid ``t`` (:func:`break_index`)."""
    dt = t[1] - t[0]
    return [break_index(b, t[0], dt, t.size) for b in d.breaks]


def _samples(d, t, derivative=False, points=None):
    """d (or ḋ, exact) at the grid points ``points`` (default all); a Piecewise by the index of
    each point (see :func:`_break_indices`), zero where it is off."""
    k = np.arange(t.size) if points is None else np.asarray(points, dtype=np.int64)
    tk = t[k]
    if isinstance(d, Sinusoids):
        return d.derivative(tk) if derivative else d(tk)
    idx = _break_indices(d, t)
    out = np.zeros(tk.shape)
    for j, part in enumerate(d.parts):
        sel = (k >= idx[j]) & (k < idx[j + 1])
        if np.any(sel):
            out[sel] = part.derivative(tk[sel]) if derivative else part(tk[sel])
    return out


def _segments(d, t):
    """Split the grid into segments with one Sinusoids each: list of (k0, k1, Sinusoids|None)."""
    if isinstance(d, Sinusoids):
        return [(0, t.size - 1, d)]
    if not isinstance(d, Piecewise):
        raise TypeError(f"d must be Sinusoids or Piecewise, found {type(d).__name__}")
    idx = [min(max(k, 0), t.size - 1) for k in _break_indices(d, t)]
    out = []
    if idx[0] > 0:
        out.append((0, idx[0], None))
    for j, part in enumerate(d.parts):
        if idx[j + 1] > idx[j]:
            out.append((idx[j], idx[j + 1], part))
    if idx[-1] < t.size - 1:
        out.append((idx[-1], t.size - 1, None))
    return out


def rotations(w, dt, K):
    """cos and sin of ``ω m Δt`` for m = 0 … K − 1: the rotations of a tone's phasor (the tables
    of this kernel and of :mod:`fdsc.stream`)."""
    theta = w * (np.arange(K) * dt)
    return np.cos(theta), np.sin(theta)


def tone_tables(pieces, t, As, B, dt):
    """The arrays of :func:`kernel` for a disturbance cut into pieces.

    Parameters
    ----------
    pieces : list of (k0, k1, Sinusoids or None)
        Steps ``k0 … k1 − 1`` use the piece's tones (None: d = 0), as returned by
        :func:`_segments`; they cover every step in order.
    t : (N,) ndarray
        The grid.
    As : (I, n, n) ndarray
        The modes' A.
    B : (n,) ndarray
    dt : float
        The grid's step.

    Returns
    -------
    dict
        ``seg_start`` (S,), ``seg_nt`` (S,), ``omega``, ``amp``, ``phase`` (S, T), ``Xr``, ``Xi``
        (S, I, n, T: the real and imaginary part of each tone's X_j for each mode), ``Rre``,
        ``Rim`` (S, K, T: the rotations ``e^{jω_j m Δt}``, m < K, K the smaller of
        :data:`PHASOR_BLOCK` and one more than the longest piece's steps).

    Raises
    ------
    SingularFrequencyError
        If a tone sits at an eigenvalue of a mode.
    """
    S, (n_modes, n) = len(pieces), As.shape[:2]
    T = max([p.frequencies.size for _, _, p in pieces if p is not None] + [1])
    # rows of the rotation tables: a piece of L steps uses rotations 0 … L (fewer rows than the
    # block for short pieces, the same numbers: no piece is re-based before its block ends)
    K = min(PHASOR_BLOCK, max(k1 - k0 for k0, k1, _ in pieces) + 1)
    out = dict(seg_start=np.array([k0 for k0, _, _ in pieces], dtype=np.int64),
               seg_nt=np.zeros(S, dtype=np.int64), omega=np.zeros((S, T)), amp=np.zeros((S, T)),
               phase=np.zeros((S, T)), Xr=np.zeros((S, n_modes, n, T)), Xi=np.zeros((S, n_modes, n, T)),
               Rre=np.zeros((S, K, T)), Rim=np.zeros((S, K, T)))
    for s, (_, _, part) in enumerate(pieces):
        if part is None:
            continue
        nt = part.frequencies.size
        out["seg_nt"][s] = nt
        out["omega"][s, :nt], out["amp"][s, :nt] = part.frequencies, part.amplitudes
        out["phase"][s, :nt] = part.phases
        for i, A in enumerate(As):
            check_no_pole_at(A, part.frequencies, what=f"the forced response of mode {i} to the disturbance")
        for j, (a, w) in enumerate(zip(part.amplitudes, part.frequencies, strict=True)):
            out["Rre"][s, :, j], out["Rim"][s, :, j] = rotations(w, dt, K)
            for i, A in enumerate(As):
                X = np.linalg.solve(1j * w * np.eye(n) - A, B * a)
                out["Xr"][s, i, :, j], out["Xi"][s, i, :, j] = X.real, X.imag
    return out


@njit(cache=True)
def kernel(Phi, A, B, C, D, W, x0, sigma0, candidate, rparams, ring, ring_sum, istate, t,
           seg_start, seg_nt, omega, amp, phase, Xr, Xi, Rre, Rim, d_last, dd_last):
    """The run: returns x, σ, ẋ, z, d on the grid (see the module docstring).

    The law's scores and the rule are written out in the loop rather than called: a compiled
    call that passes arrays reference-counts each of them, which cost more than the arithmetic
    (about 0.5 µs per sample). The law: v = [ẍ; ẋ; x] (W of size 3n) or [ẋ; x] (2n), with the
    measured derivatives of the active mode (or each candidate's own), score_i = vᵀ W_i v; the
    rule: :func:`fdsc.rules.window_scores` (windows only), the argmax (ties to the lowest
    index) and :func:`fdsc.rules.decide`, as :func:`fdsc.rules.apply_rule` composes them.

    Point k uses the segment that contains it (d at a break is the next piece's); step k → k + 1
    uses the segment of point k at both ends. The last point's d and ḋ are given
    (``d_last``, ``dd_last``: the piece convention at the end of the grid)."""
    n_modes, n = A.shape[0], A.shape[1]
    p = C.shape[1]
    q = W.shape[1]
    o = q - 2 * n
    N = t.shape[0]
    S = seg_nt.shape[0]
    T = omega.shape[1]
    K = Rre.shape[1]
    x = np.empty((N, n))
    xdot = np.empty((N, n))
    z = np.empty((N, p))
    d = np.empty(N)
    sigma = np.empty(N, np.int64)
    x[0] = x0
    prev = sigma0
    v = np.empty(q)
    sc = np.empty(n_modes)
    eff = np.empty(n_modes)
    diff = np.empty(n)
    bre = np.empty(T)       # phasor at the first point kb of the current block
    bim = np.empty(T)
    pre = np.empty(T)       # phasor at the current point
    pim = np.empty(T)
    nre = np.empty(T)       # phasor at the next point (same segment)
    nim = np.empty(T)
    margin = rparams[0]
    relative = rparams[1] > 0
    dwell_steps = int(rparams[2])
    L = int(rparams[3])
    s = -1
    kb = 0
    for k in range(N):
        if s + 1 < S and k == seg_start[s + 1]:
            s += 1
            kb = k
            for j in range(seg_nt[s]):
                th = omega[s, j] * t[k] + phase[s, j]
                bre[j] = math.cos(th)
                bim[j] = math.sin(th)
                pre[j] = bre[j]
                pim[j] = bim[j]
        nt = seg_nt[s]
        if k == N - 1:
            dk = d_last
            ddk = dd_last
        else:
            dk = 0.0
            ddk = 0.0
            for j in range(nt):
                dk += amp[s, j] * pim[j]
            if o > 0:
                for j in range(nt):
                    ddk += amp[s, j] * omega[s, j] * pre[j]
        d[k] = dk
        if n_modes > 1:
            for i in range(n_modes):
                if candidate or i == 0:
                    # the measured derivatives (default law) are the same for every candidate
                    mm = i if candidate else prev
                    for r in range(n):
                        acc = B[r] * dk
                        for c in range(n):
                            acc += A[mm, r, c] * x[k, c]
                        v[o + r] = acc
                        v[o + n + r] = x[k, r]
                    if o > 0:
                        for r in range(n):
                            acc = B[r] * ddk
                            for c in range(n):
                                acc += A[mm, r, c] * v[n + c]
                            v[r] = acc
                score = 0.0
                for r in range(q):
                    row = 0.0
                    for c in range(q):
                        row += W[i, r, c] * v[c]
                    score += v[r] * row
                sc[i] = score
            if L > 1:
                window_scores(sc, n_modes, L, ring, ring_sum, istate, eff)
            else:
                for i in range(n_modes):
                    eff[i] = sc[i]
            best = prev
            top = -np.inf
            for i in range(n_modes):
                if eff[i] > top:
                    top = eff[i]
                    best = i
            choice = decide(best, prev, eff[best], eff[prev], k, istate[2], margin, relative,
                            dwell_steps)
            if choice != prev:
                istate[2] = k
            prev = choice
        sigma[k] = prev
        m = prev
        for r in range(n):
            acc = B[r] * dk
            for c in range(n):
                acc += A[m, r, c] * x[k, c]
            xdot[k, r] = acc
        for r in range(p):
            acc = D[r] * dk
            for c in range(n):
                acc += C[m, r, c] * x[k, c]
            z[k, r] = acc
        if k + 1 < N:
            # the phasors at t_{k+1}, in the segment of point k
            jj = k + 1 - kb
            if jj >= K:
                kb = k + 1
                jj = 0
                for j in range(nt):
                    th = omega[s, j] * t[k + 1] + phase[s, j]
                    bre[j] = math.cos(th)
                    bim[j] = math.sin(th)
            for j in range(nt):
                rr = Rre[s, jj, j]
                ri = Rim[s, jj, j]
                nre[j] = bre[j] * rr - bim[j] * ri
                nim[j] = bre[j] * ri + bim[j] * rr
            # x_{k+1} = x_p(t_{k+1}) + Φ (x_k − x_p(t_k)), x_p = Σ_j Im X_j cos θ_j + Re X_j sin θ_j
            for r in range(n):
                xp = 0.0
                for j in range(nt):
                    xp += Xi[s, m, r, j] * pre[j] + Xr[s, m, r, j] * pim[j]
                diff[r] = x[k, r] - xp
            for r in range(n):
                acc = 0.0
                for j in range(nt):
                    acc += Xi[s, m, r, j] * nre[j] + Xr[s, m, r, j] * nim[j]
                for c in range(n):
                    acc += Phi[m, r, c] * diff[c]
                x[k + 1, r] = acc
            for j in range(nt):
                pre[j] = nre[j]
                pim[j] = nim[j]
    return x, sigma, xdot, z, d
