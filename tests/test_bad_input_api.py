"""Bad input to the simulators' rules, the dwell tools and the design object: refused by name.

Each refusal names the argument and what was expected (or warns what will happen); each changed
path that stays valid is checked against an independent reference: a dwell beyond the horizon
against the fixed-gain run (bit for bit, in every kernel), a window of whole steps against the
trailing mean of the scores recomputed from the trajectory.
"""

import dataclasses
import warnings

import numpy as np
import pytest
from numpy.testing import assert_array_equal

import fdsc._dwell_signals as dwell_signals
from fdsc import FDSC, Band, DimensionError, LTISystem, MemoryLimitError, Plant, Sinusoids, SwitchRule
from fdsc.dwell import check_dwell_bound, dwell_time_bound, random_dwell_signal
from fdsc.rules import MAX_RULE_STEPS
from fdsc.simulate import estimate_memory, simulate, time_grid
from fdsc.stream import Case, simulate_batch, simulate_stream

# two stable 2-state loops sharing B, D; under the LF/HF law below the 1 s run switches about 20
# times, so a rule that is dropped shows
B, C, D = [[0.0], [1.0]], [[1.0, 0.0]], [[0.0]]
MODES = [LTISystem([[-1.0, 2.0], [-2.0, -1.0]], B, C, D), LTISystem([[-3.0, 0.0], [1.0, -0.5]], B, C, D)]
LAW = dict(law_bands=[Band.lf(1.0), Band.hf(20.0)], law_Q=[np.eye(2), np.eye(2)])
TONES = Sinusoids([1.0, 1.0], [2.0, 30.0])
HORIZON, DT = 1.0, 1e-3
T = time_grid(HORIZON, DT)
NO_OUTPUT = [LTISystem(m.A, B, np.zeros((0, 2)), np.zeros((0, 1))) for m in MODES]

# --- A1: a dwell beyond the horizon gives the fixed-gain run ----------------------------------


def _energy(path, modes, **kw):
    """∫zᵀz of one run of ``modes`` by one of the simulators' paths (kernels)."""
    if path in ("stream", "python"):
        return simulate_stream(modes, TONES, HORIZON, DT, kernel="numba" if path == "stream" else "python",
                               closed_form=False, **kw).energy
    if path == "batch":
        return simulate_batch([Case(modes, TONES, HORIZON, DT, **kw)], closed_form=False).energy[0]
    return simulate(modes, TONES, T, kernel=path, **kw).energy()


PATHS = ["stream", "python", "batch", "numba", "numpy"]


def test_the_law_switches_on_this_loop():
    # the premise of the dwell tests: without a dwell the run switches
    assert simulate_stream(MODES, TONES, HORIZON, DT, **LAW).switches > 10


@pytest.mark.parametrize("tau", [1e16, 1e306])
@pytest.mark.parametrize("path", PATHS)
def test_dwell_beyond_the_horizon_is_the_fixed_gain_run_bit_for_bit(path, tau):
    # reference: the same loop with mode 0 alone (the fixed gain; sigma0 = 0 counts as switched
    # on at t = 0, so no switch may follow); the same exact step in the same mode: equal bits
    run = _energy(path, MODES, **LAW, rule=SwitchRule.dwell_time(tau))
    assert run == _energy(path, MODES[0])


@pytest.mark.parametrize("path", ["stream", "numba", "numpy"])
def test_dwell_beyond_the_horizon_keeps_sigma0_one(path):
    run = _energy(path, MODES, **LAW, sigma0=1, rule=SwitchRule.dwell_time(1e16))
    assert run == _energy(path, MODES[1])


def test_dwell_beyond_the_horizon_also_equals_a_law_that_never_leaves_mode_0():
    # a second reference: two modes, weights +I and −I (mode 0 always wins; ties go to 0)
    fixed = dict(law_weights=[np.eye(4), -np.eye(4)])
    ref = simulate_stream(MODES, TONES, HORIZON, DT, **fixed)
    run = simulate_stream(MODES, TONES, HORIZON, DT, **LAW, rule=SwitchRule.dwell_time(1e16))
    assert run.switches == 0 and run.energy == ref.energy


