import numpy as np
import pytest
from numpy.testing import assert_allclose

from fdsc import DimensionError, LTISystem, Plant
from fdsc.paper.shared.data import aircraft, paper_gains


def test_closed_loop_formula():
    p = aircraft()
    K = paper_gains()["K_f1"]
    cl = p.closed_loop(K)
    assert_allclose(cl.A, p.A + p.B2 @ K, rtol=1e-15)
    assert_allclose(cl.C, p.C + p.D2 @ K, rtol=1e-15)
    assert_allclose(cl.B, p.B1, atol=0)
    assert_allclose(cl.D, p.D1, atol=0)



def test_arrays_are_read_only():
    p = aircraft()
    with pytest.raises(ValueError):
        p.A[0, 0] = 1.0



@pytest.mark.parametrize(
    ("make", "match"),
    [
        (lambda: LTISystem(np.ones((2, 3)), np.ones((2, 1)), np.ones((1, 2)), np.zeros((1, 1))),
         "A must be square"),
        (lambda: LTISystem(np.eye(2), np.ones((3, 1)), np.ones((1, 2)), np.zeros((1, 1))),
         r"B: expected shape \(2, 1\) but found \(3, 1\)"),
        (lambda: LTISystem(np.eye(2), np.ones((2, 1)), np.ones((1, 2)), np.zeros((2, 1))),
         r"D: expected shape \(1, 1\) but found \(2, 1\)"),
        (lambda: LTISystem(np.eye(2) * np.nan, np.ones((2, 1)), np.ones((1, 2)), np.zeros((1, 1))),
         "A must have finite entries"),
        (lambda: LTISystem(np.ones(3), np.ones((2, 1)), np.ones((1, 2)), np.zeros((1, 1))),
         "A must be a 2-D array"),
        (lambda: aircraft().closed_loop(np.ones((2, 3))),
         r"K: expected shape \(2, 2\) but found \(2, 3\)"),
        (lambda: aircraft().closed_loop("abc"), "K must be a numeric matrix"),
        (lambda: Plant(np.eye(2), np.ones((2, 1)), np.ones((2, 2)), np.ones((3, 2)),
                       np.zeros((3, 2)), np.zeros((3, 2))),
         r"D1: expected shape \(3, 1\) but found \(3, 2\)"),
    ],
)
def test_bad_shapes(make, match):
    with pytest.raises((DimensionError, ValueError), match=match):
        make()

