"""The streaming, batch simulator against the exact simulator with full traces and closed forms."""

import tracemalloc
import warnings

import numpy as np
import pytest
import scipy.linalg
from numpy.testing import assert_allclose
from scipy.integrate import quad

from fdsc import Band, LTISystem, Piecewise, Sampled, Sinusoids, SwitchRule, _stream_run, _stream_setup
from fdsc.exceptions import UnstableError, UnstableRunWarning
from fdsc.paper.shared.data import hf_disturbance, mixed_disturbance, paper_modes, piecewise_disturbance
from fdsc.random_systems import random_hurwitz, random_spd
from fdsc.simulate import simulate, time_grid
from fdsc.stream import PHASOR_BLOCK, Case, simulate_batch, simulate_stream

SCALAR = LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]])


def full_and_stream(modes, d, horizon, dt, **kw):
    law = {k: kw.pop(k) for k in ("law_bands", "law_Q", "law_weights", "law", "x0") if k in kw}
    old = simulate(modes, d, time_grid(horizon, dt), **law)
    new = simulate_stream(modes, d, horizon, dt, **law, **kw)
    return old, new


def dwell_lengths(sigma):
    change = np.flatnonzero(np.diff(sigma) != 0) + 1
    return np.diff(np.concatenate([[0], change]))


@pytest.mark.parametrize("law", ["previous", "candidate"])
@pytest.mark.parametrize("kind", ["mixed", "piecewise"])
def test_switched_run_equals_the_full_exact_simulation(law, kind):
    # the paper's FDSC chatters under the "previous" law (hundreds of switches): the two exact
    # methods differ only by rounding (phasors rotated here, cos and sin evaluated there), which
    # may flip a decision that is a tie to 1e-13 — none did on the machines we ran, but the
    # test allows one in a thousand so that it cannot depend on how a libm rounds
    pm = paper_modes()
    d = mixed_disturbance(0.1) if kind == "mixed" else piecewise_disturbance(20.0, 0.5, 0.1)
    horizon = 40.0 if kind == "mixed" else float(d.breaks[-1])
    old, new = full_and_stream(pm["modes"], d, horizon, 1e-3, law_bands=pm["bands"], law_Q=pm["Q"],
                               law=law, x0=[0.01, -0.02], trace_every=1e-3, dwell_edges=[1e-3, 2e-3, 100.0])
    n_old = old.switch_times.size
    if law == "previous":
        assert new.switches > 500
    assert abs(new.switches - n_old) <= n_old // 1000
    assert_allclose(new.time_share, old.time_share(), rtol=0, atol=1e-3)
    assert np.mean(np.argmax(new.trace.share, axis=1) != old.sigma) <= 1e-3
    assert_allclose(new.energy, old.energy(), rtol=1e-9)
    assert_allclose(new.input_energy, old.input_energy(), rtol=1e-12)
    assert_allclose(new.x_final, old.x[-1], rtol=0, atol=1e-9 * np.abs(old.x).max())
    # a one-sample trace holds every sample
    assert_allclose(new.trace.x_lo, old.x, rtol=0, atol=1e-9 * np.abs(old.x).max())
    assert np.array_equal(new.trace.x_lo, new.trace.x_hi)
    # the dwell histogram counts the completed dwell intervals of the run's own σ
    sigma = np.argmax(new.trace.share, axis=1)
    lengths = dwell_lengths(sigma)        # completed dwells (each ended by a switch)
    assert new.dwell_counts.tolist() == [int(np.sum(lengths == 1)), int(np.sum(lengths >= 2))]
    assert new.dwell_counts.sum() == new.switches == lengths.size


def test_piecewise_with_silent_parts_and_a_break_at_the_horizon():
    # d = 0 before 0.5 s and from 2 s on (the last point is a break: d(t_N) = 0 there)
    d = Piecewise([0.5, 1.25, 2.0], [Sinusoids([1.0, 0.5], [3.0, 40.0]), Sinusoids([2.0], [0.0], [1.0])])
    old, new = full_and_stream(SCALAR, d, 2.0, 1e-3, trace_every=1e-3, x0=[0.3])
    assert_allclose(new.trace.d_lo, old.d, rtol=0, atol=1e-14)
    assert new.trace.d_lo[-1] == 0.0 and old.d[-1] == 0.0
    # the closed form, piece by piece: x = x_p + e^{-(t - t0)} (x(t0) - x_p(t0))
    t, ref, x_start = old.t, np.empty(old.t.size), 0.3
    edges = [0.0, 0.5, 1.25, 2.0]
    for i, part in enumerate([None, *d.parts]):
        t0, t1 = edges[i], edges[i + 1]

        def xp(s, part=part):
            if part is None:
                return 0.0 * s
            return sum(np.imag(a * np.exp(1j * (w * s + ph)) / (1 + 1j * w))
                       for a, w, ph in zip(part.amplitudes, part.frequencies, part.phases, strict=True))
        at = (t >= t0) & (t <= t1)
        ref[at] = xp(t[at]) + np.exp(-(t[at] - t0)) * (x_start - xp(t0))
        x_start = xp(t1) + np.exp(-(t1 - t0)) * (x_start - xp(t0))
    # two exact methods (per-step particular solutions; the augmented system's step) agree with
    # the closed form and each other to a few units of rounding (measured: 1.2e-14 and 1.4e-14)
    assert_allclose(new.trace.x_lo[:, 0], ref, rtol=0, atol=5e-14)
    assert_allclose(old.x[:, 0], ref, rtol=0, atol=5e-14)
    assert_allclose(new.trace.x_lo[:, 0], old.x[:, 0], rtol=0, atol=5e-14)
    assert_allclose(new.energy, old.energy(), rtol=1e-13)


