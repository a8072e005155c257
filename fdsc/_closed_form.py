"""The Simpson sums of an LTI run under pieces of tones, in closed form (no loop over the steps).

:mod:`fdsc.stream` sums ``f_k = z_kᵀ z_k`` (and ``d_k²``) over the points of a run with the
weights of the composite Simpson rule. For one mode and a disturbance made of pieces of
sinusoids the samples have a closed form, and so does every such sum, so a run of any length
costs a few small linear solves. On a piece starting at point ``k₀`` with tones
``d = Σ a_j Im P_j``, ``P_j(k) = e^{j(ω_j k Δt + φ_j)}``, the exact step
``x_{k+1} = Φ x_k + Σ_j Im(H_j P_j(k))`` has the particular solution ``Im Σ_j X_j P_j(k)``
with ``X_j = (e^{jθ_j} I − Φ)⁻¹ H_j``, ``θ_j = ω_j Δt``, so

    x_k = Φ^{k−k₀} e + Im Σ_j X_j P_j(k),   e = x_{k₀} − Im Σ_j X_j P_j(k₀),
    z_k = C Φ^{k−k₀} e + Im Σ_j Z_j P_j(k),   Z_j = C X_j + D a_j.

The Simpson weights 1, 4, 2, 4, … are ``3 − (−1)^k`` after the first point, so every weighted
sum is a combination of ``G_c = Σ_k c^k f_k`` for ``c = ±1``, and each of the three parts of
``f_k`` sums in closed form:

* transient: ``Σ_{m<L} c^m (Φ^m e)ᵀ CᵀC (Φ^m e) = eᵀ Y_c e − c^L (Φ^L e)ᵀ Y_c (Φ^L e)`` with
  ``Y_c = CᵀC + c Φᵀ Y_c Φ`` (a Stein equation, summed by Smith's doubling; for c = −1 as
  one in Φ²);
* cross terms: ``Σ_{m<L} ρ^m Φ^m e = (I − ρΦ)⁻¹ (e − ρ^L Φ^L e)`` with ``ρ = c e^{jθ_j}``;
* tones: products ``P̄_j P_l`` and ``P_j P_l`` are geometric in k, summed as
  ``(r^{k₀} − r^{b}) / (1 − r)``, or as ``e^{jα(k₀+b−1)/2} sin(αL/2) / sin(α/2)`` when ``r = e^{jα}``
  is near 1 and ``|α| L < 1`` (where the first form would cancel), and ``L`` when ``r = 1``.

This needs Φ Schur-stable (spectral radius < 1, checked with a margin by
:func:`applies`), no tone at a pole (refused before), and costs O(T² + n³) per piece and per
point of a coarse grid, independently of the run's length. It is the same sum as the loop's,
rounded differently. Its rounding grows where its terms cancel (a large steady state and a
transient that nearly annul each other, a badly scaled state whose quadratic forms are large
where e is small): :func:`simpson_sums` returns the size of its terms, and the caller keeps the
closed form only if that is at most :data:`MAX_CANCELLATION` times the sum. Where kept, it
agreed with the loop to ≤ 3.3e-11 relative (energies, coarse grid, final state) over 1100
random loops with poles from 1e-3 to 5e5 rad/s (``tests/test_stream.py`` draws 80 of them).
"""

import numpy as np

__all__ = ["applies", "simpson_sums", "RADIUS_MARGIN", "MAX_CANCELLATION"]

#: The closed form is used only if the spectral radius of Φ is at most ``1 − RADIUS_MARGIN``:
#: the Stein equations' condition grows like 1 / (1 − ρ(Φ)²).
RADIUS_MARGIN = 1e-6
#: The closed form is kept only if its terms' size is at most this multiple of the sum (each
#: factor of cancellation costs as much relative accuracy; the loop is used otherwise).
MAX_CANCELLATION = 30.0
# Smith's doubling: 2^64 terms, far more than any Φ with spectral radius ≤ 1 − 1e-6 needs
_MAX_DOUBLINGS = 64
# |α| below which a ratio r = e^{jα} counts as near 1: its geometric sums take the sine form at
# the ends where |α| L < 1 (where (q(k0) − q(b)) / (1 − r) would cancel)
_NEAR_ONE = 1e-3


def applies(Phi):
    """True if the closed form may be used for the step matrix ``Phi`` (see :data:`RADIUS_MARGIN`)."""
    return bool(np.all(np.isfinite(Phi))) and np.max(np.abs(np.linalg.eigvals(Phi))) <= 1 - RADIUS_MARGIN


