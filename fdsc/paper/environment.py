"""Chapter 'environment': versions of the build.
"""


__all__ = [
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
