import warnings

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.integrate import solve_ivp
from scipy.linalg import expm
from scipy.optimize import brentq

from fdsc import Band, LTISystem, UnstableRunWarning, simulate, time_grid
from fdsc.exceptions import DimensionError
from fdsc.paper.repairs.theorem1_counterexamples import (
    _ZERO,
    counterexample_search,
    exact_applies,
    exact_turn,
    search_case,
)

# the clean counterexample the chapter shows (first clean run of the default search proved
# divergent by its return map) and a run of the search that slides (55 % one-sample dwells)
CLEAN = ("spiral-2", 31)
SLIDING = ("spiral-2", 22)


def _turn(family_seed, law="previous"):
    c = search_case(*family_seed)
    return c, exact_turn(c.modes, c.bands, c.Q, law=law)


def _hybrid_returns(turn, returns):
    """‖x‖ and time after ``returns`` returns to the start ray, by solve_ivp with the law's
    switching events (x ᵀS_i x crossing 0 upwards) instead of the closed-form crossings."""
    x, i, t = np.array([np.cos(turn.start_angle), np.sin(turn.start_angle)]), turn.start_mode, 0.0
    for _ in range(2 * returns * (2 if turn.antipodal else 1)):
        S, A = turn.S[i], turn.A[i]

        def leave(_, y, S=S):
            return y @ S @ y
        leave.terminal, leave.direction = True, 1
        sol = solve_ivp(lambda _, y, A=A: A @ y, (0.0, 100.0), x, events=leave, rtol=1e-12,
                        atol=1e-14)
        x, t, i = sol.y_events[0][0], t + sol.t_events[0][0], 1 - i
    return np.linalg.norm(x), t


def test_multiplier_agrees_with_an_event_driven_simulation():
    _, turn = _turn(CLEAN)
    assert turn.clean and turn.antipodal
    g, T = _hybrid_returns(turn, 3)
    # independent method: an adaptive ODE solver with the law's switching surfaces as events
    assert_allclose(g ** (1 / 3), turn.multiplier, rtol=1e-8)
    assert_allclose(T / 3, turn.period, rtol=1e-8)


def test_crossing_times_agree_with_root_finding_on_matrix_exponentials():
    # independent method: bracket nᵀ e^{At} x on a grid of steps 0.1/‖A‖ (< 0.1 rad of turn per
    # step, so at most one zero per bracket) and refine with brentq
    _, turn = _turn(CLEAN)
    x = np.array([np.cos(turn.start_angle), np.sin(turn.start_angle)])
    for k, i in enumerate(turn.leaving):
        A, th = turn.A[i], turn.angles[k]
        n = np.array([-np.sin(th), np.cos(th)])

        def f(t, A=A, n=n, x=x):
            return float(n @ expm(A * t) @ x)
        grid = np.arange(1, 2000) * 0.1 / np.linalg.norm(A, 2)
        vals = np.array([f(t) for t in grid])
        j = int(np.flatnonzero(np.sign(vals[:-1]) != np.sign(vals[1:]))[0])
        t = brentq(f, grid[j], grid[j + 1], xtol=1e-14)
        assert_allclose(t, turn.dwells[k], rtol=1e-9)
        y = expm(A * t) @ x
        assert_allclose(np.linalg.norm(y), turn.gains[k], rtol=1e-9)
        x = y / np.linalg.norm(y)


def test_multiplier_agrees_with_the_sampled_law_and_the_exact_trajectory():
    c, turn = _turn(CLEAN)
    # the library's exact piecewise exponentials along the computed switching instants
    t, x = turn.trajectory(turns=2)
    assert_allclose(np.linalg.norm(x[-1]), turn.multiplier ** 2, rtol=1e-9)
    assert_allclose(t[-1], 2 * turn.period, rtol=1e-12)
    # the sampled printed law: it switches up to one step late, an O(dt) error (dt = period/10⁴)
    dt = turn.period / 10_000
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UnstableRunWarning)     # it diverges: the point
        sim = simulate(c.modes, _ZERO, time_grid(5 * turn.period, dt), x0=x[0],
                       law_bands=c.bands, law_Q=c.Q, law="previous")
    nrm = np.linalg.norm(sim.x, axis=1)
    k1, k5 = round(turn.period / dt), round(5 * turn.period / dt)
    assert_allclose((nrm[k5] / nrm[k1]) ** 0.25, turn.multiplier, rtol=1e-3)


def test_clean_case_is_transversal_certified_and_divergent():
    _, turn = _turn(CLEAN)
    # both flows cross each switching ray the same way, and the mode switched in keeps its lead
    assert np.all(turn.normal_speeds > 0) and np.all(turn.entry_margins > 0)
    assert not turn.sliding.any() and turn.lmi_holds and np.all(np.isfinite(turn.gammas))
    assert turn.multiplier > 1 and turn.proves_divergence and turn.growth_rate > 0
    assert "chattering" not in {label for *_, label in turn.cones()}
    p = turn.prose()
    assert all(isinstance(v, str) for v in p.values()) and p["lmi"] == "hold"


def test_sliding_is_detected_in_a_sliding_case():
    _, turn = _turn(SLIDING)
    # a switch lands where the mode switched in is beaten at once: the chattering region
    assert turn.sliding.any() and not turn.clean and not turn.proves_divergence
    assert turn.entry_margins[turn.sliding].max() < 0
    assert np.isnan(turn.multiplier)
    assert "chattering" in {label for *_, label in turn.cones()}


