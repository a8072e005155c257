"""Tests of fdsc.tone_bound: the Cramér–Rao bound of tone frequencies."""

import numpy as np
import pytest
from scipy.optimize import least_squares

from fdsc.tone_bound import frequency_bound, single_tone_bound


def test_one_tone_tends_to_the_classical_bound():
    # the classical bound is a large-sample one: the exact bound approaches it as the window
    # holds more cycles (here 2, 11 and 45 cycles of 7 rad/s)
    gaps = []
    for n in (200, 1000, 4000):
        t = np.arange(n) * 0.01
        exact = frequency_bound(t, [7.0], [2.0], [1.1], 0.3)[0]
        gaps.append(abs(exact / single_tone_bound(n, 0.01, 2.0, 0.3) - 1))
    assert gaps[0] > gaps[1] > gaps[2] and gaps[2] < 0.005


def test_the_bound_scales_as_the_theory_says():
    t = np.arange(500) * 0.02
    b = frequency_bound(t, [5.0], [1.0], [0.0], 1.0)[0]
    # σ doubles: the bound doubles; the amplitude doubles: it halves
    assert frequency_bound(t, [5.0], [1.0], [0.0], 4.0)[0] == pytest.approx(2 * b, rel=1e-12)
    assert frequency_bound(t, [5.0], [2.0], [0.0], 1.0)[0] == pytest.approx(b / 2, rel=1e-12)


def test_a_maximum_likelihood_fit_reaches_the_bound():
    # at a high SNR the least-squares fit of (a, ω, φ) is efficient: its spread is the bound's
    rng = np.random.default_rng(5)
    t = np.arange(300) * 0.01
    truth = np.array([1.0, 4.0, 0.3])
    sigma = 0.05
    clean = truth[0] * np.cos(truth[1] * t + truth[2])
    est = []
    for _ in range(400):
        y = clean + sigma * rng.standard_normal(t.size)
        fit = least_squares(lambda q, y=y: q[0] * np.cos(q[1] * t + q[2]) - y, truth, xtol=1e-14,
                            ftol=1e-14)
        est.append(fit.x[1])
    spread = np.std(est)
    bound = frequency_bound(t, [4.0], [1.0], [0.3], sigma**2)[0]
    # 400 draws: the sample standard deviation is within ~7 % of the true one (2 sigma)
    assert spread == pytest.approx(bound, rel=0.1)


def test_two_close_tones_are_harder_than_one():
    t = np.arange(400) * 0.01
    alone = frequency_bound(t, [10.0], [1.0], [0.0], 0.01)[0]
    pair = frequency_bound(t, [10.0, 11.0], [1.0, 1.0], [0.0, 0.5], 0.01)
    far = frequency_bound(t, [10.0, 60.0], [1.0, 1.0], [0.0, 0.5], 0.01)
    assert pair[0] > 1.2 * alone
    assert far[0] == pytest.approx(alone, rel=0.05)


def test_bad_input_is_refused_by_name():
    t = np.arange(100) * 0.01
    with pytest.raises(ValueError, match="amplitudes must be nonzero"):
        frequency_bound(t, [3.0], [0.0], [0.0], 1.0)
    with pytest.raises(ValueError, match="noise_variance"):
        frequency_bound(t, [3.0], [1.0], [0.0], 0.0)
    with pytest.raises(ValueError, match="times: 2 samples"):
        frequency_bound(t[:2], [3.0], [1.0], [0.0], 1.0)
    with pytest.raises(ValueError, match="singular"):
        frequency_bound(t, [3.0, 3.0], [1.0, 1.0], [0.0, 0.0], 1.0)
    with pytest.raises(ValueError, match="amplitudes"):
        frequency_bound(t, [3.0, 4.0], [1.0], [0.0, 0.0], 1.0)
    with pytest.raises(ValueError, match="n must be"):
        single_tone_bound(1, 0.1, 1.0, 1.0)
    with pytest.raises(ValueError, match="amplitude"):
        single_tone_bound(10, 0.1, 0.0, 1.0)
    with pytest.raises(ValueError, match="step"):
        single_tone_bound(10, -0.1, 1.0, 1.0)
