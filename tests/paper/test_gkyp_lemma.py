import numpy as np
import pytest
from numpy.testing import assert_allclose

from fdsc import LTISystem, band_peak, sigma_max
from fdsc.paper.reproduced.gkyp_lemma import (
    GainBandTable,
    GammaSlip,
    GammaSquaredCheck,
    gain_band_table,
    gamma_vs_gamma_squared,
    in_band_gamma_slip,
    record_part,
    windowed_tone_ratio,
)
from fdsc.paper.shared.data import aircraft, paper_bands, paper_gains
from fdsc.paper.shared.names import GAIN_ORDER
from fdsc.paper.shared.results import RecordPart
from fdsc.paper.shared.verdict import VERDICTS


def _check_part(part, ids):
    assert isinstance(part, RecordPart)
    assert [e["id"] for e in part.entries] == ids
    for e in part.entries:
        assert {"id", "source", "paper", "recomputed", "verdict", "note"} <= e.keys()
        assert e["verdict"] in VERDICTS


@pytest.fixture(scope="module")
def table():
    return gain_band_table()


def test_gain_band_table_is_lossless(table):
    assert isinstance(table, GainBandTable)
    assert len(table.pairs) == 16
    assert [(p.gain, p.band) for p in table.pairs[:4]] == [("K_f1", b) for b in ("LF", "MF", "HF", "EF")]
    # the gKYP lemma is lossless: certificate and sweep agree, every certificate is strict
    assert table.worst_rel_diff < 1e-4
    assert table.max_max_eig < 0
    for p in table.pairs:
        assert p.rel_diff == pytest.approx((p.lmi_gamma - p.peak) / p.peak, rel=1e-12)
        assert p.slowest_pole < 0 and p.fastest_pole <= p.slowest_pole


def test_gain_band_table_against_an_independent_sweep(table):
    # a dense grid (no refinement) can only undershoot the refined peak, and by little
    plant, gains = aircraft(), paper_gains()
    w = np.concatenate([[0.0], np.geomspace(1e-4, 1.0, 4001)])
    for name in GAIN_ORDER:
        grid_peak = sigma_max(plant.closed_loop(gains[name]), w).max()
        peak = table.pair(name, "LF").peak
        assert grid_peak <= peak * (1 + 1e-9)
        assert grid_peak == pytest.approx(peak, rel=1e-4)


def test_gain_band_table_lookups(table):
    nested = table.by_gain_band("peak")
    assert list(nested) == list(GAIN_ORDER)
    assert nested["K_f2"]["MF"] == table.pair("K_f2", "MF").peak
    assert {"gain", "band", "peak", "lmi_gamma", "poles"} <= table.rows()[0].keys()
    with pytest.raises(KeyError, match="no pair"):
        table.pair("K_f1", "XF")


def test_gain_band_table_prose_and_display_rows(table):
    text = table.prose()
    assert text["n_pairs"] == "16"
    # the MF solves stop short of full accuracy (accepted: their certificates pass the check)
    assert text["short_bands"] == "MF" and text["n_short"] == "4"
    assert text["peak_K_f3_HF"] == "1.605" and text["kf3_slow_pole"].startswith("−0.01")
    rows = table.display_rows()
    assert len(rows) == 16 and all(isinstance(v, str) for r in rows for v in r.values())
    assert "status" not in rows[0]      # no solver strings on the page


def test_table_record_entries(table):
    part = table.to_record()
    _check_part(part, ["sigma_peak", "lemma1_gamma"])
    sigma_peak, lemma1 = part.entries
    # the printed bounds are judged once, in their own entries: these two carry no verdict on them
    assert sigma_peak["verdict"] == lemma1["verdict"] == "new"
    assert sigma_peak["paper"] is None and "verdicts" not in sigma_peak
    assert sigma_peak["printed_bounds"]["K_f2"] == {"MF": 0.4025}
    assert sigma_peak["recomputed"]["K_f3"]["HF"] == table.pair("K_f3", "HF").peak
    for e in part.entries:
        assert "The printed bounds" in e["note"] and "verdict" in e["note"]


