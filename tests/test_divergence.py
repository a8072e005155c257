"""The divergence monitor (fdsc._divergence) in every simulator.

A switched loop of two Hurwitz modes that diverges under its law is flagged by ``simulate``
(both kernels), ``simulate_stream`` (both kernels) and ``simulate_batch`` at two steps; a
converging switched run and the paper's own loop are never flagged; the bound the monitor rests
on holds for LTI runs (checked against the exact simulation and against ``solve_ivp``).
"""

import warnings

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from fdsc import LTISystem, Sinusoids, _divergence
from fdsc.exceptions import UnstableRunWarning
from fdsc.paper.shared.data import hf_disturbance, paper_modes
from fdsc.random_systems import random_hurwitz
from fdsc.signals import Piecewise, Sampled
from fdsc.simulate import simulate, time_grid
from fdsc.stream import Case, simulate_batch, simulate_stream

# the classic pair: each mode is Hurwitz (eigenvalues −0.1 ± j√10), the switched loop is not
A1 = np.array([[-0.1, 1.0], [-10.0, -0.1]])
A2 = np.array([[-0.1, 10.0], [-1.0, -0.1]])
B = np.array([[0.0], [1.0]])
PAIR = [LTISystem(A1, B, np.eye(2), np.zeros((2, 1))), LTISystem(A2, B, np.eye(2), np.zeros((2, 1)))]
# law weights on [ẋ; x]: mode 1 scores −x₁x₂, mode 2 scores +x₁x₂. xᵀA₁x = −0.1‖x‖² − 9x₁x₂,
# xᵀA₂x = −0.1‖x‖² + 9x₁x₂: GROW picks the mode in which ‖x‖ grows, DECAY the other one
_S = np.array([[0.0, -0.5], [-0.5, 0.0]])
_Z = np.zeros((2, 2))
GROW = [np.block([[_Z, _Z], [_Z, _S]]), np.block([[_Z, _Z], [_Z, -_S]])]
DECAY = [GROW[1], GROW[0]]
D_TONE = Sinusoids([0.1], [1.0])
X0 = [1.0, 0.0]
HORIZON = 20.0
STEPS = (1e-3, 5e-4)


def _no_warning(fn):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        return fn()


@pytest.mark.parametrize("dt", STEPS)
@pytest.mark.parametrize("kernel", ["numba", "numpy"])
def test_simulate_flags_the_diverging_pair(dt, kernel):
    with pytest.warns(UnstableRunWarning, match=r"simulate: the switched run diverges: at t = "
                      r"[0-9.]+ s its state is [0-9.e+]+ times"):
        run = simulate(PAIR, D_TONE, time_grid(HORIZON, dt), x0=X0, law_weights=GROW, kernel=kernel)
    assert np.linalg.norm(run.x[-1]) > 1e15       # it does diverge


@pytest.mark.parametrize("dt", STEPS)
@pytest.mark.parametrize("kernel", ["numba", "python"])
def test_simulate_stream_flags_the_diverging_pair(dt, kernel):
    if kernel == "python" and dt < 1e-3:
        pytest.skip("the interpreted loop is slow; one step suffices for it")
    with pytest.warns(UnstableRunWarning, match=r"simulate_stream: the switched run diverges"):
        run = simulate_stream(PAIR, D_TONE, HORIZON, dt, x0=X0, law_weights=GROW, kernel=kernel)
    assert run.grew_at is not None and 0 < run.grew_at < HORIZON
    assert run.growth > _divergence.SAFETY
    assert np.isfinite(run.energy) and run.diverged_at is None


@pytest.mark.parametrize("dt", STEPS)
def test_simulate_batch_marks_the_diverging_case_only(dt):
    cases = [Case(PAIR, D_TONE, HORIZON, dt, x0=X0, law_weights=GROW),
             Case(PAIR, D_TONE, HORIZON, dt, x0=X0, law_weights=DECAY)]
    with pytest.warns(UnstableRunWarning, match=r"1 of 2 cases diverge .*cases \[0\]"):
        batch = simulate_batch(cases)
    assert batch.diverged.tolist() == [True, False]
    assert batch[0].grew_at is not None and batch[1].grew_at is None


def test_all_simulators_flag_at_about_the_same_time():
    dt = 1e-3
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UnstableRunWarning)
        full = simulate(PAIR, D_TONE, time_grid(HORIZON, dt), x0=X0, law_weights=GROW)
        stream = simulate_stream(PAIR, D_TONE, HORIZON, dt, x0=X0, law_weights=GROW)
    limit = _divergence.threshold([A1, A2], B, X0, D_TONE)
    k = int(np.argmax(np.max(np.abs(full.x), axis=1) > limit))
    # the stream checks once per block of 1024 steps: it flags within one block of the first point
    assert full.t[k] <= stream.grew_at <= full.t[k] + 1024 * dt


