"""A disk cache for the chapters' results, so that a book build computes each result once.

The book build sets ``FDSC_CACHE_DIR`` to a fresh folder inside its output
(``book/_ext/result_cache.py``), and a test session to a fresh temporary folder while nbmake
starts the kernels of the chapters (``conftest.py``); the kernels inherit it: the
landing page's findings and the report, built from the record, and the chapters then share one computation
of every result.
Without the variable (a user's session) nothing is cached, except inside :func:`shared_results`,
which :func:`fdsc.paper.record.reproduction_record` uses so that the command line computes each
result once too.

A cached value is keyed by the function, its arguments (plain values only: numbers, strings,
booleans, None and tuples of them; anything else bypasses the cache) and a fingerprint of the
fdsc sources, the paper's data and the versions of the numerical packages, so an edit to the
code never returns a stale value.
"""

import contextlib
import functools
import hashlib
import inspect
import os
import pickle
import shutil
import tempfile
from collections.abc import Callable
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path

try:
    import fcntl
except ImportError:        # not POSIX: no lock (concurrent processes may compute a value twice)
    fcntl = None

__all__ = ["cached", "fingerprint", "source_fingerprint", "study_fingerprint", "STUDY_MODULE",
           "STORED_OUTPUTS", "shared_results", "file_lock",
           "worker_threads", "environ",
           "CACHE_ENV", "THREAD_VARS"]

#: Environment variable naming the cache folder (unset: no caching).
CACHE_ENV = "FDSC_CACHE_DIR"
_PLAIN = (int, float, str, bool, type(None))
#: Environment variables that cap the threads of a process's BLAS (OpenBLAS, MKL, OpenMP) and of
#: numba's parallel loops; read when those libraries load, so set before a process starts.
THREAD_VARS = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "NUMBA_NUM_THREADS")


#: Files under fdsc/ that the full study writes (its stored outputs): left out of the sources'
#: fingerprint that the study records, so that writing them does not make the study look stale.
STORED_OUTPUTS = ("paper/data/fixed_in_advance.json",)


def _hash(with_outputs: bool) -> str:
    root = Path(__file__).resolve().parents[2]
    h = hashlib.sha256()
    for path in sorted(root.rglob("*")):
        if path.suffix in (".py", ".json") and "__pycache__" not in path.parts:
            rel = str(path.relative_to(root))
            if not with_outputs and rel in STORED_OUTPUTS:
                continue
            h.update(rel.encode())
            h.update(path.read_bytes())
    for pkg in ("numpy", "scipy", "cvxpy", "clarabel", "numba"):
        try:
            h.update(f"{pkg}={version(pkg)}".encode())
        except PackageNotFoundError:
            h.update(f"{pkg}=none".encode())
    return h.hexdigest()


@functools.cache
def fingerprint() -> str:
    """Hash of every fdsc source file, the paper's data and the numerical packages' versions.

    Computed once per process (the sources do not change under a running build). The results
    cache keys on it.

    Returns
    -------
    str
        SHA-256 hex digest (64 characters).

    Examples
    --------
    >>> len(fingerprint())
    64
    """
    return _hash(True)


#: The module of the stored full study: its fingerprint covers what it imports (:func:`study_fingerprint`).
STUDY_MODULE = "fdsc.paper.pays.disturbance_law_full"