@pytest.mark.parametrize("tau, n_steps, expect", [
    (1e16, 1000, (1001, 1)),                  # clamped to the run's n_steps + 1
    (1e306, 1000, (1001, 1)),                 # τ/dt overflows to inf: clamped, not an OverflowError
    (1e16, None, (MAX_RULE_STEPS, 1)),        # no run length: clamped to more than any run has
    (2.5e-3, 1000, (3, 1)),                   # ceil(2.5)
])
def test_dwell_steps_are_clamped_to_the_run(tau, n_steps, expect):
    assert SwitchRule.dwell_time(tau).steps(DT, n_steps) == expect


# --- A2: windows and dwells must be whole steps, more than one ---------------------------------

GRID_CASES = [
    (SwitchRule.moving_window(1.4e-3), r"rule\.window \(0\.0014 s\) must be a multiple of dt \(0\.001 s\)"),
    (SwitchRule.moving_window(0.4e-3), r"rule\.window \(0\.0004 s\) must be a multiple of dt"),
    (SwitchRule.moving_window(1e-3), r"rule\.window \(0\.001 s\) is one step of dt .* no effect"),
    (SwitchRule.dwell_time(0.5e-3), r"rule\.dwell \(0\.0005 s\) is at most one step of dt .* no effect"),
    (SwitchRule.dwell_time(1e-3), r"rule\.dwell \(0\.001 s\) is at most one step of dt"),
]


@pytest.mark.parametrize("rule, match", GRID_CASES, ids=["window 1.4 steps", "window 0.4 steps",
                                                        "window 1 step", "dwell 0.5 step", "dwell 1 step"])
@pytest.mark.parametrize("api", ["stream", "simulate", "steps"])
def test_window_off_the_grid_or_of_one_step_is_refused(api, rule, match):
    with pytest.raises(ValueError, match=match):
        if api == "stream":
            simulate_stream(MODES, TONES, HORIZON, DT, **LAW, rule=rule)
        elif api == "simulate":
            simulate(MODES, TONES, T, **LAW, rule=rule)
        else:
            rule.steps(DT)


def test_a_batch_names_the_case_with_the_bad_window():
    cases = [Case(MODES, TONES, HORIZON, DT, **LAW), Case(MODES, TONES, HORIZON, DT, **LAW,
                                                          rule=SwitchRule.moving_window(1.4e-3))]
    with pytest.raises(ValueError, match=r"^cases\[1\]: rule\.window"):
        simulate_batch(cases)


@pytest.mark.parametrize("kernel", ["numba", "numpy"])
def test_a_window_of_exactly_k_steps_averages_the_last_k_scores(kernel):
    # independent reference: under the "candidate" reading each mode's score at sample k is
    # vᵀ W_i v with v = [A_i x_k + B d_k; x_k], computable from the trajectory; the rule picks
    # the argmax of their mean over the last k = 5 samples (fewer at the start)
    k = 5
    run = simulate(MODES, TONES, T, **LAW, law="candidate", rule=SwitchRule.moving_window(k * DT),
                   kernel=kernel)
    W = [np.kron(b.psi.real, q) for b, q in zip(LAW["law_bands"], LAW["law_Q"], strict=True)]
    Bv = np.array(B)[:, 0]
    scores = np.empty((T.size, 2))
    for i, m in enumerate(MODES):
        v = np.hstack([run.x @ m.A.T + np.outer(run.d, Bv), run.x])
        scores[:, i] = np.einsum("kr,rc,kc->k", v, W[i], v)
    csum = np.cumsum(scores, axis=0)
    lagged = np.vstack([np.zeros((k, 2)), csum[:-k]])
    mean = (csum - lagged) / np.minimum(np.arange(1, T.size + 1), k)[:, None]
    assert run.switch_times.size > 5
    assert_array_equal(run.sigma, np.argmax(mean, axis=1))


