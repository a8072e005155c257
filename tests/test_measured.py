"""Supervisor.run_measured: the law run causally on sampled measurements, against the exact
engine (the plant's run is exact, the monitors converge at first order in the step), the
estimate's errors (a wrong model, a backward difference), and bad input by name."""

import warnings

import numpy as np
import pytest

from fdsc import (
    Band,
    EnergyOverflowError,
    Piecewise,
    Plant,
    Sinusoids,
    Supervisor,
    UnstableError,
    UnstableRunWarning,
    lqr_gain,
)

PLANT = Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
              [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.1]])
GAINS = [np.array([[-21.85, -22.27]]), np.array([[0.495, -1.473]])]
# slow, then fast, then slow again: two changes of the band that dominates
D = Piecewise([0.0, 20.0, 40.0, 80.0], [Sinusoids([1.0, 0.3], [0.2, 0.5]), Sinusoids([1.0], [12.0]),
                                        Sinusoids([1.0], [0.3])])
T = 60.0


@pytest.mark.parametrize("K0", [None, "lqr"])
def test_with_the_exact_derivative_it_takes_the_exact_engines_decisions(K0):
    sup = Supervisor(PLANT, GAINS, restart=10.0, K0=None if K0 is None else lqr_gain(PLANT))
    exact = sup.run(D, T, warmup=2.0)
    err = []
    for dt in (2e-3, 1e-3):
        run = sup.run_measured(D, T, dt, warmup=2.0)
        np.testing.assert_array_equal(run.switch_times, exact.switch_times)
        np.testing.assert_array_equal(run.sequence, exact.sequence)
        err.append(np.abs(run.mu - exact.mu).max() / exact.mu.max())
        if K0 is None:          # the plant's own run is exact along the same decisions
            assert run.energy == pytest.approx(exact.energy, rel=1e-9)
    assert exact.switches >= 2
    # the hold of ŵ is the only approximation: first order in the step
    assert 1.8 < err[0] / err[1] < 2.2 and err[1] < 1e-3


def test_a_candidate_held_throughout_is_the_fixed_run_of_the_plant_that_is_run():
    true_A = PLANT.A * 1.2
    sup = Supervisor(PLANT, GAINS)
    truth = Supervisor(Plant(true_A, PLANT.B1, PLANT.B2, PLANT.C, PLANT.D1, PLANT.D2), GAINS)
    for i in range(2):
        run = sup.run_measured(D, T, 1e-3, true_A=true_A, derivative="backward", hysteresis=1e12,
                               sigma0=i)
        assert run.switches == 0
        assert run.energy == pytest.approx(truth.prepare(D, T).fixed(i), rel=1e-9)
        assert run.energy != pytest.approx(sup.prepare(D, T).fixed(i), rel=1e-3)


def test_a_model_error_enters_the_estimate_through_the_state():
    # d = 0 from x0 ≠ 0: the exact model's estimate is 0 (monitors at rest), a wrong model's is
    # B1⁺ (A_t − A) x ≠ 0
    zero = Sinusoids([0.0], [1.0])
    sup = Supervisor(PLANT, GAINS)
    right = sup.run_measured(zero, 10.0, 1e-3, x0=[1.0, 0.0])
    wrong = sup.run_measured(zero, 10.0, 1e-3, x0=[1.0, 0.0], true_A=PLANT.A * 1.1)
    assert np.abs(right.mu).max() < 1e-24
    assert np.abs(wrong.mu).max() > 1e-4


def test_the_backward_difference_converges_to_the_exact_derivative():
    sup = Supervisor(PLANT, GAINS, restart=10.0, K0=lqr_gain(PLANT))
    gap = []
    for dt in (4e-3, 2e-3, 1e-3):
        a = sup.run_measured(D, T, dt, warmup=2.0)
        b = sup.run_measured(D, T, dt, warmup=2.0, derivative="backward")
        gap.append(np.abs(a.mu - b.mu).max() / a.mu.max())
    assert gap[0] > gap[1] > gap[2] and gap[2] < 0.02


