import numpy as np
import pytest
from numpy.testing import assert_allclose

from fdsc import Band, LTISystem, Sinusoids, random_hurwitz, simulate, simulate_stream, time_grid
from fdsc.exceptions import DimensionError, InfeasibleError
from fdsc.lyapunov_jumps import (
    JUMP_TOL,
    SwitchingCertificate,
    certify_switching,
    certify_switching_gain,
    switching_forms,
)

BANDS = [Band.lf(1.0), Band.hf(3.0)]
B = np.array([[1.0], [1.0]])
C = np.array([[1.0, 0.0]])
D = np.zeros((1, 1))
ZERO = Sinusoids([0.0], [1.0])


def _modes(*As):
    return [LTISystem(A, B, C, D) for A in As]


def _seeded_pair():
    # a pair certified with P_0 != P_1 (found by seed; the test asserts what it relies on)
    rng = np.random.default_rng(5)
    A = [random_hurwitz(rng, 2), 5.0 * random_hurwitz(rng, 2)]
    Bm, Cm = rng.standard_normal((2, 1)), rng.standard_normal((1, 2))
    return [LTISystem(a, Bm, Cm, D) for a in A]


def test_forms_closed_form_one_state():
    # ẋ = −x, LF (ϖ=1) scores −ẋ² + x² = 0, HF (ϖ=3) scores ẋ² − 9x² = −8x² (Q = 1):
    # measured reading: S_01 = −8 (HF never beats LF), S_10 = +8
    m = LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]])
    S = switching_forms([m, m], BANDS, [np.eye(1), np.eye(1)])
    assert_allclose(S[0, 1], [[-8.0]], rtol=0, atol=1e-12)
    assert_allclose(S[1, 0], [[8.0]], rtol=0, atol=1e-12)
    # candidate reading: S_ij = score_j − score_i with each mode's own ẋ, antisymmetric
    m2 = LTISystem([[-2.0]], [[1.0]], [[1.0]], [[0.0]])
    S = switching_forms([m, m2], BANDS, [np.eye(1), np.eye(1)], law="candidate")
    # score_0 = −1 + 1 = 0; score_1 = 4 − 9 = −5
    assert_allclose(S[0, 1], [[-5.0]], rtol=0, atol=1e-12)
    assert_allclose(S[1, 0], -S[0, 1], rtol=0, atol=0)


@pytest.mark.parametrize("law", ["previous", "candidate"])
@pytest.mark.parametrize("condition", ["jump", "common"])
def test_common_lyapunov_function_is_certified(law, condition):
    # −I and a damped rotation share P = I: He(P A_i) = −2I for both (closed form)
    modes = _modes(-np.eye(2), np.array([[-1.0, 5.0], [-5.0, -1.0]]))
    cert = certify_switching(modes, BANDS, [np.eye(2), 0.5 * np.eye(2)], law=law,
                             condition=condition)
    assert isinstance(cert, SwitchingCertificate)
    assert cert.decay > 0 and np.isnan(cert.gammas).all()
    assert all(np.linalg.eigvalsh(P).min() > 0 for P in cert.P)
    assert all(v < 0 for k, v in cert.max_eigs.items() if k[0] != "jump")
    if condition == "common":
        assert_allclose(cert.P[0], cert.P[1], rtol=0, atol=0)
        assert cert.tau == {}
    assert (cert.nu == {}) == (law == "candidate")


def test_unstable_mode_used_everywhere_is_infeasible_by_a_wide_margin():
    # ẋ = x in both modes: LF scores 0, HF −8x², so the law stays in mode 0 everywhere and
    # He(P A) = 2P ≻ 0 there; the best decay margin is −2/‖A‖ = −2 (far from the 1e-8 margin)
    m = LTISystem([[1.0]], [[1.0]], [[1.0]], [[0.0]])
    with pytest.raises(InfeasibleError, match="no certificate; the best decay margin is -2"):
        certify_switching([m, m], BANDS, [np.eye(1), np.eye(1)])


def test_chattering_region_forces_a_common_p():
    # the textbook pair without a common quadratic Lyapunov function (Liberzon 2003)
    modes = _modes(np.array([[-0.1, 1.0], [-10.0, -0.1]]), np.array([[-0.1, 10.0], [-1.0, -0.1]]))
    Q = [np.eye(2), np.eye(2)]
    S = switching_forms(modes, BANDS, Q)
    th = np.linspace(0.0, np.pi, 721)
    X = np.stack([np.cos(th), np.sin(th)], axis=1)
    both = (np.einsum("ki,ij,kj->k", X, S[0, 1], X) > 0) & (np.einsum("ki,ij,kj->k", X, S[1, 0], X) > 0)
    assert both.any()  # the measured law has a chattering region
    margins = []
    for condition in ("jump", "common"):
        with pytest.raises(InfeasibleError, match="no certificate") as exc:
            certify_switching(modes, BANDS, Q, condition=condition)
        margins.append(float(exc.value.status.split("decay margin ")[1].split(" ")[0]))
    # module docstring: with a chattering region the jump conditions collapse to a common P
    assert margins[0] < -0.1
    assert_allclose(margins[0], margins[1], rtol=1e-2)


