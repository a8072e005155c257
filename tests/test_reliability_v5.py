"""Fifth bad-input probe, library cases: tones on the edges of the band, tones the window does not
resolve, trends and the Nyquist frequency in the identification of :class:`fdsc.PredictiveLaw`;
its defaults and an estimate that stops early; and the non-causal limit in other units of the
states and of z."""

import math
import warnings

import numpy as np
import pytest
from numpy.testing import assert_allclose

import fdsc.noncausal as nc
from fdsc import (
    Piecewise,
    Plant,
    PredictiveLaw,
    ResolutionWarning,
    Sinusoids,
    identify_tones,
    lq_data,
    noncausal_limit,
    tone_limit,
)
from fdsc._tones import _esprit
from fdsc.predictive import DEFAULT_RANK_TOL, EDGE_SHARE

# the oscillator of tests/test_predictive.py
P2 = Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
           [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.3]])
D2TONES = Sinusoids([1.0, 0.5], [3.0, 7.0])


def _window(step, n):
    """n + 1 sample times ending at 0."""
    return np.arange(-n, 1) * step


# --- A. a tone on an edge of the closed band --------------------------------------------------

@pytest.mark.parametrize("w0", [20.0, 1.0])
def test_identify_tones_keeps_a_clean_tone_on_an_edge_of_its_band(w0):
    # ESPRIT puts the tone within 1e-14 of the edge, on either side: before, 15 (upper) and 19
    # (lower) of the 36 windows came back empty
    t = _window(0.02, 100)
    for phi in 2 * np.pi * np.arange(36) / 36:
        est = identify_tones(np.sin(w0 * t + phi), 0.02, (1.0, 20.0))
        assert_allclose(est.frequencies, [w0], rtol=1e-12)
        assert_allclose(np.abs(est.coefficients), [1.0], rtol=1e-9)


@pytest.mark.parametrize(("edge", "inside"), [(20.0, 20.0 - 1e-4), (1.0, 1.0 + 1e-4)])
def test_the_law_identifies_a_tone_on_its_bands_edge_as_one_just_inside(edge, inside):
    # before: on sin(20t) the law lost the tone at a third of its updates and had 16.2 times the
    # energy of the known tones (1.79 times 1e-4 inside); on sin(t) 1.031 times (1.0001 inside)
    law = PredictiveLaw(P2, (1.0, 20.0), window=3.0, step=0.05)
    runs = {}
    for w in (edge, inside):
        d = Sinusoids([1.0], [w])
        runs[w] = law.run(d, 30.0), law.run_known(d, 30.0)
    assert runs[edge][0].mean_tones == runs[inside][0].mean_tones
    assert runs[edge][0].energy / runs[edge][1].energy == pytest.approx(
        runs[inside][0].energy / runs[inside][1].energy, rel=1e-3)


# --- B. what a window cannot resolve ------------------------------------------------------------

def test_two_tones_closer_than_the_window_resolves_are_separated_and_said_to_be_so():
    # before: one tone at 30.15 rad/s leaving 8e-5 of the power unexplained, without a word (the
    # split of the pair lies below rank_tol, above the samples' noise)
    t = _window(0.005, 400)
    y = np.sin(30.0 * t) + np.sin(30.3 * t + 0.5)
    with pytest.warns(ResolutionWarning, match=r"identify_tones: the tones at 30 and 30.3 rad/s are closer "
                                               r"than the window resolves \(2π/T = 3.142 rad/s"):
        est = identify_tones(y, 0.005, (10.0, 200.0))
    assert_allclose(est.frequencies, [30.0, 30.3], rtol=1e-10)     # noise-free: exact to rounding
    assert_allclose(np.abs(est.coefficients), [1.0, 1.0], rtol=1e-7)


def _three_tones(n):
    t = _window(0.05, n - 1)
    return np.sin(3.0 * t) + np.sin(7.0 * t + 1.0) + np.sin(11.0 * t + 2.0)


def test_a_window_too_short_for_max_tones_is_refused_by_name():
    # before: 16 samples of three tones gave two wrong tones (5.995, 10.92 rad/s) with a residual
    # of 3e-10 of the power
    with pytest.raises(ValueError, match=r"samples: at least 52 samples are needed \(for up to max_tones = "
                                         r"12 tones: a lag matrix .* 25 columns.*\), but found 16"):
        identify_tones(_three_tones(16), 0.05, (1.0, 60.0))
    with pytest.raises(ValueError, match=r"lags must be at least 2 max_tones \+ 1 = 25 .*, but found 10"):
        identify_tones(_three_tones(200), 0.05, (1.0, 60.0), lags=10)