def _stein(Phi, Q, c):
    """Y = Σ_m c^m (Φ^m)ᵀ Q Φ^m, the solution of Y = Q + c Φᵀ Y Φ (c = ±1), by Smith's doubling
    (Y ← Y + AᵀYA, A ← A², with A = Φ, or A = Φ² and Q − ΦᵀQΦ for c = −1): sums of the series'
    own terms, accurate where a Kronecker solve is not (a badly scaled or stiff Φ)."""
    if c > 0:
        A, Y = Phi.copy(), Q.copy()
    else:
        A, Y = Phi @ Phi, Q - Phi.T @ Q @ Phi
    for _ in range(_MAX_DOUBLINGS):
        step = A.T @ Y @ A
        Y = Y + step
        A = A @ A
        if not np.any(np.abs(step) > 1e-17 * np.abs(Y)) and np.abs(A).max() < 1e-3:
            break
    return 0.5 * (Y + Y.T)


def _powers(Phi, e, L):
    """Φ^L e for every entry of the integer array L (≥ 0), as an (len(L), n) array: the binary
    digits of L applied to all vectors at once (Φ, Φ², Φ⁴, … by squaring)."""
    L = np.asarray(L, dtype=np.int64)
    out = np.tile(np.asarray(e, float), (L.size, 1))
    P, bit = Phi, 1
    top = int(L.max()) if L.size else 0
    while bit <= top:
        has = (L & bit) != 0
        if np.any(has):
            out[has] = out[has] @ P.T
        bit <<= 1
        if bit <= top:
            P = P @ P
    return out


def _pair_sums(weight, ratio, start, end_terms, pair_end, L):
    """For every end b = k0 + L: ``Σ_{k=k0}^{b−1} Σ_{jl} weight_jl q_jl(k)``, each ``q_jl``
    geometric with ratio ``ratio_jl`` (|ratio| = 1) and ``q_jl(k0) = start_jl``;
    ``end_terms(M)`` returns ``Σ_jl M_jl q_jl(b)`` for every b, ``pair_end(jj, ll)`` the
    ``q_jl(b)`` of the pairs (jj[i], ll[i]), (len(jj), nb). Also returns the size of the terms that were
    added (for the cancellation check).

    Per pair, ``Σ_{m<L} r^m`` is ``L`` if r = 1, ``(1 − r^L) / (1 − r)`` as
    ``(q(k0) − q(b)) / (1 − r)`` where that does not cancel, and
    ``e^{jα(L−1)/2} sin(αL/2) / sin(α/2)`` (r = e^{jα}) where it would: for a ratio near 1
    (|α| < :data:`_NEAR_ONE`) at ends with |α| L < 1. 1 − r is formed from α without
    cancellation."""
    alpha = np.angle(ratio)
    one = ratio == 1.0
    near = (np.abs(alpha) < _NEAR_ONE) & ~one
    far = ~near & ~one
    total = np.zeros(L.size, dtype=complex)
    size = np.zeros(L.size)
    # 1 − e^{jα} = 2 sin²(α/2) − j sin α
    om = 2.0 * np.sin(alpha / 2) ** 2 - 1j * np.sin(alpha)
    if np.any(far):
        M = np.where(far, weight / np.where(far, om, 1.0), 0.0)
        total += np.sum(M * start) - end_terms(M)
        size += 2.0 * np.sum(np.abs(M))
    if np.any(one):
        # ratio exactly 1 (equal frequencies): L equal terms
        total += np.sum(weight[one] * start[one]) * L
        size += np.sum(np.abs(weight[one])) * L
    if np.any(near):
        jj, ll = np.nonzero(near)
        a = alpha[jj, ll][:, None]
        w = weight[jj, ll][:, None]
        ws = (weight[jj, ll] * start[jj, ll])[:, None]
        Lf = L.astype(float)[None, :]
        short = np.abs(a) * Lf < 1.0
        # far form per pair: w (q(k0) − q(b)) / (1 − r), where it does not cancel
        Mn = w / om[jj, ll][:, None]
        terms = np.where(short, 0.0, Mn * (start[jj, ll][:, None] - pair_end(jj, ll)))
        mags = np.where(short, np.abs(w) * Lf, 2.0 * np.abs(Mn))
        pj, pb = np.nonzero(short)
        if pj.size:
            ap, Lp = a[pj, 0], Lf[0, pb]
            terms[pj, pb] = (ws[pj, 0] * np.sin(ap * Lp / 2) / np.sin(ap / 2)
                             * np.exp(0.5j * ap * (Lp - 1)))
        total += np.sum(terms, axis=0)
        size += np.sum(mags, axis=0)
    return total, size


