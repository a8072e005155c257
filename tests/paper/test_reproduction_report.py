"""The report's rows from small synthetic records (with and without claims and figure data)."""

import re

import numpy as np
import pytest

from fdsc.paper.appendix.report_values import key_words, note_html, value_html, words
from fdsc.paper.appendix.reproduction_report import (
    LAW_ENTRY,
    NO_CHECKLIST,
    NO_CLAIM,
    claim_rows,
    claims_sentence,
    counts_prose,
    counts_sentence,
    entry_kind,
    errata,
    figure_rows,
    figures_named,
    finding_rows,
    inequality_cell,
    input_rows,
    law_rows,
    printed_counts,
    printed_rows,
    step_rows,
    summary,
)
from fdsc.paper.record import PAPER_FIGURES
from fdsc.paper.shared.report import compact, html_table
from fdsc.paper.shared.results import entry
from fdsc.paper.shared.verdict import CLAIM_VERDICTS, VERDICTS


def _claim(source, verdict, value=0.1):
    return {"claim": f"words on {source}", "source": source, "measure": "m", "value": value,
            "verdict": verdict, "reason": "r"}


LAW_CHECK = {"draws_test": 6, "draws_train": 6, "fixed_in_advance": "tuned filtered",
             "median_ratio_vs_fixed_in_advance": 0.9594, "win_rate_vs_fixed_in_advance": 1.0,
             "reference_median_ratio": 0.9592}


def record(*, claims=True):
    rec = {
        "entries": [
            entry("K_f1", "Sec. IV, K_{f_1}", np.array([[0.1048, 15.0897], [0.0205, 2.976]]),
                  np.array([[0.104946831, 15.09821467], [0.02051961207, 2.977720048]]), "close",
                  "within 1 %"),
            entry("bound_f1", "Sec. IV", 0.3443, np.float64(0.3737360687), "not reproducible",
                  "no candidate"),
            entry("bound_f2", "Sec. IV, the bound beside K_f2", 0.4025, 0.4027932507, "close", "within 1 %",
                  inequality={"statement": "s", "subject": "K_f2", "quantity": 0.4027932507, "bound": 0.4025,
                              "holds": False}),
            entry("bound_e", "Sec. IV, the bound beside K_e", 0.7125, 0.4027932507, "differs", "loose",
                  inequality={"statement": "s", "quantity": 0.4027932507, "bound": 0.7125, "holds": True}),
            entry("psi", "Sec. III, proof of Proposition 1", "w >= 0 on Omega_i", {"sign_violations": 0},
                  "match", "no sign violation"),
            entry("prop1", "Sec. III, Proposition 1", {"LF": "(w_l - jw)(w_l + jw) > 0"}, {"grid_points": 8},
                  "differs", "wrong sign"),
            entry("lf_claims", "Sec. IV, text on paper Fig. 4", ["the range of PassC-LF is the smallest"],
                  {"the range": {"holds": False}}, "differs", "each sentence read"),
            entry(LAW_ENTRY, "ours", None, {"aircraft": LAW_CHECK}, "new", "the record's subset"),
            entry("sweep", "ours", None, {"rho_p": list(np.linspace(0, 0.5, 21))}, "new", "a finding"),
            entry("model", "Sec. IV", {"A_long": [[-1.175, 0.9871]]}, {"A_long": [[-1.175, 0.9871]]},
                  "input", "as printed"),
            entry("hf_best", "Sec. IV", {"K": [[1.0]]}, {"K": [[2.0]]}, "new", "printed K beside ours"),
        ],
        "figures": {"sigma_max": {"paper_figure": 3}, "lf_outputs": {"paper_figure": 4}},
        "environment": {},
    }
    if claims:
        rec["claims"] = [_claim("Sec. IV, text on paper Fig. 7", "PASS"),
                         _claim("Sec. IV, text on paper Fig. 7", "FAIL"),
                         _claim("Sec. IV, text on paper Figs. 4 and 5", "PARTLY"),
                         _claim("Sec. IV, text on paper Fig. 10", "FAIL"),
                         _claim("Abstract", "PASS", value={"a": 1.0})]
    return rec


def test_each_entry_has_one_kind():
    kinds = {e["id"]: entry_kind(e) for e in record()["entries"]}
    assert kinds == {"K_f1": "printed number", "bound_f1": "printed number", "bound_f2": "printed number",
                     "bound_e": "printed number", "psi": "proof step", "prop1": "proof step",
                     "lf_claims": "sentences", "sweep": "finding", "model": "input", "hf_best": "finding",
                     LAW_ENTRY: "finding"}


