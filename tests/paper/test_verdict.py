import pytest

from fdsc.paper.reproduced import claims
from fdsc.paper.shared.verdict import (
    CLAIM_VERDICT_RULES,
    CLAIM_VERDICTS,
    VERDICT_RULES,
    VERDICTS,
    verdict,
    worst_verdict,
)


@pytest.mark.parametrize(
    ("paper", "ours", "expected"),
    [(0.3443, 0.34434, "match"), (0.3443, 0.3446, "close"), (0.3443, 0.3737, "differs"),
     (0.1714, 1.605, "differs")],
)
def test_verdict(paper, ours, expected):
    assert verdict(paper, ours) == expected


@pytest.mark.parametrize(
    ("paper", "ours", "after", "expected"),
    [(0.3443, 0.3426, False, "close"), (0.3443, 0.3426, True, "differs"),
     (0.3443, 0.34434, True, "match"),
     ([[1.0, 2.0]], [[1.00004, 2.0]], False, "match"), ([[1.0, 2.0]], [[1.01, 2.0]], False, "close")],
)
def test_verdict_after_the_fact_and_matrices(paper, ours, after, expected):
    assert verdict(paper, ours, after_the_fact=after) == expected


def test_the_verdicts_and_their_rules():
    # "input" (a printed input used as printed) sits after the comparisons; "new" stays last
    assert VERDICTS == ("match", "close", "differs", "not reproducible", "input", "new")
    assert tuple(VERDICT_RULES) == VERDICTS and all(VERDICT_RULES.values())
    assert "LaTeX source" in VERDICT_RULES["input"]
    assert CLAIM_VERDICTS == ("PASS", "PARTLY", "FAIL") and tuple(CLAIM_VERDICT_RULES) == CLAIM_VERDICTS
    # the checklist grades with the same verdicts (the report and the schema read them from here)
    assert claims.CLAIM_VERDICTS == CLAIM_VERDICTS


@pytest.mark.parametrize(("verdicts", "order", "expected"), [
    (["match", "input"], VERDICTS, "input"),
    (["new", "differs"], VERDICTS, "new"),
    (["PASS", "FAIL", "PARTLY"], CLAIM_VERDICTS, "FAIL"),
    (["PASS"], CLAIM_VERDICTS, "PASS"),
])
def test_worst_verdict(verdicts, order, expected):
    assert worst_verdict(verdicts, order) == expected


@pytest.mark.parametrize(("verdicts", "order"),
                         [([], VERDICTS), (["PASS"], VERDICTS), (["match"], CLAIM_VERDICTS)])
def test_worst_verdict_refuses_unknown_or_no_verdicts(verdicts, order):
    with pytest.raises(ValueError, match="verdicts must be a non-empty list from"):
        worst_verdict(verdicts, order)
