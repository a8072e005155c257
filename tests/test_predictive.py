"""fdsc.predictive: the tone identification against known tones, the predictive law against the
non-causal limit (a bound it never passes, and a reference it reaches on held tones), its
static part against the fixed LTI loop it equals, and bad input by name."""

import math

import numpy as np
import pytest

from fdsc import (
    Controller,
    Piecewise,
    Plant,
    PredictiveLaw,
    Sinusoids,
    identify_tones,
    loop_energy,
    lq_data,
    noncausal_limit,
)

P2 = Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
           [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.3]])
BAND = (1.5, 20.0)


@pytest.mark.parametrize("seed", range(3))
def test_held_tones_are_identified_to_many_digits_beside_a_slow_drift(seed):
    rng = np.random.default_rng(seed)
    w = np.sort(rng.uniform(12.0, 180.0, 3))
    a = rng.uniform(0.5, 1.5, 3)
    ph = rng.uniform(0.0, 2 * np.pi, 3)
    t = np.arange(-400, 1) * 0.005
    y = np.sin(np.outer(t, w) + ph) @ a + 0.8 * np.sin(0.3 * t + 1.0)
    est = identify_tones(y, 0.005, (8.0, 250.0))
    np.testing.assert_allclose(est.frequencies, w, rtol=1e-5)
    # the coefficients at τ = 0: a_j sin(φ_j) = Re(c_j e^{0})·… , |c_j| = a_j
    np.testing.assert_allclose(np.abs(est.coefficients), a, rtol=1e-4)
    np.testing.assert_allclose(est(t), np.sin(np.outer(t, w) + ph) @ a, atol=2e-4)


def test_noise_alone_identifies_no_tone_above_the_rank_tolerance():
    # a quiet window: the lag covariance has no direction above the tolerance
    est = identify_tones(np.zeros(300), 0.01, (5.0, 100.0))
    assert est.frequencies.size == 0


def test_the_law_with_the_tones_known_reaches_the_limit_on_held_tones():
    d = Sinusoids([1.0, 0.5, 0.7], [0.2, 3.0, 7.0], [0.1, 0.5, 2.0])
    law = PredictiveLaw(P2, BAND, window=3.0, step=0.05)
    lim = noncausal_limit(P2, d, 300.0).energy
    assert law.run_known(d, 300.0).energy / lim == pytest.approx(1.0, abs=5e-3)
    assert law.run(d, 300.0).energy / lim == pytest.approx(1.0, abs=1e-2)


@pytest.mark.parametrize("seed", range(3))
def test_no_run_of_the_law_passes_the_non_causal_limit(seed):
    rng = np.random.default_rng(seed)
    parts = [Sinusoids(rng.uniform(0.3, 1.2, 3), np.r_[rng.uniform(0.1, 1.0), rng.uniform(2.0, 15.0, 2)],
                       rng.uniform(0, 2 * np.pi, 3)) for _ in range(3)]
    d = Piecewise([0.0, 20.0, 45.0, 80.0], parts)
    law = PredictiveLaw(P2, BAND, window=3.0, step=0.05)
    lim = noncausal_limit(P2, d, 80.0).energy
    for run in (law.run(d, 80.0), law.run_known(d, 80.0)):
        assert run.energy >= lim * (1 - 1e-10)


def test_without_tones_in_its_band_the_law_is_the_fixed_loop_of_its_static_part():
    # every tone below the band: no identification succeeds, u = K x + (K_d − R⁻¹B2ᵀψ(0)) ŵ
    d = Sinusoids([1.0, 0.6], [0.2, 0.5], [0.0, 1.0])
    law = PredictiveLaw(P2, (5.0, 20.0), window=3.0, step=0.05)
    lq = lq_data(P2)
    F = lq.K_d - lq.R_inv_B2T @ lq.psi_gain([0.0])[0]
    fixed = Controller(np.zeros((0, 0)), np.zeros((0, 2)), np.zeros((1, 0)), lq.K, E=np.zeros((0, 1)), F=F)
    run = law.run(d, 120.0)
    assert run.mean_tones == 0.0
    assert run.energy == pytest.approx(loop_energy(fixed.closed_loop(P2), d, 120.0), rel=1e-9)


def test_a_noisy_estimate_costs_energy_and_the_known_tones_do_not_read_it():
    d = Sinusoids([1.0, 0.7], [0.3, 6.0])
    noise = Sinusoids([0.05, 0.05], [9.0, 14.0])
    law = PredictiveLaw(P2, BAND, window=3.0, step=0.05)
    exact, noisy = law.run(d, 100.0), law.run(d, 100.0, estimate=d + noise)
    assert noisy.energy > exact.energy


@pytest.mark.parametrize("kw, match", [
    ({"band": (20.0, 5.0)}, r"band must have lo < hi"),
    ({"band": (1.0, 100.0), "step": 0.05}, r"above the Nyquist frequency"),
    ({"band": 5.0}, r"band must be a pair"),
    ({"window": 0.1, "step": 0.05}, r"window must hold at least 20 samples"),
    ({"update": 0.0}, r"update"),
    ({"max_tones": 0}, r"max_tones"),
    ({"rank_tol": 1.0}, r"rank_tol must lie in \(0, 1\)"),
])
def test_bad_settings_are_refused_by_name(kw, match):
    args = {"band": BAND, "step": 0.05} | kw
    with pytest.raises(ValueError, match=match):
        PredictiveLaw(P2, **args)