@pytest.mark.parametrize("dt", STEPS)
def test_a_converging_switched_pair_is_not_flagged_anywhere(dt):
    kw = dict(x0=X0, law_weights=DECAY)
    run = _no_warning(lambda: simulate(PAIR, D_TONE, time_grid(HORIZON, dt), **kw))
    assert run.switch_times.size > 10
    assert np.linalg.norm(run.x[-1]) < 1.0
    _no_warning(lambda: simulate(PAIR, D_TONE, time_grid(HORIZON, dt), kernel="numpy", **kw))
    s = _no_warning(lambda: simulate_stream(PAIR, D_TONE, HORIZON, dt, **kw))
    assert s.grew_at is None and s.growth is None
    b = _no_warning(lambda: simulate_batch([Case(PAIR, D_TONE, HORIZON, dt, **kw)]))
    assert not b.diverged.any()


@pytest.mark.parametrize("dt", STEPS)
def test_the_paper_loop_under_its_law_is_not_flagged(dt):
    pm = paper_modes()
    law = dict(law_bands=pm["bands"], law_Q=pm["Q"])
    d = hf_disturbance()
    _no_warning(lambda: simulate(pm["modes"], d, time_grid(10.0, dt), **law))
    _no_warning(lambda: simulate_stream(pm["modes"], d, 10.0, dt, x0=np.ones(2), **law))


def test_the_bound_holds_for_lti_runs_against_the_exact_run_and_solve_ivp():
    rng = np.random.default_rng(30)
    for _ in range(6):
        n = int(rng.integers(1, 4))
        A = random_hurwitz(rng, n)
        Bn = rng.standard_normal((n, 1))
        x0 = rng.standard_normal(n)
        d = Sinusoids(rng.uniform(0.1, 2.0, 2), rng.uniform(0.1, 5.0, 2), rng.uniform(0, 6, 2))
        R = _divergence.state_bound([A], Bn, x0, d)
        loop = LTISystem(A, Bn, np.eye(n), np.zeros((n, 1)))
        run = simulate(loop, d, time_grid(20.0, 1e-2), x0=x0)
        assert np.max(np.linalg.norm(run.x, axis=1)) <= R
        ref = solve_ivp(lambda t, x, A=A, b=Bn[:, 0], d=d: A @ x + b * d(t), (0.0, 20.0), x0,
                        rtol=1e-10,
                        atol=1e-12, t_eval=run.t)
        assert np.max(np.linalg.norm(ref.y, axis=0)) <= R
        np.testing.assert_allclose(ref.y.T, run.x, atol=1e-7 * R)


def test_mode_bound_closed_form_and_non_hurwitz():
    # scalar ẋ = −a x + b d: P = 1/(2a), κ = 1, R = |x0| + |b| d_max / a, the exact supremum
    assert _divergence.mode_bound(np.array([[-4.0]]), np.array([[2.0]]), 3.0, 1.5) == \
        pytest.approx(3.0 + 2.0 * 1.5 / 4.0)
    assert _divergence.mode_bound(np.array([[0.5]]), np.array([[1.0]]), 1.0, 1.0) == np.inf
    assert _divergence.mode_bound(np.array([[0.0, 1.0], [-1.0, 0.0]]), B, 1.0, 0.0) == np.inf


def test_input_bound_of_every_disturbance_kind():
    assert _divergence.input_bound(Sinusoids([1.0, -2.0], [1.0, 3.0])) == 3.0
    pw = Piecewise([0.0, 1.0, 2.0], [Sinusoids([1.0], [1.0]), Sinusoids([0.5, 0.25], [2.0, 3.0])])
    assert _divergence.input_bound(pw) == 1.0
    assert _divergence.input_bound(Sampled([0.5, -4.0, 1.0], 0.1)) == 4.0
    with pytest.raises(TypeError, match="d must be Sinusoids"):
        _divergence.input_bound([1.0])


def test_a_non_hurwitz_mode_turns_the_monitor_off_and_keeps_its_own_warning():
    bad = LTISystem([[0.05, 0.0], [0.0, -1.0]], B, np.eye(2), np.zeros((2, 1)))
    assert _divergence.threshold([A1, bad.A], B, X0, D_TONE) == np.inf
    with pytest.warns(UnstableRunWarning, match="mode 1 is not Hurwitz"):
        simulate([PAIR[0], bad], D_TONE, time_grid(5.0, 1e-2), x0=X0, law_weights=GROW)


def test_zero_input_from_rest_is_never_flagged():
    # R = 0: the state stays exactly 0, and 0 > 0 is false
    _no_warning(lambda: simulate(PAIR, Sinusoids([0.0], [1.0]), time_grid(5.0, 1e-3),
                                 law_weights=GROW))
    _no_warning(lambda: simulate_stream(PAIR, Sinusoids([0.0], [1.0]), 5.0, 1e-3,
                                        law_weights=GROW))


def test_sampled_input_is_monitored_too():
    u = Sampled(0.1 * np.sin(np.arange(20001) * 1e-3), 1e-3)
    with pytest.warns(UnstableRunWarning, match="the switched run diverges"):
        run = simulate_stream(PAIR, u, HORIZON, 1e-3, x0=X0, law_weights=GROW)
    assert run.grew_at is not None
    _no_warning(lambda: simulate_stream(PAIR, u, HORIZON, 1e-3, x0=X0, law_weights=DECAY))
