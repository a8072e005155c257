"""fdsc.tuning: exact energies of fixed loops and the local search on them, against the
full-trajectory simulator, the block-exponential engine, a closed-form scalar optimum, and bad
input by name."""

import math

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from fdsc import (
    Controller,
    LTISystem,
    Piecewise,
    Plant,
    Sinusoids,
    loop_energy,
    random_hurwitz,
    simulate,
    time_grid,
    tune_controller,
)
from fdsc.tuning import _ClassEnergies

D = Piecewise([0.0, 7.3, 15.0, 22.0], [Sinusoids([1.0, 0.4], [0.7, 3.1], [0.2, 1.0]),
                                       Sinusoids([0.8], [9.0]), Sinusoids([0.5, 0.5], [0.3, 0.9])])


def test_the_exact_energy_is_the_simulators_at_a_fine_step():
    # no feedthrough: z is continuous across the breaks, where Simpson's rule would lose order
    loop = LTISystem(random_hurwitz(np.random.default_rng(2), 3), [[1.0], [0.5], [0.0]],
                     [[1.0, 0.0, 2.0]], [[0.0]])
    exact = loop_energy(loop, D, 22.0)
    run = simulate(loop, D, time_grid(22.0, 1e-3))
    assert exact == pytest.approx(run.energy(), rel=1e-7)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_the_eigenbasis_energies_are_the_block_exponentials(seed):
    rng = np.random.default_rng(seed)
    ds = [D, Sinusoids([1.0, 0.2], [0.5, 20.0]), Piecewise([0.0, 3.0, 9.5], [Sinusoids([1.0], [2.0]),
                                                                            Sinusoids([0.3], [0.1])])]
    hs = [22.0, 12.0, 9.5]
    loop = LTISystem(random_hurwitz(rng, 4), rng.normal(size=(4, 1)), rng.normal(size=(2, 4)),
                     rng.normal(size=(2, 1)))
    ce = _ClassEnergies(ds, hs)
    np.testing.assert_allclose(ce(loop), [loop_energy(loop, d, h) for d, h in zip(ds, hs, strict=True)],
                               rtol=1e-9)


def test_an_ill_conditioned_eigenbasis_falls_back_to_the_block_exponentials():
    # a Jordan-like block (eigenvectors nearly parallel): the closed form is not used
    loop = LTISystem([[-1.0, 1e4], [0.0, -1.0 - 1e-9]], [[0.0], [1.0]], [[1.0, 0.0]], [[0.0]])
    ce = _ClassEnergies([D], [22.0])
    assert ce(loop)[0] == pytest.approx(loop_energy(loop, D, 22.0), rel=1e-12)


def _mean_log_energy(plant, gain, ds, hs):
    """The tuning objective of a static gain, evaluated directly (one exact energy per draw)."""
    cl = plant.closed_loop(gain)
    return float(np.mean([math.log(loop_energy(cl, d, h)) for d, h in zip(ds, hs, strict=True)]))


def test_a_scalar_static_gain_tunes_to_the_one_dimensional_optimum():
    # ẋ = −x + d + u, z = [x; 0.5 u]: one gain k, the optimum found by a bounded scalar search on
    # the same exact objective. Compared: the optimal value, and the value the tuned gain achieves
    # (evaluated here, not as the search reports it); not the gain, which a local search pins only
    # to about the square root of its objective's tolerance
    plant = Plant([[-1.0]], [[1.0]], [[1.0]], [[1.0], [0.0]], [[0.0], [0.0]], [[0.0], [0.5]])
    ds, hs = [Sinusoids([1.0], [0.3]), Sinusoids([1.0], [2.0])], [40.0, 40.0]
    ref = minimize_scalar(lambda k: _mean_log_energy(plant, [[k]], ds, hs), bounds=(-20.0, 0.9),
                          method="bounded", options={"xatol": 1e-9})
    res = tune_controller(plant, ds, hs, [[[0.0]]])
    assert res.objective == pytest.approx(ref.fun, abs=1e-9) and res.objective < res.start_objectives[0]
    assert _mean_log_energy(plant, res.controller.gain, ds, hs) == pytest.approx(ref.fun, abs=1e-9)


