"""Tests of fdsc.observer: the disturbance observer from sampled, noisy measurements of x."""

import numpy as np
import pytest
from scipy.linalg import expm

from fdsc import LTISystem, Plant
from fdsc.exceptions import DimensionError
from fdsc.observer import DisturbanceObserver, random_walk_model

PLANT = Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
              [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.3]])


def test_the_sampled_plant_is_the_exact_one():
    obs = DisturbanceObserver(PLANT, 0.05, 1e-4)
    # a random walk held constant: the augmented plant is (A, B1; 0, 0) with u held
    F = np.block([[PLANT.A, PLANT.B1], [np.zeros((1, 3))]])
    np.testing.assert_allclose(obs.Phi, expm(F * 0.05), rtol=1e-13, atol=1e-15)
    # the process noise over a step: ∫₀ʰ e^{Fs} G Q Gᵀ e^{Fᵀs} ds, by a fine quadrature
    G = np.array([[0.0], [0.0], [1.0]])
    s = np.linspace(0.0, 0.05, 2001)
    vals = np.array([expm(F * t) @ G @ G.T @ expm(F * t).T for t in s])
    Q = np.trapezoid(vals, s, axis=0)
    np.testing.assert_allclose(obs.process_noise, Q, rtol=1e-6, atol=1e-14)


def test_the_riccati_identities_hold():
    obs = DisturbanceObserver(PLANT, 0.02, 1e-3, intensity=5.0)
    P, Pf, L, H = obs.prior_covariance, obs.covariance, obs.gain, obs.H
    # P⁻ = Φ P⁺ Φᵀ + Q_d and P⁺ = (I − L H) P⁻, with L = P⁻Hᵀ(H P⁻Hᵀ + R)⁻¹
    np.testing.assert_allclose(obs.Phi @ Pf @ obs.Phi.T + obs.process_noise, P, rtol=1e-9, atol=1e-14)
    np.testing.assert_allclose(L, P @ H.T @ np.linalg.inv(H @ P @ H.T + obs.measurement_noise),
                               rtol=1e-10, atol=1e-14)
    np.testing.assert_allclose(obs.estimate_covariance, Pf[2:, 2:], rtol=1e-12)


def test_without_noise_the_error_follows_the_error_dynamics_exactly():
    obs = DisturbanceObserver(PLANT, 0.01, 1e-6, intensity=10.0)
    rng = np.random.default_rng(3)
    u = rng.standard_normal((300, 1))
    y, u = obs.noiseless_run([0.3, -0.2], u, d=0.7)
    _w_hat, xi = obs.estimate(y, u)
    # the true augmented state, sampled; e_0 = (I − L H)(ξ_0 − 0), then e_k = (I − LH)Φ e_{k−1}
    true = np.empty_like(xi)
    state = np.array([0.3, -0.2, 0.7])
    for k in range(len(u)):
        true[k] = state
        state = obs.Phi @ state + obs.Gamma @ u[k]
    err = true - xi
    np.testing.assert_allclose(err[0], (np.eye(3) - obs.gain @ obs.H) @ true[0], atol=1e-14)
    for k in range(1, len(u)):
        np.testing.assert_allclose(err[k], obs.error_dynamics @ err[k - 1], rtol=1e-9, atol=1e-13)


def test_the_error_covariance_of_a_long_noisy_run_is_the_riccati_one():
    obs = DisturbanceObserver(PLANT, 0.02, 1e-3, intensity=2.0)
    rng = np.random.default_rng(11)
    K = 60_000
    Lq = np.linalg.cholesky(obs.process_noise + 1e-300 * np.eye(3))
    Lr = np.linalg.cholesky(obs.measurement_noise)
    state, y = np.zeros(3), np.empty((K, 2))
    true = np.empty((K, 3))
    for k in range(K):
        true[k] = state
        y[k] = state[:2] + Lr @ rng.standard_normal(2)
        state = obs.Phi @ state + Lq @ rng.standard_normal(3)
    w, xi = obs.estimate(y, np.zeros((K, 1)))
    err = (true - xi)[1000:]
    cov = err.T @ err / len(err)
    # sampling error of a variance over ~59,000 correlated steps: a few per cent
    np.testing.assert_allclose(np.diag(cov), np.diag(obs.covariance), rtol=0.08)
    assert abs(np.mean((w[1000:, 0] - true[1000:, 2]) ** 2) / obs.estimate_covariance[0, 0] - 1) < 0.08


def test_more_noise_gives_a_worse_estimate():
    v = [DisturbanceObserver(PLANT, 0.01, r).estimate_covariance[0, 0] for r in (1e-6, 1e-4, 1e-2)]
    assert v[0] < v[1] < v[2]


def test_a_shaping_model_with_outputs_of_its_own():
    # d as a lightly damped resonator at 3 rad/s (two states)
    model = LTISystem([[0.0, 1.0], [-9.0, -0.3]], [[0.0], [1.0]], [[1.0, 0.0]], [[0.0]])
    obs = DisturbanceObserver(PLANT, 0.01, 1e-6, model=model)
    assert obs.n_states == 4 and obs.estimate_covariance.shape == (1, 1)
    assert np.max(np.abs(np.linalg.eigvals(obs.error_dynamics))) < 1


def test_bad_input_is_refused_by_name():
    with pytest.raises(ValueError, match="step"):
        DisturbanceObserver(PLANT, 0.0, 1e-3)
    with pytest.raises(ValueError, match="noise"):
        DisturbanceObserver(PLANT, 0.01, -1.0)
    with pytest.raises(ValueError, match="noise must be positive definite"):
        DisturbanceObserver(PLANT, 0.01, [[1.0, 0.0], [0.0, 0.0]])
    with pytest.raises(DimensionError, match="noise"):
        DisturbanceObserver(PLANT, 0.01, np.eye(3))
    with pytest.raises(ValueError, match="intensity"):
        DisturbanceObserver(PLANT, 0.01, 1e-3, intensity=0.0)
    with pytest.raises(DimensionError, match="model must have as many outputs"):
        DisturbanceObserver(PLANT, 0.01, 1e-3, model=random_walk_model(2))
    with pytest.raises(TypeError, match="model"):
        DisturbanceObserver(PLANT, 0.01, 1e-3, model="walk")
    with pytest.raises(ValueError, match="m must be"):
        random_walk_model(0)
    obs = DisturbanceObserver(PLANT, 0.01, 1e-3)
    with pytest.raises(DimensionError, match="y"):
        obs.estimate(np.zeros((5, 3)), np.zeros((5, 1)))
    with pytest.raises(DimensionError, match="u"):
        obs.estimate(np.zeros((5, 2)), np.zeros((4, 1)))
    with pytest.raises(DimensionError, match="prior"):
        obs.estimate(np.zeros((5, 2)), np.zeros((5, 1)), prior=np.zeros(2))


def test_a_disturbance_that_never_shows_in_x_is_refused():
    blind = Plant(PLANT.A, [[0.0], [0.0]], PLANT.B2, PLANT.C, PLANT.D1, PLANT.D2)
    with pytest.raises(ValueError, match="cannot be estimated from x"):
        DisturbanceObserver(blind, 0.01, 1e-3)
