"""Record parts and entries."""

import pytest

from fdsc.paper.shared.results import RecordPart, entry
from fdsc.paper.shared.verdict import VERDICTS


def test_entry_has_the_required_keys_and_extras():
    e = entry("K_f1", "Sec. IV", [[1.0]], [[1.0]], "match", "equal", status="optimal")
    assert list(e)[:6] == ["id", "source", "paper", "recomputed", "verdict", "note"]
    assert e["status"] == "optimal"


@pytest.mark.parametrize(("args", "match"), [
    (("x", "s", 1, 1, "fine", "n"), "verdict must be one of"),
    (("", "s", 1, 1, "match", "n"), "id must be a non-empty string"),
])
def test_bad_entries(args, match):
    with pytest.raises(ValueError, match=match):
        entry(*args)


def test_parts_add_in_order_and_refuse_duplicates():
    a = RecordPart((entry("a", "s", None, 1, "new", "n"),), {"f": {"x": 1}})
    b = RecordPart((entry("b", "s", None, 2, "new", "n"),), {"g": {"y": 2}})
    total = a + b
    assert [e["id"] for e in total.entries] == ["a", "b"] and list(total.figures) == ["f", "g"]
    with pytest.raises(ValueError, match=r"duplicate entry ids \['a'\]"):
        total + a
    with pytest.raises(ValueError, match=r"figures \['g'\]"):
        b + RecordPart(figures={"g": {}})


def test_part_refuses_an_entry_without_a_verdict():
    with pytest.raises(ValueError, match="lacks"):
        RecordPart(({"id": "a", "source": "s", "paper": None, "recomputed": 1, "note": "n"},))


def test_every_verdict_is_accepted():
    for v in VERDICTS:
        assert entry("x", "s", None, 0, v, "n")["verdict"] == v
