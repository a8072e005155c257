"""How :mod:`fdsc.stream` runs a group of prepared cases: in closed form where that applies
(:mod:`fdsc._closed_form`), else by the compiled loop (:mod:`fdsc._stream_loop`), specialized to
the group's sizes when it is long enough, on a pool of threads. Internal.
"""

import dataclasses
import functools
import math
import warnings
from concurrent.futures import ThreadPoolExecutor

import numba
import numpy as np
import scipy.linalg

from . import _closed_form, _step_energy
from ._compensated import dot
from ._stream_loop import _case_loop, _case_numba
from ._stream_setup import _KIND_FOH, _KIND_SINES, _stack, _tone_input
from ._stream_types import StreamResult, Trace
from .exceptions import UnstableRunWarning

__all__ = []

_INPUTS = ("N", "dt", "nm", "Phi", "C", "D", "Mt", "law", "sigma0", "x0", "kind",
           "seg_start", "seg_nt", "omega", "amp", "phase", "Gr", "Gi", "Rre", "Rim", "xmax",
           "Qe", "Rx", "split")


def _run(preps, kernel, threads, closed_form=True, specialize=None):
    """Results of every prepared case: by the closed form where it applies (if allowed), by the
    loop otherwise."""
    closed = [_closed_result(q) if closed_form and _closed_form_applies(q) else None for q in preps]
    looped = [i for i, c in enumerate(closed) if c is None]
    # the loop runs in groups of cases with the same number of modes, kind of input and traces
    # or none, so that each group's compiled loop can be specialized to it (_shape_tag)
    groups = {}
    for i in looped:
        q = preps[i]
        groups.setdefault((q["nm"], q["kind"] == _KIND_SINES, q["trace_every"] == 0), []).append(i)
    planned = [(members, _loop_plan([preps[i] for i in members], kernel, specialize))
               for members in groups.values()]
    # every group's cases on one pool of threads, the longest first, so that the threads finish
    # together; each case writes only its own rows of its group's outputs
    runs = sorted(((steps, run) for _, plan in planned for steps, run in plan[0]),
                  key=lambda job: -job[0])
    if kernel == "numba" and len(runs) > 1 and threads > 1:
        with ThreadPoolExecutor(min(threads, len(runs))) as pool:
            for _ in pool.map(lambda job: job[1](), runs):
                pass
    else:
        for _, run in runs:
            run()
    for members, (_, results) in planned:
        for i, res in zip(members, results(), strict=True):
            closed[i] = res
    return [_unscaled(res, q["scale_exp"]) for res, q in zip(closed, preps, strict=True)]


def _unscaled(res, e):
    """The result of a run made at scale 2^−e (:func:`fdsc._stream_setup._scale_exponent`) in
    the caller's units: states, outputs and inputs times 2^e, energies times 2^2e (exact: powers
    of two). An energy that was finite at scale and is not in the caller's units exceeds the
    float range: it is left ``inf`` here and refused by the callers (:class:`EnergyOverflowError
    <fdsc.exceptions.EnergyOverflowError>`)."""
    if e == 0:
        return res
    with np.errstate(over="ignore"):
        def big(a):
            return np.ldexp(a, e)

        def bigger(a):
            return np.ldexp(a, 2 * e)

        trace = res.trace
        if trace is not None:
            trace = dataclasses.replace(trace, x_lo=big(trace.x_lo), x_hi=big(trace.x_hi),
                                        z_lo=big(trace.z_lo), z_hi=big(trace.z_hi),
                                        d_lo=big(trace.d_lo), d_hi=big(trace.d_hi))
        return dataclasses.replace(
            res, energy=float(bigger(res.energy)), input_energy=float(bigger(res.input_energy)),
            energy_cum=bigger(res.energy_cum), input_energy_cum=bigger(res.input_energy_cum),
            x_final=big(res.x_final), trace=trace)


def energy_overflow(res) -> bool:
    """True if a run's state stayed finite but an energy exceeds the float range."""
    return res.diverged_at is None and not (np.isfinite(res.energy) and np.isfinite(res.input_energy))


