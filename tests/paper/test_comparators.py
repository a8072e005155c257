"""fdsc.paper.shared.comparators: the one comparator set behind every "best fixed"."""

import numpy as np
import pytest

from fdsc.paper.pays import baselines
from fdsc.paper.shared.comparators import COMPARATORS, PAPER_FOUR, best_fixed, comparators


def test_the_set():
    assert comparators("aircraft") == ("open loop", "PassC-EF", "PassC-LF", "PassC-HF", "HF best")
    assert set(comparators("generic")) < set(comparators("aircraft"))
    assert "FDSC" in PAPER_FOUR and "FDSC" not in COMPARATORS["aircraft"]
    assert baselines.FIXED == comparators("aircraft")      # the aircraft chapter uses the set


def test_best_fixed_ignores_switched_and_breaks_ties_by_order():
    e = {"open loop": 2.0, "PassC-EF": 2.0, "PassC-LF": 3.0, "PassC-HF": 9.0, "HF best": 5.0,
         "FDSC": 0.1}
    assert best_fixed(e) == ("open loop", 2.0)


def test_best_fixed_per_case():
    e = {n: np.array([1.0, 5.0]) * (k + 1) for k, n in enumerate(comparators("generic"))}
    e["PassC-HF"] = np.array([9.0, 0.5])
    names, energy = best_fixed(e, "generic")
    assert names.tolist() == ["open loop", "PassC-HF"]
    np.testing.assert_array_equal(energy, [1.0, 0.5])


@pytest.mark.parametrize(("call", "error", "match"), [
    (lambda: comparators("boat"), ValueError, "example must be one of"),
    (lambda: best_fixed({"open loop": 1.0}), KeyError, "lacks the comparators"),
    (lambda: best_fixed([1.0, 2.0]), TypeError, "energy must be a mapping"),
])
def test_bad_inputs(call, error, match):
    with pytest.raises(error, match=match):
        call()