def test_no_drift_over_a_million_steps_against_the_closed_form():
    # x' = −x + sin(ω t + φ): x(t) = Im(e^{j(ωt+φ)} / (1 + jω)) + e^{−t}(x0 − Im(e^{jφ} / (1 + jω)))
    w, ph, x0 = 7.3, 0.4, 0.25
    horizon, dt = 2000.0, 2e-3          # 1e6 steps, about 2000 blocks of rotated phasors
    X = 1 / (1 + 1j * w)
    exact = (X * np.exp(1j * (w * horizon + ph))).imag + np.exp(-horizon) * (x0 - (X * np.exp(1j * ph)).imag)
    for closed_form in (False, True):     # the loop, and the closed form of the LTI run
        run = simulate_stream(SCALAR, Sinusoids([1.0], [w], [ph]), horizon, dt, x0=[x0],
                              closed_form=closed_form)
        # the phase ω t is known to about eps · ω t = 3e-12 rad; the step adds no drift beyond that
        assert abs(run.x_final[0] - exact) < 20 * np.finfo(float).eps * w * horizon
    assert 1e6 / PHASOR_BLOCK > 1000


def _scalar_exact(d, x0, horizon, pieces=64):
    """∫₀ᴴ x² and ∫₀ᴴ d² for ẋ = −x + d, z = x (SCALAR): x from its closed form, integrated by
    adaptive quadrature on short pieces (an independent reference, to about 1e-13)."""
    a, w, ph = d.amplitudes, d.frequencies, d.phases
    X = a / (1j * w + 1.0)                        # the steady state's phasors
    e0 = x0 - np.sum(np.imag(X * np.exp(1j * ph)))

    def x(t):
        return e0 * np.exp(-t) + np.sum(np.imag(X * np.exp(1j * (w * t + ph))))

    edges = np.linspace(0.0, horizon, pieces + 1)
    ez = sum(quad(lambda t: x(t) ** 2, u, v, epsabs=0, epsrel=1e-13, limit=200)[0]
             for u, v in zip(edges[:-1], edges[1:], strict=True))
    ed = sum(quad(lambda t: float(d(np.array([t]))[0]) ** 2, u, v, epsabs=0, epsrel=1e-13, limit=200)[0]
             for u, v in zip(edges[:-1], edges[1:], strict=True))
    return ez, ed


def test_energy_is_the_exact_integral_for_odd_and_even_point_counts():
    # each step's energy is an exact quadratic form: the total is ∫ x² itself, not a quadrature of
    # samples (Simpson's rule was off by (ω dt)⁴/180 here, and by a step's energy at a switch)
    d = Sinusoids([1.0, 0.3], [2.0, 11.0], [0.1, 0.0])
    for horizon in (3.0, 3.001, 0.002, 0.001):       # 3001, 3002, 3 and 2 points
        run = simulate_stream(SCALAR, d, horizon, 1e-3, trace_every=1e-3, x0=[0.5])
        ez, ed = _scalar_exact(d, 0.5, horizon)
        assert_allclose(run.energy, ez, rtol=1e-12)
        assert_allclose(run.input_energy, ed, rtol=1e-12)


def test_cumulative_grid_running_ratio_and_windows():
    d = Sinusoids([1.0], [np.pi])           # period 2 s
    run = simulate_stream(SCALAR, d, 10.0, 1e-3, cumulative_every=0.5, trace_every=1e-3)
    for j in (1, 7, 20):
        ez, ed = _scalar_exact(d, 0.0, j * 0.5, pieces=8)
        assert_allclose([run.energy_cum[j], run.input_energy_cum[j]], [ez, ed], rtol=1e-12)
    assert run.energy_cum[0] == 0.0 and run.t_cum[-1] == 10.0
    assert_allclose(run.energy_cum[-1], run.energy, rtol=1e-14)
    tr, ratio = run.running_l2()
    assert np.isnan(ratio[0])
    assert_allclose(ratio[1:], np.sqrt(run.energy_cum[1:] / run.input_energy_cum[1:]), rtol=1e-15)
    t0, ez, ed = run.window_energies(2.0)
    assert t0.size == run.t_cum.size - 4
    assert_allclose(ez[3], run.energy_cum[7] - run.energy_cum[3])
    # steady state: over a whole period the ratio is |1/(1 + jπ)|² (transient e^{−8} left)
    assert_allclose(ez[-1] / ed[-1], 1 / (1 + np.pi**2), rtol=1e-3)
    with pytest.raises(ValueError, match="multiple of the coarse step"):
        run.window_energies(0.7)
    with pytest.raises(ValueError, match="cumulative_every"):
        simulate_stream(SCALAR, d, 1.0, 1e-3).running_l2()


def test_trace_bins_hold_min_max_and_mode_shares():
    pm = paper_modes()
    old, new = full_and_stream(pm["modes"], mixed_disturbance(0.2), 6.0, 1e-3, law_bands=pm["bands"],
                               law_Q=pm["Q"], trace_every=0.25)
    every = 250
    for b in (0, 5, new.trace.t.size - 1):
        sl = slice(b * every, (b + 1) * every)
        assert_allclose(new.trace.z_lo[b], old.z[sl].min(axis=0), rtol=1e-10, atol=1e-15)
        assert_allclose(new.trace.z_hi[b], old.z[sl].max(axis=0), rtol=1e-10, atol=1e-15)
        assert_allclose(new.trace.share[b, 1], np.mean(old.sigma[sl] == 1))
    assert new.trace.t.size == 25                      # 6001 points: 24 full bins and one of 1
    assert_allclose(new.trace.share.sum(axis=1), 1.0)


def test_zero_and_first_order_hold_are_exact_for_their_signals():
    dt, N = 0.01, 501
    t = np.arange(N) * dt
    # ZOH of a constant 1: x = 1 − e^{−t}; FOH of the ramp t: x = t − 1 + e^{−t}
    zoh = simulate_stream(SCALAR, Sampled(np.ones(N), dt), 5.0, dt)
    foh = simulate_stream(SCALAR, Sampled(t, dt, hold="foh"), 5.0, dt)
    assert abs(zoh.x_final[0] - (1 - np.exp(-5.0))) < 5e-14
    assert abs(foh.x_final[0] - (5.0 - 1 + np.exp(-5.0))) < 1e-13
    # a ZOH input is not the ramp: it lags by dt/2, the stated error of the hold
    zoh_ramp = simulate_stream(SCALAR, Sampled(t, dt), 5.0, dt)
    assert_allclose(foh.x_final[0] - zoh_ramp.x_final[0], dt / 2, rtol=1e-2)