def test_printed_rows_hold_the_printed_numbers_in_words_with_both_axes():
    rows = printed_rows(record(), {"passive_controllers": "Passive controllers"})
    # proof steps, sentences, inputs and findings have tables of their own
    assert [r["id"] for r in rows] == ["K_f1", "bound_f1", "bound_f2", "bound_e"]
    k, b2, be = rows[0], rows[2], rows[3]
    assert k["printed"].startswith("<table class='matrix'>") and "<td>15.0897</td>" in k["printed"]
    assert "<td>15.098</td>" in k["ours"] and k["holds"] == "—" and k["verdict"] == "close"
    # the value's verdict and the inequality are two axes: close but false, differs but true
    assert (b2["verdict"], b2["holds"]) == ("close", "fails: 0.4028 ≥ 0.4025")
    assert (be["verdict"], be["holds"]) == ("differs", "holds: 0.4028 &lt; 0.7125")
    assert "Sec. IV, K_{f_1}" in k["item"] and "within 1 %" in k["item"]


@pytest.mark.parametrize("rows", [printed_rows, step_rows, input_rows, finding_rows, claim_rows, errata,
                                  lambda rec: law_rows(rec, None)])
def test_no_cell_holds_a_raw_dictionary_or_an_internal_key(rows):
    text = " ".join(str(v) for r in rows(record()) for k, v in r.items() if k not in ("id", "kind"))
    # neither a Python dict nor the record's compact form of one ("key: {key: value}")
    assert not re.search(r"\{\s*['\"]?[\w ]+['\"]?\s*:", text), text
    for key in ("sign_violations", "grid_points", "A_long", "draws_test", "bound_f2", "K_f1<"):
        assert key not in text


def test_step_rows_hold_proof_steps_then_sentences():
    rows = step_rows(record())
    assert [(r["id"], r["kind"]) for r in rows] == [("psi", "proof step"), ("prop1", "proof step"),
                                                     ("lf_claims", "sentences")]
    assert rows[0]["printed"] == "w ≥ 0 on Ω_i"
    assert rows[1]["printed"] == '<ul class="kv"><li>LF: (w_l - jw)(w_l + jw) &gt; 0</li></ul>'
    assert rows[2]["printed"] == "<ul><li>the range of PassC-LF is the smallest</li></ul>"


def test_input_rows_fold_the_printed_values():
    [row] = input_rows(record())
    assert row["printed"].startswith("<details><summary>the printed values</summary>")
    assert "A_long" not in row["printed"] and "<td>−1.175</td>" in row["printed"]


def test_counts_are_over_one_kind_each():
    c = printed_counts(record())
    assert c["numbers"] == {"match": 0, "close": 2, "differs": 1, "not reproducible": 1}
    assert c["inequalities"] == {"hold": 1, "fail": 1} and c["fail_printed"] == [0.4025]
    assert c["proof_steps"] == {"match": 1, "close": 0, "differs": 1, "not reproducible": 0}
    assert (c["sentences"], c["inputs"], c["findings"]) == (1, 1, 3)
    assert c["claims"] == {"PASS": 2, "PARTLY": 1, "FAIL": 2}
    p = counts_prose(record())
    assert (p["n_numbers"], p["numbers_close"]) == ("4", "2")
    assert (p["n_inequalities"], p["inequalities_fail"]) == ("2", "1")
    assert p["inequalities_fail_printed"] == "0.4025"
    # by how much each printed inequality fails: the quantity against the printed bound
    assert p["inequalities_fail_by"] == "K_f2 0.07 % above"
    assert (p["n_steps"], p["steps_match"], p["n_claims"], p["claims_fail"]) == ("2", "1", "5", "2")
    assert counts_prose(record(claims=False))["n_claims"] == "0"
    assert counts_sentence(record()) == (
        "Of the 4 numbers the paper prints as results, 0 match ours, 2 are close (within 1 %), 1 differ "
        "and 1 cannot be reproduced; 2 are the bounds of printed inequalities, of which 1 holds and "
        "1 fails (the quantity against the printed bound: K_f2 0.07 % above). Checked apart: 2 "
        "proof steps, of which 1 holds as printed; 5 claims about the simulations, of which 2 "
        "hold, 1 hold in part and 2 fail.")


