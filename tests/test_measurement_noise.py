"""Tests of fdsc.measurement_noise: band-limited white noise on ŵ, its expected cost through a
loop, and the optimal K x + Q(s) ŵ controller redesigned for it."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from fdsc import Controller, LTISystem, Plant, SegmentClass, expected_power, optimal_lti
from fdsc.measurement_noise import noise_density, noise_loop, noise_power, optimal_lti_in_noise

PLANT = Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
              [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.1]])
CLS = SegmentClass([(0.5, 2.0), (10.0, 30.0)], [0.5, 0.5])
NYQ = 100.0


def test_noise_density_gives_the_stated_variance():
    S = noise_density(2.0, 10.0, 50.0)
    assert S * 50.0 / math.pi == pytest.approx(0.2, rel=1e-14)       # σ² = P / 10^(SNR/10)
    assert noise_density(2.0, math.inf, 50.0) == 0.0
    assert noise_density(1.0, -10.0, 50.0) == pytest.approx(100 * noise_density(1.0, 10.0, 50.0))


@pytest.mark.parametrize("args, exc, match", [
    ((0.0, 10.0, 1.0), ValueError, "signal_power"), ((1.0, 10.0, -1.0), ValueError, "nyquist"),
    ((1.0, math.nan, 1.0), ValueError, "snr_db"), ((1.0, -math.inf, 1.0), ValueError, "snr_db"),
    ((1.0, "loud", 1.0), TypeError, "snr_db"),
])
def test_noise_density_refuses_bad_input_by_name(args, exc, match):
    with pytest.raises(exc, match=match):
        noise_density(*args)


def test_noise_power_of_a_second_order_loop_is_its_integral():
    loop = LTISystem([[0.0, 1.0], [-9.0, -0.6]], [[0.0], [1.0]], [[1.0, 0.0], [0.0, 2.0]], [[0.0], [0.5]])
    S, W = 0.3, 40.0

    def g(w):
        T = np.linalg.solve(1j * w * np.eye(2) - np.asarray(loop.A), np.asarray(loop.B))[:, 0]
        z = np.asarray(loop.C) @ T + np.asarray(loop.D)[:, 0]
        return float(np.sum(np.abs(z) ** 2))

    exact = quad(g, 0, W, points=[3.0], limit=400)[0] * S / math.pi
    assert noise_power(loop, S, W) == pytest.approx(exact, rel=1e-4)
    assert noise_power(loop, 0.0, W) == 0.0


def test_noise_power_refuses_what_has_no_steady_state():
    unstable = LTISystem([[0.5]], [[1.0]], [[1.0]], [[0.0]])
    with pytest.raises(ValueError, match="stable"):
        noise_power(unstable, 1.0, 10.0)
    with pytest.raises(ValueError, match="density"):
        noise_power(LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]]), -1.0, 10.0)
    with pytest.raises(ValueError, match="one input"):
        noise_power(LTISystem([[-1.0]], [[1.0, 1.0]], [[1.0]], [[0.0, 0.0]]), 1.0, 10.0)


def test_the_noise_loop_of_a_static_feedforward_is_the_plant_driven_through_b2():
    K, F = np.array([[-1.0, -0.5]]), np.array([[0.7]])
    ctrl = Controller(np.zeros((0, 0)), np.zeros((0, 2)), np.zeros((1, 0)), K, E=np.zeros((0, 1)), F=F)
    loop = noise_loop(PLANT, ctrl)
    A, B2, C, D2 = (np.asarray(m) for m in (PLANT.A, PLANT.B2, PLANT.C, PLANT.D2))
    want = LTISystem(A + B2 @ K, B2 @ F, C + D2 @ K, D2 @ F)
    S = noise_density(1.0, 0.0, NYQ)
    assert noise_power(loop, S, NYQ) == pytest.approx(noise_power(want, S, NYQ), rel=1e-12)
    with pytest.raises(ValueError, match="does not read ŵ"):
        noise_loop(PLANT, Controller(np.zeros((0, 0)), np.zeros((0, 2)), np.zeros((1, 0)), K))


@pytest.fixture(scope="module")
def designs():
    """The optimal LTI controller and the redesign without noise, at 20 dB and at −60 dB (one
    band, so that the class's spectrum, the costly part, is quick)."""
    cls = SegmentClass([(10.0, 30.0)], [1.0])
    out = {"cls": cls, "clean": optimal_lti(PLANT, cls)}
    for snr in (math.inf, 20.0, -60.0):
        S = noise_density(cls.power, snr, NYQ)
        out[snr] = (S, optimal_lti_in_noise(PLANT, cls, S, NYQ))
    return out


def test_without_noise_the_design_is_the_optimal_lti_controller(designs):
    _S, quiet = designs[math.inf]
    assert quiet.noise_power == 0.0
    assert quiet.power == pytest.approx(designs["clean"].power, rel=5e-3)


def test_the_redesign_beats_the_noise_free_optimum_under_noise_and_tends_to_ignoring_w(designs):
    cls, clean = designs["cls"], designs["clean"].controller
    for snr in (20.0, -60.0):
        S, res = designs[snr]
        assert res.power == pytest.approx(res.signal_power + res.noise_power, rel=1e-12)
        # the design counted the noise, the clean optimum did not: under the noise it is no worse
        clean_total = (expected_power(PLANT.closed_loop(clean), cls)
                       + noise_power(noise_loop(PLANT, clean), S, NYQ))
        assert res.power <= clean_total * (1 + 5e-3)
    assert designs[math.inf][1].power < designs[20.0][1].power < designs[-60.0][1].power
    # with overwhelming noise, Q → 0: the LQ gain alone
    lq = expected_power(PLANT.closed_loop(clean.D), cls)
    assert designs[-60.0][1].power == pytest.approx(lq, rel=1e-2)


@pytest.mark.parametrize("kw, exc, match", [
    ({"density": -1.0}, ValueError, "density"), ({"density": math.inf}, ValueError, "density"),
    ({"nyquist": 0.0}, ValueError, "nyquist"), ({"cls": "class"}, TypeError, "cls"),
    ({"tol": 0.0}, ValueError, "tol"),
])
def test_the_redesign_refuses_bad_input_by_name(kw, exc, match):
    args = {"plant": PLANT, "cls": CLS, "density": 0.0, "nyquist": NYQ} | kw
    with pytest.raises(exc, match=match):
        optimal_lti_in_noise(args.pop("plant"), args.pop("cls"), args.pop("density"), args.pop("nyquist"),
                             **args)
