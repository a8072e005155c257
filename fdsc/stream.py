"""Streaming, batch simulation of LTI and switched loops: one compiled loop per run, O(1) memory.

:func:`fdsc.simulate.simulate` keeps every sample of a run and computes the particular
solutions of all steps in NumPy before its loop. This module does the same exact step without
any per-step array: the disturbance is generated inside the loop and everything a study needs is
reduced while the run goes.

**The step.** On a segment where the disturbance is ``d(t) = Σ a_j sin(ω_j t + φ_j)`` (a
:class:`~fdsc.signals.Sinusoids`, or one part of a :class:`~fdsc.signals.Piecewise`), write
``d = Σ a_j Im p_j`` with the phasors ``p_j(t) = e^{j(ω_j t + φ_j)}``: the plant and the tones'
oscillators form one autonomous linear system, and its exact discretization gives the step of
mode i from ``t_k`` to ``t_{k+1}``

    x_{k+1} = Φ_i x_k + Σ_j Im(H_ij p_j(t_k)),   Φ_i = e^{A_i Δt},
    H_ij = a_j ∫₀^Δt e^{A_i(Δt−s)} B e^{jω_j s} ds,

``H_i`` being the top-right block of ``expm([[A_i, B aᵀ], [0, diag(jω)]] Δt)`` (Van Loan). A
step costs ``n² + 2nT`` multiplications for T tones and needs no particular solution (a tone at a
pole of a mode is still refused, as by :func:`~fdsc.simulate.simulate`).
The phasors are rotated, not recomputed: within blocks of
:data:`PHASOR_BLOCK` steps, ``e^{j(ω t_k + φ)} = e^{j(ω t_b + φ)} · e^{jω (k − b) Δt}`` with the
block's first phasor computed by cos and sin and the rotations taken from a table, so each phasor
is a product of two correctly rounded numbers and no rounding error accumulates over the run.
Against a closed form and ``solve_ivp`` at rtol 1e-12 the states agree to a few 1e-14 (scalar
loop) and 4e-13 (the paper's switched loop, bounded by ``solve_ivp``'s own error); against
:func:`~fdsc.simulate.simulate` (particular solutions per step) to about 1e-13 relative (see the
tests and ``benchmarks/bench_simulate.py``). The switching law's score
``vᵀ W_i v`` with ``v = [ẋ; x]`` (or ``[ẍ; ẋ; x]``) is linear in ``ξ = [x; d]`` (or
``[x; d; ḋ]``), so it is evaluated as ``ξᵀ M ξ`` with M precomputed per (mode whose derivative
is measured, candidate): ``(n + 1)(n + 2)/2`` products instead of ``(2n)(2n + 1)/2``.
A :class:`~fdsc.signals.Sampled` input is integrated
exactly for its hold: ``x_{k+1} = Φ x_k + Γ₀ u_k`` (zero-order) or ``+ Γ₁ (u_{k+1} − u_k)``
(first-order), with ``Φ, Γ₀, Γ₁`` from one matrix exponential (Van Loan's block form).

**Reductions**: ``∫ zᵀz`` over the run, exact: within a step the mode (or the held input) and
the disturbance's tones are fixed, so the step's energy is the quadratic form ``ηᵀ Q η`` of
``η = [x_k; a∘cos(ω t_k + φ); a∘sin(ω t_k + φ)]`` (or ``[x_k; u_k; u_{k+1} − u_k]`` for a held
input), with one Q per mode and piece computed before the loop (:mod:`fdsc._step_energy`;
``(n + 2T)²`` multiplications a step). A switched run's output jumps at every switch, where a
quadrature of the samples (Simpson's rule, as before) was wrong by up to a step's energy: 9 %
of the whole on the paper's FDSC under its LF disturbance. The sums are Neumaier-compensated
(1e9 steps lose no digits); ``∫ d²`` is formed outside the loop in closed form. The same two
integrals at every point of a coarse grid (for the running L2-induced ratio and window
energies); the switch count; the
histogram of dwell times; the number of steps spent in each mode; and, only if asked for,
traces decimated to min/max per bin (plus the share of each mode per bin), which represent a
fast oscillation faithfully at any plot resolution. A run that keeps no traces needs memory
independent of its length.

**LTI runs in closed form.** A run of one mode under a Sinusoids or Piecewise disturbance, with
no traces, has samples in closed form (a transient plus a steady state per piece), and so have
the sums of its step energies: :mod:`fdsc._closed_form` computes them, the coarse grid included, in a time
independent of the horizon, wherever that keeps the loop's accuracy (else the loop runs; see
:func:`simulate_stream`, Notes).

**Batch.** :func:`simulate_batch` runs many :class:`Case` s (mode sets, disturbances, laws,
horizons and steps may all differ) in one call, parallel over cases on
``numba.get_num_threads()`` threads: each case is one call of the compiled loop, which releases
the GIL, from a pool of Python threads, the longest cases first; the results come back as arrays
(:class:`BatchResult`). The compiled loop is specialized to the batch's sizes when the batch is
long enough to repay a compilation (:data:`UNROLL_MIN_STEPS`), with the same results bit for bit.
"""

