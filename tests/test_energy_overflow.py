"""Energies that do not overflow on the way: runs whose samples come near the square root of the
float range are simulated at a scale of a power of two and scaled back exactly; only a total that
exceeds the float range is an error (EnergyOverflowError), and "the state overflowed" is said
only when the state did."""

import math
import warnings

import numpy as np
import pytest

from fdsc import EnergyOverflowError, LTISystem, Sinusoids, UnstableError
from fdsc.simulate import simulate, time_grid
from fdsc.stream import Case, simulate_batch, simulate_stream

FIRST = LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]])
ZERO = Sinusoids([0.0], [1.0])
T, DT = 10.0, 1e-3

# the classic pair of Hurwitz modes under a law that converges (tests/test_divergence.py)
A1 = np.array([[-0.1, 1.0], [-10.0, -0.1]])
A2 = np.array([[-0.1, 10.0], [-1.0, -0.1]])
B = np.array([[0.0], [1.0]])
PAIR = [LTISystem(A1, B, np.eye(2), np.zeros((2, 1))), LTISystem(A2, B, np.eye(2), np.zeros((2, 1)))]
_S = np.array([[0.0, -0.5], [-0.5, 0.0]])
_Z = np.zeros((2, 2))
DECAY = [np.block([[_Z, _Z], [_Z, -_S]]), np.block([[_Z, _Z], [_Z, _S]])]


def _exact_free_energy(x0):
    # ẋ = −x, z = x from x0: ∫₀ᵀ x0² e^{−2t} dt, in closed form; Simpson's error at dt = 1 ms is
    # about 1e-13 relative
    return x0**2 / 2 * -math.expm1(-2 * T)


@pytest.mark.parametrize("closed_form", [True, False])
def test_a_huge_initial_state_has_its_finite_energy_in_every_path(closed_form):
    x0 = 1e153       # the energy, 5e305, is finite; its samples' squares near 1e306 sum to it
    ref = _exact_free_energy(x0)
    r = simulate_stream(FIRST, ZERO, T, DT, x0=[x0], closed_form=closed_form)
    assert r.energy == pytest.approx(ref, rel=1e-9) and r.diverged_at is None
    assert r.x_final[0] == pytest.approx(x0 * math.exp(-T), rel=1e-12)
    b = simulate_batch([Case(FIRST, ZERO, T, DT, x0=[x0])], closed_form=closed_form)
    assert b.energy[0] == pytest.approx(ref, rel=1e-9) and not b.diverged[0]
    assert simulate(FIRST, ZERO, time_grid(T, DT), x0=[x0]).energy() == pytest.approx(ref, rel=1e-9)


def test_the_loop_and_the_closed_form_agree_on_large_x0():
    for x0 in (1.0, 1e100, 1e153):
        loop = simulate_stream(FIRST, ZERO, T, DT, x0=[x0], closed_form=False)
        closed = simulate_stream(FIRST, ZERO, T, DT, x0=[x0], closed_form=True)
        assert closed.energy == pytest.approx(loop.energy, rel=1e-11), x0
        assert closed.energy == pytest.approx(_exact_free_energy(x0), rel=1e-9), x0
    for closed_form in (True, False):     # 5e399: beyond the float range, by either path
        with pytest.raises(EnergyOverflowError, match="∫zᵀz over the run exceeds the float range"):
            simulate_stream(FIRST, ZERO, T, DT, x0=[1e200], closed_form=closed_form)


def test_a_large_tone_keeps_its_digits():
    # the step's tone input is computed for unit amplitudes and scaled: put into the matrix
    # exponential, an amplitude of 2^200 used to ruin the step (energy off by a factor 5e7)
    d = Sinusoids([0.3, 0.2], [0.7, 2.0])
    x0 = np.array([1.0, -0.5])
    for closed_form in (True, False):
        ref = simulate_stream(PAIR[0], d, T, DT, x0=x0, closed_form=closed_form)
        for k in (100, 200, 300):
            big = Sinusoids(np.ldexp(d.amplitudes, k), d.frequencies, d.phases)
            r = simulate_stream(PAIR[0], big, T, DT, x0=np.ldexp(x0, k), closed_form=closed_form)
            assert r.energy == math.ldexp(ref.energy, 2 * k), (closed_form, k)
    # and against the full-trajectory simulator, which never had the problem
    big = Sinusoids(np.ldexp(d.amplitudes, 200), d.frequencies, d.phases)
    full = simulate(PAIR[0], big, time_grid(T, DT), x0=np.ldexp(x0, 200)).energy()
    assert simulate_stream(PAIR[0], big, T, DT, x0=np.ldexp(x0, 200)).energy == pytest.approx(full, rel=1e-9)


def test_a_scaled_switched_run_is_the_unscaled_one_times_a_power_of_two():
    # amplitudes and x0 times 2^500: the run is made at a smaller power-of-two scale; it makes the
    # same decisions and its numbers are exactly the unscaled ones times 2^500 (states) and
    # 2^1000 (energies)
    d = Sinusoids([0.3, 0.2], [0.7, 2.0])
    big = Sinusoids(np.ldexp(d.amplitudes, 500), d.frequencies, d.phases)
    x0 = np.array([1.0, -0.5])
    kw = dict(law_weights=DECAY, cumulative_every=1.0, trace_every=0.5)
    r1 = simulate_stream(PAIR, d, T, DT, x0=x0, **kw)
    r2 = simulate_stream(PAIR, big, T, DT, x0=np.ldexp(x0, 500), **kw)
    assert r1.switches > 10 and r2.switches == r1.switches
    assert r2.energy == math.ldexp(r1.energy, 1000)
    assert r2.input_energy == math.ldexp(r1.input_energy, 1000)
    np.testing.assert_array_equal(r2.x_final, np.ldexp(r1.x_final, 500))
    np.testing.assert_array_equal(r2.energy_cum, np.ldexp(r1.energy_cum, 1000))
    np.testing.assert_array_equal(r2.trace.z_hi, np.ldexp(r1.trace.z_hi, 500))
    np.testing.assert_array_equal(r2.trace.d_lo, np.ldexp(r1.trace.d_lo, 500))


def test_an_energy_beyond_the_float_range_is_an_error_that_says_so():
    tone = Sinusoids([1e160], [1.0])     # a stable loop: the state stays near 1e160
    with pytest.raises(EnergyOverflowError, match="exceed the float range .* state stays finite"):
        simulate_stream(FIRST, tone, T, DT)
    with pytest.raises(EnergyOverflowError, match=r"cases\[1\]: .*exceed the float range"):
        simulate_batch([Case(FIRST, ZERO, T, DT), Case(FIRST, tone, T, DT)])
    run = simulate(FIRST, tone, time_grid(T, DT))      # the trajectory itself is finite
    assert np.isfinite(run.x).all()
    with pytest.raises(EnergyOverflowError, match="energy: ∫zᵀz over the run exceeds"):
        run.energy()
    with pytest.raises(EnergyOverflowError, match="input_energy: ∫d² over the run exceeds"):
        run.input_energy()
    # the error is not an instability: nothing says "the state overflowed"
    with pytest.raises(EnergyOverflowError) as info:
        simulate_stream(FIRST, tone, T, DT)
    assert "overflowed" not in str(info.value) and not isinstance(info.value, UnstableError)


def test_a_state_that_overflows_is_still_called_so():
    unstable = LTISystem([[50.0]], [[1.0]], [[1.0]], [[0.0]])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with pytest.raises(UnstableError, match="state overflowed"):
            simulate_stream(unstable, ZERO, 20.0, DT, x0=[1.0])
