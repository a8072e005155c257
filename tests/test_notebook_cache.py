"""The notebook cache shared by the tests and the book build (``book/_ext/notebook_cache.py``).

The key must follow every byte of the sources and nothing else, a notebook stored by the test side
must be found by MyST-NB's lookup for the same code and only for it, and a failure is never stored.
Everything runs on a copy of ``fdsc/`` in a temporary folder; the few real executions are of a
one-cell notebook.
"""

import inspect
import os
import shutil
import sys
from pathlib import Path
from types import SimpleNamespace

import nbformat
import pytest
from jupyter_cache import get_cache
from myst_nb.core.read import standard_nb_read
from nbmake.nb_run import NotebookRun
from sphinx.errors import ExtensionError

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "book" / "_ext"))

import notebook_cache as nc  # noqa: E402

# conftest.py wraps nbmake's execute during a test run; these tests wrap the original
EXECUTE = inspect.unwrap(NotebookRun.execute)


@pytest.fixture
def root(tmp_path):
    """A repository with a copy of fdsc/ (no __pycache__), requirements.txt and an empty book/."""
    shutil.copytree(ROOT / "fdsc", tmp_path / "fdsc", ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copy(ROOT / "requirements.txt", tmp_path / "requirements.txt")
    (tmp_path / "book").mkdir()
    return tmp_path


def write_notebook(path, *code, markdown="# A page"):
    nb = nbformat.v4.new_notebook()
    nb.metadata["kernelspec"] = {"display_name": "Python 3", "language": "python", "name": "python3"}
    nb.cells = [nbformat.v4.new_markdown_cell(markdown)] + [nbformat.v4.new_code_cell(c) for c in code]
    nbformat.write(nb, str(path))
    return path


def match(root, path):
    """What MyST-NB does in 'cache' mode: read the page, hash it, look it up (KeyError: a miss)."""
    cache = get_cache(str(nc.cache_path(root)))
    nb = standard_nb_read(Path(path).read_text(encoding="utf-8"))
    return cache.match_cache_notebook(nb), cache.merge_match_into_notebook(nb)[1]


def cached_records(root):
    folder = nc.cache_path(root)
    return get_cache(str(folder)).list_cache_records() if folder.exists() else []


def flip_byte(path, index):
    data = bytearray(path.read_bytes())
    data[index] ^= 1
    path.write_bytes(bytes(data))


# -- the key ---------------------------------------------------------------------------------------

def test_key_changes_with_any_byte_of_any_source(root):
    sources = sorted(p for p in (root / "fdsc").rglob("*") if p.suffix in (".py", ".json"))
    sources.append(root / "requirements.txt")
    assert len(sources) > 30 and any(p.suffix == ".json" for p in sources)
    key = nc.source_key(root)
    for path in sources:
        original = path.read_bytes()
        for index in (0, len(original) // 2, len(original) - 1):
            flip_byte(path, index)
            assert nc.source_key(root) != key, f"{path.relative_to(root)} byte {index}"
            path.write_bytes(original)
    assert nc.source_key(root) == key


def test_key_changes_with_a_new_or_renamed_source(root):
    key = nc.source_key(root)
    (root / "fdsc" / "bands.py").rename(root / "fdsc" / "bands2.py")
    renamed = nc.source_key(root)
    (root / "fdsc" / "paper" / "data" / "extra.json").write_text("{}")
    assert len({key, renamed, nc.source_key(root)}) == 3


def test_key_ignores_pycache_notebooks_and_other_files(root):
    key = nc.source_key(root)
    (root / "fdsc" / "__pycache__").mkdir()
    (root / "fdsc" / "__pycache__" / "bands.cpython-311.pyc").write_bytes(b"\0compiled")
    (root / "fdsc" / "paper" / "__pycache__").mkdir()
    (root / "fdsc" / "paper" / "__pycache__" / "stale.py").write_text("x = 1\n")
    (root / "fdsc" / "notes.txt").write_text("not a source\n")
    page = write_notebook(root / "book" / "page.ipynb", "print(1)")
    assert nc.source_key(root) == key
    write_notebook(page, "print(2)")
    assert nc.source_key(root) == key
    assert nc.cache_path(root) == root / "book" / "_build" / ".jupyter_cache" / key[:16]


def test_key_needs_the_package(tmp_path):
    with pytest.raises(FileNotFoundError, match="no fdsc package"):
        nc.source_key(tmp_path)


# -- the test side stores, MyST-NB finds -------------------------------------------------------------

def test_a_notebook_executed_by_nbmake_is_found_for_the_same_code_only(root):
    page = write_notebook(root / "book" / "page.ipynb", "print(1)", "x = 2\nx * 21")
    result = nc.caching_execute(EXECUTE, root=root)(NotebookRun(page, 60))
    assert result.error is None
    # nbmake records timings in the cells' metadata; what is stored must still match the page
    assert "execution" in result.nb.cells[1].metadata

    record, merged = match(root, page)
    assert record.data["execution_seconds"] > 0
    assert merged.cells[1].outputs[0]["text"] == "1\n"
    assert merged.cells[2].outputs[0]["data"]["text/plain"] == "42"

    # prose is not hashed: a change of a markdown cell still finds the stored outputs
    write_notebook(page, "print(1)", "x = 2\nx * 21", markdown="# Another title")
    assert match(root, page)[0].pk == record.pk

    # a change of a code cell is a miss
    write_notebook(page, "print(1)", "x = 2\nx * 22")
    with pytest.raises(KeyError):
        match(root, page)

    # a change of the code is a miss: another key, another (empty) folder
    write_notebook(page, "print(1)", "x = 2\nx * 21")
    old = nc.cache_path(root)
    with (root / "fdsc" / "bands.py").open("a") as fh:
        fh.write("# a comment\n")
    assert nc.cache_path(root) != old
    with pytest.raises(KeyError):
        match(root, page)

    # the next stored execution deletes the folder of the old code
    nc.caching_execute(EXECUTE, root=root)(NotebookRun(page, 60))
    assert not old.exists() and match(root, page)[1].cells[1].outputs[0]["text"] == "1\n"


def test_a_notebook_cached_for_the_same_sources_is_not_executed_again(root):
    # make book, then make test: the test run takes the build's execution instead of computing
    # the chapter again; another code cell, or other sources, executes it
    page = write_notebook(root / "book" / "page.ipynb", "print(1)")
    calls = []

    def counting(run):
        calls.append(run.filename)
        return fake_execute(page, lambda: None)(run)

    first = nc.caching_execute(counting, root=root)(fake_run(page))
    again = nc.caching_execute(counting, root=root)(fake_run(page))
    assert len(calls) == 1 and again.error is None
    assert again.nb.cells[1].outputs[0]["text"] == first.nb.cells[1].outputs[0]["text"] == "1\n"
    # an import check or another kernel always executes
    nc.caching_execute(counting, root=root)(fake_run(page, find_import_errors=True))
    assert len(calls) == 2
    write_notebook(page, "print(2)")
    nc.caching_execute(counting, root=root)(fake_run(page))
    assert len(calls) == 3
    with (root / "fdsc" / "bands.py").open("a") as fh:
        fh.write("# a comment\n")
    nc.caching_execute(counting, root=root)(fake_run(page))
    assert len(calls) == 4


def test_a_failed_execution_is_not_cached(root):
    page = write_notebook(root / "book" / "bad.ipynb", "print(1)", "raise ValueError('boom')")
    result = nc.caching_execute(EXECUTE, root=root)(NotebookRun(page, 60))
    assert result.error is not None and "boom" in result.error.summary
    assert cached_records(root) == []


def test_an_error_allowed_by_the_notebook_is_not_cached(root):
    page = write_notebook(root / "book" / "allowed.ipynb", "raise ValueError('boom')", "print(1)")
    nb = nbformat.read(str(page), as_version=4)
    nb.metadata["execution"] = {"allow_errors": True}
    nbformat.write(nb, str(page))
    result = nc.caching_execute(EXECUTE, root=root)(NotebookRun(page, 60))
    assert result.error is None and nc.error_outputs(result.nb) == [1]
    assert cached_records(root) == []
    with pytest.raises(ValueError, match="never cached"):
        nc.store_execution(nc.cache_path(root), nb, result.nb, str(page), 1.0)


def fake_execute(page, action):
    """An execute that runs ``action`` instead of a kernel and returns the page with an output."""
    def execute(run):
        action()
        nb = nbformat.read(str(page), as_version=4)
        nb.cells[1].outputs = [nbformat.v4.new_output("stream", name="stdout", text="1\n")]
        nb.cells[1].execution_count = 1
        return SimpleNamespace(nb=nb, error=None)
    return execute


def fake_run(page, kernel=None, find_import_errors=False):
    return SimpleNamespace(filename=page, kernel=kernel, find_import_errors=find_import_errors)


def test_nothing_is_cached_if_the_code_changes_during_the_execution(root):
    page = write_notebook(root / "book" / "page.ipynb", "print(1)")

    def edit():
        with (root / "fdsc" / "bands.py").open("a") as fh:
            fh.write("# edited while the notebook ran\n")

    nc.caching_execute(fake_execute(page, edit), root=root)(fake_run(page))
    assert cached_records(root) == []
    nc.caching_execute(fake_execute(page, lambda: None), root=root)(fake_run(page))
    assert len(cached_records(root)) == 1


def test_another_kernel_or_an_import_check_is_not_cached(root):
    page = write_notebook(root / "book" / "page.ipynb", "print(1)")
    execute = nc.caching_execute(fake_execute(page, lambda: None), root=root)
    execute(fake_run(page, kernel="julia"))
    execute(fake_run(page, find_import_errors=True))
    assert cached_records(root) == []
    execute(fake_run(page, kernel="python3"))
    assert len(cached_records(root)) == 1


def test_the_kernel_environment_is_set_during_the_execution_only(root, monkeypatch):
    monkeypatch.setenv("FDSC_TEST_OUTER", "outer")
    monkeypatch.delenv("FDSC_TEST_NEW", raising=False)
    page = write_notebook(root / "book" / "page.ipynb", "print(1)")
    seen = {}

    def look():
        seen.update(outer=os.environ.get("FDSC_TEST_OUTER"), new=os.environ.get("FDSC_TEST_NEW"))

    env = {"FDSC_TEST_OUTER": "inner", "FDSC_TEST_NEW": "new"}
    nc.caching_execute(fake_execute(page, look), root=root, kernel_env=env)(fake_run(page))
    assert seen == {"outer": "inner", "new": "new"}
    assert os.environ["FDSC_TEST_OUTER"] == "outer" and "FDSC_TEST_NEW" not in os.environ


# -- the book side -----------------------------------------------------------------------------------

def test_the_build_uses_the_keyed_folder_and_drops_the_others(root, monkeypatch):
    monkeypatch.setattr(nc, "ROOT", root)
    stale = root / "book" / "_build" / ".jupyter_cache" / "0123456789abcdef"
    stale.mkdir(parents=True)
    config = SimpleNamespace(nb_execution_cache_path="")
    nc._use_keyed_cache(None, config)
    assert config.nb_execution_cache_path == str(nc.cache_path(root)) and not stale.exists()

    doctrees = root / "book" / "_build" / ".doctrees"
    doctrees.mkdir()
    (doctrees / "environment.pickle").write_bytes(b"pages read")
    app = SimpleNamespace(config=config, doctreedir=str(doctrees))
    nc._check_sources_unchanged(app, None)  # same sources: nothing to say
    assert (doctrees / "environment.pickle").exists()
    nc.cache_path(root).mkdir(parents=True)
    with (root / "fdsc" / "bands.py").open("a") as fh:
        fh.write("# edited during the build\n")
    with pytest.raises(ExtensionError, match="changed during the build"):
        nc._check_sources_unchanged(app, None)
    # the next build executes and reads every page again
    assert not Path(config.nb_execution_cache_path).exists()
    assert not (doctrees / "environment.pickle").exists()


def test_the_build_refuses_another_cache_folder(root, monkeypatch):
    monkeypatch.setattr(nc, "ROOT", root)
    with pytest.raises(ExtensionError, match="execute.cache"):
        nc._use_keyed_cache(None, SimpleNamespace(nb_execution_cache_path="/somewhere/else"))
