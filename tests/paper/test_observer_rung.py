"""The ladder with ŵ from a disturbance observer (fdsc.paper.pays.observer_rung): the observer
against its closed forms (the Riccati equation, F(0) = 1, the error's independence of the
controller, the exact samples of F(s) d and the noise's stationary law), bad input refused, and
the stored result against the stored study, the bound and a recomputation."""

import math

import numpy as np
import pytest

import fdsc
from fdsc._closed_energy import closed_form_energies
from fdsc.controller import Controller
from fdsc.measurement_noise import noise_power
from fdsc.paper.pays import observer_rung as ob
from fdsc.plant import LTISystem

EXAMPLES = ("aircraft", "generic")


@pytest.fixture(scope="module")
def small():
    """A lightly damped plant, a controller u = K x + Q(s) ŵ on it, and an observer."""
    p = fdsc.Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
                   [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.3]])
    ctrl = Controller([[-2.0]], [[0.0, 0.0]], [[0.5]], [[-1.0, -0.8]], [[2.0]], [[-0.6]], name="c")
    S = np.array([1e-3, 2e-3])
    Ae, L, G, P = ob.kalman_bucy(p, S, 5.0)
    return p, ctrl, S, Ae, L, G, P


def test_the_observer_solves_its_riccati_equation_and_estimates_a_constant_exactly(small):
    p, _c, S, Ae, L, G, P = small
    n = p.n_states
    Fa = np.block([[p.A, p.B1], [np.zeros((1, n + 1))]])
    H = np.hstack([np.eye(n), np.zeros((n, 1))])
    res = Fa @ P + P @ Fa.T - P @ H.T @ np.diag(1 / S) @ H @ P + 5.0 * G @ G.T
    assert np.max(np.abs(res)) < 1e-9 * np.max(np.abs(P))
    assert np.max(np.linalg.eigvals(Ae).real) < 0
    F, N = ob.observer_filters(Ae, L, G)
    # a constant d is estimated exactly in steady state; the noise's filter has no direct term
    assert (F.C @ np.linalg.solve(-F.A, F.B))[0, 0] == pytest.approx(1.0, abs=1e-12)
    assert N.B.shape == (n + 1, n) and not np.any(N.D)


def test_the_observers_error_does_not_depend_on_the_controller(small):
    # the controller with its observer (reading x alone) and the controller reading F(s) d have
    # the same loop on d: the observer knows u, so its error is F(s) d − d whatever u is
    p, c, _S, Ae, L, G, _P = small
    d = fdsc.Piecewise([0.0, 3.0, 7.5], [fdsc.Sinusoids([1.0, 0.4], [1.3, 5.0]),
                                         fdsc.Sinusoids([0.7], [2.2])])
    e_obs = closed_form_energies(p.closed_loop(ob.with_observer(c, p, Ae, L)), [d], [10.0])[0][0]
    e_fb = closed_form_energies(p.closed_loop(ob.filtered_base(c, Ae, G)), [d], [10.0])[0][0]
    assert e_obs == pytest.approx(e_fb, rel=1e-10)
    # and the observer costs something against the exact estimate
    assert e_obs != pytest.approx(closed_form_energies(p.closed_loop(c), [d], [10.0])[0][0], rel=1e-3)
    # a controller that does not read ŵ is left as it is
    k = Controller.static([[-1.0, -1.0]])
    assert ob.with_observer(k, p, Ae, L) is k


def test_the_sensors_noise_power_is_the_sum_over_the_states(small):
    p, c, S, Ae, L, _G, _P = small
    co = ob.with_observer(c, p, Ae, L)
    loop = ob.sensor_loop(p, co)
    each = [noise_power(LTISystem(loop.A, loop.B[:, [i]], loop.C, loop.D[:, [i]]), S[i], 50.0)
            for i in range(2)]
    assert ob.sensor_noise_power(p, co, S, 50.0) == pytest.approx(sum(each), rel=1e-12)
    # the static part K reads the noise too: a controller without the observer still sees it
    assert ob.sensor_noise_power(p, Controller.static([[-1.0, -1.0]]), S, 50.0) > 0
    with pytest.raises(ValueError, match="reads ŵ: give it with its observer"):
        ob.sensor_loop(p, c)


