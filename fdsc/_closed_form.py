"""The energy of an LTI run under pieces of tones, in closed form (no loop over the steps).

:mod:`fdsc.stream` sums the exact energy of every step, ``e_k = η_kᵀ Q η_k`` with
``η_k = [x_k; a∘Re P(k); a∘Im P(k)]`` (:mod:`fdsc._step_energy`). For one mode and a
disturbance made of pieces of sinusoids the states have a closed form, and so does every such
sum, so a run of any length costs a few small linear solves. On a piece starting at point
``k₀`` with tones ``d = Σ a_j Im P_j``, ``P_j(k) = e^{j(ω_j k Δt + φ_j)}``, the exact step
``x_{k+1} = Φ x_k + Σ_j Im(H_j P_j(k))`` has the particular solution ``Im Σ_j X_j P_j(k)`` with
``X_j = (e^{jθ_j} I − Φ)⁻¹ H_j``, ``θ_j = ω_j Δt``, so

    x_k = Φ^{k−k₀} e + Im Σ_j X_j P_j(k),   e = x_{k₀} − Im Σ_j X_j P_j(k₀),
    η_k = [Φ^{k−k₀} e; 0] + Im (Y P(k)),    Y = [X; j diag(a); diag(a)],

and each of the three parts of ``Σ_k e_k`` sums in closed form:

* transient: ``Σ_{m<L} (Φ^m e)ᵀ Q_xx (Φ^m e) = eᵀ Y₁ e − (Φ^L e)ᵀ Y₁ (Φ^L e)`` with
  ``Y₁ = Q_xx + Φᵀ Y₁ Φ`` (a Stein equation, summed by Smith's doubling);
* cross terms: ``Σ_{m<L} ρ^m Φ^m e = (I − ρΦ)⁻¹ (e − ρ^L Φ^L e)`` with ``ρ = e^{jθ_j}``;
* tones: products ``P̄_j P_l`` and ``P_j P_l`` are geometric in k, summed as
  ``(r^{k₀} − r^{b}) / (1 − r)``, or as ``e^{jα(k₀+b−1)/2} sin(αL/2) / sin(α/2)`` when ``r = e^{jα}``
  is near 1 and ``|α| L < 1`` (where the first form would cancel), and ``L`` when ``r = 1``.

This needs Φ Schur-stable (spectral radius < 1, checked with a margin by
:func:`applies`), no tone at a pole (refused before), and costs O(T² + n³) per piece and per
point of a coarse grid, independently of the run's length. It is the same sum as the loop's,
rounded differently (a stiff mode is summed in the coordinates that separate its fast and slow
parts, as the loop forms its energy). Its rounding grows where its terms cancel (a large
steady state and a transient that nearly annul each other, a badly scaled state whose
quadratic forms are large where e is small): :func:`step_sums` returns the size of its terms,
and the caller keeps the closed form only if that is at most :data:`MAX_CANCELLATION` times the
sum. Where kept, it agreed with the loop to ≤ 1.3e-10 relative (energies, coarse grid, final
state) over random loops with poles from 1e-3 to 5e5 rad/s (``tests/test_stream.py`` draws 80
of them).
"""

import numpy as np

__all__ = ["applies", "step_sums", "RADIUS_MARGIN", "MAX_CANCELLATION"]

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


def _tone_sums(herm, sym, theta, P0, Pb, k0, bb):
    """Σ_{k=k0}^{b−1} |Im (L Y P(k))|² for each end b, given ``herm = Yᴴ LᵀL Y`` and
    ``sym = Yᵀ LᵀL Y`` (T × T), P0 (T,) and Pb (T, nb) the phasors at k0 and at the ends. Also
    returns the size of its terms.

    ``|Im w|² = ½ w̄ᵀw − ½ Re(wᵀw)``: the products ``P̄_j P_l`` and ``P_j P_l`` are geometric in k
    with ratios ``e^{j(θ_l − θ_j)}`` and ``e^{j(θ_j + θ_l)}``."""
    L = bb - k0
    r1 = np.exp(1j * (theta[None, :] - theta[:, None]))
    r2 = np.exp(1j * (theta[None, :] + theta[:, None]))
    s1, m1 = _pair_sums(herm, r1, np.outer(P0.conj(), P0),
                        lambda M: np.sum(Pb.conj() * (M @ Pb), axis=0),
                        lambda jj, ll: Pb[jj].conj() * Pb[ll], L)
    s2, m2 = _pair_sums(sym, r2, np.outer(P0, P0),
                        lambda M: np.sum(Pb * (M @ Pb), axis=0),
                        lambda jj, ll: Pb[jj] * Pb[ll], L)
    return 0.5 * np.real(s1) - 0.5 * np.real(s2), 0.5 * (m1 + m2)