def test_a_window_longer_than_the_run_is_the_mean_since_t0():
    # clamped to the run's N = 1001 samples: the same run as a window of exactly N steps
    far = simulate_stream(MODES, TONES, HORIZON, DT, **LAW, rule=SwitchRule.moving_window(1e6))
    whole = simulate_stream(MODES, TONES, HORIZON, DT, **LAW, rule=SwitchRule.moving_window(1.001))
    assert far.energy == whole.energy and far.switches == whole.switches


# --- A3: an MF range has no place in the law ----------------------------------------------------

MF_LAW = dict(law_bands=[Band.lf(1.0), Band.mf(2.0, 5.0)], law_Q=[np.eye(2), np.eye(2)])


@pytest.mark.parametrize("api", ["stream", "simulate", "batch"])
def test_mf_range_in_law_bands_is_refused_as_theorem_1_refuses_it(api):
    match = (r"law_bands\[1\] is an MF range \(MF \[2, 5\] rad/s\): the switching law is implemented "
             r"for real Ψ")
    with pytest.raises(ValueError, match=match):
        if api == "stream":
            simulate_stream(MODES, TONES, HORIZON, DT, **MF_LAW)
        elif api == "simulate":
            simulate(MODES, TONES, T, **MF_LAW)
        else:
            simulate_batch([Case(MODES, TONES, HORIZON, DT, **MF_LAW)])


# --- A4: a rule on a single mode has no effect: a warning says so --------------------------------

@pytest.mark.parametrize("api", ["stream", "simulate"])
def test_a_rule_on_a_single_mode_warns_and_changes_nothing(api):
    rule = SwitchRule(margin=0.2, dwell=0.01, window=0.01)
    match = (r"rule \(window 0\.01 s, hysteresis 0\.2 \(relative\), dwell 0\.01 s\) has no effect on a "
             r"single mode")
    with pytest.warns(UserWarning, match=match) as record:
        if api == "stream":
            got = simulate_stream(MODES[0], TONES, HORIZON, DT, rule=rule).energy
        else:
            got = simulate(MODES[0], TONES, T, rule=rule).energy()
    assert [w.category for w in record] == [UserWarning]       # not an UnstableRunWarning
    with warnings.catch_warnings():
        warnings.simplefilter("error")                          # the printed rule: no warning
        ref = (simulate_stream(MODES[0], TONES, HORIZON, DT).energy if api == "stream"
               else simulate(MODES[0], TONES, T).energy())
    assert got == ref


# --- A5: a relative margin ≥ 1 never switches: refused -------------------------------------------

@pytest.mark.parametrize("make", [
    lambda: SwitchRule.hysteresis(1.0),
    lambda: SwitchRule.hysteresis(1.5),
    lambda: SwitchRule(margin=1.0, dwell=0.5),
], ids=["1.0", "1.5", "with dwell"])
def test_relative_margin_of_one_or_more_is_refused(make):
    with pytest.raises(ValueError, match=r"margin must be < 1 for a relative hysteresis margin"):
        make()


def test_absolute_margin_above_one_is_valid():
    assert SwitchRule.hysteresis(5.0, relative=False).margin == 5.0


# --- A6: a loop without a regulated output -------------------------------------------------------

@pytest.mark.parametrize("api", ["stream", "simulate", "batch"])
def test_modes_without_regulated_output_are_refused(api):
    match = r"modes have no regulated output: C has shape \(0, 2\) \(0 rows\)"
    with pytest.raises(ValueError, match=match):
        if api == "stream":
            simulate_stream(NO_OUTPUT[0], TONES, HORIZON, DT)
        elif api == "simulate":
            simulate(NO_OUTPUT, TONES, T, **LAW)
        else:
            simulate_batch([Case(NO_OUTPUT, TONES, HORIZON, DT, **LAW)])


