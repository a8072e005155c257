import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.integrate import quad

from fdsc import Band, Sinusoids
from fdsc.paper.frequency_ranges import (
    out_of_band_fraction,
    paley_wiener_table,
    prop1_weight_check,
    truncated_energy,
    truncated_spectrum,
)

LF_SIGNAL = Sinusoids([1.0, 1.0, 1.0], [0.1, 0.2, 0.3])


def test_printed_products_in_closed_form():
    w = np.linspace(-30.0, 30.0, 601)
    r = prop1_weight_check(omega=w)
    # (ϖ − jω)(ϖ + jω) = ϖ² + ω² and (jω − ϖ)(jω + ϖ) = −ω² − ϖ² (expand by hand)
    assert_allclose(r["LF"]["printed"], 1.0 + w**2, rtol=1e-14, atol=1e-12)
    assert_allclose(r["HF"]["printed"], -(w**2) - 100.0, rtol=1e-14, atol=1e-12)
    # the weight [jω; 1]* Ψ [jω; 1] in closed form (frequency_ranges chapter, eq. psi-weight)
    assert_allclose(r["LF"]["weight"], 1.0 - w**2, rtol=1e-14, atol=1e-12)
    assert_allclose(r["MF"]["weight"], -(w - 1.0) * (w - 10.0), rtol=1e-14, atol=1e-12)
    assert_allclose(r["HF"]["weight"], w**2 - 100.0, rtol=1e-14, atol=1e-12)


def test_counts_match_explicit_masks():
    r = prop1_weight_check()
    w = r["omega"]
    # LF: printed > 0 everywhere, weight < 0 for |ω| > 1; HF: printed < 0, weight > 0 for |ω| > 10
    assert r["LF"]["n_wrong_sign"] == np.sum(np.abs(w) > 1.0)
    assert r["HF"]["n_wrong_sign"] == np.sum(np.abs(w) > 10.0)
    assert r["HF"]["n_claim_fails"] == np.sum(np.abs(w) >= 10.0)
    # MF: the product is the weight, positive on [1, 10] only, negative on [−10, −1]
    assert r["MF"]["n_wrong_sign"] == 0
    assert r["MF"]["n_claim_fails"] == np.sum((w >= -10.0) & (w <= -1.0))
    assert r["LF"]["max_abs_diff"] == pytest.approx(2 * np.max(w**2), rel=1e-12)


@pytest.mark.parametrize("kind", ["LF", "MF", "HF"])
def test_corrected_factorizations_and_theorem1_tau_equal_the_weight(kind):
    r = prop1_weight_check(varpi_l=2.0, varpi_1=0.5, varpi_2=3.0, varpi_h=7.0)[kind]
    scale = np.max(np.abs(r["weight"]))
    assert r["max_abs_diff_corrected"] <= 1e-12 * scale
    assert r["max_abs_diff_tau"] <= 1e-12 * scale


@pytest.mark.parametrize("omega", [0.0, 0.1, 0.37, 2.0])
def test_truncated_spectrum_against_quadrature(omega):
    T = 40.0
    re = quad(lambda t: LF_SIGNAL(np.array([t]))[0] * np.cos(omega * t), 0, T, limit=400)[0]
    im = quad(lambda t: -LF_SIGNAL(np.array([t]))[0] * np.sin(omega * t), 0, T, limit=400)[0]
    assert_allclose(truncated_spectrum(LF_SIGNAL, T, [omega])[0], re + 1j * im, rtol=1e-9, atol=1e-9)


def test_truncated_energy_against_quadrature():
    T = 73.0
    ref = quad(lambda t: LF_SIGNAL(np.array([t]))[0] ** 2, 0, T, limit=400)[0]
    assert truncated_energy(LF_SIGNAL, T) == pytest.approx(ref, rel=1e-10)


def test_out_of_band_fraction_against_fft():
    # Parseval on a sampled, zero-padded record: an independent estimate of the same share.
    T, dt, n = 50.0, 0.01, 2**21
    t = np.arange(0.0, T, dt)
    x = np.zeros(n)
    x[: t.size] = LF_SIGNAL(t)
    power = np.abs(np.fft.rfft(x)) ** 2
    w = 2 * np.pi * np.fft.rfftfreq(n, dt)
    weights = np.where((w == 0) | (w == w[-1]), 1.0, 2.0)  # one-sided spectrum
    fft_share = np.sum((weights * power)[w > 1.0]) / np.sum(weights * power)
    assert out_of_band_fraction(LF_SIGNAL, T, Band.lf(1.0)) == pytest.approx(fft_share, rel=2e-2)


def test_out_of_band_fraction_of_a_full_period_tone_in_closed_form():
    # sin t on [0, 2π]: energy π; in-band share from the closed-form spectrum by quad
    d = Sinusoids([1.0], [1.0])
    T = 2 * np.pi
    low = quad(lambda w: abs(truncated_spectrum(d, T, [w])[0]) ** 2, 0, 3.0, limit=200)[0] / np.pi
    assert out_of_band_fraction(d, T, Band.lf(3.0)) == pytest.approx(1 - low / np.pi, rel=1e-8)


def test_paley_wiener_table_is_positive_for_every_horizon():
    rows = paley_wiener_table((20.0, 200.0))
    assert len(rows) == 4
    assert all(0 < r["fraction_out"] < 0.05 for r in rows)


@pytest.mark.parametrize("args, match", [
    ((Sinusoids([1.0], [1.0], [0.3]), 10.0, Band.lf(1.0)), "zero phases"),
    ((LF_SIGNAL, -1.0, Band.lf(1.0)), "T"),
    ((LF_SIGNAL, 10.0, Band.mf(1.0, 10.0)), "LF or HF"),
    ((LF_SIGNAL, 10.0, "LF"), "band"),
])
def test_out_of_band_fraction_rejects_bad_input(args, match):
    with pytest.raises((ValueError, TypeError), match=match):
        out_of_band_fraction(*args)
