"""The supervisor run causally on sampled measurements: the engine of
:meth:`fdsc.supervisor.Supervisor.run_measured`. Internal.

:class:`fdsc.prepared.Prepared` assumes the estimate ŵ is known as a signal (``d`` itself, or
``d`` plus a given error), so the decisions are computed before the loop is run. When ŵ is
computed from the loop's own measurements with a wrong model or a finite-difference derivative,

    ŵ_k = B1⁺ (ẋ_k − A x_k − B2 u_k),

its error depends on the state, hence on the decisions, and the monitors, the copies and the
plant must be run together. Here they are, on a grid of step ``dt``:

* at ``t_k`` the controller reads ``x_k`` and ``ẋ_k``: the true derivative
  ``A_t x_k + B1 d(t_k) + B2 u_k`` of the plant that is run (``derivative="exact"``) or the
  backward difference ``(x_k − x_{k−1}) / dt`` (``"backward"``; ``x_{−1} = x_0``), and forms ŵ_k
  with the *nominal* ``A`` (the model), so a plant run with ``A_t ≠ A`` gives
  ``ŵ = d + B1⁺ (A_t − A) x`` even with the exact derivative;
* ŵ_k is held over ``[t_k, t_{k+1})`` (a zero-order hold): every monitor and every copy of the
  realization steps exactly under the held input (Van Loan's block exponential of the system
  with ŵ as a constant state), and its output energy over the step is integrated exactly;
* the copies of the realization start from x0, as in :class:`~fdsc.prepared.Prepared`, the
  monitors from rest; ŵ_k below the rounding of its own terms counts as 0 (an exact model and
  derivative leave only rounding there, on which a relative hysteresis must not decide);
* the plant, with the copy of the active candidate that the realization through copies feeds
  back, steps exactly under the true disturbance (its tones' oscillators in the state, as in
  :mod:`fdsc._blocks`) and the held ŵ, and its output energy is integrated exactly;
* at each decision point the monitors' interval energies enter the fading signals μ, the banks
  restart, and the law decides, exactly as :meth:`fdsc.prepared.Prepared.mu` and
  :meth:`~fdsc.prepared.Prepared.decide` do.

The only approximation against :class:`~fdsc.prepared.Prepared` with the exact estimate is
the hold of ŵ (first order in dt); the plant's own run is exact for the decisions taken.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
from numba import njit

from . import _divergence
from ._blocks import Grid, _pair, pieces
from ._defaults import DEFAULT_MAX_MEMORY
from ._simulate_kernel import check_resolved
from ._validation import as_choice, as_matrix, as_nonnegative, as_positive, as_vector, check_type
from .decisions import (
    SupervisedRun,
    _bank_starts,
    _input_energy,
    _n_blocks,
    _older_bank,
    _scale_exponent,
    _scaled,
    _schedule,
    _unscale,
)
from .exceptions import EnergyOverflowError, MemoryLimitError, UnstableError, UnstableRunWarning
from .signals import Piecewise, Sinusoids

__all__ = []

DERIVATIVES = ("exact", "backward")
#: ŵ is set to 0 where it is below this multiple of the rounding scale of its terms.
EPS_FLOOR = 64 * np.finfo(float).eps
#: Steps between exact evaluations of the tones' oscillators (rotated in between).
RESYNC = 512


def _held(A, B, C, D, dt):
    """``(P, Q)`` of one step of an LTI system under an input held constant: the state
    ``[x; v]`` with ``v̇ = 0``, ``P`` its transition (top rows) and ``Q`` the output energy's
    quadratic form."""
    n, m = A.shape[0], B.shape[1]
    Aa = np.zeros((n + m, n + m))
    Aa[:n, :n] = A
    Aa[:n, n:] = B
    Ca = np.hstack([C, D])
    P, Q = _pair(Aa, np.zeros((n + m, 1)), Ca, np.zeros((C.shape[0], 1)), np.zeros(0), dt)
    return P[:n], Q


def _joint(plant, A_true, K, K0, dt, w):
    """``(P, Q)`` of one step of the plant ``A_true`` with the candidate gain K, its copy (if
    K0 is given) and the held ŵ as states, under the tones ``w`` (module docstring)."""
    A, B1, B2, C, D1, D2 = plant.A, plant.B1, plant.B2, plant.C, plant.D1, plant.D2
    n = A.shape[0]
    nc = 0 if K0 is None else n
    Kx = K if K0 is None else K0
    N = n + nc + 1
    Aj = np.zeros((N, N))
    Aj[:n, :n] = A_true + B2 @ Kx
    Cj = np.zeros((C.shape[0], N))
    Cj[:, :n] = C + D2 @ Kx
    if nc:
        Aj[:n, n:2 * n] = B2 @ (K - K0)
        Aj[n:2 * n, n:2 * n] = A + B2 @ K
        Aj[n:2 * n, 2 * n:] = B1
        Cj[:, n:2 * n] = D2 @ (K - K0)
    Bj = np.zeros((N, 1))
    Bj[:n] = B1
    P, Q = _pair(Aj, Bj, Cj, D1, w, dt)
    return P[:n + nc], Q


def modes(sup, A_true):
    """``(A_modes, B)``: the loop with each candidate active, as the continuous-time limit of
    the run (ŵ = d + B1⁺ (A_t − A) x fed through the copy of the active candidate): the state
    ``[x; x̂_σ]`` (copies) or x (direct); the other copies do not act on the plant."""
    p = sup.plant
    n = p.n_states
    if sup.K0 is None:
        return [A_true + p.B2 @ K for K in sup.gains], p.B1
    leak = p.B1 @ np.linalg.pinv(p.B1) @ (A_true - p.A)
    out = []
    for K in sup.gains:
        M = np.zeros((2 * n, 2 * n))
        M[:n, :n] = A_true + p.B2 @ sup.K0
        M[:n, n:] = p.B2 @ (K - sup.K0)
        M[n:, :n] = leak
        M[n:, n:] = p.A + p.B2 @ K
        out.append(M)
    return out, np.vstack([p.B1, p.B1])


def run_measured(sup, d, horizon, dt, *, derivative, true_A, x0, forgetting, hysteresis, warmup,
                 min_dwell, sigma0):
    """:meth:`fdsc.supervisor.Supervisor.run_measured` of the supervisor ``sup`` (see there)."""

    check_type("d", d, Sinusoids | Piecewise, "an fdsc.Sinusoids or fdsc.Piecewise")
    horizon = as_positive("horizon", horizon)
    dt = as_positive("dt", dt)
    derivative = as_choice("derivative", derivative, DERIVATIVES)
    n = sup.plant.n_states
    A_t = sup.plant.A if true_A is None else np.array(as_matrix("true_A", true_A, (n, n)))
    block = round(sup.decide_every / dt)
    if block < 1 or abs(block * dt - sup.decide_every) > 1e-9 * sup.decide_every:
        raise ValueError(f"dt must divide decide_every = {sup.decide_every:g} s into whole steps, "
                         f"but found {dt!r}")
    nb = _n_blocks(horizon, sup.decide_every)
    check_resolved(d, dt, "run_measured: ")
    x0 = np.zeros(n) if x0 is None else np.array(as_vector("x0", x0, n))
    lam = as_positive("forgetting", forgetting)
    h = as_nonnegative("hysteresis", hysteresis)
    nm = len(sup.gains)
    first, dwell = _schedule(nb, sup.decide_every, warmup, min_dwell, sigma0, nm)
    need = 8.0 * nb * (len(sup.gains) + 4)
    if need > DEFAULT_MAX_MEMORY:
        raise MemoryLimitError(f"run_measured: {nb} decision intervals need about {need / 2**30:.3g} GiB "
                               f"for the monitoring signals, over the limit of "
                               f"{DEFAULT_MAX_MEMORY / 2**30:.3g} GiB; shorten the horizon")
    if any(c.reads_estimate for c in sup.candidates):
        raise ValueError("run_measured: a candidate reads ŵ directly; on sampled measurements only "
                         "candidates that read x (gains and controllers without E, F) are supported")
    n_plant = n
    if any(c.n_states for c in sup.candidates):
        sup, A_t, x0 = _augmented(sup, A_t, x0)
    # the run scaled by a power of two (as fdsc.prepared.Prepared's): linear in (x0, d), ŵ
    # floored relative to its own terms and the law's hysteresis relative, so the decisions do
    # not depend on the scale, and the results are the scaled ones times 2^e (2^2e energies)
    scale = _scale_exponent(x0, d)
    d, x0 = _scaled(d, scale), np.ldexp(x0, -scale)
    A_modes, B_modes = modes(sup, A_t)
    worst = max(float(np.max(np.linalg.eigvals(M).real)) for M in A_modes)
    if worst >= 0:
        warnings.warn(f"run_measured: a candidate's loop with the plant that is run (true_A) and "
                      f"the estimate it feeds back has an eigenvalue with real part {worst:.4g} ≥ 0; "
                      "the divergence monitor is off", UnstableRunWarning, stacklevel=3)
    e, sigma, mu, big, x = run(sup, A_t, d, horizon, dt, x0, derivative,
                                         math.exp(-lam * sup.decide_every), h, first, dwell,
                                         int(sigma0))
    start = x0 if sup.K0 is None else np.tile(x0, 2)
    limit = _divergence.threshold(A_modes, B_modes, start, d)
    change = np.flatnonzero(np.diff(sigma)) + 1
    diverged = None
    if not np.all(np.isfinite(big)):
        k = int(np.flatnonzero(~np.isfinite(big))[0])
        t = (k + 1) * sup.decide_every
        raise UnstableError(f"run_measured: the state overflowed by t = {t:g} s; the loop diverges and "
                            "no finite energy summarizes it")
    over = np.flatnonzero(~(big <= limit))
    if not np.all(np.isfinite(mu)):
        if worst >= 0 or over.size:
            raise UnstableError("run_measured: a monitoring signal overflowed while the loop diverges "
                                "(the estimate carries the growing state); no finite energy "
                                "summarizes it")
        raise EnergyOverflowError("run_measured: a monitoring signal exceeds the float range (about "
                                  "1.8e308), so the law cannot compare them: scale the disturbance "
                                  "(or x0) down")
    if over.size:
        diverged = float((over[0] + 1) * sup.decide_every)
        bound = limit / _divergence.SAFETY
        with np.errstate(over="ignore"):
            shown = float(np.ldexp(bound, scale))
        warnings.warn(_divergence.message("run_measured: ", diverged, float(big[over[0]]) / bound,
                                          shown), UnstableRunWarning, stacklevel=3)
    elif not np.all(np.isfinite(e)):
        raise EnergyOverflowError("run_measured: the state stays finite but the energy exceeds the "
                                  "float range (about 1.8e308): scale the disturbance (or x0) down")
    points = np.arange(nb + 1) * sup.decide_every
    points[-1] = horizon
    share = np.bincount(sigma, minlength=nm) / sigma.size
    where = "run_measured: "
    input_energy = _unscale(_input_energy(Grid(d, np.array([0.0, horizon]))), scale, where=where,
                            what="the disturbance's energy ∫d²")
    energy = float(e.sum()) if diverged is not None else _unscale(float(e.sum()), scale, where=where)
    with np.errstate(over="ignore"):                    # a diverged run has warned
        x = np.ldexp(x[:n_plant], scale)
        if diverged is not None:
            energy = float(np.ldexp(energy, 2 * scale))
    mu = _unscale(mu, scale, where=where, what="a monitoring signal")
    return SupervisedRun(horizon, dt, energy, input_energy, change * sup.decide_every,
                         np.r_[sigma[:1], sigma[change]], share, x, points, mu, diverged)


def _augmented(sup, A_true, x0):
    """The supervisor with controllers that have states, seen as gains on the plant with every
    controller's states (:func:`fdsc.switched_loops`): the plant ``[x; x_k,1; …]`` whose
    controllers run on x, gains that pick the active one's output, K0 on x alone; the true
    plant's A in its first block. ``(view, A_true, x0)`` for the run."""
    from types import SimpleNamespace

    from .plant import Plant

    p, cs = sup.plant, sup.candidates
    n, sizes = p.n_states, [c.n_states for c in cs]
    N = n + sum(sizes)
    offs = np.cumsum([n, *sizes])
    A = np.zeros((N, N))
    A[:n, :n] = p.A
    gains = []
    for c, o, k in zip(cs, offs[:-1], sizes, strict=True):
        A[o:o + k, :n] = c.B
        A[o:o + k, o:o + k] = c.A
        K = np.zeros((p.n_controls, N))
        K[:, :n] = c.D
        K[:, o:o + k] = c.C
        gains.append(K)
    pad = np.zeros((N - n, 1))
    plant = Plant(A, np.vstack([p.B1, pad]), np.vstack([p.B2, np.zeros((N - n, p.n_controls))]),
                  np.hstack([p.C, np.zeros((p.C.shape[0], N - n))]), p.D1, p.D2)
    K0 = None
    if sup.K0 is not None:
        K0 = np.zeros((p.n_controls, N))
        K0[:, :n] = sup.K0
    At = A.copy()
    At[:n, :n] = A_true
    view = SimpleNamespace(plant=plant, gains=gains, K0=K0, monitors=sup.monitors,
                           loops=[plant.closed_loop(K) for K in gains], law=sup.law,
                           decide_every=sup.decide_every, restart_blocks=sup.restart_blocks,
                           candidates=cs)
    return view, At, np.r_[x0, np.zeros(N - n)]


