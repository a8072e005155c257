"""The book build's pre-execution of chapters (book/_ext/result_cache.py): a chapter that runs
without error is stored in the notebook cache, one that fails is not, longest first."""

import json
from types import SimpleNamespace

import nbformat
import result_cache  # book/_ext is on the path (conftest.py)
from notebook_cache import cached_execution


def _notebook(path, code):
    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_markdown_cell("# A chapter"), nbformat.v4.new_code_cell(code)]
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
    nbformat.write(nb, str(path))
    return nbformat.read(str(path), as_version=4)


def _app(tmp_path):
    folder = tmp_path / "_build" / ".jupyter_cache" / "key"
    return SimpleNamespace(srcdir=str(tmp_path),
                           config=SimpleNamespace(nb_execution_timeout=120,
                                                  nb_execution_cache_path=str(folder))), folder


def test_a_chapter_that_runs_is_stored_and_one_that_fails_is_not(tmp_path):
    app, folder = _app(tmp_path)
    good = _notebook(tmp_path / "good.ipynb", "print(6 * 7)")
    bad = _notebook(tmp_path / "bad.ipynb", "raise ValueError('no')")
    stem, seconds, stored = result_cache._execute_one(app, tmp_path / "good.ipynb")
    assert (stem, stored) == ("good", True) and seconds > 0
    done = cached_execution(folder, good)
    assert done is not None and "42" in done.cells[1].outputs[0]["text"]
    assert result_cache._execute_one(app, tmp_path / "bad.ipynb")[2] is False
    assert cached_execution(folder, bad) is None


def test_chapters_start_longest_first_unknown_ones_before_them(tmp_path):
    app, _folder = _app(tmp_path)
    (tmp_path / "data").mkdir()
    (tmp_path / "data" / "cold_times.json").write_text(json.dumps({"chapters": {"a": 5.0, "b": 50.0}}))
    paths = [tmp_path / f"{s}.ipynb" for s in ("a", "b", "new")]
    assert [p.stem for p in result_cache._longest_first(app, paths)] == ["new", "b", "a"]
    # without measured times, the order given
    (tmp_path / "data" / "cold_times.json").unlink()
    assert [p.stem for p in result_cache._longest_first(app, paths)] == ["a", "b", "new"]