def test_sampled_sinusoid_converges_to_the_exact_sinusoidal_run():
    d = Sinusoids([1.0], [3.0])
    exact = simulate_stream(SCALAR, d, 5.0, 1e-3).x_final[0]
    errors = {}
    for hold in ("zoh", "foh"):
        for dt in (1e-2, 5e-3):
            t = np.arange(round(5.0 / dt) + 1) * dt
            errors[hold, dt] = abs(simulate_stream(SCALAR, Sampled(d(t), dt, hold=hold), 5.0, dt).x_final[0]
                                   - exact)
    assert 1.8 < errors["zoh", 1e-2] / errors["zoh", 5e-3] < 2.2        # O(dt)
    assert 3.6 < errors["foh", 1e-2] / errors["foh", 5e-3] < 4.4        # O(dt²)


def test_batch_pads_cases_of_different_sizes_and_equals_single_runs():
    rng = np.random.default_rng(4)
    two = [LTISystem(random_hurwitz(rng, 2), [[1.0], [0.5]], [[1.0, 0.0]], [[0.0]]) for _ in range(2)]
    three = LTISystem(random_hurwitz(rng, 3), [[1.0], [0.0], [0.2]], np.eye(3)[:2], [[0.1], [0.0]])
    bands = [Band.lf(1.0), Band.hf(5.0)]
    Q = [random_spd(rng, 2), random_spd(rng, 2)]
    cases = [Case(two, mixed_disturbance(0.3), 20.0, 1e-3, law_bands=bands, law_Q=Q, x0=[0.1, 0.0]),
             Case(three, hf_disturbance(), 10.0, 2e-3, x0=[0.0, 0.1, 0.0]),
             Case(two[0], Sampled(np.sin(np.arange(5001) * 0.01), 2e-3, hold="foh"), 10.0, 2e-3),
             Case(two, Sinusoids([1.0], [0.5]), 6.0, 1e-3, law_bands=bands, law_Q=Q, law="candidate")]
    opts = dict(cumulative_every=2.0, trace_every=0.5)
    batch = simulate_batch(cases, threads=2, **opts)
    serial = simulate_batch(cases, threads=1, **opts)
    for c, case in enumerate(cases):
        one = simulate_stream(case.modes, case.d, case.horizon, case.dt, x0=case.x0,
                              law_bands=case.law_bands, law_Q=case.law_Q, law=case.law, **opts)
        for res in (batch[c], serial[c]):
            assert res.energy == one.energy and res.switches == one.switches
            assert np.array_equal(res.x_final, one.x_final)
            assert np.array_equal(res.energy_cum, one.energy_cum)
            assert np.array_equal(res.trace.z_hi, one.trace.z_hi)
            assert res.time_share.size == one.time_share.size
    assert batch[1].x_final.shape == (3,) and batch[1].trace.z_lo.shape == (21, 2)
    assert batch.time_share.shape == (4, 2) and batch.time_share[1, 1] == 0.0
    assert batch[0].switches > 0


def test_a_near_tie_switches_the_same_in_a_padded_batch_as_alone():
    # two modes whose scores differ in the last bits (W and W·(1 + 1e-15), A and A + 1e-9·noise):
    # the law's forms must be those of the case's own run even when a bigger case pads the batch
    # to 10 states (they were once computed on the padded matrices, whose products round
    # otherwise for n ≥ 5: 118 switches alone, 110 in the batch)
    rng = np.random.default_rng(0)
    n = 7
    B, C, A = rng.standard_normal((n, 1)), rng.standard_normal((1, n)), random_hurwitz(rng, n)
    W = random_spd(rng, 2 * n)
    modes = [LTISystem(A, B, C, [[0.0]]),
             LTISystem(A + 1e-9 * rng.standard_normal((n, n)), B, C, [[0.0]])]
    d = Sinusoids([1.0, 0.5], [3.0, 17.0])
    case = Case(modes, d, 5.0, 1e-3, law_weights=[W, W * (1 + 1e-15)], x0=np.full(n, 0.1))
    big = LTISystem(-np.eye(10), np.ones((10, 1)), np.ones((1, 10)), [[0.0]])
    pad = Case([big, big], d, 0.01, 1e-3, law_weights=[np.eye(20)] * 2)
    alone = simulate_stream(case.modes, d, 5.0, 1e-3, x0=case.x0, law_weights=case.law_weights)
    for batch in (simulate_batch([case, pad], threads=1), simulate_batch([pad, case], threads=2)):
        res = batch[0] if batch[0].x_final.size == n else batch[1]
        assert res.switches == alone.switches and res.energy == alone.energy
        assert np.array_equal(res.x_final, alone.x_final)
    assert alone.switches > 50


def _spy_tags(monkeypatch):
    """The list that receives every ``shape`` tag the loop is called with."""
    tags = []
    real = _stream_run._shape_tag
    monkeypatch.setattr(_stream_run, "_shape_tag", lambda *a: tags.append(real(*a)) or tags[-1])
    return tags


def _loop_both_ways(monkeypatch, cases, **opts):
    """The batch by the general loop and by the loop specialized to its sizes, and the tags."""
    tags = _spy_tags(monkeypatch)
    general = simulate_batch(cases, closed_form=False, specialize=False, **opts)
    fixed = simulate_batch(cases, closed_form=False, specialize=True, **opts)
    return general, fixed, tags