def test_three_tones_within_a_short_windows_resolution_are_said_to_be_unresolved():
    # max_tones = 3 admits 16 samples, whose 0.75 s resolve 8.4 rad/s: the tones 4 apart are not
    with pytest.warns(ResolutionWarning, match=r"closer than the window resolves \(2π/T = 8.378 rad/s"):
        identify_tones(_three_tones(16), 0.05, (1.0, 60.0), max_tones=3)


@pytest.mark.parametrize("gap", [0.0, 1.0])
def test_a_tone_at_the_nyquist_frequency_is_said_to_be_undetermined(gap):
    # before: a unit tone sin(πt/step + 0.5) came back with amplitude 0.479 (= sin 0.5) silently;
    # 1 rad/s below π/step is still within π/T = 1.57 rad/s of it
    step = 0.01
    t = _window(step, 200)
    with pytest.warns(ResolutionWarning, match=r"within π/T = 1.571 rad/s of the Nyquist frequency "
                                               r"π/step = 314.159 rad/s"):
        identify_tones(np.sin((math.pi / step - gap) * t + 0.5), step, (1.0, math.pi / step))


def test_a_tone_well_below_the_nyquist_frequency_gets_no_warning():
    step = 0.01
    t = _window(step, 200)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        est = identify_tones(np.sin(0.9 * math.pi / step * t + 0.5), step, (1.0, math.pi / step))
    assert_allclose(np.abs(est.coefficients), [1.0], rtol=1e-9)


@pytest.mark.parametrize("a", [0.01, 0.1, 1.0, 100.0])
def test_a_quadratic_trend_does_not_move_the_frequencies(a):
    # a quadratic is within the fitted trend (degree 3); its second difference is a constant that,
    # below rank_tol, biased ESPRIT: before, 0.1 τ² moved the tone by 4.6e-5 rad/s
    t = _window(0.005, 400)
    est = identify_tones(np.sin(30.0 * t + 0.3) + a * t ** 2, 0.005, (10.0, 200.0))
    assert_allclose(est.frequencies, [30.0], rtol=1e-12)
    assert_allclose(np.abs(est.coefficients), [1.0], rtol=1e-9)


def test_on_noisy_samples_the_identification_is_the_laws_own():
    # noise above rank_tol / 100 leaves no direction below rank_tol that stands above it: the
    # second pass does not run and the tones are those the law identifies
    rng = np.random.default_rng(3)
    t = _window(0.005, 400)
    y = np.sin(30.0 * t) + 0.5 * np.sin(71.0 * t + 1.0) + 1e-3 * rng.standard_normal(t.size)
    est = identify_tones(y, 0.005, (10.0, 200.0))
    law = _esprit(y, 0.005, 10.0, 200.0, 12, 48, DEFAULT_RANK_TOL, EDGE_SHARE)
    assert_allclose(est.frequencies, law, rtol=0, atol=0)


# --- C. the law's defaults and an estimate that stops early ---------------------------------------

def test_the_laws_defaults_fit_any_band():
    # before: PredictiveLaw(plant, (1, 20)) refused its own default window of 2 s (16 samples at
    # the default step 0.1257 s)
    law = PredictiveLaw(P2, (1.0, 20.0))
    assert law.step == pytest.approx(math.pi / 25.0, rel=1e-15)
    assert law.window == pytest.approx(20 * law.step, rel=1e-15)
    assert PredictiveLaw(P2, (1.0, 100.0)).window == 2.0            # unchanged where 2 s fits
    assert law.run(D2TONES, 20.0).identifications > 0


def test_a_window_too_short_for_the_default_step_names_the_step():
    with pytest.raises(ValueError, match=r"window must hold at least 20 samples \(2.513 s at the default "
                                         r"step π/\(1.25·band\[1\]\) = 0.1257 s\), but found 2.0"):
        PredictiveLaw(P2, (1.0, 20.0), window=2.0)


def test_an_estimate_that_stops_before_the_horizon_is_refused_by_name():
    # before: from 5 s on the law read ŵ = 0 and reported 0.51 against 0.29 on the full estimate
    law = PredictiveLaw(P2, (1.0, 20.0), window=3.0, step=0.05)
    with pytest.raises(ValueError, match=r"estimate must cover \[0, 20\] s, where d acts within the "
                                         r"horizon 20 s, but its breaks span \[0, 5\] s"):
        law.run(D2TONES, 20.0, estimate=Piecewise([0.0, 5.0], [D2TONES]))
    # an estimate that stops where d stops covers it
    d = Piecewise([0.0, 5.0], [D2TONES])
    assert law.run(d, 20.0, estimate=d).energy == pytest.approx(law.run(d, 20.0).energy, rel=1e-12)


# --- D. the non-causal limit in other units of the states and of z ----------------------------------