def step_sums(Phi, forms, x0, seg_start, parts, H, dt, ends):
    """The exact energy of one LTI run up to given points, and its last state.

    Parameters
    ----------
    Phi : (n, n) ndarray
        e^{AΔt} (Schur-stable: :func:`applies`).
    forms : list of (n + 2T_s, n + 2T_s) ndarray
        Per piece, the form of a step's energy on ``[x; a∘c; a∘s]`` for unit amplitudes
        (:func:`fdsc._step_energy.sine_forms`, in the state's own coordinates).
    x0 : (n,) ndarray
    seg_start : sequence of int
        First point of each piece, then N (the number of points).
    parts : list of Sinusoids or None
        The tones of each piece (None: d = 0).
    H : list of (n, T_s) complex ndarray or None
        The input matrices of each piece's exact step (see :func:`fdsc.stream._tone_input`).
    dt : float
    ends : (nb,) int ndarray
        Ends K (0 ≤ K ≤ N − 1) of the sums ``Σ_{k<K} e_k`` (e_k the energy of step k).

    Returns
    -------
    G : (nb,) ndarray
        The sums.
    x_last : (n,) ndarray
        The state at the last point N − 1.
    magnitude : (nb,) ndarray
        The size of the terms that make up G (transient, cross and tone parts, each summed in
        absolute value): ``magnitude / G`` ≫ 1 means they cancel and digits are lost (a large
        steady state and transient that nearly annul each other, as for a tone near a slow
        pole over a short run); see :data:`MAX_CANCELLATION`.
    """
    n = x0.size
    ends = np.asarray(ends, dtype=np.int64)
    G = np.zeros(ends.size)
    mag = np.zeros(ends.size)
    x = np.asarray(x0, float).copy()
    N = seg_start[-1]
    x_last = None
    eye = np.eye(n)
    for s, part in enumerate(parts):
        k0, k1 = int(seg_start[s]), int(seg_start[s + 1])
        Qf = forms[s]
        Y1 = _stein(Phi, Qf[:n, :n], 1)
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
        if T:
            P0 = _phasors(omega, phase, np.array([k0]), dt)[:, 0]
            e = x - np.imag(X @ P0)
            # η_k = [Φ^{k−k0} e; 0] + Im(Y P(k)), Y = [X; j diag(a); diag(a)]
            Y = np.concatenate([X, 1j * np.diag(amp), np.diag(amp).astype(complex)], axis=0)
            QY = Qf @ Y
            CZ = QY[:n]                                                     # (n, T)
            herm, sym = Y.conj().T @ QY, Y.T @ QY
        else:
            e = x.copy()
        # every point this piece needs (the ends of its sums and its last point), with
        # Φ^{k−k0} e and the phasors computed once for all of them
        bu, inv = np.unique(np.clip(ends, k0, k1), return_inverse=True)
        keep = bu > k0
        bb = bu[keep]
        k_end = N - 1 if s == len(parts) - 1 else k1
        ks = np.union1d(bb, [k_end])
        V = _powers(Phi, e, ks - k0)                                        # (len(ks), n)
        Pk = _phasors(omega, phase, ks, dt) if T else None                  # (T, len(ks))
        if bb.size:
            ib = np.searchsorted(ks, bb)
            v = V[ib]
            part_G = np.zeros(bu.size)
            part_mag = np.zeros(bu.size)
            head = e @ Y1 @ e
            tail = np.einsum("bi,ij,bj->b", v, Y1, v)
            total = head - tail
            # rounding of the quadratic forms: |e|ᵀ|Y||e| (Y may be large where the state is
            # badly scaled, with e small in those directions)
            aY = np.abs(Y1)
            part_mag[keep] += np.abs(e) @ aY @ np.abs(e) + np.einsum("bi,ij,bj->b", np.abs(v), aY,
                                                                    np.abs(v))
            if T:
                Pb = Pk[:, ib]                                              # (T, nb)
                # cross terms: u_j = (I − e^{jθ_j} Φ)⁻ᵀ (Q Y)_x,j (one batched solve)
                u = np.linalg.solve(np.swapaxes(eye - np.exp(1j * theta)[:, None, None] * Phi, 1, 2),
                                    CZ.T[:, :, None])[:, :, 0].T
                first = np.sum(P0 * (e @ u))
                last = np.einsum("jb,bj->b", Pb, v @ u)
                total = total + 2.0 * np.imag(first - last)
                tones, size = _tone_sums(herm, sym, theta, P0, Pb, k0, bb)
                total = total + tones
                au = np.sum(np.abs(u), axis=1)
                part_mag[keep] += 2.0 * (np.abs(e) @ au + np.abs(v) @ au) + size
            part_G[keep] = total
            G += part_G[inv]
            mag += part_mag[inv]
        # the state x_k = Φ^{k−k0} e + Im Σ_j X_j P_j(k) at the piece's end
        xs_all = V + (np.imag(Pk.T @ X.T) if T else 0.0)
        x_end = xs_all[np.searchsorted(ks, k_end)]
        if s == len(parts) - 1:
            x_last = x_end
        else:
            x = x_end
    return G, x_last, mag
