"""Sphinx extension: the chapters of one build share one computation of every result.

At the start of a build it empties ``<outdir>/../.fdsc-cache`` and sets ``FDSC_CACHE_DIR`` to
it; the kernels that execute the notebooks inherit the variable, and
:func:`fdsc.paper.shared.cache.cached` keeps each chapter result there. The landing page's findings
and the report (built from the whole record) and the chapters then reuse the same values instead of
computing them again. A fresh folder per build keeps builds independent of each other.
"""

import os
import shutil
from pathlib import Path

from fdsc.paper.shared.cache import CACHE_ENV


def _use_fresh_cache(app):
    folder = Path(app.outdir).parent / ".fdsc-cache"
    shutil.rmtree(folder, ignore_errors=True)
    folder.mkdir(parents=True)
    os.environ[CACHE_ENV] = str(folder)


def setup(app):
    app.connect("builder-inited", _use_fresh_cache)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
