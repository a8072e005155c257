"""Reliability of the law on the disturbance estimate and its certificates at the edges: scale
(the exact and the measured engines decide and integrate the same way for a disturbance scaled
by any power of two the float range holds, and refuse by name what it cannot hold), the
stiffness check of stepped runs from the start, breaks off the grid at their absolute time,
the memory check of the exact engine, the min-switching law's forms at any scale, the plant
boundary (python-control plants, a contradictory ``n_disturbances``) and dwell margins for
very long dwells."""

import math
import warnings

import numpy as np
import pytest

import fdsc
from fdsc import (
    EnergyOverflowError,
    MemoryLimitError,
    Piecewise,
    Plant,
    Sinusoids,
    Supervisor,
    as_plant,
    periodic_dwell_margin,
    supervise,
)
from fdsc.min_switching import MinSwitchingCertificate

# the README's oscillator with its LF and HF designs
PLANT = Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
              [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.1]])
GAINS = [np.array([[-21.85, -22.27]]), np.array([[0.495, -1.473]])]
# slow, then fast, then slow: the law switches twice
D = Piecewise([0.0, 30.0, 60.0, 90.0], [Sinusoids([1.0, 0.4], [0.2, 0.35]), Sinusoids([1.0], [12.0]),
                                        Sinusoids([0.8], [0.25])])
T = 90.0
X0 = np.array([0.3, -0.2])


def scaled(d, k):
    """``d`` times 2^k (exact)."""
    if isinstance(d, Sinusoids):
        return Sinusoids(np.ldexp(d.amplitudes, k), d.frequencies, d.phases)
    return Piecewise(d.breaks, [scaled(p, k) for p in d.parts])


@pytest.fixture(scope="module")
def reference():
    sup = Supervisor(PLANT, GAINS)
    prep = sup.prepare(D, T, x0=X0)
    return sup, prep, prep.run(warmup=2.0)


# --- scale: the exact engine -------------------------------------------------------------------

@pytest.mark.parametrize("k", [-600, -800, -1000, 300])
def test_the_exact_law_decides_the_same_at_any_representable_scale(reference, k):
    sup, _prep, ref = reference
    r = sup.prepare(scaled(D, k), T, x0=np.ldexp(X0, k)).run(warmup=2.0)
    assert ref.switches == 2
    np.testing.assert_array_equal(r.switch_times, ref.switch_times)
    np.testing.assert_array_equal(r.sequence, ref.sequence)


@pytest.mark.parametrize("k", [-500, 250])
def test_the_exact_engines_results_scale_exactly(reference, k):
    sup, prep, ref = reference
    p = sup.prepare(scaled(D, k), T, x0=np.ldexp(X0, k))
    r = p.run(warmup=2.0)
    assert r.energy == pytest.approx(math.ldexp(ref.energy, 2 * k), rel=1e-12)
    assert r.input_energy == pytest.approx(math.ldexp(ref.input_energy, 2 * k), rel=1e-12)
    np.testing.assert_allclose(r.x_final, np.ldexp(ref.x_final, k), rtol=1e-12)
    np.testing.assert_allclose(r.mu, np.ldexp(ref.mu, 2 * k), rtol=1e-12, atol=0)
    # and every other result of the same engine
    assert p.fixed(1) == pytest.approx(math.ldexp(prep.fixed(1), 2 * k), rel=1e-12)
    e, choice = p.clairvoyant()
    e0, choice0 = prep.clairvoyant()
    assert choice == choice0 and e == pytest.approx(math.ldexp(e0, 2 * k), rel=1e-12)
    assert p.segment_law([0, 1, 0]) == pytest.approx(math.ldexp(prep.segment_law([0, 1, 0]), 2 * k),
                                                     rel=1e-12)
    loop = PLANT.closed_loop(fdsc.lqr_gain(PLANT))
    assert p.energy_of(loop) == pytest.approx(math.ldexp(prep.energy_of(loop), 2 * k), rel=1e-12)
    sigma = prep.decide(prep.mu(0.5), warmup=2.0)
    c, c0 = p.control(sigma), prep.control(sigma)
    assert c0["jumps"].size == 2
    np.testing.assert_allclose(c["jumps"], np.ldexp(c0["jumps"], k), rtol=1e-12)
    assert c["rms"] == pytest.approx(math.ldexp(c0["rms"], k), rel=1e-12)


def test_decide_on_the_public_signals_matches_the_run(reference):
    sup, _prep, ref = reference
    p = sup.prepare(scaled(D, -500), T, x0=np.ldexp(X0, -500))
    sigma = p.decide(p.mu(0.5), warmup=2.0)
    assert np.flatnonzero(np.diff(sigma)).size == 2
    np.testing.assert_array_equal((np.flatnonzero(np.diff(sigma)) + 1) * sup.decide_every,
                                  ref.switch_times)