def test_law_rows_label_the_stored_study_or_else_the_build_time_check():
    full = {"n": 500, "commit": "048c47d821e7618526fc6ede3a9a4bf9876badfe",
            "aircraft": dict(LAW_CHECK, draws_test=250, median_ratio_vs_fixed_in_advance=0.9836,
                             win_rate_vs_fixed_in_advance=0.848)}
    stored, = law_rows(record(), full)
    assert stored["study"] == "stored study: 500 draws per example, computed at commit 048c47d"
    assert (stored["scored"], stored["median"], stored["wins"]) == ("250", "×0.984", "85 %")
    assert "sources have changed" in law_rows(record(), full, fresh=False)[0]["study"]
    # without a stored study, the record's build-time check, labelled as such
    check, = law_rows(record(), None)
    assert check["study"].startswith("build-time check: the procedure rerun on the first 12 draws")
    assert "training draws of the stored study" in check["study"]
    assert (check["scored"], check["median"], check["wins"]) == ("6", "×0.959", "100 %")
    # the check is shown beside the stored study, not among the findings
    assert LAW_ENTRY not in [r["id"] for r in finding_rows(record())]


def test_values_and_notes_in_words():
    assert words("rho_p <= 0.2 for 2 delta_E") == "ρ_p ≤ 0.2 for 2δ_E"
    assert key_words("max_fdsc_over_band_peak") == "max fdsc over band peak" and key_words("w_l") == "w_l"
    assert value_html(list(range(30))).startswith("<details><summary>0, 1, 2, 3, … (30 values)")
    nested = '<ul class="kv"><li>a: <ul class="kv"><li>b_c: 1</li></ul></li></ul>'
    assert value_html({"a": {"b_c": 1.0}}) == nested
    assert value_html(True) == "yes" and value_html(None) == "—" and value_html(np.float64(2.5)) == "2.5"
    long = "The first sentence is here. " + "More words follow. " * 20
    folded = note_html(long)
    assert folded.startswith("<details><summary>The first sentence is here. …</summary>")
    assert folded.count("More words follow.") == 20
    assert inequality_cell({"inequality": {"quantity": 0.40251, "bound": 0.4025, "holds": False}}) == (
        "fails: 0.40251 ≥ 0.4025")


def test_compact_shortens_long_lists_and_dicts():
    assert compact(np.linspace(0, 0.5, 21)) == "[0, 0.025, 0.05, 0.075, 0.1, 0.125, …] (21 values)"
    assert compact({f"k{i}": i for i in range(8)}, max_items=2) == "k0: 0; k1: 1; … (8 keys)"
    assert compact({"a": {"b": [1, 2]}}) == "a: {b: [1, 2]}"
    text = compact({"s": "x" * 500})
    assert len(text) == 160 and text.endswith("…")
    assert compact("inf") == "inf" and compact(True) == "yes" and compact(np.int64(3)) == "3"


@pytest.mark.parametrize(("source", "figures"), [
    ("Sec. IV, text on paper Fig. 7", {7}),
    ("paper Fig. 1", {1}),
    ("paper Fig. 10", {10}),
    ("paper Fig. 1, and the Abstract", {1}),
    ("paper Figs. 7 and 8", {7, 8}),
    ("paper Figs. 4–6", {4, 5, 6}),
    ("paper Figs. 4, 5 and 8", {4, 5, 8}),
    ("Fig. 7 of another paper", set()),
    ("Abstract", set()),
])
def test_figures_named(source, figures):
    assert figures_named(source) == figures


def test_figure_rows_cover_every_paper_figure_with_link_status_and_verdict():
    rows = figure_rows(record(), {"gkyp_lemma": "The gKYP lemma"})
    assert [r["number"] for r in rows] == list(PAPER_FIGURES) == list(range(1, 9))
    by = {r["number"]: r for r in rows}
    assert by[3]["link"] == '<a href="gkyp_lemma.html">The gKYP lemma</a>'
    assert by[3]["status"] == "redrawn from recorded data" and by[3]["record_entry"] == "sigma_max"
    # the worst claim on a figure; a claim on "Fig. 10" is not a claim on paper Fig. 1
    assert by[7]["verdict"] == "FAIL" and by[4]["verdict"] == by[5]["verdict"] == "PARTLY"
    assert by[1]["verdict"] == NO_CLAIM and by[3]["verdict"] == NO_CLAIM
    # a figure without data says so, whatever chapter it points at
    assert by[7]["status"] in ("not reproduced yet", "drawn (no data)") and by[7]["record_entry"] == ""
    if PAPER_FIGURES[2][1] is None:
        assert by[2]["link"] == "" and by[2]["status"] == "nothing to reproduce"