def _closed_form_applies(pr):
    return (pr["nm"] == 1 and pr["kind"] == _KIND_SINES and pr["trace_every"] == 0
            and _closed_form.applies(pr["Phi"][0]))


def _closed_result(pr):
    """The result of an LTI run under pieces of tones from the closed form of its step energies'
    sums (:mod:`fdsc._closed_form`): the same numbers as the loop's, rounded differently; None if
    the closed form's terms cancel too much to keep its accuracy."""
    N, dt, ce = pr["N"], pr["dt"], pr["cum_every"]
    A, B, Phi, x0 = pr["A"][0], pr["B"], pr["Phi"][0], pr["x0"]
    # a stiff mode's step forms are in the coordinates η = S⁻¹ x that separate its fast and slow
    # parts (fdsc._step_energy): the closed form runs in those coordinates
    Ae, Be, _, _, S, Si = _step_energy.mode_coordinates(pr["modes"][:1])[0]
    if S is not None:
        A, B = Ae, Be[:, 0]
        Phi, x0 = scipy.linalg.expm(A * dt), dot(Si, x0[:, None])[:, 0]
    parts = pr["segments"]
    H = [None if part is None else _tone_input(A, B, part, dt) for part in parts]
    grid = np.arange(0, N, ce, dtype=np.int64) if ce else np.zeros(0, dtype=np.int64)
    ends = np.concatenate([[N - 1], grid]).astype(np.int64)
    G, x_last, mag = _closed_form.step_sums(Phi, [f[0][0] for f in pr["forms"]], x0,
                                            pr["seg_start"], parts, H, dt, ends)
    if S is not None:
        x_last = dot(S, x_last[:, None])[:, 0]
    if not np.all(mag <= _closed_form.MAX_CANCELLATION * np.abs(G[0])):
        return None     # its terms cancel: digits would be lost, run the loop
    d_all = _input_energies(pr, ends)
    edges = pr["dwell_edges"].astype(float) * dt
    return StreamResult(
        horizon=pr["horizon"], dt=dt, energy=float(G[0]), input_energy=float(d_all[0]),
        switches=0, time_share=np.ones(1), dwell_edges=edges,
        dwell_counts=np.zeros(edges.size - 1, dtype=np.int64),
        x_final=x_last, sigma_final=0, t_cum=grid * dt, energy_cum=G[1:].copy(),
        input_energy_cum=d_all[1:].copy(), trace=None, diverged_at=None)


#: Largest size for which the compiled loop is specialized (see :func:`_shape_tag`): states,
#: outputs, tones and modes up to this many have loops of a fixed trip count.
UNROLL_MAX = 8
#: Fewest steps in one call (one group of cases) for which the specialized loop is used by
#: default. Compiling it for new sizes costs about 3–4 s of one core once (then numba's disk cache
#: has it) and saves 30–40 ns per step on the paper's loop, so a call repays its first
#: compilation from about 1e8 steps on; 5e7 lets the record's four largest calls (of the
#: paper's two-mode loop under 6 and 3 tones) share two compiled loops, and leaves its other
#: calls (3e8 steps in all, about 10 s) to the general loop rather than compile eight more
#: (about 30 s on every fresh install, such as each CI run).
UNROLL_MIN_STEPS = 50_000_000