def tables(sup, A_true, d, horizon, dt):
    """Everything the compiled loop reads, for a supervisor ``sup`` whose plant is run with the
    state matrix ``A_true``."""
    plant = sup.plant
    N = round(horizon / dt)
    pcs = pieces(d, horizon)
    T = max([p[2].size for p in pcs] + [0])
    nP = len(pcs)
    piece_start = np.empty(nP + 1, dtype=np.int64)
    for j, (t0, _t1, *_r) in enumerate(pcs):
        k = round(t0 / dt)
        if abs(k * dt - t0) > 1e-6 * dt + 1e-12 * max(1.0, t0):
            raise ValueError(f"run_measured: the disturbance switches at t = {t0!r} s, which is not a "
                             f"multiple of dt = {dt!r} s; choose dt dividing every break")
        piece_start[j] = k
    piece_start[-1] = N
    W = np.zeros((nP, T))
    AMP = np.zeros((nP, T))
    PH = np.zeros((nP, T))
    for j, (_t0, _t1, w, a, ph) in enumerate(pcs):
        W[j, :w.size], AMP[j, :w.size], PH[j, :w.size] = w, a, ph
    n_cand = len(sup.gains)
    n = plant.n_states
    nc = 0 if sup.K0 is None else n
    nj = n + nc + 1
    PJ = np.zeros((nP, n_cand, n + nc, nj + 2 * T))
    QJ = np.zeros((nP, n_cand, nj + 2 * T, nj + 2 * T))
    for j, (_t0, _t1, w, _a, _ph) in enumerate(pcs):
        idx = np.r_[np.arange(nj), nj + np.arange(w.size), nj + T + np.arange(w.size)]
        for i, K in enumerate(sup.gains):
            P, Q = _joint(plant, A_true, K, sup.K0, dt, w)
            PJ[j, i][:, idx] = P
            QJ[j, i][np.ix_(idx, idx)] = Q
    nm = max(m.A.shape[0] for m in sup.monitors)
    PM = np.zeros((n_cand, nm, nm + 1))
    QM = np.zeros((n_cand, nm + 1, nm + 1))
    for i, m in enumerate(sup.monitors):
        k = m.A.shape[0]
        P, Q = _held(m.A, m.B, m.C, m.D, dt)
        sel = np.r_[np.arange(k), nm]
        PM[i][np.ix_(np.arange(k), sel)] = P
        QM[i][np.ix_(sel, sel)] = Q
    PC = np.zeros((n_cand, n, n + 1))
    for i, loop in enumerate(sup.loops):
        PC[i] = _held(loop.A, loop.B, loop.C, loop.D, dt)[0]
    return (piece_start, W, AMP, PH, PJ, QJ, PM, QM, PC)