def test_without_a_checklist_the_figures_say_so():
    assert {r["verdict"] for r in figure_rows(record(claims=False))} == {NO_CHECKLIST}
    assert claim_rows(record(claims=False)) == []


def test_claim_rows():
    rows = claim_rows(record())
    assert len(rows) == 5 and rows[0]["claim"].startswith(
        "“words on Sec. IV, text on paper Fig. 7”<br><small>Sec. IV, text on paper Fig. 7</small>"
        "<details><summary>how it is read</summary>")
    assert "measure" not in rows[0]
    assert (rows[0]["value"], rows[0]["verdict"], rows[0]["reason"]) == ("0.1", "PASS", "r")
    assert rows[-1]["value"] == '<ul class="kv"><li>a: 1</li></ul>'


def test_finding_rows_are_the_new_entries():
    rows = finding_rows(record(), {"stationary": "Stationary disturbances"})
    assert [r["id"] for r in rows] == ["sweep", "hf_best"]
    assert set(rows[0]) == {"id", "item", "finding", "link"}


def test_errata_list_what_is_false_or_cannot_be_reproduced():
    rows = errata(record())
    # the bound that cannot be reproduced, the close bound whose inequality fails, the proof step that
    # differs, then the two failing claims; the loose but true bound, matches, inputs, sentences (decided
    # through their claims) and findings are not errata
    assert [(r["n"], r["where"], r["verdict"]) for r in rows] == [
        (1, "Sec. IV", "not reproducible"),
        (2, "Sec. IV, the bound beside K_f2", "close; the printed inequality fails"),
        (3, "Sec. III, Proposition 1", "differs"),
        (4, "Sec. IV, text on paper Fig. 7", "FAIL"), (5, "Sec. IV, text on paper Fig. 10", "FAIL")]
    assert rows[0]["printed"] == "0.3443" and rows[2]["ours"] == ""
    assert rows[3]["printed"] == "words on Sec. IV, text on paper Fig. 7"
    assert errata(record(claims=False))[-1]["where"] == "Sec. III, Proposition 1"


def test_summary_counts_every_verdict():
    s = summary(record())
    assert list(s["entries"]) == list(VERDICTS) and list(s["claims"]) == list(CLAIM_VERDICTS)
    assert s["entries"] == {"match": 1, "close": 2, "differs": 3, "not reproducible": 1, "input": 1, "new": 3}
    assert s["kinds"] == {"printed number": 4, "proof step": 2, "sentences": 1, "input": 1, "finding": 3}
    assert s["claims"] == {"PASS": 2, "PARTLY": 1, "FAIL": 2}
    assert (s["n_entries"], s["n_claims"], s["n_figures"]) == (11, 5, 8)
    assert sum(s["figures"].values()) == 8 and s["figures"]["redrawn from recorded data"] == 2
    none = summary(record(claims=False))
    assert none["claims"] is None and none["n_claims"] == 0


@pytest.mark.parametrize(("rec", "message"), [
    ({"figures": {}}, "record must be a dict with a list 'entries'"),
    ([], "record must be a dict with a list 'entries'.*found list"),
    ({"entries": [{"id": "x", "verdict": "OK"}], "figures": {}}, "entry 'x' has verdict 'OK'"),
    ({"entries": [], "figures": {}, "claims": [_claim("s", "OK")]}, "claim 'words on s' has verdict 'OK'"),
])
def test_a_malformed_record_is_refused(rec, message):
    with pytest.raises(ValueError, match=message):
        summary(rec)


def test_html_table_escapes_all_but_the_raw_columns():
    rows = figure_rows(record())
    table = html_table(rows, {"figure": "paper figure", "link": "page"}, raw={"link"})
    assert '<td><a href="simulations.html">simulations</a></td>' in table
    escaped = html_table(rows, {"link": "page"})
    assert "&lt;a href=" in escaped and "<a href" not in escaped
    with pytest.raises(ValueError, match=r"raw must name columns \['link'\], but found \['page'\]"):
        html_table(rows, {"link": "page"}, raw={"page"})


def test_claims_sentence_counts_or_says_the_checklist_is_missing():
    assert claims_sentence(record()) == "The checklist holds 5 claims: 2 PASS, 1 PARTLY and 2 FAIL."
    assert "no claims checklist" in claims_sentence(record(claims=False))


