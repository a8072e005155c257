import numpy as np
import pytest

from fdsc import simulate_stream
from fdsc.lmi import _sym
from fdsc.lyapunov_jumps import certify_switching
from fdsc.paper.repairs.theorem1_counterexamples import (
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
    smallest_table,
)
from fdsc.paper.shared.results import RecordPart
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
    e, false = part.entries
    assert e["id"] == "theorem1_counterexamples" and e["verdict"] == "new"
    assert e["recomputed"]["counts"] == cnt
    # statement (1) is a printed statement that the exact counterexample refutes: a proof step
    # that differs, which the report's errata list
    from fdsc.paper.appendix.reproduction_report import PROOF_STEP, entry_kind, errata
    assert false["id"] == "thm1_statement1_false" and false["verdict"] == "differs"
    assert entry_kind(false) == PROOF_STEP
    assert false["recomputed"]["multiplier"] > 1 and false["recomputed"]["lmi_holds"]
    assert false["recomputed"]["clean_divergent_cases"] == cnt["clean_previous"] >= 1
    assert [r["where"] for r in errata({"entries": list(part.entries)})] == [
        "Theorem 1, statement (1)"]


def test_residues_bound_the_energy_weighted_excess():
    for r in residues():
        assert np.isclose(r.beta_time.sum(), 1) and np.isclose(r.beta_energy.sum(), 1)
        # integrating (T1-2) with the jumps written out: ratio − Σ β^E γ² ≤ (J − ΔV − ∫Δs)/E_d
        # (equality up to the sampled law and left Riemann sums: 1 % of max γ² slack)
        assert r.ratio - r.bound_energy <= r.jumps + r.boundary + r.law_term + 1e-2 * r.bound_max
        assert r.eps >= 0


def test_lmi_witness_closed_form():
    # A_0 = −1, A_1 = −2, B = C = 1, D = 0, LF [0, 1], HF [10, ∞), Q = 1: L_0 = 1/2 and
    # M_0 = [−1; 1]ᵀ diag(−1 − 1, 1 + 100)[−1; 1] = 99, so t_s = 2·99 + 1 and (T1-1) = −199 + 99
    from fdsc.bands import Band
    from fdsc.paper.repairs.theorem1_counterexamples import lmi_witness
    from fdsc.plant import LTISystem
    modes = [LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]]),
             LTISystem([[-2.0]], [[1.0]], [[1.0]], [[0.0]])]
    bands = [Band.lf(1.0), Band.hf(10.0)]
    w = lmi_witness(modes, bands, [[[1.0]], [[1.0]]])
    assert w.holds()
    np.testing.assert_allclose(w.t_s[0], 199.0)
    np.testing.assert_allclose(w.max_eig_1[0], -100.0)
    # the same point checked through fdsc's own (T1-1)/(T1-2) matrices
    for i, j in ((0, 1), (1, 0)):
        L = 1.0 / (2.0 * -modes[i].A[0, 0])
        M1, M2 = theorem1_matrices(modes[i], bands[i], bands[j], w.t_s[i] * np.array([[L]]),
                                   w.t[i] * np.array([[L]]), np.eye(1), np.eye(1), w.gammas[i])
        assert np.linalg.eigvalsh(_sym(M1)).max() < 0 and np.linalg.eigvalsh(_sym(M2)).max() < 0
    with pytest.raises(ValueError, match="Hurwitz"):
        lmi_witness([LTISystem([[1.0]], [[1.0]], [[1.0]], [[0.0]]), modes[1]], bands,
                    [[[1.0]], [[1.0]]])


