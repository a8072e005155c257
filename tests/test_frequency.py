import math

import control
import numpy as np
import pytest
from numpy.testing import assert_allclose

from fdsc import Band, DimensionError, LTISystem, band_peak, freqresp, sigma_max
from fdsc.paper.shared.data import aircraft, paper_bands, paper_gains


def first_order(a=1.0):
    return LTISystem([[-a]], [[1.0]], [[1.0]], [[0.0]])


def test_sigma_max_first_order_closed_form():
    w = np.geomspace(1e-3, 1e3, 50)
    # |1/(jω + 2)| = 1/sqrt(ω² + 4)
    assert_allclose(sigma_max(first_order(2.0), w), 1 / np.sqrt(w**2 + 4), rtol=1e-13)


def test_freqresp_matches_python_control():
    p = aircraft()
    cl = p.closed_loop(paper_gains()["K_f1"])
    w = np.geomspace(1e-2, 1e3, 40)
    ref = control.ss(cl.A, cl.B, cl.C, cl.D).frequency_response(w)
    G = freqresp(cl, w)
    assert_allclose(G[:, :, 0].T, np.asarray(ref.complex)[:, 0, :], rtol=1e-10)


def test_band_peak_against_brute_force_on_aircraft():
    p = aircraft()
    for name, K in paper_gains().items():
        cl = p.closed_loop(K)
        for kind, band in paper_bands().items():
            pk = band_peak(cl, band)
            hi = band.upper if math.isfinite(band.upper) else 1e5
            lo = band.lower if band.lower > 0 else 1e-6
            w = np.concatenate([[0.0] if band.lower == 0 else [], np.geomspace(lo, hi, 200_000)])
            brute = sigma_max(cl, w).max()
            # refinement can only find more than the brute-force grid, and not much more
            assert pk.gamma >= brute * (1 - 1e-12), (name, kind)
            assert pk.gamma <= brute * (1 + 1e-4), (name, kind)
            assert band.contains(pk.omega) or math.isinf(pk.omega)


def test_band_peak_finds_far_resonance_in_hf():
    # lightly damped pair at 5000 rad/s plus a slow pole: the HF peak is the resonance
    wn, zeta = 5000.0, 0.01
    A = np.array([[0, 1, 0], [-(wn**2), -2 * zeta * wn, 0], [0, 0, -1.0]])
    sys = LTISystem(A, [[0.0], [wn**2], [1.0]], [[1.0, 0.0, 1.0]], [[0.0]])
    pk = band_peak(sys, Band.hf(10.0))
    assert abs(pk.omega - wn) / wn < 1e-3
    assert pk.gamma > 40  # ≈ 1/(2ζ) = 50


def test_band_peak_supremum_at_infinity():
    # G(s) = 2 - 1/(s + 1): |G| increases towards |D| = 2 as ω → ∞
    sys = LTISystem([[-1.0]], [[1.0]], [[-1.0]], [[2.0]])
    pk = band_peak(sys, Band.hf(1.0))
    assert pk.omega == math.inf
    assert_allclose(pk.gamma, 2.0, rtol=1e-14)


def test_band_peak_interior_of_mf():
    # G(s) = ω0² / (s² + 2ζω0 s + ω0²), resonance inside [1, 10]
    w0, z = 4.0, 0.05
    sys = LTISystem([[0, 1], [-(w0**2), -2 * z * w0]], [[0.0], [w0**2]], [[1.0, 0.0]], [[0.0]])
    pk = band_peak(sys, Band.mf(1.0, 10.0))
    # closed form: peak 1/(2ζ sqrt(1-ζ²)) at ω0 sqrt(1-2ζ²)
    assert_allclose(pk.gamma, 1 / (2 * z * math.sqrt(1 - z**2)), rtol=1e-9)
    assert_allclose(pk.omega, w0 * math.sqrt(1 - 2 * z**2), rtol=1e-5)


@pytest.mark.parametrize(
    ("call", "exc", "match"),
    [
        (lambda: sigma_max("not a system", [1.0]), TypeError, "sys must be an fdsc.LTISystem"),
        (lambda: sigma_max(first_order(), [[1.0, 2.0]]), DimensionError, "omega must be a 1-D array"),
        (lambda: sigma_max(first_order(), [np.nan]), ValueError, "omega must have finite entries"),
        (lambda: band_peak(first_order(), "LF"), TypeError, "band must be an fdsc.Band"),
        (lambda: band_peak(first_order(), Band.lf(1.0), n_grid=3), ValueError, "n_grid must be"),
    ],
)
def test_bad_frequency_inputs(call, exc, match):
    with pytest.raises(exc, match=match):
        call()


def test_steady_state_gains_equal_one_gain_per_disturbance_and_name_a_bad_one():
    from fdsc import steady_state_gain, steady_state_gains

    sys = aircraft().closed_loop(paper_gains()["K_f3"])
    rng = np.random.default_rng(2)
    tones = [(rng.uniform(0.1, 300.0, k), rng.uniform(0.1, 2.0, k)) for k in (1, 3, 6, 2)]
    many = steady_state_gains(sys, tones)
    assert many.shape == (4,)
    assert all(g == steady_state_gain(sys, w, a) for g, (w, a) in zip(many, tones, strict=True))
    with pytest.raises(ValueError, match=r"tones\[1\]: frequencies must be distinct"):
        steady_state_gains(sys, [tones[0], ([1.0, 1.0], [1.0, 1.0])])
    with pytest.raises(ValueError, match="at least one"):
        steady_state_gains(sys, [])
