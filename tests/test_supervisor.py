"""fdsc.supervisor: the predictive-cost supervisor on the disturbance estimate, against
independent runs (the fixed-gain run after its decision, the copies' monitoring signals, the
realization through copies), its scale independence, and bad input by name."""

import math
import warnings

import numpy as np
import pytest

from fdsc import (
    DimensionError,
    Piecewise,
    Plant,
    Sampled,
    Sinusoids,
    lqr_gain,
    shift_signal,
    simulate,
    supervise,
)
from fdsc.simulate import time_grid

# the README's oscillator with its LF and HF designs
PLANT = Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
              [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.1]])
GAINS = [np.array([[-21.85, -22.27]]), np.array([[0.495, -1.473]])]
DT = 1e-2
SLOW = Sinusoids([1.0, 0.5], [0.2, 0.3])


def _energy(loop, d, t0, t1, x0):
    """∫zᵀz of a fixed loop on [t0, t1] from x0 by the full-trajectory simulator."""
    run = simulate(loop, shift_signal(d, t0), time_grid(t1 - t0, DT), x0=x0)
    return run.energy(), run.x[-1]


def test_a_one_band_disturbance_gives_the_fixed_gain_run_after_the_first_decision():
    T = 60.0
    run = supervise(PLANT, GAINS, SLOW, T, DT, sigma0=1, warmup=5.0)   # starts on the HF gain
    # the first decision comes at the end of the warm-up
    assert run.sequence.tolist() == [1, 0] and run.switch_times[0] == pytest.approx(5.0)
    ts = run.switch_times[0]
    e1, x1 = _energy(PLANT.closed_loop(GAINS[1]), SLOW, 0.0, ts, np.zeros(2))
    e2, x2 = _energy(PLANT.closed_loop(GAINS[0]), SLOW, ts, T, x1)
    assert run.energy == pytest.approx(e1 + e2, rel=1e-9)
    np.testing.assert_allclose(run.x_final, x2, rtol=1e-9, atol=1e-12)
    assert run.time_share[0] == pytest.approx(1 - ts / T)


def test_the_monitoring_signals_are_the_copies_fading_energies():
    # before the first restart of either bank every copy runs from rest at t = 0: μ_i at the
    # decision points is the fading sum of the fixed loop i's energy over each decision
    # interval, here from the full-trajectory simulator (Simpson's rule on each interval, at a
    # step fine enough that its error, ~(ω h)⁴, is below the tolerance; μ itself is exact)
    lam, R, step, h = 0.5, 20.0, 0.1, 1e-3
    run = supervise(PLANT, GAINS, SLOW, 9.0, DT, forgetting=lam, restart=R, decide_every=step)
    t = time_grid(9.0, h)
    per = round(step / h)
    decay = math.exp(-lam * step)
    for i, K in enumerate(GAINS):
        z2 = np.sum(simulate(PLANT.closed_loop(K), SLOW, t).z ** 2, axis=1)
        ref = [0.0]
        for k in range(1, run.t_mu.size):
            block = z2[(k - 1) * per:k * per + 1]
            e = h / 3 * (block[0] + block[-1] + 4 * block[1:-1:2].sum() + 2 * block[2:-1:2].sum())
            ref.append(decay * ref[-1] + e)
        np.testing.assert_allclose(run.mu[:, i], ref, rtol=1e-8, atol=1e-14)
    np.testing.assert_allclose(run.t_mu, np.arange(91) * step)


def test_the_law_does_not_depend_on_the_disturbances_scale():
    d = Piecewise([0.0, 40.0, 100.0], [SLOW, Sinusoids([1.0], [12.0])])
    a = supervise(PLANT, GAINS, d, 100.0, DT)
    big = Piecewise(d.breaks, [p.scaled(1e3) for p in d.parts])
    b = supervise(PLANT, GAINS, big, 100.0, DT)
    assert a.sequence.tolist() == b.sequence.tolist()
    np.testing.assert_array_equal(a.switch_times, b.switch_times)
    assert b.energy == pytest.approx(1e6 * a.energy, rel=1e-9)
    assert 40.0 < a.switch_times[-1] < 50.0 and a.sequence[-1] == 1


