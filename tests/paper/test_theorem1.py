from numpy.testing import assert_allclose

from fdsc import Sinusoids
from fdsc.paper.data import our_q
from fdsc.paper.theorem1 import autonomous_lyapunov_jumps, autonomous_stability

LF_SIGNAL = Sinusoids([1.0, 1.0, 1.0], [0.1, 0.2, 0.3])


def test_autonomous_jumps_use_the_runs_of_autonomous_stability():
    res = our_q()
    j = autonomous_lyapunov_jumps(res, 3, horizon=10.0)
    ref = autonomous_stability(3, horizon=10.0, Q=res.Q)
    assert_allclose(j["final_ratio"], ref["final_ratio"], rtol=1e-12)
    assert j["n_switches"] == int(ref["switches"].sum())
    assert j["ratios"].size == j["n_switches"]
