"""fdsc.min_switching: the Geromel–Colaneri min-switching law and its L2-gain certificate,
against runs of the law (within the bound; the max-switching law of the same P_i diverges), the
certificate's own inequalities recomputed, a closed-form scalar case, and bad input by name."""

import warnings

import numpy as np
import pytest

from fdsc import InfeasibleError, LTISystem, Sinusoids, UnstableRunWarning, min_switching, simulate_stream

# two non-normal modes whose fast periodic switching diverges (no common Lyapunov function)
A1 = np.array([[-1.0, 4.0], [0.0, -1.0]])
A2 = np.array([[-1.0, 0.0], [4.0, -1.0]])
B, C, D = np.array([[1.0], [1.0]]), np.eye(2), np.zeros((2, 1))
LOOPS = [LTISystem(A1, B, C, D), LTISystem(A2, B, C, D)]


@pytest.fixture(scope="module")
def cert():
    return min_switching(LOOPS)


def test_the_certificate_satisfies_its_inequalities(cert):
    nI = len(LOOPS)
    Pi = cert.rate * (np.ones((nI, nI)) - np.eye(nI)) / (nI - 1) - cert.rate * np.eye(nI)
    assert np.allclose(Pi.sum(axis=0), 0.0) and np.all(Pi - np.diag(np.diag(Pi)) >= 0)
    for i, lp in enumerate(LOOPS):
        P = cert.P[i]
        assert np.linalg.eigvalsh(P).min() > 0
        top = lp.A.T @ P + P @ lp.A + sum(Pi[j, i] * cert.P[j] for j in range(nI)) + lp.C.T @ lp.C
        off = P @ lp.B + lp.C.T @ lp.D
        M = np.block([[top, off], [off.T, lp.D.T @ lp.D - cert.l2_bound**2 * np.eye(1)]])
        assert np.linalg.eigvalsh(0.5 * (M + M.T)).max() < 0


@pytest.mark.parametrize("w", [0.3, 1.0, 3.0])
def test_the_law_stays_within_its_bound_and_the_max_law_diverges(cert, w):
    d = Sinusoids([1.0], [w])
    run = simulate_stream(LOOPS, d, 40.0, 1e-3, law_weights=cert.law_weights())
    assert run.switches > 0
    assert run.energy <= cert.l2_bound**2 * run.input_energy
    # the same forms with the opposite choice (the largest xᵀ P_i x): the switching diverges
    with pytest.warns(UnstableRunWarning, match="diverges"):
        simulate_stream(LOOPS, d, 40.0, 1e-3, law_weights=[-W for W in cert.law_weights()])


def test_choose_refuses_a_state_it_cannot_score(cert):
    for bad in ([np.nan, 0.0], [1.0, 2.0, 3.0], None):
        with pytest.raises((ValueError, TypeError)):
            cert.choose(bad)


def test_the_law_picks_the_least_quadratic_form(cert):
    rng = np.random.default_rng(0)
    for x in rng.standard_normal((20, 2)):
        assert cert.choose(x) == int(np.argmin([x @ p @ x for p in cert.P]))
        W = cert.law_weights()
        scores = [np.r_[np.zeros(2), x] @ Wi @ np.r_[np.zeros(2), x] for Wi in W]
        assert int(np.argmax(scores)) == cert.choose(x)


def test_a_scalar_pair_reduces_to_its_faster_loop():
    loops = [LTISystem([[-2.0]], [[1.0]], [[1.0]], [[0.0]]), LTISystem([[-4.0]], [[1.0]], [[1.0]], [[0.0]])]
    c = min_switching(loops)
    assert c.choose([1.0]) == c.choose([-3.0]) == 1
    # the bound is at least the H∞ norm 1/4 of the loop it keeps, and at most the slower's 1/2
    assert 0.25 * (1 - 1e-6) <= c.l2_bound <= 0.5 * (1 + 1e-3)


def test_a_rate_that_forces_a_common_lyapunov_function_is_infeasible():
    # at a large rate the P_i must nearly coincide, and the pair has no common Lyapunov function
    with pytest.raises(InfeasibleError, match="no rate among 1 gives a certificate"):
        min_switching(LOOPS, rates=(1e4,))


@pytest.mark.parametrize("loops, kwargs, error, match", [
    (LOOPS[:1], {}, ValueError, "at least two"),
    (LOOPS[0], {}, TypeError, "list or tuple of fdsc.LTISystem"),
    ([LOOPS[0], LTISystem(A1, 2 * B, C, D)], {}, ValueError, r"loops\[1\] differs"),
    ([LOOPS[0], LTISystem(-A1, B, C, D)], {}, ValueError, r"loops\[1\] must be Hurwitz"),
    (LOOPS, {"rates": (0.0,)}, ValueError, r"rates\[0\] must be a positive"),
    (LOOPS, {"rates": ()}, ValueError, "rates must be a non-empty sequence"),
    (LOOPS, {"rates": "fast"}, ValueError, "rates must be a non-empty sequence"),
    (LOOPS, {"rates": [[1.0]]}, ValueError, "rates must be a non-empty sequence"),
    (LOOPS, {"rates": [1.0, True]}, (ValueError, TypeError), r"rates\[1\]"),
    (LOOPS, {"margin": -1.0}, ValueError, "margin"),
    (LOOPS, {"margin": None}, (ValueError, TypeError), "margin"),
])
def test_bad_input_is_refused_by_name(loops, kwargs, error, match):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with pytest.raises(error, match=match):
            min_switching(loops, **kwargs)
