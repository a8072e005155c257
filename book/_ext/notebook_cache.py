"""One execution of each chapter per run, shared by the tests and the book build.

``python -m pytest`` executes every chapter (nbmake), and ``jupyter-book build book`` would execute
each one again. Instead, the test run stores every notebook it executed without error in a
jupyter-cache (``conftest.py`` wraps nbmake's execution with :func:`caching_execute`), and
the book build (``execute_notebooks: cache`` in ``_config.yml``) takes a chapter's outputs from
there when it finds them, and executes and stores the others itself. The other way round, a test
run that finds a chapter in the cache, executed without error for the same sources, does not
execute it again: ``make book`` then ``make test`` computes each chapter once.

Jupyter-cache matches a notebook by its code cells and kernelspec only, never by the code they
import. The cache therefore lives in a folder named after :func:`source_key`, a hash of everything
else the outputs depend on: the sources and data of ``fdsc`` (``*.py`` and ``*.json`` under
``fdsc/``; the top-level ``data`` is a link into it), the pinned ``requirements.txt``, the lock
``constraints.txt`` (the version of every installed package), the chapters' ``matplotlibrc``
and the Python version. After a
change of any of them both sides use a new, empty folder and delete the old ones, so the book
executes the chapters again instead of showing numbers of old code or of other packages.

Loaded by Sphinx as an extension (``sphinx.local_extensions`` in ``_config.yml``), it points
MyST-NB's ``nb_execution_cache_path`` at :func:`cache_path`; the changed value also makes Sphinx
read every page again, so an incremental build cannot keep pages of old code either. Both sides
check the key again after executing: if the sources changed meanwhile, the test side stores
nothing, and the build fails and deletes its cache folder and its environment (build again).
"""

import copy
import functools
import hashlib
import platform
import shutil
import time
from pathlib import Path

import nbformat
from jupyter_cache import get_cache
from jupyter_cache.base import CacheBundleIn
from nbmake.nb_result import NotebookResult
from sphinx.application import ENV_PICKLE_FILENAME
from sphinx.errors import ExtensionError

from fdsc.paper.shared.cache import environ, file_lock

#: The repository: ``fdsc/``, ``requirements.txt``, ``constraints.txt`` and ``book/`` are in it.
ROOT = Path(__file__).resolve().parents[2]
SOURCE_SUFFIXES = (".py", ".json")
KEY_LENGTH = 16  # hex digits of the key that name the cache folder


def source_key(root):
    """Hash of everything besides a notebook's code cells that its outputs depend on.

    Parameters
    ----------
    root : path-like
        The repository, holding ``fdsc/``, ``requirements.txt`` and (optionally) ``constraints.txt``.

    Returns
    -------
    str
        SHA-256 hex digest over the relative path and contents of every ``*.py`` and ``*.json``
        file under ``fdsc/`` (``__pycache__`` skipped), of ``requirements.txt`` and of the lock
        ``constraints.txt`` if there is one, in sorted order, and the Python version.

    Raises
    ------
    FileNotFoundError
        If ``root`` holds no ``fdsc`` folder or no ``requirements.txt``.

    Examples
    --------
    >>> len(source_key(ROOT))
    64
    """
    root = Path(root)
    package = root / "fdsc"
    if not package.is_dir():
        raise FileNotFoundError(f"notebook_cache: no fdsc package at {package}")
    files = [p for p in package.rglob("*")
             if p.suffix in SOURCE_SUFFIXES and p.is_file() and "__pycache__" not in p.parts]
    files.append(root / "requirements.txt")
    # the lock: a package's version changes a chapter's outputs as much as a change of fdsc does
    files += [p for p in [root / "constraints.txt"] if p.is_file()]
    # data the chapters read that is not in the package: the measured cold execution times and
    # the full study of the law on the disturbance estimate
    files += [p for p in [root / "book" / "data" / "cold_times.json",
                          root / "book" / "data" / "disturbance_law_full.json"] if p.is_file()]
    # and the chapters' matplotlib settings (their figures' resolution)
    files += [p for p in [root / "book" / "matplotlibrc"] if p.is_file()]
    h = hashlib.sha256()
    for path in sorted(files, key=lambda p: p.relative_to(root).as_posix()):
        data = path.read_bytes()
        # name and length first, so that no two different trees give the same byte stream
        h.update(f"{path.relative_to(root).as_posix()}\0{len(data)}\0".encode())
        h.update(data)
    h.update(f"python {platform.python_version()}".encode())
    return h.hexdigest()


