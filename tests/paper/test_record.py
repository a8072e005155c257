import numpy as np
import pytest
from numpy.testing import assert_allclose

from fdsc import Band, band_peak
from fdsc.paper.record import FIGURE_IDS, reproduction_record
from fdsc.paper.shared.data import aircraft
from fdsc.paper.shared.verdict import VERDICTS


def test_record_entries_have_the_required_fields():
    rec = reproduction_record()
    ids = {e["id"] for e in rec["entries"]}
    assert {"sigma_peak", "lemma1_gamma"} <= ids
    assert {"K_f1", "K_f2", "K_f3", "K_e", "bound_f1", "bound_f2", "bound_f3", "bound_e",
            "hf_best"} <= ids
    for e in rec["entries"]:
        assert {"id", "source", "paper", "recomputed", "verdict", "note"} <= set(e)
        assert e["verdict"] in VERDICTS
    by_id = {e["id"]: e for e in rec["entries"]}
    for key in ("sigma_peak", "lemma1_gamma"):
        assert set(by_id[key]["recomputed"]) == {"K_f1", "K_f2", "K_f3", "K_e"}
        for per_band in by_id[key]["recomputed"].values():
            assert set(per_band) == {"LF", "MF", "HF", "EF"}
    # K_f3 depends on σ and ε, which the paper does not print: its own rule says "not reproducible"
    assert by_id["K_f3"]["verdict"] == "not reproducible"
    # the recomputed K_e achieves the printed K_e's H∞ norm (every optimizer of the H∞ LMI achieves
    # between the optimum 0.4027932 and γ_lmi = 0.4027966, plus the 1e-5 the synthesis allows its
    # sweep above it); the recomputed gain itself is one optimizer among many, not compared
    norms = [band_peak(aircraft().closed_loop(np.array(by_id["K_e"][k])), Band.entire()).gamma
             for k in ("recomputed", "paper")]
    assert_allclose(*norms, rtol=2e-5)
    # one verdict per printed bound, by the quantity the text states (the band peak of σ_max):
    # K_f2's peak 0.40279 is close to 0.4025, the other three are far from theirs
    assert [by_id[f"bound_{k}"]["verdict"] for k in ("f1", "f2", "f3", "e")] == [
        "differs", "close", "differs", "differs"]
    assert by_id["thm1_gammas"]["verdict"] == "new" and by_id["hf_best"]["verdict"] == "new"
    assert by_id["Q_1"]["verdict"] == by_id["Q_2"]["verdict"] == "not reproducible"
    assert "nan" not in by_id["K_e"]["note"]
    assert by_id["prop1_checks"]["recomputed"]["passed"] + by_id["prop1_checks"]["recomputed"][
        "failed"] >= 100
    assert len(by_id["table1_checks"]["recomputed"]) == 7
    assert {"Q_1", "Q_2", "thm1_gammas"} <= ids
    assert {k: v["paper_figure"] for k, v in rec["figures"].items()} == FIGURE_IDS
    for fig in ("lf_outputs", "hf_outputs"):
        f = rec["figures"][fig]
        assert set(f["energy"]) == {"PassC-EF", "PassC-LF", "PassC-HF", "FDSC"}
        assert f["horizon"] > 0 and f["dt"] > 0 and f["units"]["horizon"] == "s"
    l2 = rec["figures"]["hf_l2"]
    assert "FDSC" in l2["l2_induced_norm_final"]
    # the running ratio from rest approaches the closed-form steady state from above (the
    # transient of K_f3's slow pole at -0.0165 is still in the 500 s integral)
    for c, ss in l2["l2_induced_norm_steady_state"].items():
        assert ss < l2["l2_induced_norm_final"][c] < 1.2 * ss, c
    # paper Figs. 7 and 8: the grids the issue asks for, unscaled energies, the bisected crossover
    ms, ps = rec["figures"]["mixed_sweep"], rec["figures"]["piecewise_sweep"]
    assert len(ms["rho_p"]) >= 21 and len(ps["rho_t"]) >= 11 and ps["T"] == 500 and ps["rho_p_star"] == 0.1
    for fig in (ms, ps):
        assert {"PassC-EF", "PassC-LF", "PassC-HF", "FDSC"} <= set(fig["energy"])
    assert max(ms["energy"]["PassC-HF"]) > 1e6        # unscaled (the paper draws it × 1/5000)
    assert 0 < ms["crossover"]["PassC-LF"] <= ms["crossover"]["PassC-EF"] < 0.5
    assert ms["crossover"]["tolerance"] <= 1e-3
    assert len(rec["claims"]) >= 10
    assert {c["verdict"] for c in rec["claims"]} <= {"PASS", "PARTLY", "FAIL"}
    assert by_id["claims_step_halving"]["all_equal"] is True
    hb = by_id["hf_best"]["recomputed"]
    assert hb["in_band"] <= hb["gamma_lmi"] * (1 + 1e-5)
    assert rec["environment"]["packages"]["numpy"] == np.__version__