@pytest.mark.parametrize("law", ["previous", "candidate"])
def test_certified_pair_converges_under_the_law(law):
    modes = _seeded_pair()
    Q = [np.eye(2), np.eye(2)]
    cert = certify_switching(modes, BANDS, Q, law=law)
    assert cert.condition == "jump" and cert.decay > 0
    rng = np.random.default_rng(11)
    for _ in range(5):
        x0 = rng.standard_normal(2)
        run = simulate_stream(modes, ZERO, 40.0, 1e-3, x0=x0, law_bands=BANDS, law_Q=Q, law=law)
        # V ≥ λ_min|x|² decays at least like exp(−decay·t) between switches and never jumps up
        assert np.linalg.norm(run.x_final) < 1e-3 * np.linalg.norm(x0)


def test_jump_certificate_with_distinct_p_has_nonpositive_jumps_along_a_run():
    # the non-normal pair of tests/test_dwell.py (no common quadratic Lyapunov function) with
    # Q_1 = diag(1, 10): no common P certifies it on the law's regions (best decay margin −0.47,
    # far below 0), so every jump certificate has P_0 ≠ P_1, whichever optimizer the solver
    # returns, and the run's jumps test the jump conditions
    modes = _modes(np.array([[-1.0, 4.0], [0.0, -1.0]]), np.array([[-1.0, 0.0], [4.0, -1.0]]))
    Q = [np.eye(2), np.diag([1.0, 10.0])]
    with pytest.raises(InfeasibleError, match="no certificate") as exc:
        certify_switching(modes, BANDS, Q, condition="common")
    assert float(exc.value.status.split("decay margin ")[1].split(" ")[0]) < -0.1
    cert = certify_switching(modes, BANDS, Q)
    P = np.array(cert.P)
    # S_01 is negative definite (mode 1 never beats mode 0): start in mode 1 on the switching set
    # of 1 → 0 (the positive eigenvector of S_10)
    w, V = np.linalg.eigh(switching_forms(modes, BANDS, Q)[1, 0])
    assert w[-1] > 0
    run = simulate(modes, ZERO, time_grid(20.0, 1e-3), x0=V[:, -1], law_bands=BANDS, law_Q=Q,
                   sigma0=1)
    sig = np.concatenate([[1], run.sigma])   # the mode before t = 0, then σ on every step
    k = np.flatnonzero(np.diff(sig))
    x = run.x[k]
    jumps = np.einsum("ki,kij,kj->k", x, P[sig[k + 1]] - P[sig[k]], x)
    assert k.size > 0
    # what the certificate guarantees for any P it returns: its jump LMIs hold to JUMP_TOL ‖P‖
    scale = max(np.linalg.norm(p, 2) for p in P)
    assert np.all(jumps <= JUMP_TOL * scale * np.einsum("ki,ki->k", x, x))


def test_gain_certificate_bounds_the_energy_of_a_run():
    modes = _seeded_pair()
    Q = [np.eye(2), np.eye(2)]
    cert = certify_switching_gain(modes, BANDS, Q)
    assert np.all(np.isfinite(cert.gammas)) and all(np.linalg.eigvalsh(P).min() > -1e-9
                                                     for P in cert.P)
    dt = 1e-3
    run = simulate(modes, Sinusoids([1.0, 0.5], [0.3, 7.0]), time_grid(30.0, dt),
                   law_bands=BANDS, law_Q=Q)
    s = run.sigma[:-1]
    ez = np.sum(run.z[:-1] ** 2) * dt
    ed = np.array([np.sum(run.d[:-1][s == i] ** 2) * dt for i in range(2)])
    # from x(0) = 0: ∫zᵀz ≤ Σ γ_i² ∫_{mode i} d² (module docstring); 1 % for the sampled law
    assert ez <= 1.01 * float(cert.gammas**2 @ ed)


@pytest.mark.parametrize(("kwargs", "exc", "match"), [
    ({"law": "measured"}, ValueError, "law must be one of"),
    ({"condition": "both"}, ValueError, "condition must be one of"),
    ({"margin": 0.0}, ValueError, "margin must be a positive"),
    ({"Q": [np.eye(2)]}, ValueError, "Q must list one matrix per mode"),
    ({"Q": [np.eye(2), -np.eye(2)]}, ValueError, "positive definite"),
    ({"Q": [np.eye(3), np.eye(3)]}, DimensionError, "expected"),
    ({"bands": [Band.lf(1.0)]}, ValueError, "bands must list one range per mode"),
    ({"bands": [Band.lf(1.0), Band.mf(1.0, 3.0)]}, ValueError, "real"),
    ({"bands": [Band.lf(1.0), "HF"]}, TypeError, "bands\\[1\\] must be"),
    ({"modes": _modes(-np.eye(2))}, ValueError, "at least two closed loops"),
])
def test_bad_inputs(kwargs, exc, match):
    args = {"modes": _modes(-np.eye(2), -2 * np.eye(2)), "bands": BANDS,
            "Q": [np.eye(2), np.eye(2)]}
    args.update(kwargs)
    for fn in (certify_switching, certify_switching_gain):
        with pytest.raises(exc, match=match):
            fn(args["modes"], args["bands"], args["Q"],
               **{k: v for k, v in args.items() if k not in ("modes", "bands", "Q")})


def test_modes_must_share_b():
    other = LTISystem(-np.eye(2), np.array([[1.0], [0.0]]), C, D)
    with pytest.raises(ValueError, match="share B, D"):
        switching_forms([_modes(-np.eye(2))[0], other], BANDS, [np.eye(2), np.eye(2)])
