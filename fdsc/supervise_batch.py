"""Many runs of the laws on the disturbance estimate in one call, here or on an executor.

A :class:`SupervisedCase` is one run of a :class:`~fdsc.supervisor.Supervisor`: exact (the
estimate is the disturbance, :meth:`Supervisor.run <fdsc.supervisor.Supervisor.run>`) or on
sampled measurements at a step ``dt`` (:meth:`Supervisor.run_measured
<fdsc.supervisor.Supervisor.run_measured>`, with its model error and derivative).
:func:`supervise_batch` runs a list of them one after the other in this process, or in chunks on
the workers of a process pool or a Dask cluster, the same executors
:func:`fdsc.simulate_batch` takes; the results come back in the order of the cases and equal
those of the serial path bit for bit (each run is deterministic and independent of the others),
and the warnings raised on a worker are raised again by the caller, naming the case. A chunk
records its warnings holding the lock of :func:`fdsc.simulate_batch`'s chunks, so that chunks on
the threads of one process (an in-process Dask client) do not lose them.
"""

from __future__ import annotations

import warnings
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field

from ._validation import as_count, check_type
from .stream import _as_executor, _chunk_lock, _for_executor, _result, _submit
from .supervisor import SupervisedRun, Supervisor

__all__ = ["SupervisedCase", "supervise_batch"]

#: Options of :meth:`Supervisor.run` and those :meth:`Supervisor.run_measured` adds.
EXACT_OPTIONS = ("x0", "forgetting", "hysteresis", "warmup", "min_dwell", "sigma0")
MEASURED_OPTIONS = EXACT_OPTIONS + ("derivative", "true_A")


@dataclass(frozen=True)
class SupervisedCase:
    """One run of a law on the disturbance estimate.

    Parameters
    ----------
    supervisor : Supervisor
    d : Sinusoids or Piecewise
        The disturbance.
    horizon : float
        Run length (s), a whole number of the supervisor's decision intervals.
    dt : float, optional
        None (default): the exact run on the exact estimate (:meth:`Supervisor.run`); given: the
        run on measurements sampled at this step (:meth:`Supervisor.run_measured`).
    options : dict, optional
        Keyword arguments of that method: ``x0``, ``forgetting``, ``hysteresis``, ``warmup``,
        ``min_dwell``, ``sigma0``, and with ``dt`` also ``derivative`` and ``true_A``.
    label : object, optional
        Kept for the caller.
    """

    supervisor: Supervisor
    d: object
    horizon: float
    dt: float | None = None
    options: dict = field(default_factory=dict)
    label: object = field(default=None, compare=False)

    def run(self) -> SupervisedRun:
        """Run the case here.

        Returns
        -------
        SupervisedRun

        Raises
        ------
        TypeError
            If ``supervisor`` is not a Supervisor or ``options`` not a dict.
        ValueError
            If an option is unknown for the kind of run, or as the run itself raises.
        """
        check_type("supervisor", self.supervisor, Supervisor, "an fdsc.Supervisor")
        check_type("options", self.options, dict, "a dict of keyword arguments")
        allowed = EXACT_OPTIONS if self.dt is None else MEASURED_OPTIONS
        unknown = sorted(set(self.options) - set(allowed))
        if unknown:
            kind = "an exact run (dt=None)" if self.dt is None else "a run on measurements"
            raise ValueError(f"options {unknown} do not apply to {kind}; expected some of {list(allowed)}")
        if self.dt is None:
            return self.supervisor.run(self.d, self.horizon, **self.options)
        return self.supervisor.run_measured(self.d, self.horizon, self.dt, **self.options)


def _run_chunk(cases, offset):
    """On a worker: the runs of ``cases`` and the warnings they raised (category, text). Holds
    the lock of :func:`fdsc.simulate_batch`'s chunks while it records them."""
    out, caught_all = [], []
    with _chunk_lock():
        for i, c in enumerate(cases):
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                try:
                    out.append(c.run())
                except Exception as exc:        # re-raised by the caller, naming the case
                    return out, caught_all, (offset + i, exc)
            caught_all += [(w.category, f"cases[{offset + i}]: {w.message}") for w in caught]
    return out, caught_all, None