def _in_states(p, scale):
    """The plant in the states x' = diag(scale) x."""
    T, Ti = np.diag(scale), np.diag(1.0 / np.asarray(scale))
    return Plant(T @ p.A @ Ti, T @ p.B1, T @ p.B2, p.C @ Ti, p.D1, p.D2)


def _in_z(p, c):
    """The plant with z in units 1/c times as large."""
    return Plant(p.A, p.B1, p.B2, p.C * c, p.D1 * c, p.D2 * c)


@pytest.mark.parametrize("scale", [(1e3, 1e-3), (1e6, 1e-6), (1e-8, 1.0)])
@pytest.mark.parametrize("H", [3.0, 10.0])
def test_the_limit_does_not_depend_on_the_units_of_the_states(scale, H):
    # before: diag(1e3, 1e-3) gave 2.2e-3 (H = 10) and 8.5e-2 (H = 3) too much, with only SciPy's
    # warning that its Lyapunov solver perturbed the equation; diag(1e6, 1e-6) and diag(1e-8, 1)
    # were refused for an ill-conditioned eigenbasis
    x0 = np.array([1.0, -0.5])
    ref = noncausal_limit(P2, D2TONES, H, x0=x0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        lim = noncausal_limit(_in_states(P2, scale), D2TONES, H, x0=np.asarray(scale) * x0)
    assert lim.energy == pytest.approx(ref.energy, rel=1e-12)
    t = [0.5, H / 2, H]
    got, want = lim.trajectory(t), ref.trajectory(t)
    assert_allclose(got["x"] / np.asarray(scale), want["x"], rtol=1e-9, atol=1e-12)
    for k in ("u", "z"):
        assert_allclose(got[k], want[k], rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize("scale", [(1e3, 1e-3), (1e6, 1e-6), (1e8, 1e-8)])
def test_the_tone_limit_does_not_depend_on_the_units_of_the_states(scale):
    # before: diag(1e6, 1e-6) was refused: "omega[0] = 0.1 lies on a pole of the plant"
    w = np.linspace(0.1, 10.0, 25)
    assert_allclose(tone_limit(_in_states(P2, scale), w), tone_limit(P2, w), rtol=1e-12)


@pytest.mark.filterwarnings("ignore:Input \"a\" has an eigenvalue pair:RuntimeWarning")
def test_an_end_condition_missed_is_said_in_fdscs_words(monkeypatch):
    # without the balancing, the scaled plant's Lyapunov solve perturbs its equation: the run then
    # misses P x(H) + ξ(H) = 0 by 0.15 of its size, which the limit now says itself
    monkeypatch.setattr(nc, "_state_scale", lambda A: np.ones(A.shape[0]))
    with pytest.warns(RuntimeWarning, match=r"noncausal_limit: the end condition P x\(H\) \+ ξ\(H\) = 0 is "
                                            r"met only to a relative"):
        noncausal_limit(_in_states(P2, (1e3, 1e-3)), D2TONES, 10.0)


@pytest.mark.parametrize("c", [1e-13, 1e-100, 1e60, 1e100])
def test_the_limit_does_not_depend_on_the_units_of_z(c):
    # before: z × 1e-13 (D2 = 3e-14) was refused, "D2 must have full column rank" (an absolute rank
    # floor); z × 1e60 "no stabilizing solution" (the Riccati solve at that scale)
    ref, lq = noncausal_limit(P2, D2TONES, 10.0).energy, lq_data(P2)
    plant = _in_z(P2, c)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert noncausal_limit(plant, D2TONES, 10.0).energy / c / c == pytest.approx(ref, rel=1e-12)
        assert_allclose(tone_limit(plant, [3.0]) / c / c, tone_limit(P2, [3.0]), rtol=1e-12)
    scaled = lq_data(plant)
    assert_allclose(scaled.K, lq.K, rtol=1e-12)
    assert_allclose(scaled.P / c / c, lq.P, rtol=1e-12)


@pytest.mark.parametrize("c", [1.0, 1e-13, 1e60])
def test_a_rank_deficient_d2_is_refused_in_any_units_of_z(c):
    # two controls, the second penalized 1e-14 of the first: rank one at any scale
    p = Plant(P2.A, P2.B1, np.hstack([P2.B2, P2.B2]), [[1.0, 0.0], [0.0, 0.0], [0.0, 0.0]],
              [[0.0], [0.0], [0.0]], [[0.0, 0.0], [0.3, 0.0], [0.0, 3e-15]])
    with pytest.raises(ValueError, match=r"plant: D2 must have full column rank .*, 3e-15 of the size of "
                                         r"z's map"):
        lq_data(_in_z(p, c))


def test_z_so_large_that_p_leaves_the_float_range_is_refused_by_name():
    with pytest.raises(ValueError, match=r"plant: the LQ quantity P leaves the float range in z's units"):
        lq_data(_in_z(P2, 1e200))
