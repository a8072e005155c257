"""The paper layer is laid out like the book: shared machinery, then the parts in the book's order.

* ``fdsc.paper.shared`` imports no part;
* a part (``reproduced`` = Part I, ``pays`` = Part II, ``repairs`` = Part III) imports the
  library, the shared machinery and earlier parts, never a later one;
* the appendix may read the record (``fdsc.paper.record``, the sum of the parts); the landing
  page's findings and the command line sit on top;
* a chapter's notebook imports from the library, the shared machinery, its own part and earlier
  parts (the landing page from anything), so no chapter uses what a later one defines;
* a chapter split into sibling modules keeps ``record_part()`` in its entry module, which
  re-exports every public name that moved.
"""

import ast
import importlib
import json
import re
from pathlib import Path

import pytest
import yaml
from import_graph import import_graph

import fdsc.paper

PAPER = Path(fdsc.paper.__file__).parent
BOOK = Path(__file__).resolve().parents[2] / "book"

#: The layers, lowest first: a module may import its own layer and lower ones only.
LEVEL = {"shared": 0, "reproduced": 1, "pays": 2, "repairs": 3, "record": 4, "appendix": 5,
         "findings": 6, "cli": 6, "__main__": 7}
#: The book's parts (``book/_toc.yml`` captions) and the landing page, as layers.
PART_LEVEL = {"I. The paper, reproduced": 1, "II. Does FDSC pay?": 2, "Appendices": 5}
#: Chapters of Part I that also tell what the layers after it compute about the same result (the
#: switching law with its repairs, Theorem 1 with its counterexamples, the paper's simulations with
#: the comparators on the same cases): their layer is the highest of what they tell.
CHAPTER_LEVEL = {"switching_law": LEVEL["repairs"], "theorem1": LEVEL["repairs"],
                 "simulations": LEVEL["pays"]}

#: The entry module of each chapter split into siblings, and the split modules of the appendix
#: on the printed bounds and of the figures.
ENTRY_MODULES = ("reproduced.frequency_ranges", "reproduced.gkyp_lemma", "reproduced.passive_controllers",
                 "reproduced.frequency_selective", "reproduced.theorem1", "reproduced.stationary",
                 "reproduced.nonstationary", "repairs.wellposed", "repairs.theorem1_counterexamples",
                 "pays.disturbance_law", "pays.baselines", "reproduced.bound_search", "shared.plotting")
#: Entry modules whose chapter contributes to the reproduction record.
CHAPTER_ENTRIES = tuple(m for m in ENTRY_MODULES if m not in ("reproduced.bound_search", "shared.plotting"))


def level(module):
    """The layer of a module of the paper layer (None for the library and the package itself)."""
    parts = module.split(".")
    if parts[:2] != ["fdsc", "paper"] or len(parts) < 3:
        return None
    return LEVEL[parts[2]]


def test_every_subpackage_is_a_layer_and_says_which_part_it_computes():
    subpackages = {p.name for p in PAPER.iterdir() if (p / "__init__.py").exists()}
    assert subpackages == {"shared", "reproduced", "pays", "repairs", "appendix"}
    for name in subpackages:
        doc = importlib.import_module(f"fdsc.paper.{name}").__doc__
        assert doc and ("Part" in doc or "appendi" in doc or "Shared" in doc), name
    top = {p.stem for p in PAPER.glob("*.py")} - {"__init__"}
    assert top == {"record", "findings", "cli", "__main__"}


def test_no_module_imports_a_later_layer():
    graph = import_graph()
    paper = {m: deps for m, deps in graph.items() if level(m) is not None}
    assert len(paper) >= 70
    bad = [f"{m} imports {d}" for m, deps in paper.items() for d in deps
           if level(d) is not None and level(d) > level(m)]
    assert bad == []


def test_the_layer_rule_would_catch_a_forward_import():
    # the rule on a made-up edge: Part I reading Part II's runs is refused, the reverse is not
    assert level("fdsc.paper.pays.baselines") > level("fdsc.paper.reproduced.stationary")
    assert level("fdsc.paper.shared.comparators") < level("fdsc.paper.reproduced.stationary")
    assert level("fdsc.plant") is None


def _notebook_parts():
    toc = yaml.safe_load((BOOK / "_toc.yml").read_text(encoding="utf-8"))
    out = {toc["root"]: 7}
    for part in toc["parts"]:
        for chapter in part["chapters"]:
            out[chapter["file"]] = CHAPTER_LEVEL.get(chapter["file"], PART_LEVEL[part["caption"]])
    return out


def _notebook_imports(path):
    nb = json.loads(path.read_text(encoding="utf-8"))
    found = []
    for cell in nb["cells"]:
        if cell["cell_type"] != "code":
            continue
        source = re.sub(r"^\s*[%!].*$", "", "".join(cell["source"]), flags=re.M)
        for node in ast.walk(ast.parse(source)):
            if isinstance(node, ast.ImportFrom) and node.module:
                found += [node.module] + [f"{node.module}.{a.name}" for a in node.names]
            elif isinstance(node, ast.Import):
                found += [a.name for a in node.names]
    return found


@pytest.mark.parametrize("stem", sorted(_notebook_parts()))
def test_a_chapter_imports_from_its_own_part_and_earlier_ones(stem):
    path = BOOK / f"{stem}.ipynb"
    if not path.exists():
        pytest.skip(f"{stem} is a Markdown page")
    own = _notebook_parts()[stem]
    modules = [m for m in _notebook_imports(path) if m.startswith("fdsc.paper.")]
    later = [m for m in modules if level(m) is not None and level(m) > own]
    assert later == [], f"{stem} (layer {own}) imports from later layers: {later}"


def test_the_notebook_rule_reads_imports():
    # guards the test above against reading nothing
    imports = _notebook_imports(BOOK / "simulations.ipynb")
    assert "fdsc.paper.reproduced.stationary" in imports


@pytest.mark.parametrize("name", ENTRY_MODULES)
def test_every_name_of_an_entry_module_is_importable_from_it(name):
    module = importlib.import_module(f"fdsc.paper.{name}")
    missing = []
    for public in module.__all__:
        try:
            exec(f"from fdsc.paper.{name} import {public}", {})
        except ImportError:
            missing.append(public)
    assert missing == [], f"fdsc.paper.{name} lists {missing} in __all__ but does not provide them"


@pytest.mark.parametrize("name", CHAPTER_ENTRIES)
def test_a_chapter_entry_module_keeps_its_record_part(name):
    module = importlib.import_module(f"fdsc.paper.{name}")
    assert "record_part" in module.__all__
    assert module.record_part.__module__ == module.__name__