def test_gamma_squared_not_gamma_bounds_the_energy_ratio():
    r = gamma_vs_gamma_squared()
    assert isinstance(r, GammaSquaredCheck)
    kf3 = r["K_f3"]
    assert kf3.simulated_ratio > kf3.gamma_lf  # statement (2) as printed fails
    assert kf3.simulated_ratio < kf3.gamma_sq
    assert not kf3.bound_gamma_holds and kf3.bound_gamma_sq_holds
    # a slowly windowed tone: energy ratio → |G(jω0)|²
    for t in r.tones:
        assert t.rel_to_tone_gain < 1e-3
    part = r.to_record()
    _check_part(part, ["lemma1_gamma_squared"])
    assert part.entries[0]["verdict"] == "differs"
    text = r.prose()
    assert (text["omega0"], text["tau"]) == ("0.5", "300")   # chosen parameters, as chosen
    assert text["ratio_K_f3"] == "1,072"


def test_gamma_vs_gamma_squared_rejects_an_out_of_band_tone():
    with pytest.raises(ValueError, match="omega0"):
        gamma_vs_gamma_squared(5.0)


def test_windowed_tone_ratio_of_a_first_order_lag():
    # |1/(jω + 2)|² = 1/(ω² + 4) at ω = 3: 1/13
    sys = LTISystem([[-2.0]], [[1.0]], [[1.0]], [[0.0]])
    r = windowed_tone_ratio(sys, 3.0, tau=40.0, dt=0.02)
    assert r.gain_sq == pytest.approx(1 / 13, rel=1e-12)
    assert r.ratio == pytest.approx(1 / 13, rel=1e-3)
    assert (r.omega0, r.tau, r.dt) == (3.0, 40.0, 0.02)


@pytest.mark.parametrize("kwargs, match", [
    ({"tau": -1.0, "dt": 0.1}, "tau"),
    ({"tau": 10.0, "dt": 0.0}, "dt"),
])
def test_windowed_tone_ratio_rejects_bad_numbers(kwargs, match):
    sys = LTISystem([[-2.0]], [[1.0]], [[1.0]], [[0.0]])
    with pytest.raises(ValueError, match=match):
        windowed_tone_ratio(sys, 1.0, **kwargs)


def test_windowed_tone_ratio_rejects_two_inputs():
    sys = LTISystem(-np.eye(2), np.eye(2), np.eye(2), np.zeros((2, 2)))
    with pytest.raises(ValueError, match="one input"):
        windowed_tone_ratio(sys, 1.0, tau=10.0, dt=0.1)


def test_in_band_gamma_slip_ratio_is_the_tone_gain_squared():
    r = in_band_gamma_slip()
    assert isinstance(r, GammaSlip)
    assert r.ratio == pytest.approx(r.gain_sq, rel=1e-3)
    assert r.gamma < r.ratio < r.gamma_sq
    assert r.excess == pytest.approx(r.ratio - r.gamma, rel=1e-15)
    # γ recomputed independently from the band peak of the printed K_f3 on Ω_3
    cl = aircraft().closed_loop(paper_gains()["K_f3"])
    assert_allclose(r.gamma, band_peak(cl, paper_bands()["HF"]).gamma, rtol=1e-12)
    assert_allclose(r.sigma_at_omega0, sigma_max(cl, [r.omega0])[0], rtol=1e-12)
    part = r.to_record()
    _check_part(part, ["gamma_slip_in_band"])
    assert part.entries[0]["verdict"] == "differs"
    assert r.prose()["omega0"] == "10.5" and r.prose()["gamma"] == "1.605"


@pytest.mark.parametrize("kwargs, match", [
    ({"omega0": 5.0}, "omega0"),
    ({"gain": "K_x"}, "gain"),
    ({"kind": "XF"}, "kind"),
])
def test_in_band_gamma_slip_rejects_bad_input(kwargs, match):
    with pytest.raises(ValueError, match=match):
        in_band_gamma_slip(**kwargs)


def test_record_part_ids():
    _check_part(record_part(), ["sigma_peak", "lemma1_gamma", "lemma1_gamma_squared",
                                "gamma_slip_in_band"])
