"""The report's rows from small synthetic records (with and without claims and figure data)."""

import numpy as np
import pytest

from fdsc.paper.appendix.reproduction_report import (
    NO_CHECKLIST,
    NO_CLAIM,
    claim_rows,
    claims_sentence,
    errata,
    figure_rows,
    figures_named,
    finding_rows,
    printed_rows,
    summary,
)
from fdsc.paper.record import PAPER_FIGURES
from fdsc.paper.shared.report import compact, html_table
from fdsc.paper.shared.results import entry
from fdsc.paper.shared.verdict import CLAIM_VERDICTS, VERDICTS


def _claim(source, verdict, value=0.1):
    return {"claim": f"words on {source}", "source": source, "measure": "m", "value": value,
            "verdict": verdict, "reason": "r"}


def record(*, claims=True):
    rec = {
        "entries": [
            entry("K_f1", "Sec. IV, K_{f_1}", np.array([[0.1048, 15.0897], [0.0205, 2.976]]),
                  np.array([[0.104946831, 15.09821467], [0.02051961207, 2.977720048]]), "close",
                  "within 1 %"),
            entry("bound_f1", "Sec. IV", 0.3443, np.float64(0.3737360687), "not reproducible",
                  "no candidate"),
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


def test_printed_rows_hold_every_printed_entry_with_compact_values():
    rows = printed_rows(record())
    # hf_best carries the printed K_f3 for reference but compares nothing (verdict new): left out
    assert [r["id"] for r in rows] == ["K_f1", "bound_f1", "model"]
    k = rows[0]
    assert k["paper"] == "[[0.1048, 15.09], [0.0205, 2.976]]"
    assert k["ours"] == "[[0.1049, 15.1], [0.02052, 2.978]]"
    assert (k["verdict"], k["reason"], k["source"]) == ("close", "within 1 %", "Sec. IV, K_{f_1}")
    assert rows[1]["ours"] == "0.3737" and rows[2]["paper"] == "A_long: [[-1.175, 0.9871]]"


def test_compact_shortens_long_lists_and_dicts():
    assert compact(np.linspace(0, 0.5, 21)) == "[0, 0.025, 0.05, 0.075, 0.1, 0.125, …] (21 values)"
    assert compact({f"k{i}": i for i in range(8)}, max_items=2) == "k0: 0; k1: 1; … (8 keys)"
    assert compact({"a": {"b": [1, 2]}}) == "a: {b: [1, 2]}"
    text = compact({"s": "x" * 500})
    assert len(text) == 160 and text.endswith("…")
    assert compact("inf") == "inf" and compact(True) == "True" and compact(np.int64(3)) == "3"


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
    rows = figure_rows(record())
    assert [r["number"] for r in rows] == list(PAPER_FIGURES) == list(range(1, 9))
    by = {r["number"]: r for r in rows}
    assert by[3]["link"] == '<a href="gkyp_lemma.html">gkyp_lemma</a>'
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
    assert len(rows) == 5 and rows[0] == {"claim": "words on Sec. IV, text on paper Fig. 7",
                                          "source": "Sec. IV, text on paper Fig. 7", "measure": "m",
                                          "value": "0.1", "verdict": "PASS", "reason": "r"}
    assert rows[-1]["value"] == "a: 1"


def test_finding_rows_are_the_new_entries():
    assert [r["id"] for r in finding_rows(record())] == ["sweep", "hf_best"]
    assert set(finding_rows(record())[0]) == {"id", "entry", "source", "note"}


def test_errata_list_what_differs_and_what_fails():
    rows = errata(record())
    # the printed bound that cannot be reproduced, then the two failing claims; matches, inputs and
    # findings are not errata
    assert [(r["n"], r["where"], r["verdict"]) for r in rows] == [
        (1, "Sec. IV", "not reproducible"), (2, "Sec. IV, text on paper Fig. 7", "FAIL"),
        (3, "Sec. IV, text on paper Fig. 10", "FAIL")]
    assert rows[0]["printed"] == "0.3443" and rows[1]["printed"] == "words on Sec. IV, text on paper Fig. 7"
    assert errata(record(claims=False))[-1]["verdict"] == "not reproducible"


def test_summary_counts_every_verdict():
    s = summary(record())
    assert list(s["entries"]) == list(VERDICTS) and list(s["claims"]) == list(CLAIM_VERDICTS)
    assert s["entries"] == {"match": 0, "close": 1, "differs": 0, "not reproducible": 1, "input": 1, "new": 2}
    assert s["claims"] == {"PASS": 2, "PARTLY": 1, "FAIL": 2}
    assert (s["n_entries"], s["n_claims"], s["n_figures"]) == (5, 5, 8)
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
    assert '<td><a href="stationary.html">stationary</a></td>' in table
    escaped = html_table(rows, {"link": "page"})
    assert "&lt;a href=" in escaped and "<a href" not in escaped
    with pytest.raises(ValueError, match=r"raw must name columns \['link'\], but found \['page'\]"):
        html_table(rows, {"link": "page"}, raw={"page"})


def test_claims_sentence_counts_or_says_the_checklist_is_missing():
    assert claims_sentence(record()) == "The checklist holds 5 claims: 2 PASS, 1 PARTLY and 2 FAIL."
    assert "no claims checklist" in claims_sentence(record(claims=False))


def test_printed_rows_show_whole_values_and_link_the_page():
    rec = {"entries": [
        {"id": "K_f1", "source": "Sec. IV", "paper": [[0.1048, 15.0897]], "chapter": "passive_controllers",
         "recomputed": [[0.104946831, 15.09821467]], "verdict": "close", "note": "n"},
        {"id": "long", "source": "Sec. IV", "paper": list(range(40)), "recomputed": [0.5] * 40,
         "verdict": "differs", "note": "n"}]}
    rows = printed_rows(rec)
    # the short form cuts printed digits (15.09); the full cell keeps every one
    assert rows[0]["paper"] == "[[0.1048, 15.09]]" and rows[0]["paper_full"] == "[[0.1048, 15.0897]]"
    assert rows[0]["ours_full"] == "[[0.104946831, 15.09821467]]"
    assert rows[0]["entry"] == '<a href="passive_controllers.html">K_f1</a>'
    # a long value is folded, whole, in a details element; an entry without a page is plain text
    assert rows[1]["paper_full"].startswith("<details><summary>[0, 1, 2, 3, 4, 5, …] (40 values)")
    assert ", 39]</span></details>" in rows[1]["paper_full"] and rows[1]["entry"] == "long"
