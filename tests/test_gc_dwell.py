import functools

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.linalg import expm

from fdsc import InfeasibleError, IterationLimitError, LTISystem, SolverError, UnstableError
from fdsc.dwell import dwell_time_bound, periodic_dwell_margin
from fdsc.gc_dwell import LOWER_FRACTION, DwellCertificate, geromel_colaneri_dwell

# both modes have the double eigenvalue −1; their average [[−1, 2], [2, −1]] has the eigenvalue +1,
# so fast periodic switching diverges
PAIR = [np.array([[-1.0, 4.0], [0.0, -1.0]]), np.array([[-1.0, 0.0], [4.0, -1.0]])]
# lightly damped oscillators with orthogonal elongated orbits (Liberzon 2003, Ch. 2): each is
# stable, switching at the right moments diverges
ORBITS = [np.array([[-0.1, 1.0], [-10.0, -0.1]]), np.array([[-0.1, 10.0], [-1.0, -0.1]])]
# dwells of the periodic signals tried (both pairs diverge up to a dwell of about 2.15 and 11.45 s;
# a finer grid moves these up by < 0.1 s and costs seconds: the pairs (τ_1, τ_2) make k² products)
PERIODIC_TAUS = np.linspace(0.05, 12.0, 240)


PAIRS = {"PAIR": PAIR, "ORBITS": ORBITS}


@functools.cache
def divergence_margin(name):
    """The longest dwell of PERIODIC_TAUS at which a periodic switching of the pair diverges."""
    return periodic_dwell_margin(PAIRS[name], PERIODIC_TAUS).lower_bound


@pytest.fixture(scope="module", params=list(PAIRS))
def sandwich(request):
    A = PAIRS[request.param]
    return A, geromel_colaneri_dwell(A), dwell_time_bound(A), divergence_margin(request.param)


def _largest_eigs(A, P, T):
    """Largest eigenvalues of the flow blocks, then the jump blocks (i, j), i ≠ j, at dwell T."""
    E = [expm(a * T) for a in A]
    flow = [np.linalg.eigvalsh(a.T @ p + p @ a).max() for a, p in zip(A, P, strict=True)]
    jump = [np.linalg.eigvalsh(E[i].T @ P[j] @ E[i] - P[i]).max()
            for i in range(len(A)) for j in range(len(A)) if i != j]
    return np.array(flow + jump)


def test_certified_dwell_lies_between_periodic_divergence_and_the_lyapunov_bound(sandwich):
    A, cert, ld, t_p = sandwich
    # a periodic signal with dwells ≥ t_p diverges, so no valid dwell time is ≤ t_p
    assert t_p > 1.0
    assert t_p < cert.tau
    # ld.P certify the GC LMIs at every T > ld.tau (module Notes), so the GC minimum is ≤ ld.tau;
    # both are computed to their tolerances (rtol = 1e-3 here, tau_rtol = 1e-3 and a λ grid there)
    assert cert.tau <= ld.tau * (1 + 2e-3)
    assert cert.bracket[1] == cert.tau and cert.bracket[1] / cert.bracket[0] - 1 <= 1e-3
    assert cert.n_failed == 0 and cert.n_solves <= 20


def test_certificate_verifies_independently_and_for_longer_dwells(sandwich):
    A, cert, _, _ = sandwich
    for p in cert.P:
        assert_allclose(p, p.T, rtol=0, atol=0)
        assert np.linalg.eigvalsh(p).min() >= 1 - 1e-7  # the normalization P_i ⪰ I
    eigs = _largest_eigs(A, cert.P, cert.tau)
    assert np.all(eigs < 0)
    assert_allclose(cert.max_eigs, eigs, rtol=1e-9, atol=1e-12)
    # the same P_i certify every longer dwell (flow condition, module Notes)
    for factor in (1.5, 10.0, 100.0):
        assert np.all(_largest_eigs(A, cert.P, factor * cert.tau) < 0)


def test_the_lyapunov_dwell_certificate_is_a_gc_certificate(sandwich):
    # the inequality chain of the module docstring: e^{AᵢᵀT} Pⱼ e^{AᵢT} ⪯ μ e^{−2λT} Pᵢ ≺ Pᵢ for T > τ*
    A, _, ld, _ = sandwich
    assert np.all(_largest_eigs(A, ld.P, 1.01 * ld.tau) < 0)


def test_the_bisection_is_cut_short_by_its_cap():
    with pytest.raises(IterationLimitError, match="max_bisections = 2"):
        geromel_colaneri_dwell(PAIR, max_bisections=2)


# closed form: P_1 = P_2 = I satisfies A_iᵀ + A_i ≺ 0 and e^{A_iᵀT}e^{A_iT} = e^{(A_iᵀ + A_i)T} ≺ I for
# every T > 0 (the modes are normal), so the lower end of the bracket is certified
COMMON_P = {
    "scaled identities": [-np.eye(2), -2 * np.eye(2)],
    "diagonal": [np.diag([-1.0, -2.0]), np.diag([-3.0, -0.5])],
    "rotation and diagonal": [np.array([[-1.0, 2.0], [-2.0, -1.0]]), np.diag([-2.0, -3.0])],
    "three scalar modes": [[[-1.0]], [[-5.0]], [[-0.2]]],
}


@pytest.mark.parametrize("modes", COMMON_P.values(), ids=COMMON_P.keys())
@pytest.mark.parametrize("tau_max", [1e3, 10.0])
def test_a_common_lyapunov_function_is_certified_at_the_lower_end(modes, tau_max):
    cert = geromel_colaneri_dwell(modes, tau_max=tau_max)
    assert cert.tau == tau_max * LOWER_FRACTION
    assert cert.bracket == (0.0, cert.tau) and cert.n_solves == 2
    assert np.all(_largest_eigs([np.asarray(a, dtype=float) for a in modes], cert.P, cert.tau) < 0)