# --- A7: outputs beyond the memory limit are refused before they are allocated ---------------------

LONG = 1e6        # s: 1e9 steps of dt = 1 ms (nothing of this length is ever allocated here)


# the estimates, N = 1e9 + 1 points, n = 2 states, p = 1 output, I = 2 modes, 8 bytes a float:
# traces N bins × 2 (2 (n + p + 1) + I + 1) = 22 floats (164 GiB); coarse grid every 2 steps
# (N − 1)/2 + 1 points × 5 floats (18.6 GiB); a window of the whole run N × I floats (14.9 GiB)
@pytest.mark.parametrize("kw, match", [
    (dict(trace_every=DT), r"trace_every = 0\.001 s on 1000000001 points needs about 164 GiB"),
    (dict(cumulative_every=2 * DT),
     r"cumulative_every = 0\.002 s on 1000000001 points needs about 18\.6 GiB"),
    (dict(rule=SwitchRule.moving_window(1e6)),
     r"rule\.window = 1000000\.0 s on 1000000001 points needs about 14\.9 GiB"),
], ids=["trace_every", "cumulative_every", "window"])
def test_outputs_beyond_max_memory_are_refused_naming_the_argument(kw, match):
    with pytest.raises(MemoryLimitError, match=match):
        simulate_stream(MODES, TONES, LONG, DT, **LAW, **kw)


def test_max_memory_overrides_the_default_limit():
    # 1001 trace bins: 2 (2 (n + p + 1) + I + 1) floats each = 22 · 8 bytes · 1001 ≈ 176 kB
    with pytest.raises(MemoryLimitError, match=r"trace_every .* more than max_memory"):
        simulate_stream(MODES, TONES, HORIZON, DT, **LAW, trace_every=DT, max_memory=100_000)
    run = simulate_stream(MODES, TONES, HORIZON, DT, **LAW, trace_every=DT, max_memory=200_000)
    assert run.trace.t.size == T.size


def test_simulate_counts_the_window_against_max_memory():
    need = estimate_memory(T.size, 2, 1, 2, 2)               # 2 states, 1 output, 2 modes, 2 tones
    ring = 8 * 2 * T.size                                     # the window's (L, I) samples, L = N
    rule = SwitchRule.moving_window(10.0)
    with pytest.raises(MemoryLimitError, match=r"rule\.window = 10\.0 s"):
        simulate(MODES, TONES, T, **LAW, rule=rule, max_memory=need + ring - 1)
    assert simulate(MODES, TONES, T, **LAW, rule=rule, max_memory=need + ring).sigma.size == T.size


# --- B8: check_dwell_bound compares the modes with the certificate's ------------------------------

COMMON = [np.array([[-1.0, 2.0], [-2.0, -1.0]]), np.array([[-2.0, 0.0], [0.0, -3.0]])]
# the same sizes, other matrices: fast switching between them diverges
PAIR = [np.array([[-1.0, 4.0], [0.0, -1.0]]), np.array([[-1.0, 0.0], [4.0, -1.0]])]
SIGNAL = dict(x0=[1.0, 0.0], switch_times=[0.1, 0.2, 0.3], sequence=[0, 1, 0, 1], t=np.linspace(0, 1, 11))


@pytest.fixture(scope="module")
def common_bound():
    return dwell_time_bound(COMMON, decay=0.5)


@pytest.mark.parametrize("modes, match", [
    (PAIR, r"modes must be the modes of the certificate, but modes\[0\] differs from its A_0 by up to 2"),
    ([COMMON[0], PAIR[1]], r"modes\[1\] differs from its A_1"),
    ([COMMON[0] * (1 + 1e-6), COMMON[1]], r"modes\[0\] differs"),
], ids=["other pair", "one other mode", "perturbed"])
def test_check_dwell_bound_refuses_modes_other_than_the_certificates(common_bound, modes, match):
    with pytest.raises(ValueError, match=match):
        check_dwell_bound(common_bound, modes, **SIGNAL)


