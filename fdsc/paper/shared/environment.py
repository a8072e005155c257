"""Chapter 'environment': versions of the build.
"""


__all__ = [
    "build_commit",
    "environment",
    "COLD_TIMES_FILE",
    "measure_cold_times",
    "cold_times",
]


def environment():
    """Versions of Python and of the numerical packages (for the record and the book)."""
    import platform
    from importlib.metadata import PackageNotFoundError, version

    pkgs = {}
    for name in ("numpy", "scipy", "cvxpy", "clarabel", "control", "matplotlib", "numba",
                 "jupyter-book", "myst-nb", "playwright", "dask", "distributed"):
        try:
            pkgs[name] = version(name)
        except PackageNotFoundError:
            pkgs[name] = None
    return {"python": platform.python_version(), "platform": platform.platform(),
            "packages": pkgs}


def build_commit(root=None):
    """The git commit of the tree the book is built from, and whether the tree was dirty.

    Parameters
    ----------
    root : path-like, optional
        A folder in the repository (default: the one holding this package).

    Returns
    -------
    str
        ``"<full hash>"``, ``"<full hash> (with uncommitted changes)"``, or
        ``"not a git checkout"`` when git or the repository is absent (never raises).

    Examples
    --------
    >>> build_commit("/") in ("not a git checkout",) or len(build_commit("/")) >= 40
    True
    """
    import subprocess
    from pathlib import Path

    root = Path(__file__).resolve().parents[3] if root is None else Path(root)

    def git(*args):
        return subprocess.run(["git", "-C", str(root), *args], capture_output=True, text=True,
                              timeout=20, check=True).stdout.strip()

    try:
        head = git("rev-parse", "HEAD")
        dirty = bool(git("status", "--porcelain", "--untracked-files=no"))
    except (OSError, subprocess.SubprocessError):
        return "not a git checkout"
    if not head:
        return "not a git checkout"
    return f"{head} (with uncommitted changes)" if dirty else head


#: Where the measured cold execution times of the chapters are kept (:func:`measure_cold_times`),
#: relative to the repository: beside the book, outside the package, so that storing a
#: measurement does not change the sources' fingerprint it was measured for.
COLD_TIMES_FILE = "book/data/cold_times.json"


def _book_chapters(book):
    """The chapters of the book's table of contents, in order (file stems)."""
    import re
    from pathlib import Path

    toc = (Path(book) / "_toc.yml").read_text(encoding="utf-8")
    return [m for m in re.findall(r"file:\s*([\w/.-]+)", toc)
            if (Path(book) / f"{m}.ipynb").is_file()]


def _host():
    import os
    import platform

    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    return {"cpus": os.cpu_count(), "load_1min": round(load, 2), "machine": platform.machine(),
            "processor": platform.processor() or platform.machine()}


def measure_cold_times(book, out, *, timeout: float = 1800.0):
    """Execute every chapter notebook of ``book`` cold and write the times to ``out`` (JSON).

    Each chapter runs alone, in a fresh kernel, with an empty results folder of its own
    (``FDSC_CACHE_DIR``), so that it computes everything it shows and reads nothing another
    chapter computed: the time a reader pays to run that chapter alone. Numba's compiled loops
    are read from numba's own disk cache if it holds them (their first compilation, a few seconds
    per loop on a fresh install, is not included once any run has compiled them).

    Parameters
    ----------
    book : path-like
        The book's folder (with ``_toc.yml``).
    out : path-like
        The JSON file to write: ``{"commit", "fingerprint", "date", "host", "chapters":
        {stem: seconds}}`` (``fingerprint``: :func:`fdsc.paper.shared.cache.fingerprint` of the code
        measured).
    timeout : float, optional
        Seconds allowed per cell.

    Returns
    -------
    dict
        What was written.
    """
    import datetime
    import json
    import os
    import tempfile
    import time
    from pathlib import Path

    import nbformat
    from nbclient import NotebookClient

    book = Path(book)
    host, times = _host(), {}
    saved = os.environ.get("FDSC_CACHE_DIR")
    try:
        for stem in _book_chapters(book):
            nb = nbformat.read(book / f"{stem}.ipynb", as_version=4)
            with tempfile.TemporaryDirectory(prefix="fdsc-cold-") as folder:
                os.environ["FDSC_CACHE_DIR"] = folder
                t0 = time.perf_counter()
                NotebookClient(nb, timeout=timeout, kernel_name="python3",
                               resources={"metadata": {"path": str(book)}}).execute()
                times[stem] = round(time.perf_counter() - t0, 2)
            print(f"{stem:<28} {times[stem]:8.1f} s", flush=True)
    finally:
        if saved is None:
            os.environ.pop("FDSC_CACHE_DIR", None)
        else:
            os.environ["FDSC_CACHE_DIR"] = saved
    from fdsc.paper.shared.cache import fingerprint

    result = {"commit": build_commit(), "fingerprint": fingerprint(),
              "date": datetime.date.today().isoformat(), "host": host, "chapters": times}
    Path(out).write_text(json.dumps(result, indent=1) + "\n", encoding="utf-8")
    return result


def cold_times():
    """The cold execution times last measured (:func:`measure_cold_times`), or None.

    Returns
    -------
    dict or None
        As written by :func:`measure_cold_times` (None outside a checkout of the repository).
    """
    import json
    from pathlib import Path

    path = Path(__file__).resolve().parents[3] / COLD_TIMES_FILE
    if not path.is_file():
        return None
    return json.loads(path.read_text(encoding="utf-8"))
