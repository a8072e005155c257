"""Exact runs of LTI systems on a coarse grid of instants, with energies integrated exactly.

Internal: the engine of :func:`fdsc.supervisor.supervise` and :class:`fdsc.prepared.Prepared`
(the monitoring copies, the switched runs, fixed runs and segment laws).

On an interval where the disturbance is ``d(t) = Σ_j a_j sin(ω_j t + φ_j)``, the system
``ẋ = A x + B d, z = C x + D d`` and the tones' oscillators ``c_j = cos(ω_j t + φ_j)``,
``s_j = sin(ω_j t + φ_j)`` form one autonomous linear system ``ξ̇ = F ξ``, ``ξ = [x; a∘c; a∘s]``
(the oscillators scaled by their amplitudes, so that F and G do not depend on them and a large
amplitude does not unbalance F), ``z = G ξ`` with ``G = [C, 0, D 1ᵀ]``. Over
a step of length h

    x(t + h) = [Φ, M] ξ(t),       ∫_t^{t+h} ‖z‖² = ξ(t)ᵀ Q ξ(t),

with ``[Φ, M]`` the top rows of ``e^{Fh}`` and ``Q = ∫₀^h e^{Fᵀs} GᵀG e^{Fs} ds``. Both are
exact: no quadrature, no dependence on a sampling step. They are Taylor series at ``h / 2^k``
with ``‖F‖₁ h / 2^k ≤ 1``, doubled k times in the form ``e^{Fh} = I + E``: ``E ← 2E + E²``,
``Q ← 2Q + QE + EᵀQ + EᵀQE`` (squaring I + E itself would round away the slow modes' small
departures from 1 at every doubling, an error that grows like 2^k). The oscillators' state at the
start of a step is computed from the absolute time (cos and sin), not propagated, so no rounding
accumulates.

A stiff system is integrated in other coordinates. When the sorted magnitudes of A's
eigenvalues have a gap of :data:`STIFF_GAP` or more, ``η = R x`` separates the groups
(:func:`_separate`: an ordered Schur form and a Sylvester equation per gap; the similarity by
compensated products, :mod:`fdsc._compensated`). The reason is where the digits go in physical
coordinates: in a loop whose controller has a pole at −2·10⁵ /s beside plant poles near −2 /s,
the fast controller state follows a quasi-static function of the slow ones and the output reads
it through gains of 10⁵, so z is a small difference of terms 10⁵ times larger; GᵀG, Q and the
quadratic form ``ξᵀQξ`` then hold terms 10¹⁰ times the energy, and their rounding (in forming
GᵀG, in every doubling, in the final sum) cost five digits. In η the fast coordinate is the
departure from the quasi-static value and every term is of the size of the result. The state is
still carried in physical coordinates (``[Φ, M]`` maps ξ to x); the step's energy is ``ηᵀQη``
with ``η = [R x; a∘c; a∘s]`` and Q in those coordinates.

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
from scipy.linalg import schur, solve_sylvester

from ._compensated import dot, refined_inverse, similar
from .signals import Piecewise, Sinusoids

__all__ = []

#: Sorted eigenvalue magnitudes of a system's A that differ by this factor or more split its
#: state into groups, integrated in coordinates that separate them (module docstring).
STIFF_GAP = 10.0
#: A split is made only if its coupling (the Sylvester solution X of :func:`_separate`) has no
#: entry above this: beyond it the groups' subspaces are nearly parallel, and the physical
#: coordinates are the better conditioned.
MAX_COUPLING = 1e4
# Taylor terms at most (‖F h₀‖₁ ≤ 1 needs about 20 for E and 25 for Q)
_TAYLOR_CAP = 40


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


def _separate(T):
    """``(S, S⁻¹)`` with ``S⁻¹ T S`` block diagonal, one block per group of eigenvalues whose
    sorted magnitudes are linked by ratios below :data:`STIFF_GAP` (the groups split at the
    largest gap first: an ordered real Schur form, then a Sylvester equation for the coupling);
    ``(None, None)`` if there is one group. A split whose coupling needs a transformation larger
    than :data:`MAX_COUPLING`, or that LAPACK cannot order, is not made."""
    n = T.shape[0]
    if n < 2:
        return None, None
    mag = np.sort(np.abs(np.linalg.eigvals(T)))
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = mag[1:] / mag[:-1]
    ratio[~np.isfinite(ratio)] = np.inf                     # a zero eigenvalue beside others
    c = int(np.argmax(ratio))
    if not ratio[c] >= STIFF_GAP:
        return None, None
    tau2 = mag[c] * mag[c + 1]                              # |λ|² at the gap's geometric middle
    try:
        Ts, U, m = schur(T, output="real", sort=lambda re, im: re * re + im * im <= tau2)
        X = solve_sylvester(Ts[:m, :m], -Ts[m:, m:], -Ts[:m, m:]) if m == c + 1 else None
    except np.linalg.LinAlgError:                           # LAPACK could not reorder or solve
        X = None
    if X is None or not np.all(np.isfinite(X)) or np.abs(X).max(initial=0.0) > MAX_COUPLING:
        return None, None
    S = U.copy()
    S[:, m:] += U[:, :m] @ X
    Si = U.T.copy()
    Si[:m] -= X @ U[:, m:].T
    for sl in (slice(0, m), slice(m, n)):                   # the groups on either side
        S2, S2i = _separate(Ts[sl, sl])
        if S2 is not None:
            S[:, sl] = S[:, sl] @ S2
            Si[sl] = S2i @ Si[sl]
    return S, Si


def _coordinates(A, B, C, D):
    """The system ``(A, B, C, D, S, S⁻¹)`` in the coordinates ``x = S η`` of a split of A
    (:func:`_separate`; the similarity by compensated products, S⁻¹ refined once so that it is
    exact to rounding whatever S's condition), or as given with ``S = S⁻¹ = None`` if there is
    none."""
    if A.shape[0] >= 2 and np.all(np.isfinite(A)):
        S, Si = _separate(A)
        if S is not None:
            Si = refined_inverse(S, Si)
            return similar(Si, A, S), dot(Si, B), dot(C, S), D, S, Si
    return A, B, C, D, None, None


def _gram(F, M, h):
    """``(E, Q)`` with ``E = e^{Fh} − I`` and ``Q = ∫₀^h e^{Fᵀs} M e^{Fs} ds``: Taylor series
    at ``h₀ = h / 2^k`` (``‖F‖₁ h₀ ≤ 1``), then k doublings ``Q ← 2Q + QE + EᵀQ + EᵀQE``,
    ``E ← 2E + E²`` (I + E squared without forming I + E, whose rounding would grow like 2^k
    for the slow modes)."""
    W = F.shape[0]
    if W == 0:
        return np.zeros((0, 0)), np.zeros((0, 0))
    norm = float(np.abs(F).sum(axis=0).max()) * h
    k = max(0, math.ceil(math.log2(norm))) if norm > 1 else 0
    return _gram_kernel(np.ascontiguousarray(F, dtype=float), np.ascontiguousarray(M, dtype=float),
                        h / 2**k, norm / 2**k, k)


@njit(cache=True)
def _gram_kernel(F, M, h0, theta, k):
    W = F.shape[0]
    Fh = F * h0
    eye = np.eye(W)
    # E(h0) = Fh (I + Fh/2 (I + Fh/3 (…))), to a term below 2⁻⁶⁰ of the first
    m, term = 1, theta
    while term > 2.0**-60 and m < _TAYLOR_CAP:
        m += 1
        term *= theta / m
    E = eye.copy()
    for j in range(m, 1, -1):
        E = eye + (Fh @ E) / j
    E = Fh @ E
    # Q(h0) = h0 Σ_j L^j(M) / (j + 1)!, L(X) = Fhᵀ X + X Fh (X symmetric: XFh + (XFh)ᵀ)
    X, Q, c, j = M.copy(), M.copy(), 1.0, 0
    while j < _TAYLOR_CAP:
        j += 1
        Y = X @ Fh
        X = Y + Y.T
        c /= j + 1
        Q += c * X
        if c * (2 * theta) ** j <= 2.0**-60:
            break
    Q *= h0
    for _ in range(k):
        QE = Q @ E
        Q = 2.0 * Q + (QE + QE.T) + np.ascontiguousarray(E.T) @ QE
        E = 2.0 * E + E @ E
    return E, 0.5 * (Q + Q.T)


def _augmented(A, B, C, D, w, ch):
    """``(F, G)`` of ``ξ = [x; a∘c; a∘s]`` (module docstring)."""
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
    return F, G


def _step(system, w, h, ch=None):
    """``([Φ, M], Q, R)`` of one step of length h for unit amplitudes, for a system in the
    coordinates of :func:`_coordinates`: ``[Φ, M]`` maps ξ to x at the step's end, and the energy
    is ``ηᵀ Q η`` with ``η = [R x; a∘c; a∘s]`` in the coordinates of a split (module docstring),
    or ``ξᵀ Q ξ`` with ``R = None`` where there is none; ``ch`` as in :func:`_pair`."""
    A, B, C, D, S, Si = system
    n = A.shape[0]
    F, G = _augmented(A, B, C, D, w, ch)
    E, Q = _gram(F, G.T @ G, h)
    top = E[:n]
    top[:, :n] += np.eye(n)
    if S is None:
        return top, Q, None
    P = S @ top
    P[:, :n] = P[:, :n] @ Si
    return P, Q, Si


def _pair(A, B, C, D, w, h, ch=None):
    """``([Φ, M], Q)`` of one step of length h for unit amplitudes (module docstring), padded by
    the caller, Q the energy's quadratic form in ξ. ``ch`` (one entry per tone) is the input
    column each tone drives, for a system with two inputs ``[d; ŵ]`` on a grid of two signals; a
    system with one input is driven by the tones of channel 0 (d) only."""
    P, Q, R = _step(_coordinates(A, B, C, D), w, h, ch)
    if R is not None:
        n = A.shape[0]
        RR = np.eye(Q.shape[0])
        RR[:n, :n] = R
        Q = RR.T @ Q @ RR
        Q = 0.5 * (Q + Q.T)
    return P, Q


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
        """``(PHI, Q, R, split)`` for systems ``(A, B, C, D)`` of one state size n: PHI
        ``(kinds, systems, n, n + 2T)`` maps ξ to the state at a step's end, Q ``(kinds,
        systems, n + 2T, n + 2T)`` is the step energy's quadratic form in ``η = [R x; a∘c;
        a∘s]`` for a system that is split (``split[i]``; R ``(systems, n, n)``) and in ξ
        otherwise (module docstring)."""
        n = systems[0][0].shape[0]
        W = n + 2 * self.T
        PHI = np.zeros((len(self.kinds), len(systems), n, W))
        Q = np.zeros((len(self.kinds), len(systems), W, W))
        R = np.zeros((len(systems), n, n))
        split = np.zeros(len(systems), dtype=np.bool_)
        coords = [_coordinates(*sy) for sy in systems]
        for k, (pc, h) in enumerate(self.kinds):
            _t0, _t1, w, _a, _ph = self.pieces[pc]
            T = w.size
            ch = None if self.channels is None else self.channels[pc]
            idx = np.r_[np.arange(n), n + np.arange(T), n + self.T + np.arange(T)]
            for i, (_A, B, _C, _D) in enumerate(systems):
                if ch is None and B.shape[1] != 1:
                    raise ValueError(f"a system with {B.shape[1]} inputs needs a grid of as many "
                                     "signals (an estimate beside d)")
                P, q, r = _step(coords[i], w, h, ch)
                PHI[k, i][:, idx] = P
                Q[k, i][np.ix_(idx, idx)] = q
                if r is not None:
                    R[i], split[i] = r, True
        return PHI, Q, R, split

    def run(self, tables, system, restart, x0, start: int = 0, stop: int | None = None) -> tuple:
        """Energies of the steps ``start … stop − 1``, the largest ``|x_r|`` at the end of each,
        and the final state, of a run that takes, on step s, the system ``system[s]`` (an index
        into the tables; a scalar for all) and starts it from rest if ``restart[s]``."""
        PHI, Q, R, split = tables
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
        _steps(self.kind[start:stop], system, restart, self.cs[start:stop], PHI, Q, R, split, x, e, big)
        return e, big, x

    def per_block(self, e) -> np.ndarray:
        """The step energies summed over each interval of ``points``."""
        return np.bincount(self.block, weights=e, minlength=self.points.size - 1)


@njit(cache=True)
def _steps(kind, system, restart, cs, PHI, Q, R, split, x, e, big):
    n = x.shape[0]
    W = PHI.shape[3]
    xi = np.empty(W)
    eta = np.empty(W)
    for s in range(kind.shape[0]):
        if restart[s]:
            for r in range(n):
                x[r] = 0.0
        k, m = kind[s], system[s]
        for r in range(n):
            xi[r] = x[r]
        for r in range(n, W):
            xi[r] = cs[s, r - n]
            eta[r] = xi[r]
        if split[m]:                    # the energy in the split's coordinates, the state in x's
            for r in range(n):
                row = 0.0
                for c in range(n):
                    row += R[m, r, c] * x[c]
                eta[r] = row
        else:
            for r in range(n):
                eta[r] = x[r]
        acc = 0.0
        for r in range(W):
            row = 0.0
            for c in range(W):
                row += Q[k, m, r, c] * eta[c]
            acc += eta[r] * row
        e[s] = acc
        top = 0.0
        for r in range(n):
            row = 0.0
            for c in range(W):
                row += PHI[k, m, r, c] * xi[c]
            x[r] = row
            top = max(top, abs(row))
        big[s] = top
