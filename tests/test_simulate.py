import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.linalg import expm

from fdsc import LTISystem, Sinusoids
from fdsc.exceptions import MemoryLimitError
from fdsc.paper.shared.data import (
    aircraft,
    lf_disturbance,
    mixed_disturbance,
    paper_disturbance,
    paper_gains,
    paper_modes,
    piecewise_disturbance,
)
from fdsc.simulate import particular, simulate, time_grid


def modal(A, y0, t):
    lam, V = np.linalg.eig(A)
    return ((np.exp(np.outer(t, lam)) * np.linalg.solve(V, y0)) @ V.T).real


def test_lti_matches_closed_form():
    cl = aircraft().closed_loop(paper_gains()["K_f1"])
    d = lf_disturbance()
    t = time_grid(100.0, 1e-3)
    sim = simulate(cl, d, t, x0=[0.1, -0.2])
    xp, _ = particular(cl.A, cl.B, d, t)
    ref = xp + modal(cl.A, np.array([0.1, -0.2]) - xp[0], t)  # x = x_p + e^{At}(x0 − x_p(0))
    assert_allclose(sim.x, ref, atol=1e-12)
    assert_allclose(sim.xdot, sim.x @ cl.A.T + np.outer(sim.d, cl.B[:, 0]), atol=1e-12)


def test_lti_energy_equals_closed_form():
    # steady state of a single tone: z = Im(Z e^{jωt}), ∫ z² over whole periods = |Z|² T / 2
    sys = LTISystem([[-2.0]], [[1.0]], [[1.0]], [[0.0]])
    w = 1.0
    d = Sinusoids([1.0], [w])
    T = 2 * np.pi * 200
    xp, _ = particular(sys.A, sys.B, d, [0.0])
    sim = simulate(sys, d, time_grid(T, T / 400_000), x0=xp[0])  # start on the steady state
    Z = 1 / (1j * w + 2)
    assert_allclose(sim.energy(), abs(Z) ** 2 * T / 2, rtol=1e-9)


def test_numba_kernel_equals_numpy_reference():
    pm = paper_modes()
    t = time_grid(5.0, 1e-3)
    for law in ("previous", "candidate"):
        kw = dict(law_bands=pm["bands"], law_Q=pm["Q"], law=law, x0=[0.01, -0.02])
        a = simulate(pm["modes"], mixed_disturbance(0.1), t, kernel="numba", **kw)
        b = simulate(pm["modes"], mixed_disturbance(0.1), t, kernel="numpy", **kw)
        assert np.array_equal(a.sigma, b.sigma)
        # x_p from rotated phasors (compiled) or from NumPy's cos and sin (reference): the two
        # agree to rounding, measured against the size of the run's state
        scale = np.abs(b.x).max()
        assert_allclose(a.x, b.x, rtol=0, atol=1e-12 * scale)
        assert_allclose(a.z, b.z, rtol=0, atol=1e-12 * np.abs(b.z).max())
        assert_allclose(a.d, b.d, rtol=0, atol=1e-12 * np.abs(b.d).max())



@pytest.mark.parametrize("law", ["previous", "candidate"])
def test_numba_kernel_equals_numpy_reference_on_second_order_weights_and_rules(law):
    # the compiled kernel writes the scores and the rule out in its loop: three modes, weights
    # on [ẍ; ẋ; x] (the ẍ path), a window with hysteresis and a dwell time, two pieces of tones
    from fdsc import Piecewise, SwitchRule
    from fdsc.random_systems import random_hurwitz

    rng = np.random.default_rng(11)
    n, nm = 3, 3
    B, D = rng.standard_normal((n, 1)), rng.standard_normal((2, 1))
    modes = [LTISystem(random_hurwitz(rng, n), B, rng.standard_normal((2, n)), D) for _ in range(nm)]
    W = [M + M.T for M in rng.standard_normal((nm, 3 * n, 3 * n))]
    d = Piecewise([0.0, 2.0, 4.0], [Sinusoids([1.0, 0.5], [3.0, 40.0]), Sinusoids([0.8], [9.0], [0.3])])
    rule = SwitchRule(margin=0.02, dwell=0.005, window=0.01)
    t = time_grid(4.0, 1e-3)
    kw = dict(law_weights=W, law=law, rule=rule, x0=rng.standard_normal(n), sigma0=2)
    a = simulate(modes, d, t, kernel="numba", **kw)
    b = simulate(modes, d, t, kernel="numpy", **kw)
    assert a.switch_times.size > 5 and set(np.unique(a.sigma)) == {0, 1, 2}
    assert np.array_equal(a.sigma, b.sigma)
    assert_allclose(a.x, b.x, rtol=1e-12, atol=1e-13 * np.abs(b.x).max())