def test_the_laws_samples_of_the_observers_output_are_exact_and_its_noise_has_the_stationary_law(small):
    p, c, S, Ae, L, G, _P = small
    law = ob.ObservedLaw(p, (1.0, 8.0), observer=(Ae, L, G), densities=S, base=c, window=3.0, step=0.05)
    d = fdsc.Piecewise([0.0, 4.0, 9.0], [fdsc.Sinusoids([1.0], [1.5]),
                                         fdsc.Sinusoids([0.5, 0.8], [3.0, 6.0])])
    law._states = law._piece_states(d, 12.0)
    t = fdsc.time_grid(12.0, 0.01)
    F, N = ob.observer_filters(Ae, L, G)
    ref = fdsc.simulate(F, d, t).z[:, 0]          # the simulator's exact discretization
    assert np.max(np.abs(law._filtered(t) - ref)) < 1e-10 * np.max(np.abs(ref))
    assert law.response([0.0])[0] == pytest.approx(1.0, abs=1e-12)
    # the noise of the samples: the sensor's noise band-limited to the sampler's Nyquist frequency Ω,
    # so their variance is the loop's noise power up to Ω (the noise-power integral, an independent
    # route) and their covariance at one step the same integral weighted by cos(ω h) (seeded, 2·10⁵)
    law._seed_obs = 7
    x = np.concatenate([law._noise(law._M // 4, k) for k in range(200_000 // (law._M // 4) + 1)])
    omega = np.pi / 0.05
    var = sum(noise_power(LTISystem(N.A, N.B[:, [i]], N.C, N.D[:, [i]]), S[i], omega) for i in range(2))
    w = np.linspace(0.0, omega, 200_001)
    T = np.array([(N.C @ np.linalg.solve(1j * v * np.eye(N.A.shape[0]) - N.A, N.B))[0] for v in w[::100]])
    dens = np.interp(w, w[::100], np.sum(np.abs(T) ** 2 * S[None, :], axis=1))
    lag = float(np.trapezoid(dens * np.cos(w * 0.05), w) / np.pi)
    assert np.var(x) == pytest.approx(var, rel=0.03)
    assert np.mean(x[1:] * x[:-1]) == pytest.approx(lag, rel=0.05, abs=0.03 * var)
    with pytest.raises(ValueError, match="m must be at most"):
        law._noise(law._M + 1, 0)


def test_bad_input_is_refused_by_name(small):
    p = small[0]
    with pytest.raises(ValueError, match="densities must be 2 finite numbers > 0"):
        ob.kalman_bucy(p, [1e-3, 0.0], 1.0)
    with pytest.raises(ValueError, match="q must be a finite number > 0"):
        ob.kalman_bucy(p, [1e-3, 1e-3], -1.0)
    with pytest.raises(ValueError, match="example must be one of"):
        ob.summary({"levels": []}, "glider")
    with pytest.raises(ValueError, match="n_test ≥ 2 and n_train ≥ 1"):
        ob.observer_study({}, n_test=1)


@pytest.fixture(scope="module")
def res(full):
    r = ob.load_observer()
    if r is None:
        pytest.skip("the stored observer study is not in this checkout")
    return r


def test_the_observer_study_was_computed_on_the_stored_study(res, full):
    assert res["stored_study"] == {"commit": full["commit"], "fingerprint": full["fingerprint"]}
    assert res["levels"] == [f"{v:g} dB" for v in ob.LEVELS]
    for e in EXAMPLES:
        assert res[e]["test_indices"] == full[e]["test_indices"][:res["n_test"]]


@pytest.mark.parametrize("e", EXAMPLES)
def test_no_rung_passes_the_limit_and_the_setting_is_the_training_draws_best(res, e):
    for key in res["levels"]:
        row = res[e][key]
        lim = np.asarray(row["energies"]["limit"])
        for rung, v in row["energies"].items():
            assert len(v) == res["n_test"] and np.all(np.isfinite(v))
            assert np.all(np.asarray(v) >= lim * (1 - 1e-9)), (key, rung)
        best = min(row["train_scores"], key=row["train_scores"].get)
        assert row["window"] == (ob.FALLBACK if best == ob.FALLBACK else float(best))
        # the reference is the controller of least expected power of the two
        p = row["expected_power"]
        assert row["reference"] == (row["best"] if p[row["best"]] <= p[row["best_x"]] else row["best_x"])
        # the observer's intensity: the least of the grid within INTENSITY_TOL of the least cost
        scores = {float(k): v for k, v in row["q_scores"].items()}
        cut = min(scores.values()) * (1 + ob.INTENSITY_TOL)
        assert scores[row["q"]] <= cut and all(v > cut for q, v in scores.items() if q < row["q"])
        (s,) = [s for s in ob.summary(res, e) if s["level"] == key]
        assert s[s["reference"]][:3] == (1.0, 1.0, 1.0)
        if row["window"] == ob.FALLBACK:
            assert row["energies"]["predictive (observer)"] == row["energies"][s["reference"]]


def test_a_stored_fixed_energy_recomputes(res, full):
    from fdsc.paper.pays.stored_study import stored_fixed_set

    row, k = res["generic"]["20 dB"], 0
    i = res["generic"]["test_indices"][k]
    design = {"densities": row["densities"], "q": row["q"], "noise": row["noise_power"]}
    ctrl = stored_fixed_set(full, "generic").controllers[row["best"]]
    got = ob.fixed_energy("generic", i, res["seed"], design, ctrl, row["best"])
    assert got == pytest.approx(row["energies"]["best fixed (x, ŵ)"][k], rel=1e-6)
    assert math.isfinite(got)
