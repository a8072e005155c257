"""The lock ``constraints.txt``: every package the tests and the book install, at one exact version.

``make``, ``.ci/run`` and the README install ``pip install -r requirements.txt -c constraints.txt``,
and ``make lock`` regenerates the file. The lock must agree with the pins of ``requirements.txt``,
hold nothing but ``name==version`` lines that PyPI can serve, and be complete: every package that
requirements.txt pulls in (read from the installed metadata) is in it, at the version installed.
"""

import importlib.metadata as md
import re
import sys
from pathlib import Path

import pytest
from packaging.markers import default_environment
from packaging.requirements import Requirement
from packaging.utils import canonicalize_name

ROOT = Path(__file__).resolve().parent.parent
LOCK = ROOT / "constraints.txt"
REQUIREMENTS = ROOT / "requirements.txt"
PIN = re.compile(r"^([A-Za-z0-9][A-Za-z0-9._-]*)==([A-Za-z0-9.+!_-]+)$")

sys.path.insert(0, str(ROOT / "book" / "_ext"))

import notebook_cache as nc  # noqa: E402


def entries(path):
    """The requirement lines of ``path`` (comments and blank lines dropped), in order."""
    lines = (line.split(" #", 1)[0].strip() for line in path.read_text(encoding="utf-8").splitlines())
    return [line for line in lines if line and not line.startswith("#")]


def lock():
    """The lock as {canonical name: version}."""
    return {canonicalize_name(PIN.match(e)[1]): PIN.match(e)[2] for e in entries(LOCK)}


def requirements():
    """The requirements of requirements.txt (``-e .`` and other options left out)."""
    return [Requirement(e) for e in entries(REQUIREMENTS) if not e.startswith("-")]


def test_every_line_is_an_exact_pin_of_a_registry_package():
    lines = entries(LOCK)
    assert len(lines) > 100
    for line in lines:
        assert PIN.match(line), f"not a name==version line: {line!r}"
        assert not re.search(r"@|file:|://|^-", line), f"not from the registry: {line!r}"
    assert "fdsc" not in lock(), "the lock pins the project itself (freeze with --exclude-editable)"


def test_no_package_twice():
    names = [canonicalize_name(PIN.match(e)[1]) for e in entries(LOCK)]
    assert sorted(names) == sorted(set(names)), "a package appears twice in the lock"


def test_the_lock_agrees_with_requirements_txt():
    locked = lock()
    reqs = requirements()
    assert len(reqs) >= 15
    for req in reqs:
        name = canonicalize_name(req.name)
        assert name in locked, f"{req.name} is in requirements.txt but not in the lock: run make lock"
        assert req.specifier.contains(locked[name], prereleases=True), (
            f"requirements.txt wants {req}, the lock has {locked[name]}: run make lock")
        pins = [s.version for s in req.specifier if s.operator == "=="]
        assert pins in ([], [locked[name]])


def test_the_lock_says_how_to_regenerate_it():
    lines = LOCK.read_text(encoding="utf-8").splitlines()
    header = "\n".join(lines[:next(i for i, line in enumerate(lines) if not line.startswith("#"))])
    assert "make lock" in header
    makefile = (ROOT / "Makefile").read_text(encoding="utf-8")
    assert re.search(r"^lock:", makefile, re.M)
    # the installs use it, and a change of it installs again
    assert re.search(r"^\$\(STAMP\):.*\bconstraints\.txt\b", makefile, re.M)
    assert "-r requirements.txt -c constraints.txt" in makefile
    assert "constraints.txt" in (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert "pip install -r requirements.txt -c constraints.txt" in readme
    assert "make lock" in readme


def test_the_environment_is_the_lock():
    """Every locked package is installed at its locked version (the venv was made from the lock)."""
    installed = {canonicalize_name(d.metadata["Name"]): d.version for d in md.distributions()}
    wrong = {name: (version, installed.get(name)) for name, version in lock().items()
             if installed.get(name) != version}
    assert not wrong, f"locked vs installed: {wrong} (make test installs the lock)"


def test_the_lock_holds_everything_requirements_txt_pulls_in():
    """Walk the installed metadata from requirements.txt and fdsc: every package reached is locked."""
    locked = lock()
    base = default_environment()
    todo = [(req, "requirements.txt") for req in requirements()]
    todo += [(Requirement(r), "fdsc") for r in md.requires("fdsc") or []]
    seen, missing = set(), []
    while todo:
        req, parent = todo.pop()
        name = canonicalize_name(req.name)
        if (name, frozenset(req.extras)) in seen:
            continue
        seen.add((name, frozenset(req.extras)))
        if name not in locked:
            missing.append(f"{req.name} (needed by {parent})")
            continue
        for text in md.requires(req.name) or []:
            dep = Requirement(text)
            extras = [""] + sorted(req.extras)
            if dep.marker is None or any(dep.marker.evaluate({**base, "extra": e}) for e in extras):
                todo.append((dep, req.name))
    assert not missing, f"not in the lock: {missing}: run make lock"


@pytest.mark.parametrize("name", ["constraints.txt", "requirements.txt"])
def test_the_notebook_cache_key_follows_the_lock(tmp_path, name):
    (tmp_path / "fdsc").mkdir()
    (tmp_path / "fdsc" / "__init__.py").write_text("")
    for path in (LOCK, REQUIREMENTS):
        (tmp_path / path.name).write_bytes(path.read_bytes())
    key = nc.source_key(tmp_path)
    path = tmp_path / name
    path.write_text(path.read_text().replace("numpy==", "numpy==9"))
    assert nc.source_key(tmp_path) != key
