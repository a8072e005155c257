"""Sphinx extension: the chapters of one build share one computation of every result.

At the start of a build it sets ``FDSC_CACHE_DIR`` for the kernels that execute the notebooks, and
:func:`fdsc.paper.shared.cache.cached` keeps each chapter result there: the landing page's
findings and the report (built from the whole record) and the chapters then reuse the same
values instead of computing them again. If ``FDSC_CACHE_DIR`` is already set (``make book``,
``make test`` and ``.ci/run`` set it to ``book/_build/.fdsc-results``), that folder is used and
kept, so that a build and a test run share one computation of each result whichever runs first;
its keys hash the sources, so results of other code are never read. Otherwise the build uses a
fresh folder ``<outdir>/../.fdsc-cache`` of its own.
"""

import os
import shutil
from pathlib import Path

from fdsc.paper.shared.cache import CACHE_ENV


def _use_results_folder(app):
    if os.environ.get(CACHE_ENV):
        Path(os.environ[CACHE_ENV]).mkdir(parents=True, exist_ok=True)
        return
    folder = Path(app.outdir).parent / ".fdsc-cache"
    shutil.rmtree(folder, ignore_errors=True)
    folder.mkdir(parents=True)
    os.environ[CACHE_ENV] = str(folder)


def setup(app):
    app.connect("builder-inited", _use_results_folder)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
