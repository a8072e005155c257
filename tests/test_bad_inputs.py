"""Bad and edge inputs across the public API: each gets a named error that names the argument.

Every case is valid except for the one defect it probes, so that it exercises that defect's check
(not an earlier guard of the same function). Shape errors are ``DimensionError``; wrong values are
``ValueError`` (never a ``DimensionError``); loops that must be stable raise ``UnstableError``.
"""

import warnings

import numpy as np
import pytest

from fdsc import (
    Band,
    BandError,
    DimensionError,
    LTISystem,
    MemoryLimitError,
    Plant,
    SingularFrequencyError,
    Sinusoids,
    UnstableError,
    UnstableRunWarning,
    band_peak,
    dominance_degree,
    sigma_max,
)
from fdsc.energy import (
    fdeef,
    fdeef_autonomous,
    fdeef_parseval_autonomous,
    instantaneous_power,
    steady_state_power,
)
from fdsc.lmi import gkyp_gamma
from fdsc.paper.reproduced.stationary import stationary_runs
from fdsc.paper.reproduced.theorem1 import window_ratios
from fdsc.paper.shared.data import paper_disturbance, run_controller
from fdsc.simulate import particular, simulate, time_grid
from fdsc.switching import certify_q, design_q

TWO_BANDS = [Band.lf(1.0), Band.hf(10.0)]
OSC = LTISystem([[0.0, 1.0], [-1.0, 0.0]], [[0.0], [1.0]], [[1.0, 0.0]], [[0.0]])  # poles ±1j
STABLE = LTISystem([[-1.0, 0.0], [0.0, -2.0]], [[1.0], [1.0]], [[1.0, 0.0]], [[0.0]])
UNSTABLE = LTISystem([[1.0, 0.0], [0.0, -2.0]], [[1.0], [1.0]], [[1.0, 0.0]], [[0.0]])
Q2 = np.eye(2)
TONE = Sinusoids([1.0], [1.0])
T = time_grid(1.0, 0.01)
X = np.zeros((5, 2))
T5 = np.linspace(0.0, 1.0, 5)


def _run(name, d=TONE, t=T):
    return run_controller(name, d, t)