def test_the_realization_through_copies_equals_the_fixed_run_without_switching():
    # plant and copies start equal, so x = x̂_σ for all time and u = K_σ x: the fixed-gain run
    x0 = np.array([0.3, -0.1])
    K0 = lqr_gain(PLANT)
    run = supervise(PLANT, GAINS, SLOW, 30.0, DT, K0=K0, x0=x0, hysteresis=1e9)
    assert run.switches == 0 and run.sequence.tolist() == [0]
    e, x = _energy(PLANT.closed_loop(GAINS[0]), SLOW, 0.0, 30.0, x0)
    assert run.energy == pytest.approx(e, rel=1e-9)
    np.testing.assert_allclose(run.x_final, x, rtol=1e-9, atol=1e-12)


def test_lqr_gain_solves_the_riccati_equation():
    K = lqr_gain(PLANT)
    A, B, C, D = PLANT.A, PLANT.B2, PLANT.C, PLANT.D2
    assert np.all(np.linalg.eigvals(A + B @ K).real < 0)
    # the optimal cost matrix P: K = −R⁻¹(BᵀP + DᵀC) and the Riccati residual vanishes
    R, S = D.T @ D, C.T @ D
    # K = −R⁻¹(BᵀP + Sᵀ) with P the stabilizing solution of AᵀP + PA − (PB + S)R⁻¹(BᵀP + Sᵀ) + CᵀC = 0:
    # recover P from the Lyapunov equation of the closed loop, (A + BK)ᵀP + P(A + BK) = −(C + DK)ᵀ(C + DK)
    from scipy.linalg import solve_continuous_lyapunov
    Acl, Ccl = A + B @ K, C + D @ K
    P = solve_continuous_lyapunov(Acl.T, -Ccl.T @ Ccl)
    np.testing.assert_allclose(K, -np.linalg.solve(R, B.T @ P + S.T), rtol=1e-8)


@pytest.mark.parametrize(("kwargs", "error", "match"), [
    (dict(gains=GAINS[:1]), ValueError, "at least two candidate gains"),
    (dict(gains=GAINS[0]), TypeError, "sequence of gains"),
    (dict(gains=[GAINS[0], np.zeros((1, 2)) + [[5.0, 0.0]]]), ValueError, r"gains\[1\] must stabilize"),
    (dict(gains=[GAINS[0], np.zeros((1, 3))]), DimensionError, r"gains\[1\]"),
    (dict(d=Sampled(np.zeros(11), DT)), TypeError, "d must be an fdsc.Sinusoids or fdsc.Piecewise"),
    (dict(forgetting=0.0), ValueError, "forgetting"),
    (dict(hysteresis=-0.1), ValueError, "hysteresis"),
    (dict(warmup=-1.0), ValueError, "warmup"),
    (dict(restart=0.15), ValueError, "restart must be at least two decision intervals"),
    (dict(decide_every=0.015, horizon=0.9), ValueError, "decide_every must be a whole number of steps"),
    (dict(decide_every=0.3), ValueError, "horizon must be a whole number of decision intervals"),
    (dict(sigma0=2), ValueError, r"sigma0 must be a candidate's index in \[0, 2\)"),
    (dict(sigma0=True), ValueError, "sigma0"),
    (dict(K0=np.array([[5.0, 0.0]])), ValueError, "K0 must stabilize"),
    (dict(K0=np.zeros((2, 2))), DimensionError, "K0"),
    (dict(x0=[1.0]), DimensionError, "x0"),
    (dict(horizon=0.015), ValueError, "horizon"),
])
def test_bad_input_is_refused_by_name(kwargs, error, match):
    args = dict(plant=PLANT, gains=GAINS, d=SLOW, horizon=1.0, dt=DT) | kwargs
    with pytest.raises(error, match=match):
        supervise(args.pop("plant"), args.pop("gains"), args.pop("d"), args.pop("horizon"),
                  args.pop("dt"), **args)