def supervise_batch(cases, *, executor=None, chunksize: int | None = None) -> list:
    """Run many :class:`SupervisedCase` s, here or on an executor.

    Parameters
    ----------
    cases : sequence of SupervisedCase
    executor : concurrent.futures.ProcessPoolExecutor or dask.distributed.Client, optional
        Where to run them (as in :func:`fdsc.simulate_batch`, but not on a thread pool: the runs
        hold the interpreter's lock); default: here, one after the other. An in-process Dask
        client (``Client(processes=False)``) is accepted, but on threads of one process the
        chunks run one at a time (each holds a lock while it records its warnings, and a warning
        that another thread raises meanwhile is caught into that chunk): use processes for
        speed. A case's ``label`` stays here (it need not pickle); the rest must pickle.
    chunksize : int, optional
        Cases per chunk sent to the executor (default: the cases split into 16 chunks); only
        with ``executor``.

    Returns
    -------
    list of SupervisedRun
        In the order of ``cases``.

    Raises
    ------
    TypeError
        If ``cases`` is not a non-empty sequence of SupervisedCase, ``executor`` is a thread
        pool or neither an executor nor a Dask client, or a case given with ``executor`` does
        not pickle but for its label (naming ``cases[c]``).
    ValueError
        If ``chunksize`` is not a positive integer, or is given without ``executor``.
    RuntimeError
        If ``executor`` cannot run the chunks (as in :func:`fdsc.simulate_batch`; the message
        starts with ``executor``): shut down, a broken process pool, or a closed Dask client.
    Exception
        The first failing case's own exception, its message prefixed with ``"cases[c]: "``.

    Warns
    -----
    UnstableRunWarning
        As each run warns, prefixed with ``"cases[c]: "``.

    Examples
    --------
    >>> from fdsc import Piecewise, Plant, Sinusoids
    >>> plant = Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
    ...               [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.1]])
    >>> sup = Supervisor(plant, [[[-21.85, -22.27]], [[0.495, -1.473]]])
    >>> d = Piecewise([0.0, 60.0, 200.0], [Sinusoids([1.0], [0.2]), Sinusoids([1.0], [12.0])])
    >>> runs = supervise_batch([SupervisedCase(sup, d, 120.0, options={"warmup": 5.0}),
    ...                         SupervisedCase(sup, d, 120.0, 1e-3,
    ...                                        {"warmup": 5.0, "derivative": "backward"})])
    >>> [r.sequence.tolist() for r in runs]
    [[0, 1], [0, 1]]
    """
    if not isinstance(cases, list | tuple) or not cases:
        raise TypeError("cases must be a non-empty list or tuple of fdsc.SupervisedCase")
    for k, c in enumerate(cases):
        check_type(f"cases[{k}]", c, SupervisedCase, "an fdsc.SupervisedCase")
    if executor is None:
        if chunksize is not None:
            raise ValueError("chunksize applies only with an executor; give executor= or drop "
                             f"chunksize (found {chunksize!r})")
        results = [_run_chunk(list(cases), 0)]
    else:
        if chunksize is not None:
            chunksize = as_count("chunksize", chunksize)
        if isinstance(executor, ThreadPoolExecutor):
            raise TypeError("executor must be a process pool or a Dask client, not a ThreadPoolExecutor: the "
                            "runs hold the interpreter's lock (threads would not run them in parallel) and "
                            "the warnings of concurrent threads cannot be told apart")
        pool = _as_executor(executor)
        size = -(-len(cases) // 16) if chunksize is None else chunksize
        sent = _for_executor(cases)
        futures = [_submit(pool, _run_chunk, sent[a:a + size], a) for a in range(0, len(cases), size)]
        results = [_result(f) for f in futures]
    out = []
    for runs, caught, failed in results:
        for category, text in caught:
            warnings.warn(text, category, stacklevel=2)
        if failed is not None:
            k, exc = failed
            try:
                named = type(exc)(f"cases[{k}]: {exc}")
            except TypeError:                   # an exception with other arguments: keep it
                exc.add_note(f"raised by cases[{k}]")
                raise exc from None
            raise named from exc
        out += runs
    return out
