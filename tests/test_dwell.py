import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.linalg import expm

from fdsc import DimensionError, IterationLimitError, LTISystem, UnstableError
from fdsc.dwell import (
    DwellTimeBound,
    check_dwell_bound,
    dwell_time_bound,
    lyapunov_dwell,
    periodic_dwell_margin,
    random_dwell_signal,
    switched_states,
)

# P = I is a common Lyapunov function: A1 + A1ᵀ = −2I, A2 + A2ᵀ = diag(−4, −6)
COMMON = [np.array([[-1.0, 2.0], [-2.0, -1.0]]), np.array([[-2.0, 0.0], [0.0, -3.0]])]
# both modes have the double eigenvalue −1; their average [[−1, 2], [2, −1]] has the eigenvalue +1,
# so fast periodic switching diverges
PAIR = [np.array([[-1.0, 4.0], [0.0, -1.0]]), np.array([[-1.0, 0.0], [4.0, -1.0]])]


@pytest.fixture(scope="module")
def pair_bound():
    return dwell_time_bound(PAIR)


def _check_certificate(b, A):
    # recompute everything the certificate claims from its P_i alone
    for a, p in zip(A, b.P, strict=True):
        assert np.linalg.eigvalsh(p).min() > 0
        assert np.linalg.eigvalsh(a.T @ p + p @ a + 2 * b.decay * p).max() < 0
    mu = max(np.linalg.eigvals(np.linalg.solve(b.P[i], b.P[j])).real.max()
             for i in range(len(A)) for j in range(len(A)) if i != j)
    assert_allclose(b.mu, max(mu, 1.0), rtol=1e-9)
    assert_allclose(b.tau, np.log(b.mu) / (2 * b.decay), rtol=1e-12)


def test_common_lyapunov_function_gives_mu_one_and_zero_dwell():
    b = dwell_time_bound(COMMON)
    # closed form: μ = 1 exactly (a common P), so τ* = 0; among the λ's with τ* = 0 the largest
    # is kept, and the limit is the slower mode's rate 1
    assert b.mu == 1.0 and b.tau == 0.0
    assert_allclose(b.decay_limits, [1.0, 2.0], rtol=1e-12)
    assert 0.95 < b.decay < 1.0
    assert_allclose(b.P[0], b.P[1], rtol=0, atol=0)
    assert_allclose(b.rate(1.0), 2 * b.decay, rtol=1e-12)
    _check_certificate(b, COMMON)


def test_scalar_modes():
    # scalar modes −1 and −3: any common p > 0 is a Lyapunov function with decay < 1, so μ = 1,
    # and the crude form (max p / min p) can be made 1 too
    b = dwell_time_bound([[[-1.0]], [[-3.0]]], decay=0.5)
    assert b.mu == 1.0 and b.tau == 0.0 and b.decays.tolist() == [0.5]
    assert_allclose(b.mu_crude, 1.0, rtol=1e-6)
    assert b.n_failed == 0


def test_pair_bound_is_consistent_and_not_below_periodic_instability(pair_bound):
    b = pair_bound
    _check_certificate(b, PAIR)
    assert b.decays.size == 2 * 16 and np.all(np.diff(b.decays) > 0)
    assert_allclose(b.taus, np.log(b.mus) / (2 * b.decays), rtol=1e-12)
    assert b.tau == b.taus.min()
    # the generalized-eigenvalue μ never exceeds the crude λ_max/λ_min form
    assert np.all(b.mus <= b.mus_crude * (1 + 1e-9))
    assert b.tau_crude >= b.tau
    # periodic switching with both dwells ≥ τ diverges up to τ ≈ 2.18 s (grid below), so every
    # valid dwell bound must exceed that; τ* ≈ 2.68 s does
    m = periodic_dwell_margin(PAIR, np.linspace(0.01, 4.0, 400))
    assert m.lower_bound > 2.0
    assert b.tau >= m.lower_bound
    assert b.rate(1.01 * b.tau) > 0 > b.rate(0.99 * b.tau)


def test_bound_is_invariant_under_time_scaling_and_similarity():
    lam = 0.6
    ref = dwell_time_bound(PAIR, decay=lam)
    # ẋ = cAx is the same system on the time scale t/c: λ → cλ, τ* → τ*/c, μ unchanged
    fast = dwell_time_bound([4.0 * a for a in PAIR], decay=4.0 * lam)
    assert_allclose(fast.mu, ref.mu, rtol=3e-3)
    assert_allclose(fast.tau, ref.tau / 4.0, rtol=3e-3)
    # x = T x': P_i → TᵀP_iT leaves the generalized eigenvalues (μ) unchanged
    T = np.array([[1.0, 2.0], [0.5, 3.0]])
    sim = dwell_time_bound([np.linalg.solve(T, a @ T) for a in PAIR], decay=lam)
    assert_allclose(sim.mu, ref.mu, rtol=3e-3)