def _shape_tag(st, kernel, specialize=None):
    """The ``shape`` argument of the compiled loop for the stacked cases ``st``.

    The general loop (``((),) * 7``) reads every size from its arrays, so its small inner loops
    (over the n states, p outputs, T tones, modes) have trip counts unknown to the compiler.
    For a group of cases run by the compiled kernel (``specialize`` True, or None and at least
    :data:`UNROLL_MIN_STEPS` steps in the group), each size up to :data:`UNROLL_MAX` that all
    cases share (after padding: n, p, T and the law's vector are padded to the largest case,
    the number of modes only if every case has it) becomes the length of a tuple: a constant
    of the compiled code, one compiled loop per combination. The arithmetic is the same, in the
    same order, so the results are the general loop's bit for bit (the tests check this):
    padded tones add exact zeros.

    A shorter group (``specialize`` None) is specialized too if this process already has the
    loop for its sizes (compiled or read from the disk cache by a longer group): it costs
    nothing more, and the results are the same either way.
    """
    general = ((),) * 7
    if kernel != "numba" or specialize is False:
        return general

    def fixed(size):
        return (0,) * int(size) if 0 < size <= UNROLL_MAX else ()

    nm = st["nm"]
    sines = st["kind"] == _KIND_SINES
    n_law = st["Mt"].shape[3]
    tag = (fixed(st["x0"].shape[1]), fixed(st["D"].shape[1]),
           fixed(nm[0]) if np.all(nm == nm[0]) else (),
           (0,) * n_law if n_law <= (UNROLL_MAX + 1) * (UNROLL_MAX + 2) // 2 else (),
           fixed(st["omega"].shape[2]) if np.any(sines) else (),
           (0,) if np.all(sines) else (), (0,) if np.all(st["trace_every"] == 0) else ())
    if specialize is None and int((st["N"] - 1).sum()) < UNROLL_MIN_STEPS:   # N − 1 steps
        return tag if _has_loop_for(tag) else general
    return tag


def _has_loop_for(tag):
    """True if the compiled loop for the specialization ``tag`` is loaded in this process."""
    ty = numba.typeof(tag)
    return any(sig[-1] == ty for sig in _case_numba.signatures)


def _loop_plan(preps, kernel, specialize=None):
    """The loop's runs of a group of cases: ``([(points, run), ...], results)``, each ``run()``
    stepping one case into the group's output arrays and ``results()`` reading them once every
    run is done."""
    st, dims = _stack(preps)
    shape = _shape_tag(st, kernel, specialize)
    Cn, n, p, nm, nb = len(preps), dims["n"], dims["p"], dims["nm"], dims["nb"]
    q = n + p + 1
    sums = np.zeros((Cn, 4))
    share_steps = np.zeros((Cn, nm), dtype=np.int64)
    dwell_counts = np.zeros((Cn, nb - 1), dtype=np.int64)
    cum = np.zeros((int(st["cum_off"][-1]), 2))
    n_tr = int(st["tr_off"][-1])
    tr_lo, tr_hi, tr_share = np.zeros((n_tr, q)), np.zeros((n_tr, q)), np.zeros((n_tr, nm))
    x_out = np.zeros((Cn, n))
    info = np.zeros((Cn, 3), dtype=np.int64)
    args = [st[k] for k in _INPUTS]
    ring = np.zeros((int(st["ring_off"][-1]), nm))
    ring_sum = np.zeros((Cn, nm))
    istate = np.zeros((Cn, 3), dtype=np.int64)
    loop = _case_numba if kernel == "numba" else _case_loop

    def run_case(c):
        u = st["u_all"][st["u_off"][c]:st["u_off"][c + 1]]
        cs = slice(st["cum_off"][c], st["cum_off"][c + 1])
        ts = slice(st["tr_off"][c], st["tr_off"][c + 1])
        with np.errstate(over="ignore", invalid="ignore"):
            loop(*[a[c] for a in args], u, st["G0"][c], st["G1"][c], st["cum_every"][c],
                 st["trace_every"][c], st["dwell_edges"][c], st["rparams"][c],
                 ring[st["ring_off"][c]:st["ring_off"][c + 1]], ring_sum[c], istate[c],
                 sums[c], share_steps[c],
                 dwell_counts[c], cum[cs], tr_lo[ts], tr_hi[ts], tr_share[ts], x_out[c], info[c],
                 shape)

    def results():
        return [_result(pr, c, st, sums, share_steps, dwell_counts, cum, tr_lo, tr_hi, tr_share,
                        x_out, info) for c, pr in enumerate(preps)]

    return [(int(st["N"][c]), functools.partial(run_case, c)) for c in range(Cn)], results