def run(sup, A_true, d, horizon, dt, x0, derivative, decay, h, first, dwell, sigma0):
    """``(energy per decision interval, σ per interval, μ at the decision points, max |x| at the
    end of each interval, final plant state)`` of the law run on measurements."""
    piece_start, W, AMP, PH, PJ, QJ, PM, QM, PC = tables(sup, A_true, d, horizon, dt)
    plant = sup.plant
    block = round(sup.decide_every / dt)
    nb = round(horizon / sup.decide_every)

    starts = _bank_starts(nb, sup.restart_blocks)       # as in Prepared
    fresh = np.zeros((2, nb + 1), dtype=np.bool_)
    for b, st in enumerate(starts):
        fresh[b, st] = True
    read = _older_bank(starts, nb)
    b1p = np.linalg.pinv(plant.B1)[0]
    Kx = np.array(sup.gains) if sup.K0 is None else np.array([sup.K0] * len(sup.gains))
    Kc = np.array(sup.gains) - Kx
    out_e = np.zeros(nb)
    sigma = np.zeros(nb, dtype=np.int64)
    mu = np.zeros((nb + 1, len(sup.gains)))
    big = np.zeros(nb)
    x = np.array(x0, dtype=float)
    _loop(block, nb, dt, piece_start, W, AMP, PH, np.cos(W * dt), np.sin(W * dt), PJ, QJ, PM, QM, PC,
          fresh, read, plant.A, A_true, plant.B1[:, 0], plant.B2, b1p, Kx, Kc, sup.K0 is not None,
          derivative == "backward", sup.law == "band_power", decay, h, first, dwell, sigma0,
          x, out_e, sigma, mu, big)
    return out_e, sigma, mu, big, x


