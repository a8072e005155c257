"""The chapters executed by the tests (nbmake) are not executed again by the book build.

With ``--nbmake`` (in pytest's ``addopts``), nbmake's execution of a notebook is wrapped by
:func:`notebook_cache.caching_execute` (``book/_ext/notebook_cache.py``): every chapter that runs
without error is stored in the notebook cache that ``jupyter-book build book`` reads, keyed by the
sources of ``fdsc``. The tests of one pytest session and the kernels it starts share a fresh
folder of chapter results (``FDSC_CACHE_DIR``, as in a book build), so that the reproduction
record, the sweeps and the other chapter results are computed once per session, whether a unit
test or a chapter asks first; the folder is deleted when the session ends. Tests of the cache
itself set or unset the variable with ``monkeypatch``.
"""

import os
import shutil
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent / "book" / "_ext"))

import notebook_cache  # noqa: E402

from fdsc.paper.cache import CACHE_ENV  # noqa: E402


def pytest_configure(config):
    results = tempfile.mkdtemp(prefix="fdsc-results-")
    previous = os.environ.get(CACHE_ENV)
    os.environ[CACHE_ENV] = results

    def restore_env():
        if previous is None:
            os.environ.pop(CACHE_ENV, None)
        else:
            os.environ[CACHE_ENV] = previous
        shutil.rmtree(results, ignore_errors=True)

    config.add_cleanup(restore_env)
    if not getattr(config.option, "nbmake", False):
        return
    from nbmake.nb_run import NotebookRun

    original = NotebookRun.execute
    NotebookRun.execute = notebook_cache.caching_execute(original, kernel_env={CACHE_ENV: results})
    config.add_cleanup(lambda: setattr(NotebookRun, "execute", original))