def test_a_plant_whose_disturbance_cannot_be_estimated_is_refused():
    two = Plant(PLANT.A, np.eye(2), PLANT.B2, PLANT.C, np.zeros((2, 2)), PLANT.D2)
    with pytest.raises(ValueError, match="one disturbance input"):
        supervise(two, GAINS, SLOW, 1.0, DT)
    blind = Plant(PLANT.A, np.zeros((2, 1)), PLANT.B2, PLANT.C, PLANT.D1, PLANT.D2)
    with pytest.raises(ValueError, match="B1 is zero"):
        supervise(blind, GAINS, SLOW, 1.0, DT)


def test_the_divergence_monitor_is_applied_at_the_switches(monkeypatch):
    # the rule itself is tested with the simulators (tests/test_divergence.py); here its plumbing:
    # a state beyond the monitor's threshold at a switch or at the end is warned about, once
    import warnings

    from fdsc import UnstableRunWarning, _divergence

    d = Piecewise([0.0, 40.0, 100.0], [SLOW, Sinusoids([1.0], [12.0])])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        supervise(PLANT, GAINS, d, 100.0, DT)                     # the real threshold: silent
    monkeypatch.setattr(_divergence, "threshold", lambda *a: 1e-12)
    with pytest.warns(UnstableRunWarning, match=r"supervise: the switched run diverges: at t = ") as rec:
        supervise(PLANT, GAINS, d, 100.0, DT)
    assert len([w for w in rec if issubclass(w.category, UnstableRunWarning)]) == 1


# --- the exact engine, the band-power law, the oracles --------------------------------------

import fdsc  # noqa: E402
from fdsc import Band, Supervisor, band_filter, freqresp, simulate_stream  # noqa: E402
from fdsc._blocks import Grid  # noqa: E402

TWO = Piecewise([0.0, 40.0, 100.0], [SLOW, Sinusoids([1.0], [12.0])])


def test_the_exact_engine_agrees_with_the_simulator_at_any_step():
    # both integrate every step exactly (the simulator's step energies are quadratic forms, not
    # a quadrature of its samples), so they agree to rounding whatever the simulator's step
    loop = PLANT.closed_loop(GAINS[1])
    d = Piecewise([1.0, 30.02, 60.0], [SLOW, Sinusoids([1.0, 0.3], [12.0, 3.0], [0.2, 0.1])])
    g = Grid(d, np.arange(0, 601) * 0.1)
    e, big, x = g.run(g.tables([(loop.A, loop.B, loop.C, loop.D)]), 0, False, np.zeros(2))
    for h in (2e-2, 1e-2, 5e-3):
        r = simulate_stream(loop, d, 60.0, h)
        np.testing.assert_allclose(r.energy, e.sum(), rtol=1e-11)
        np.testing.assert_allclose(x, r.x_final, rtol=1e-9, atol=1e-12)
    assert big[-1] == np.abs(x).max() and big.size == e.size == 601      # 600 steps and the break


def test_the_exact_engine_handles_a_stiff_loop():
    # a pole at −10⁶ /s over steps of 0.1 s: the block exponential is scaled and doubled
    from fdsc import LTISystem
    loop = LTISystem(np.diag([-1e6, -1.0]), [[1e6], [1.0]], [[1.0, 1.0]], [[0.0]])
    d = Sinusoids([1.0], [2.0])
    g = Grid(d, np.arange(0, 101) * 0.1)
    e, _big, x = g.run(g.tables([(loop.A, loop.B, loop.C, loop.D)]), 0, False, np.zeros(2))
    assert np.all(np.isfinite(e))
    r = simulate_stream(loop, d, 10.0, 1e-3)
    np.testing.assert_allclose(x, r.x_final, rtol=1e-8, atol=1e-12)
    # the 1 µs transient is inside the simulator's first step, and its energy in that step's form
    assert e.sum() == pytest.approx(r.energy, rel=1e-10)


def test_a_stepped_run_that_switches_a_stiff_loop_is_exact():
    # with a cheap control, a candidate with a mode at −2·10⁴ /s wins at once: at dt = 10 ms the
    # transient after the switch to it is sub-step; each step's energy is still exact (it was a
    # quadrature of the samples, which missed it, and a warning said so)
    cheap = Plant(PLANT.A, PLANT.B1, PLANT.B2, PLANT.C, PLANT.D1, [[0.0], [1e-4]])
    stiff = [GAINS[0], np.array([[-4.0e4, -2.0e4]])]
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        run = supervise(cheap, stiff, TWO, 100.0, 1e-2)
        exact = supervise(cheap, stiff, TWO, 100.0)
    assert run.sequence.tolist() == exact.sequence.tolist() == [0, 1]
    assert run.energy == pytest.approx(exact.energy, rel=1e-9)


