"""The package's shape: no module over 600 lines, and no import circle anywhere in ``fdsc/``.

The import graph is read from the sources (every ``import`` and ``from … import``, at module
level or inside a function, relative imports resolved), so an import deferred into a function
to dodge a circle at import time still counts as an edge: what two modules share belongs in a
third module that both import.
"""

import pytest
from import_graph import ROOT, circles, import_graph

MAX_LINES = 600
MODULES = sorted(p for p in ROOT.rglob("*.py") if "__pycache__" not in p.parts)


def test_the_graph_sees_the_whole_package():
    graph = import_graph()
    assert len(graph) == len(MODULES) >= 100
    # a function-level import is an edge too (the record imports every chapter it sums)
    assert "fdsc.paper.reproduced.passive_controllers" in graph["fdsc.paper.record"]
    assert "fdsc._blocks" in graph["fdsc.prepared"]


def test_the_circle_finder_finds_circles(tmp_path):
    # a throwaway package: a -> b -> c -> a (one of them deferred into a function), d alone
    pkg = tmp_path / "pkg"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "a.py").write_text("from .b import f\n")
    (pkg / "b.py").write_text("def f():\n    from pkg import c\n")
    (pkg / "c.py").write_text("import pkg.a\n")
    (pkg / "d.py").write_text("from . import a\n")
    assert circles(import_graph(pkg)) == [["pkg.a", "pkg.b", "pkg.c"]]
    (pkg / "c.py").write_text("")
    assert circles(import_graph(pkg)) == []


def test_no_import_circle_in_the_package():
    assert circles(import_graph()) == []


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(ROOT)))
def test_every_module_is_at_most_600_lines(path):
    n = len(path.read_text(encoding="utf-8").splitlines())
    assert n <= MAX_LINES, f"{path.relative_to(ROOT)} has {n} lines (at most {MAX_LINES})"
