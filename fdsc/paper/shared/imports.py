"""The import graph of the fdsc package, read from its sources: what a stored result depends on.

Every ``import`` and ``from … import`` counts, at module level or inside a function (an import
deferred into a function is still a dependency), relative imports resolved. The package's
``__init__`` lists every library module under ``TYPE_CHECKING``, so a module that imports
``fdsc`` depends on the whole library (it may reach any of it through a lazy attribute), and on
the paper layer's modules only through their imports.
"""

from __future__ import annotations

import ast
from pathlib import Path

import fdsc

__all__ = ["ROOT", "module_name", "import_graph", "closure"]

#: The package's folder.
ROOT = Path(fdsc.__file__).resolve().parent


def module_name(path, root=ROOT) -> str:
    """``fdsc.x.y`` of a file under ``root`` (a package's ``__init__`` is the package).

    Parameters
    ----------
    path : pathlib.Path
    root : pathlib.Path, optional

    Returns
    -------
    str
    """
    parts = list(Path(path).relative_to(Path(root).parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def import_graph(root=ROOT) -> dict:
    """``{module: set of modules of the package it imports}`` for every ``*.py`` under ``root``.

    Parameters
    ----------
    root : pathlib.Path, optional

    Returns
    -------
    dict
    """
    root = Path(root)
    paths = {module_name(p, root): p for p in root.rglob("*.py") if "__pycache__" not in p.parts}
    graph = {}
    for name, path in paths.items():
        package = name if path.name == "__init__.py" else name.rpartition(".")[0]
        found = set()
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                found |= {a.name for a in node.names if a.name in paths}
            elif isinstance(node, ast.ImportFrom):
                if node.level:
                    base = package.split(".")[:len(package.split(".")) - node.level + 1]
                    mod = ".".join(base + ([node.module] if node.module else []))
                else:
                    mod = node.module
                for a in node.names:
                    if f"{mod}.{a.name}" in paths:      # a submodule: from pkg import module
                        found.add(f"{mod}.{a.name}")
                    elif mod in paths:
                        found.add(mod)
        found.discard(name)
        graph[name] = found
    return graph


def closure(graph: dict, start: str) -> set:
    """Every module ``start`` imports, directly or not, and ``start`` itself.

    Parameters
    ----------
    graph : dict
        :func:`import_graph`.
    start : str

    Returns
    -------
    set of str

    Raises
    ------
    KeyError
        If ``start`` is not a module of the graph.
    """
    if start not in graph:
        raise KeyError(f"start: {start!r} is not a module of the package")
    seen, todo = {start}, [start]
    while todo:
        for m in graph[todo.pop()]:
            if m not in seen:
                seen.add(m)
                todo.append(m)
    return seen