def _bitwise_equal(a, b):
    for x, y in zip(a, b, strict=True):
        assert x.energy == y.energy and x.input_energy == y.input_energy
        assert x.switches == y.switches and x.sigma_final == y.sigma_final
        assert np.array_equal(x.x_final, y.x_final) and np.array_equal(x.time_share, y.time_share)
        assert np.array_equal(x.dwell_counts, y.dwell_counts)
        assert np.array_equal(x.energy_cum, y.energy_cum)
        assert np.array_equal(x.input_energy_cum, y.input_energy_cum)
        if x.trace is not None:
            assert np.array_equal(x.trace.x_lo, y.trace.x_lo) and np.array_equal(x.trace.z_hi, y.trace.z_hi)
            assert np.array_equal(x.trace.share, y.trace.share)


def test_specialized_loop_equals_the_general_loop_bit_for_bit(monkeypatch):
    # the paper's loop (the record's most used sizes): the six tones of d_h + ρ d_l, the
    # piecewise disturbance whose segments have fewer tones (padded with zero tones), a
    # hysteresis rule, the candidate law and a fixed gain; every size becomes a constant
    pm = paper_modes()
    law = dict(law_bands=pm["bands"], law_Q=pm["Q"])
    cases = [Case(pm["modes"], mixed_disturbance(0.2), 8.0, 1e-3, **law),
             Case(pm["modes"], piecewise_disturbance(1.0, 0.1, 0.5), 3.0, 1e-3, **law),
             Case(pm["modes"], mixed_disturbance(0.1), 8.0, 1e-3, rule=SwitchRule.hysteresis(0.1),
                  x0=[0.05, -0.1], **law),
             Case(pm["modes"], mixed_disturbance(0.4), 6.0, 1e-3, law="candidate", **law),
             Case([pm["modes"][0]] * 2, hf_disturbance(), 5.0, 1e-3, **law)]
    general, fixed, tags = _loop_both_ways(monkeypatch, cases, cumulative_every=0.5)
    assert tags[0] == ((), ) * 7 and [len(t) for t in tags[1]] == [2, 3, 2, 6, 6, 1, 1]
    assert general.switches[0] > 100 and general.switches[1] > 0
    _bitwise_equal(general, fixed)


