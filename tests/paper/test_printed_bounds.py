"""fdsc.paper.printed_bounds: the four printed bounds, one verdict each, every reading."""

import pytest

from fdsc.paper.passive_controllers import printed_bound_entries
from fdsc.paper.printed_bounds import printed_bounds_appendix


@pytest.fixture(scope="module")
def pb():
    return printed_bounds_appendix()


def test_one_verdict_per_bound_and_the_entries_agree(pb):
    entries = {e["paper"]: e["verdict"] for e in printed_bound_entries().entries}
    assert [b.printed for b in pb.bounds] == [0.3443, 0.4025, 0.1714, 0.7125]
    assert {b.printed: b.verdict for b in pb.bounds} == entries


def test_the_stated_quantity_and_lemma1_agree(pb):
    for b in pb.bounds:
        assert b.lemma1 == pytest.approx(b.peak, rel=1e-5)
    # the stated quantity of K_f3 is ten times the printed bound: not a rounding question
    kf3 = next(b for b in pb.bounds if b.gain == "K_f3")
    assert kf3.peak > 9 * kf3.printed


def test_prose_and_rows(pb):
    text = pb.prose()
    assert text["n_close"] == "1" and text["n_not"] == "3"
    assert text["hit_gains"] == "K_f1 and K_f3"
    rows = pb.rows()
    assert [r["gain"] for r in rows] == ["K_f1", "K_f2", "K_f3", "K_e"]
    assert all("[" not in r["time"] for r in rows)