@functools.cache
def study_fingerprint(module: str = STUDY_MODULE) -> str:
    """Hash of exactly what a stored study's numbers depend on: the source of every fdsc module
    ``module`` imports, directly or not (:func:`fdsc.paper.shared.imports.closure`: the whole
    library and the paper layer's modules on its import path), the package's data files but its
    stored outputs (:data:`STORED_OUTPUTS`), and the numerical packages' versions.

    A change of a chapter's prose, figures or record (modules the study does not import) leaves
    it unchanged, so the book can tell a stale study from one that is merely older than the
    build's commit.

    Parameters
    ----------
    module : str, optional

    Returns
    -------
    str
        SHA-256 hex digest.
    """
    from fdsc.paper.shared.imports import ROOT, closure, import_graph

    graph = import_graph(ROOT)
    files = {ROOT.parent / Path(*m.split(".")) for m in closure(graph, module)}
    paths = sorted([p.with_suffix(".py") if p.with_suffix(".py").is_file() else p / "__init__.py"
                    for p in files]
                   + [p for p in ROOT.rglob("*.json") if "__pycache__" not in p.parts
                      and str(p.relative_to(ROOT)) not in STORED_OUTPUTS])
    h = hashlib.sha256()
    for path in paths:
        h.update(str(path.relative_to(ROOT)).encode())
        h.update(path.read_bytes())
    for pkg in ("numpy", "scipy", "cvxpy", "clarabel", "numba"):
        try:
            h.update(f"{pkg}={version(pkg)}".encode())
        except PackageNotFoundError:
            h.update(f"{pkg}=none".encode())
    return h.hexdigest()


@functools.cache
def source_fingerprint() -> str:
    """:func:`fingerprint` without the study's stored outputs (:data:`STORED_OUTPUTS`): what a
    stored study records and what the book compares with to tell whether it is stale.

    Returns
    -------
    str
    """
    return _hash(False)