CASES = {
    # --- bands: typed limits, in range, Ψ representable ----------------------------------------
    "band limit underflows": (lambda: Band.lf(1e-200), BandError, r"w_l must lie in \[1e-100"),
    "band limit overflows": (lambda: Band.hf(1e200), BandError, r"w_h must lie in"),
    "band limit is a string": (lambda: Band.lf("1"), BandError, r"w_l must be a positive number"),
    "band limit is complex": (lambda: Band.mf(1j, 2.0), BandError, r"w_1 must be a positive number"),
    "raw band upper underflows": (lambda: Band("LF", 0.0, 1e-300), BandError, r"upper limit must lie"),
    "band kind unknown": (lambda: Band("XF", 0.0, 1.0), BandError, r"kind must be one of"),
    "weight at complex omega": (lambda: Band.lf(1.0).weight([1j]), ValueError, r"omega must be real"),
    # --- systems: real, finite, shapes named ----------------------------------------------------
    "complex A": (lambda: LTISystem([[1j]], [[1.0]], [[1.0]], [[0.0]]), ValueError,
                  r"A must be real, but found complex entries"),
    "NaN in B": (lambda: LTISystem([[-1.0]], [[np.nan]], [[1.0]], [[0.0]]), ValueError,
                 r"B must have finite entries"),
    "D of wrong shape": (lambda: LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0, 0.0]]), DimensionError,
                         r"D: expected shape \(1, 1\) but found \(1, 2\)"),
    "string entries in C": (lambda: LTISystem([[-1.0]], [[1.0]], [["a"]], [[0.0]]), ValueError,
                            r"C must be a numeric matrix"),
    "gain of wrong shape": (lambda: Plant([[-1.0]], [[1.0]], [[1.0]], [[1.0]], [[0.0]], [[0.0]])
                            .closed_loop([[1.0, 2.0]]), DimensionError, r"K: expected shape \(1, 1\)"),
    "boolean B2": (lambda: Plant([[-1.0]], [[1.0]], [[True]], [[1.0]], [[0.0]], [[0.0]]), ValueError,
                   r"B2 must be a numeric matrix, but found booleans"),
    # --- frequency sweeps: jω poles, stability of a gain --------------------------------------
    "pole on jω inside the sweep": (lambda: sigma_max(OSC, [0.5, 1.0]), SingularFrequencyError,
                                    r"undefined at ω = 1 rad/s"),
    "band peak of an unstable loop": (lambda: band_peak(UNSTABLE, Band.lf(1.0)), UnstableError,
                                      r"sys is not stable: A has the eigenvalue 1 "),
    "band peak, n_grid not an integer": (lambda: band_peak(STABLE, Band.lf(1.0), n_grid=100.5), ValueError,
                                         r"n_grid must be an integer >= 10"),
    "sigma_max of a 2-D omega": (lambda: sigma_max(STABLE, [[1.0, 2.0]]), DimensionError,
                                 r"omega must be a 1-D array"),
    # --- Lemma 1 and Theorem 1: stable loops only -----------------------------------------------
    "Lemma 1 on a loop with a pole at +1": (lambda: gkyp_gamma(UNSTABLE, Band.hf(10.0)), UnstableError,
                                            r"eigenvalue 1 with real part >= 0"),
    "Lemma 1 margin zero": (lambda: gkyp_gamma(STABLE, Band.lf(1.0), margin=0.0), ValueError,
                            r"margin must be a positive finite number"),
    "Theorem 1 with an unstable mode": (lambda: certify_q([STABLE, UNSTABLE], TWO_BANDS, [Q2, Q2]),
                                        UnstableError, r"modes\[1\] is not stable"),
    "Theorem 1, Q not a list": (lambda: certify_q([STABLE, STABLE], TWO_BANDS, Q2),
                                ValueError, r"Q must list one matrix per mode \(2\), found ndarray"),
    "Theorem 1, Q not positive definite": (lambda: certify_q([STABLE, STABLE], TWO_BANDS, [Q2, -Q2]),
                                           ValueError, r"Q must be positive definite"),
    "Remark 4 design, in_band out of range": (lambda: design_q([STABLE, STABLE], TWO_BANDS, 2),
                                              ValueError, r"in_band must be a mode index in \[0, 2\)"),
    "Remark 4 design, in_band a float": (lambda: design_q([STABLE, STABLE], TWO_BANDS, 0.5),
                                         ValueError, r"in_band must be an integer"),
    # --- FD-EEF / FD-EPF ------------------------------------------------------------------------
    "NaN in the states": (lambda: instantaneous_power(np.full((5, 2), np.nan), X, Band.lf(1.0), Q2),
                          ValueError, r"x must have finite entries"),
    "xdot of another shape": (lambda: instantaneous_power(X, np.zeros((4, 2)), Band.lf(1.0), Q2),
                              DimensionError, r"xdot: expected shape \(5, 2\) but found \(4, 2\)"),
    "NaN in the window times": (lambda: fdeef([0.0, np.nan, 0.5, 0.7, 1.0], X, X, Band.lf(1.0), Q2),
                                ValueError, r"t must have finite entries"),
    "window times of another length": (lambda: fdeef(np.linspace(0, 1, 6), X, X, Band.lf(1.0), Q2),
                                       DimensionError, r"t has 6 samples but x has 5 rows"),
    "complex initial state": (lambda: fdeef_autonomous(STABLE, [1j, 0.0], Band.lf(1.0), Q2), ValueError,
                              r"x0 must be real"),
    "initial state of wrong size": (lambda: fdeef_autonomous(STABLE, [1.0, 0.0, 0.0], Band.lf(1.0), Q2),
                                    DimensionError, r"x0: expected 2 entries but found 3"),
    "FD-EEF closed form, unstable A": (lambda: fdeef_autonomous(UNSTABLE, [1.0, 0.0], Band.lf(1.0), Q2),
                                       UnstableError, r"sys is not stable"),
    "FD-EEF by Parseval, unstable A": (
        lambda: fdeef_parseval_autonomous(UNSTABLE, [1.0, 0.0], Band.lf(1.0), Q2),
        UnstableError, r"sys is not stable"),
    "steady state of an unstable loop": (
        lambda: steady_state_power(UNSTABLE, TONE, Band.lf(1.0), Q2),
        UnstableError, r"a steady state needs"),
    "steady state, band not a Band": (lambda: steady_state_power(STABLE, TONE, "LF", Q2),
                                      TypeError, r"band must be an fdsc.Band"),
    # --- signals --------------------------------------------------------------------------------
    "complex amplitudes": (lambda: Sinusoids([1j], [1.0]), ValueError, r"amplitudes must be real"),
    "NaN time": (lambda: TONE([0.0, np.nan]), ValueError, r"t must have finite entries"),
    "phases of wrong length": (lambda: Sinusoids([1.0, 1.0], [1.0, 2.0], [0.0]), DimensionError,
                               r"phases: expected 2 entries but found 1"),
    "unknown paper disturbance": (lambda: paper_disturbance("MF"), ValueError,
                                  r"kind must be one of \('LF', 'HF'\), but found 'MF'"),
    "record of complex samples": (lambda: dominance_degree(np.ones(16) * 1j, 0.1, Band.lf(1.0)), ValueError,
                                  r"x must be real"),
    # --- simulator ------------------------------------------------------------------------------
    "NaN initial state": (lambda: simulate(STABLE, TONE, T, x0=[np.nan, 0.0]), ValueError,
                          r"x0 must have finite entries"),
    "complex initial state (simulate)": (lambda: simulate(STABLE, TONE, T, x0=[1j, 0.0]), ValueError,
                                         r"x0 must be real"),
    "non-uniform grid": (lambda: simulate(STABLE, TONE, np.array([0.0, 0.1, 0.3])), ValueError,
                         r"t must be a uniform grid \(use time_grid\)"),
    "unknown kernel": (lambda: simulate(STABLE, TONE, T, kernel="fortran"), ValueError,
                       r"kernel must be one of \('numba', 'numpy'\)"),
    "unknown law": (lambda: simulate([STABLE, STABLE], TONE, T, law_bands=[Band.lf(1.0), Band.hf(1.0)],
                                     law_Q=[Q2, Q2], law="next"), ValueError, r"law must be one of"),
    "tone at a closed-loop eigenvalue": (lambda: simulate(OSC, TONE, T), SingularFrequencyError,
                                         r"forced response of mode 0"),
    "particular solution at resonance": (lambda: particular([[0.0, 2.0], [-2.0, 0.0]], [[0.0], [1.0]],
                                                            Sinusoids([1.0], [2.0]), [0.0]),
                                         SingularFrequencyError, r"undefined at ω = 2 rad/s"),
    "run larger than max_memory": (lambda: simulate(STABLE, TONE, time_grid(1000.0, 1e-3), max_memory=1e6),
                                   MemoryLimitError, r"more than max_memory = 0\.00 GiB"),
    "diverging loop": (lambda: simulate(LTISystem([[50.0]], [[1.0]], [[1.0]], [[0.0]]), TONE,
                                        time_grid(20.0, 0.01)),
                       UnstableError, r"the state overflowed at t ="),
    "sigma0 beyond the modes": (lambda: simulate(STABLE, TONE, T, sigma0=1), ValueError,
                                r"sigma0 must be a mode index in \[0, 1\)"),
    # --- paper scenarios and CLI-level helpers --------------------------------------------------
    "unknown controller": (lambda: _run("PassC-XX"), ValueError,
                           r"name must be one of \('PassC-EF', 'PassC-LF', 'PassC-HF', 'FDSC'\)"),
    "window of zero length": (lambda: window_ratios(_run("PassC-EF"), 0.0), ValueError,
                              r"window must be a positive finite number"),
    "window shorter than two steps": (lambda: window_ratios(_run("PassC-EF"), 0.001), ValueError,
                                      r"window must span between 2 steps"),
    "stationary run of an unknown kind": (lambda: stationary_runs("MF"), ValueError, r"kind must be one of"),
}