def test_lmi_and_peak_agree_in_the_record():
    rec = {e["id"]: e for e in reproduction_record()["entries"]}
    for g, per_band in rec["sigma_peak"]["recomputed"].items():
        for b, peak in per_band.items():
            assert abs(rec["lemma1_gamma"]["recomputed"][g][b] - peak) <= 1e-4 * peak, (g, b)


def test_chapters_on_several_processes_give_the_record_of_one(monkeypatch, tmp_path):
    # two cheap chapters computed by two fresh processes sharing a results folder give the same
    # record as the same chapters computed here, one after the other: equal to the record's ten
    # significant digits (the workers cap their BLAS threads, so a sum may round differently in
    # its last bits than in this process, e.g. 2.382734138221e-05 against 2.382734138233e-05)
    from fdsc.paper.record import chapter_parts
    from fdsc.paper.reproduced import frequency_ranges
    from fdsc.paper.shared import inputs
    from fdsc.paper.shared.cache import CACHE_ENV, shared_results
    from fdsc.paper.shared.results import to_jsonable

    chapters = (inputs, frequency_ranges)
    monkeypatch.setenv(CACHE_ENV, str(tmp_path / "parallel"))
    with shared_results():
        parallel = chapter_parts(chapters, 2)
    monkeypatch.setenv(CACHE_ENV, str(tmp_path / "serial"))
    with shared_results():
        serial = chapter_parts(chapters, 1)
    assert [e["id"] for p in parallel for e in p.entries] == [e["id"] for p in serial for e in p.entries]
    assert to_jsonable([(p.entries, p.figures) for p in parallel]) == to_jsonable(
        [(p.entries, p.figures) for p in serial])
    # the worker processes wrote their results into the shared folder (the cached results of the
    # chapter frequency_ranges live in its sibling modules, e.g. fdsc.paper.reproduced.paley_wiener)
    assert any((tmp_path / "parallel").glob("fdsc.paper.reproduced.paley_wiener.*.pickle"))


@pytest.mark.parametrize("value", ["0", "-2", "two", "1.5"])
def test_record_jobs_refuses_what_is_not_a_process_count(monkeypatch, value):
    from fdsc.paper.record import JOBS_ENV, record_jobs

    monkeypatch.setenv(JOBS_ENV, value)
    with pytest.raises(ValueError, match="FDSC_JOBS must be a whole number"):
        record_jobs()
    monkeypatch.setenv(JOBS_ENV, "3")
    assert record_jobs() == 3


def test_every_entry_names_the_book_page_that_computes_it():
    from pathlib import Path

    rec = reproduction_record()
    book = Path(__file__).resolve().parents[2] / "book"
    pages = {e["id"]: e["chapter"] for e in rec["entries"]}
    assert all((book / f"{p}.ipynb").is_file() for p in pages.values()), pages
    assert pages["bound_f3"] == "printed_bounds" and pages["K_f3"] == "passive_controllers"
    assert pages["comparators"] == "simulations" and pages["claims_step_halving"] == "report"
    assert pages["hysteresis_dwell"] == "switching_law" and pages["mixed_crossover"] == "simulations"
    assert pages["fixed_controllers"] == "ladder" and pages["theorem1_counterexamples"] == "theorem1"
