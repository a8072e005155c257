"""The chapters executed by the tests (nbmake) are not executed again by the book build.

With ``--nbmake`` (in pytest's ``addopts``), nbmake's execution of a notebook is wrapped by
:func:`notebook_cache.caching_execute` (``book/_ext/notebook_cache.py``): every chapter that runs
without error is stored in the notebook cache that ``jupyter-book build book`` reads, keyed by the
sources of ``fdsc``. The tests of one pytest session and the kernels it starts share a fresh
folder of chapter results (``FDSC_CACHE_DIR``, as in a book build), so that the reproduction
record, the sweeps and the other chapter results are computed once per session, whether a unit
test or a chapter asks first; the folder is deleted when the session ends. With pytest-xdist
(``-n auto`` in ``addopts``) the workers share the controller's folder, and a per-key lock
(:func:`fdsc.paper.shared.cache.cached`) makes a worker that needs a result another one is computing
wait for it instead of computing it again; each worker's BLAS and numba threads are capped so
that the workers share the CPUs. If ``FDSC_CACHE_DIR`` is set when pytest starts, that
folder is used and kept (``.ci/run`` shares it with ``python -m fdsc reproduce``; the keys hash
the sources, so a folder kept from older code never answers for new code). Tests of the cache
itself set or unset the variable with ``monkeypatch``.
"""

import contextlib
import os
import shutil
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent / "book" / "_ext"))

import notebook_cache  # noqa: E402
import pytest  # noqa: E402

from fdsc.paper.shared.cache import CACHE_ENV, worker_threads  # noqa: E402

_RESULTS_KEY = "fdsc_results"


def pytest_configure(config):
    worker = getattr(config, "workerinput", None)      # set in a worker of pytest-xdist
    previous = os.environ.get(CACHE_ENV)
    if worker is not None and worker.get(_RESULTS_KEY):
        results = worker[_RESULTS_KEY]                 # the session's folder (the controller's)
        own = False
    elif previous:
        results = previous                             # a folder the caller chose: used and kept
        own = False
    else:
        results = tempfile.mkdtemp(prefix="fdsc-results-")
        own = True
    config._fdsc_results = results
    os.environ[CACHE_ENV] = results

    def restore_env():
        if previous is None:
            os.environ.pop(CACHE_ENV, None)
        else:
            os.environ[CACHE_ENV] = previous
        if own:
            shutil.rmtree(results, ignore_errors=True)

    config.add_cleanup(restore_env)
    processes = getattr(config.option, "numprocesses", None)
    if worker is None and isinstance(processes, int) and processes > 1:
        # the workers of pytest-xdist (and the kernels they start) share the CPUs: cap each
        # one's BLAS and numba threads (set before the workers start; restored at the end)
        caps = contextlib.ExitStack()
        caps.enter_context(worker_threads(processes))
        config.add_cleanup(caps.close)
    if not getattr(config.option, "nbmake", False):
        return
    from nbmake.nb_run import NotebookRun

    original = NotebookRun.execute
    NotebookRun.execute = notebook_cache.caching_execute(original, kernel_env={CACHE_ENV: results})
    config.add_cleanup(lambda: setattr(NotebookRun, "execute", original))


@pytest.hookimpl(optionalhook=True)
def pytest_configure_node(node):
    """pytest-xdist: every worker uses the controller's folder of chapter results."""
    node.workerinput[_RESULTS_KEY] = node.config._fdsc_results
