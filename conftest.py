"""The chapters executed by the tests (nbmake) are not executed again by the book build.

With ``--nbmake`` (in pytest's ``addopts``), nbmake's execution of a notebook is wrapped by
:func:`notebook_cache.caching_execute` (``book/_ext/notebook_cache.py``): every chapter that runs
without error is stored in the notebook cache that ``jupyter-book build book`` reads, keyed by the
sources of ``fdsc``. The kernels of one pytest session share a fresh folder of chapter results
(``FDSC_CACHE_DIR``, as in a book build), so that the introduction's reproduction record and the
chapters compute each result once; the folder is deleted when the session ends.
"""

import shutil
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent / "book" / "_ext"))

import notebook_cache  # noqa: E402

from fdsc.paper.cache import CACHE_ENV  # noqa: E402


def pytest_configure(config):
    if not getattr(config.option, "nbmake", False):
        return
    from nbmake.nb_run import NotebookRun

    results = tempfile.mkdtemp(prefix="fdsc-results-")
    original = NotebookRun.execute
    NotebookRun.execute = notebook_cache.caching_execute(original, kernel_env={CACHE_ENV: results})

    def restore():
        NotebookRun.execute = original
        shutil.rmtree(results, ignore_errors=True)

    config.add_cleanup(restore)
