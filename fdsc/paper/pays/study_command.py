"""What the stored studies of Part II share: how one is read from the repository, run on a pool of
worker processes with its wall time, CPU time and host recorded, and called from the command line.

The four studies on the full study's draws (:mod:`~fdsc.paper.pays.information`,
:mod:`~fdsc.paper.pays.adaptive_rung`, :mod:`~fdsc.paper.pays.variant_laws`,
:mod:`~fdsc.paper.pays.observer_rung`) each take the stored full study and an executor; their
commands (``python -m fdsc information`` …) and ``python -m fdsc part-two``
(:mod:`~fdsc.paper.pays.part_two`, every study at one commit) run them through
:func:`run_on_pool`.
"""

from __future__ import annotations

import json
import os
import sys
import time
from pathlib import Path

__all__ = ["REPO", "load_stored", "run_on_pool", "study_main"]

#: The repository this package lies in (where the stored studies are, under ``book/data``).
REPO = Path(__file__).resolve().parents[3]


def load_stored(file, path=None):
    """A stored study: the JSON at ``path``, or at ``file`` in the repository (None if absent).

    Parameters
    ----------
    file : path
        The study's place relative to the repository's root (``book/data/….json``).
    path : path, optional
        An explicit file instead.

    Returns
    -------
    dict or None
        None if the file is absent.
    """
    path = REPO / file if path is None else Path(path)
    if not path.is_file():
        return None
    return json.loads(path.read_text(encoding="utf-8"))


def _cpu_seconds() -> float:
    """CPU seconds of this process and of its joined children."""
    import resource

    return sum(u.ru_utime + u.ru_stime for u in (resource.getrusage(resource.RUSAGE_SELF),
                                                  resource.getrusage(resource.RUSAGE_CHILDREN)))


def run_on_pool(study, full: dict, workers: int, **kwargs) -> dict:
    """``study(full, executor=pool, **kwargs)`` on a fresh pool of ``workers`` spawned processes
    (one BLAS thread each), its result with ``seconds`` (wall) and ``host`` (CPUs, workers, CPU
    seconds of the study, load average before and after) added.

    Parameters
    ----------
    study : callable
        ``study(full, *, executor, **kwargs) -> dict``.
    full : dict
        The full study it reads.
    workers : int
        Worker processes, at least 1.
    **kwargs
        Passed to ``study``.

    Returns
    -------
    dict
    """
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    from fdsc._validation import as_count

    workers = as_count("workers", workers, 1)
    # one BLAS thread per worker (spawned, so that the setting holds): several workers each
    # spinning several BLAS threads on the same cores run many times slower
    for var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ.setdefault(var, "1")
    t0, load0, cpu0 = time.perf_counter(), os.getloadavg()[0], _cpu_seconds()
    with ProcessPoolExecutor(workers, mp_context=multiprocessing.get_context("spawn")) as pool:
        res = study(full, executor=pool, **kwargs)
    res["seconds"] = round(time.perf_counter() - t0, 1)
    res["host"] = {"cpus": os.cpu_count(), "workers": workers, "cpu_seconds": round(_cpu_seconds() - cpu0, 1),
                   "load_before": round(load0, 2), "load_after": round(os.getloadavg()[0], 2)}
    return res


def study_main(argv, *, prog: str, description: str, file, study, options=()) -> int:
    """The command line of a study on the stored full study: ``prog [--workers W] [--OPTION N …]
    [--out FILE | --replace]``.

    Parameters
    ----------
    argv : list of str or None
        The arguments (None: ``sys.argv[1:]``).
    prog : str
        The command's name (``python -m fdsc information``).
    description : str
    file : path
        The stored study it writes with ``--replace`` (relative to the repository's root); by
        default it writes ``out/`` and the same file name.
    study : callable
        ``study(full, *, executor, **options) -> dict``.
    options : sequence of (str, int, int, int or None)
        Integer options: keyword, default, least and greatest value (None: no greatest); the flag
        is the keyword with dashes (``n_test`` → ``--n-test``).

    Returns
    -------
    int
        0 on success (a bad argument or a missing stored study exits with a one-line message).
    """
    import argparse

    from fdsc.paper.pays.stored_study import FULL_FILE, load_full

    file = Path(file)
    ap = argparse.ArgumentParser(prog=prog, description=description)
    ap.add_argument("--workers", type=int, default=min(os.cpu_count() or 1, 4))
    for key, default, _lo, _hi in options:
        ap.add_argument("--" + key.replace("_", "-"), type=int, default=default)
    ap.add_argument("--out", default=str(Path("out") / file.name))
    ap.add_argument("--replace", action="store_true", help=f"write {file}, which the book reads")
    args = ap.parse_args(argv)
    if args.workers < 1:
        ap.error(f"--workers must be at least 1, but found {args.workers}")
    kwargs = {}
    for key, _default, lo, hi in options:
        v = getattr(args, key)
        if v < lo or (hi is not None and v > hi):
            span = f"at least {lo}" if hi is None else f"in [{lo}, {hi}]"
            ap.error(f"--{key.replace('_', '-')} must be {span}, but found {v}")
        kwargs[key] = v
    full = load_full()
    if full is None:
        ap.error(f"the stored study {FULL_FILE} is missing")
    out = REPO / file if args.replace else Path(args.out)
    res = run_on_pool(study, full, args.workers, **kwargs)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(res, indent=1) + "\n", encoding="utf-8")
    print(f"{prog.split()[-1]}: {res['seconds']:.0f} s on {args.workers} workers; written to {out}",
          file=sys.stderr)
    return 0