def _phasors(omega, phase, k, dt):
    """P_j(k) = e^{j(ω_j (k Δt) + φ_j)} as in the loop: (T, len(k))."""
    th = omega[:, None] * (k[None, :] * dt) + phase[:, None]
    return np.cos(th) + 1j * np.sin(th)


def _tone_sums(Zc, theta, P0, Pb, k0, bb, c):
    """Σ_{k=k0}^{b−1} c^k |Im Σ_j Z_j P_j(k)|² for each end b; Zc is (p, T) complex, P0 (T,) and
    Pb (T, nb) the phasors at k0 and at the ends. Also returns the size of its terms.

    ``|Im w|² = ½ w̄ᵀw − ½ Re(wᵀw)``: the products ``c^k P̄_j P_l`` and ``c^k P_j P_l`` are
    geometric in k with ratios ``c e^{j(θ_l − θ_j)}`` and ``c e^{j(θ_j + θ_l)}``."""
    L = bb - k0
    ck0 = 1.0 if (c > 0 or k0 % 2 == 0) else -1.0
    cb = np.where(bb % 2 == 0, 1.0, float(c))
    herm = Zc.conj().T @ Zc                      # Z_jᴴ Z_l
    sym = Zc.T @ Zc                              # Z_jᵀ Z_l
    r1 = c * np.exp(1j * (theta[None, :] - theta[:, None]))
    r2 = c * np.exp(1j * (theta[None, :] + theta[:, None]))
    s1, m1 = _pair_sums(herm, r1, ck0 * np.outer(P0.conj(), P0),
                        lambda M: cb * np.sum(Pb.conj() * (M @ Pb), axis=0),
                        lambda jj, ll: cb * Pb[jj].conj() * Pb[ll], L)
    s2, m2 = _pair_sums(sym, r2, ck0 * np.outer(P0, P0),
                        lambda M: cb * np.sum(Pb * (M @ Pb), axis=0),
                        lambda jj, ll: cb * Pb[jj] * Pb[ll], L)
    return 0.5 * np.real(s1) - 0.5 * np.real(s2), 0.5 * (m1 + m2)


