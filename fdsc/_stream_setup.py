"""Preparation of the cases of :mod:`fdsc.stream`: grids, segments, exact step matrices, the
tones' phasor tables, the law's quadratic forms, and the stacking of a group of cases into the
padded arrays of the compiled loop (:mod:`fdsc._stream_loop`). Internal.
"""

import math
import warnings

import numpy as np
from scipy.linalg import expm

from . import _divergence, _step_energy
from ._defaults import DEFAULT_MAX_MEMORY
from ._modes import LAWS, _as_modes, _law_weights, _shared_input
from ._simulate_kernel import PHASOR_BLOCK, break_index, check_resolved, rotations
from ._stream_types import Case
from ._validation import as_choice, as_count, as_positive, as_vector, check_type
from .exceptions import MemoryLimitError
from .frequency import check_no_pole_at
from .rules import SwitchRule, _rule_steps, rule_state
from .signals import Piecewise, Sampled, Sinusoids

__all__ = []


_KIND_SINES, _KIND_ZOH, _KIND_FOH = 0, 1, 2
#: Most steps of one run: its step index is a 64-bit integer.
MAX_STEPS = 2**62
_LAW_CODE = {"previous": 0, "candidate": 1}


def _steps_of(name, seconds, dt, where):
    """A duration in s as a whole number of steps of ``dt`` (≥ 1)."""
    seconds = as_positive(name, seconds)
    k = round(seconds / dt)
    if k < 1 or abs(k * dt - seconds) > 1e-9 * seconds:
        raise ValueError(f"{where}{name} ({seconds!r} s) must be a multiple of dt ({dt!r} s)")
    return k