def test_envelope_and_decay_hold_along_random_signals_with_dwell_above_the_bound(pair_bound):
    b = pair_bound
    rng = np.random.default_rng(7)
    t = np.linspace(0.0, 40.0, 801)
    for _ in range(5):
        st, seq = random_dwell_signal(rng, 2, 1.05 * b.tau, 40.0, max_dwell=2.0 * b.tau)
        c = check_dwell_bound(b, PAIR, rng.standard_normal(2), st, seq, t)
        assert c.n_switches >= 7 and c.min_dwell >= 1.05 * b.tau
        assert c.rate_bound > 0
        assert c.holds()
        assert c.max_ratio <= 1 + 1e-9
        assert c.final_norm_ratio < 1e-3


def test_fast_switching_diverges_and_the_envelope_still_holds(pair_bound):
    # counter-check: switching every 0.2 s (far below the periodic-instability dwell) diverges;
    # the envelope V ≤ μ^N e^{−2λt} V(0) holds for every signal, but grows
    st = 0.2 * np.arange(1, 100)
    seq = np.arange(100) % 2
    c = check_dwell_bound(pair_bound, PAIR, [1.0, 1.0], st, seq, np.linspace(0.0, 20.0, 201))
    assert c.final_norm_ratio > 10.0
    assert c.max_ratio <= 1 + 1e-9
    assert c.rate_bound < 0


def test_periodic_margin_closed_forms():
    taus = np.array([0.1, 0.5, 1.0])
    # scalar (commuting) modes −1, −3: ρ = e^{−4τ}; growth = −4τ/(2τ) = −2; worst pair (τ, τ)
    m = periodic_dwell_margin([[[-1.0]], [[-3.0]]], taus)
    assert_allclose(m.rho, np.exp(-4 * taus), rtol=1e-12)
    assert_allclose(m.growth, -2.0, rtol=1e-12)
    assert_allclose(m.rho_worst, np.exp(-4 * taus), rtol=1e-12)
    assert m.lower_bound == 0.0
    # fast switching tends to the average matrix, whose eigenvalue +1 sets the growth rate
    fast = periodic_dwell_margin(PAIR, [1e-3])
    assert_allclose(fast.growth[0], 1.0, rtol=1e-2)
    # three modes: equal dwells only
    m3 = periodic_dwell_margin([PAIR[0], PAIR[1], COMMON[1]], taus)
    assert np.all(np.isnan(m3.rho_worst)) and m3.rho.shape == taus.shape


def test_switched_states_matches_commuting_closed_form():
    # diagonal modes commute: x(t) = exp(Σ_i A_i · time spent in mode i) x0
    A = [np.diag([-1.0, -0.5]), np.diag([-0.2, -2.0])]
    st, seq = np.array([0.7, 1.5, 2.0]), np.array([0, 1, 0, 1])
    t = np.array([0.0, 0.7, 1.0, 2.5])
    x = switched_states([LTISystem(a, np.ones((2, 1)), np.eye(2), np.zeros((2, 1))) for a in A],
                        [1.0, 2.0], st, seq, t)
    in_0 = np.array([0.0, 0.7, 0.7, 0.7 + 0.5])
    in_1 = t - in_0
    ref = np.array([expm(A[0] * a + A[1] * b) @ [1.0, 2.0] for a, b in zip(in_0, in_1, strict=True)])
    assert_allclose(x, ref, rtol=1e-12)


def test_bisection_cap_raises():
    with pytest.raises(IterationLimitError, match="bisection on ln\\(mu\\)"):
        dwell_time_bound(PAIR, decay=0.5, max_bisections=1)


def test_dwell_time_bound_result_is_frozen(pair_bound):
    assert isinstance(pair_bound, DwellTimeBound)
    with pytest.raises(AttributeError):
        pair_bound.tau = 0.0
    with pytest.raises(ValueError):
        pair_bound.P[0][0, 0] = 1.0