def test_filippov_sliding_ray_when_the_flows_point_against_each_other():
    # each candidate's own ẋ: one ray for both modes; spirals turning opposite ways cross it in
    # opposite directions, so at a switch the new mode's flow points back: a sliding ray
    A0 = np.array([[-0.1, 2.0], [-0.5, -0.1]])
    A1 = np.array([[-0.1, -2.0], [0.5, -0.1]])
    B, C, D = [[0.0], [1.0]], [[1.0, 0.0]], [[0.0]]
    modes = [LTISystem(A0, B, C, D), LTISystem(A1, B, C, D)]
    bands, Q = [Band.lf(1.0), Band.hf(1.0)], [np.eye(2), np.eye(2)]
    turn = exact_turn(modes, bands, Q, law="candidate")
    assert turn.sense[0] == -turn.sense[1]
    assert turn.sliding.all() and np.all(turn.entry_margins == 0)
    assert np.all(np.sign(turn.normal_speeds[:, 0]) != np.sign(turn.normal_speeds[:, 1]))


def _spiral(A):
    return LTISystem(A, [[0.0], [1.0]], [[1.0, 0.0]], [[0.0]])


def test_one_mode_twice_gives_the_closed_form_growth_of_a_turn():
    # A with eigenvalues α ± jβ: e^{A·2π/β} = e^{2πα/β} I, whatever the switches
    alpha, beta = -0.1, 1.0
    A = np.array([[alpha, beta], [-beta, alpha]])
    bands, Q = [Band.lf(1.0), Band.hf(1.0)], [np.eye(2), np.diag([1.0, 3.0])]
    for law in ("previous", "candidate"):
        turn = exact_turn([_spiral(A), _spiral(A)], bands, Q, law=law)
        assert_allclose(turn.multiplier, np.exp(2 * np.pi * alpha / beta), rtol=1e-12)
        assert_allclose(turn.period, 2 * np.pi / beta, rtol=1e-12)


def test_a_rotation_of_the_plane_leaves_the_return_map_unchanged():
    # x' = R x: A' = R A Rᵀ, Q' = R Q Rᵀ, B' = R B, C' = C Rᵀ give the same scores at R x
    c, turn = _turn(CLEAN)
    phi = 0.7
    R = np.array([[np.cos(phi), -np.sin(phi)], [np.sin(phi), np.cos(phi)]])
    modes = [LTISystem(R @ m.A @ R.T, R @ m.B, m.C @ R.T, m.D) for m in c.modes]
    rot = exact_turn(modes, c.bands, [R @ q @ R.T for q in c.Q])
    assert_allclose(rot.multiplier, turn.multiplier, rtol=1e-9)
    assert_allclose(np.sort(rot.dwells), np.sort(turn.dwells), rtol=1e-9)
    assert_allclose(np.sort(rot.entry_margins), np.sort(turn.entry_margins), rtol=1e-7, atol=1e-12)


def test_the_search_counts_clean_and_sliding_runs_apart():
    search = counterexample_search()
    cnt = search.counts()
    kinds = search.run_kinds()
    assert cnt["clean_previous"] + cnt["sliding_previous"] == cnt["diverging_previous"]
    assert cnt["clean_previous"] == len(search.clean()) >= 1
    # every divergent run of the printed law is 2-D here, so the exact map decides every one
    assert {how for _, how in kinds.values()} == {"exact"}
    o, turn = search.exact_counterexample()
    assert (o.family, o.seed) == CLEAN and turn.proves_divergence
    # a clean run's exact verdict agrees with its samples: no one-sample dwells at all
    assert all(d.chatter == 0 for d in search.clean())


@pytest.mark.parametrize("change, error, match", [
    ("three_states", DimensionError, "2 states"),
    ("one_mode", ValueError, "exactly two"),
    ("real_eigenvalues", ValueError, "complex eigenvalues"),
    ("start_mode", ValueError, "start_mode must be 0 or 1"),
    ("no_exit", ValueError, "no exit ray"),
])
def test_bad_input_is_refused_by_name(change, error, match):
    c = search_case(*CLEAN)
    modes, bands, Q, kw = list(c.modes), c.bands, c.Q, {}
    if change == "three_states":
        modes = [LTISystem(-np.eye(3) + np.diag([1.0, 1.0], 1) - np.diag([1.0, 1.0], -1),
                           np.ones((3, 1)), np.ones((1, 3)), [[0.0]]) for _ in range(2)]
        Q = [np.eye(3), np.eye(3)]
    elif change == "one_mode":
        modes, bands, Q = modes[:1], bands[:1], Q[:1]
    elif change == "real_eigenvalues":
        modes[1] = LTISystem(np.diag([-1.0, -2.0]), modes[0].B, modes[0].C, modes[0].D)
    elif change == "start_mode":
        kw = {"start_mode": 2}
    else:
        # one slow spiral against itself with equal Q's on LF and HF edges far apart: the HF
        # score never beats the LF one, so mode 0 is never left
        A = np.array([[-0.1, 0.1], [-0.1, -0.1]])
        modes, bands, Q = [_spiral(A), _spiral(A)], [Band.lf(1.0), Band.hf(10.0)], [np.eye(2)] * 2
    with pytest.raises(error, match=match):
        exact_turn(modes, bands, Q, **kw)
    if change in ("three_states", "real_eigenvalues", "no_exit"):
        assert not exact_applies(modes, bands, Q)
