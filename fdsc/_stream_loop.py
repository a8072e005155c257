"""The compiled loop of :mod:`fdsc.stream`: one run, every reduction written into output arrays.

Internal: :func:`fdsc.stream.simulate_stream` and :func:`fdsc.stream.simulate_batch` prepare
the arrays (:mod:`fdsc._stream_setup`) and call it (:mod:`fdsc._stream_run`); the module
docstring of :mod:`fdsc.stream` describes the step and the reductions.
"""

import math

import numpy as np
from numba import njit

from .rules import decide, window_scores

__all__ = []

#: Points per block of plain summation; blocks are added with Neumaier's compensation.
_SUM_BLOCK = 1024


@njit(cache=True)
def _neumaier_add(s, c, b):
    """``s + b``, and the compensation ``c`` plus what that sum rounded off (Neumaier): the
    compensated total is ``(s + b) + c``."""
    t = s + b
    if abs(s) >= abs(b):
        c += (s - t) + b
    else:
        c += (b - t) + s
    return t, c


def _case_loop(N, dt, nm, Phi, C, D, Mt, law, sigma0, x0,
               kind, seg_start, seg_nt, omega, amp, phase, Gr, Gi, Rre, Rim, xmax, Qe, Rx, split,
               u, G0, G1, cum_every, trace_every, dwell_edges, rparams, ring, ring_sum, istate,
               sums, share_steps, dwell_counts, cum, tr_lo, tr_hi, tr_share, x_out, info, shape):
    """One run (see the docstring of :mod:`fdsc.stream`). Writes every result into the output
    arguments.

    ``sums`` = [∫zᵀz, 0 (∫d² is formed by the caller, in closed form), switches, ‖x‖∞ where
    the divergence monitor fired]; ``info`` =
    [diverged point or −1, final mode, point where the monitor fired or −1]: the monitor
    (:mod:`fdsc._divergence`) compares ``max_r |x_r|`` with ``xmax`` once per block of
    :data:`_SUM_BLOCK` points and at the last point. Points
    are k = 0 … N−1; step k goes from point k to point k+1 and uses
    the mode chosen at point k and the disturbance segment that contains point k.

    The energy of step k is exact: ``ηᵀ Q η`` with ``η = [R x_k; a∘c; a∘s]`` (tones: the
    oscillators' cos and sin at t_k times the amplitudes) or ``[R x_k; u_k; u_{k+1} − u_k]`` (a
    held input), ``Q = Qe[segment, mode]`` (W × W, symmetric) and ``R =
    Rx[mode]`` where ``split[mode]`` (:mod:`fdsc._step_energy`). The coarse grid keeps the sum of
    the steps before each of its points.

    ``shape`` specializes the compiled loop (see :func:`_shape_tag`): seven tuples whose
    lengths, constants of the compiled code, are n, p, the number of modes, the length of a
    row of ``Mt``, the number of tones T (every segment padded to T: padded tones have zero
    amplitude, gains and rotations and add exact zeros), 1 if the disturbance is a sum of
    sinusoids and 1 if no traces are kept; an empty tuple leaves that quantity to the arrays
    and arguments. The loops then have fixed trip counts, about twice as fast for the paper's
    loop, and give the same numbers."""
    # sizes: constants of the compiled code where ``shape`` gives them, else from the arrays
    n = len(shape[0]) if len(shape[0]) > 0 else x0.shape[0]
    p = len(shape[1]) if len(shape[1]) > 0 else C.shape[1]
    if len(shape[2]) > 0:
        nm = len(shape[2])
    nt2 = len(shape[3]) if len(shape[3]) > 0 else Mt.shape[2]
    TT = len(shape[4])      # > 0: every segment's tone loops run over all T tones
    T = TT if TT > 0 else omega.shape[1]
    if len(shape[5]) > 0:
        kind = 0
    if len(shape[6]) > 0:
        trace_every = 0
    K = Rre.shape[1]
    W = n + 2 * T           # the step energy's η = [R x; a∘c; a∘s] or [R x; u; Δu; 0 …]
    eta = np.zeros(W)
    # ξ = [x; d] (first-order law) or [x; d; ḋ] (second-order law): nt2 = r (r + 1) / 2
    r_xi = n + 1 if nt2 == (n + 1) * (n + 2) // 2 else n + 2
    prod = np.empty(nt2)
    xi = np.zeros(r_xi)
    sc = np.empty(Mt.shape[1])
    eff = np.empty(Mt.shape[1])
    margin = rparams[0]
    relative = rparams[1] > 0
    dwell_steps = int(rparams[2])
    win = int(rparams[3])
    plain = margin == 0.0 and dwell_steps == 0
    last_switch = 0
    x = x0.copy()
    xn = np.empty(n)
    bre = np.empty(T)       # phasor at the first point kb of the current block
    bim = np.empty(T)
    pre = np.empty(T)       # phasor at the current point
    pim = np.empty(T)
    s = 0
    kb = 0
    if kind == 0:
        for j in range(TT if TT > 0 else seg_nt[0]):
            th = omega[0, j] * (0.0 * dt) + phase[0, j]
            bre[j] = math.cos(th)
            bim[j] = math.sin(th)
            pre[j] = bre[j]
            pim[j] = bim[j]
    prev = sigma0
    switches = 0
    dwell_start = 0
    share_start = 0     # first point of the current mode (steps per mode: counted at switches)
    k_done = 0
    cum_next = 0 if cum_every > 0 else -1
    n_edges = dwell_edges.shape[0]
    # the step energies' sum: plain within blocks, Neumaier-compensated between them
    sz = 0.0
    cz = 0.0
    bz = 0.0        # the current block's plain sum
    kblock = 0
    diverged = -1
    grew = -1
    xgrew = 0.0
    for k in range(N):
        k_done = k
        if kind == 0 and k == seg_start[s + 1]:
            s += 1
            kb = k
            for j in range(TT if TT > 0 else seg_nt[s]):
                th = omega[s, j] * (k * dt) + phase[s, j]
                bre[j] = math.cos(th)
                bim[j] = math.sin(th)
                pre[j] = bre[j]
                pim[j] = bim[j]
        if kind == 0:
            nt = TT if TT > 0 else seg_nt[s]
            dk = 0.0
            for j in range(nt):
                dk += amp[s, j] * pim[j]
        else:
            nt = 0
            dk = u[k]
        # the switching law at point k: score_i = ξᵀ M ξ with ξ = [x; d] or [x; d; ḋ]
        if nm > 1:
            for c in range(n):
                xi[c] = x[c]
            xi[n] = dk
            if r_xi > n + 1:
                # ḋ at point k, for the measured ẍ = A_σ ẋ + B ḋ of a second-order law
                ddk = 0.0
                if kind == 0:
                    for j in range(nt):
                        ddk += amp[s, j] * omega[s, j] * pre[j]
                elif kind == 2:
                    ddk = (u[k + 1] - u[k]) / dt if k + 1 < N else (u[k] - u[k - 1]) / dt
                xi[n + 1] = ddk
            idx = 0
            for a in range(r_xi):
                xa = xi[a]
                for b_ in range(a, r_xi):
                    prod[idx] = xa * xi[b_]
                    idx += 1
            if law == 0:
                # the measured derivatives are those of the active mode, for every candidate
                for i in range(nm):
                    acc = 0.0
                    for q_ in range(nt2):
                        acc += Mt[prev, i, q_] * prod[q_]
                    sc[i] = acc
            else:
                for i in range(nm):
                    acc = 0.0
                    for q_ in range(nt2):
                        acc += Mt[i, i, q_] * prod[q_]
                    sc[i] = acc
            # the rule (fdsc.rules): window means, argmax of the case's own nm modes (padded
            # modes of a batch are never chosen), dwell time and hysteresis
            if win > 1:
                window_scores(sc, nm, win, ring, ring_sum, istate, eff)
                for i in range(nm):
                    sc[i] = eff[i]
            best = -np.inf
            choice = prev
            for i in range(nm):
                if sc[i] > best:
                    best = sc[i]
                    choice = i
            if not plain:
                choice = decide(choice, prev, sc[choice], sc[prev], k, last_switch, margin,
                                relative, dwell_steps)
                if choice != prev:
                    last_switch = k
            if choice != prev:
                if k > 0:
                    switches += 1
                    length = k - dwell_start
                    for e in range(n_edges - 1):
                        if dwell_edges[e] <= length < dwell_edges[e + 1]:
                            dwell_counts[e] += 1
                            break
                dwell_start = k
                share_steps[prev] += k - share_start
                share_start = k
            prev = choice
        m = prev
        # the exact energy of step k → k + 1 (none after the last point)
        ek = 0.0
        if k < N - 1:
            if split[m]:
                for r in range(n):
                    acc = 0.0
                    for c in range(n):
                        acc += Rx[m, r, c] * x[c]
                    eta[r] = acc
            else:
                for r in range(n):
                    eta[r] = x[r]
            if kind == 0:
                for j in range(T):
                    if j < nt:
                        eta[n + j] = amp[s, j] * pre[j]
                        eta[n + T + j] = amp[s, j] * pim[j]
                    else:
                        eta[n + j] = 0.0
                        eta[n + T + j] = 0.0
                si = s
            else:
                eta[n] = u[k]
                eta[n + 1] = u[k + 1] - u[k] if kind == 2 else 0.0
                si = 0
            for a in range(W):
                row = 0.0
                for b_ in range(W):
                    row += Qe[si, m, a, b_] * eta[b_]
                ek += eta[a] * row
        else:
            for r in range(n):
                ek += x[r] * x[r]       # only to detect an overflowed state at the last point
        if not ek < np.inf:
            diverged = k
            break
        if k == N - 1:
            ek = 0.0
        if trace_every > 0:
            b = k // trace_every
            first = k % trace_every == 0
            tr_share[b, m] += 1.0
            for r in range(p):
                zr = D[r] * dk
                for c in range(n):
                    zr += C[m, r, c] * x[c]
                if first or zr < tr_lo[b, n + r]:
                    tr_lo[b, n + r] = zr
                if first or zr > tr_hi[b, n + r]:
                    tr_hi[b, n + r] = zr
            for r in range(n):
                if first or x[r] < tr_lo[b, r]:
                    tr_lo[b, r] = x[r]
                if first or x[r] > tr_hi[b, r]:
                    tr_hi[b, r] = x[r]
            if first or dk < tr_lo[b, n + p]:
                tr_lo[b, n + p] = dk
            if first or dk > tr_hi[b, n + p]:
                tr_hi[b, n + p] = dk
        if k == cum_next:
            # ∫₀^{t_k} zᵀz: the steps before point k (∫ d² is formed by the caller)
            cum_next += cum_every
            cum[k // cum_every, 0] = (sz + bz) + cz
        bz += ek
        if k - kblock == _SUM_BLOCK - 1:
            kblock = k + 1
            sz, cz = _neumaier_add(sz, cz, bz)
            bz = 0.0
            if grew < 0:
                # the divergence monitor (fdsc._divergence), once per block
                xa = 0.0
                for r in range(n):
                    if abs(x[r]) > xa:
                        xa = abs(x[r])
                if xa > xmax:
                    grew = k
                    xgrew = xa
        if k == N - 1:
            if grew < 0:
                xa = 0.0
                for r in range(n):
                    if abs(x[r]) > xa:
                        xa = abs(x[r])
                if xa > xmax:
                    grew = k
                    xgrew = xa
            break
        # the exact step k → k + 1 in mode m: x_{k+1} = Φ x_k + Γ p_k (augmented system)
        if kind == 0:
            for r in range(n):
                acc = 0.0
                for c in range(n):
                    acc += Phi[m, r, c] * x[c]
                for j in range(nt):
                    acc += Gr[s, m, r, j] * pre[j] + Gi[s, m, r, j] * pim[j]
                xn[r] = acc
            if nt > 0:
                # phasors at t_{k+1}: the block's first phasor times a rotation from the table
                jj = k + 1 - kb
                if jj >= K:
                    kb = k + 1
                    jj = 0
                    for j in range(nt):
                        th = omega[s, j] * ((k + 1) * dt) + phase[s, j]
                        bre[j] = math.cos(th)
                        bim[j] = math.sin(th)
                for j in range(nt):
                    rr = Rre[s, jj, j]
                    ri = Rim[s, jj, j]
                    pre[j] = bre[j] * rr - bim[j] * ri
                    pim[j] = bre[j] * ri + bim[j] * rr
        else:
            for r in range(n):
                acc = G0[m, r] * u[k]
                if kind == 2:
                    acc += G1[m, r] * (u[k + 1] - u[k])
                for c in range(n):
                    acc += Phi[m, r, c] * x[c]
                xn[r] = acc
        for r in range(n):
            x[r] = xn[r]
    # steps 0 … min(last point, N − 2) in the last mode
    share_steps[prev] += min(k_done, N - 2) + 1 - share_start
    # the exact energy: the sum of every step's
    if diverged >= 0:
        sums[0] = np.inf
        sums[1] = np.nan
    else:
        sums[0] = (sz + bz) + cz
        sums[1] = 0.0
    sums[2] = switches
    sums[3] = xgrew
    for r in range(n):
        x_out[r] = x[r]
    info[0] = diverged
    info[1] = prev
    info[2] = grew



# nogil: the cases of a batch run on Python threads (see fdsc._stream_run._run), each in
# compiled code
_case_numba = njit(cache=True, nogil=True)(_case_loop)