def test_the_decisions_do_not_depend_on_the_step():
    a = supervise(PLANT, GAINS, TWO, 100.0, 1e-2)
    b = supervise(PLANT, GAINS, TWO, 100.0, 5e-3)
    c = supervise(PLANT, GAINS, TWO, 100.0)                  # exact
    for r in (b, c):
        np.testing.assert_array_equal(a.switch_times, r.switch_times)
        np.testing.assert_array_equal(a.sequence, r.sequence)
    assert a.dt == 1e-2 and c.dt is None
    assert c.energy == pytest.approx(b.energy, rel=1e-6) and a.energy == pytest.approx(b.energy, rel=1e-5)


def test_a_candidate_held_throughout_is_the_fixed_run_bit_for_bit():
    prep = Supervisor(PLANT, GAINS).prepare(TWO, 100.0, x0=[0.2, 0.0])
    for i in range(2):
        held = prep.run_sequence(np.full(prep.n_blocks, i))
        assert held.energy == prep.fixed(i) and held.switches == 0
        assert held.energy == prep.energy_of(PLANT.closed_loop(GAINS[i]))
        # the copies realization without a switch is the same loop: x = x̂_i throughout
        copies = prep.with_K0(lqr_gain(PLANT)).run_sequence(np.full(prep.n_blocks, i))
        assert copies.energy == pytest.approx(held.energy, rel=1e-9)


def test_segment_laws_and_the_clairvoyant_oracle():
    prep = Supervisor(PLANT, GAINS).prepare(TWO, 120.0)
    spans = prep.piece_steps()
    assert len(spans) == 3                                    # the two pieces and the silent tail
    fixed = [prep.fixed(i) for i in range(2)]
    for i in range(2):
        assert prep.segment_law([i] * 3) == pytest.approx(fixed[i], rel=1e-12)
    energy, choice = prep.clairvoyant()
    # on each piece the least energy from the carried state; here LF gain, then HF gain
    assert choice[:2] == [0, 1]
    assert energy == pytest.approx(prep.segment_law(choice), rel=1e-12)
    assert energy < min(fixed)
    with pytest.raises(ValueError, match="one candidate per piece"):
        prep.segment_law([0, 1])
    # one piece: the oracle is the best fixed gain
    one = Supervisor(PLANT, GAINS).prepare(SLOW, 50.0)
    assert one.clairvoyant()[0] == min(one.fixed(0), one.fixed(1))


def test_the_band_power_law_picks_the_gain_of_the_band_that_holds_the_power():
    bands = [Band.lf(1.0), Band.hf(5.0)]
    run = supervise(PLANT, GAINS, TWO, 100.0, law="band_power", bands=bands, warmup=2.0, sigma0=1)
    assert run.sequence.tolist() == [1, 0, 1]
    assert run.switch_times[0] == pytest.approx(2.0)          # its first decision
    assert 40.0 < run.switch_times[1] < 45.0
    # one band throughout: after the first decision, the fixed-gain run of that band
    prep = Supervisor(PLANT, GAINS, law="band_power", bands=bands).prepare(SLOW, 60.0)
    r = prep.run(warmup=2.0, sigma0=1)
    assert r.sequence.tolist() == [1, 0]
    sigma = np.r_[np.ones(20, dtype=int), np.zeros(580, dtype=int)]
    assert r.energy == prep.run_sequence(sigma).energy


def test_band_filters_pass_their_band():
    for band, inside, outside in ((Band.lf(1.0), 0.1, 10.0), (Band.hf(10.0), 100.0, 1.0),
                                  (Band.mf(1.0, 10.0), 3.0, 100.0)):
        f = band_filter(band)
        g = np.abs(freqresp(f, [inside, outside])[:, 0, 0])
        assert g[0] > 0.95 and g[1] < 0.02
    assert np.abs(freqresp(band_filter(Band.entire()), [0.1, 100.0])[:, 0, 0]).tolist() == [1.0, 1.0]


