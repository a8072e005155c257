"""fdsc.paper.pays.ladder (chapter 'ladder'): the summaries and intervals, the figure, the rungs of
one draw against the bound, the stored study's ladder rechecked, and the summary page's errata
equal to the report's."""

import json
from pathlib import Path

import numpy as np
import pytest

from fdsc.paper.pays import ladder as ld
from fdsc.paper.pays.disturbance_law import load_full

ROOT = Path(__file__).resolve().parents[2]


def test_the_bootstrap_interval_holds_the_median_and_narrows_with_more_draws():
    rng = np.random.default_rng(0)
    x = rng.lognormal(0.0, 0.1, 400)
    m, lo, hi = ld.bootstrap_median(x)
    m4, lo4, hi4 = ld.bootstrap_median(x[:100])
    assert lo < m < hi and lo4 < m4 < hi4
    assert hi - lo < hi4 - lo4                          # four times the draws: about half the width
    assert ld.bootstrap_median(x) == (m, lo, hi)         # seeded


def test_the_summary_measures_each_causal_rung_against_the_limit():
    lim = np.array([0.5, 0.8, 0.64])
    ratios = {"limit": lim, "predictive": np.sqrt(lim), "best fixed (x, ŵ)": np.ones(3),
              "FDSC": 2 * np.ones(3)}
    s = ld.summarize(ratios)
    np.testing.assert_allclose(s["predictive"]["headroom_share"][0], 0.5)   # half of every log gap
    assert s["FDSC"]["headroom_share"][0] < 0 and s["FDSC"]["win_rate"] == 0.0
    assert "headroom_share" not in s["best fixed (x, ŵ)"] and s["predictive"]["win_rate"] == 1.0
    assert ld.best_realizable(s) == "predictive"


def test_the_figure_draws_a_rung_beyond_its_axis_at_the_edge_with_its_median():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from fdsc.paper.pays.plotting_ladder import plot_ladder

    summary = {"limit": {"median": 0.7, "low": 0.68, "high": 0.72},
               "FDSC": {"median": 53.0, "low": 40.0, "high": 60.0}}
    fig, ax = plt.subplots()
    plot_ladder(summary, ax)
    texts = [t.get_text() for t in ax.texts]
    assert "×53.0" in texts and "×0.700" in texts   # as the prose writes them
    lo, hi = ax.get_xlim()
    assert lo < 0.68 and 1.0 < hi <= 2.0              # the axis holds the intervals below ×2 and ×1
    plt.close(fig)


def _stored():
    full = load_full()
    if full is None or "ladder" not in full.get("generic", {}):
        pytest.skip("the stored study with the ladder is not in this checkout")
    return full


@pytest.mark.parametrize("example", ["aircraft", "generic"])
def test_the_stored_ladder_respects_its_bound_on_every_draw(example):
    lad = _stored()[example]["ladder"]
    r = {k: np.asarray(v) for k, v in lad["ratios"].items()}
    for rung in r:
        assert np.all(r["limit"] <= r[rung] * (1 + 1e-9)), rung
    assert np.all(r["best fixed (x, ŵ)"] == 1.0)
    assert len(r["limit"]) == len(lad["test_indices"]) == _stored()[example]["draws_test"]


@pytest.mark.parametrize("example", ["aircraft", "generic"])
def test_the_stored_ladder_is_recomputed_from_its_controllers(example):
    # the record's ladder entry holds the recomputation (ld.recheck_ladder on the stored study's
    # first test draws, from the stored controllers), computed with this checkout's sources
    from fdsc.paper.record import reproduction_record

    _stored()
    (entry,) = [e for e in reproduction_record()["entries"] if e["id"] == "ladder"]
    chk = entry["recomputed"][example]["recheck"]
    assert chk["draws"] == ld.N_RECHECK and chk["rungs"] >= 8
    assert chk["largest_difference"] < 1e-6


def test_a_changed_stored_ratio_is_caught_by_the_recheck(monkeypatch):
    # the recomputation itself is the test above; here each draw's rungs are the stored ratios
    # over a reference of 2 (what a recomputation that agrees returns), so that only the
    # comparison is tested, without recomputing a draw
    stored = _stored()

    def agreeing_draw(example, index, seed, fs, settings):
        lad = stored[example]["ladder"]
        j = lad["test_indices"].index(index)
        return {rung: 2.0 * ratios[j] for rung, ratios in lad["ratios"].items()}

    monkeypatch.setattr(ld, "ladder_draw", agreeing_draw)
    assert ld.recheck_ladder(stored, "generic")["largest_difference"] < 1e-15
    full = json.loads(json.dumps(stored))
    full["generic"]["ladder"]["ratios"]["predictive"][0] *= 1.001
    assert ld.recheck_ladder(full, "generic")["largest_difference"] == pytest.approx(1 - 1 / 1.001, rel=1e-9)


def test_the_summary_pages_errata_are_the_reports():
    from fdsc.paper.appendix.reproduction_report import errata, errata_summary

    record = json.loads((ROOT / "book" / "data" / "reproduction.json").read_text()) \
        if (ROOT / "book" / "data" / "reproduction.json").is_file() else None
    if record is None:
        pytest.skip("no built record in this checkout")
    lines = errata_summary(record).splitlines()
    assert len(lines) == len(errata(record)) > 0
    assert [ln.split(". ", 1)[0] for ln in lines] == [str(r["n"]) for r in errata(record)]