def _check_memory(where, N, nm, n, p, cum_steps, trace_steps, window_steps, sizes, max_memory):
    """Refuse a run whose per-run outputs would exceed ``max_memory`` bytes, before they are
    allocated: the coarse grid (its two running integrals and the result's three arrays), the
    traces (min and max of x, z, d and the mode shares per bin, twice: loop and result) and the
    moving window's (L, I) samples. ``sizes`` names the arguments (their values in s)."""
    parts = {
        "cumulative_every": 5 * ((N - 1) // cum_steps + 1) if cum_steps else 0,
        "trace_every": 2 * (2 * (n + p + 1) + nm + 1) * -(-N // trace_steps) if trace_steps else 0,
        "rule.window": nm * window_steps if window_steps > 1 else 0,
    }
    need = 8 * sum(parts.values())
    if need > max_memory:
        name = max(parts, key=parts.get)
        raise MemoryLimitError(
            f"{where}{name} = {sizes[name]!r} s on {N} points needs about {8 * parts[name] / 2**30:.3g} "
            f"GiB ({need / 2**30:.3g} GiB for the run's outputs in all), more than max_memory = "
            f"{max_memory / 2**30:.3g} GiB; {'shorten' if name == 'rule.window' else 'enlarge'} "
            f"{name}, shorten the horizon or raise max_memory")


def _segments(d, N, dt, where):
    """Point segments [start_s, start_{s+1}) and their Sinusoids (None: d = 0 there)."""
    if isinstance(d, Sinusoids):
        return [0, N], [d]
    idx = [min(max(break_index(b, 0.0, dt, N, where), 0), N) for b in d.breaks]
    pieces = [(0, idx[0], None)] + [(idx[j], idx[j + 1], p) for j, p in enumerate(d.parts)] \
        + [(idx[-1], N, None)]
    starts, parts = [], []
    for k0, k1, part in pieces:
        if k1 > k0:
            starts.append(k0)
            parts.append(part)
    return starts + [N], parts


#: Runs whose samples may exceed 2^SCALE_LIMIT run scaled down to it by a power of two: their
#: squares (≤ 2^800 per output) then sum over 2^62 steps without overflow.
SCALE_LIMIT = 400


def _scale_exponent(A, B, C, D, x0, d):
    """The exponent e ≥ 0 by which a run is scaled (x0 and d times 2^−e): 0 unless a bound of
    its samples (x0, d, and z = C x + D d with x within the modes' bound of
    :mod:`fdsc._divergence`) exceeds 2^SCALE_LIMIT.

    The simulated loop is linear in (x0, d) and the switching law's scores are quadratic forms of
    them (an absolute hysteresis margin is scaled by 2^−2e with them), so a run scaled by a power
    of two makes the same decisions and its samples are the unscaled ones times 2^−e, exactly
    (barring underflow of components below 2^(e − 1022) of the largest): its energies are its
    scaled energies times 2^2e, and they overflow only if the true energy exceeds the float
    range."""
    dm = _divergence.input_bound(d)
    x0n = _divergence.norm(x0)
    R = _divergence.state_bound(A, B[:, None], x0, d)
    if not np.isfinite(R):
        R = x0n + dm
    with np.errstate(over="ignore"):
        mag = max(x0n, dm, max(float(np.linalg.norm(c, 2)) for c in C) * R
                  + float(np.linalg.norm(D)) * dm)
    if not mag > 2.0 ** SCALE_LIMIT:
        return 0
    if not np.isfinite(mag):
        mag = max(x0n, dm) * 2.0 ** 64
    return max(0, math.frexp(mag)[1] - SCALE_LIMIT) if np.isfinite(mag) else 1023


def _scaled_signal(d, e):
    """``d`` times 2^−e (the same object for e = 0)."""
    if e == 0:
        return d
    if isinstance(d, Sinusoids):
        return Sinusoids(np.ldexp(d.amplitudes, -e), d.frequencies, d.phases)
    if isinstance(d, Piecewise):
        return Piecewise(d.breaks, [_scaled_signal(q, e) for q in d.parts])
    return Sampled(np.ldexp(d.values, -e), d.dt, d.hold)


def _prepare(case, where, cumulative_every, trace_every, dwell_edges, max_memory=DEFAULT_MAX_MEMORY):
    check_type(f"{where}case", case, Case)
    modes = _as_modes(case.modes)
    n, B, D = _shared_input(modes, where)
    B, D = B[:, 0].copy(), D[:, 0].copy()
    nm, p = len(modes), modes[0].n_outputs
    law = as_choice(f"{where}law", case.law, LAWS)
    W = _law_weights(n, nm, case.law_bands, case.law_Q, case.law_weights, where)
    check_type(f"{where}rule", case.rule, SwitchRule)
    if nm == 1 and not case.rule.is_printed:
        warnings.warn(f"{where}rule ({case.rule.describe()}) has no effect on a single mode: the "
                      "run is the fixed-gain run", UserWarning, stacklevel=3)
    sigma0 = as_count(f"{where}sigma0", case.sigma0, 0)
    if sigma0 >= nm:
        raise ValueError(f"{where}sigma0 must be a mode index in [0, {nm}), found {sigma0}")
    dt = as_positive(f"{where}dt", case.dt)
    horizon = as_positive(f"{where}horizon", case.horizon)
    steps = round(horizon / dt)
    if steps < 1 or abs(steps * dt - horizon) > 1e-9 * horizon:
        raise ValueError(f"{where}horizon ({horizon!r}) must be a multiple of dt ({dt!r})")
    if steps >= MAX_STEPS:
        raise ValueError(f"{where}horizon / dt = {steps:.3g} steps: at most {MAX_STEPS:.3g} steps "
                         "(the step index is a 64-bit integer); enlarge dt or shorten the horizon")
    N = steps + 1
    cum_steps = 0 if cumulative_every is None else _steps_of(
        "cumulative_every", cumulative_every, dt, where)
    if cum_steps > steps:
        raise ValueError(f"{where}cumulative_every ({cumulative_every:g} s) exceeds the horizon "
                         f"({horizon:g} s): the coarse grid would hold one point")
    trace_steps = 0 if trace_every is None else _steps_of("trace_every", trace_every, dt, where)
    _check_memory(where, N, nm, n, p, cum_steps, trace_steps, _rule_steps(case.rule, dt, steps, where)[1],
                  {"cumulative_every": cumulative_every, "trace_every": trace_every,
                   "rule.window": case.rule.window}, as_positive(f"{where}max_memory", max_memory))
    x0 = np.zeros(n) if case.x0 is None else np.array(as_vector(f"{where}x0", case.x0, n))
    A = np.array([m.A for m in modes])
    C = np.array([m.C for m in modes])
    Phi = np.array([expm(a * dt) for a in A])
    check_type(f"{where}d", case.d, Sinusoids | Piecewise | Sampled,
               "an fdsc.signals.Sinusoids, Piecewise or Sampled")
    rparams, ring, _, _ = rule_state(case.rule, dt, nm, steps, where)
    # a run whose samples could reach the square root of the float range runs scaled by 2^−e
    # (exact: every sum and score scales by a power of two; see _scale_exponent)
    e = _scale_exponent(A, B, C, D, x0, case.d)
    d = _scaled_signal(case.d, e)
    x0 = np.ldexp(x0, -e)
    if e and not rparams[1]:
        rparams[0] = math.ldexp(rparams[0], -2 * e)      # an absolute margin is in score units
    out = dict(N=N, dt=dt, nm=nm, n=n, p=p, Phi=Phi, A=A, B=B, C=C, D=D, W=W, law=_LAW_CODE[law],
               sigma0=sigma0, x0=x0, horizon=steps * dt, modes=modes, rparams=rparams,
               ring_len=ring.shape[0], scale_exp=e)
    # the divergence monitor's bound (fdsc._divergence); off for one mode, which cannot exceed it
    out["x_bound"] = _divergence.state_bound(A, B[:, None], x0, d) if nm > 1 else np.inf
    if isinstance(d, Sampled):
        if abs(d.dt - dt) > 1e-12 * dt:
            raise ValueError(f"{where}d is sampled every {d.dt!r} s but the run steps by "
                             f"dt = {dt!r} s; they must be equal")
        if d.values.size < N:
            raise ValueError(f"{where}d has {d.values.size} samples but the horizon needs {N}")
        G0, G1 = _hold_matrices(A, B, dt)
        out.update(kind=_KIND_ZOH if d.hold == "zoh" else _KIND_FOH, u=d.values[:N],
                   G0=G0, G1=G1, seg_start=np.array([0, N]), segments=[None],
                   forms=[_step_energy.held_forms(_step_energy.mode_coordinates(modes), dt, d.hold)])
    else:
        check_resolved(d, dt, where)
        seg_start, parts = _segments(d, N, dt, where)
        out.update(kind=_KIND_SINES, u=np.zeros(0), G0=np.zeros((nm, n)), G1=np.zeros((nm, n)),
                   seg_start=np.array(seg_start, dtype=np.int64), segments=parts)
        for part in parts:
            if part is not None:
                for i, a in enumerate(A):
                    check_no_pole_at(a, part.frequencies,
                                     what=f"{where}the forced response of mode {i} to the disturbance")
        # the exact energy of a step, per piece and mode (unit amplitudes: the loop scales the
        # oscillators by the piece's amplitudes)
        coords = _step_energy.mode_coordinates(modes)
        out["forms"] = [_step_energy.sine_forms(coords, np.zeros(0) if part is None else part.frequencies, dt)
                        for part in parts]
    out["cum_every"], out["trace_every"] = cum_steps, trace_steps
    if dwell_edges is None:
        edges = 2 ** np.arange(0, max(2, math.ceil(math.log2(N)) + 2), dtype=np.int64)
    else:
        try:
            e = np.asarray(dwell_edges, dtype=float)
        except (TypeError, ValueError):
            e = np.full(1, np.nan)
        if e.ndim != 1 or e.size < 2 or np.any(np.isnan(e)) or np.any(np.isinf(e[:-1])) \
                or not np.all(np.diff(e) > 0) or e[0] < 0:
            raise ValueError(f"{where}dwell_edges must be at least 2 increasing times ≥ 0 (s; the "
                             f"last may be inf), found {dwell_edges!r}")
        # edges beyond the horizon (inf included) all mean "longer than any dwell of this run";
        # the others count steps, so they must lie on the grid (as cumulative_every, trace_every)
        k = np.round(np.minimum(e, horizon + (np.arange(e.size) + 1) * dt) / dt)
        off = (e <= horizon) & (np.abs(k * dt - e) > 1e-9 * np.maximum(e, dt))
        if np.any(off):
            raise ValueError(f"{where}dwell_edges must be multiples of dt = {dt!r} s (dwell times are "
                             f"whole steps), found {float(e[off][0])!r} s")
        edges = k.astype(np.int64)
        if np.any(np.diff(edges) <= 0):
            # edges beyond the horizon need not lie on the grid, so two may round to one step
            raise ValueError(f"{where}dwell_edges must be at least one step (dt = {dt!r} s) apart, "
                             f"found {e.tolist()}")
    out["dwell_edges"] = edges
    return out


def _hold_matrices(A, B, dt):
    """Φ, Γ₀, Γ₁ of the exact step under a held input (Van Loan): expm of
    [[A, B, 0], [0, 0, 1/dt], [0, 0, 0]] dt = [[Φ, Γ₀, Γ₁], …]."""
    nm, n = A.shape[0], A.shape[1]
    G0, G1 = np.zeros((nm, n)), np.zeros((nm, n))
    for i, a in enumerate(A):
        M = np.zeros((n + 2, n + 2))
        M[:n, :n] = a
        M[:n, n] = B
        M[n, n + 1] = 1.0 / dt
        E = expm(M * dt)
        G0[i], G1[i] = E[:n, n], E[:n, n + 1]
    return G0, G1


def _tone_arrays(prep, T):
    """Per segment: frequencies, amplitudes, phases, the input matrices H of the augmented
    system and the rotation table, padded to T tones.

    Step k → k + 1 of mode i under ``d = Σ a_j Im(p_j)``, ``p_j = e^{j(ω_j t + φ_j)}``, is
    ``x_{k+1} = Φ_i x_k + Σ_j Im(H_ij p_j(t_k))`` with ``H_ij = a_j ∫₀^Δt e^{A_i(Δt−s)} B
    e^{jω_j s} ds``: the top-right block of ``expm([[A_i, B a], [0, diag(jω)]] Δt)`` (the exact
    discretization of the plant driven by the tones' oscillators)."""
    S, nm, n, dt = len(prep["segments"]), prep["nm"], prep["n"], prep["dt"]
    K = PHASOR_BLOCK
    nt = np.zeros(S, dtype=np.int64)
    omega, amp, phase = np.zeros((S, T)), np.zeros((S, T)), np.zeros((S, T))
    H = np.zeros((S, nm, n, T), dtype=complex)
    R = np.zeros((S, T, K), dtype=complex)
    for s, part in enumerate(prep["segments"]):
        if part is None:
            continue
        k = part.frequencies.size
        nt[s] = k
        omega[s, :k], amp[s, :k], phase[s, :k] = part.frequencies, part.amplitudes, part.phases
        for j, w in enumerate(part.frequencies):
            c, si = rotations(w, dt, K)
            R[s, j] = c + 1j * si
        for i, Ai in enumerate(prep["A"]):
            H[s, i, :, :k] = _tone_input(Ai, prep["B"], part, dt)
    return nt, omega, amp, phase, H, R


def _tone_input(A, B, part, dt):
    """H of one mode and one piece: the top-right block of ``expm([[A, B aᵀ], [0, diag(jω)]] Δt)``
    (see :func:`_tone_arrays`); (n, T) complex.

    The block is linear in the amplitudes a (column j is a_j ∫₀^Δt e^{A(Δt−s)} B e^{jω_j s} ds),
    so it is computed for unit amplitudes and scaled by a afterwards: the exponential's scaling
    and squaring then does not depend on the amplitudes, and a run with every amplitude (and
    x0) times 2^e gives every sample times 2^e exactly. Put into the exponential, a large
    amplitude (2^150 and beyond) costs digits, and 2^200 ruins the step."""
    n, k = A.shape[0], part.frequencies.size
    M = np.zeros((n + k, n + k), dtype=complex)
    M[:n, :n] = A
    M[:n, n:] = np.outer(B, np.ones(k))
    M[n:, n:] = np.diag(1j * part.frequencies)
    return expm(M * dt)[:n, n:] * np.asarray(part.amplitudes, dtype=float)[None, :]


def _law_forms(A, B, W, f):
    """The law's forms on ξ = [x; d] (f = 2) or [x; d; ḋ] (f = 3), packed for the kernel.

    Score i with the derivatives of mode m is ``vᵀ W_i v``, ``v = L_m ξ`` (``v = [ẋ; x]`` or
    ``[ẍ; ẋ; x]``), so it is ``ξᵀ (L_mᵀ W_i L_m) ξ``; returns ``Mt[m, q, i]``, the upper
    triangle of that form (row-major, off-diagonal entries doubled) at position q (the caller
    stores it as ``[m, i, q]``, each score one contiguous dot product)."""
    nm, n = A.shape[0], A.shape[1]
    r = n + f - 1
    iu = np.triu_indices(r)
    Mt = np.zeros((nm, r * (r + 1) // 2, W.shape[0]))
    for m in range(nm):
        L = np.zeros((f * n, r))
        Am = A[m]
        if f == 2:
            L[:n, :n], L[:n, n] = Am, B                      # ẋ = A x + B d
        else:
            L[:n, :n], L[:n, n], L[:n, n + 1] = Am @ Am, Am @ B, B   # ẍ = A² x + A B d + B ḋ
            L[n:2 * n, :n], L[n:2 * n, n] = Am, B
        L[(f - 1) * n:, :n] = np.eye(n)                      # x
        for i in range(W.shape[0]):
            F = L.T @ W[i] @ L
            F = F + F.T - np.diag(np.diag(F))
            Mt[m, :, i] = F[iu]
    return Mt


def _packed_positions(n_own, f_own, n, f):
    """Where the packed upper triangle of a form on ``ξ = [x; d(; ḋ)]`` with ``n_own`` states and
    law order ``f_own`` goes in that of ``n ≥ n_own`` states and order ``f ≥ f_own``: the states
    keep their indices, d and ḋ move from ``n_own`` on to ``n`` on."""
    r_own, r = n_own + f_own - 1, n + f - 1
    idx = np.arange(r_own)
    idx = np.where(idx < n_own, idx, idx - n_own + n)
    a, b = np.triu_indices(r_own)
    ia, ib = idx[a], idx[b]
    # row-major upper triangle of an r × r matrix: row a starts at a·r − a(a − 1)/2
    return ia * r - ia * (ia - 1) // 2 + (ib - ia)


def _stack(preps):
    """Pad every case to common sizes and concatenate the ragged outputs."""
    C = len(preps)
    n = max(q["n"] for q in preps)
    p = max(q["p"] for q in preps)
    nm = max(q["nm"] for q in preps)
    S = max(len(q["segments"]) for q in preps)
    T = max([1] + [s.frequencies.size for q in preps for s in q["segments"] if s is not None])
    nb = max(q["dwell_edges"].size for q in preps)
    # the law's vector: [ẋ; x] (f = 2), or [ẍ; ẋ; x] (f = 3) if any case has a second-order law
    f = max(q["W"].shape[1] // q["n"] for q in preps)
    K = PHASOR_BLOCK
    st = dict(N=np.array([q["N"] for q in preps], dtype=np.int64),
              dt=np.array([q["dt"] for q in preps]),
              nm=np.array([q["nm"] for q in preps], dtype=np.int64),
              Phi=np.zeros((C, nm, n, n)), C=np.zeros((C, nm, p, n)), D=np.zeros((C, p)),
              Mt=np.zeros((C, nm, nm, (n + f - 1) * (n + f) // 2)),
              law=np.array([q["law"] for q in preps], dtype=np.int64),
              sigma0=np.array([q["sigma0"] for q in preps], dtype=np.int64),
              x0=np.zeros((C, n)), kind=np.array([q["kind"] for q in preps], dtype=np.int64),
              seg_start=np.zeros((C, S + 1), dtype=np.int64), seg_nt=np.zeros((C, S), dtype=np.int64),
              omega=np.zeros((C, S, T)), amp=np.zeros((C, S, T)), phase=np.zeros((C, S, T)),
              Gr=np.zeros((C, S, nm, n, T)), Gi=np.zeros((C, S, nm, n, T)),
              Rre=np.zeros((C, S, K, T)), Rim=np.zeros((C, S, K, T)),
              G0=np.zeros((C, nm, n)), G1=np.zeros((C, nm, n)),
              cum_every=np.array([q["cum_every"] for q in preps], dtype=np.int64),
              trace_every=np.array([q["trace_every"] for q in preps], dtype=np.int64),
              dwell_edges=np.full((C, nb), np.iinfo(np.int64).max, dtype=np.int64),
              rparams=np.zeros((C, 4)),
              xmax=np.array([_divergence.SAFETY * q["x_bound"] for q in preps]),
              Qe=np.zeros((C, S, nm, n + 2 * T, n + 2 * T)),
              Rx=np.tile(np.eye(n), (C, nm, 1, 1)), split=np.zeros((C, nm), dtype=np.bool_))
    u_off, cum_off, tr_off = [0], [0], [0]
    for c, q in enumerate(preps):
        qn, qm, qp = q["n"], q["nm"], q["p"]
        st["Phi"][c, :qm, :qn, :qn] = q["Phi"]
        # padded states: Φ = I keeps them at zero; padded modes are never chosen (nm per case)
        for i in range(qm):
            st["Phi"][c, i, qn:, qn:] = np.eye(n - qn)
        st["C"][c, :qm, :qp, :qn] = q["C"]
        st["D"][c, :qp] = q["D"]
        # the forms on ξ from the case's own matrices, then placed in the padded ξ = [x; d; ḋ]
        # (a first-order law in a second-order batch leaves the ḋ entries zero; computed on
        # padded matrices, the products would round differently with the padding, and a
        # near-tie of the scores could switch otherwise than in the case's own run)
        g = q["W"].shape[1] // qn
        own = _law_forms(q["A"], q["B"], q["W"], g).transpose(0, 2, 1)
        st["Mt"][c, :qm, :qm][..., _packed_positions(qn, g, n, f)] = own
        st["rparams"][c] = q["rparams"]
        st["x0"][c, :qn] = q["x0"]
        st["G0"][c, :qm, :qn] = q["G0"]
        st["G1"][c, :qm, :qn] = q["G1"]
        ss = q["seg_start"]
        st["seg_start"][c, :ss.size] = ss
        st["seg_start"][c, ss.size:] = q["N"]
        if q["kind"] == _KIND_SINES:
            nt, om, am, ph, H, R = _tone_arrays(q, T)
            s_ = nt.size
            st["seg_nt"][c, :s_] = nt
            st["omega"][c, :s_], st["amp"][c, :s_], st["phase"][c, :s_] = om, am, ph
            # Im(H p) = Im(H) Re(p) + Re(H) Im(p); the tone index innermost: contiguous loops
            st["Gr"][c, :s_, :qm, :qn], st["Gi"][c, :s_, :qm, :qn] = H.imag, H.real
            R = R.transpose(0, 2, 1)
            st["Rre"][c, :s_], st["Rim"][c, :s_] = R.real, R.imag
        st["dwell_edges"][c, :q["dwell_edges"].size] = q["dwell_edges"]
        # the step energy's forms, placed in the padded η = [R x; a∘c; a∘s] (or [R x; u; Δu])
        for s_, (Qf, Rf, sp) in enumerate(q["forms"]):
            k_ = (Qf.shape[1] - qn) // 2
            if q["kind"] == _KIND_SINES:
                idx = np.r_[np.arange(qn), n + np.arange(k_), n + T + np.arange(k_)]
            else:
                idx = np.r_[np.arange(qn), n, n + 1]
            st["Qe"][c, s_, :qm][:, idx[:, None], idx[None, :]] = Qf
            st["Rx"][c, :qm, :qn, :qn] = Rf
            st["split"][c, :qm] = sp
        u_off.append(u_off[-1] + q["u"].size)
        ce, te = q["cum_every"], q["trace_every"]
        cum_off.append(cum_off[-1] + ((q["N"] - 1) // ce + 1 if ce else 0))
        tr_off.append(tr_off[-1] + (-(-q["N"] // te) if te else 0))
    st["u_all"] = np.concatenate([q["u"] for q in preps]) if u_off[-1] else np.zeros(1)
    st["u_off"], st["cum_off"], st["tr_off"] = (np.array(o, dtype=np.int64) for o in (u_off, cum_off, tr_off))
    st["ring_off"] = np.concatenate([[0], np.cumsum([q["ring_len"] for q in preps])]).astype(np.int64)
    return st, dict(n=n, p=p, nm=nm, nb=nb)
