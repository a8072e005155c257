"""Exact runs of LTI systems on a coarse grid of instants, with energies integrated exactly.

Internal: the engine of :func:`fdsc.supervisor.supervise` and :class:`fdsc.prepared.Prepared`
(the monitoring copies, the switched runs, fixed runs and segment laws).

On an interval where the disturbance is ``d(t) = Σ_j a_j sin(ω_j t + φ_j)``, the system
``ẋ = A x + B d, z = C x + D d`` and the tones' oscillators ``c_j = cos(ω_j t + φ_j)``,
``s_j = sin(ω_j t + φ_j)`` form one autonomous linear system ``ξ̇ = F ξ``, ``ξ = [x; a∘c; a∘s]``
(the oscillators scaled by their amplitudes, so that F and G do not depend on them and a large
amplitude does not unbalance the block exponential), ``z = G ξ`` with ``G = [C, 0, D 1ᵀ]``. Over
a step of length h

    x(t + h) = [Φ, M] ξ(t),       ∫_t^{t+h} ‖z‖² = ξ(t)ᵀ Q ξ(t),

with ``[Φ, M]`` the top rows of ``e^{Fh}`` and ``Q = ∫₀^h e^{Fᵀs} GᵀG e^{Fs} ds`` (Van Loan's
block exponential). Both are exact: no quadrature, no dependence on a sampling step. The block
exponential is taken at ``h / 2^k`` with ``‖F‖₁ h / 2^k ≤ 1`` and doubled k times
(``Q(2h) = Q(h) + e^{Fᵀh} Q(h) e^{Fh}``), so that a stiff loop (a pole at −5·10⁵ /s) does not
overflow the ``e^{−Fᵀh}`` block. The oscillators' state at the start of a step is computed from
the absolute time (cos and sin), not propagated, so no rounding accumulates.

The steps are the intervals between consecutive instants of a grid that contains every break of
the disturbance; steps of equal length on the same piece share one ``(Φ, M, Q)``. A compiled
loop runs a sequence of steps, each with its system (several systems of one state size: a
switched run) and an optional restart from rest (monitoring copies), and returns the energy of
every step and the final state.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit
from scipy.linalg import expm

from .signals import Piecewise, Sinusoids

__all__ = []


def pieces(d, horizon: float) -> list:
    """``[(t0, t1, ω, a, φ)]`` covering ``[0, horizon]``: the tones of ``d`` on each interval
    (empty arrays where ``d`` is zero)."""
    empty = np.zeros(0)
    if isinstance(d, Sinusoids):
        return [(0.0, float(horizon), d.frequencies, d.amplitudes, d.phases)]
    if not isinstance(d, Piecewise):
        raise TypeError(f"d must be an fdsc.Sinusoids or fdsc.Piecewise, but found {type(d).__name__}")
    out, t = [], 0.0
    spans = [(d.breaks[k], d.breaks[k + 1], p) for k, p in enumerate(d.parts)]
    for a, b, p in spans:
        a, b = max(float(a), 0.0), min(float(b), float(horizon))
        if b <= a:
            continue
        if a > t:
            out.append((t, a, empty, empty, empty))
        keep = p.amplitudes != 0
        out.append((a, b, p.frequencies[keep], p.amplitudes[keep], p.phases[keep]))
        t = b
    if t < horizon:
        out.append((t, float(horizon), empty, empty, empty))
    return out


def _pair(A, B, C, D, w, h, ch=None):
    """``([Φ, M], Q)`` of one step of length h for unit amplitudes (module docstring), padded by
    the caller. ``ch`` (one entry per tone) is the input column each tone drives, for a system
    with two inputs ``[d; ŵ]`` on a grid of two signals; a system with one input is driven by
    the tones of channel 0 (d) only."""
    n, T = A.shape[0], w.size
    W = n + 2 * T
    F = np.zeros((W, W))
    F[:n, :n] = A
    if ch is None:
        Bt, Dt = B @ np.ones((1, T)), D @ np.ones((1, T))
    elif B.shape[1] == 1:
        on = (np.asarray(ch) == 0).astype(float)[None, :]
        Bt, Dt = B @ on, D @ on
    else:
        Bt, Dt = B[:, ch], D[:, ch]
    if T:
        F[:n, n + T:] = Bt
        F[n:n + T, n + T:] = -np.diag(w)
        F[n + T:, n:n + T] = np.diag(w)
    G = np.zeros((C.shape[0], W))
    G[:, :n] = C
    if T:
        G[:, n + T:] = Dt
    GtG = G.T @ G
    norm = float(np.abs(F).sum(axis=0).max()) * h
    k = max(0, math.ceil(math.log2(norm))) if norm > 1 else 0
    h0 = h / 2**k
    big = np.zeros((2 * W, 2 * W))
    big[:W, :W] = -F.T
    big[:W, W:] = GtG
    big[W:, W:] = F
    E = expm(big * h0)
    Phi = E[W:, W:]
    Q = Phi.T @ E[:W, W:]
    for _ in range(k):
        Q = Q + Phi.T @ Q @ Phi
        Phi = Phi @ Phi
    Q = 0.5 * (Q + Q.T)
    return Phi[:n], Q


def _merged(d, estimate, horizon):
    """The pieces of two signals on their common breaks, and the channel of each tone (0: d,
    1: the estimate)."""
    a, b = pieces(d, horizon), pieces(estimate, horizon)
    cuts = np.union1d([p[0] for p in a] + [horizon], [p[0] for p in b])
    keep = np.concatenate([[True], np.diff(cuts) > 1e-9 * max(1.0, horizon)])
    cuts = cuts[keep]
    out, channels = [], []
    for t0, t1 in zip(cuts[:-1], cuts[1:], strict=True):
        mid = 0.5 * (t0 + t1)
        pa = next(p for p in a if p[0] <= mid < p[1] or p is a[-1])
        pb = next(p for p in b if p[0] <= mid < p[1] or p is b[-1])
        out.append((float(t0), float(t1), np.r_[pa[2], pb[2]], np.r_[pa[3], pb[3]], np.r_[pa[4], pb[4]]))
        channels.append(np.r_[np.zeros(pa[2].size, dtype=np.int64), np.ones(pb[2].size, dtype=np.int64)])
    return out, channels


class Grid:
    """The steps between the instants ``points`` (sorted, from 0 to the horizon) and the breaks
    of ``d`` (and of ``estimate``), with the tones' oscillator state at the start of each step.

    Attributes: ``edges`` (S + 1,), ``block`` (S,) the index of the interval of ``points`` that
    holds each step, ``kind`` (S,) the index of its (piece, length) class, ``cs`` (S, 2T) the
    oscillators ``[cos; sin]`` at its start (padded with zeros to the most tones T of a piece),
    ``channels`` (None, or per piece the input each tone drives: 0 for d, 1 for the estimate).
    """

    def __init__(self, d, points: np.ndarray, estimate=None):
        points = np.asarray(points, dtype=float)
        horizon = float(points[-1])
        if estimate is None:
            self.pieces, self.channels = pieces(d, horizon), None
        else:
            self.pieces, self.channels = _merged(d, estimate, horizon)
        inner = [p[0] for p in self.pieces[1:]]
        edges = np.union1d(points, inner)
        # merge instants closer than a rounding error (a break on a decision point)
        keep = np.concatenate([[True], np.diff(edges) > 1e-9 * max(1.0, horizon)])
        edges = edges[keep]
        edges[-1] = horizon
        self.edges = edges
        self.points = points
        starts = edges[:-1]
        self.block = np.searchsorted(points, starts + 1e-9 * max(1.0, horizon), side="right") - 1
        lo = np.array([p[0] for p in self.pieces])
        self.piece = np.searchsorted(lo, starts + 1e-9 * max(1.0, horizon), side="right") - 1
        self.T = max([p[2].size for p in self.pieces] + [0])
        h = np.diff(edges)
        keys = {}
        kind = np.empty(h.size, dtype=np.int64)
        for s, (pc, hs) in enumerate(zip(self.piece, h, strict=True)):
            key = (int(pc), round(float(hs) * 1e9))
            kind[s] = keys.setdefault(key, len(keys))
        self.kind = kind
        self.kinds = [(pc, hn / 1e9) for (pc, hn) in keys]
        cs = np.zeros((h.size, 2 * self.T))
        for k, (_t0, _t1, w, a, ph) in enumerate(self.pieces):
            sel = self.piece == k
            if w.size:
                arg = np.outer(starts[sel], w) + ph[None, :]
                cs[sel, :w.size] = a[None, :] * np.cos(arg)
                cs[sel, self.T:self.T + w.size] = a[None, :] * np.sin(arg)
        self.cs = cs

    def tables(self, systems) -> tuple:
        """``(PHI, Q)`` of shapes ``(kinds, systems, n, n + 2T)`` and ``(kinds, systems, n + 2T,
        n + 2T)`` for systems ``(A, B, C, D)`` of one state size n."""
        n = systems[0][0].shape[0]
        W = n + 2 * self.T
        PHI = np.zeros((len(self.kinds), len(systems), n, W))
        Q = np.zeros((len(self.kinds), len(systems), W, W))
        for k, (pc, h) in enumerate(self.kinds):
            _t0, _t1, w, _a, _ph = self.pieces[pc]
            T = w.size
            ch = None if self.channels is None else self.channels[pc]
            idx = np.r_[np.arange(n), n + np.arange(T), n + self.T + np.arange(T)]
            for i, (A, B, C, D) in enumerate(systems):
                if ch is None and B.shape[1] != 1:
                    raise ValueError(f"a system with {B.shape[1]} inputs needs a grid of as many "
                                     "signals (an estimate beside d)")
                P, q = _pair(A, B, C, D, w, h, ch)
                PHI[k, i][:, idx] = P
                Q[k, i][np.ix_(idx, idx)] = q
        return PHI, Q

    def run(self, tables, system, restart, x0, start: int = 0, stop: int | None = None) -> tuple:
        """Energies of the steps ``start … stop − 1``, the largest ``|x_r|`` at the end of each,
        and the final state, of a run that takes, on step s, the system ``system[s]`` (an index
        into the tables; a scalar for all) and starts it from rest if ``restart[s]``."""
        PHI, Q = tables
        stop = self.kind.size if stop is None else stop
        S = stop - start
        system = np.broadcast_to(np.asarray(system, dtype=np.int64), (self.kind.size,))[start:stop].copy()
        if system.size and (system.min() < 0 or system.max() >= PHI.shape[1]):
            raise ValueError(f"a step's system index must be in [0, {PHI.shape[1]}), but found "
                             f"{int(system.min())} to {int(system.max())}")
        if np.shape(x0) != (PHI.shape[2],):
            raise ValueError(f"x0 must have {PHI.shape[2]} entries, but found shape {np.shape(x0)}")
        restart = np.broadcast_to(np.asarray(restart, dtype=np.bool_), (self.kind.size,))[start:stop].copy()
        e, big = np.empty(S), np.empty(S)
        x = np.array(x0, dtype=float)
        _steps(self.kind[start:stop], system, restart, self.cs[start:stop], PHI, Q, x, e, big)
        return e, big, x

    def per_block(self, e) -> np.ndarray:
        """The step energies summed over each interval of ``points``."""
        return np.bincount(self.block, weights=e, minlength=self.points.size - 1)


@njit(cache=True)
def _steps(kind, system, restart, cs, PHI, Q, x, e, big):
    n = x.shape[0]
    W = PHI.shape[3]
    xi = np.empty(W)
    for s in range(kind.shape[0]):
        if restart[s]:
            for r in range(n):
                x[r] = 0.0
        k, m = kind[s], system[s]
        for r in range(n):
            xi[r] = x[r]
        for r in range(n, W):
            xi[r] = cs[s, r - n]
        acc = 0.0
        for r in range(W):
            row = 0.0
            for c in range(W):
                row += Q[k, m, r, c] * xi[c]
            acc += xi[r] * row
        e[s] = acc
        top = 0.0
        for r in range(n):
            row = 0.0
            for c in range(W):
                row += PHI[k, m, r, c] * xi[c]
            x[r] = row
            top = max(top, abs(row))
        big[s] = top