def test_bad_runs_and_samples_are_refused_by_name():
    law = PredictiveLaw(P2, BAND, window=3.0, step=0.05)
    with pytest.raises(TypeError, match=r"estimate must be an fdsc.Sinusoids"):
        law.run(Sinusoids([1.0], [1.0]), 10.0, estimate=np.ones(3))
    with pytest.raises(ValueError, match=r"x0: expected 2 entries"):
        law.run(Sinusoids([1.0], [1.0]), 10.0, x0=[0.0])
    with pytest.raises(ValueError, match=r"samples must have finite entries"):
        identify_tones([0.0] * 20 + [math.nan], 0.01, (5.0, 100.0))
    with pytest.raises(ValueError, match=r"samples: at least"):
        identify_tones(np.ones(5), 0.01, (5.0, 100.0))


# --- bad and edge input: a rank tolerance that finds nothing, bad times, extreme scales


def test_identify_tones_refuses_a_rank_tolerance_that_leaves_no_signal():
    y = np.sin(30.0 * np.arange(-400, 1) * 0.005)
    with pytest.raises(ValueError, match=r"rank_tol must lie in \(0, 1\)"):
        identify_tones(y, 0.005, (10.0, 200.0), rank_tol=2.0)


def test_the_tone_estimate_refuses_non_finite_times_by_name():
    est = identify_tones(np.sin(30.0 * np.arange(-400, 1) * 0.005), 0.005, (10.0, 200.0))
    with pytest.raises(ValueError, match=r"tau must have finite entries"):
        est([math.nan])


def test_tiny_samples_give_the_same_tones_and_huge_ones_a_named_overflow():
    from fdsc import EnergyOverflowError, EnergyUnderflowWarning

    t = np.arange(-400, 1) * 0.005
    y = np.sin(30.0 * t) + 0.5 * np.sin(47.0 * t)
    ref = identify_tones(y, 0.005, (10.0, 200.0))
    with pytest.warns(EnergyUnderflowWarning, match=r"residual's mean square"):
        tiny = identify_tones(1e-160 * y, 0.005, (10.0, 200.0))        # found 5 spurious tones
    np.testing.assert_allclose(tiny.frequencies, ref.frequencies, rtol=1e-12)
    np.testing.assert_allclose(tiny.coefficients, 1e-160 * ref.coefficients, rtol=1e-9)
    with pytest.raises(EnergyOverflowError, match=r"identify_tones: the residual"):
        identify_tones(1e300 * y, 0.005, (10.0, 200.0))                # returned no tone


def test_the_law_takes_the_same_decisions_at_any_scale_of_d():
    from fdsc import EnergyOverflowError, EnergyUnderflowWarning

    d = Sinusoids([1.0, 0.5], [3.0, 7.0])
    law = PredictiveLaw(P2, BAND, window=3.0, step=0.05)
    ref = law.run(d, 10.0)
    with pytest.warns(EnergyUnderflowWarning, match=r"PredictiveLaw: the energy"):
        tiny = law.run(d.scaled(1e-160), 10.0)                          # identified other tones
    assert tiny.mean_tones == ref.mean_tones
    assert tiny.energy == pytest.approx(1e-320 * ref.energy, rel=1e-3)
    small = law.run(d.scaled(1e-100), 10.0)
    assert small.energy == pytest.approx(1e-200 * ref.energy, rel=1e-9)
    for run in (law.run, law.run_known):                                 # LinAlgError, NaN
        with pytest.raises(EnergyOverflowError, match=r"PredictiveLaw: the energy exceeds"):
            run(d.scaled(1e200), 10.0)


@pytest.mark.parametrize("n, lags", [(12, 3), (50, 7), (481, 160), (3200, 160), (5, 1)])
def test_hankel_gram_is_the_lag_matrix_gram(n, lags):
    # the recurrence along the diagonals gives H.T @ H of the sliding-window lag matrix
    from fdsc._tones import _hankel_gram

    y = np.random.default_rng(n).standard_normal(n) + 3.0
    H = np.lib.stride_tricks.sliding_window_view(y, lags)
    G = H.T @ H
    assert np.allclose(_hankel_gram(y, lags), G, rtol=0, atol=1e-13 * np.max(np.abs(G)))
    assert np.array_equal(_hankel_gram(y, lags), _hankel_gram(y, lags).T)


def test_merged_terms_sum_equal_exponents_in_order():
    # terms of one exponent and anchor become one (their coefficients summed), the first
    # occurrence's place kept; a term anchored elsewhere stays apart; -0.0 is 0.0
    from fdsc._modal import Modal, _merged

    e = np.array([1j, -2 + 0j, 1j, -0.0 + 3j, 0.0 + 3j, 1j])
    a = np.array([False, False, False, False, False, True])
    g = np.arange(12, dtype=float).reshape(6, 2)
    ee, aa, gg = _merged(e, a, g)
    assert ee.tolist() == [1j, -2, 3j, 1j] and aa.tolist() == [False, False, False, True]
    assert gg.tolist() == [[4, 6], [2, 3], [14, 16], [10, 11]]
    # the Gram is unchanged by the merge (z is linear in the coefficients)
    G1 = Modal.gram(e, a, g + 1j, 0.7)
    G2 = Modal.gram(ee, aa, gg + np.array([[2j], [1j], [2j], [1j]]), 0.7)
    assert np.allclose(G1, G2, rtol=1e-13)
