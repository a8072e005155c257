"""fdsc.noncausal and its engine fdsc._modal: the non-causal limit against closed forms (a single
tone's per-frequency optimum, the stationary Riccati cost), a forward simulation of its own
control, the Hamiltonian identity on a plant with every cross term, the bound against fixed
loops, and bad input by name."""

import math

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp

from fdsc import (
    LTISystem,
    Piecewise,
    Plant,
    Sinusoids,
    loop_energy,
    lq_data,
    lqr_gain,
    noncausal_limit,
    random_hurwitz,
    tone_limit,
)
from fdsc._modal import Modal, tone_terms

P1 = Plant([[-1.0]], [[1.0]], [[1.0]], [[1.0], [0.0]], [[0.0], [0.0]], [[0.0], [0.5]])
# a lightly damped oscillator, u penalized, the disturbance on the velocity
P2 = Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
           [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.3]])
D3 = Piecewise([0.0, 4.0, 9.0, 15.0], [Sinusoids([1.0, 0.3], [0.7, 6.0], [0.2, 1.0]),
                                       Sinusoids([0.8], [2.5]), Sinusoids([0.5, 0.5], [0.3, 11.0])])


def test_the_scalar_tone_limit_is_the_distance_from_the_range_of_the_control_response():
    # ẋ = −x + d + u, z = [x; ρu]: with g = 1/(jω + 1), min_u |g(1 + u)|² + ρ²|u|² = |g|²ρ²/(|g|² + ρ²)
    w = np.array([0.0, 0.5, 2.0, 30.0])
    g2 = 1.0 / (w ** 2 + 1.0)
    np.testing.assert_allclose(tone_limit(P1, w), g2 * 0.25 / (g2 + 0.25), rtol=1e-12)


@pytest.mark.parametrize("w", [0.7, 2.0, 9.0])
def test_a_long_single_tone_reaches_the_per_frequency_bound(w):
    # the energy's growth between two long horizons, whole periods apart and ending at one phase:
    # the start from rest, the end effect and the oscillating part of the power all cancel
    d = Sinusoids([1.3], [w], [0.4])
    T = 2 * math.pi / w
    H1, H2 = T * round(1000.0 / T), T * round(3000.0 / T)
    grow = (noncausal_limit(P2, d, H2).energy - noncausal_limit(P2, d, H1).energy) / (H2 - H1)
    assert grow == pytest.approx(0.5 * 1.3 ** 2 * tone_limit(P2, [w])[0], rel=1e-9)


def test_from_a_state_without_disturbance_the_limit_is_the_stationary_riccati_cost():
    # d = 0 over a long horizon: J* = x0ᵀ P x0 (the end effect is e^{2 λ H}, negligible)
    x0 = np.array([0.7, -1.2])
    lim = noncausal_limit(P2, Sinusoids([0.0], [1.0]), 60.0, x0=x0)
    assert lim.energy == pytest.approx(float(x0 @ lq_data(P2).P @ x0), rel=1e-10)


def test_the_limits_own_control_run_forward_gives_its_energy_and_trajectory():
    lim = noncausal_limit(P2, D3, 15.0)
    times = np.linspace(0.0, 15.0, 3001)
    traj = lim.trajectory(times)

    def u_of(t):
        return lim.trajectory([t])["u"][0]

    def rhs(t, y):
        x, _e = y[:2], y[2]
        u = u_of(t)
        z = P2.C @ x + P2.D1[:, 0] * D3(t) + P2.D2 @ u
        return np.r_[P2.A @ x + P2.B1[:, 0] * D3(t) + P2.B2 @ u, z @ z]

    sol = solve_ivp(rhs, (0.0, 15.0), np.zeros(3), t_eval=times, rtol=1e-11, atol=1e-13,
                    max_step=0.01)
    np.testing.assert_allclose(sol.y[:2].T, traj["x"], atol=1e-7)
    assert sol.y[2, -1] == pytest.approx(lim.energy, rel=1e-6)


def test_the_hamiltonian_identity_holds_with_feedthrough_and_cross_terms():
    # z = C x + D1 d + D2 u with D1 ≠ 0 and Cᵀ D2 ≠ 0: J* = ∫ λᵀB̃1 d + xᵀN d + dᵀD̃ d dt,
    # λ = P x + ξ, N = CᵀΠD1, D̃ = D1ᵀΠD1 (the cost's quadratic terms cancel along the optimum)
    rng = np.random.default_rng(3)
    A = random_hurwitz(rng, 3)
    C = rng.normal(size=(3, 3))
    D1 = rng.normal(size=(3, 1))
    D2 = rng.normal(size=(3, 1))
    plant = Plant(A, rng.normal(size=(3, 1)), rng.normal(size=(3, 1)), C, D1, D2)
    lim = noncausal_limit(plant, D3, 15.0)
    lq = lim.lq
    R = float((D2.T @ D2)[0, 0])
    Pi = np.eye(3) - D2 @ D2.T / R
    t = np.linspace(0.0, 15.0, 60001)
    tr = lim.trajectory(t)
    d = D3(t)
    lam = tr["x"] @ lq.P + tr["xi"]
    f = lam @ lq.B1t[:, 0] * d + tr["x"] @ (C.T @ Pi @ D1)[:, 0] * d + float((D1.T @ Pi @ D1)[0, 0]) * d * d
    cost = np.sum(tr["z"] ** 2, axis=1)
    assert np.trapezoid(cost, t) == pytest.approx(lim.energy, rel=1e-5)
    assert np.trapezoid(f, t) == pytest.approx(lim.energy, rel=1e-5)


