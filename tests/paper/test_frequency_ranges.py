import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.integrate import quad

from fdsc import Band, Sinusoids
from fdsc.paper.reproduced.frequency_ranges import (
    DominanceVsRho,
    PaleyWienerTable,
    PiecewiseDominance,
    PsiWeights,
    dominance_vs_rho,
    localized_dominance_piecewise,
    out_of_band_fraction,
    paley_wiener_table,
    prop1_weight_check,
    psi_table,
    psi_weights,
    record_part,
    truncated_energy,
    truncated_spectrum,
)
from fdsc.paper.shared.results import RecordPart
from fdsc.paper.shared.verdict import VERDICTS

LF_SIGNAL = Sinusoids([1.0, 1.0, 1.0], [0.1, 0.2, 0.3])


def test_printed_products_in_closed_form():
    w = np.linspace(-30.0, 30.0, 601)
    r = prop1_weight_check(omega=w)
    # (ϖ − jω)(ϖ + jω) = ϖ² + ω² and (jω − ϖ)(jω + ϖ) = −ω² − ϖ² (expand by hand)
    assert_allclose(r["LF"].printed, 1.0 + w**2, rtol=1e-14, atol=1e-12)
    assert_allclose(r["HF"].printed, -(w**2) - 100.0, rtol=1e-14, atol=1e-12)
    # the weight [jω; 1]* Ψ [jω; 1] in closed form (frequency_ranges chapter, eq. psi-weight)
    assert_allclose(r["LF"].weight, 1.0 - w**2, rtol=1e-14, atol=1e-12)
    assert_allclose(r["MF"].weight, -(w - 1.0) * (w - 10.0), rtol=1e-14, atol=1e-12)
    assert_allclose(r["HF"].weight, w**2 - 100.0, rtol=1e-14, atol=1e-12)


def test_counts_match_explicit_masks():
    r = prop1_weight_check()
    w = r.omega
    # LF: printed > 0 everywhere, weight < 0 for |ω| > 1; HF: printed < 0, weight > 0 for |ω| > 10
    assert r["LF"].n_wrong_sign == np.sum(np.abs(w) > 1.0)
    assert r["HF"].n_wrong_sign == np.sum(np.abs(w) > 10.0)
    assert r["HF"].n_claim_fails == np.sum(np.abs(w) >= 10.0)
    # MF: the product is the weight, positive on [1, 10] only, negative on [−10, −1]
    assert r["MF"].n_wrong_sign == 0
    assert r["MF"].n_claim_fails == np.sum((w >= -10.0) & (w <= -1.0))
    assert r["MF"].n_in_band_negative == r["MF"].n_claim_fails
    assert r["MF"].n_in_band + r["MF"].n_out_of_band == w.size
    assert r["LF"].max_abs_diff == pytest.approx(2 * np.max(w**2), rel=1e-12)
    assert r.max_printed_diff == pytest.approx(2 * np.max(w**2), rel=1e-12)


@pytest.mark.parametrize("kind", ["LF", "MF", "HF"])
def test_corrected_factorizations_and_theorem1_tau_equal_the_weight(kind):
    r = prop1_weight_check(varpi_l=2.0, varpi_1=0.5, varpi_2=3.0, varpi_h=7.0)[kind]
    assert r.rel_diff_corrected <= 1e-12
    assert r.rel_diff_tau <= 1e-12


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
    table = paley_wiener_table((20.0, 200.0))
    assert isinstance(table, PaleyWienerTable)
    assert len(table.cases) == 4 and table.n_positive == 4
    assert all(0 < c.fraction_out < 0.05 for c in table.cases)
    assert table.horizons == (20.0, 200.0)
    for kind in ("LF", "HF"):
        assert table.min_fraction(kind) == min(c.fraction_out for c in table.cases if c.kind == kind)
    assert [r["T"] for r in table.rows()] == [20.0, 200.0, 20.0, 200.0]


@pytest.mark.parametrize("args, match", [
    ((Sinusoids([1.0], [1.0], [0.3]), 10.0, Band.lf(1.0)), "zero phases"),
    ((LF_SIGNAL, -1.0, Band.lf(1.0)), "T"),
    ((LF_SIGNAL, 10.0, Band.mf(1.0, 10.0)), "LF or HF"),
    ((LF_SIGNAL, 10.0, "LF"), "band"),
])
def test_out_of_band_fraction_rejects_bad_input(args, match):
    with pytest.raises((ValueError, TypeError), match=match):
        out_of_band_fraction(*args)


# -- typed results and what reaches the record ---------------------------------------------------

def _check_part(part, ids):
    assert isinstance(part, RecordPart)
    assert [e["id"] for e in part.entries] == ids
    for e in part.entries:
        assert {"id", "source", "paper", "recomputed", "verdict", "note"} <= e.keys()
        assert e["verdict"] in VERDICTS
        assert e["note"]