def test_lmi_witness_on_the_smallest_counterexample_and_q_scaling():
    from scipy.linalg import solve_continuous_lyapunov

    from fdsc.paper.repairs.theorem1_counterexamples import CaseOutcome, lmi_witness, q_scaling
    case = search_case(*SMALLEST[:2])
    w = lmi_witness(case.modes, case.bands, case.Q)
    assert w.holds()
    for i, j in ((0, 1), (1, 0)):
        L = solve_continuous_lyapunov(case.modes[i].A.T, -np.eye(case.n))
        M1, M2 = theorem1_matrices(case.modes[i], case.bands[i], case.bands[j], w.t_s[i] * L,
                                   w.t[i] * L, case.Q[i], case.Q[j], w.gammas[i])
        assert np.linalg.eigvalsh(_sym(M1)).max() < 0 and np.linalg.eigvalsh(_sym(M2)).max() < 0
    # a common scaling of the Q's leaves the switching signal unchanged
    dt, T = case.grid()
    x0 = _x0s(case)[0]
    out = CaseOutcome.__new__(CaseOutcome)
    for k, v in {"dt": dt, "horizon": T, "worst_x0": x0, "law": SMALLEST[2]}.items():
        object.__setattr__(out, k, v)
    q = q_scaling(case, out, 2.0**27, horizon=T / 4)
    assert q.n_switches > 0 and q.mismatches == 0 and q.max_state_difference == 0
    with pytest.raises(ValueError, match="positive"):
        q_scaling(case, out, 0.0)


def test_clean_runs_are_measured_and_do_not_chatter():
    search = counterexample_search()
    clean = search.clean()
    assert clean and all(d.law == "previous" and d.chatter <= 0.05 for d in clean)
    rows = search.dwell_rows()
    assert len(rows) == len(search.diagnoses)
    assert sum(r["clean"] == "yes" for r in rows) == len(clean)
    assert all("previous" not in str(v) for r in rows for v in r.values())


def test_tables_and_prose_are_text_for_readers():
    search = counterexample_search()
    p = search.prose()
    assert all(isinstance(v, str) for v in p.values())
    causes = search.causes()
    assert p["cause_measured_V"] == str(causes["previous"]["V jumps up at switches"])
    for rows in (search.family_table(), search.diagnosis_table(), search.dwell_rows(),
                 gap_closing().paper_rows(), [r.table_row() for r in residues()],
                 smallest_table(search)):
        assert rows and all(isinstance(v, str) for r in rows for v in r.values())
        # no code names of the readings of ẋ, no raw complex numbers
        text = " ".join(f"{k} {v}" for r in rows for k, v in r.items())
        assert "previous" not in text and "candidate)" not in text.replace("candidate ẋ)", "")
        assert "j)" not in text and "(-" not in text


def test_the_divergence_monitor_flags_every_clean_certified_counterexample():
    # the book's own search: each clean divergent run (printed law, measured ẋ, few one-sample
    # dwells) is a pair of Hurwitz modes with Q's that Theorem 1 certifies. The simulators must
    # flag them once the state passes the monitor's bound (10⁶ times what either mode reaches
    # alone); these grow by ×6 to ×10⁹³ over the search's horizon T, so 16 T suffices for all.
    import warnings

    from fdsc import Case, Sinusoids, UnstableRunWarning, simulate_batch
    from fdsc.paper.repairs.theorem1_counterexamples import counterexample_search

    search = counterexample_search()
    clean = search.clean()
    assert len(clean) >= 4
    zero = Sinusoids([0.0], [1.0])
    cases = []
    for d in clean:
        c = search.case(d.family, d.seed)
        o = next(o for o in search.outcomes if (o.family, o.seed, o.law) == (d.family, d.seed, d.law))
        assert c.status == "feasible" and all(np.isfinite(c.gammas))         # certified
        assert all(np.linalg.eigvals(m.A).real.max() < 0 for m in c.modes)   # both Hurwitz
        dt, T = c.grid()
        for step in (dt, dt / 2):
            # the shortest of T, 4 T, 16 T at which the run is flagged (a longer one may overflow,
            # which simulate_stream refuses to summarize: UnstableError)
            for m in (1, 4, 16):
                with warnings.catch_warnings(record=True) as caught:
                    warnings.simplefilter("always")
                    r = simulate_stream(c.modes, zero, m * T, step, x0=o.worst_x0, law_bands=c.bands,
                                        law_Q=c.Q, law=d.law)
                flagged = [w for w in caught if issubclass(w.category, UnstableRunWarning)]
                if flagged:
                    break
            assert flagged and "diverges: at t = " in str(flagged[0].message), (d.family, d.seed, step)
            assert r.grew_at <= m * T and r.growth > 1e6
        cases.append(Case(c.modes, zero, m * T, dt / 2, x0=o.worst_x0, law_bands=c.bands, law_Q=c.Q,
                          law=d.law))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UnstableRunWarning)
        batch = simulate_batch(cases)
    assert batch.diverged.all()