import concurrent.futures
import dataclasses
import math
import os
import pickle
import threading
import warnings
from concurrent.futures.process import BrokenProcessPool

import numba
import numpy as np
from numpy.typing import ArrayLike

from . import _divergence
from ._defaults import DEFAULT_MAX_MEMORY
from ._stream_run import UNROLL_MAX, UNROLL_MIN_STEPS, _run, _warn_unstable_modes, energy_overflow
from ._stream_setup import PHASOR_BLOCK, _prepare
from ._stream_types import BatchResult, Case, StreamResult, Trace
from ._validation import as_choice, as_count, check_type
from .exceptions import EnergyOverflowError, UnstableError, UnstableRunWarning
from .rules import PRINTED, SwitchRule
from .signals import Piecewise, Sampled, Sinusoids

__all__ = ["Case", "Trace", "StreamResult", "BatchResult", "simulate_stream", "simulate_batch",
           "PHASOR_BLOCK", "STREAM_KERNELS", "UNROLL_MAX", "UNROLL_MIN_STEPS"]

#: The compiled kernel, or the same loop run by the Python interpreter (for tests; slow).
STREAM_KERNELS = ("numba", "python")


# ---------------------------------------------------------------------------------------------
# public functions
# ---------------------------------------------------------------------------------------------

def _bound(pr):
    """The divergence monitor's bound R of a prepared case, in the caller's units."""
    return math.ldexp(pr["x_bound"], pr["scale_exp"])


def _overflow_message(where, res):
    which = " and ".join(name for name, v in (("∫zᵀz", res.energy), ("∫d²", res.input_energy))
                         if not math.isfinite(v))
    verb = "exceed" if " and " in which else "exceeds"
    return (f"{where}{which} over the run {verb} the float range (about 1.8e308) although the "
            f"state stays finite (|x(T)| = {float(np.abs(res.x_final).max()):.3g}); scale the "
            "disturbance or the initial state down")


