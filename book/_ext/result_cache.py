"""Sphinx extension: the chapters of one build share one computation of every result.

At the start of a build it sets ``FDSC_CACHE_DIR`` for the kernels that execute the notebooks, and
:func:`fdsc.paper.shared.cache.cached` keeps each chapter result there: the landing page's
findings and the report (built from the whole record) and the chapters then reuse the same
values instead of computing them again. If ``FDSC_CACHE_DIR`` is already set (``make book``,
``make test`` and ``.ci/run`` set it to ``book/_build/.fdsc-results``), that folder is used and
kept, so that a build and a test run share one computation of each result whichever runs first;
its keys hash the sources, so results of other code are never read. Otherwise the build uses a
fresh folder ``<outdir>/../.fdsc-cache`` of its own.

If any chapter is to be executed (the notebook cache does not hold it for these sources), the
whole reproduction record is computed first, on :func:`fdsc.paper.record.record_jobs`
processes; then those chapters are executed as many at a time, each in its own kernel, longest
first (by the cold times the environment page shows), and every chapter that ran without error
is stored in the notebook cache (:func:`notebook_cache.store_execution`), where MyST-NB finds
it. A chapter that failed is not stored: MyST-NB executes it again itself and reports its error
as usual. MyST-NB would execute the chapters one after the other on one core.
"""

import copy
import json
import os
import shutil
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import nbformat

from fdsc.paper.shared.cache import CACHE_ENV


def _use_results_folder(app):
    if os.environ.get(CACHE_ENV):
        Path(os.environ[CACHE_ENV]).mkdir(parents=True, exist_ok=True)
        return
    folder = Path(app.outdir).parent / ".fdsc-cache"
    shutil.rmtree(folder, ignore_errors=True)
    folder.mkdir(parents=True)
    os.environ[CACHE_ENV] = str(folder)


def _chapters_to_execute(app):
    """The notebooks of the book that the notebook cache does not hold for these sources."""
    from notebook_cache import cached_execution

    folder = Path(app.config.nb_execution_cache_path)
    return [p for p in sorted(Path(app.srcdir).glob("*.ipynb"))
            if cached_execution(folder, nbformat.read(str(p), as_version=4)) is None]


def _precompute_record(app):
    if app.config.nb_execution_mode in ("off", "inline"):
        return
    todo = _chapters_to_execute(app)
    if not todo:
        return
    from fdsc.paper.record import record_jobs, reproduction_record

    jobs = record_jobs()
    start = time.perf_counter()
    reproduction_record()
    print(f"result_cache: the reproduction record computed on {jobs} processes in "
          f"{time.perf_counter() - start:.0f} s before executing {len(todo)} chapters")
    if jobs > 1 and len(todo) > 1:
        _execute_chapters(app, todo, jobs)


def _longest_first(app, paths):
    """``paths`` ordered by their last measured cold time, longest first (unknown ones first)."""
    try:
        times = json.loads((Path(app.srcdir) / "data" / "cold_times.json").read_text())["chapters"]
    except (OSError, ValueError, KeyError):
        times = {}
    return sorted(paths, key=lambda p: -times.get(p.stem, float("inf")))


def _execute_one(app, path):
    """Execute one chapter in its own kernel; store it in the notebook cache if no cell failed.
    Returns ``(stem, seconds, stored)``."""
    from nbclient import NotebookClient
    from notebook_cache import error_outputs, store_execution, writer_lock

    source = nbformat.read(str(path), as_version=4)
    executed = copy.deepcopy(source)
    start = time.perf_counter()
    try:
        NotebookClient(executed, timeout=app.config.nb_execution_timeout, allow_errors=True,
                       kernel_name=source.metadata.get("kernelspec", {}).get("name", "python3"),
                       resources={"metadata": {"path": str(path.parent)}}).execute()
    except Exception:   # noqa: BLE001 — MyST-NB executes it again and reports the error itself
        return path.stem, time.perf_counter() - start, False
    seconds = time.perf_counter() - start
    if error_outputs(executed):
        return path.stem, seconds, False
    with writer_lock(app.config.nb_execution_cache_path):
        store_execution(app.config.nb_execution_cache_path, source, executed, str(path.resolve()), seconds)
    return path.stem, seconds, True


def _execute_chapters(app, todo, jobs):
    from fdsc.paper.shared.cache import worker_threads

    start = time.perf_counter()
    with worker_threads(jobs), ThreadPoolExecutor(jobs) as pool:
        done = list(pool.map(lambda p: _execute_one(app, p), _longest_first(app, todo)))
    failed = [stem for stem, _s, stored in done if not stored]
    print(f"result_cache: {len(done) - len(failed)} chapters executed, {jobs} at a time, in "
          f"{time.perf_counter() - start:.0f} s"
          + (f"; left to MyST-NB (a cell failed): {', '.join(failed)}" if failed else ""))


def setup(app):
    app.connect("builder-inited", _use_results_folder)
    app.connect("builder-inited", _precompute_record, priority=900)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
