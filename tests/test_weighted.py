"""fdsc.weighted: frequency-weighted H∞ state feedback, against the bound it certifies (swept on
the true loop) and the loop of the weighted plant it was synthesized on; bad input by name."""

import numpy as np
import pytest

from fdsc import (
    Band,
    Plant,
    band_weight,
    dynamic_front,
    freqresp,
    random_plant,
    sigma_max,
    weighted_hinf,
)

PLANT = Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
              [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.1]])
LF, HF = Band.lf(0.5), Band.hf(5.0)


def test_the_weight_is_its_band_weights_at_the_ends():
    W = band_weight(LF, HF, 4.0, 2.0, floor=0.01)
    g = np.abs(freqresp(W, [1e-4, 1e6])[:, 0, 0])
    np.testing.assert_allclose(g, [4.0 + 0.04, 2.0 + 0.04], rtol=1e-6)


@pytest.mark.parametrize("ratio", [0.3, 3.0])
def test_the_certified_gamma_bounds_the_weighted_true_loop(ratio):
    des = weighted_hinf(PLANT, LF, HF, ratio, 1.0)
    loop = PLANT.closed_loop(des.controller)
    W = band_weight(LF, HF, ratio, 1.0)
    w = np.logspace(-3, 4, 2000)
    weighted = np.abs(freqresp(W, w)[:, 0, 0]) * sigma_max(loop, w)
    # ‖W G‖∞ < γ on the true loop: the controller built from the augmented gain is that loop
    assert weighted.max() <= des.gamma * (1 + 1e-5)
    assert weighted.max() >= 0.9 * des.gamma                   # and the bound is nearly tight
    assert des.controller.n_states == 4 * PLANT.C.shape[0] and np.all(des.loop_poles.real < 0)


def test_the_ratio_trades_the_bands():
    front = dynamic_front(PLANT, LF, HF, [0.1, 10.0])
    (lf0, hf0), (lf1, hf1) = front.peaks()
    assert lf1 < lf0 and hf1 > hf0          # more LF weight: a quieter LF band, a louder HF band
    assert front.nondominated().tolist() == [True, True] and front.failures == {}


def test_a_penalty_on_u_bounds_the_controllers_size():
    plant = random_plant(np.random.default_rng(7))
    sizes = [weighted_hinf(plant, LF, HF, 1.0, 1.0, u_penalty=r).size for r in (0.0, 1.0)]
    assert sizes[1] < sizes[0]


@pytest.mark.parametrize(("call", "match"), [
    (lambda: band_weight(HF, LF, 1.0, 1.0), "lf and hf must be an LF band and an HF band"),
    (lambda: band_weight(LF, HF, 0.0, 0.0), "both 0"),
    (lambda: band_weight(LF, HF, -1.0, 1.0), "w_lf"),
    (lambda: band_weight(LF, HF, 1.0, 1.0, corner=10.0), "corner must lie in"),
    (lambda: weighted_hinf(PLANT, LF, HF, 1.0, 1.0, u_penalty=-1.0), "u_penalty"),
    (lambda: dynamic_front(PLANT, LF, HF, [1.0, -2.0]), "ratios must be positive"),
    (lambda: dynamic_front(PLANT, LF, HF, []), "ratios must be positive"),
])
def test_bad_input_is_refused_by_name(call, match):
    with pytest.raises(ValueError, match=match):
        call()