def simulate_stream(modes, d: Sinusoids | Piecewise | Sampled, horizon: float, dt: float, *,
                    x0: ArrayLike | None = None, law_bands: list | None = None,
                    law_Q: list | None = None, law: str = "previous", sigma0: int = 0,
                    rule: SwitchRule = PRINTED, law_weights: list | None = None,
                    cumulative_every: float | None = None, trace_every: float | None = None,
                    dwell_edges: ArrayLike | None = None, kernel: str = "numba",
                    closed_form: bool = True, specialize: bool | None = None,
                    max_memory: float = DEFAULT_MAX_MEMORY) -> StreamResult:
    """Simulate one LTI or switched loop on ``0, dt, …, horizon`` and return its reductions.

    The same exact step and the same sampled switching law (paper eq. (31)) as
    :func:`fdsc.simulate.simulate`, streamed: the memory does not grow with the horizon unless
    traces or a coarse grid are asked for.

    Parameters
    ----------
    modes : LTISystem or list of LTISystem
        Closed loop(s) sharing B and D (``StateSpace`` or ``(A, B, C, D)`` accepted).
    d : Sinusoids, Piecewise or Sampled
        Scalar disturbance (see :class:`Case`).
    horizon, dt : float
        End time and step in s; the horizon must be a multiple of dt.
    x0 : (n,) array_like, optional
        Initial state (default 0).
    law_bands, law_Q : list, optional
        Ω_i and Q_i of the switching law (required for several modes).
    law : {"previous", "candidate"}, optional
        How ẋ enters the law (:data:`fdsc.simulate.LAWS`).
    sigma0 : int, optional
        Mode assumed active before t = 0.
    rule : SwitchRule, optional
        Hysteresis, minimum dwell time and/or moving window (:class:`~fdsc.rules.SwitchRule`;
        default the printed argmax). Its window must be a whole number ≥ 2 of steps, its dwell
        more than one step; either longer than the run is clamped to it (a dwell beyond the
        horizon gives the fixed-gain run of ``sigma0``). With a single mode a rule has no
        effect (a warning says so).
    law_weights : list of array_like, optional
        Instead of ``law_bands`` and ``law_Q``: one symmetric W_i per mode on ``[ẋ; x]`` (2n) or
        ``[ẍ; ẋ; x]`` (3n); see :func:`fdsc.simulate.simulate`.
    cumulative_every : float, optional
        Step (s) of the coarse grid on which ``∫₀ᵗ zᵀz`` and ``∫₀ᵗ d²`` are kept (exact): a
        whole number of steps of dt. Needed by :meth:`StreamResult.running_l2` and
        :meth:`StreamResult.window_energies`.
    trace_every : float, optional
        Bin width (s, a multiple of dt) of decimated min/max traces of x, z and d and of the
        mode share per bin.
    dwell_edges : (B + 1,) array_like, optional
        Edges (s) of the dwell-time histogram, at least one step apart (default 1, 2, 4, …
        steps, up to beyond the horizon); dwells longer than the last edge are not counted.
    kernel : {"numba", "python"}, optional
        The compiled loop or the same loop in the interpreter (slow; for tests).
    closed_form : bool, optional
        Sum an LTI run (one mode) under a Sinusoids or Piecewise disturbance, with no traces,
        in closed form instead of stepping through it (default True; see Notes).
    specialize : bool, optional
        Compile the loop for the run's sizes (states, outputs, modes, law vector, tones up to
        :data:`UNROLL_MAX`): about twice as fast per step, the same numbers bit for bit, but a
        first use for new sizes compiles for a few seconds (then numba's disk cache has it).
        Default None: for runs of at least :data:`UNROLL_MIN_STEPS` steps, and for shorter
        ones whose sizes this process has already compiled or loaded. Ignored by the
        ``"python"`` kernel.
    max_memory : float, optional
        Refuse a run whose outputs (coarse grid, traces and the moving window's samples) would
        need more than this many bytes (default :data:`fdsc.simulate.DEFAULT_MAX_MEMORY`, 4 GiB).

    Returns
    -------
    StreamResult

    Raises
    ------
    ValueError
        On a grid, coarse grid, trace bin or break that does not fit ``dt``, modes that do not
        share B and D or have no regulated output (C with 0 rows), a non-scalar disturbance, an
        MF range in ``law_bands`` (the law takes real Ψ only), non-PD ``law_Q``, law weights
        that are not symmetric or given together with ``law_bands``/``law_Q``, an unknown law
        or kernel, or a ``rule`` whose window is off the grid or whose window or dwell is one
        step or less (:meth:`SwitchRule.steps <fdsc.rules.SwitchRule.steps>`).
    MemoryLimitError
        If the outputs would need more than ``max_memory`` bytes; the message names the
        argument that asks for most of them (``cumulative_every``, ``trace_every`` or
        ``rule.window``) and the estimate. Raised before they are allocated.
    TypeError
        If ``modes``, ``d``, ``law_bands`` or ``rule`` are not of the accepted types.
    DimensionError
        If a law weight is neither (2n, 2n) nor (3n, 3n).
    SingularFrequencyError
        If a disturbance tone sits at an eigenvalue of a mode.
    UnstableError
        If the state overflows: the loop diverges and no finite energy summarizes it.
    EnergyOverflowError
        If the state stays finite but ``∫zᵀz`` or ``∫d²`` exceeds the float range. Runs whose
        samples could come near the square root of the float range (a huge ``x0`` or tone) are
        simulated scaled down by a power of two and scaled back, exactly, so that no sum
        overflows on the way: the energy of ``x0 = [1e153]`` through a stable first-order loop
        (about 5e305) is finite.

    Warns
    -----
    UnstableRunWarning
        If a mode that is not Hurwitz is active but the run stayed finite; or if the divergence
        monitor flags the run (:mod:`fdsc._divergence`: the state exceeds 10⁶ times the largest
        state any of its modes reaches alone from the same x0 under the same disturbance; the
        time and the growth are in the message and in ``grew_at`` and ``growth``).
    UserWarning
        If ``rule`` is not the printed law but there is a single mode (it has no effect).

    Notes
    -----
    The samples of an LTI run under tones are a transient plus a steady state in closed form,
    so the same sums of step energies (total and coarse grid) and the state at the end are
    computed without the loop, in a time independent of the horizon (:mod:`fdsc._closed_form`). It is
    used only where it keeps the loop's accuracy: the step Φ = e^{AΔt} has spectral radius
    ≤ 1 − 1e-6, and the closed form's terms are at most 30 times its sums (not so for a large
    steady state against the transient of a slow pole over a short run, or for a stiff loop in
    badly scaled coordinates); otherwise, and for ``closed_form=False``, the run goes through
    the loop. Where it is kept it agrees with the loop to a few 1e-10 relative or better
    (random loops with poles from 1e-3 to 5e5 rad/s; the paper's loops: about 1e-12).

    Examples
    --------
    >>> from fdsc import LTISystem, Sinusoids
    >>> loop = LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]])
    >>> run = simulate_stream(loop, Sinusoids([1.0], [1.0]), 100.0, 1e-3)
    >>> round(run.energy / run.input_energy, 3)     # |1/(j + 1)|² = 1/2, plus the transient
    0.499
    >>> run.switches, run.time_share
    (0, array([1.]))
    """
    as_choice("kernel", kernel, STREAM_KERNELS)
    check_type("closed_form", closed_form, (bool, np.bool_), "True or False")
    check_type("specialize", specialize, (bool, np.bool_, type(None)), "True, False or None")
    case = Case(modes, d, horizon, dt, x0=x0, law_bands=law_bands, law_Q=law_Q, law=law,
                sigma0=sigma0, rule=rule, law_weights=law_weights)
    pr = _prepare(case, "", cumulative_every, trace_every, dwell_edges, max_memory)
    (res,) = _run([pr], kernel, 1, closed_form, specialize)
    if res.diverged_at is not None:
        raise UnstableError(f"simulate_stream: the state overflowed at t = {res.diverged_at:g} s; "
                            "the loop diverges and no finite energy summarizes it")
    if energy_overflow(res):
        raise EnergyOverflowError(_overflow_message("simulate_stream: ", res))
    if res.grew_at is not None:
        warnings.warn(_divergence.message("simulate_stream: ", res.grew_at, res.growth,
                                          _bound(pr)), UnstableRunWarning, stacklevel=2)
    _warn_unstable_modes(pr, res, "simulate_stream: ", 3)
    return res