@pytest.mark.parametrize("seed", range(4))
def test_no_fixed_loop_has_less_energy_than_the_limit(seed):
    rng = np.random.default_rng(seed)
    K = lqr_gain(P2) + 0.3 * rng.normal(size=(1, 2))
    loop = P2.closed_loop(K)
    if not loop.is_hurwitz():
        pytest.skip("this perturbation does not stabilize")
    lim = noncausal_limit(P2, D3, 15.0)
    assert lim.energy <= loop_energy(loop, D3, 15.0) * (1 + 1e-12)
    assert lim.energy <= loop_energy(P2.closed_loop(lqr_gain(P2)), D3, 15.0)


def test_the_engine_integrates_a_tail_anchored_at_the_end_of_a_piece():
    # ẋ = −x + e^{a(τ − L)}, z = x, x(0) = 0: x = (e^{a(τ−L)} − e^{−τ − aL}) / (a + 1); a long piece
    # (e^{aL} overflows) is integrated without overflow
    a, L = 3.0, 400.0
    m = Modal([[-1.0]], [[1.0]])
    e, an, g, xL = m.piece(np.zeros(1), [a], [True], [[1.0]], [[0.0]], L)
    exact, _err = quad(lambda s: ((math.exp(a * (s - L)) - math.exp(-s - a * L)) / (a + 1)) ** 2,
                       L - 30.0, L, epsabs=0.0, epsrel=1e-13)
    assert float(Modal.gram(e, an, g, L)[0, 0]) == pytest.approx(exact, rel=1e-12)
    assert xL[0] == pytest.approx(1.0 / (a + 1), rel=1e-14)


def test_the_engine_agrees_with_the_block_exponentials_on_tones():
    rng = np.random.default_rng(1)
    A = random_hurwitz(rng, 4)
    B, C, D = rng.normal(size=(4, 1)), rng.normal(size=(2, 4)), rng.normal(size=(2, 1))
    d = Sinusoids([1.0, 0.4], [0.7, 3.1], [0.2, 1.0])
    s, c = tone_terms(0.0, d.frequencies, d.amplitudes, d.phases)
    e, an, g, _x = Modal(A, C).piece(np.zeros(4), s, np.zeros(s.size, dtype=bool),
                                      c[:, None] * B[:, 0], c[:, None] * D[:, 0], 13.7)
    assert np.trace(Modal.gram(e, an, g, 13.7)) == pytest.approx(
        loop_energy(LTISystem(A, B, C, D), d, 13.7), rel=1e-11)


def test_the_gram_sums_repeated_terms_and_forms_half_of_its_hermitian_integrals():
    # the same tones entering twice (a disturbance and its exact estimate) and a tail anchored at
    # the end: the Gram of the terms as given equals the Gram formed term by term over the full
    # matrix of pair integrals, and the one of the repeated terms summed by hand
    from fdsc._modal import pair_integrals

    rng = np.random.default_rng(4)
    s = np.r_[1j * 2.0, -1j * 2.0, 0.3, 1j * 2.0, -1j * 2.0, -0.5 + 1j, -0.5 - 1j]
    an = np.array([False, False, True, False, False, False, False])
    g = rng.normal(size=(7, 2)) + 1j * rng.normal(size=(7, 2))
    L = 3.7
    full = (g.conj().T @ pair_integrals(s.conj(), an, s, an, L) @ g).real
    G, size = Modal.gram(s, an, g, L, bound=True)
    np.testing.assert_allclose(G, full, rtol=1e-13, atol=1e-13 * np.abs(full).max())
    keep = [0, 1, 2, 5, 6]
    summed = g[keep].copy()
    summed[0] += g[3]
    summed[1] += g[4]
    np.testing.assert_allclose(Modal.gram(s[keep], an[keep], summed, L), G, rtol=1e-13,
                               atol=1e-13 * np.abs(G).max())
    assert size >= np.trace(G) > 0
    # the same exponent anchored at the other end is another term: not summed
    an2 = an.copy()
    an2[3] = True
    full2 = (g.conj().T @ pair_integrals(s.conj(), an2, s, an2, L) @ g).real
    np.testing.assert_allclose(Modal.gram(s, an2, g, L), full2, rtol=1e-12, atol=1e-12 * np.abs(full2).max())