@contextlib.contextmanager
def file_lock(path):
    """Hold an exclusive POSIX ``flock`` on the file ``path`` (created if missing) in the block.

    Without ``fcntl`` (not POSIX) the block runs unlocked. :func:`cached` locks one file per key,
    so that processes sharing a cache folder (the workers of ``pytest -n``, the kernels they
    start, the processes of :func:`fdsc.paper.record.chapter_parts`) compute each value once:
    the others wait and read it. Locks of different keys are independent, and a cached function
    only calls cached functions of other keys, so waiting cannot deadlock.

    Parameters
    ----------
    path : path-like
        The lock file.
    """
    if fcntl is None:
        yield
        return
    with open(path, "a") as fh:
        fcntl.flock(fh, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(fh, fcntl.LOCK_UN)


def _plain(value):
    if isinstance(value, tuple):
        return all(_plain(v) for v in value)
    return isinstance(value, _PLAIN)


def cached(fn: Callable) -> Callable:
    """Decorate a result function so that its value is kept in ``$FDSC_CACHE_DIR`` if set.

    Parameters
    ----------
    fn : callable
        A deterministic function of plain arguments returning a picklable value.

    Returns
    -------
    callable
        The wrapped function (same signature; ``__wrapped__`` is the original). Without the
        environment variable, or with an argument that is not plain, it calls ``fn`` directly.

    Notes
    -----
    A value is stored as ``<module>.<qualname>-<key>.pickle``, the key hashing the
    :func:`fingerprint`, the function's name and its arguments (by name, defaults filled in:
    ``f()``, ``f(21)`` and ``f(n=21)`` share a value); it is written to a temporary
    file and renamed, so that a concurrent reader never sees half a file. A process computing a
    value holds a lock on its key, so that processes sharing the folder compute it once.

    Examples
    --------
    >>> @cached
    ... def square(x):
    ...     return x * x
    >>> square(3), square.__wrapped__(4)
    (9, 16)
    """
    signature = inspect.signature(fn)

    @functools.wraps(fn)
    def wrapper(*args, **kwargs):
        folder = os.environ.get(CACHE_ENV)
        if not folder:
            return fn(*args, **kwargs)
        # the key names every argument with its default filled in, so that f(), f(21) and
        # f(n=21) share one value
        try:
            bound = signature.bind(*args, **kwargs)
        except TypeError:
            return fn(*args, **kwargs)      # Python's own message, naming the function
        bound.apply_defaults()
        # a **kwargs parameter binds to a dict: key on its items
        values = tuple(tuple(sorted(v.items())) if isinstance(v, dict) else v
                       for v in bound.arguments.values())
        if not _plain(values):
            return fn(*args, **kwargs)
        key = hashlib.sha256(repr((fingerprint(), fn.__module__, fn.__qualname__,
                                   sorted(zip(bound.arguments, values, strict=True)))).encode()
                             ).hexdigest()[:24]
        path = Path(folder) / f"{fn.__module__}.{fn.__qualname__}-{key}.pickle"
        path.parent.mkdir(parents=True, exist_ok=True)
        with file_lock(path.with_name(path.name + ".lock")):
            # stored earlier, or by another process while this one waited for the lock
            if path.is_file():
                with path.open("rb") as fh:
                    return pickle.load(fh)
            value = fn(*args, **kwargs)
            # write then rename, so that a reader never sees half a file
            with tempfile.NamedTemporaryFile(dir=path.parent, delete=False) as fh:
                pickle.dump(value, fh)
            os.replace(fh.name, path)
        return value

    return wrapper


@contextlib.contextmanager
def shared_results():
    """Within the block, :func:`cached` results are shared: in ``$FDSC_CACHE_DIR`` if it is set,
    otherwise in a temporary folder deleted at the end of the block.

    Yields
    ------
    str
        The folder in use.

    Examples
    --------
    >>> import uuid
    >>> calls, token = [], uuid.uuid4().int     # a fresh argument: no result stored before
    >>> @cached
    ... def twice(x):
    ...     calls.append(x)
    ...     return 2 * x
    >>> with shared_results():
    ...     twice(token) == twice(token) == 2 * token
    True
    >>> len(calls)
    1
    """
    folder = os.environ.get(CACHE_ENV)
    if folder:
        yield folder
        return
    folder = tempfile.mkdtemp(prefix="fdsc-results-")
    os.environ[CACHE_ENV] = folder
    try:
        yield folder
    finally:
        os.environ.pop(CACHE_ENV, None)
        shutil.rmtree(folder, ignore_errors=True)


@contextlib.contextmanager
def worker_threads(processes: int):
    """Within the block, processes started inherit thread caps that share the CPUs among
    ``processes`` of them: each BLAS and numba gets ``max(1, CPUs // processes)`` threads.

    Without caps, every worker starts one BLAS thread and one numba thread per CPU, and on a
    machine with as many workers as CPUs those threads wait for each other in every small
    matrix product and parallel loop. A variable the caller has set is kept.

    Parameters
    ----------
    processes : int
        How many processes will run at once (≥ 1).

    Yields
    ------
    dict
        The caps in force, ``{variable: value}``.

    Examples
    --------
    >>> with worker_threads(os.cpu_count() or 1) as caps:
    ...     sorted(caps) == sorted(THREAD_VARS)
    True
    """
    if not isinstance(processes, int) or isinstance(processes, bool) or processes < 1:
        raise ValueError(f"processes must be a whole number ≥ 1, found {processes!r}")
    per = str(max(1, (os.cpu_count() or 1) // processes))
    caps = {v: os.environ.get(v) or per for v in THREAD_VARS}
    with environ(caps):
        yield caps


@contextlib.contextmanager
def environ(values: dict):
    """Within the block, the environment variables ``values`` are set; afterwards each is back
    to its earlier value (or unset).

    Parameters
    ----------
    values : dict
        ``{name: value}``, strings.

    Examples
    --------
    >>> with environ({"FDSC_EXAMPLE_VARIABLE": "1"}):
    ...     os.environ["FDSC_EXAMPLE_VARIABLE"]
    '1'
    >>> "FDSC_EXAMPLE_VARIABLE" in os.environ
    False
    """
    saved = {name: os.environ.get(name) for name in values}
    os.environ.update(values)
    try:
        yield
    finally:
        for name, old in saved.items():
            if old is None:
                os.environ.pop(name, None)
            else:
                os.environ[name] = old