def simpson_sums(Phi, C, D, x0, seg_start, parts, H, dt, ends, points):
    """Weighted sums of one LTI run and its samples at given points.

    Parameters
    ----------
    Phi : (n, n) ndarray
        e^{AΔt} (Schur-stable: :func:`applies`).
    C : (p, n) ndarray
    D : (p,) ndarray
    x0 : (n,) ndarray
    seg_start : sequence of int
        First point of each piece, then N (the number of points).
    parts : list of Sinusoids or None
        The tones of each piece (None: d = 0).
    H : list of (n, T_s) complex ndarray or None
        The input matrices of each piece's exact step (see :func:`fdsc.stream._tone_input`).
    dt : float
    ends : (nb,) int ndarray
        Ends K (0 ≤ K ≤ N) of the sums ``Σ_{k<K} c^k f_k``.
    points : (np_,) int ndarray
        Points (0 ≤ k < N) at which f_k and d_k² are returned.

    Returns
    -------
    G : (2, 2, nb) ndarray
        ``G[i, s]``: for ``i = 0`` (z) and ``1`` (d), the sums with ``c = +1`` (s = 0) and
        ``c = −1`` (s = 1).
    f : (2, np_) ndarray
        ``f_k = z_kᵀ z_k`` and ``d_k²`` at the points.
    x_last : (n,) ndarray
        The state at the last point N − 1.
    magnitude : (nb,) ndarray
        The size of the terms that make up ``G[0, 0]`` (transient, cross and tone parts, each
        summed in absolute value): ``magnitude / G[0, 0]`` ≫ 1 means they cancel and digits are
        lost (a large steady state and transient that nearly annul each other, as for a tone
        near a slow pole over a short run); see :data:`MAX_CANCELLATION`.
    """
    n = x0.size
    Q = C.T @ C
    Y = {c: _stein(Phi, Q, c) for c in (1, -1)}
    ends = np.asarray(ends, dtype=np.int64)
    points = np.asarray(points, dtype=np.int64)
    G = np.zeros((2, 2, ends.size))
    mag = np.zeros(ends.size)
    f = np.zeros((2, points.size))
    x = np.asarray(x0, float).copy()
    N = seg_start[-1]
    x_last = None
    eye = np.eye(n)
    for s, part in enumerate(parts):
        k0, k1 = int(seg_start[s]), int(seg_start[s + 1])
        if part is None:
            T = 0
            omega = phase = amp = theta = np.zeros(0)
            X = np.zeros((n, 0), dtype=complex)
        else:
            omega, phase, amp = part.frequencies, part.phases, part.amplitudes
            T, theta = omega.size, omega * dt
            # X_j = (e^{jθ_j} I − Φ)⁻¹ H_j, all tones in one batched solve
            X = np.linalg.solve(np.exp(1j * theta)[:, None, None] * eye - Phi,
                                H[s].T[:, :, None])[:, :, 0].T
        Z = C @ X + np.outer(D, amp) if T else np.zeros((C.shape[0], 0), complex)
        if T:
            P0 = _phasors(omega, phase, np.array([k0]), dt)[:, 0]
            e = x - np.imag(X @ P0)
        else:
            e = x.copy()
        # every point this piece needs (the ends of its sums, its sample points and its last
        # point), with Φ^{k−k0} e and the phasors computed once for all of them
        bu, inv = np.unique(np.clip(ends, k0, k1), return_inverse=True)
        keep = bu > k0
        bb = bu[keep]
        here = (points >= k0) & (points < k1)
        kk = points[here]
        k_end = N - 1 if s == len(parts) - 1 else k1
        ks = np.union1d(np.union1d(bb, kk), [k_end])
        V = _powers(Phi, e, ks - k0)                                        # (len(ks), n)
        Pk = _phasors(omega, phase, ks, dt) if T else None                  # (T, len(ks))
        if bb.size:
            ib = np.searchsorted(ks, bb)
            L = bb - k0
            v = V[ib]
            part_G = np.zeros((2, 2, bu.size))
            part_mag = np.zeros(bu.size)
            if T:
                Pb = Pk[:, ib]                                              # (T, nb)
                # cross terms: u_j = (I − ρ_j Φ)⁻ᵀ Cᵀ Z_j, ρ_j = c e^{jθ_j} (one batched solve per c)
                CZ = (C.T @ Z).T[:, :, None]
                u_of = {c: np.linalg.solve(np.swapaxes(eye - (c * np.exp(1j * theta))[:, None, None] * Phi,
                                                       1, 2), CZ)[:, :, 0].T for c in (1, -1)}
            for si, c in enumerate((1, -1)):
                cL = np.where(L % 2 == 0, 1.0, float(c))
                ck0 = 1.0 if (c > 0 or k0 % 2 == 0) else -1.0
                head = e @ Y[c] @ e
                tail = np.einsum("bi,ij,bj->b", v, Y[c], v)
                total = ck0 * (head - cL * tail)
                if c > 0:
                    # rounding of the quadratic forms: |e|ᵀ|Y||e| (Y may be large where the state is
                    # badly scaled, with e small in those directions)
                    aY = np.abs(Y[c])
                    part_mag[keep] += np.abs(e) @ aY @ np.abs(e) + np.einsum("bi,ij,bj->b", np.abs(v), aY,
                                                                            np.abs(v))
                if T:
                    u = u_of[c]
                    cb = np.where(bb % 2 == 0, 1.0, float(c))
                    first = ck0 * np.sum(P0 * (e @ u))
                    last = cb * np.einsum("jb,bj->b", Pb, v @ u)
                    total = total + 2.0 * np.imag(first - last)
                    tones, size = _tone_sums(Z, theta, P0, Pb, k0, bb, c)
                    total = total + tones
                    if c > 0:
                        au = np.sum(np.abs(u), axis=1)
                        part_mag[keep] += 2.0 * (np.abs(e) @ au + np.abs(v) @ au) + size
                    part_G[1, si, keep] = _tone_sums(amp[None, :].astype(complex), theta, P0, Pb,
                                                     k0, bb, c)[0]
                part_G[0, si, keep] = total
            G += part_G[:, :, inv]
            mag += part_mag[inv]
        # the state x_k = Φ^{k−k0} e + Im Σ_j X_j P_j(k) at the points of ks that are used
        xs_all = V + (np.imag(Pk.T @ X.T) if T else 0.0)
        if kk.size:
            ip = np.searchsorted(ks, kk)
            xs = xs_all[ip]
            dk = (np.imag(Pk[:, ip]).T @ amp) if T else np.zeros(kk.size)
            zs = xs @ C.T + dk[:, None] * D[None, :]
            f[0, here] = np.sum(zs * zs, axis=1)
            f[1, here] = dk * dk
        # the state at the piece's end (the next piece's start, or the last point)
        x_end = xs_all[np.searchsorted(ks, k_end)]
        if s == len(parts) - 1:
            x_last = x_end
        else:
            x = x_end
    return G, f, x_last, mag