def _result(pr, c, st, sums, share_steps, dwell_counts, cum, tr_lo, tr_hi, tr_share, x_out, info):
    N, dt, n, p, nm = pr["N"], pr["dt"], pr["n"], pr["p"], pr["nm"]
    diverged = int(info[c, 0])
    ce, te = pr["cum_every"], pr["trace_every"]
    cs = slice(st["cum_off"][c], st["cum_off"][c + 1])
    t_cum = np.arange(cs.stop - cs.start) * ce * dt
    e_cum = cum[cs, 0].copy()
    d_all = _input_energies(pr, np.r_[N - 1, np.arange(cs.stop - cs.start) * ce])
    d_cum = d_all[1:]
    trace = None
    if te:
        ts = slice(st["tr_off"][c], st["tr_off"][c + 1])
        lo, hi, sh = tr_lo[ts].copy(), tr_hi[ts].copy(), tr_share[ts, :nm].copy()
        start = np.arange(lo.shape[0]) * te
        last = N - 1 if diverged < 0 else diverged - 1  # the last point written
        counts = np.clip(last + 1 - start, 1, te).astype(float)
        # bins after the point where the state overflowed were never written: not a value
        lo[start > last], hi[start > last], sh[start > last] = np.nan, np.nan, np.nan
        nn = st["x0"].shape[1]
        cols_x, cols_z = slice(0, n), slice(nn, nn + p)
        dcol = nn + st["D"].shape[1]
        trace = Trace(start * dt, lo[:, cols_x], hi[:, cols_x], lo[:, cols_z], hi[:, cols_z],
                      lo[:, dcol], hi[:, dcol], sh / counts[:, None])
    if diverged >= 0:
        # rows at and after the point where the state overflowed were never written
        keep = np.arange(t_cum.size) * ce < diverged
        t_cum, e_cum, d_cum = t_cum[keep], e_cum[keep], d_cum[keep]
    edges = st["dwell_edges"][c, :pr["dwell_edges"].size].astype(float) * dt
    return StreamResult(
        horizon=pr["horizon"], dt=dt, energy=float(sums[c, 0]),
        input_energy=float(d_all[0]) if diverged < 0 else math.nan, switches=int(sums[c, 2]),
        time_share=share_steps[c, :nm] / (N - 1),
        dwell_edges=edges, dwell_counts=dwell_counts[c, :edges.size - 1].copy(),
        x_final=x_out[c, :n].copy(), sigma_final=int(info[c, 1]), t_cum=t_cum, energy_cum=e_cum,
        input_energy_cum=d_cum, trace=trace, diverged_at=None if diverged < 0 else diverged * dt,
        grew_at=None if info[c, 2] < 0 else int(info[c, 2]) * dt,
        growth=None if info[c, 2] < 0 else float(sums[c, 3]) / pr["x_bound"])   # both at scale


def _input_energies(pr, ends):
    """``∫₀^{t_K} d²`` of a prepared case at the points ``ends``, exactly (in closed form for
    tones, per held step for samples: :mod:`fdsc._step_energy`)."""
    if pr["kind"] == _KIND_SINES:
        return _step_energy.sines_input_energy(pr["segments"], pr["seg_start"], pr["dt"], ends)
    return _step_energy.held_input_energy(pr["u"], pr["dt"], "foh" if pr["kind"] == _KIND_FOH else "zoh",
                                          ends)


def _warn_unstable_modes(pr, res, where, stacklevel):
    for i, m in enumerate(pr["modes"]):
        ev = np.linalg.eigvals(m.A)
        if ev.real.max() >= 0 and res.time_share[i] > 0:
            worst = ev[np.argmax(ev.real)]
            warnings.warn(f"{where}mode {i} is not Hurwitz (eigenvalue {worst:.6g}) and is active "
                          "in this run; its energies grow with the horizon", UnstableRunWarning,
                          stacklevel=stacklevel)
