"""The FDSC design with controllers that have states as modes: the modes on the shared state,
Theorem 1's LMIs there, the special case of gains, and bad input refused by name."""

import numpy as np
import pytest
from numpy.testing import assert_allclose, assert_array_equal

from fdsc import (
    FDSC,
    Band,
    Controller,
    DimensionError,
    Piecewise,
    Plant,
    Sinusoids,
    simulate,
    simulate_batch,
    switched_loops,
    time_grid,
)
from fdsc.exceptions import UnstableError

A = [[0.0, 1.0], [-4.0, -0.4]]
OSC = Plant(A, [[0.0], [1.0]], [[0.0], [1.0]], [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.1]])
BANDS = [Band.lf(0.5), Band.hf(5.0)]
D_SWITCH = Piecewise([0.0, 5.0, 50.0], [Sinusoids([1.0], [0.2]), Sinusoids([1.0], [12.0])])


@pytest.fixture(scope="module")
def static():
    return FDSC.synthesize(OSC, BANDS, in_band=1)


@pytest.fixture(scope="module")
def filtered(static):
    """Mode 0 a filtered controller (LF gain below 2 rad/s, the HF gain above), mode 1 the HF gain."""
    K_lf, K_hf = static.gains
    return FDSC.from_gains(OSC, [Controller.filtered(K_lf, K_hf, 2.0, name="filtered"), K_hf], BANDS, 1)


def test_static_controllers_are_the_gains(static):
    again = FDSC.from_gains(OSC, [Controller.static(K) for K in static.gains], BANDS, 1, Q=list(static.Q))
    assert all(isinstance(g, np.ndarray) for g in again.gains)
    assert again.n_states == OSC.n_states
    for a, b in zip(again.modes, static.modes, strict=True):
        assert_array_equal(a.A, b.A)
    assert_array_equal(again.simulate(D_SWITCH, time_grid(10.0, 1e-3)).z,
                       static.simulate(D_SWITCH, time_grid(10.0, 1e-3)).z)


def test_modes_live_on_the_shared_state_and_the_lmis_hold_there(filtered):
    k = filtered.controllers[0].n_states
    assert k == 2 and filtered.n_states == OSC.n_states + k
    assert all(q.shape == (4, 4) for q in filtered.Q)
    for mode, ref in zip(filtered.modes, switched_loops(OSC, filtered.controllers), strict=True):
        assert_array_equal(mode.A, ref.A)
        assert mode.is_hurwitz()
    # Theorem 1's LMIs on the shared state: every one negative definite, Q's positive definite
    assert all(v < 0 for v in filtered.certificate.max_eigs.values())
    assert all(np.linalg.eigvalsh(q).min() > 0 for q in filtered.Q)
    assert filtered.gammas[0] == pytest.approx(10.0, rel=1e-6) and filtered.gammas[1] < 1.0


def test_the_shared_state_mode_is_the_fixed_controller_on_z(filtered):
    """The controller that is not in the loop does not act: mode 0 on the shared state and the
    filtered controller alone give the same output."""
    t = time_grid(20.0, 1e-3)
    alone = simulate(filtered.mode(0), D_SWITCH, t, x0=[1.0, 0.0, 0.0, 0.0])
    shared = simulate(filtered.modes[0], D_SWITCH, t, x0=[1.0, 0.0, 0.0, 0.0])
    assert_allclose(shared.z, alone.z, rtol=0, atol=1e-12 * np.abs(alone.z).max())
    assert filtered.mode(0).A.shape == (4, 4) and filtered.mode(1).A.shape == (2, 2)


def test_switched_run_pads_x0_and_follows_the_disturbance(filtered):
    t = time_grid(10.0, 1e-3)
    run = filtered.simulate(D_SWITCH, t, x0=[0.5, 0.0])
    same = filtered.simulate(D_SWITCH, t, x0=[0.5, 0.0, 0.0, 0.0])
    assert run.x.shape == (t.size, 4)
    assert_array_equal(run.z, same.z)
    assert np.mean(run.sigma[t >= 5.0] == 1) > 0.5
    # the controller's states are the filter of x: at rest at t = 0, moving afterwards
    assert_array_equal(run.x[0, 2:], 0.0) and np.abs(run.x[-1, 2:]).max() > 0
    batch = simulate_batch([filtered.case(D_SWITCH, 10.0, 1e-3, x0=[0.5, 0.0])])
    assert_allclose(batch.energy[0], run.energy(), rtol=1e-6)


