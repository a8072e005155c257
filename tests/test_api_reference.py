"""The book's API reference (``book/api/``) and its link resolver (``book/_ext/api_links.py``).

Every public module of the package, the paper layer included, has an ``automodule`` on one of the
reference's pages, and every page is in the book's table of contents; the resolver maps the names
readers and docstrings use (``fdsc.synthesize``, a chapter module's re-export) to the module that
defines, and so documents, the object.
"""

import pkgutil
import re
import sys
from pathlib import Path

import pytest

import fdsc

ROOT = Path(__file__).resolve().parent.parent
API = ROOT / "book" / "api"
sys.path.insert(0, str(ROOT / "book" / "_ext"))

import api_links  # noqa: E402


def _public_modules():
    names = [m.name for m in pkgutil.walk_packages(fdsc.__path__, "fdsc.")]
    return sorted(n for n in names if not any(p.startswith("_") for p in n.split(".")))


def test_every_public_module_is_documented_once():
    documented = [m for page in API.glob("*.rst")
                  for m in re.findall(r"^\.\. automodule:: (\S+)$", page.read_text(encoding="utf-8"), re.M)]
    assert sorted(set(documented)) == sorted(documented), "a module documented twice"
    assert set(_public_modules()) - {"fdsc.paper.__main__"} <= set(documented)


def test_every_api_page_is_in_the_toc():
    toc = (ROOT / "book" / "_toc.yml").read_text(encoding="utf-8")
    for page in API.glob("*.rst"):
        assert f"file: api/{page.stem}\n" in toc, page.name


@pytest.mark.parametrize(("name", "where"), [
    ("fdsc.synthesize", "fdsc.synthesis.synthesize"),
    # the function, not the submodule of the same name
    ("fdsc.simulate", "fdsc.simulate.simulate"),
    ("fdsc.Supervisor.prepare", "fdsc.supervisor.Supervisor.prepare"),
    ("fdsc.paper.reproduced.stationary.StationaryRuns",
     "fdsc.paper.reproduced.stationary_figures.StationaryRuns"),
])
def test_a_name_resolves_to_its_defining_module(name, where):
    assert api_links._defined_at(api_links._lookup(name)) == where


def test_names_without_a_module_of_their_own():
    # data carries no __module__, a private module's object is documented where it is exported
    assert api_links._defined_at(api_links._lookup("fdsc.PHI")) is None
    assert api_links._exported_from("fdsc.PHI") == "fdsc.bands.PHI"
    assert api_links._exported_from("fdsc.shift_signal") == "fdsc.prepared.shift_signal"
    assert api_links._exported_from("fdsc.no_such_name") is None
    assert api_links._lookup("fdsc.no_such_name") is None
    assert api_links._lookup("numpy.array") is None


def test_a_module_documents_what_it_defines():
    from fdsc import prepared, stream
    assert api_links._defined_in(stream.simulate_stream, "fdsc.stream")
    assert not api_links._defined_in(stream.simulate_stream, "fdsc.simulate")
    assert api_links._defined_in(prepared.shift_signal, "fdsc.prepared")  # from fdsc._grid_run
    assert api_links._defined_in(3.0, "fdsc.anything")
