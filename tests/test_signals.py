import numpy as np
import pytest
from numpy.testing import assert_allclose

from fdsc import Band, Sinusoids, dominance_degree, localized_dominance
from fdsc.paper.shared.data import lf_disturbance, mixed_disturbance, piecewise_disturbance


def test_derivative_matches_finite_difference():
    d = mixed_disturbance(0.3)
    t = np.linspace(0, 5, 11)
    h = 1e-6
    assert_allclose(d.derivative(t), (d(t + h) - d(t - h)) / (2 * h), rtol=1e-6, atol=1e-6)



@pytest.mark.parametrize("rho", [0.0, 0.1, 0.25, 0.5])
def test_mixed_dominance_closed_form_and_fft(rho):
    hf = Band.hf(10.0)
    exact = mixed_disturbance(rho).dominance(hf)
    assert_allclose(exact, 1 / (1 + rho**2), rtol=1e-14)  # three unit tones vs three of size ρ
    t = np.arange(0, 500, 2e-3)
    # Hann-tapered FFT of a 500 s record: leakage across the 1..10 rad/s gap is tiny
    assert_allclose(dominance_degree(mixed_disturbance(rho)(t), 2e-3, hf), exact, atol=1e-4)



def test_power_of_sum_of_sinusoids():
    d = Sinusoids([2.0, 1.0], [1.0, 3.0])
    t = np.linspace(0, 2000 * np.pi, 2_000_001)
    assert_allclose(np.mean(d(t) ** 2), d.power(), rtol=1e-4)



def test_piecewise_segments():
    d = piecewise_disturbance(500.0, 0.2, 0.1)
    assert_allclose(d.breaks, [0, 500, 600, 1100])
    t = np.array([100.0, 550.0, 700.0, 1200.0])
    assert list(d.segment_of(t)) == [0, 1, 2, -1]
    assert_allclose(d(t)[1], 0.1 * lf_disturbance()(np.array([550.0]))[0])
    assert d(t)[3] == 0.0



def test_localized_dominance_tracks_the_segments():
    dt = 2e-3
    d = piecewise_disturbance(500.0, 0.2, 0.1)
    t = np.arange(0, 1100, dt)
    loc = localized_dominance(d(t), dt, Band.lf(1.0), window_length=60.0, hop=10.0)
    half = loc.window_length / 2
    in_lf = (loc.t - half >= 500) & (loc.t + half <= 600)
    in_hf = (loc.t + half <= 500) | (loc.t - half >= 600)
    assert in_lf.any() and in_hf.any()
    assert np.all(loc.alpha[in_lf] > 0.99)
    assert np.all(loc.alpha[in_hf] < 1e-3)



@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda: Sinusoids([1, 2], [1.0]),
         r"frequencies: expected 2 entries but found 1 \(one per sinusoid\)"),
        (lambda: Sinusoids([1.0], [-1.0]), "frequencies must be >= 0"),
        (lambda: Sinusoids([1.0, 1.0], [1.0, 1.0]).dominance(Band.lf(2.0)), "distinct frequencies"),
        (lambda: mixed_disturbance(-0.1), "rho_p must be >= 0"),
        (lambda: piecewise_disturbance(0.0, 0.2, 0.1), "T must be a positive"),
        (lambda: dominance_degree(np.ones(100), 0.0, Band.lf(1.0)), "dt must be a positive"),
        (lambda: dominance_degree(np.ones((10, 2)), 0.1, Band.lf(1.0)),
         r"x must be a 1-D array, but found shape \(10, 2\)"),
        (lambda: dominance_degree(np.zeros(100), 0.1, Band.lf(1.0)), "identically zero"),
        (lambda: localized_dominance(np.ones(100), 0.1, Band.lf(1.0), window_length=100.0),
         "window_length must span"),
    ],
)
def test_bad_signal_inputs(call, match):
    with pytest.raises(ValueError, match=match):
        call()