def cache_path(root, key=None):
    """Folder of the jupyter-cache for the current sources: ``book/_build/.jupyter_cache/<key>``.

    Parameters
    ----------
    root : path-like
        The repository.
    key : str, optional
        A :func:`source_key` already computed (default: compute it now).

    Returns
    -------
    pathlib.Path
        The folder, named after the first 16 hex digits of the key (it need not exist yet).
    """
    key = source_key(root) if key is None else key
    return Path(root) / "book" / "_build" / ".jupyter_cache" / key[:KEY_LENGTH]


def prune_other_keys(root, key):
    """Delete the cache folders of other sources, which nothing can match any more.

    Parameters
    ----------
    root : path-like
        The repository.
    key : str
        The current :func:`source_key`; its folder is kept.

    Returns
    -------
    list of pathlib.Path
        What was deleted (everything in ``book/_build/.jupyter_cache`` but the current folder).
    """
    keep = cache_path(root, key)
    parent = keep.parent
    removed = [p for p in sorted(parent.iterdir()) if p != keep] if parent.is_dir() else []
    for path in removed:
        if path.is_dir() and not path.is_symlink():
            shutil.rmtree(path)
        else:
            path.unlink()
    return removed


def error_outputs(nb):
    """Indices of the code cells of ``nb`` that hold an error output.

    Parameters
    ----------
    nb : nbformat.NotebookNode
        An executed notebook.

    Returns
    -------
    list of int
        Cell indices (empty for a notebook that ran without error).
    """
    return [i for i, cell in enumerate(nb.cells) if cell.cell_type == "code"
            and any(out.get("output_type") == "error" for out in cell.get("outputs", []))]


def store_execution(folder, source, executed, uri, seconds):
    """Store the outputs of a successful execution in the jupyter-cache at ``folder``.

    The stored notebook is ``source`` with the outputs, execution counts and language info of
    ``executed``: jupyter-cache hashes code cells with their metadata, and an executor may add
    metadata (nbmake records timings in every cell), which would keep MyST-NB from matching it.

    Parameters
    ----------
    folder : path-like
        The cache folder (:func:`cache_path`); created if missing.
    source : nbformat.NotebookNode
        The notebook as stored in the book (version 4), read before the execution.
    executed : nbformat.NotebookNode
        The same notebook after its execution.
    uri : str
        Where the notebook lives (recorded in the cache, not used for matching).
    seconds : float
        How long the execution took; MyST-NB shows it in ``{nb-exec-table}``.

    Returns
    -------
    jupyter_cache.cache.db.NbCacheRecord
        The cache record (a notebook already cached with the same code is replaced).

    Raises
    ------
    ValueError
        If ``executed`` holds an error output, or its code cells are not those of ``source``.
    """
    failed = error_outputs(executed)
    if failed:
        raise ValueError(f"{uri}: cells {failed} failed; a failed execution is never cached")
    nb = copy.deepcopy(source)
    cells = [c for c in nb.cells if c.cell_type == "code"]
    ran = [c for c in executed.cells if c.cell_type == "code"]
    if [c.source for c in cells] != [c.source for c in ran]:
        raise ValueError(f"{uri}: the executed notebook's code cells are not those of its source")
    for cell, out in zip(cells, ran, strict=True):
        cell.outputs = out.outputs
        cell.execution_count = out.execution_count
    for name in ("language_info", "widgets"):
        if name in executed.metadata:
            nb.metadata[name] = executed.metadata[name]
    bundle = CacheBundleIn(nb, uri, data={"execution_seconds": seconds})
    return get_cache(str(folder)).cache_notebook_bundle(bundle, check_validity=False, overwrite=True)


def cached_execution(folder, source):
    """The executed notebook stored for ``source`` in the jupyter-cache at ``folder``, or None.

    Parameters
    ----------
    folder : path-like
        The cache folder of the current sources (:func:`cache_path`).
    source : nbformat.NotebookNode
        The notebook as stored in the book.

    Returns
    -------
    nbformat.NotebookNode or None
        ``source`` with the stored outputs merged in, if the folder holds an execution of the
        same code cells without an error output (only such executions are ever stored: by
        :func:`store_execution` and by a book build, which fails on any cell error); None if
        there is none.
    """
    folder = Path(folder)
    if not (folder / "global.db").is_file():
        return None
    try:
        _, merged = get_cache(str(folder)).merge_match_into_notebook(copy.deepcopy(source))
    except KeyError:
        return None
    return None if error_outputs(merged) else merged