def test_compiled_kernel_rebases_phasors_on_an_offset_grid_with_pieces():
    # the compiled kernel rotates the tones' phasors, re-based by cos and sin every PHASOR_BLOCK
    # steps and at each piece: a grid that starts at t0 ≠ 0, spans about 90 blocks and ends on
    # the last break (d = 0 there by the Piecewise convention), with d = 0 before the first break,
    # against the NumPy reference, whose x_p, d come from cos and sin of ω t_k + φ on the grid
    from fdsc import Piecewise
    from fdsc._simulate_kernel import PHASOR_BLOCK

    sys = LTISystem([[-0.5, 2.0], [-2.0, -0.5]], [[1.0], [0.5]], [[1.0, 0.0], [0.0, 2.0]], [[0.2], [0.0]])
    d = Piecewise([1.0, 3.0, 5.0], [Sinusoids([1.0, 0.3], [7.0, 40.0], [0.2, 1.0]), Sinusoids([0.5], [3.0])])
    t = 0.5 + time_grid(4.5, 1e-4)
    assert t.size > 80 * PHASOR_BLOCK
    a = simulate(sys, d, t, x0=[0.3, -0.1])
    b = simulate(sys, d, t, x0=[0.3, -0.1], kernel="numpy")
    assert_allclose(a.d, d(t), rtol=0, atol=1e-13)
    assert a.d[-1] == 0.0 and np.all(a.d[t < 1.0 - 1e-9] == 0.0) and np.abs(a.d).max() > 1.0
    for u, v in ((a.x, b.x), (a.xdot, b.xdot), (a.z, b.z)):
        assert_allclose(u, v, rtol=0, atol=1e-12 * np.abs(v).max())
    # the reference is exact too: before the first break the state decays freely
    k = int(np.searchsorted(t, 1.0 - 1e-9))
    free = np.array([expm(sys.A * (tk - t[0])) @ [0.3, -0.1] for tk in t[:k:997]])
    assert_allclose(a.x[:k:997], free, rtol=0, atol=1e-13)


def test_compiled_kernel_needs_the_trajectories_and_its_tone_tables():
    # the compiled kernel builds no per-step particular solutions: less than a third of the
    # reference's memory for the paper's sizes (n = 2, p = 3, two modes, six tones) ...
    from fdsc import Piecewise
    from fdsc._simulate_kernel import _segments, tone_tables
    from fdsc.simulate import estimate_memory

    assert 3 * estimate_memory(10**6, 2, 3, 2, 6) < estimate_memory(10**6, 2, 3, 2, 6, kernel="numpy")
    with pytest.raises(ValueError, match="kernel"):
        estimate_memory(10, 2, 3, 2, kernel="jax")
    # ... but tone tables per piece: the estimate counts exactly what tone_tables allocates, for
    # many short pieces (tables of piece length) as for one long one (tables of a block)
    pm = paper_modes()
    A, B = np.array([m.A for m in pm["modes"]]), pm["modes"][0].B[:, 0]
    hf = paper_disturbance("HF")
    for t, d in ((time_grid(9.999, 1e-3), Piecewise(np.append(time_grid(9.999, 1e-3)[::10], 9.999),
                                                    [hf] * 1000)),
                 (time_grid(5.0, 1e-3), hf)):
        pieces = _segments(d, t)
        longest = max(k1 - k0 for k0, k1, _ in pieces)
        tables = sum(a.nbytes for a in tone_tables(pieces, t, A, B, 1e-3).values())
        full = estimate_memory(t.size, 2, 3, 2, 3, n_pieces=len(pieces), longest_piece=longest)
        assert full - estimate_memory(t.size, 2, 3, 2, 3, n_pieces=0) == tables
        # and simulate refuses the run from that estimate on
        with pytest.raises(MemoryLimitError):
            simulate(pm["modes"], d, t, law_bands=pm["bands"], law_Q=pm["Q"], max_memory=full - 1)
        simulate(pm["modes"], d, t, law_bands=pm["bands"], law_Q=pm["Q"], max_memory=full)


