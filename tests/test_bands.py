import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from fdsc import Band, BandError, band_from_spec

RNG_SEED = 1


def random_bands(rng, count):
    out = []
    for _ in range(count):
        w1 = float(rng.uniform(0.05, 50.0))
        out += [Band.lf(w1), Band.mf(w1, w1 * float(rng.uniform(1.01, 20.0))), Band.hf(w1)]
    return out


def test_psi_matrices_match_lemma_1():
    # reference: the three matrices printed under Lemma 1 with ϖ_l = 1, ϖ_1 = 1, ϖ_2 = 10, ϖ_h = 10
    assert_allclose(Band.lf(1.0).psi, [[-1, 0], [0, 1]], atol=0)
    assert_allclose(Band.mf(1.0, 10.0).psi, [[-1, 5.5j], [-5.5j, -10]], atol=0)
    assert_allclose(Band.hf(10.0).psi, [[1, 0], [0, -100]], atol=0)
    assert_allclose(Band.entire().psi, np.zeros((2, 2)), atol=0)
    assert_allclose(Band.lf(1.0).phi, [[0, 1], [1, 0]], atol=0)


@pytest.mark.parametrize("band", [Band.lf(1.0), Band.mf(1.0, 10.0), Band.hf(10.0)])
def test_psi_is_hermitian(band):
    assert_allclose(band.psi, band.psi.conj().T, atol=0)


def test_weight_closed_forms():
    w = np.linspace(-30, 30, 601)
    # closed forms from the proof of Proposition 1
    assert_allclose(Band.lf(2.0).weight(w), 4.0 - w**2, rtol=1e-14, atol=1e-12)
    assert_allclose(Band.mf(1.0, 10.0).weight(w), -(w - 1) * (w - 10), rtol=1e-14, atol=1e-12)
    assert_allclose(Band.hf(10.0).weight(w), w**2 - 100, rtol=1e-14, atol=1e-12)


def test_weight_equals_quadratic_form():
    # independent evaluation: v^* Ψ v with v = [jω, 1]^T
    for band in (Band.lf(1.3), Band.mf(0.7, 4.0), Band.hf(3.0)):
        for w in (-5.0, -0.3, 0.0, 0.9, 2.2, 7.0):
            v = np.array([1j * w, 1.0])
            assert_allclose(band.weight(w), (v.conj() @ band.psi @ v).real, atol=1e-12)


def test_weight_sign_inside_and_outside_random_bands():
    rng = np.random.default_rng(RNG_SEED)
    for band in random_bands(rng, 30):
        w = np.concatenate([np.geomspace(1e-3, 1e4, 2000), [band.lower, band.upper]])
        w = w[np.isfinite(w)]
        if band.kind != "MF":
            w = np.concatenate([w, -w])
        val = band.weight(w)
        scale = 1e-12 * max(1.0, band.lower**2, (band.upper if math.isfinite(band.upper) else 0) ** 2)
        inside = band.contains(w)
        assert np.all(val[inside] >= -scale), band
        assert np.all(val[~inside] <= scale), band


def test_mf_weight_negative_on_mirror_interval_and_real_part_negative():
    band = Band.mf(1.0, 10.0)
    w = np.linspace(1.5, 9.5, 50)
    assert np.all(band.weight(-w) < 0)
    assert np.all(band.real_weight(np.linspace(-100, 100, 401)) < 0)
    assert_allclose(band.real_weight(w), -(w**2 + 10.0), rtol=1e-14)


def test_contains_is_symmetric():
    b = Band.mf(1.0, 10.0)
    assert list(b.contains([-5.0, 5.0, 0.5, 11.0])) == [True, True, False, False]


def test_band_from_spec_round_trip():
    assert band_from_spec({"kind": "LF", "w_l": 1}) == Band.lf(1.0)
    assert band_from_spec({"kind": "HF", "w_h": 10}) == Band.hf(10.0)
    assert band_from_spec({"kind": "EF"}) == Band.entire()


@pytest.mark.parametrize(
    ("make", "match"),
    [
        (lambda: Band.mf(10.0, 1.0), "w_1 must be smaller than w_2"),
        (lambda: Band.mf(2.0, 2.0), "w_1 must be smaller than w_2"),
        (lambda: Band.lf(-1.0), "w_l must be a positive"),
        (lambda: Band.lf(float("nan")), "w_l must be a positive"),
        (lambda: Band.hf(0.0), "w_h must be a positive"),
        (lambda: Band.hf(float("inf")), "w_h must be a positive"),
        (lambda: Band.mf(1.0, float("inf")), "w_2 must be a positive"),
        (lambda: Band("XF", 0.0, 1.0), "kind must be one of"),
        (lambda: Band("LF", 0.0, math.inf), "LF band must have upper=finite"),
        (lambda: band_from_spec({"kind": "MF", "w_1": 1}), "lacks the key 'w_2'"),
        (lambda: band_from_spec({"kind": "BF"}), r"spec\['kind'\] must be one of"),
    ],
)
def test_bad_band_inputs(make, match):
    with pytest.raises(BandError, match=match):
        make()


def test_band_error_is_value_error():
    with pytest.raises(ValueError):
        Band.lf(0.0)