def test_printed_rows_link_the_page_by_its_title():
    rec = {"entries": [
        {"id": "K_f1", "source": "Sec. IV", "paper": [[0.1048, 15.0897]], "chapter": "passive_controllers",
         "recomputed": [[0.104946831, 15.09821467]], "verdict": "close", "note": "n"},
        {"id": "long", "source": "Sec. IV", "paper": list(range(40)), "recomputed": [0.5] * 40,
         "verdict": "differs", "note": "n"}]}
    rows = printed_rows(rec, {"passive_controllers": "Passive controllers"})
    assert rows[0]["link"] == '<a href="passive_controllers.html">Passive controllers</a>'
    assert printed_rows(rec)[0]["link"] == '<a href="passive_controllers.html">passive controllers</a>'
    # a long value is folded, whole, in a details element; an entry without a page has no link
    assert rows[1]["printed"].startswith("<details><summary>0, 1, 2, 3, … (40 values)")
    assert ", 39</p></details>" in rows[1]["printed"] and rows[1]["link"] == ""


def test_the_ladder_rows_give_a_share_only_where_a_rung_takes_headroom():
    from fdsc.paper.appendix.report_law import ladder_rows

    def row(median, share):
        return {"median": median, "low": median * 0.99, "high": median * 1.01, "win_rate": 0.5,
                "draws": 250, "headroom_share": [share, share - 0.1, share + 0.1]}

    full = {"commit": "048c47d821e7", "aircraft": {"ladder": {"summary": {
        "predictive": row(0.92, 0.69), "FDSC": row(334.0, -46.57),
        "best fixed (x, ŵ)": {"median": 1.0, "low": 1.0, "high": 1.0, "win_rate": 0.0, "draws": 250}}}}}
    rows = ladder_rows(full)
    # a rung that takes headroom carries its interval; one that loses says none, without one
    assert sorted(r["share"] for r in rows) == ["", "69 % [59 %, 79 %]", "none"]
    # the reference is not said to win on 0 % of the draws against itself
    assert sorted(r["wins"] for r in rows) == ["50 %", "50 %", "the reference"]


def test_the_law_rows_carry_an_interval_where_the_per_draw_ratios_are_stored():
    from fdsc.paper.appendix.report_law import law_rows

    ratios = [0.9, 0.95, 1.0, 1.05, 1.1] * 10
    one = {"draws_test": 50, "draws_train": 50, "fixed_in_advance": "tuned",
           "median_ratio_vs_fixed_in_advance": 1.0, "win_rate_vs_fixed_in_advance": 0.4,
           "reference_median_ratio": 1.0,
           "ratio_vs_fixed_in_advance": ratios, "reference_ratio": {"tuned pair": ratios},
           "reference_family": "tuned pair"}
    stored, = law_rows({"entries": []}, {"n": 100, "commit": "048c47d821e7", "aircraft": one})
    assert re.fullmatch(r"×1\.00 \[0\.9\d*, 1\.0\d*\]", stored["median"])
    assert stored["clairvoyant"] == stored["median"]
    # the record's build-time check stores no per-draw ratios: the median alone
    bare = {k: v for k, v in one.items() if k not in ("ratio_vs_fixed_in_advance", "reference_ratio")}
    rec = {"entries": [{"id": "supervisor", "verdict": "new", "recomputed": {"aircraft": bare}}]}
    assert [r["median"] for r in law_rows(rec)] == ["×1.00"]


def test_the_papers_best_hf_sentence_is_an_erratum_when_kf3_has_the_largest_hf_peak():
    from fdsc.paper.appendix.report_further import further_findings

    peaks = {"K_f1": 0.4089, "K_f2": 0.4028, "K_f3": 1.605, "K_e": 0.4028}
    entry = {"id": "sigma_peak", "source": "s", "paper": None, "verdict": "new", "note": "n",
             "recomputed": {k: {"LF": 1.0, "HF": v} for k, v in peaks.items()}}
    [row] = further_findings({"entries": [entry]})
    assert row["where"] == "Sec. IV, text on paper Fig. 3"
    assert "band peak over the HF range is 1.605, the worst of the four printed gains" in row["what"]
    assert "(the others 0.4028 to 0.4089)" in row["what"]
    entry["recomputed"]["K_f3"]["HF"] = 0.405      # between the others: not the best, not the worst
    assert "not the best of the four" in further_findings({"entries": [entry]})[0]["what"]
