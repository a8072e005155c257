import numpy as np
import pytest
from numpy.testing import assert_allclose

from fdsc import Band, DimensionError, LTISystem, Sinusoids, UnstableError
from fdsc.energy import (
    average_power,
    fdeef,
    fdeef_autonomous,
    fdeef_parseval_autonomous,
    instantaneous_power,
    steady_state_power,
)
from fdsc.simulate import simulate, time_grid

A = np.array([[-1.0, 2.0], [-2.0, -0.5]])
B = np.array([[1.0], [0.5]])
Q = np.array([[2.0, 0.3], [0.3, 1.0]])
TONE = Sinusoids([1.0], [1.0])
SYS = LTISystem(A, B, np.eye(2), np.zeros((2, 1)))


def modal_solution(A, x0, t):
    lam, V = np.linalg.eig(A)
    c = np.linalg.solve(V, x0)
    x = ((np.exp(np.outer(t, lam)) * c) @ V.T).real
    return x, x @ A.T


@pytest.mark.parametrize("band", [Band.lf(1.0), Band.mf(1.0, 3.0), Band.hf(2.0)])
def test_autonomous_fdeef_three_ways(band):
    # Lyapunov closed form, Parseval quadrature and Simpson on the modal solution agree
    x0 = np.array([1.0, -0.5])
    t = np.linspace(0.0, 60.0, 60001)  # e^{-0.75·60} ≈ 3e-20: the tail is negligible
    x, xd = modal_solution(A, x0, t)
    ref = fdeef_autonomous(SYS, x0, band, Q)
    assert_allclose(fdeef_parseval_autonomous(SYS, x0, band, Q), ref, rtol=1e-9)
    assert_allclose(fdeef(t, x, xd, band, Q), ref, rtol=1e-9)


def test_long_horizon_average_power_matches_the_frequency_domain():
    # time-domain P_a over a long window → Parseval value; the difference is the transient
    # energy and the finite-window cross terms, both O(1/T): with T = 2000 s a 1e-3 tolerance
    d = Sinusoids([1.0, 0.7], [0.3, 4.0], [0.2, 1.0])
    sys = LTISystem(A, B, np.eye(2), np.zeros((2, 1)))
    sim = simulate(sys, d, time_grid(2000.0, 2e-3))
    for band in (Band.lf(1.0), Band.hf(2.0)):
        exact = steady_state_power(SYS, d, band, Q).total
        assert_allclose(average_power(sim.t, sim.x, sim.xdot, band, Q), exact, rtol=1e-3)


def test_integral_of_instantaneous_power_is_the_fdeef():
    d = Sinusoids([1.0], [0.5])
    sys = LTISystem(A, B, np.eye(2), np.zeros((2, 1)))
    sim = simulate(sys, d, time_grid(50.0, 1e-3))
    p = instantaneous_power(sim.x, sim.xdot, Band.lf(1.0), Q)
    trap = float(np.sum(0.5 * (p[1:] + p[:-1])) * 1e-3)
    assert_allclose(trap, fdeef(sim.t, sim.x, sim.xdot, Band.lf(1.0), Q), rtol=1e-6)


def test_selectiveness_on_random_frequency_limited_signals():
    rng = np.random.default_rng(5)
    for _ in range(30):
        Qr = rng.standard_normal((2, 2))
        Qr = Qr @ Qr.T + 0.01 * np.eye(2)
        lf = Sinusoids(rng.uniform(0.1, 2, 2), np.sort(rng.uniform(0.05, 0.95, 2)))
        hf = Sinusoids(rng.uniform(0.1, 2, 2), np.sort(rng.uniform(11, 200, 2)))
        for d, inside, outside in ((lf, Band.lf(1.0), Band.hf(10.0)), (hf, Band.hf(10.0), Band.lf(1.0))):
            assert steady_state_power(SYS, d, inside, Qr).total > 0
            assert steady_state_power(SYS, d, outside, Qr).total < 0


def test_remark1_split_adds_up():
    d = Sinusoids([1.0, 1.0], [0.5, 20.0])
    s = steady_state_power(SYS, d, Band.lf(1.0), Q)
    assert s.in_band > 0 > s.out_of_band
    assert_allclose(s.in_band + s.out_of_band, s.total, rtol=1e-14)


def test_mf_power_of_real_signals_is_negative():
    d = Sinusoids([1.0], [5.0])  # inside [1, 10]
    assert steady_state_power(SYS, d, Band.mf(1.0, 10.0), Q).total < 0


@pytest.mark.parametrize(
    ("call", "exc", "match"),
    [
        (lambda: fdeef([0.0, 1.0], np.zeros((2, 2)), np.zeros((2, 2)), Band.lf(1.0), Q), ValueError,
         "at least 3 samples"),
        (lambda: fdeef([0.0, 2.0, 1.0], np.zeros((3, 2)), np.zeros((3, 2)), Band.lf(1.0), Q), ValueError,
         "increasing"),
        (lambda: instantaneous_power(np.zeros((3, 2)), np.zeros((3, 2)), Band.lf(1.0), -Q), ValueError,
         "Q must be positive definite"),
        (lambda: instantaneous_power(np.zeros((3, 2)), np.zeros((3, 2)), Band.lf(1.0), [[1, 2], [0, 1]]),
         ValueError, "Q must be symmetric"),
        (lambda: instantaneous_power(np.zeros((3, 2)), np.zeros((3, 2)), Band.lf(1.0), np.eye(3)),
         DimensionError, r"Q: expected shape \(2, 2\)"),
        (lambda: instantaneous_power(np.zeros((3, 2)), np.zeros((4, 2)), Band.lf(1.0), Q), DimensionError,
         r"xdot: expected shape \(3, 2\) but found \(4, 2\)"),
        (lambda: steady_state_power((-A, B, np.eye(2), np.zeros((2, 1))), TONE, Band.lf(1.0), Q),
         UnstableError, "sys is not stable: A has the eigenvalue .* needs a Hurwitz A"),
        (lambda: steady_state_power((A, np.eye(2), np.eye(2), np.zeros((2, 2))), TONE, Band.lf(1.0), Q),
         DimensionError, "one disturbance input"),
    ],
)
def test_bad_energy_inputs(call, exc, match):
    with pytest.raises(exc, match=match):
        call()


def test_energy_accepts_every_system_form():
    # one boundary: LTISystem, (A, B, C, D) and a python-control StateSpace give the same numbers
    import control

    d = Sinusoids([1.0, 0.5], [0.4, 7.0])
    forms = [SYS, (A, B, np.eye(2), np.zeros((2, 1))), control.ss(A, B, np.eye(2), np.zeros((2, 1)))]
    powers = [steady_state_power(f, d, Band.hf(2.0), Q).total for f in forms]
    energies = [fdeef_autonomous(f, [1.0, 0.0], Band.lf(1.0), Q) for f in forms]
    assert powers[0] == powers[1] == powers[2]
    assert energies[0] == energies[1] == energies[2]
