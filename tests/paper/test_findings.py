"""fdsc.paper.findings: the landing page's answer, read from the record."""

import numpy as np
import pytest

from fdsc.paper.findings import PRINTED_BOUNDS, findings
from fdsc.paper.pays.baselines import SWITCHED, baselines
from fdsc.paper.record import reproduction_record
from fdsc.paper.shared.comparators import best_fixed


@pytest.fixture(scope="module")
def found():
    return findings(reproduction_record())


def test_the_cases_and_their_winners_agree_with_the_chapter(found):
    # recounted independently from the aircraft chapter's scenarios and the comparator set
    scen = baselines().scenarios
    assert found.n_cases == len(scen) == 34
    winners = [best_fixed(s.energy)[0] for s in scen]
    assert found.best_wins == {n: winners.count(n) for n in found.best_wins}
    beaten = sum(min(s.energy[n] for n in SWITCHED) < best_fixed(s.energy)[1] for s in scen)
    assert found.switched_wins == beaten


def test_the_numbers_are_the_records(found):
    rec = reproduction_record()
    by_id = {e["id"]: e for e in rec["entries"]}
    assert found.crossover == by_id["mixed_crossover"]["recomputed"]["PassC-LF"] < 0.2
    assert found.crossover_printed == 0.2
    assert set(found.bounds) == set(PRINTED_BOUNDS)
    assert sum(found.verdicts.values()) == sum(
        e["verdict"] in ("match", "close", "differs", "not reproducible") for e in rec["entries"])
    assert found.figures_total == 7 and found.figures_redrawn <= 7
    assert found.gains_reproduced == sum(by_id[k]["verdict"] in ("match", "close")
                                         for k in ("K_f1", "K_f2", "K_f3", "K_e"))
    assert sum(found.claims.values()) == len(rec["claims"])
    # the ideal segment law can only be compared where it has a value at every ρ_t
    assert 0 < found.ideal["aircraft"] and 0 < found.ideal["generic"]
    # the K_f1 loop's fast pole lies above the HF edge, the airframe's modes below it
    assert found.airframe_mode < found.w_h < found.fast_pole


def test_prose_is_formatted(found):
    text = found.prose()
    assert all(isinstance(v, str) for v in text.values())
    assert text["lf_switches"] == f"{found.lf_switches:,}"
    assert text["lf_ratio"].startswith("×") and " times" not in " ".join(text.values())
    assert not any("[" in v or "array" in v for v in text.values())
    assert np.isclose(float(text["crossover"]), found.crossover, rtol=5e-3)


def test_missing_entries_are_named():
    with pytest.raises(KeyError, match="lacks the entries .*comparators"):
        findings({"entries": [], "figures": {}, "claims": []})


def test_the_law_sentence_says_whether_it_pays_and_against_what():
    from fdsc.paper.findings import law_sentence
    from fdsc.paper.shared.prose import pct

    pays = {"median_ratio_vs_fixed_in_advance": 0.96, "win_rate_vs_fixed_in_advance": 0.78,
            "reference_median_ratio": 0.967, "fixed_in_advance": "tuned filtered", "draws_test": 250}
    flat = dict(pays, median_ratio_vs_fixed_in_advance=1.01, win_rate_vs_fixed_in_advance=0.3)
    text = law_sentence({"generic": pays, "aircraft": flat})
    assert text.startswith("on the generic example it pays: the best such law has a median energy ×0.960 "
                           f"that of the fixed controller chosen in advance (tuned filtered) and less on "
                           f"{pct(0.78)} of 250 test draws")
    assert "on the aircraft example it does not pay: the best such law has a median energy ×1.01" in text
    assert "controllers designed for each type of segment reaches ×0.967" in text
    # with the noisy estimate and the sampled measurements
    rob = {"snr_db": {"20.0": {"median": 0.99}, "10.0": {"median": 1.12}, "0.0": {"median": 2.5}}}
    meas = {"variants": {"exact": {"median": 0.96}, "min_switching": {"median": 3.9},
                         "a": {"median": 0.958}, "b": {"median": 0.986}}}
    text = law_sentence({"generic": dict(pays, robustness=rob, measured=meas)})
    assert "with the estimate's noise at 20 dB the median is ×0.990, and from 10 dB on the law loses" in text
    assert "its medians are ×0.958–×0.986" in text


def test_the_law_comes_from_the_full_study_or_the_record(found):
    assert set(found.law) == {"generic", "aircraft"}
    for r in found.law.values():
        assert r["certified"] is True and r["diverged"] == 0


def test_the_open_loop_against_passc_hf_is_a_steady_state_ratio(found):
    # the energies over [1000 s, 2000 s] of a run from rest, by the exact simulator: the K_f3
    # loop's slow pole (−0.0165 /s) has decayed there, as it has not over the paper's 500 s
    import fdsc
    from fdsc.paper.shared.data import aircraft, hf_disturbance, paper_gains

    plant, K, d = aircraft(), paper_gains()["K_f3"], hf_disturbance()
    tail = []
    for G in (np.zeros_like(K), K):
        r = fdsc.simulate_stream(plant.closed_loop(G), d, 2000.0, 1e-3, cumulative_every=1000.0)
        tail.append(r.energy_cum[-1] - r.energy_cum[-2])
    assert found.hf_open_loop_ratio == pytest.approx(tail[0] / tail[1], rel=1e-3)
    assert 0.99 < found.hf_open_loop_ratio < 1.0          # not the from-rest run's ×0.76