#: Held by a chunk of :func:`simulate_batch` or :func:`fdsc.supervise_batch` around its
#: ``warnings.catch_warnings(record=True)``, which swaps process-wide state and is not
#: thread-safe: chunks on the threads of one process (an in-process Dask client) run one at a
#: time. Each process has its own (a forked child gets a new one, never one held by a thread
#: that did not follow it).
_CHUNK_LOCK = threading.RLock()


def _renew_chunk_lock():
    global _CHUNK_LOCK
    _CHUNK_LOCK = threading.RLock()


if hasattr(os, "register_at_fork"):
    os.register_at_fork(after_in_child=_renew_chunk_lock)


def _chunk_lock():
    """The lock a chunk holds while it records its warnings (:data:`_CHUNK_LOCK`)."""
    return _CHUNK_LOCK


def _as_executor(executor):
    """``executor`` as a :class:`concurrent.futures.Executor` (a Dask client gives its own);
    a closed Dask client (or its executor, whose futures would never finish) is refused."""
    if type(executor).__module__.split(".")[0] == "distributed":
        for client in (executor, getattr(executor, "_client", None)):
            if getattr(client, "status", None) in ("closed", "closing"):
                raise RuntimeError(f"executor is a closed Dask client ({type(executor).__name__} "
                                   f"with status {client.status!r}); give a running client")
    if isinstance(executor, concurrent.futures.Executor):
        return executor
    if type(executor).__module__.split(".")[0] == "distributed" and hasattr(executor, "get_executor"):
        return executor.get_executor()
    raise TypeError("executor must be a concurrent.futures.Executor (a ProcessPoolExecutor, or "
                    "dask.distributed.Client(...).get_executor()) or a dask.distributed.Client, "
                    f"but found {type(executor).__name__}")


