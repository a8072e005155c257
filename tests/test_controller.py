"""fdsc.controller: controllers with states, against the frequency-domain algebra of the loop
they close, the static gain as their special case, and as candidates of the law on the estimate
(copies that carry their controllers' states, the direct realization on the shared state, runs
on sampled measurements, copies on an estimate with errors); bad input by name."""

import numpy as np
import pytest

import fdsc
from fdsc import (
    Band,
    Controller,
    DimensionError,
    Piecewise,
    Plant,
    Sinusoids,
    Supervisor,
    as_controller,
    band_peak,
    freqresp,
    lqr_gain,
    shift_signal,
    simulate_stream,
    switched_loops,
)

# the README's oscillator with its LF and HF designs
PLANT = Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
              [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.1]])
GAINS = [np.array([[-21.85, -22.27]]), np.array([[0.495, -1.473]])]
D = Piecewise([0.0, 20.0, 40.0, 80.0], [Sinusoids([1.0, 0.3], [0.2, 0.5]), Sinusoids([1.0], [12.0]),
                                        Sinusoids([1.0], [0.3])])
T = 60.0


def filtered(K1, dK, wc, name=""):
    """u = K1 x + dK (x − x_f), ẋ_f = wc (x − x_f): K1 well below wc, K1 + dK well above."""
    n = np.shape(K1)[1]
    return Controller(-wc * np.eye(n), wc * np.eye(n), -np.asarray(dK), np.asarray(K1) + dK, name=name)


DYN = filtered(GAINS[0], GAINS[1] - GAINS[0], 3.0, "LF gain below 3 rad/s, HF gain above")


def _loop_response(plant, K_of_w, omega):
    """G(jω) = (C + D2 K) (jω − A − B2 K)⁻¹ B1 + D1 with K = K(jω): the loop's algebra."""
    out = []
    for w, K in zip(omega, K_of_w, strict=True):
        M = 1j * w * np.eye(plant.n_states) - plant.A - plant.B2 @ K
        out.append((plant.C + plant.D2 @ K) @ np.linalg.solve(M, plant.B1) + plant.D1)
    return np.array(out)


def test_the_closed_loop_of_a_controller_is_the_loop_algebra_at_every_frequency():
    rng = np.random.default_rng(3)
    n, m = 3, 2                      # two controls, three outputs, one disturbance
    plant = Plant(fdsc.random_hurwitz(rng, n), rng.normal(size=(n, 1)), rng.normal(size=(n, m)),
                  rng.normal(size=(3, n)), rng.normal(size=(3, 1)), rng.normal(size=(3, m)))
    c = Controller(fdsc.random_hurwitz(rng, 2), rng.normal(size=(2, n)), rng.normal(size=(m, 2)) * 0.1,
                   rng.normal(size=(m, n)) * 0.1)
    omega = np.logspace(-2, 2, 7)
    loop = c.closed_loop(plant)
    assert loop.A.shape == (5, 5)
    np.testing.assert_allclose(freqresp(loop, omega), _loop_response(plant, c.response(omega), omega),
                               rtol=1e-9, atol=1e-12)


def test_a_static_gain_is_the_controller_without_states():
    c = Controller.static(GAINS[0])
    assert c.is_static and c.n_states == 0 and not c.reads_estimate
    ref, got = PLANT.closed_loop(GAINS[0]), PLANT.closed_loop(c)
    for a, b in zip((ref.A, ref.B, ref.C, ref.D), (got.A, got.B, got.C, got.D), strict=True):
        np.testing.assert_array_equal(a, b)
    np.testing.assert_array_equal(c.gain, GAINS[0])
    with pytest.raises(ValueError, match="has 2 states: it is not a gain"):
        DYN.gain  # noqa: B018


def test_the_filter_controller_has_the_lf_gain_below_and_the_hf_gain_above_its_corner():
    r = DYN.response([1e-4, 1e4])
    np.testing.assert_allclose(r[0].real, GAINS[0], rtol=1e-6)
    np.testing.assert_allclose(r[1].real, GAINS[1], rtol=1e-3)
    np.testing.assert_allclose(DYN.poles(), [-3.0, -3.0])


