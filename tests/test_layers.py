"""The two layers: the library ``fdsc`` never imports ``fdsc.paper`` and holds no number of the paper."""

import ast
import importlib
import json
import subprocess
import sys
from pathlib import Path

import pytest

import fdsc
from fdsc.__main__ import commands, main

ROOT = Path(fdsc.__file__).resolve().parent
LIBRARY = sorted(p for p in ROOT.glob("*.py"))
DATA = sorted((ROOT / "paper" / "data").glob("*.json"))


def _imports(path):
    """Every module name a file imports (absolute, with relative imports resolved)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    names = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names += [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = "fdsc" if node.level == 1 else ""
            mod = ".".join(x for x in (base, node.module or "") if x)
            names.append(mod)
            names += [f"{mod}.{a.name}" for a in node.names]
        elif isinstance(node, ast.Call) and any(
                isinstance(a, ast.Constant) and isinstance(a.value, str) and "paper" in a.value
                for a in node.args):
            names.append(f"<call with a string naming 'paper' at line {node.lineno}>")
    return names


def _printed_numbers():
    """Numbers of the paper's data with at least three significant digits (e.g. 15.0897, 0.3443)."""
    found = set()

    def walk(v):
        if isinstance(v, dict):
            for x in v.values():
                walk(x)
        elif isinstance(v, list):
            for x in v:
                walk(x)
        elif isinstance(v, float | int) and not isinstance(v, bool):
            digits = repr(abs(float(v))).replace(".", "").lstrip("0").rstrip("0")
            if len(digits) >= 3:
                found.add(v)

    for path in DATA:
        walk(json.loads(path.read_text(encoding="utf-8")))
    return found


def test_the_library_finds_its_modules_and_the_paper_data():
    # guards the two checks below against scanning nothing
    assert len(LIBRARY) >= 15 and {p.name for p in LIBRARY} >= {"lmi.py", "design.py", "simulate.py"}
    assert len(_printed_numbers()) >= 20


@pytest.mark.parametrize("path", LIBRARY, ids=[p.name for p in LIBRARY])
def test_library_module_does_not_import_the_paper_layer(path):
    bad = [n for n in _imports(path) if "paper" in n]
    assert bad == [], f"{path.name} imports the paper layer: {bad}"


@pytest.mark.parametrize("path", LIBRARY, ids=[p.name for p in LIBRARY])
def test_library_module_holds_no_printed_number(path):
    text = path.read_text(encoding="utf-8")
    consts = {n.value for n in ast.walk(ast.parse(text))
              if isinstance(n, ast.Constant) and isinstance(n.value, float | int)}
    printed = _printed_numbers()
    as_literal = sorted(consts & printed)
    in_text = sorted(v for v in printed if isinstance(v, float) and repr(v) in text)
    assert as_literal == [] and in_text == [], f"{path.name} holds paper numbers: {as_literal or in_text}"


def test_importing_the_whole_library_loads_nothing_of_the_paper_layer():
    code = ("import importlib, pkgutil, sys, fdsc\n"
            "for m in pkgutil.iter_modules(fdsc.__path__):\n"
            "    if m.name not in ('paper', '__main__'):\n"
            "        importlib.import_module('fdsc.' + m.name)\n"
            "print(sorted(k for k in sys.modules if k.startswith('fdsc.paper')))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


def test_a_simulation_loads_neither_cvxpy_nor_the_scipy_it_does_not_use():
    # fdsc's names are imported on first use: simulating the paper's loops (the benchmark's
    # memory run) must not load CVXPY, its solvers or scipy.signal/optimize/integrate
    heavy = ("cvxpy", "clarabel", "control", "matplotlib", "scipy.signal", "scipy.optimize",
             "scipy.integrate")
    code = ("import sys, fdsc\n"
            "from fdsc import Sinusoids, simulate_stream\n"
            "from fdsc.paper.shared.data import paper_modes\n"
            "pm = paper_modes()\n"
            "r = simulate_stream(pm['modes'], Sinusoids([1.0], [2.0]), 0.1, 1e-3, law_bands=pm['bands'], "
            "law_Q=pm['Q'])\n"
            f"print(sorted(m for m in {heavy!r} if m in sys.modules))\n"
            "fdsc.synthesize\n"
            "print('cvxpy' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split("\n")[:2] == ["[]", "True"]


def test_every_public_name_resolves_and_unknown_names_raise():
    for name in fdsc.__all__:
        assert getattr(fdsc, name) is getattr(importlib.import_module("fdsc." + fdsc._WHERE[name]), name)
    assert set(fdsc.__all__) <= set(dir(fdsc)) and set(fdsc.__all__) == set(fdsc._WHERE)
    assert fdsc.stream.simulate_stream is fdsc.simulate_stream
    with pytest.raises(AttributeError, match="module 'fdsc' has no attribute 'no_such_name'"):
        getattr(fdsc, "no_such_name")  # noqa: B009 (the attribute access is what is tested)


def test_the_command_line_finds_the_paper_command_through_entry_points():
    assert "reproduce" in commands()
    assert commands()["reproduce"].value == "fdsc.paper.cli:reproduce"


@pytest.mark.parametrize(("argv", "status", "stream", "text"), [
    ([], 2, "out", "commands: adaptive-rung, cold-times, disturbance-law, information, observer-rung, part-two, "
     "reproduce, variant-laws"),
    (["--help"], 0, "out", "usage: python -m fdsc COMMAND"),
    (["frobnicate"], 2, "err", "unknown command 'frobnicate'"),
])
def test_command_line_without_a_known_command(argv, status, stream, text, capsys):
    assert main(argv) == status
    captured = capsys.readouterr()
    assert text in (captured.out if stream == "out" else captured.err)