def test_closed_loops_are_read_through_their_state_matrix():
    loops = [LTISystem(a, np.ones((2, 1)), np.eye(2), np.zeros((2, 1))) for a in COMMON_P["diagonal"]]
    cert = geromel_colaneri_dwell(loops)
    assert cert.tau == 1e3 * LOWER_FRACTION
    assert_allclose(cert.A[1], COMMON_P["diagonal"][1], rtol=0, atol=0)


def test_an_unstable_mode_is_named():
    with pytest.raises(UnstableError, match=r"modes\[1\] is not stable.*eigenvalue 0\.5") as info:
        geromel_colaneri_dwell([PAIR[0], np.array([[0.5, 1.0], [0.0, -1.0]])])
    assert info.value.eigenvalue == 0.5


def test_no_certificate_below_the_periodic_divergence_margin():
    t_p = divergence_margin("PAIR")
    tau_max = 1.0
    # infeasible by a wide margin: a certificate at T ≤ t_p / 2 would cover a diverging signal
    assert tau_max < t_p / 2
    with pytest.raises(InfeasibleError, match=r"no dwell time up to tau_max = 1 s could be certified") \
            as info:
        geromel_colaneri_dwell(PAIR, tau_max=tau_max)
    assert isinstance(info.value, SolverError) and info.value.status


@pytest.mark.parametrize(("modes", "kwargs", "error", "match"), [
    (PAIR, {"tau_max": 0.0}, ValueError, "tau_max must be a positive finite number"),
    (PAIR, {"tau_max": -1.0}, ValueError, "tau_max must be a positive finite number"),
    (PAIR, {"tau_max": np.inf}, ValueError, "tau_max must be a positive finite number"),
    (PAIR, {"tau_max": "10"}, ValueError, "tau_max must be a positive number"),
    (PAIR, {"rtol": 0.0}, ValueError, "rtol must be a positive finite number"),
    (PAIR, {"rtol": 1.0}, ValueError, r"rtol must be in \(0, 1\)"),
    (PAIR, {"rtol": 2.0}, ValueError, r"rtol must be in \(0, 1\)"),
    (PAIR, {"margin": 0.0}, ValueError, "margin must be a positive finite number"),
    (PAIR, {"max_bisections": 0}, ValueError, "max_bisections must be an integer >= 1"),
    (PAIR, {"max_bisections": 2.5}, ValueError, "max_bisections must be an integer >= 1"),
    (PAIR[:1], {}, ValueError, "modes must hold at least two modes, found 1"),
    ([PAIR[0], -np.eye(3)], {}, ValueError, r"modes must share the state dimension.*modes\[1\] is \(3, 3\)"),
    ([PAIR[0], np.ones((2, 3))], {}, ValueError, r"modes\[1\] must be square"),
    (PAIR[0], {}, TypeError, "modes must be a list of square matrices"),
])
def test_bad_arguments_are_named(modes, kwargs, error, match):
    with pytest.raises(error, match=match):
        geromel_colaneri_dwell(modes, **kwargs)


@pytest.fixture(scope="module")
def pair_cert():
    return geromel_colaneri_dwell(PAIR, rtol=0.05)


def test_admits_compares_each_gap_between_switches_with_tau(pair_cert):
    tau = pair_cert.tau
    assert pair_cert.admits([0.1, 0.1 + 1.001 * tau, 0.1 + 3 * tau])
    assert pair_cert.admits([tau, 2 * tau])  # a gap of exactly tau (2τ − τ is exact)
    assert not pair_cert.admits([0.1, 0.1 + 0.999 * tau])
    assert not pair_cert.admits([0.1, 0.1 + 2 * tau, 0.1 + 2.5 * tau])
    # the first switch may come early, and one switch or none has no gap
    assert pair_cert.admits([0.01 * tau, 1.01 * tau])
    assert pair_cert.admits([0.5]) and pair_cert.admits([])


def test_admits_judges_only_the_window_up_to_the_horizon(pair_cert):
    tau = pair_cert.tau
    st = [1.0, 1.0 + 2 * tau, 1.0 + 2.5 * tau]  # the short gap ends at 1 + 2.5τ
    assert not pair_cert.admits(st)
    assert pair_cert.admits(st, horizon=1.0 + 2.2 * tau)
    assert not pair_cert.admits(st, horizon=1.0 + 2.5 * tau)


@pytest.mark.parametrize(("st", "horizon", "match"), [
    ([2.0, 1.0], None, "switch_times must be positive and strictly increasing"),
    ([1.0, 1.0], None, "switch_times must be positive and strictly increasing"),
    ([0.0, 5.0], None, "switch_times must be positive and strictly increasing"),
    ([[1.0, 5.0]], None, "switch_times must be a 1-D array"),
    ([1.0, 5.0], 0.0, "horizon must be a positive finite number"),
])
def test_admits_refuses_a_malformed_signal(pair_cert, st, horizon, match):
    with pytest.raises(ValueError, match=match):
        pair_cert.admits(st, horizon=horizon)


def test_a_certificate_must_describe_its_modes(pair_cert):
    with pytest.raises(ValueError, match="P and max_eigs must describe the 2 modes of A"):
        DwellCertificate(1.0, pair_cert.P[:1], pair_cert.A, pair_cert.max_eigs, 1, (0.5, 1.0))
    with pytest.raises(ValueError, match="tau must be a positive finite number"):
        DwellCertificate(0.0, pair_cert.P, pair_cert.A, pair_cert.max_eigs, 1, (0.0, 0.0))
    assert not pair_cert.P[0].flags.writeable and not pair_cert.max_eigs.flags.writeable
