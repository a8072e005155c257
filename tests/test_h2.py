"""fdsc.h2: shaping filters and the H2-optimal fixed controller for a spectrum, against the
separation argument (the gain on x is the plant's LQR gain), the H2 cost of simpler controllers
(by Lyapunov equations), and bad input by name."""

import numpy as np
import pytest
from scipy.linalg import solve_continuous_lyapunov

from fdsc import LTISystem, Plant, fit_shaping_filter, h2_controller, lqr_gain, shaping_filter

PLANT = Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
              [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.1]])
F = shaping_filter([0.5, 12.0], [0.3, 0.2], [1.0, 0.5])


def h2_cost(controller, F=F):
    """E‖z‖² with d = F ν, ν unit white noise and ŵ = d: the closed loop with F in front, by a
    Lyapunov equation (the H2 norm squared)."""
    loop = PLANT.closed_loop(controller)
    n, nf = loop.n_states, F.n_states
    A = np.block([[loop.A, loop.B @ F.C], [np.zeros((nf, n)), F.A]])
    B = np.vstack([np.zeros((n, 1)), F.B])
    C = np.hstack([loop.C, loop.D @ F.C])
    X = solve_continuous_lyapunov(A, -B @ B.T)
    return float(np.trace(C @ X @ C.T))


def test_the_filter_has_the_powers_it_is_given():
    for j, (w, z, P) in enumerate([(0.5, 0.3, 1.0), (12.0, 0.2, 0.5)]):
        one = shaping_filter([w], [z], [P])
        X = solve_continuous_lyapunov(one.A, -one.B @ one.B.T)
        assert float((one.C @ X @ one.C.T)[0, 0]) == pytest.approx(P, rel=1e-10), j


def test_a_fit_centres_each_group_at_its_tones():
    w = np.r_[np.geomspace(0.1, 1.0, 50), np.geomspace(10.0, 100.0, 50)]
    Ff = fit_shaping_filter(w, np.r_[np.full(50, 0.02), np.full(50, 0.01)], [3.0])
    centres = np.sqrt(-np.diag(Ff.A, -1)[::2])
    np.testing.assert_allclose(centres, [np.sqrt(0.1), np.sqrt(1000.0)], rtol=1e-9)


@pytest.mark.parametrize("reads", ["x", "x+w"])
def test_the_gain_on_x_is_the_plants_lqr_gain(reads):
    # separation: the shaping filter is not controllable from u, so the augmented LQR's block
    # on x is the plant's own
    c = h2_controller(PLANT, F, reads=reads)
    np.testing.assert_allclose(c.D, lqr_gain(PLANT), rtol=1e-7, atol=1e-9)
    assert c.reads_estimate == (reads == "x+w")


def test_knowing_the_spectrum_lowers_the_h2_cost_below_the_lqr_gains():
    lqr = h2_cost(lqr_gain(PLANT))
    full = h2_cost(h2_controller(PLANT, F, reads="x+w"))
    only_x = h2_cost(h2_controller(PLANT, F, reads="x"))
    assert full < 0.95 * lqr and only_x < 0.99 * lqr


@pytest.mark.parametrize(("call", "error", "match"), [
    (lambda: shaping_filter([1.0], [0.1, 0.2], [1.0]), ValueError, "one equal length"),
    (lambda: shaping_filter([-1.0], [0.1], [1.0]), ValueError, "centres and dampings must be positive"),
    (lambda: fit_shaping_filter([1.0, 2.0], [1.0, 1.0], [10.0]), ValueError, "group 1"),
    (lambda: h2_controller(PLANT, F, reads="y"), ValueError, "reads"),
    (lambda: h2_controller(PLANT, F, noise=0.0), ValueError, "noise"),
    (lambda: h2_controller(PLANT, LTISystem([[1.0]], [[1.0]], [[1.0]], [[0.0]])), ValueError,
     "shaping must be stable"),
    (lambda: h2_controller(PLANT, "F"), ValueError, "shaping must be an fdsc.LTISystem"),
])
def test_bad_input_is_refused_by_name(call, error, match):
    with pytest.raises(error, match=match):
        call()
