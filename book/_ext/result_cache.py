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
processes: the chapters, executed one after the other by the build, then read their results
instead of computing them one chapter at a time on one core.
"""

import os
import shutil
import time
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

    start = time.perf_counter()
    reproduction_record()
    print(f"result_cache: the reproduction record computed on {record_jobs()} processes in "
          f"{time.perf_counter() - start:.0f} s before executing {len(todo)} chapters")


def setup(app):
    app.connect("builder-inited", _use_results_folder)
    app.connect("builder-inited", _precompute_record, priority=900)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
