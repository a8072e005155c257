"""Chapter 'environment': versions of the build.
"""


__all__ = [
    "build_commit",
    "environment",
]


def environment():
    """Versions of Python and of the numerical packages (for the record and the book)."""
    import platform
    from importlib.metadata import PackageNotFoundError, version

    pkgs = {}
    for name in ("numpy", "scipy", "cvxpy", "clarabel", "control", "matplotlib", "numba",
                 "jupyter-book", "myst-nb", "playwright"):
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

    root = Path(__file__).resolve().parents[2] if root is None else Path(root)

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