def writer_lock(folder):
    """The lock that lets one writer at a time store in the notebook caches beside ``folder``
    (the workers of ``pytest -n`` and the book build's parallel chapters store concurrently):
    ``.jupyter_cache.lock`` in the build folder that holds ``.jupyter_cache/<key>``.

    Parameters
    ----------
    folder : path-like
        A cache folder (:func:`cache_path`).

    Returns
    -------
    context manager
        :func:`fdsc.paper.shared.cache.file_lock` on that file (its folder made if missing).
    """
    lock = Path(folder).parent.parent / ".jupyter_cache.lock"
    lock.parent.mkdir(parents=True, exist_ok=True)
    return file_lock(lock)


def caching_execute(execute, root=ROOT, kernel_env=None):
    """Wrap nbmake's ``NotebookRun.execute`` so that every successful execution is cached.

    Parameters
    ----------
    execute : callable
        ``nbmake.nb_run.NotebookRun.execute``: takes the run (``filename``, ``kernel``,
        ``find_import_errors``) and returns a result with ``nb`` and ``error``.
    root : path-like, optional
        The repository whose sources key the cache (default: this one).
    kernel_env : dict of str to str, optional
        Environment variables set while the kernel starts (and restored afterwards).

    Returns
    -------
    callable
        The wrapped method, returning what ``execute`` returns. A notebook that
        :func:`cache_path` already holds, executed without error for the current sources (by
        the book build or an earlier test run), is not executed again: its stored execution is
        returned (:func:`cached_execution`), so ``make book`` then ``make test`` computes each
        chapter once. Otherwise it executes and stores the executed notebook in
        :func:`cache_path` (deleting the folders of other sources) only if the execution raised
        no error, no cell holds an error output, the notebook ran in its own kernel, nbmake was
        not only looking for import errors, and the sources did not change while it ran.
    """
    env = dict(kernel_env or {})

    @functools.wraps(execute)
    def run_and_store(run):
        source = nbformat.read(str(run.filename), as_version=4)
        key = source_key(root)
        own_kernel = run.kernel in (None, source.metadata.get("kernelspec", {}).get("name"))
        if own_kernel and not run.find_import_errors:
            done = cached_execution(cache_path(root, key), source)
            if done is not None:
                # executed without error for these very sources (by a book build or an earlier
                # test run): the chapter is not computed a second time
                return NotebookResult(nb=done, error=None)
        start = time.perf_counter()
        with environ(env):
            result = execute(run)
        seconds = time.perf_counter() - start
        if (result.error is None and not error_outputs(result.nb) and own_kernel
                and not run.find_import_errors and source_key(root) == key):
            folder = cache_path(root, key)
            with writer_lock(folder):
                prune_other_keys(root, key)
                store_execution(folder, source, result.nb, str(Path(run.filename).resolve()), seconds)
        return result

    return run_and_store


def _use_keyed_cache(app, config):
    key = source_key(ROOT)
    folder = cache_path(ROOT, key)
    if config.nb_execution_cache_path not in ("", str(folder)):
        raise ExtensionError("notebook_cache: remove execute.cache from _config.yml; the "
                             f"cache folder is set from the sources ({folder})")
    prune_other_keys(ROOT, key)
    config.nb_execution_cache_path = str(folder)


def _check_sources_unchanged(app, exception):
    folder = Path(app.config.nb_execution_cache_path)
    if exception is None and folder.name != source_key(ROOT)[:KEY_LENGTH]:
        # neither these outputs nor these pages may be reused, even if the code changes back
        shutil.rmtree(folder, ignore_errors=True)
        Path(app.doctreedir, ENV_PICKLE_FILENAME).unlink(missing_ok=True)
        raise ExtensionError("notebook_cache: fdsc, requirements.txt or constraints.txt changed "
                             "during the build, so its pages may mix results of old and new code; "
                             f"its notebook cache {folder} was deleted: build again")


def setup(app):
    app.connect("config-inited", _use_keyed_cache)
    app.connect("build-finished", _check_sources_unchanged)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