def _broken(exc):
    what = "executor's process pool is broken" if isinstance(exc, BrokenProcessPool) else "executor is broken"
    return RuntimeError(f"{what} (a worker died abruptly: killed, out of memory or crashed); "
                        f"make a new one ({type(exc).__name__}: {exc})")


def _submit(pool, fn, *args):
    """``pool.submit(fn, *args)``, a shut-down or broken pool named as ``executor``."""
    try:
        return pool.submit(fn, *args)
    except concurrent.futures.BrokenExecutor as exc:
        raise _broken(exc) from exc
    except RuntimeError as exc:
        if "shutdown" not in str(exc):
            raise
        raise RuntimeError(f"executor is shut down ({type(pool).__name__}: {exc}); give one that "
                           "is running") from exc


def _result(future):
    """``future.result()``, a pool broken while it ran the chunk named as ``executor``."""
    try:
        return future.result()
    except concurrent.futures.BrokenExecutor as exc:
        raise _broken(exc) from exc


def _for_executor(cases):
    """``cases`` as sent to an executor: without their labels (kept by the caller, they need not
    pickle), each checked here to pickle, else a TypeError names it."""
    sent = []
    for k, c in enumerate(cases):
        if getattr(c, "label", None) is not None and dataclasses.is_dataclass(c):
            c = dataclasses.replace(c, label=None)
        try:
            pickle.dumps(c, pickle.HIGHEST_PROTOCOL)
        except Exception as exc:
            raise TypeError(f"cases[{k}] cannot be sent to the executor: it does not pickle "
                            f"({type(exc).__name__}: {exc}); every part of a case but its label "
                            "must be picklable") from exc
        sent.append(c)
    return sent


def _run_chunk(cases, offset, opts):
    """On a worker: prepare and run ``cases`` (those from ``offset`` on) one after the other.
    Returns the results, what the caller's checks need of each prepared case, and the warnings
    raised here (category, text), to be raised again by the caller. Holds :data:`_CHUNK_LOCK`
    while it records them."""
    cumulative_every, trace_every, dwell_edges, max_memory, kernel, closed_form, specialize = opts
    with _chunk_lock(), warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        preps = [_prepare(c, f"cases[{offset + i}]: ", cumulative_every, trace_every, dwell_edges,
                          max_memory) for i, c in enumerate(cases)]
        results = _run(preps, kernel, 1, closed_form, specialize)
    lite = [{"modes": p["modes"], "x_bound": p["x_bound"], "scale_exp": p["scale_exp"]} for p in preps]
    return results, lite, [(w.category, str(w.message)) for w in caught]