def test_a_model_error_that_destabilizes_a_loop_is_reported():
    sup = Supervisor(PLANT, GAINS)
    with pytest.warns(UnstableRunWarning, match="true_A"):
        sup.run_measured(D, 4.0, 1e-3, true_A=PLANT.A + 30.0 * np.eye(2))


def test_a_model_error_within_the_loops_margins_is_silent():
    sup = Supervisor(PLANT, GAINS, K0=lqr_gain(PLANT))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        sup.run_measured(D, 4.0, 1e-3, true_A=PLANT.A * 0.9, derivative="backward")


@pytest.mark.parametrize("kwargs, match", [
    ({"dt": 0.03}, "dt must divide decide_every"),
    ({"dt": -1e-3}, "dt"),
    ({"derivative": "forward"}, "derivative"),
    ({"true_A": np.eye(3)}, "true_A"),
    ({"horizon": 4.05}, "whole number of decision intervals"),
    ({"d": Piecewise([0.0, 1.0005], [Sinusoids([1.0], [1.0])])}, "not a multiple of dt"),
    ({"d": Sinusoids([1.0], [4000.0])}, "Nyquist"),
    ({"sigma0": 2}, "sigma0"),
    ({"forgetting": 0.0}, "forgetting"),
    ({"x0": [1.0]}, "x0"),
])
def test_bad_input_is_refused_by_name(kwargs, match):
    args = {"d": D, "horizon": 4.0, "dt": 1e-3, **kwargs}
    with pytest.raises((ValueError, TypeError), match=match):
        Supervisor(PLANT, GAINS).run_measured(args.pop("d"), args.pop("horizon"), args.pop("dt"),
                                              **args)


def test_without_a_disturbance_the_exact_estimate_is_zero_and_nothing_switches():
    # d = 0 from x0 ≠ 0 with an exact model: ŵ is 0 up to rounding, which must not decide
    zero = Sinusoids([0.0], [1.0])
    for K0 in (None, lqr_gain(PLANT)):
        sup = Supervisor(PLANT, GAINS, K0=K0)
        run = sup.run_measured(zero, 10.0, 1e-3, x0=[2.0, -1.0])
        exact = sup.run(zero, 10.0, x0=[2.0, -1.0])
        assert run.switches == exact.switches == 0 and np.all(run.mu == 0.0)
        # the copies start from x0, as in the exact engine: the same run
        assert run.energy == pytest.approx(exact.energy, rel=1e-9)


def test_results_beyond_the_float_range_are_refused_by_name():
    # the engines run scaled, so the law decides; what the disturbance's units cannot hold
    # (here ∫d², the energies and the monitoring signals, all about 1e310) is refused by name
    huge = Piecewise(D.breaks, [Sinusoids(p.amplitudes * 1e155, p.frequencies, p.phases) for p in D.parts])
    sup = Supervisor(PLANT, GAINS, law="band_power", bands=[Band.lf(2.0), Band.hf(8.0)], restart=60.0)
    with pytest.raises(EnergyOverflowError, match="run_measured: .* exceeds the float range"):
        sup.run_measured(huge, 40.0, 1e-2, warmup=2.0)
    with pytest.raises(EnergyOverflowError, match="prepare: .* exceeds the float range"):
        sup.run(huge, 40.0, warmup=2.0)


def test_a_loop_that_overflows_is_refused_not_summarized():
    sup = Supervisor(PLANT, GAINS)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UnstableRunWarning)
        with pytest.raises(UnstableError, match="diverges"):
            sup.run_measured(D, 200.0, 1e-2, true_A=[[0.0, 1.0], [4.0, 2.0]])


def test_very_long_warmups_dwells_and_restarts_mean_never():
    sup = Supervisor(PLANT, GAINS, restart=1e300)
    assert sup.run_measured(D, 4.0, 1e-3, warmup=1e20).switches == sup.run(D, 4.0, warmup=1e20).switches == 0
    # the dwell counts from the last switch, not from t = 0: one switch at most
    a, b = sup.run_measured(D, 40.0, 1e-3, min_dwell=1e20), sup.run(D, 40.0, min_dwell=1e20)
    assert a.switches == b.switches == 1
