import numpy as np
import pytest

from fdsc import simulate_stream
from fdsc.lmi import _sym
from fdsc.lyapunov_jumps import certify_switching
from fdsc.paper.results import RecordPart
from fdsc.paper.theorem1_counterexamples import (
    _ZERO,
    CAUSES,
    REFINE,
    _x0s,
    counterexample_search,
    gap_closing,
    record_part,
    residues,
    search_case,
    smallest_case,
)
from fdsc.switching import certify_q, theorem1_matrices

# the smallest divergent case of the default search (record entry theorem1_counterexamples,
# "smallest"): family spiral-2, seed 6, measured ẋ
SMALLEST = ("spiral-2", 6, "previous")


def test_smallest_case_is_rebuilt_from_its_seed_certified_and_divergent():
    case = search_case(*SMALLEST[:2])
    assert case.status == "feasible" and case.n == 2
    # Theorem 1 holds: every (T1-1) and (T1-2) matrix at the certificate is negative definite
    cert = certify_q(case.modes, case.bands, case.Q)
    for i, j in ((0, 1), (1, 0)):
        M1, M2 = theorem1_matrices(case.modes[i], case.bands[i], case.bands[j], cert.Ps[i],
                                   cert.P[i], case.Q[i], case.Q[j], cert.gammas[i])
        assert np.linalg.eigvalsh(_sym(M1)).max() < 0 and np.linalg.eigvalsh(_sym(M2)).max() < 0
    assert all(np.linalg.eigvals(m.A).real.max() < 0 for m in case.modes)
    # ... and yet the loop with d = 0 grows on the grid dt / REFINE from a seeded initial state
    dt, T = case.grid()
    ratios = []
    for h in (T / 2, T):
        runs = [simulate_stream(case.modes, _ZERO, h, dt / REFINE, x0=x0, law_bands=case.bands,
                                law_Q=case.Q, law=SMALLEST[2]) for x0 in _x0s(case)]
        ratios.append(max(np.linalg.norm(r.x_final) / np.linalg.norm(x0)
                          for r, x0 in zip(runs, _x0s(case), strict=True)))
    assert ratios[1] > 1 and ratios[1] > ratios[0]
    # the gap-closing certificate rejects it
    with pytest.raises(Exception, match="no certificate"):
        certify_switching(case.modes, case.bands, case.Q, law=SMALLEST[2])


def test_search_case_is_deterministic_and_validates_family():
    a, b = search_case("random-3", 4), search_case("random-3", 4)
    np.testing.assert_array_equal(a.modes[0].A, b.modes[0].A)
    assert a.status == b.status
    with pytest.raises(ValueError, match="family must be one of"):
        search_case("random-4", 0)


def test_search_counts_and_record():
    search = counterexample_search()
    cnt = search.counts()
    assert cnt["feasible"] <= cnt["tried"] - cnt["not_hurwitz"]
    for law in ("previous", "candidate"):
        assert 0 <= cnt[f"diverging_{law}"] <= cnt["feasible"]
    assert cnt["diverging_previous"] + cnt["diverging_candidate"] >= 1
    div = search.divergent()
    assert (div[0].family, div[0].seed, div[0].law) == SMALLEST
    assert smallest_case(search)["seed"] == SMALLEST[1]
    assert sum(sum(v.values()) for v in search.causes().values()) == len(div)
    assert all(d.cause in CAUSES for d in search.diagnoses)
    for d in search.diagnoses:
        # log V(T)/V(0) = jumps + flows > 0 on a divergent trace
        assert d.log_growth_jumps + d.log_growth_flows > 0
    gap = gap_closing()
    summary = gap.summary()
    # a certificate is a proof: no divergent run may be certified
    assert summary["divergent"] == len(div) and summary["divergent_certified"] == 0
    assert gap.paper["paper", "previous", "jump", "stability"]["certified"] is False
    part = record_part()
    assert isinstance(part, RecordPart)
    (e,) = part.entries
    assert e["id"] == "theorem1_counterexamples" and e["verdict"] == "new"
    assert e["recomputed"]["counts"] == cnt


def test_residues_bound_the_energy_weighted_excess():
    for r in residues():
        assert np.isclose(r.beta_time.sum(), 1) and np.isclose(r.beta_energy.sum(), 1)
        # integrating (T1-2) with the jumps written out: ratio − Σ β^E γ² ≤ (J − ΔV − ∫Δs)/E_d
        # (equality up to the sampled law and left Riemann sums: 1 % of max γ² slack)
        assert r.ratio - r.bound_energy <= r.jumps + r.boundary + r.law_term + 1e-2 * r.bound_max
        assert r.eps >= 0