@pytest.mark.parametrize("plant, d, horizon, kw, err, match", [
    (Plant([[-1.0]], [[1.0]], [[1.0]], [[1.0]], [[0.0]], [[0.0]]), D3, 5.0, {}, ValueError,
     r"D2 must have full column rank"),
    (Plant([[-1.0]], [[1.0, 1.0]], [[1.0]], [[1.0], [0.0]], [[0.0, 0.0], [0.0, 0.0]], [[0.0], [1.0]]), D3,
     5.0, {}, ValueError, r"one disturbance input"),
    (P1, np.ones(3), 5.0, {}, TypeError, r"d must be an fdsc.Sinusoids or fdsc.Piecewise"),
    (P1, D3, 0.0, {}, ValueError, r"horizon"),
    (P1, D3, 5.0, {"x0": [0.0, 1.0]}, ValueError, r"x0: expected 1 entries"),
    (P1, D3, 5.0, {"x0": [math.nan]}, ValueError, r"x0 must have finite entries"),
])
def test_bad_input_is_refused_by_name(plant, d, horizon, kw, err, match):
    with pytest.raises(err, match=match):
        noncausal_limit(plant, d, horizon, **kw)


def test_a_tone_on_a_pole_of_the_plant_is_refused():
    undamped = Plant([[0.0, 1.0], [-4.0, 0.0]], [[0.0], [1.0]], [[0.0], [1.0]],
                     [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.3]])
    with pytest.raises(ValueError, match=r"omega\[0\] = 2.0 lies on a pole"):
        tone_limit(undamped, [2.0])


# --- bad and edge input: small penalties, bad times, extreme scales, horizons too short


def test_a_small_control_penalty_gets_the_riccati_solution_not_zero():
    # ẋ = −x + d + u, z = [x; ρu]: P = ρ²(√(1 + ρ⁻²) − 1); at ρ = 1e-8 the solver returned P = 0
    rho = 1e-8
    plant = Plant([[-1.0]], [[1.0]], [[1.0]], [[1.0], [0.0]], [[0.0], [0.0]], [[0.0], [rho]])
    assert lq_data(plant).P[0, 0] == pytest.approx(rho ** 2 * (math.sqrt(1 + rho ** -2) - 1), rel=1e-9)
    H = math.pi * 30                                     # whole periods of the tone at 2 rad/s
    assert noncausal_limit(plant, Sinusoids([1.0], [2.0]), H).energy / H == pytest.approx(
        0.5 * tone_limit(plant, [2.0])[0], rel=1e-6)


@pytest.mark.parametrize("t, err, match", [
    ([math.nan], ValueError, r"t must have finite entries"),
    ([[1.0, 2.0]], ValueError, r"t must be a 1-D array"),
    ("abc", ValueError, r"t must be a numeric vector"),
])
def test_the_trajectory_refuses_bad_times_by_name(t, err, match):
    lim = noncausal_limit(P1, Sinusoids([1.0], [2.0]), 5.0)
    with pytest.raises(err, match=match):
        lim.trajectory(t)


def test_psi_gain_refuses_a_non_finite_frequency_by_name():
    with pytest.raises(ValueError, match=r"omega must have finite entries"):
        lq_data(P1).psi_gain([math.nan])


def test_a_tiny_disturbance_keeps_its_digits_and_says_its_energy_underflows():
    from fdsc import EnergyUnderflowWarning

    d = Sinusoids([1.0], [2.0])
    ref = noncausal_limit(P1, d, 5.0)
    with pytest.warns(EnergyUnderflowWarning, match=r"noncausal_limit: the energy"):
        tiny = noncausal_limit(P1, d.scaled(1e-160), 5.0)
    assert tiny.energy == pytest.approx(ref.energy * 1e-320, rel=1e-3)          # subnormal: 3 digits
    small = noncausal_limit(P1, d.scaled(1e-100), 5.0)                            # run at scale
    assert small.energy == pytest.approx(ref.energy * 1e-200, rel=1e-12)
    np.testing.assert_allclose(small.trajectory([2.0])["x"], 1e-100 * ref.trajectory([2.0])["x"], rtol=1e-12)


def test_a_horizon_too_short_for_the_closed_forms_is_said_to_lose_its_digits():
    # over 1e-12 s every term of the closed form is about H and the energy about H³: it came out
    # negative without a word
    with pytest.warns(RuntimeWarning, match=r"closed-form terms that cancel"):
        noncausal_limit(P1, Sinusoids([1.0], [2.0], [1.0]), 1e-12)