def test_the_minimum_dwell_is_enforced():
    d = Piecewise(np.arange(0.0, 101.0, 5.0), [SLOW if k % 2 == 0 else Sinusoids([1.0], [12.0])
                                               for k in range(20)])
    free = supervise(PLANT, GAINS, d, 100.0, forgetting=5.0, hysteresis=0.0)
    held = supervise(PLANT, GAINS, d, 100.0, forgetting=5.0, hysteresis=0.0, min_dwell=12.0)
    assert np.min(np.diff(free.switch_times)) < 12.0
    assert np.all(np.diff(held.switch_times) >= 12.0 - 1e-9) and held.switches < free.switches


@pytest.mark.parametrize(("kwargs", "error", "match"), [
    (dict(law="state"), ValueError, "law"),
    (dict(law="band_power"), ValueError, "bands must give one Band per gain"),
    (dict(law="band_power", bands=[Band.lf(1.0)]), ValueError, "bands must give one Band per gain"),
    (dict(bands=[Band.lf(1.0), Band.hf(2.0)]), ValueError, "bands is used by the band-power law only"),
    (dict(law="band_power", bands=[Band.lf(1.0), "HF"]), TypeError, "band"),
    (dict(min_dwell=-1.0), ValueError, "min_dwell"),
])
def test_bad_law_options_are_refused_by_name(kwargs, error, match):
    with pytest.raises(error, match=match):
        supervise(PLANT, GAINS, SLOW, 1.0, **kwargs)


def test_a_sequence_of_the_wrong_shape_is_refused():
    prep = Supervisor(PLANT, GAINS).prepare(SLOW, 1.0)
    with pytest.raises(ValueError, match="sigma must be an integer array of one candidate index"):
        prep.run_sequence(np.zeros(3, dtype=int))
    with pytest.raises(ValueError, match="sigma must be an integer array"):
        prep.run_sequence(np.full(10, 0.7))
    with pytest.raises(ValueError, match=r"sigma must hold candidate indices in \[0, 2\), but found 0 to 2"):
        prep.run_sequence(np.r_[np.zeros(9, dtype=int), 2])
    with pytest.raises(ValueError, match="sigma must hold candidate indices"):
        prep.run_sequence(np.full(10, -1))


@pytest.mark.parametrize(("call", "error", "match"), [
    (lambda p: p.segment_law([0, 100000000]), ValueError, r"choice\[1\] must be a candidate's index"),
    (lambda p: p.segment_law([0, -1]), ValueError, r"choice\[1\] must be a candidate's index"),
    (lambda p: p.segment_law([0.5, 1.5]), ValueError, r"choice\[0\] must be a candidate's index"),
    (lambda p: p.segment_law(None), TypeError, "choice must be a sequence"),
    (lambda p: p.fixed(-1), ValueError, r"i must be a candidate's index in \[0, 2\)"),
    (lambda p: p.fixed(1.5), ValueError, "i must be a candidate's index"),
    (lambda p: p.fixed(True), ValueError, "i must be a candidate's index"),
    (lambda p: p.decide(np.zeros((3, 2))), ValueError, r"mu must be a float array of shape \(501, 2\)"),
    (lambda p: p.decide(np.full((501, 2), np.nan)), ValueError, "mu must hold finite, non-negative"),
    (lambda p: p.decide(-np.ones((501, 2))), ValueError, "mu must hold finite, non-negative"),
    (lambda p: p.decide(np.zeros(501)), ValueError, "mu must be a float array"),
    (lambda p: p.energy_of(np.eye(2)), TypeError, "loop must be an fdsc.LTISystem"),
    (lambda p: p.energy_of(PLANT.closed_loop(GAINS[0]).__class__(np.eye(1) * -1, np.ones((1, 1)),
                                                                    np.ones((1, 1)), [[0.0]])),
     DimensionError, "loop must have at least the plant's 2 states"),
    (lambda p: p.energy_of(PLANT.closed_loop(np.array([[5.0, 0.0]]))), ValueError, "loop must be stable"),
])
def test_prepared_refuses_bad_input_by_name(call, error, match):
    prep = Supervisor(PLANT, GAINS).prepare(TWO, 50.0)         # two pieces, 500 decisions
    with pytest.raises(error, match=match):
        call(prep)