def test_a_large_state_beside_a_small_disturbance_keeps_the_decisions(reference):
    # the monitors see ŵ only: their scale is ŵ's, not x0's
    sup, _prep, _ref = reference
    ref0 = sup.prepare(D, T).run(warmup=2.0)
    r = sup.prepare(scaled(D, -300), T, x0=np.ldexp(X0, 300)).run(warmup=2.0)
    np.testing.assert_array_equal(r.switch_times, ref0.switch_times)


def test_the_stepped_run_scales_too(reference):
    _sup, _prep, _ref = reference
    ref = supervise(PLANT, GAINS, D, T, 0.01, warmup=2.0, x0=X0)
    for k in (-700, -500):
        r = supervise(PLANT, GAINS, scaled(D, k), T, 0.01, warmup=2.0, x0=np.ldexp(X0, k))
        np.testing.assert_array_equal(r.switch_times, ref.switch_times)
    assert r.energy == pytest.approx(math.ldexp(ref.energy, -1000), rel=1e-12)
    assert r.input_energy == pytest.approx(math.ldexp(ref.input_energy, -1000), rel=1e-12)


@pytest.mark.parametrize("dt", [None, 0.01])
def test_an_input_energy_beyond_the_float_range_is_refused_beside_a_finite_output(dt):
    # a quiet output (z small against d) whose ∫d² overflows: refused by name, never inf
    quiet = Plant(PLANT.A, PLANT.B1, PLANT.B2, 1e-6 * PLANT.C, PLANT.D1, 1e-6 * PLANT.D2)
    d = Sinusoids([1.3e154], [0.2])
    with pytest.raises(EnergyOverflowError, match="∫d² exceeds the float range"):
        supervise(quiet, GAINS, d, 20.0, dt)


# --- scale: the measured engine ----------------------------------------------------------------

def test_the_measured_law_decides_the_same_at_any_representable_scale():
    sup = Supervisor(PLANT, GAINS)
    kw = dict(derivative="backward", true_A=1.1 * PLANT.A, warmup=2.0)
    ref = sup.run_measured(D, T, 0.01, x0=X0, **kw)
    assert ref.switches == 2
    for k in (-620, -900):
        r = sup.run_measured(scaled(D, k), T, 0.01, x0=np.ldexp(X0, k), **kw)
        np.testing.assert_array_equal(r.switch_times, ref.switch_times)
    r = sup.run_measured(scaled(D, -500), T, 0.01, x0=np.ldexp(X0, -500), **kw)
    assert r.energy == pytest.approx(math.ldexp(ref.energy, -1000), rel=1e-12)
    assert r.input_energy == pytest.approx(math.ldexp(ref.input_energy, -1000), rel=1e-12)
    np.testing.assert_allclose(r.mu, np.ldexp(ref.mu, -1000), rtol=1e-12)
    np.testing.assert_allclose(r.x_final, np.ldexp(ref.x_final, -500), rtol=1e-12)


def test_the_measured_input_energy_beyond_the_float_range_is_refused():
    quiet = Plant(PLANT.A, PLANT.B1, PLANT.B2, 1e-6 * PLANT.C, PLANT.D1, 1e-6 * PLANT.D2)
    with pytest.raises(EnergyOverflowError, match="run_measured: the disturbance's energy ∫d²"):
        Supervisor(quiet, GAINS).run_measured(Sinusoids([1.3e154], [0.2]), 20.0, 0.01)


# --- the stepped run's checks ------------------------------------------------------------------

STIFF = [np.array([[0.0, -300.0]]), GAINS[1]]      # its loop has a mode near −300 /s


def test_a_stiff_loop_excited_from_the_start_has_the_same_exact_energy_at_any_step():
    # a mode at −300 /s excited by x0 decays within a step of 0.01 s: a quadrature of the samples
    # misses it, the exact per-step energy does not (so no step-size warning is needed)
    kw = dict(x0=[1.0, 0.0], hysteresis=1e9)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        coarse = supervise(PLANT, STIFF, Sinusoids([1.0], [0.2]), 10.0, 0.01, **kw)
        fine = supervise(PLANT, STIFF, Sinusoids([1.0], [0.2]), 10.0, 0.0005, **kw)
    assert coarse.switches == fine.switches == 0
    assert coarse.energy == pytest.approx(fine.energy, rel=1e-9)


def test_an_off_grid_break_is_reported_at_its_absolute_time():
    d = Piecewise([0.0, 30.0, 60.005, 90.0], D.parts)
    with pytest.raises(ValueError, match=r"switches at t = 60\.005 s, which is not on the grid"):
        supervise(PLANT, GAINS, d, T, 0.01, warmup=2.0)


# --- memory ------------------------------------------------------------------------------------