def test_psi_table_holds_the_three_ranges():
    t = psi_table()
    assert [r.kind for r in t.ranges] == ["LF", "MF", "HF"]
    # Ψ_MF = [[−1, jϖ_c], [−jϖ_c, −ϖ_1ϖ_2]], ϖ_c = 5.5 for the paper's MF band [1, 10]
    assert_allclose(t.ranges[1].psi, [[-1, 5.5j], [-5.5j, -10]], rtol=0, atol=1e-15)
    assert [r["complex"] for r in t.rows()] == ["no", "yes", "no"]


def test_sign_violations_against_explicit_masks():
    # a grid with points on the band edges and a planted mirror MF interval
    w = np.array([-20.0, -10.0, -5.0, -1.0, -0.5, 0.0, 0.5, 1.0, 5.0, 10.0, 20.0])
    r = psi_weights(w)
    assert isinstance(r, PsiWeights)
    # closed-form weights: 1 − ω², −(ω − 1)(ω − 10), ω² − 100; zero on the edges counts as neither
    assert_allclose(r["LF"].weight, 1 - w**2, rtol=1e-14, atol=1e-12)
    assert r.n_sign_violations == 0
    # MF for ω < 0 in band is negative but excluded by the rule; counting it would add 3 points
    assert int(np.sum((r["MF"].weight < 0) & (np.abs(w) >= 1) & (np.abs(w) <= 10))) == 3
    # −(ω² + ϖ_1ϖ_2) is largest at ω = 0
    assert r.mf_real_max == pytest.approx(-10.0, rel=1e-15)
    assert r.mf_product == 10.0


def test_psi_weights_record_entry():
    part = psi_weights().to_record()
    _check_part(part, ["psi_weight_sign"])
    e = part.entries[0]
    assert e["verdict"] == "match"
    assert e["recomputed"]["sign_violations"] == {"LF": 0, "MF": 0, "HF": 0}


def test_prop1_factorizations_record_entry():
    part = prop1_weight_check().to_record()
    _check_part(part, ["prop1_factorizations"])
    e = part.entries[0]
    assert e["verdict"] == "differs"
    assert e["recomputed"]["LF"]["wrong_sign"] == 480  # |ω| > 1 on the default grid
    assert e["recomputed"]["corrected_max_rel_diff"] < 1e-12


def test_dominance_vs_rho_matches_the_closed_form():
    rhos = (0.0, 0.2, 0.5)
    r = dominance_vs_rho(rhos, horizon=200.0)
    assert isinstance(r, DominanceVsRho)
    # three unit HF tones and three LF tones of amplitude ρ: α(Ω_3) = 3 / (3 + 3ρ²)
    assert_allclose(r.exact, 1 / (1 + np.square(rhos)), rtol=1e-14)
    assert r.max_fft_error < 5e-3  # a 200 s record: leakage of the 0.1 rad/s tone
    _check_part(r.to_record(), ["alpha_mixed"])
    assert r.to_record().entries[0]["verdict"] == "new"


@pytest.mark.parametrize("rhos, match", [((-0.1,), "rho_p"), ((np.nan,), "rhos")])
def test_dominance_vs_rho_rejects_bad_rho(rhos, match):
    with pytest.raises(ValueError, match=match):
        dominance_vs_rho(rhos, horizon=10.0)


def test_localized_dominance_segments():
    r = localized_dominance_piecewise(0.5, T=100.0, window_length=20.0, hop=2.0)
    assert isinstance(r, PiecewiseDominance)
    assert_allclose(r.breaks, [0.0, 100.0, 150.0, 250.0], rtol=0, atol=0)
    lf, hf = r.inside("LF"), r.inside("HF")
    assert not np.any(lf & hf)
    # windows of 20 s wholly in [100, 150]: centres in [110, 140]
    assert_allclose(r.t[lf].min(), 110.0, atol=r.hop)
    assert_allclose(r.t[lf].max(), 140.0, atol=r.hop)
    assert r.alpha_lf_in_lf > 0.99 and r.alpha_lf_in_hf < 1e-3
    # no MF tone: only the Hann window's leakage (of order 1e-4 for 20 s windows) reaches Ω_2
    assert_allclose(r.alpha["LF"][lf] + r.alpha["HF"][lf], 1.0, atol=1e-3)
    assert r.resolution == pytest.approx(2 * np.pi / 20.0, rel=1e-15)
    _check_part(r.to_record(), ["alpha_localized"])


def test_localized_dominance_without_a_whole_window_in_the_lf_segment_is_nan():
    r = localized_dominance_piecewise(0.1, T=100.0, window_length=20.0, hop=2.0)
    assert not r.inside("LF").any()
    assert np.isnan(r.alpha_lf_in_lf)


def test_localized_dominance_rejects_an_unknown_segment():
    r = localized_dominance_piecewise(0.5, T=100.0, window_length=20.0, hop=2.0)
    with pytest.raises(ValueError, match="segment"):
        r.inside("MF")


def test_paley_wiener_record_entry():
    part = paley_wiener_table((50.0,)).to_record()
    _check_part(part, ["paley_wiener_share"])
    assert set(part.entries[0]["recomputed"]) == {"LF", "HF"}


def test_record_part_ids():
    part = record_part()
    _check_part(part, ["psi_weight_sign", "prop1_factorizations", "paley_wiener_share",
                       "alpha_mixed", "alpha_localized"])
    assert part.figures == {}