def test_the_energies_scale_with_the_disturbance_squared_up_to_huge_amplitudes():
    # the oscillators carry the amplitudes, so the step tables do not depend on them
    d = Piecewise([0.0, 40.0, 100.0], [Sinusoids([1.0, 0.5], [0.2, 0.3]), Sinusoids([1.0], [12.0])])
    ref = supervise(PLANT, GAINS, d, 100.0)
    for a in (1e-100, 1e12, 1e100):
        big = Piecewise(d.breaks, [p.scaled(a) for p in d.parts])
        r = supervise(PLANT, GAINS, big, 100.0)
        np.testing.assert_array_equal(r.switch_times, ref.switch_times)
        assert r.energy == pytest.approx(a * a * ref.energy, rel=1e-9)
        assert r.input_energy == pytest.approx(a * a * ref.input_energy, rel=1e-9)
    huge = Piecewise(d.breaks, [p.scaled(1e160) for p in d.parts])
    with pytest.raises(fdsc.EnergyOverflowError, match="exceeds the float range"):
        supervise(PLANT, GAINS, huge, 100.0)


def test_band_filters_refuse_edges_they_cannot_resolve():
    with pytest.raises(ValueError, match=r"resolves band edges in \[1e-6, 1e6\]"):
        band_filter(Band.hf(1e8))
    with pytest.raises(ValueError, match=r"bands\[1\]: .*resolves band edges"):
        supervise(PLANT, GAINS, SLOW, 1.0, law="band_power", bands=[Band.lf(1.0), Band.hf(1e8)])
    with pytest.raises(TypeError, match=r"bands\[0\]: band must be an fdsc.Band"):
        supervise(PLANT, GAINS, SLOW, 1.0, law="band_power", bands=[(0, 1), Band.hf(5.0)])


def test_lqr_gain_refuses_a_plant_it_cannot_stabilize():
    # a double integrator whose cost sees nothing: the LQR "gain" is zero and does not stabilize
    blind = Plant([[0.0, 1.0], [0.0, 0.0]], [[0.0], [1.0]], [[0.0], [1.0]], [[0.0, 0.0]], [[0.0]], [[1.0]])
    with pytest.raises(ValueError, match="does not stabilize|no stabilizing solution"):
        lqr_gain(blind)


def test_shift_signal_refuses_a_bad_shift():
    for tau in ("1", None, np.nan, True):
        with pytest.raises(ValueError, match="tau must be a finite real number"):
            shift_signal(SLOW, tau)


def test_the_restart_period_used_is_reported():
    assert Supervisor(PLANT, GAINS, restart=0.25).restart == pytest.approx(0.2)


def test_an_estimate_drives_the_decisions_only():
    prep = Supervisor(PLANT, GAINS).prepare(TWO, 100.0)
    same = Supervisor(PLANT, GAINS).prepare(TWO, 100.0, estimate=TWO)
    np.testing.assert_array_equal(prep.E, same.E)
    # an estimate that is the fast tone throughout: the law picks the HF gain from the start,
    # while the plant still runs under d (its fixed runs are d's)
    fast = Sinusoids([1.0], [12.0])
    wrong = Supervisor(PLANT, GAINS).prepare(TWO, 100.0, estimate=fast)
    assert wrong.fixed(0) == prep.fixed(0)
    a, b = wrong.run(warmup=1.0), prep.run(warmup=1.0)
    assert a.sequence.tolist() == [0, 1] and a.switch_times[0] < 2.0
    assert b.sequence[-1] == 1 and b.switch_times[-1] > 40.0     # the exact estimate: at the break
    with pytest.raises(TypeError, match="estimate must be an fdsc.Sinusoids or fdsc.Piecewise"):
        Supervisor(PLANT, GAINS).prepare(TWO, 100.0, estimate=[1.0])
