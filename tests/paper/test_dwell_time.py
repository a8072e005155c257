import json

import numpy as np
import pytest
from numpy.testing import assert_allclose

from fdsc.dwell import lyapunov_dwell, periodic_dwell_margin
from fdsc.paper.shared.data import paper_modes
from fdsc.paper.shared.dwell_time import DwellCertificate, dwell_certificate


@pytest.fixture(scope="module")
def cert():
    return dwell_certificate(n_runs=4, horizon=60.0)


def test_bound_for_the_paper_modes(cert):
    b = cert.bound
    modes = paper_modes()["modes"]
    # decay limits: −max Re eig of the K_f1 and K_f3 loops (≈ 1.12 and 0.0165, Sec. VI data)
    ref = [-np.linalg.eigvals(m.A).real.max() for m in modes]
    assert_allclose(b.decay_limits, ref, rtol=1e-12)
    assert 0.0165 < ref[1] < 0.0166 and 0 < b.decay < ref[1]
    assert_allclose(b.tau, np.log(b.mu) / (2 * b.decay), rtol=1e-12)
    assert b.mu > 1.0  # no common quadratic Lyapunov function at any λ tried
    assert b.mu <= b.mu_crude and b.tau <= b.tau_crude
    assert np.all(b.max_eigs < 0) and np.all(b.min_eig_P > 0)
    # the certificate recomputed from its P_i alone
    g = lyapunov_dwell(modes, list(b.P))
    assert_allclose(g.mu, b.mu, rtol=1e-12)
    assert g.decay >= b.decay


def test_periodic_margin_and_theorem1_ps(cert):
    p = cert.periodic
    assert p.taus.size == 300 and p.n_modes == 2
    # τ* is never below a dwell at which periodic switching diverges
    assert cert.bound.tau >= p.lower_bound
    # the worst pair over dwells ≥ τ is at least the equal-dwell case at τ
    assert np.all(p.rho_worst >= p.rho * (1 - 1e-12))
    # an independent evaluation at a few dwells
    q = periodic_dwell_margin(paper_modes()["modes"], p.taus[::100])
    assert_allclose(q.rho, p.rho[::100], rtol=1e-10)
    # Theorem 1's P^s_i: a dwell time only if every mode decays; then never below the optimum
    for r in cert.theorem1.values():
        assert (r.tau == np.inf) == (r.decay <= 0)
        assert r.tau >= cert.bound.tau
        assert r.mu <= r.mu_crude * (1 + 1e-12)


def test_runs_check_the_envelope(cert):
    assert cert.slow.all_hold and cert.fast.all_hold
    s = cert.slow.summary()
    assert s["n_runs"] == 4 and s["min_dwell"] > cert.bound.tau
    for c in cert.slow.checks:
        assert c.min_dwell >= 1.01 * cert.bound.tau and c.rate_bound > 0 and c.holds()
    for c in cert.fast.checks:
        assert c.max_ratio <= 1 + 1e-9 and c.rate_bound < 0


def test_record_dict_is_plain_json(cert):
    assert isinstance(cert, DwellCertificate)
    d = cert.record_dict()
    back = json.loads(json.dumps(d, allow_nan=False))
    assert set(back) >= {"tau_star", "decay", "mu", "mu_crude", "tau_crude", "periodic",
                         "theorem1_Ps", "checks"}
    assert back["tau_star"] == cert.bound.tau
    assert back["periodic"]["lower_bound"] == cert.periodic.lower_bound
    assert back["checks"]["slow"]["all_hold"] is True
    assert set(back["theorem1_Ps"]) == {"paper", "ours"}
