"""Chapters are stored without outputs, and every chapter is listed in the table of contents."""

import json
from pathlib import Path

import pytest

BOOK = Path(__file__).resolve().parent.parent / "book"
NOTEBOOKS = sorted(p for p in BOOK.glob("*.ipynb"))


def stored_outputs(path):
    nb = json.loads(path.read_text(encoding="utf-8"))
    return [i for i, c in enumerate(nb["cells"])
            if c["cell_type"] == "code" and (c.get("outputs") or c.get("execution_count"))]


def test_there_are_chapters():
    assert len(NOTEBOOKS) >= 3


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_notebook_stored_without_outputs(path):
    assert stored_outputs(path) == [], f"{path.name} has outputs in cells {stored_outputs(path)}"


def test_detector_catches_outputs(tmp_path):
    nb = {"cells": [{"cell_type": "code", "source": "1", "metadata": {}, "execution_count": 1,
                     "outputs": [{"output_type": "execute_result", "data": {"text/plain": "1"},
                                  "metadata": {}, "execution_count": 1}]}],
          "metadata": {}, "nbformat": 4, "nbformat_minor": 5}
    p = tmp_path / "dirty.ipynb"
    p.write_text(json.dumps(nb))
    assert stored_outputs(p) == [0]


def test_every_chapter_is_in_the_toc():
    toc = (BOOK / "_toc.yml").read_text(encoding="utf-8")
    for path in NOTEBOOKS:
        assert f"file: {path.stem}" in toc or f"root: {path.stem}" in toc, path.name