@njit(cache=True)
def _loop(block, nb, dt, piece_start, W, AMP, PH, RC, RS, PJ, QJ, PM, QM, PC, fresh, read,
          A, At, b1, B2, b1p, Kx, Kc, copies, backward, largest, decay, h, first, dwell, q,
          x, out_e, sigma, mu, big):
    n = x.shape[0]
    nI = PC.shape[0]
    T = W.shape[1]
    nm = PM.shape[1]
    mu_u = B2.shape[1]
    nc = n if copies else 0
    nj = n + nc + 1
    Wd = nj + 2 * T
    xi = np.zeros(Wd)
    cs = np.zeros(2 * T)
    mon = np.zeros((2, nI, nm))
    acc = np.zeros((2, nI))
    bank = np.zeros((2, nI))
    cop = np.zeros((nI, n))
    if copies:
        for i in range(nI):
            for r in range(n):
                cop[i, r] = x[r]
    xprev = x.copy()
    xnew = np.zeros(n + nc)
    u = np.zeros(mu_u)
    v = np.zeros(nm + 1)
    tmp = np.zeros(nm)
    last = -dwell
    piece = 0
    sigma_now = q
    N = nb * block
    for k in range(N):
        while piece_start[piece + 1] <= k:
            piece += 1
        # the tones' oscillators: from cos and sin at a piece's start and every RESYNC steps,
        # rotated by the exact step rotation in between
        w = 0.0
        if (k - piece_start[piece]) % RESYNC == 0:
            t = k * dt
            for j in range(T):
                a = AMP[piece, j]
                arg = W[piece, j] * t + PH[piece, j]
                cs[j] = a * math.cos(arg)
                cs[T + j] = a * math.sin(arg)
                w += cs[T + j]
        else:
            for j in range(T):
                c0, s0 = cs[j], cs[T + j]
                cs[j] = c0 * RC[piece, j] - s0 * RS[piece, j]
                cs[T + j] = s0 * RC[piece, j] + c0 * RS[piece, j]
                w += cs[T + j]
        s = sigma_now
        Qs = QJ[piece, s]
        Ps = PJ[piece, s]
        # the control and the measured derivative
        for r in range(mu_u):
            acc_u = 0.0
            for c in range(n):
                acc_u += Kx[s, r, c] * x[c]
                if copies:
                    acc_u += Kc[s, r, c] * cop[s, c]
            u[r] = acc_u
        what = 0.0
        floor = 0.0
        for r in range(n):
            ax = 0.0
            at = 0.0
            for c in range(n):
                ax += A[r, c] * x[c]
                at += At[r, c] * x[c]
            bu = 0.0
            for c in range(mu_u):
                bu += B2[r, c] * u[c]
            if backward:
                xd = (x[r] - xprev[r]) / dt
            else:
                xd = at + b1[r] * w + bu
            what += b1p[r] * (xd - ax - bu)
            floor += abs(b1p[r]) * (abs(xd) + abs(ax) + abs(bu))
        # below the rounding of the difference, ŵ is 0 (an exact model and derivative give
        # ŵ = d exactly up to it; a relative hysteresis must not decide on rounding)
        if abs(what) <= EPS_FLOOR * floor:
            what = 0.0
        # the monitors, both banks
        for b in range(2):
            for i in range(nI):
                for c in range(nm):
                    v[c] = mon[b, i, c]
                v[nm] = what
                e = 0.0
                for r in range(nm + 1):
                    row = 0.0
                    for c in range(nm + 1):
                        row += QM[i, r, c] * v[c]
                    e += v[r] * row
                acc[b, i] += e
                for r in range(nm):
                    row = 0.0
                    for c in range(nm + 1):
                        row += PM[i, r, c] * v[c]
                    tmp[r] = row
                for r in range(nm):
                    mon[b, i, r] = tmp[r]
        # the plant with the active copy, under d and the held estimate
        for r in range(n):
            xi[r] = x[r]
        for r in range(nc):
            xi[n + r] = cop[s, r]
        xi[n + nc] = what
        for r in range(2 * T):
            xi[nj + r] = cs[r]
        e = 0.0
        for r in range(Wd):
            row = 0.0
            for c in range(Wd):
                row += Qs[r, c] * xi[c]
            e += xi[r] * row
        out_e[k // block] += e
        for r in range(n + nc):
            row = 0.0
            for c in range(Wd):
                row += Ps[r, c] * xi[c]
            xnew[r] = row
        # the other copies of the realization
        if copies:
            for i in range(nI):
                if i == s:
                    continue
                for r in range(n):
                    row = PC[i, r, n] * what
                    for c in range(n):
                        row += PC[i, r, c] * cop[i, c]
                    tmp[r] = row
                for r in range(n):
                    cop[i, r] = tmp[r]
            for r in range(n):
                cop[s, r] = xnew[n + r]
        for r in range(n):
            xprev[r] = x[r]
            x[r] = xnew[r]
        if (k + 1) % block == 0:
            kb = (k + 1) // block - 1
            top = 0.0
            for r in range(n):
                ax_r = abs(x[r])
                if not ax_r <= top:         # NaN propagates
                    top = ax_r
            big[kb] = top
            p = kb + 1
            for b in range(2):
                for i in range(nI):
                    if fresh[b, p]:
                        bank[b, i] = 0.0
                        for c in range(nm):
                            mon[b, i, c] = 0.0
                    else:
                        bank[b, i] = decay * bank[b, i] + acc[b, i]
                    acc[b, i] = 0.0
            rb = read[p]
            for i in range(nI):
                mu[p, i] = bank[rb, i]
            if p < nb:
                if p >= first and p - last >= dwell:
                    best = 0
                    cbest = math.inf
                    for i in range(nI):
                        ci = mu[p, i]
                        if largest:
                            ci = math.inf if ci == 0.0 else 1.0 / ci
                        if ci < cbest:
                            cbest = ci
                            best = i
                    cq = mu[p, sigma_now]
                    if largest:
                        cq = math.inf if cq == 0.0 else 1.0 / cq
                    if best != sigma_now and (1.0 + h) * cbest < cq:
                        sigma_now = best
                        last = p
                sigma[p] = sigma_now
    sigma[0] = q
