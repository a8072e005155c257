import pytest

from fdsc.paper.verdict import verdict


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