def test_a_filtered_search_starts_where_the_static_one_ends_and_only_improves():
    plant = Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
                  [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.1]])
    ds = [D, Sinusoids([1.0], [12.0])]
    hs = [22.0, 15.0]
    static = tune_controller(plant, ds, hs, [[[-1.0, -1.0]]], maxiter=400)
    filt = tune_controller(plant, ds, hs, [static.controller.D], structure="filtered", corner=2.0,
                           maxiter=400)
    assert filt.start_objectives[0] == pytest.approx(static.objective, abs=1e-9)
    assert filt.objective <= static.objective
    low, high, wc = Controller.filtered_parameters(filt.controller)
    assert filt.controller.n_states == 2 and wc > 0


def test_a_cap_on_the_hinf_norm_holds_on_the_tuned_loop():
    plant = Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
                  [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.1]])
    free = tune_controller(plant, [D], [22.0], [[[-1.0, -1.0]]], maxiter=400)
    capped = tune_controller(plant, [D], [22.0], [[[-1.0, -1.0]]], hinf_cap=0.9 * free.hinf, maxiter=400)
    assert capped.hinf <= 0.9 * free.hinf * 1.01 and capped.objective >= free.objective


@pytest.mark.parametrize(("call", "error", "match"), [
    (lambda p: tune_controller(p, D, [22.0], [[[0.0]]]), TypeError, "disturbances must be a sequence"),
    (lambda p: tune_controller(p, [D], [22.0, 1.0], [[[0.0]]]), ValueError, "of one length"),
    (lambda p: tune_controller(p, [D], [22.0], []), ValueError, "starts must hold"),
    (lambda p: tune_controller(p, [D], [22.0], [[[0.0]]], structure="pid"), ValueError, "structure"),
    (lambda p: tune_controller(p, [D], [-1.0], [[[0.0]]]), ValueError, "horizons\\[0\\]"),
    (lambda p: tune_controller(p, ["d"], [1.0], [[[0.0]]]), TypeError, "disturbances\\[0\\]"),
    (lambda p: tune_controller(p, [D], [22.0], [[[0.0]]], hinf_cap=0.0), ValueError, "hinf_cap"),
    (lambda p: tune_controller(p, [D], [22.0], [Controller.filtered([[0.0]], [[1.0]], 1.0)]),
     ValueError, "starts from gains"),
    (lambda p: loop_energy(p.closed_loop([[0.0]]), D, 0.0), ValueError, "horizon"),
])
def test_bad_input_is_refused_by_name(call, error, match):
    plant = Plant([[-1.0]], [[1.0]], [[1.0]], [[1.0], [0.0]], [[0.0], [0.0]], [[0.0], [0.5]])
    with pytest.raises(error, match=match):
        call(plant)


# --- reliability: a tuned controller is never unstable, never unit-dependent, never above its cap

_P1 = Plant([[-1.0]], [[1.0]], [[1.0]], [[1.0], [0.0]], [[0.0], [0.0]], [[0.0], [0.5]])
_DS1 = [Sinusoids([1.0], [0.3]), Sinusoids([1.0], [2.0])]


def test_a_search_that_finds_no_stabilizing_controller_raises_naming_starts():
    from fdsc import UnstableError

    with pytest.raises(UnstableError, match=r"starts: no stabilizing controller"):
        tune_controller(_P1, _DS1, [40.0, 40.0], [[[10.0]]])     # 1 + 10 > 0: every start unstable


@pytest.mark.parametrize("factor", [1e-160, 1e150])
def test_the_tuned_gain_does_not_depend_on_the_disturbances_units(factor):
    # energies near 1e-320 were clipped at 1e-300: the objective went flat and the search stopped.
    # The gain tuned on the scaled draws, run on the draws as given, achieves the optimum tuned on
    # them (the gains themselves differ in their last digits: 6e-7 here, the search's resolution)
    a = tune_controller(_P1, _DS1, [40.0, 40.0], [[[0.0]]])
    b = tune_controller(_P1, [d.scaled(factor) for d in _DS1], [40.0, 40.0], [[[0.0]]])
    assert b.objective - a.objective == pytest.approx(2 * math.log(factor), abs=1e-8)
    achieved = _mean_log_energy(_P1, b.controller.gain, _DS1, [40.0, 40.0])
    assert achieved == pytest.approx(a.objective, abs=1e-8)


def test_an_unmeetable_hinf_cap_raises_instead_of_returning_a_controller_above_it():
    from fdsc import InfeasibleError

    # no gain makes ‖(s + 1 − k)⁻¹‖∞ with a 0.5 k u-penalty smaller than about 0.447
    with pytest.raises(InfeasibleError, match=r"hinf_cap: the search found no controller"):
        tune_controller(_P1, _DS1, [40.0, 40.0], [[[0.0]]], hinf_cap=0.01)


