import numpy as np
import pytest

from fdsc import LTISystem, Sinusoids
from fdsc.paper.gkyp_lemma import (
    gamma_vs_gamma_squared,
    in_band_gamma_slip,
    printed_bounds,
    windowed_tone_ratio,
)

LF_SIGNAL = Sinusoids([1.0, 1.0, 1.0], [0.1, 0.2, 0.3])


def test_printed_bounds_rows():
    rows = printed_bounds()
    assert [r["gain"] for r in rows] == ["K_f1", "K_f2", "K_f3", "K_e"]
    assert rows[1]["verdict"] == "close"  # K_f2: 0.4025 printed, 0.40279 recomputed


def test_gamma_squared_not_gamma_bounds_the_energy_ratio():
    rows = {r["gain"]: r for r in gamma_vs_gamma_squared()}
    kf3 = rows["K_f3"]
    assert kf3["simulated_ratio"] > kf3["gamma_lf"]  # statement (2) as printed fails
    assert kf3["simulated_ratio"] < kf3["gamma_sq"]
    # a slowly windowed tone: energy ratio → |G(jω0)|²
    for r in rows.values():
        assert abs(r["simulated_ratio"] - r["gain_at_omega0_sq"]) < 1e-3 * r["gain_at_omega0_sq"]


def test_windowed_tone_ratio_of_a_first_order_lag():
    # |1/(jω + 2)|² = 1/(ω² + 4) at ω = 3: 1/13
    sys = LTISystem([[-2.0]], [[1.0]], [[1.0]], [[0.0]])
    r = windowed_tone_ratio(sys, 3.0, tau=40.0, dt=0.02)
    assert r["gain_sq"] == pytest.approx(1 / 13, rel=1e-12)
    assert r["ratio"] == pytest.approx(1 / 13, rel=1e-3)


def test_windowed_tone_ratio_rejects_two_inputs():
    sys = LTISystem(-np.eye(2), np.eye(2), np.eye(2), np.zeros((2, 2)))
    with pytest.raises(ValueError, match="one input"):
        windowed_tone_ratio(sys, 1.0, tau=10.0, dt=0.1)


def test_in_band_gamma_slip_ratio_is_the_tone_gain_squared():
    r = in_band_gamma_slip()
    assert r["ratio"] == pytest.approx(r["gain_sq"], rel=1e-3)
    assert r["gamma"] < r["ratio"] < r["gamma_sq"]


def test_in_band_gamma_slip_rejects_an_out_of_band_tone():
    with pytest.raises(ValueError, match="omega0"):
        in_band_gamma_slip(omega0=5.0)