@pytest.mark.parametrize(("call", "exc", "match"), list(CASES.values()), ids=list(CASES))
def test_bad_input_gets_a_named_error(call, exc, match):
    with pytest.raises(exc, match=match):
        call()


def test_value_errors_are_not_dimension_errors():
    # a wrong value must not be reported as a shape problem (and the other way round)
    value_cases = [k for k, (_, exc, _) in CASES.items() if exc is ValueError]
    for key in value_cases:
        with pytest.raises(ValueError) as info:
            CASES[key][0]()
        assert not isinstance(info.value, DimensionError), key
    assert len(value_cases) >= 20 and len(CASES) >= 40


def test_every_grid_time_grid_makes_is_accepted():
    # 1e7 steps: linspace rounding at t ~ 1e4 once made the uniformity check refuse it; the
    # check runs before any allocation, so a tiny max_memory proves the grid passed it
    t = time_grid(1e4, 1e-3)
    with pytest.raises(MemoryLimitError):
        simulate(STABLE, TONE, t, max_memory=1.0)


def test_unstable_mode_that_stays_finite_warns():
    # a slowly growing mode over a short run: finite numbers, but never without a word
    slow = LTISystem([[0.01]], [[1.0]], [[1.0]], [[0.0]])
    with pytest.warns(UnstableRunWarning, match=r"mode 0 is not Hurwitz \(eigenvalue 0\.01"):
        sim = simulate(slow, TONE, T)
    assert np.isfinite(sim.energy())
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        simulate(STABLE, TONE, T)  # a Hurwitz loop: silent
