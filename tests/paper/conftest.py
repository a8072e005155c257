"""Fixtures of the paper layer's tests."""

import pytest

from fdsc.paper.pays.stored_study import load_full


@pytest.fixture(scope="module")
def full():
    """The stored full study of Part II (the test skips where the checkout has none)."""
    study = load_full()
    if study is None:
        pytest.skip("the full study is not in this checkout")
    return study
