import numpy as np
import pytest
from numpy.testing import assert_allclose

from fdsc import Band, InfeasibleError, band_peak
from fdsc.paper.shared.data import paper_modes
from fdsc.switching import certify_q, design_q, theorem1_matrices


def test_paper_q_are_certified_and_lmis_hold_at_the_solution():
    pm = paper_modes()
    res = certify_q(pm["modes"], pm["bands"], pm["Q"])
    assert all(v < 0 for v in res.max_eigs.values())
    assert np.all(np.isfinite(res.gammas)) and np.all(res.gammas > 0)
    # the certificate reproduces negative-definite matrices independently of the solver
    M1, M2 = theorem1_matrices(pm["modes"][0], pm["bands"][0], pm["bands"][1], res.Ps[0],
                               res.P[0], res.Q[0], res.Q[1], res.gammas[0])
    assert np.linalg.eigvalsh(M1).max() < 0 and np.linalg.eigvalsh(M2).max() < 0


def test_remark3_design_reaches_the_in_band_peak():
    # with γ_1 = γ_tol fixed, the in-band γ_2 cannot beat the HF peak of the HF loop (Lemma 1
    # is the special case Q_1 → 0), and the design attains it
    pm = paper_modes()
    res = design_q(pm["modes"], pm["bands"], 1, gamma_tol=10.0)
    assert_allclose(res.gammas[0], 10.0, rtol=1e-6)
    hf_peak = band_peak(pm["modes"][1], Band.hf(10.0)).gamma
    assert res.gammas[1] >= hf_peak * (1 - 1e-6)
    assert_allclose(res.gammas[1], hf_peak, rtol=1e-4)
    assert all(np.linalg.eigvalsh(q).min() > 0 for q in res.Q)


def test_gamma_tol_below_the_out_of_band_mode_gain_is_infeasible():
    # counter-example: mode 1 (PassC-LF) cannot have γ_1 = 0.1 < its LF peak 0.37
    pm = paper_modes()
    with pytest.raises(InfeasibleError):
        design_q(pm["modes"], pm["bands"], 1, gamma_tol=0.1)


@pytest.mark.parametrize(
    ("call", "exc", "match"),
    [
        (lambda pm: certify_q(pm["modes"][:1], pm["bands"][:1], pm["Q"][:1]), ValueError,
         "at least two"),
        (lambda pm: certify_q(pm["modes"], pm["bands"][:1], pm["Q"]), ValueError,
         "one range per mode"),
        (lambda pm: certify_q(pm["modes"], pm["bands"], pm["Q"][:1]), ValueError,
         "one matrix per mode"),
        (lambda pm: certify_q(pm["modes"], pm["bands"], [pm["Q"][0], -pm["Q"][1]]), ValueError,
         "Q must be positive definite"),
        (lambda pm: certify_q(pm["modes"], [Band.mf(1, 10), pm["bands"][1]], pm["Q"]), ValueError,
         "real Ψ"),
        (lambda pm: design_q(pm["modes"], pm["bands"], 2), ValueError, "in_band must be"),
        (lambda pm: design_q(pm["modes"], pm["bands"], 1, gamma_tol=0.0), ValueError,
         "gamma_tol must be"),
    ],
)
def test_bad_theorem1_inputs(call, exc, match):
    with pytest.raises(exc, match=match):
        call(paper_modes())