@pytest.mark.parametrize("call", [
    lambda: Supervisor(PLANT, GAINS).prepare(D, 1e12),
    lambda: supervise(PLANT, GAINS, D, 1e12),
    lambda: Supervisor(PLANT, GAINS, decide_every=1e-9).prepare(D, 1e3),
])
def test_the_exact_engine_refuses_a_run_beyond_the_memory_limit_by_name(call):
    with pytest.raises(MemoryLimitError, match="decision intervals .* GiB"):
        call()


# --- the min-switching law at any scale --------------------------------------------------------

P1 = np.array([[2.0, 0.3], [0.3, 0.5]])
P2 = np.array([[0.6, -0.2], [-0.2, 1.7]])


def certificate(scale=1.0):
    return MinSwitchingCertificate((scale * P1, scale * P2), 1.0, 1.0, np.array([-1.0, -1.0]))


@pytest.mark.parametrize("x", [[1.0, 0.2], [0.1, 1.0], [-1.0, 0.9]])
@pytest.mark.parametrize("s", [1e-200, 1e200, 1e-320])
def test_choose_does_not_depend_on_the_states_norm(x, s):
    c = certificate()
    want = int(np.argmin([np.array(x) @ p @ np.array(x) for p in (P1, P2)]))
    assert c.choose(np.array(x) * s) == want


@pytest.mark.parametrize("scale", [1e-250, 1e250])
def test_choose_and_law_weights_do_not_depend_on_a_common_scale_of_the_forms(scale):
    c = certificate(scale)
    x = np.array([0.1, 1.0])
    assert c.choose(x) == 0 and c.choose([1.0, 0.2]) == 1
    W = c.law_weights()
    assert 0.5 <= max(float(np.abs(w).max()) for w in W) < 1.0
    xi = np.r_[np.zeros(2), x]                      # [ẋ; x]: the law picks the largest score
    assert int(np.argmax([xi @ w @ xi for w in W])) == 0


# --- the plant boundary ------------------------------------------------------------------------

def _ss():
    control = pytest.importorskip("control")
    p = PLANT
    return control.ss(p.A, np.hstack([p.B1, p.B2]), p.C, np.hstack([p.D1, p.D2]))


def test_supervise_takes_a_python_control_plant_with_the_disturbance_first():
    want = supervise(PLANT, GAINS, D, T, warmup=2.0)
    got = supervise(_ss(), GAINS, D, T, warmup=2.0)
    np.testing.assert_array_equal(got.switch_times, want.switch_times)
    assert got.energy == want.energy


def test_a_python_control_plant_with_one_input_is_refused_by_name():
    control = pytest.importorskip("control")
    one = control.ss(PLANT.A, PLANT.B1, PLANT.C, PLANT.D1)
    with pytest.raises(ValueError, match="n_disturbances must be below the number of inputs 1"):
        Supervisor(one, GAINS)


@pytest.mark.parametrize("plant", [PLANT, (PLANT.A, PLANT.B1, PLANT.B2, PLANT.C, PLANT.D1, PLANT.D2)])
def test_a_contradictory_n_disturbances_is_refused(plant):
    with pytest.raises(ValueError, match=r"n_disturbances must match the plant's 1 disturbance"):
        as_plant(plant, n_disturbances=2)
    assert as_plant(plant, n_disturbances=1).B1.shape == (2, 1)


# --- dwell margins for long dwells -------------------------------------------------------------

A1 = [[-1.0, 4.0], [0.0, -1.0]]
A2 = [[-1.0, 0.0], [4.0, -1.0]]


def test_a_long_dwell_gives_its_growth_rate_not_minus_infinity():
    with warnings.catch_warnings():
        warnings.simplefilter("error")              # no division by zero in a log
        m = periodic_dwell_margin([A1, A2], [0.5, 1e3, 1e5])
    assert np.all(np.isfinite(m.growth)) and np.all(np.isfinite(m.growth_worst))
    # e^{A τ} = e^{−τ} (I + 4τ N): the period's growth rate tends to −1 from above
    assert -1.0 < m.growth[2] < m.growth[1] + 1e-12 < -0.98
    short = periodic_dwell_margin([A1, A2], [0.5])
    # (the long dwells take every τ through the normalized squaring: equal to rounding)
    assert m.rho[0] == pytest.approx(short.rho[0], rel=1e-12)
    assert m.growth[0] == pytest.approx(short.growth[0], rel=1e-12)


@pytest.mark.parametrize("taus, match", [([0.5, 1e300], "taus must be short enough"),
                                         ([0.5, np.inf], "taus must have finite entries")])
def test_dwells_beyond_what_floats_represent_are_refused_by_name(taus, match):
    with pytest.raises(ValueError, match=match):
        periodic_dwell_margin([A1, A2], taus)