def test_both_kernels_cut_a_piecewise_at_the_grid_index_of_its_breaks():
    # the paper's piecewise disturbance on a time_grid: its last break 0.63 lies an ulp above
    # t[630] = 0.6299999999999999; the steps and the samples both cut the pieces by index, so
    # d[630] is the value after the break (0: the disturbance is off) in both kernels
    pm = paper_modes()
    d = piecewise_disturbance(0.3, 0.1, 0.1)
    t = time_grid(1.13, 1e-3)
    assert t[630] < d.breaks[-1] == 0.63 and d(t[630]) != 0.0
    kw = dict(law_bands=pm["bands"], law_Q=pm["Q"])
    a, b = simulate(pm["modes"], d, t, **kw), simulate(pm["modes"], d, t, kernel="numpy", **kw)
    assert a.d[630] == b.d[630] == 0.0 and a.d[629] != 0.0
    assert np.array_equal(a.sigma, b.sigma)
    assert_allclose(a.x, b.x, rtol=0, atol=1e-12 * np.abs(b.x).max())


def test_switching_law_picks_the_argmax():
    pm = paper_modes()
    t = time_grid(2.0, 1e-3)
    sim = simulate(pm["modes"], mixed_disturbance(0.2), t, law_bands=pm["bands"], law_Q=pm["Q"])
    A = [m.A for m in pm["modes"]]
    prev = 0
    for k in range(0, t.size, 37):
        prev = sim.sigma[k - 1] if k else 0
        xd = A[prev] @ sim.x[k] + pm["modes"][0].B[:, 0] * sim.d[k]
        v = np.concatenate([xd, sim.x[k]])
        scores = [v @ np.kron(b.psi.real, Q) @ v for b, Q in zip(pm["bands"], pm["Q"], strict=True)]
        assert sim.sigma[k] == int(np.argmax(scores))


def test_piecewise_run_equals_restarted_runs():
    # the piecewise run is the LTI run of each segment restarted from the state at the break
    cl = aircraft().closed_loop(paper_gains()["K_f1"])
    d = piecewise_disturbance(5.0, 0.2, 0.1)  # HF on [0, 5), LF on [5, 6), HF on [6, 11)
    t = time_grid(11.0, 1e-3)
    sim = simulate(cl, d, t)
    first = simulate(cl, d.parts[0], t[:5001])
    assert_allclose(sim.x[:5001], first.x, atol=1e-13)
    second = simulate(cl, d.parts[1], t[5000:6001] - 0.0, x0=sim.x[5000])
    assert_allclose(sim.x[5000:6001], second.x, atol=1e-12)


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda m, b, q: time_grid(1.0, 0.0), "dt must be a positive"),
        (lambda m, b, q: time_grid(1.0, 0.3), "multiple of dt"),
        (lambda m, b, q: simulate(m, lf_disturbance(), time_grid(1, 0.1), law_bands=b[:1], law_Q=q),
         "one entry per mode"),
        (lambda m, b, q: simulate(m, lf_disturbance(), time_grid(1, 0.1), law_bands=b,
                                  law_Q=[q[0], -q[1]]), "Q must be positive definite"),
        (lambda m, b, q: simulate(m, lf_disturbance(), time_grid(1, 0.1), law_bands=b, law_Q=q,
                                  law="future"), "law must be one of"),
        (lambda m, b, q: simulate(m, piecewise_disturbance(0.5525, 0.2, 0.1), time_grid(1, 0.005),
                                  law_bands=b, law_Q=q), "0.5525 s, which is not on the grid"),
        (lambda m, b, q: simulate(m, piecewise_disturbance(0.55, 0.2, 0.1), time_grid(1, 0.1),
                                  law_bands=b, law_Q=q), "dt = 0.1 s does not resolve piece 0"),
        (lambda m, b, q: simulate(m, lf_disturbance(), np.array([0.0, 0.1, 0.3]), law_bands=b,
                                  law_Q=q), "uniform"),
    ],
)
def test_bad_simulation_inputs(call, match):
    pm = paper_modes()
    with pytest.raises(ValueError, match=match):
        call(pm["modes"], pm["bands"], pm["Q"])