def test_every_erratum_of_the_summary_says_what_is_wrong_in_one_line():
    from fdsc.paper.appendix.reproduction_report import errata, errata_summary, erratum_words

    record = json.loads((ROOT / "book" / "data" / "reproduction.json").read_text()) \
        if (ROOT / "book" / "data" / "reproduction.json").is_file() else None
    if record is None:
        pytest.skip("no built record in this checkout")
    for line, row in zip(errata_summary(record).splitlines(), errata(record), strict=True):
        what = line.split(f"*{row['verdict']}*: ", 1)[1]
        assert what == row["what"] and 20 < len(what) < 400, line
    # the bound beside K_f3 reads its numbers from the entry: its band peak over the printed bound
    entry = {"id": "bound_f3", "inequality": {"quantity": 1.605, "bound": 0.1714, "holds": False}}
    assert "1.605, above the printed 0.1714 (×9.364)" in erratum_words(entry)
    # every erratum of the book's record has its own line (not its note's first sentence)
    from fdsc.paper.appendix.reproduction_report import ERRATUM_WORDS

    missing = [r["id"] for r in errata(record) if r["id"] is not None and r["id"] not in ERRATUM_WORDS]
    assert missing == []
    assert erratum_words({"id": "new_entry", "note": "The sign is wrong. More words."}) == "The sign is wrong"


def test_runs_submitted_without_waiting_come_back_in_order_wherever_they_run():
    # submit_draws starts the runs (on an executor) and collects them later, in the order of the
    # arguments, as map_draws does; without an executor they run when collected
    from concurrent.futures import ThreadPoolExecutor

    from fdsc.paper.pays.stored_study import map_draws, submit_draws

    calls = []

    def slow_square(k, delay):
        import time

        time.sleep(delay)
        calls.append(k)
        return k * k

    args = [(k, 0.05 * (3 - k)) for k in range(4)]
    pending = submit_draws(slow_square, args, None)
    assert calls == []                              # nothing runs before it is collected
    assert pending.result() == [0, 1, 4, 9] == map_draws(slow_square, args, None)
    with ThreadPoolExecutor(4) as pool:
        calls.clear()
        pending = submit_draws(slow_square, args, pool)
        assert pending.result() == [0, 1, 4, 9]        # in the order of the arguments
        assert sorted(calls) == [0, 1, 2, 3]


def test_the_further_statements_found_false_read_their_numbers_from_the_findings():
    from fdsc.paper.appendix.reproduction_report import FURTHER_WORDS, further_findings, further_summary

    # a synthetic record: each line follows its finding's numbers, in the order of FURTHER_WORDS
    entries = [
        {"id": "remark3_gap", "source": "s", "paper": None, "verdict": "new", "note": "n",
         "recomputed": {"first_sign_change_rad_s": {"a": 12.5, "b": 13.0},
                        "gap_at_lowest_omega": {"a": 7.0}}},
        {"id": "paley_wiener_share", "source": "s", "paper": None, "verdict": "new", "note": "n",
         "recomputed": {"LF": {"T=50": 0.25}, "HF": {"T=50": 0.001}}},
        {"id": "unrelated", "source": "s", "paper": None, "verdict": "new", "note": "n", "recomputed": {}}]
    rows = further_findings({"entries": entries})
    assert [r["id"] for r in rows] == ["paley_wiener_share", "remark3_gap"]
    assert [r["n"] for r in rows] == [1, 2]
    assert "0.10 % to 25 %" in rows[0]["what"] and "between 12.5 and 13.0 rad/s" in rows[1]["what"]
    assert further_summary({"entries": entries}).splitlines()[1].startswith("2. paper Remark 3")
    # on the book's record every such statement is there, each with its own line
    path = ROOT / "book" / "data" / "reproduction.json"
    if not path.is_file():
        pytest.skip("no built record in this checkout")
    record = json.loads(path.read_text())
    assert [r["id"] for r in further_findings(record)] == list(FURTHER_WORDS)
    assert all(20 < len(r["what"]) < 400 for r in further_findings(record))


def test_the_law_on_a_noisy_estimate_is_scored_against_the_fixed_controller_on_the_same_estimate():
    from fdsc.paper.pays.disturbance_law_study import _noise_words

    # the law loses ×1.5 over the fixed controller on the exact estimate at 0 dB, but the noise costs
    # that fixed controller ×3 too: on the same estimate the law has half its energy
    rob = {"draws": 3, "snr_db": {"20.0": {"ratios": [1.1, 1.1, 1.1], "fixed_ratios": [1.0, 1.0, 1.0]},
                                  "0.0": {"ratios": [1.5, 1.5, 1.5], "fixed_ratios": [3.0, 3.0, 3.0]}}}
    words = _noise_words(rob)
    assert "×1.10 [1.10, 1.10] at 20 dB" in words and "×0.500 [0.500, 0.500] at 0 dB" in words
    assert _noise_words({}) == ""