def test_padded_specialized_loop_equals_the_general_loop_bit_for_bit(monkeypatch):
    # cases of different sizes in one group (two modes, tones, traces): 2 and 3 states and 1 and
    # 2 outputs padded to the largest, a second-order law (on [ẍ; ẋ; x]) padding the law's vector
    # of the others, traces (their flag stays general); a first-order-hold input on one mode
    # forms a group of its own
    rng = np.random.default_rng(4)
    two = [LTISystem(random_hurwitz(rng, 2), [[1.0], [0.5]], [[1.0, 0.0]], [[0.0]]) for _ in range(2)]
    three = [LTISystem(random_hurwitz(rng, 3), [[1.0], [0.0], [0.2]], np.eye(3)[:2], [[0.1], [0.0]])
             for _ in range(2)]
    W = [random_spd(rng, 6), random_spd(rng, 6)]
    W[1][:2, :2] += 3.0 * np.eye(2)
    cases = [Case(two, mixed_disturbance(0.3), 20.0, 1e-3, law_bands=[Band.lf(1.0), Band.hf(5.0)],
                  law_Q=[random_spd(rng, 2), random_spd(rng, 2)], x0=[0.1, 0.0]),
             Case(three, hf_disturbance(), 10.0, 2e-3, law_bands=[Band.lf(1.0), Band.hf(5.0)],
                  law_Q=[random_spd(rng, 3), random_spd(rng, 3)], x0=[0.0, 0.1, 0.0]),
             Case(two[0], Sampled(np.sin(np.arange(5001) * 0.01), 2e-3, hold="foh"), 10.0, 2e-3),
             Case(two, mixed_disturbance(0.5), 10.0, 1e-3, law_weights=W)]
    general, fixed, tags = _loop_both_ways(monkeypatch, cases, cumulative_every=2.0, trace_every=0.5)
    sizes = sorted([len(t) for t in tag] for tag in tags[len(tags) // 2:])
    assert sizes == [[2, 1, 1, 6, 0, 0, 0], [3, 2, 2, 15, 6, 1, 0]]
    assert all(general.switches[[0, 1, 3]] > 0)
    _bitwise_equal(general, fixed)


_TWO_THREADS = """
import numpy as np, numba
from fdsc.paper.shared.data import mixed_disturbance, paper_modes
from fdsc.stream import Case, simulate_batch
assert numba.config.NUMBA_NUM_THREADS >= 2
pm = paper_modes()
cases = [Case(pm["modes"], mixed_disturbance(r), 3.0, 1e-3, law_bands=pm["bands"], law_Q=pm["Q"])
         for r in (0.0, 0.1, 0.3, 0.5, 1.0)]
a = simulate_batch(cases, threads=2, cumulative_every=0.5)
b = simulate_batch(cases, threads=1, cumulative_every=0.5)
assert np.array_equal(a.energy, b.energy) and np.array_equal(a.switches, b.switches)
assert all(np.array_equal(x.energy_cum, y.energy_cum) for x, y in zip(a, b))
print("same", int(a.switches.sum()))
"""


def test_batch_on_two_threads_equals_one_thread_in_a_fresh_process():
    # the test session caps numba at one thread per worker (conftest.py): two threads are
    # checked in a process of their own
    import os
    import subprocess
    import sys

    env = dict(os.environ, NUMBA_NUM_THREADS="2")
    out = subprocess.run([sys.executable, "-c", _TWO_THREADS], env=env, capture_output=True,
                         text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    assert out.stdout.startswith("same") and int(out.stdout.split()[1]) > 0


def test_python_loop_equals_the_compiled_one():
    pm = paper_modes()
    kw = dict(law_bands=pm["bands"], law_Q=pm["Q"], x0=[0.01, -0.02], cumulative_every=0.1, trace_every=0.05)
    a = simulate_stream(pm["modes"], mixed_disturbance(0.1), 0.6, 1e-3, **kw)
    b = simulate_stream(pm["modes"], mixed_disturbance(0.1), 0.6, 1e-3, kernel="python", **kw)
    # the same arithmetic in the same order (cos and sin may come from different libm entry points)
    assert a.switches == b.switches
    assert_allclose(a.energy, b.energy, rtol=1e-13)
    assert_allclose(a.x_final, b.x_final, rtol=1e-12)
    assert_allclose(a.trace.x_hi, b.trace.x_hi, rtol=1e-12, atol=1e-15)


@pytest.mark.parametrize("specialize", [False, True])
def test_memory_does_not_grow_with_the_horizon(specialize):
    d = mixed_disturbance(0.1)
    pm = paper_modes()
    kw = dict(law_bands=pm["bands"], law_Q=pm["Q"], specialize=specialize)
    simulate_stream(pm["modes"], d, 1.0, 1e-3, **kw)        # compile outside the measurement
    peaks = []
    for horizon in (10.0, 1000.0):                          # 1e4 and 1e6 steps
        tracemalloc.start()
        simulate_stream(pm["modes"], d, horizon, 1e-3, **kw)
        peaks.append(tracemalloc.get_traced_memory()[1])
        tracemalloc.stop()
    # a full trace of 1e6 steps would take > 100 MB; the streamed run's extra is the dwell edges
    assert peaks[1] - peaks[0] < 4096, peaks


def test_divergence_is_an_error_alone_and_a_flag_in_a_batch():
    unstable = LTISystem([[50.0]], [[1.0]], [[1.0]], [[0.0]])
    with pytest.raises(UnstableError, match="overflowed"):
        simulate_stream(unstable, Sinusoids([1.0], [1.0]), 30.0, 1e-3)
    tone = Sinusoids([1.0], [1.0])
    cases = [Case(unstable, tone, 30.0, 1e-3), Case(SCALAR, tone, 1.0, 1e-3)]
    with pytest.warns(UnstableRunWarning, match=r"1 of 2 cases diverged.*\[0\]"):
        batch = simulate_batch(cases, cumulative_every=1.0)
    assert batch.diverged.tolist() == [True, False]
    assert batch.energy[0] == np.inf and np.isfinite(batch.energy[1])
    assert batch[0].diverged_at is not None and batch[0].t_cum[-1] < batch[0].diverged_at
    # every kept point of the running integral was written (none is a stale zero)
    assert np.all(np.diff(batch[0].energy_cum) > 0)
    with pytest.raises(UnstableError):
        batch[0].l2_ratio()
    # traces: the bins after the overflow were never written and say so (NaN, not stale zeros);
    # the bins before it hold the samples, each bin's mode shares summing to 1
    with pytest.warns(UnstableRunWarning, match="1 of 2 cases diverged"):
        traced = simulate_batch(cases, trace_every=0.5)[0].trace
    after = traced.t > batch[0].diverged_at
    assert after.any() and np.isnan(traced.x_hi[after]).all() and np.isnan(traced.share[after]).all()
    assert np.isfinite(traced.x_hi[~after][:-1]).all() and np.all(traced.x_hi[~after][1:-1] > 0)
    assert_allclose(traced.share[~after].sum(axis=1), 1.0, rtol=1e-15)
    # finite but growing: a warning names the mode
    slow = LTISystem([[0.01]], [[1.0]], [[1.0]], [[0.0]])
    with pytest.warns(UnstableRunWarning, match="mode 0 is not Hurwitz"):
        simulate_stream(slow, Sinusoids([1.0], [1.0]), 1.0, 1e-3)


@pytest.mark.parametrize("kwargs, exc, match", [
    (dict(cumulative_every=0.0025), ValueError, "multiple of dt"),
    (dict(trace_every=-1.0), ValueError, "trace_every"),
    (dict(dwell_edges=[1.0, 0.5]), ValueError, "dwell_edges"),
    (dict(dwell_edges=[1e-4, 2e-4, 1.0]), ValueError, "dwell_edges must be multiples of dt"),
    (dict(dwell_edges=[0.0014, 0.0031, 1.0]), ValueError, "dwell_edges must be multiples of dt"),
    (dict(dwell_edges=[0.5, 1.0, 1.0004]), ValueError, "at least one step"),
    (dict(dwell_edges=[1.0, np.inf, np.inf]), ValueError, "dwell_edges must be at least 2 increasing"),
    (dict(dwell_edges=["a", "b"]), ValueError, "dwell_edges must be at least 2 increasing"),
    (dict(horizon=1e19, dt=1.0), ValueError, "at most 4.61e\\+18 steps"),
    (dict(d=Sinusoids([1.0], [2 * np.pi / 0.1]), dt=0.1), ValueError, "does not resolve the disturbance"),
    (dict(d=Piecewise([0.0, 0.5, 1.0], [Sinusoids([1.0], [1.0]), Sinusoids([1.0], [40.0])]), dt=0.1),
     ValueError, "does not resolve piece 1 of the disturbance"),
    (dict(d=Piecewise([0.0, 1.4e-10, 1e-9], [Sinusoids([1.0], [0.0]), Sinusoids([2.0], [0.0])]),
          horizon=1e-9, dt=1e-10), ValueError, "1.4e-10 s, which is not on the grid"),
    (dict(cumulative_every=4.0), ValueError, "exceeds the horizon"),
    (dict(modes=[SCALAR, SCALAR], law_bands=Band.lf(1.0), law_Q=[[[1.0]]] * 2), ValueError,
     "law_bands must be a list with one entry per mode"),
    (dict(modes=[SCALAR, SCALAR], law_bands=[Band.lf(1.0), Band.hf(2.0)], law_Q=[[[1.0]], [[-1.0]]]),
     ValueError, r"law_Q\[1\]"),
    (dict(kernel="fortran"), ValueError, "kernel"),
    (dict(horizon=1.0005), ValueError, "multiple of dt"),
    (dict(d=Sampled(np.zeros(10), 1e-3)), ValueError, "has 10 samples but the horizon needs 1001"),
    (dict(d=Sampled(np.zeros(2001), 5e-4)), ValueError, "must be equal"),
    (dict(d=Piecewise([0.0, 0.0005, 1.0], [Sinusoids([1.0], [1.0])] * 2)), ValueError, "not on the grid"),
    (dict(d=np.zeros(1001)), TypeError, "Sampled"),
    (dict(law="sticky"), ValueError, "law must be one of"),
    (dict(x0=[1.0, 2.0]), Exception, "x0"),
])
def test_bad_inputs_name_the_argument(kwargs, exc, match):
    args = dict(modes=SCALAR, d=Sinusoids([1.0], [1.0]), horizon=1.0, dt=1e-3)
    for k in ("modes", "d", "horizon", "dt"):
        if k in kwargs:
            args[k] = kwargs.pop(k)
    with pytest.raises(exc, match=match):
        simulate_stream(args["modes"], args["d"], args["horizon"], args["dt"], **kwargs)


def test_batch_errors_name_the_case():
    good = Case(SCALAR, Sinusoids([1.0], [1.0]), 1.0, 1e-3)
    with pytest.raises(ValueError, match=r"cases\[1\]: horizon"):
        simulate_batch([good, Case(SCALAR, Sinusoids([1.0], [1.0]), 1.0005, 1e-3)])
    with pytest.raises(TypeError, match=r"cases\[0\]: case"):
        simulate_batch([(SCALAR, Sinusoids([1.0], [1.0]))])
    with pytest.raises(ValueError, match="at least one Case"):
        simulate_batch([])
    with pytest.raises(TypeError, match="sequence of Case"):
        simulate_batch(good)
    with pytest.raises(ValueError, match=r"cases\[1\]: cumulative_every"):
        simulate_batch([good, Case(SCALAR, Sinusoids([1.0], [1.0]), 0.999, 3e-3)], cumulative_every=0.002)
    with pytest.raises(ValueError, match="threads"):
        simulate_batch([good], threads=0)
    pm = paper_modes()
    with pytest.raises(ValueError, match=r"cases\[0\]: law_bands must be a list"):
        simulate_batch([Case(pm["modes"], Sinusoids([1.0], [1.0]), 1.0, 1e-3)])


def test_sampled_signal_values_and_errors():
    d = Sampled([0.0, 1.0, 3.0], 0.5, hold="foh")
    assert_allclose(d([-0.1, 0.0, 0.5, 0.6, 1.0, 1.01]), [0.0, 0.0, 1.0, 1.4, 3.0, 0.0])
    with pytest.raises(ValueError, match="at least 2 samples"):
        Sampled([1.0], 0.1)
    with pytest.raises(ValueError, match="hold must be one of"):
        Sampled([1.0, 2.0], 0.1, hold="cubic")
    with pytest.raises(ValueError, match="dt"):
        Sampled([1.0, 2.0], 0.0)


def test_dwell_edges_beyond_the_horizon_catch_every_long_dwell():
    pm = paper_modes()
    kw = dict(law_bands=pm["bands"], law_Q=pm["Q"])
    d = mixed_disturbance(0.1)
    a = simulate_stream(pm["modes"], d, 5.0, 1e-3, dwell_edges=[1e-3, 5e-3, np.inf], **kw)
    b = simulate_stream(pm["modes"], d, 5.0, 1e-3, dwell_edges=[1e-3, 5e-3, 1e17], **kw)
    assert a.dwell_counts.sum() == a.switches > 0
    assert a.dwell_counts.tolist() == b.dwell_counts.tolist()


def test_single_mode_runs_ignore_the_law_and_warn_nothing():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        run = simulate_stream(SCALAR, hf_disturbance(), 2.0, 1e-3)
    assert run.switches == 0 and run.time_share.tolist() == [1.0] and run.dwell_counts.sum() == 0


@pytest.mark.parametrize("f", [2, 3])
def test_law_forms_on_xi_equal_the_scores_on_the_derivatives(f):
    # ξᵀ M[m, :, i] ξ (packed) = vᵀ W_i v with v = [ẋ; x] or [ẍ; ẋ; x] of mode m, by hand
    rng = np.random.default_rng(5)
    n, nm = 3, 2
    A = rng.standard_normal((nm, n, n))
    B = rng.standard_normal(n)
    W = np.array([w + w.T for w in rng.standard_normal((nm, f * n, f * n))])
    Mt = _stream_setup._law_forms(A, B, W, f)
    iu = np.triu_indices(n + f - 1)
    for _ in range(5):
        x, d, dd = rng.standard_normal(n), rng.standard_normal(), rng.standard_normal()
        xi = np.concatenate([x, [d, dd][:f - 1]])
        prod = np.outer(xi, xi)[iu]
        for m in range(nm):
            xd = A[m] @ x + B * d
            v = np.concatenate([A[m] @ xd + B * dd, xd, x]) if f == 3 else np.concatenate([xd, x])
            for i in range(nm):
                assert_allclose(prod @ Mt[m, :, i], v @ W[i] @ v, rtol=1e-12)


def test_tone_input_matrices_equal_the_particular_solution_step():
    # Im(H p) = x_p(t + Δt) − Φ x_p(t) for x_p = Im(X p), X = (jωI − A)⁻¹ B a: the step of
    # fdsc.simulate, written with the augmented system's exponential instead
    A = np.array([[0.0, 1.0], [-4.0, -0.4]])
    B = np.array([0.0, 1.0])
    part = Sinusoids([1.0, 0.3], [0.7, 50.0], [0.2, -1.0])
    dt = 1e-3
    prep = dict(segments=[part], nm=1, n=2, dt=dt, A=A[None], B=B)
    _, _, _, _, H, _ = _stream_setup._tone_arrays(prep, 2)
    Phi = scipy.linalg.expm(A * dt)
    for j, (a, w) in enumerate(zip(part.amplitudes, part.frequencies, strict=True)):
        X = np.linalg.solve(1j * w * np.eye(2) - A, B * a)
        expected = X * np.exp(1j * w * dt) - Phi @ X
        assert_allclose(H[0, 0, :, j], expected, rtol=0, atol=1e-13 * np.abs(X).max())


def test_more_modes_than_law_products_on_a_scalar_loop():
    # n = 1: the law's form on ξ = [x; d] has 3 products; 5 modes must still get 5 scores
    modes = [LTISystem([[-a]], [[1.0]], [[1.0]], [[0.0]]) for a in (0.5, 1.0, 2.0, 4.0, 8.0)]
    W = [np.diag([c, 1.0 - c]) for c in (0.1, 0.3, 0.5, 0.7, 0.9)]
    d = Sinusoids([1.0, 0.5], [0.3, 20.0])
    old, new = full_and_stream(modes, d, 20.0, 1e-3, law_weights=W, x0=[0.2])
    assert new.time_share.size == 5
    assert new.switches == old.switch_times.size > 0
    assert_allclose(new.energy, old.energy(), rtol=1e-9)


def _random_lti_case(rng):
    """A random stable loop (poles from 1e-3 to 30 rad/s, sometimes one at 5e5 rad/s, sometimes
    in badly scaled coordinates), disturbance and grid."""
    n, p = int(rng.integers(1, 5)), int(rng.integers(1, 3))
    basis, _ = np.linalg.qr(rng.normal(size=(n, n)))
    poles = -10 ** rng.uniform(-3, 1.5, size=n)
    if rng.random() < 0.2:
        poles[0] = -5e5                                       # stiff: e^{AΔt} has an eigenvalue ~0
    A = basis @ np.diag(poles) @ basis.T
    if n > 1 and rng.random() < 0.3:
        scale = 10 ** rng.uniform(-3, 3, size=n)              # badly scaled state coordinates
        A = (A * scale[:, None]) / scale[None, :]
    loop = LTISystem(A, rng.normal(size=(n, 1)), rng.normal(size=(p, n)),
                     rng.normal(size=(p, 1)) * (rng.random() < 0.5))

    def tones():
        T = int(rng.integers(1, 5))
        w = rng.uniform(0, 60, size=T)
        if rng.random() < 0.3:
            w[0] = 0.0                                        # a constant
        if T > 1 and rng.random() < 0.3:
            w[1] = w[0] + rng.choice([0.0, 1e-7, 1e-4])       # equal or nearly equal tones
        return Sinusoids(rng.normal(size=T), w, rng.uniform(0, 6, size=T))
    dt = float(rng.choice([1e-3, 2e-3, 1e-2]))
    steps = max(1, round(10 ** rng.uniform(-2.5, 2.5) / dt))
    if steps > 10 and rng.random() < 0.5:
        breaks = np.sort(rng.choice(np.arange(steps + 1), size=int(rng.integers(2, 5)), replace=False)) * dt
        d = Piecewise(breaks, [tones() if rng.random() < 0.8 else Sinusoids([0.0], [1.0])
                               for _ in range(breaks.size - 1)])
    else:
        d = tones()
    every = 2 * max(1, (steps + 1) // 20) * dt if steps >= 20 and rng.random() < 0.5 else None
    x0 = rng.normal(size=n) if rng.random() < 0.6 else None
    return Case(loop, d, steps * dt, dt, x0=x0), every


def test_closed_form_lti_sums_equal_the_loop_on_random_loops():
    # the closed form is kept only where its terms do not cancel (nor its quadratic forms lose
    # digits to a badly scaled state); where it is kept it agrees with the loop to 1e-11
    # (measured over 400 such cases: 9.6e-12, for poles near 1e-3 rad/s)
    rng = np.random.default_rng(7)
    kept = 0
    for _ in range(80):
        case, every = _random_lti_case(rng)
        pr = _stream_setup._prepare(case, "", every, None, None)
        closed = _stream_run._closed_result(pr)
        loop = _stream_run._run([pr], "numba", 1, closed_form=False)[0]
        auto = _stream_run._run([pr], "numba", 1)[0]
        if closed is None:                      # the run falls back to the loop, bit for bit
            assert auto.energy == loop.energy and np.array_equal(auto.x_final, loop.x_final)
            continue
        kept += 1
        assert auto.energy == closed.energy
        assert_allclose(closed.energy, loop.energy, rtol=3e-10)
        assert_allclose(closed.input_energy, loop.input_energy, rtol=2e-11)
        # the final state of two exact methods agrees to rounding; on some CPUs (an AMD EPYC family 25
        # host: 1.1e-10 of the largest entry on one of these loops) the two round apart by a little
        # more than 1e-10, so 1e-9 of the largest entry: still a millionth of the energy's tolerance
        assert_allclose(closed.x_final, loop.x_final, rtol=0, atol=1e-9 * np.abs(loop.x_final).max())
        assert_allclose(closed.energy_cum, loop.energy_cum, rtol=3e-10, atol=0)
        assert_allclose(closed.input_energy_cum, loop.input_energy_cum, rtol=2e-11, atol=0)
        assert closed.t_cum.size == loop.t_cum.size and closed.switches == 0
        assert_allclose(closed.time_share, [1.0]) and closed.dwell_counts.sum() == 0
    assert 20 <= kept <= 70                     # both paths were exercised


def test_closed_form_refuses_what_would_lose_digits():
    # a constant input into a pole at −0.0165 rad/s for 1 s: steady state (60× the state) and
    # transient nearly annul each other; summed in closed form this lost 8 digits
    loop = paper_modes()["modes"][1]
    pr = _stream_setup._prepare(Case(loop, Sinusoids([2.0], [0.0], [1.0]), 1.0, 1e-3), "", None, None, None)
    assert _stream_run._closed_result(pr) is None
    # a step whose spectral radius is within 1e-6 of 1 (a pole at −1e-4 rad/s, Δt = 1 ms)
    slow = LTISystem([[-1e-4]], [[1.0]], [[1.0]], [[0.0]])
    prep = _stream_setup._prepare(Case(slow, Sinusoids([1.0], [1.0]), 100.0, 1e-3), "", None, None, None)
    assert not _stream_run._closed_form_applies(prep)
    # a traced run or a sampled input goes through the loop too
    pr = _stream_setup._prepare(Case(SCALAR, Sinusoids([1.0], [1.0]), 1.0, 1e-3), "", None, 0.1, None)
    assert not _stream_run._closed_form_applies(pr)


def test_closed_form_is_the_exact_integral_for_odd_and_even_point_counts():
    d = Sinusoids([1.0, 0.3], [2.0, 11.0], [0.1, 0.0])
    for horizon in (3.0, 3.001, 0.002, 0.001):       # 3001, 3002, 3 and 2 points
        traced = simulate_stream(SCALAR, d, horizon, 1e-3, trace_every=1e-3, x0=[0.5])
        closed = simulate_stream(SCALAR, d, horizon, 1e-3, x0=[0.5])
        ez, ed = _scalar_exact(d, 0.5, horizon)
        assert_allclose([closed.energy, closed.input_energy], [ez, ed], rtol=1e-12)
        assert_allclose(closed.x_final, traced.trace.x_lo[-1], rtol=1e-13)


def test_closed_form_flag_is_checked():
    with pytest.raises(TypeError, match="closed_form must be True or False"):
        simulate_stream(SCALAR, Sinusoids([1.0], [1.0]), 1.0, 1e-3, closed_form="yes")
    with pytest.raises(TypeError, match="closed_form must be True or False"):
        simulate_batch([Case(SCALAR, Sinusoids([1.0], [1.0]), 1.0, 1e-3)], closed_form=1)


@pytest.mark.parametrize("threads", [0, -1, 1.5, True, False, np.True_, "2"])
def test_threads_must_be_a_whole_number_not_a_bool(threads):
    with pytest.raises(ValueError, match="threads must be an integer >= 1"):
        simulate_batch([Case(SCALAR, Sinusoids([1.0], [1.0]), 1.0, 1e-3)], threads=threads)


def test_specialize_flag_is_checked():
    with pytest.raises(TypeError, match="specialize must be True, False or None"):
        simulate_stream(SCALAR, Sinusoids([1.0], [1.0]), 1.0, 1e-3, specialize="yes")
    with pytest.raises(TypeError, match="specialize must be True, False or None"):
        simulate_batch([Case(SCALAR, Sinusoids([1.0], [1.0]), 1.0, 1e-3)], specialize=1)


def test_by_default_only_long_runs_are_specialized(monkeypatch):
    tags = _spy_tags(monkeypatch)
    # as in a fresh process: no specialized loop loaded yet (another test may have loaded one)
    monkeypatch.setattr(_stream_run, "_has_loop_for", lambda tag: False)
    pm = paper_modes()
    kw = dict(law_bands=pm["bands"], law_Q=pm["Q"])
    short = simulate_stream(pm["modes"], mixed_disturbance(0.1), 10.0, 1e-3, **kw)
    # the flip at the threshold, on a threshold lowered to keep the test short (the default's
    # 5e7 steps would take seconds); the runs read the constant when called
    steps = 200_000
    monkeypatch.setattr(_stream_run, "UNROLL_MIN_STEPS", steps)
    for n_steps in (steps - 1, steps):
        simulate_stream(pm["modes"], mixed_disturbance(0.1), n_steps * 1e-3, 1e-3, **kw)
    forced = simulate_stream(pm["modes"], mixed_disturbance(0.1), 10.0, 1e-3, specialize=True, **kw)
    # specialized: 2 states, 3 outputs, 2 modes, 6 law products, 6 tones, sines, no traces
    assert [sum(len(t) for t in tag) for tag in tags] == [0, 0, 21, 21]
    assert forced.energy == short.energy and forced.switches == short.switches


def test_a_short_run_uses_a_specialized_loop_already_loaded(monkeypatch):
    pm = paper_modes()
    kw = dict(law_bands=pm["bands"], law_Q=pm["Q"])
    d = mixed_disturbance(0.1)
    forced = simulate_stream(pm["modes"], d, 2.0, 1e-3, specialize=True, **kw)   # loads it
    tags = _spy_tags(monkeypatch)
    short = simulate_stream(pm["modes"], d, 2.0, 1e-3, **kw)
    general = simulate_stream(pm["modes"], d, 2.0, 1e-3, specialize=False, **kw)
    # a size not loaded (3 tones instead of 6) stays general; 2 + 3 + 2 + 6 + 6 + 1 + 1 = 21
    simulate_stream(pm["modes"], Sinusoids([1.0] * 3, [1.0, 2.0, 3.0]), 2.0, 1e-3, **kw)
    sizes = [sum(len(t) for t in tag) for tag in tags]
    assert sizes[:2] == [21, 0] and (sizes[2] == 0 or _stream_run._has_loop_for(tags[2]))
    assert short.energy == forced.energy == general.energy and short.switches == general.switches


def test_breaks_outside_the_run_need_not_lie_on_the_grid():
    # a break before the start or after the end of the run cuts no step: off the grid it is
    # accepted and the run is that of the same disturbance with the break moved onto the grid
    from fdsc.simulate import simulate, time_grid

    one, two = Sinusoids([1.0], [3.0]), Sinusoids([0.5], [7.0], [0.3])
    off = Piecewise([-0.00035, 0.5, 2.00005], [one, two])
    on = Piecewise([0.0, 0.5, 3.0], [one, two])
    for closed in (True, False):
        a = simulate_stream(SCALAR, off, 1.0, 1e-3, closed_form=closed)
        b = simulate_stream(SCALAR, on, 1.0, 1e-3, closed_form=closed)
        assert (a.energy, a.input_energy) == (b.energy, b.input_energy) and a.input_energy > 0.1
    t = time_grid(1.0, 1e-3)
    assert np.array_equal(simulate(SCALAR, off, t).x, simulate(SCALAR, on, t).x)
    # inside the run the same offset is refused, by both simulators
    inside = Piecewise([0.0, 0.50035, 3.0], [one, two])
    with pytest.raises(ValueError, match="0.50035 s, which is not on the grid"):
        simulate_stream(SCALAR, inside, 1.0, 1e-3)
    with pytest.raises(ValueError, match="0.50035 s, which is not on the grid"):
        simulate(SCALAR, inside, t)
