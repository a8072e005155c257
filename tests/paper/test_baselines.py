"""Tests of the chapter module fdsc.paper.pays.baselines (does FDSC pay on the aircraft?)."""

import numpy as np
import pytest

import fdsc
from fdsc.paper.pays import baselines as bl
from fdsc.paper.reproduced.nonstationary import mixed_sweep
from fdsc.paper.shared.data import paper_disturbance
from fdsc.paper.shared.examples import OPEN_LOOP


@pytest.fixture(scope="module")
def b():
    return bl.baselines()


def test_aircraft_example_holds_the_paper_controllers():
    ex = bl.aircraft_example()
    assert ex.names == bl.FIXED + bl.SWITCHED
    assert not np.any(ex.gains[OPEN_LOOP])
    printed, rule = ex.designs["FDSC"]
    assert rule == fdsc.PRINTED and ex.designs[bl.FDSC_DWELL][1] == fdsc.SwitchRule.dwell_time(bl.DWELL_TAU)
    with_best, _ = ex.designs[bl.FDSC_HF_BEST]
    np.testing.assert_array_equal(with_best.gains[1], ex.gains[bl.HF_BEST])
    np.testing.assert_array_equal(with_best.gains[0], printed.gains[0])


def test_the_paper_controllers_are_the_runs_of_nonstationary(b):
    sweep = mixed_sweep()
    _, e = b.energies("mixed")
    for name in ("PassC-EF", "PassC-LF", "PassC-HF", "FDSC"):
        np.testing.assert_array_equal(e[name], sweep.energy[name])


def test_stationary_energies_tend_to_the_closed_form(b):
    # a fixed loop from rest: ∫zᵀz/∫d² over 500 s against the steady-state gain squared
    # (closed form); the transient and the cross terms of distinct tones make up the rest
    for s in b.family("stationary"):
        d = paper_disturbance(s.label)
        for name in ("PassC-EF", "PassC-LF", bl.HF_BEST):
            ratio = s.energy[name] / s.input_energy
            np.testing.assert_allclose(ratio, b.steady[name][s.label] ** 2, rtol=0.05,
                                       err_msg=f"{name} under {s.label} ({d.frequencies})")


def test_headline_no_switched_controller_beats_the_fixed_ones_by_much(b):
    # measured: no switched controller beats the best fixed one in any of the 34 cases (the
    # closest, FDSC (dwell) under the HF tones, has 1.01 times the open loop's energy); the
    # margin of 10 % keeps the test off the rounding of the chattering law
    for name in bl.SWITCHED:
        assert np.min(b.switched_ratio(name)) > 0.9, name
    lf, hf = b.family("stationary")
    assert lf.winner() == "PassC-LF" and lf.factor("FDSC") > 10     # measured 119
    assert hf.winner(bl.FIXED) == OPEN_LOOP                       # 1.018 below PassC-HF


def test_hf_good_in_band(b):
    # the best HF design helps FDSC under LF tones (measured 0.44) and hurts under HF tones (7.0)
    lf, hf = b.family("stationary")
    assert lf.energy[bl.FDSC_HF_BEST] < 0.7 * lf.energy["FDSC"]
    assert hf.energy[bl.FDSC_HF_BEST] > 3 * hf.energy["FDSC"]
    assert b.steady[bl.HF_BEST]["HF"] > 2 * b.steady[OPEN_LOOP]["HF"]    # 0.291 against 0.108


def test_winner_table_covers_every_case(b):
    rows = b.winner_table()
    stationary = [r["winner"] for r in rows if r["family"] == "stationary"]
    assert stationary == [s.winner() for s in b.family("stationary")]
    for r in rows:
        lo, hi = r["runner-up factor"]
        assert 1.0 <= lo <= hi


def test_record_entries(b):
    part = b.to_record()
    ids = [e["id"] for e in part.entries]
    assert ids == ["baselines", "hf_good_in_band"]
    assert all(e["verdict"] == "new" and e["paper"] is None for e in part.entries)
    assert sum(part.entries[0]["recomputed"]["wins"].values()) == len(b.scenarios)