def test_band_peaks_take_the_loop_of_a_controller():
    # a controller whose states do not reach u (C = 0) is its direct gain
    quiet = Controller(-np.eye(2), np.eye(2), np.zeros((1, 2)), GAINS[1])
    for band in (Band.lf(1.0), Band.hf(10.0)):
        a = band_peak(PLANT.closed_loop(quiet), band).gamma
        assert a == pytest.approx(band_peak(PLANT.closed_loop(GAINS[1]), band).gamma, rel=1e-8)


def test_a_controller_reading_the_estimate_sees_d_through_it():
    c = Controller(-np.eye(1), np.zeros((1, 2)), [[1.0]], GAINS[0], E=[[2.0]], F=[[0.5]])
    assert c.reads_estimate and not c.is_static
    one, two = c.closed_loop(PLANT), c.closed_loop(PLANT, estimate_input=True)
    assert two.B.shape == (3, 2)
    np.testing.assert_allclose(one.B, two.B.sum(axis=1, keepdims=True))
    np.testing.assert_allclose(one.D, two.D.sum(axis=1, keepdims=True))


def test_switched_loops_share_the_state_and_each_is_its_controllers_loop():
    loops = switched_loops(PLANT, [GAINS[0], DYN])
    assert [lp.A.shape for lp in loops] == [(4, 4), (4, 4)]
    np.testing.assert_array_equal(loops[0].B, loops[1].B)     # the simulators' requirement
    omega = np.logspace(-1, 2, 5)
    np.testing.assert_allclose(freqresp(loops[0], omega), freqresp(PLANT.closed_loop(GAINS[0]), omega),
                               rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(freqresp(loops[1], omega), freqresp(PLANT.closed_loop(DYN), omega),
                               rtol=1e-9, atol=1e-12)
    static = switched_loops(PLANT, GAINS)
    np.testing.assert_array_equal(static[1].A, PLANT.closed_loop(GAINS[1]).A)


def test_a_statespace_from_x_to_u_is_a_controller():
    control = pytest.importorskip("control")
    c = as_controller(control.ss(DYN.A, DYN.B, DYN.C, DYN.D), PLANT)
    np.testing.assert_allclose(c.response([2.0]), DYN.response([2.0]))


@pytest.mark.parametrize(("call", "error", "match"), [
    (lambda: as_controller("K", PLANT), TypeError, "controller must be a gain"),
    (lambda: as_controller(PLANT.closed_loop(GAINS[0]), PLANT), TypeError, "found an LTISystem"),
    (lambda: as_controller(np.ones((2, 2)), PLANT, "gains[1]"), DimensionError, "gains\\[1\\]"),
    (lambda: as_controller(Controller.static(np.ones((1, 3))), PLANT), DimensionError,
     "must map the plant's 2 states"),
    (lambda: Controller(-np.eye(1), np.ones((1, 2)), np.ones((1, 1)), np.ones((1, 2)), E=[[1.0]]),
     ValueError, "E and F go together"),
    (lambda: Controller(-np.eye(2), np.ones((1, 2)), np.ones((1, 2)), np.ones((1, 2))), DimensionError,
     "B"),
    (lambda: Controller(-np.eye(1), np.ones((1, 2)), np.ones((1, 1)), [[np.nan, 0.0]]), ValueError, "D"),
    (lambda: Controller.static([[1.0, 0.0]], name=3), TypeError, "name must be a str"),
    (lambda: Supervisor(PLANT, [GAINS[0], Controller(np.eye(1), np.zeros((1, 2)), [[0.0]], GAINS[1])]),
     ValueError, "gains\\[1\\] must stabilize"),
    (lambda: Supervisor(PLANT, DYN), TypeError, "not one"),
])
def test_bad_controllers_are_refused_by_name(call, error, match):
    with pytest.raises(error, match=match):
        call()


@pytest.mark.parametrize("realization", ["direct", "copies"])
def test_a_controller_held_throughout_is_its_fixed_loop(realization):
    # from rest every copy equals the plant's run, so holding candidate i is its fixed loop
    K0 = None if realization == "direct" else lqr_gain(PLANT)
    prep = Supervisor(PLANT, [GAINS[0], DYN], K0=K0, restart=10.0).prepare(D, T)
    for i, c in enumerate((Controller.static(GAINS[0]), DYN)):
        assert prep.fixed(i) == pytest.approx(prep.energy_of(c), rel=1e-9)
    assert prep.energy_of(DYN) != pytest.approx(prep.energy_of(Controller.static(GAINS[0])), rel=1e-2)


def test_a_segment_law_among_controllers_carries_their_states_over_the_break():
    # piece 1 under the gain, piece 2 under the filter controller, against the stepping
    # simulator run piece by piece on the shared state (the filter's states ran during piece 1)
    d = Piecewise([0.0, 20.0, 40.0], [Sinusoids([1.0], [0.3]), Sinusoids([1.0], [12.0])])
    prep = Supervisor(PLANT, [GAINS[0], DYN]).prepare(d, 40.0)
    exact = prep.segment_law([0, 1])
    loops = switched_loops(PLANT, [GAINS[0], DYN])
    a = simulate_stream(loops[0], d, 20.0, 1e-3)
    b = simulate_stream(loops[1], shift_signal(d, 20.0), 20.0, 1e-3, x0=a.x_final)
    assert exact == pytest.approx(a.energy + b.energy, rel=1e-6)
    assert np.any(a.x_final[2:] != 0)


def test_the_law_switches_among_controllers_through_copies_and_stays_bounded():
    sup = Supervisor(PLANT, [DYN, GAINS[1]], K0=lqr_gain(PLANT), restart=10.0)
    run = sup.run(D, T, warmup=2.0)
    assert run.switches >= 1 and run.diverged_at is None and run.x_final.shape == (2,)
    prep = sup.prepare(D, T)
    assert run.energy < 5 * min(prep.fixed(0), prep.fixed(1))


@pytest.mark.parametrize("K0", [None, "lqr"])
def test_on_sampled_measurements_with_controllers_it_takes_the_exact_engines_decisions(K0):
    sup = Supervisor(PLANT, [DYN, GAINS[1]], restart=10.0, K0=None if K0 is None else lqr_gain(PLANT))
    exact = sup.run(D, T, warmup=2.0)
    run = sup.run_measured(D, T, 1e-3, warmup=2.0)
    np.testing.assert_array_equal(run.sequence, exact.sequence)
    np.testing.assert_array_equal(run.switch_times, exact.switch_times)
    assert run.x_final.shape == (2,)
    if K0 is None:
        assert run.energy == pytest.approx(exact.energy, rel=1e-9)
    else:
        assert run.energy == pytest.approx(exact.energy, rel=1e-2)


def test_run_measured_refuses_a_candidate_that_reads_the_estimate():
    reader = Controller(-np.eye(1), np.zeros((1, 2)), [[0.0]], GAINS[0], E=[[1.0]], F=[[0.0]])
    with pytest.raises(ValueError, match="reads ŵ directly"):
        Supervisor(PLANT, [reader, GAINS[1]]).run_measured(D, T, 1e-3)


def test_copies_on_an_exact_estimate_are_the_copies_on_d():
    sup = Supervisor(PLANT, [DYN, GAINS[1]], K0=lqr_gain(PLANT), restart=10.0)
    a = sup.prepare(D, T).run(warmup=2.0)
    b = sup.prepare(D, T, estimate=D).run(warmup=2.0)
    assert b.energy == pytest.approx(a.energy, rel=1e-9)
    np.testing.assert_array_equal(a.sequence, b.sequence)


def test_copies_on_a_noisy_estimate_feed_the_noise_to_the_plant():
    noise = Sinusoids([0.3, 0.3], [5.0, 40.0], [0.1, 0.7])
    noisy = Piecewise(D.breaks, [p + noise for p in D.parts])
    sup = Supervisor(PLANT, GAINS, K0=lqr_gain(PLANT), restart=10.0)
    real = sup.prepare(D, T, estimate=noisy)
    ideal = sup.prepare(D, T, estimate=noisy, copies_on_estimate=False)
    clean = sup.prepare(D, T)
    # holding a candidate: on the ideal copies the plant's run does not see the noise
    assert ideal.fixed(0) == pytest.approx(clean.fixed(0), rel=1e-9)
    assert real.fixed(0) > 1.01 * clean.fixed(0)
    # a fixed gain reads x only: no estimate reaches it; a controller reading ŵ feels the noise
    assert real.energy_of(Controller.static(GAINS[0])) == pytest.approx(clean.fixed(0), rel=1e-9)
    reader = Controller(-np.eye(1), np.zeros((1, 2)), [[0.0]], GAINS[0], E=[[0.0]], F=[[3.0]])
    assert real.energy_of(reader) > 1.01 * clean.energy_of(reader)