def test_a_zero_training_disturbance_is_refused_by_name():
    with pytest.raises(ValueError, match=r"disturbances\[1\] is zero"):
        tune_controller(_P1, [_DS1[0], Sinusoids([0.0], [1.0])], [40.0, 40.0], [[[0.0]]])


@pytest.mark.parametrize("x0, match", [([0.0, 1.0], r"x0: expected 1 entries"),
                                       ([math.nan], r"x0 must have finite entries")])
def test_loop_energy_refuses_a_bad_x0_by_name(x0, match):
    loop = _P1.closed_loop([[-1.0]])
    with pytest.raises(ValueError, match=match):
        loop_energy(loop, _DS1[0], 10.0, x0=x0)


# --- controllers that read x and ŵ: the feedforward's exact gains and the structures

_P2 = Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
            [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.3]])
_DS2 = [D, Sinusoids([1.0, 0.5], [12.0, 0.4])]
_HS2 = [22.0, 15.0]


def test_the_feedforwards_energies_are_exact_quadratics_in_its_gains():
    from fdsc._feedforward_tuning import Quadratic, with_feedforward

    ce = _ClassEnergies(_DS2, _HS2)
    fb = Controller.static([[-1.0, -1.5]])
    poles = [0.5, 5.0]

    def loop_of(g):
        return with_feedforward(fb, poles, g).closed_loop(_P2)

    quad = Quadratic(ce, loop_of, 3, step=[0.7, 2.0, 0.3])
    for g in np.random.default_rng(0).normal(size=(4, 3)):
        np.testing.assert_allclose(quad.energies(g), ce(loop_of(g)), rtol=1e-9)
    # the majorization–minimization ends at a stationary point of the mean log energy
    best = quad.minimize()

    def J(g):
        return float(np.mean(np.log(ce(loop_of(g)))))

    for i in range(3):
        for h in (1e-3, -1e-3):
            step = np.zeros(3)
            step[i] = h
            assert J(best + step) >= J(best) - 1e-12


def test_a_richer_feedforward_only_improves_and_reads_the_estimate():
    static = tune_controller(_P2, _DS2, _HS2, [[[-1.0, -1.5]]], maxiter=300)
    ff0 = tune_controller(_P2, _DS2, _HS2, [static.controller.D], feedforward="static", maxiter=300)
    ff2 = tune_controller(_P2, _DS2, _HS2, [static.controller.D], feedforward=[0.5, 5.0], maxiter=300)
    assert ff2.objective <= ff0.objective <= static.objective
    assert ff0.controller.reads_estimate and ff0.controller.n_states == 0
    assert ff2.controller.n_states == 2
    np.testing.assert_allclose(np.sort(ff2.controller.poles().real), [-5.0, -0.5])


def test_a_held_feedback_part_tunes_only_the_feedforward():
    K = [[-1.0, -1.5]]
    res = tune_controller(_P2, _DS2, _HS2, [K], structure="held", feedforward=[1.0])
    np.testing.assert_array_equal(res.controller.D, K)
    assert res.controller.reads_estimate


@pytest.mark.parametrize("kw, match", [
    ({"feedforward": [-1.0]}, r"feedforward: the filter poles must be positive"),
    ({"feedforward": "dynamic"}, r"feedforward"),
    ({"feedforward": "static", "hinf_cap": 2.0}, r"hinf_cap applies to controllers that read x only"),
    ({"structure": "held"}, r"structure 'held' needs a feedforward"),
    ({"feedforward": [1.0, 1.0]}, r"feedforward: the filter poles must be distinct"),
    ({"feedforward": [1e-12]}, r"feedforward: the filter poles must lie above 1e-10"),
])
def test_bad_feedforward_settings_are_refused_by_name(kw, match):
    with pytest.raises(ValueError, match=match):
        tune_controller(_P2, _DS2, _HS2, [[[-1.0, -1.5]]], **kw)


def test_a_start_that_reads_the_estimate_is_refused():
    start = Controller(np.zeros((0, 0)), np.zeros((0, 2)), np.zeros((1, 0)), [[-1.0, -1.5]],
                       E=np.zeros((0, 1)), F=[[0.5]])
    with pytest.raises(ValueError, match=r"starts\[0\] reads ŵ"):
        tune_controller(_P2, _DS2, _HS2, [start], feedforward="static")