def test_check_dwell_bound_without_stored_modes_checks_the_decay_inequality(common_bound):
    # a certificate assembled by hand (no A): P = I does not give PAIR[0] a decay of 0.5
    hand = dataclasses.replace(common_bound, A=None)
    with pytest.raises(ValueError, match=r"modes\[0\] violates A'P \+ PA <= -2\*decay\*P"):
        check_dwell_bound(hand, PAIR, **SIGNAL)
    assert check_dwell_bound(hand, COMMON, **SIGNAL).holds()


def test_check_dwell_bound_accepts_its_own_modes_as_systems(common_bound):
    systems = [LTISystem(a, [[1.0], [0.0]], [[1.0, 0.0]], [[0.0]]) for a in COMMON]
    assert check_dwell_bound(common_bound, systems, **SIGNAL).holds()


# --- B9: random_dwell_signal has a cap on its switches --------------------------------------------

@pytest.mark.parametrize("min_dwell, horizon", [(1e-12, 1.0), (1e-300, 1e300), (0.09, 1e6)])
def test_random_dwell_signal_refuses_more_switches_than_the_cap(min_dwell, horizon):
    with pytest.raises(ValueError, match=r"min_dwell \(.* s\) allows up to horizon / min_dwell = .* "
                                         r"more than MAX_SWITCHES = 1e\+07"):
        random_dwell_signal(np.random.default_rng(0), 2, min_dwell, horizon)


def test_random_dwell_signal_cap_is_the_documented_constant(monkeypatch):
    monkeypatch.setattr(dwell_signals, "MAX_SWITCHES", 10)
    st, seq = random_dwell_signal(np.random.default_rng(0), 2, 0.1, 1.0)      # 10 switches at most
    assert st.size <= 10 and seq.size == st.size + 1
    with pytest.raises(ValueError, match="min_dwell"):
        random_dwell_signal(np.random.default_rng(0), 2, 0.099, 1.0)


# --- C10, C11: the design object's messages name its own arguments --------------------------------

PLANT = Plant([[-1.0]], [[1.0]], [[1.0]], [[1.0], [0.0]], [[0.0], [0.0]], [[0.0], [0.1]])
BANDS = [Band.lf(1.0), Band.hf(5.0)]


@pytest.fixture(scope="module")
def ctrl():
    return FDSC.from_gains(PLANT, [[[-0.5]], [[-2.0]]], BANDS, in_band=1)


@pytest.mark.parametrize("index, match", [
    (5, r"^i must be a mode index in \[0, 2\), but found 5$"),
    (2, r"^i must be a mode index in \[0, 2\), but found 2$"),
    (-1, r"^i must be an integer >= 0, but found -1$"),
    (0.5, r"^i must be an integer >= 0, but found 0\.5$"),
])
def test_mode_names_its_index(ctrl, index, match):
    with pytest.raises(ValueError, match=match):
        ctrl.mode(index)


def test_mode_of_a_valid_index_is_the_fixed_gain_loop(ctrl):
    assert_array_equal(ctrl.mode(1).A, PLANT.closed_loop(ctrl.gains[1]).A)


@pytest.mark.parametrize("gains, match", [
    ([[[-0.5]], [[-2.0, 0.0]]], r"^gains\[1\]: expected shape \(1, 1\) but found \(1, 2\)$"),
    ([[[-0.5, 1.0]], [[-2.0]]], r"^gains\[0\]: expected shape \(1, 1\) but found \(1, 2\)$"),
])
def test_from_gains_names_the_gain_with_the_wrong_shape(gains, match):
    with pytest.raises(DimensionError, match=match):
        FDSC.from_gains(PLANT, gains, BANDS, in_band=1)
