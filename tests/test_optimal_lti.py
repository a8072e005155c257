import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from fdsc import Controller, LTISystem, Plant
from fdsc.class_spectrum import SegmentClass
from fdsc.exceptions import IterationLimitError
from fdsc.h2 import fit_shaping_filter, h2_controller
from fdsc.optimal_lti import expected_power, optimal_lti, wiener_power

CLASS = SegmentClass([(0.5, 2.0), (10.0, 30.0)], [0.5, 0.5])
# a lightly damped oscillator, u through D2 = 0.1 (the README's plant)
OSC = Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
            [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.1]])


def test_expected_power_of_a_first_order_loop_is_its_closed_form():
    # T = 1/(s + a), tones log-uniform on [l, h], segments so long that their breaks do not
    # broaden the lines: E|z|² = P / ln(h/l) ∫_l^h dν / (ν (ν² + a²))
    a, lo, hi = 3.0, 1.0, 10.0
    cls = SegmentClass([(lo, hi)], [1.0], power=2.0, min_length=1e4, mean_extra=1e4)
    loop = LTISystem([[-a]], [[1.0]], [[1.0]], [[0.0]])

    def F(v):
        return math.log(v * v / (v * v + a * a)) / (2 * a * a)

    exact = 2.0 / math.log(hi / lo) * (F(hi) - F(lo))
    assert_allclose(expected_power(loop, cls), exact, rtol=1e-3)


def test_a_static_optimum_is_found_and_meets_the_wiener_bound():
    # z = [d + u; r u] (no state in the cost): per frequency the best u is −d / (1 + r²), a
    # static (hence causal) filter, so the optimal LTI power and the non-causal bound are both
    # P r² / (1 + r²)
    r = 0.5
    p = Plant([[-1.0]], [[0.0]], [[1.0]], [[0.0], [0.0]], [[1.0], [0.0]], [[1.0], [r]])
    res = optimal_lti(p, CLASS)
    bound = r * r / (1 + r * r)
    assert_allclose([res.power, res.wiener], [bound, bound], rtol=2e-3)
    assert res.converged


def test_the_optimum_beats_every_other_lti_design_and_respects_the_bound():
    res = optimal_lti(OSC, CLASS)
    assert res.converged and res.change < 5e-3
    assert res.wiener <= res.power
    lq = expected_power(OSC.closed_loop(res.gain), CLASS)
    w = np.concatenate([np.geomspace(0.5, 2.0, 50), np.geomspace(10.0, 30.0, 50)])
    h2 = h2_controller(OSC, fit_shaping_filter(w, np.full(100, 0.01), [5.0]), reads="x+w")
    assert res.power < expected_power(OSC.closed_loop(h2), CLASS) and res.power < 0.8 * lq
    # local optimality: scaling the feedforward filter either way costs power
    c = res.controller
    for f in (0.9, 1.1):
        other = Controller(c.A, c.B, f * c.C, c.D, E=c.E, F=f * c.F)
        assert expected_power(OSC.closed_loop(other), CLASS) > res.power
    # the refinements' powers fall towards the limit; each is reached by a causal controller
    assert np.all(np.diff(res.powers) <= 1e-12 * res.powers[0])
    assert res.full_power <= res.power <= res.full_power * (1 + 1e-3)
    assert OSC.closed_loop(c).is_hurwitz() and c.reads_estimate


def test_a_search_that_cannot_converge_says_so():
    with pytest.raises(IterationLimitError, match=r"did not converge to tol = 1e-12"):
        optimal_lti(OSC, CLASS, tol=1e-12)
    res = optimal_lti(OSC, CLASS, tol=1e-12, strict=False)
    assert not res.converged and res.densities.size == 7


@pytest.mark.parametrize("call, exc, match", [
    (lambda: optimal_lti(OSC, [(1.0, 2.0)]), TypeError, "cls must be an fdsc.SegmentClass"),
    (lambda: optimal_lti(OSC, CLASS, tol=0.0), ValueError, "tol"),
    (lambda: optimal_lti(OSC, CLASS, reduce_tol=-1.0), ValueError, "reduce_tol"),
    (lambda: optimal_lti(Plant([[-1.0]], [[1.0, 1.0]], [[1.0]], [[1.0], [0.0]], [[0.0, 0.0], [0.0, 0.0]],
                               [[0.0], [1.0]]), CLASS), ValueError, "one disturbance input"),
    (lambda: expected_power(LTISystem([[1.0]], [[1.0]], [[1.0]], [[0.0]]), CLASS), ValueError,
     "loop must be stable"),
    (lambda: expected_power(LTISystem([[-1.0]], [[1.0, 1.0]], [[1.0]], [[0.0, 0.0]]), CLASS), ValueError,
     "loop must have one input"),
    (lambda: wiener_power(OSC, None), TypeError, "cls must be an fdsc.SegmentClass"),
])
def test_bad_input_is_refused_by_name(call, exc, match):
    with pytest.raises(exc, match=match):
        call()