def test_supervisor_gets_the_controllers(filtered):
    sup = filtered.supervisor()
    assert [c.n_states for c in sup.candidates] == [2, 0]


def test_a_decoupled_controller_state_changes_nothing_but_the_size(static):
    """A controller whose one state never acts (C_k = 0) is the gain D_k: the in-band γ Theorem 1
    allows is the static design's (up to the solver's accuracy)."""
    K_lf, K_hf = static.gains
    idle = Controller([[-1.0]], np.zeros((1, 2)), np.zeros((1, 1)), K_lf)
    again = FDSC.from_gains(OSC, [idle, K_hf], BANDS, 1)
    assert again.n_states == 3
    assert again.gammas[1] == pytest.approx(static.gammas[1], rel=1e-4)


@pytest.mark.parametrize(("make", "exc", "match"), [
    (lambda s: FDSC.from_gains(OSC, [s.gains[0], Controller([[0.5]], [[1.0, 0.0]], [[1.0]], s.gains[1])],
                               BANDS, 1), ValueError, r"gains\[1\] must be a controller that is stable"),
    (lambda s: FDSC.from_gains(OSC, [s.gains[0], Controller.static(np.zeros((1, 3)))], BANDS, 1),
     DimensionError, r"gains\[1\]"),
    (lambda s: FDSC.from_gains(OSC, [s.gains[0], "K"], BANDS, 1), TypeError, r"gains\[1\]"),
    (lambda s: FDSC(OSC, [Controller.filtered(*s.gains, 2.0), s.gains[1]], BANDS, 1, s.certificate),
     DimensionError, r"certificate.Q\[0\] must be \(4, 4\)"),
])
def test_bad_controller_modes(static, make, exc, match):
    with pytest.raises(exc, match=match):
        make(static)


def test_more_bad_input_is_named(static, filtered):
    import control

    K_lf, K_hf = static.gains
    reads = Controller(np.zeros((0, 0)), np.zeros((0, 2)), np.zeros((1, 0)), K_hf, E=np.zeros((0, 1)),
                       F=[[0.5]])
    with pytest.raises(ValueError, match=r"gains\[1\] reads ŵ directly"):
        FDSC.from_gains(OSC, [K_lf, reads], BANDS, 1)
    with pytest.raises(ValueError, match="x0 must be a numeric vector"):
        filtered.simulate(D_SWITCH, time_grid(1.0, 1e-3), x0=[True, False])
    with pytest.raises(ValueError, match="certificate must solve Theorem 1's LMIs"):
        FDSC(OSC, [K_hf, Controller.filtered(K_lf, K_hf, 2.0)], BANDS, 1, filtered.certificate)
    with pytest.raises(TypeError, match="synthesis must be None"):
        FDSC(OSC, list(filtered.gains), BANDS, 1, filtered.certificate, synthesis="junk")
    with pytest.raises(UnstableError, match=r"the closed loop of gains\[0\] is not stable"):
        FDSC.from_gains(OSC, [np.array([[10.0, 0.0]]), K_hf], BANDS, 1)
    with pytest.raises(DimensionError, match=r"Q\[0\]: expected shape \(4, 4\)"):
        FDSC.from_gains(OSC, list(filtered.gains), BANDS, 1, Q=[np.eye(2), np.eye(2)])
    with pytest.raises(TypeError, match="bands must be a list or tuple"):
        FDSC.from_gains(OSC, list(filtered.gains), (b for b in BANDS), 1)
    # python-control's static gain (no states, dt None) is a gain
    again = FDSC.from_gains(OSC, [K_lf, control.ss([], [], [], K_hf)], BANDS, 1, Q=list(static.Q))
    assert_array_equal(again.gains[1], K_hf)


def test_bad_x0_names_both_sizes(filtered):
    with pytest.raises(DimensionError,
                       match=r"x0 must be the plant's state \(2,\) or the shared state \(4,\)"):
        filtered.simulate(D_SWITCH, time_grid(1.0, 1e-3), x0=[1.0, 0.0, 0.0])