@pytest.mark.parametrize(
    ("call", "exc", "match"),
    [
        (lambda: dwell_time_bound(PAIR[0]), TypeError, "modes must be a list"),
        (lambda: dwell_time_bound(PAIR[:1]), ValueError, "at least two modes"),
        (lambda: dwell_time_bound([PAIR[0], -np.eye(3)]), ValueError, "share the state dimension"),
        (lambda: dwell_time_bound([PAIR[0], np.ones((2, 3))]), DimensionError, "modes\\[1\\] must be square"),
        (lambda: dwell_time_bound([PAIR[0], np.diag([-1.0, 0.5])]), UnstableError,
         "modes\\[1\\] is not stable"),
        (lambda: dwell_time_bound(PAIR, decay=1.0), ValueError, "decay must be below"),
        (lambda: dwell_time_bound(PAIR, decay=-0.1), ValueError, "decay must be a positive"),
        (lambda: dwell_time_bound(PAIR, n_decays=0), ValueError, "n_decays must be an integer"),
        (lambda: dwell_time_bound(PAIR, tau_rtol=1.5), ValueError, "tau_rtol must be in"),
        (lambda: dwell_time_bound(PAIR, margin=0.0), ValueError, "margin must be a positive"),
        (lambda: periodic_dwell_margin(PAIR, [1.0, 0.5]), ValueError, "taus must be positive and"),
        (lambda: periodic_dwell_margin(PAIR, [[1.0]]), DimensionError, "taus must be a 1-D"),
        (lambda: random_dwell_signal(np.random.default_rng(0), 2, 1.0, 5.0, max_dwell=0.5),
         ValueError, "max_dwell must be >="),
        (lambda: random_dwell_signal(0, 2, 1.0, 5.0), TypeError, "rng must be"),
        (lambda: random_dwell_signal(np.random.default_rng(0), 1, 1.0, 5.0), ValueError,
         "n_modes must be an integer >= 2"),
        (lambda: switched_states(PAIR, [1.0, 0.0], [1.0], [0, 0], [0.0]), ValueError,
         "sequence must change mode"),
        (lambda: switched_states(PAIR, [1.0, 0.0], [1.0], [0], [0.0]), ValueError,
         "one mode per interval"),
        (lambda: switched_states(PAIR, [1.0, 0.0], [2.0, 1.0], [0, 1, 0], [0.0]), ValueError,
         "switch_times must be positive and strictly"),
        (lambda: switched_states(PAIR, [1.0, 0.0], [1.0], [0, 2], [0.0]), ValueError,
         "mode indices in"),
        (lambda: switched_states(PAIR, [1.0], [1.0], [0, 1], [0.0]), DimensionError,
         "x0: expected 2 entries"),
        (lambda: switched_states(PAIR, [1.0, 0.0], [1.0], [0, 1], [-1.0]), ValueError, "t must be >= 0"),
    ],
)
def test_bad_inputs(call, exc, match):
    with pytest.raises(exc, match=match):
        call()


@pytest.mark.parametrize(
    ("args", "exc", "match"),
    [
        (("bound",), TypeError, "bound must be an fdsc.dwell.DwellTimeBound"),
        (("modes",), ValueError, "modes must be the 2 modes"),
        (("x0",), ValueError, "x0 must be nonzero"),
        (("t",), ValueError, "t must start at 0"),
    ],
)
def test_bad_check_inputs(args, exc, match):
    b = dwell_time_bound(COMMON, decay=0.5)
    kw = {"bound": b, "modes": COMMON, "x0": [1.0, 0.0], "switch_times": [1.0], "sequence": [0, 1],
          "t": [0.0, 1.0, 2.0]}
    bad = {"bound": "b", "modes": COMMON + [COMMON[0]], "x0": [0.0, 0.0], "t": [0.5, 1.0]}
    kw[args[0]] = bad[args[0]]
    with pytest.raises(exc, match=match):
        check_dwell_bound(**kw)


def test_lyapunov_dwell_closed_form_and_agreement_with_the_bound(pair_bound):
    # scalar modes −1, −3 with p = 1, 2: rates a_i, μ = max(2/1, 1/2) = 2, τ = ln 2 / 2
    r = lyapunov_dwell([[[-1.0]], [[-3.0]]], [[[1.0]], [[2.0]]])
    assert_allclose(r.rates, [1.0, 3.0], rtol=1e-12)
    assert r.mu == 2.0 and r.mu_crude == 2.0
    assert_allclose(r.tau, np.log(2.0) / 2.0, rtol=1e-12)
    # evaluated at the bound's own P_i: same μ, and each mode decays at least at λ
    g = lyapunov_dwell(PAIR, list(pair_bound.P))
    assert_allclose(g.mu, pair_bound.mu, rtol=1e-12)
    assert g.decay >= pair_bound.decay and g.tau <= pair_bound.tau
    # P = I is no Lyapunov matrix of a mode with A + Aᵀ indefinite: no dwell time certified
    bad = lyapunov_dwell(PAIR, [np.eye(2), 2 * np.eye(2)])
    assert bad.decay < 0 and bad.tau == np.inf


@pytest.mark.parametrize(
    ("P", "match"),
    [
        ([np.eye(2)], "one matrix per mode"),
        ([np.eye(2), -np.eye(2)], "P\\[1\\] must be symmetric positive definite"),
        ([np.eye(2), np.array([[1.0, 0.5], [0.0, 1.0]])], "P\\[1\\] must be symmetric"),
        ([np.eye(2), np.eye(3)], "P\\[1\\]: expected shape"),
    ],
)
def test_bad_lyapunov_dwell_inputs(P, match):
    with pytest.raises(ValueError, match=match):
        lyapunov_dwell(PAIR, P)