def simulate_batch(cases, *, cumulative_every: float | None = None, trace_every: float | None = None,
                   dwell_edges: ArrayLike | None = None, threads: int | None = None,
                   kernel: str = "numba", closed_form: bool = True,
                   specialize: bool | None = None,
                   max_memory: float = DEFAULT_MAX_MEMORY, executor=None,
                   chunksize: int | None = None) -> BatchResult:
    """Run many :class:`Case` s in one call, in parallel over cases: on the threads of this
    process, or on the workers of an executor (a process pool, or a Dask cluster).

    Parameters
    ----------
    cases : sequence of Case
        The runs (modes, disturbance, law, horizon and step may differ between cases).
    cumulative_every, trace_every, dwell_edges : optional
        As in :func:`simulate_stream`, the same for every case (each must fit every case's dt).
    threads : int, optional
        Threads to use (default ``numba.get_num_threads()``, i.e. every core; at most
        ``numba.config.NUMBA_NUM_THREADS``).
    kernel : {"numba", "python"}, optional
        The compiled loop (cases in parallel) or the same loop in the interpreter (one case
        after the other).
    closed_form : bool, optional
        LTI cases under tones without traces in closed form (default True; see
        :func:`simulate_stream`).
    specialize : bool, optional
        As in :func:`simulate_stream`, for each group of cases with the same number of modes,
        kind of input and traces or none (default None: groups of at least
        :data:`UNROLL_MIN_STEPS` steps, or whose sizes this process already has).
    max_memory : float, optional
        As in :func:`simulate_stream`, for each case.
    executor : concurrent.futures.Executor or dask.distributed.Client, optional
        Where to run the cases instead of this process's threads: a
        :class:`~concurrent.futures.ProcessPoolExecutor`, the executor of a Dask cluster
        (``client.get_executor()``) or the ``dask.distributed.Client`` itself. The cases go in
        chunks of ``chunksize``; each chunk is prepared and run on one worker, one case after the
        other (``threads`` does not apply), and the results come back in the order of ``cases``,
        equal bit for bit to those of the thread path: the loops are the same compiled code
        (read from numba's disk cache by each worker), and no result depends on which worker ran
        a case or with which other cases. Warnings raised on a worker are raised again here.
        Dask is imported only by the caller who makes the client. A
        :class:`~concurrent.futures.ThreadPoolExecutor` is refused (give ``threads`` instead);
        an in-process Dask client (``Client(processes=False)``) is accepted, but on threads of
        one process the chunks run one at a time, each holding a lock while it records its
        warnings (:func:`warnings.catch_warnings` is not thread-safe), and a warning that another
        thread raises meanwhile is caught into that chunk: use processes for speed. A case's
        ``label`` stays here (it need not pickle); every other part of a case must pickle.
    chunksize : int, optional
        Cases per chunk sent to the executor (default: the cases split into 16 chunks, at most
        256 cases each); only with ``executor``.

    Returns
    -------
    BatchResult
        Cases that diverged have ``diverged`` set (and ``energy = inf`` if the state
        overflowed); they are reported by a warning, not by an exception, so that the other
        cases are kept.

    Raises
    ------
    ValueError, TypeError, SingularFrequencyError, MemoryLimitError
        As :func:`simulate_stream`, with the message naming the case (``cases[c]``); also if
        ``cases`` is empty, ``threads`` or ``chunksize`` is not a positive integer,
        ``chunksize`` is given without ``executor``, ``executor`` is neither an executor nor a
        Dask client or is a ThreadPoolExecutor (TypeError), or a case given with ``executor``
        does not pickle but for its label (TypeError naming ``cases[c]``).
    RuntimeError
        If ``executor`` cannot run the chunks, the message starting with ``executor``: a pool
        that is shut down, a process pool that is broken (a worker died, also while it ran),
        or a closed Dask client (checked first: its futures would never finish). The error of
        the pool is chained; RuntimeError is what the pool itself raises.
    EnergyOverflowError
        If a case's state stays finite but its energy exceeds the float range (the first such
        case is named).

    Warns
    -----
    UnstableRunWarning
        For diverged cases (listed: the state overflowed, or the divergence monitor flagged the
        run, see :func:`simulate_stream`), and for a non-Hurwitz mode active in a finite run.
    UserWarning
        For a case of a single mode with a ``rule`` other than the printed law (no effect).

    Examples
    --------
    >>> from fdsc import LTISystem, Sinusoids
    >>> loop = LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]])
    >>> runs = simulate_batch([Case(loop, Sinusoids([1.0], [w]), 50.0, 1e-3) for w in (0.5, 2.0)])
    >>> np.round(runs.energy / runs.input_energy, 3)     # ≈ 1 / (1 + ω²) after the transient
    array([0.801, 0.201])
    """
    as_choice("kernel", kernel, STREAM_KERNELS)
    check_type("closed_form", closed_form, (bool, np.bool_), "True or False")
    check_type("specialize", specialize, (bool, np.bool_, type(None)), "True, False or None")
    if isinstance(cases, Case) or not hasattr(cases, "__iter__"):
        raise TypeError(f"cases must be a sequence of Case, found {type(cases).__name__}")
    cases = list(cases)
    if not cases:
        raise ValueError("cases must hold at least one Case")
    threads = numba.get_num_threads() if threads is None else as_count("threads", threads)
    threads = min(threads, numba.config.NUMBA_NUM_THREADS)
    opts = (cumulative_every, trace_every, dwell_edges, max_memory, kernel, closed_form, specialize)
    if executor is None:
        if chunksize is not None:
            raise ValueError("chunksize applies only with an executor; give executor= or drop "
                             f"chunksize (found {chunksize!r})")
        preps = [_prepare(c, f"cases[{i}]: ", cumulative_every, trace_every, dwell_edges, max_memory)
                 for i, c in enumerate(cases)]
        results = _run(preps, kernel, threads, closed_form, specialize)
    else:
        if isinstance(executor, concurrent.futures.ThreadPoolExecutor):
            raise TypeError("executor must be a process pool or a Dask client, not a "
                            "ThreadPoolExecutor: to run the cases on this process's threads, drop "
                            "executor and give threads= (the compiled loops run in parallel there)")
        pool = _as_executor(executor)
        size = (max(1, min(256, -(-len(cases) // 16))) if chunksize is None
                else as_count("chunksize", chunksize))
        sent = _for_executor(cases)
        futures = [_submit(pool, _run_chunk, sent[i:i + size], i, opts)
                   for i in range(0, len(cases), size)]
        results, preps = [], []
        for future in futures:
            part, lite, caught = _result(future)
            results += part
            preps += lite
            for category, text in caught:
                warnings.warn(text, category, stacklevel=2)
    big = [i for i, r in enumerate(results) if energy_overflow(r)]
    if big:
        raise EnergyOverflowError(f"simulate_batch: {len(big)} of {len(cases)} cases: "
                                  + _overflow_message(f"cases[{big[0]}]: ", results[big[0]])
                                  + f" (cases {big[:20]})")
    batch = BatchResult(cases, results)
    over = np.array([r.diverged_at is not None for r in results])
    if over.any():
        bad = np.flatnonzero(over)
        warnings.warn(f"simulate_batch: {bad.size} of {len(cases)} cases diverged (the state "
                      f"overflowed): cases {bad.tolist()[:20]}; their energy is inf",
                      UnstableRunWarning, stacklevel=2)
    grew = np.flatnonzero(batch.diverged & ~over)
    if grew.size:
        first = results[grew[0]]
        warnings.warn(f"simulate_batch: {grew.size} of {len(cases)} cases diverge (flagged by the "
                      f"divergence monitor, their energies are finite but meaningless): cases "
                      f"{grew.tolist()[:20]}; "
                      + _divergence.message(f"cases[{grew[0]}]: ", first.grew_at, first.growth,
                                            _bound(preps[grew[0]])),
                      UnstableRunWarning, stacklevel=2)
    for pr, res, i in zip(preps, results, range(len(preps)), strict=True):
        if res.diverged_at is None:
            _warn_unstable_modes(pr, res, f"simulate_batch: cases[{i}]: ", 3)
    return batch
