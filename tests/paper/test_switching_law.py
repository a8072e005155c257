import numpy as np
import pytest

from fdsc.paper.reproduced.switching_law import law_conflict, record_part, switching_statistics
from fdsc.paper.shared.data import our_q, paper_modes, piecewise_disturbance, run_controller
from fdsc.paper.shared.results import RecordPart
from fdsc.paper.shared.verdict import VERDICTS
from fdsc.simulate import time_grid


@pytest.fixture(scope="module")
def stats():
    return switching_statistics(T=5.0, rho_t=0.2)


@pytest.mark.parametrize("which", ["paper", "ours"])
def test_every_sample_in_the_conflict_region_is_a_switch(which):
    # with the measured xdot, in the region the active mode's own score prefers another mode,
    # so the simulated law must switch there: region samples = switches taken in the region
    pm = paper_modes()
    Q = pm["Q"] if which == "paper" else our_q().Q
    d = piecewise_disturbance(5.0, 0.2, 0.1)
    t = time_grid(d.breaks[-1], 1e-3)
    sim = run_controller("FDSC", d, t, Q=Q)
    c = law_conflict(sim, pm["modes"], pm["bands"], Q)
    assert c.n_switches == int(np.count_nonzero(np.diff(sim.sigma)))
    assert 0.0 <= c.in_region <= 1.0 and 0.0 <= c.switches_in_region <= 1.0
    assert round(c.in_region * t.size) == round(c.switches_in_region * c.n_switches)


def test_switching_statistics_variants(stats):
    assert list(stats.variants) == ["paper Q, measured ẋ", "paper Q, candidate ẋ", "our Q, measured ẋ"]
    assert stats.breaks.tolist() == [0.0, 5.0, 6.0, 11.0]
    assert (stats.T, stats.rho_t, stats.rho_p_star) == (5.0, 0.2, 0.1)
    for v in stats.variants.values():
        assert v.sigma.shape == stats.t.shape
        assert np.all((v.sigma >= 0) & (v.sigma <= 1))
        assert len(v.share_hf) == 3 and all(0.0 <= s <= 1.0 for s in v.share_hf)
        assert 0.0 <= v.single_sample_dwell <= 1.0 and v.energy > 0
        assert (v.conflict is None) == (v.law == "candidate")
        if v.conflict is not None:
            assert v.conflict.n_switches == v.switches


def test_switching_statistics_rows_and_record(stats):
    rows = stats.rows()
    assert [r["law"] for r in rows] == list(stats.variants)
    assert [r["switches"] for r in rows] == [v.switches for v in stats.variants.values()]
    part = stats.to_record()
    assert isinstance(part, RecordPart)
    (e,) = part.entries
    assert e["id"] == "law_chattering" and e["verdict"] in VERDICTS
    assert "in_conflict_region" not in e["recomputed"]["paper Q, candidate ẋ"]
    assert "in_conflict_region" in e["recomputed"]["paper Q, measured ẋ"]


def test_record_part_is_the_output_matrix_and_the_default_statistics():
    part = record_part()
    assert [e["id"] for e in part.entries] == ["closed_loop_output_matrix", "law_chattering"]
    # paper eq. (32) prints C + B2 K_sigma: C (3 x 2) and B2 K (2 x 2) cannot be added, a printed
    # expression that differs, which the report's errata list
    from fdsc.paper.appendix.reproduction_report import PROOF_STEP, entry_kind, errata
    from fdsc.paper.shared.data import aircraft

    e = part.entries[0]
    plant = aircraft()
    K = np.zeros((plant.B2.shape[1], plant.A.shape[0]))
    assert (plant.B2 @ K).shape != plant.C.shape == (plant.C + plant.D2 @ K).shape
    assert (e["verdict"], entry_kind(e)) == ("differs", PROOF_STEP)
    assert e["recomputed"]["C"] == list(plant.C.shape)
    assert [r["where"] for r in errata({"entries": [e]})] == [
        "Sec. III-B, the switched closed loop, paper eq. (32)"]


def test_bad_piecewise_input():
    with pytest.raises(ValueError, match=r"rho_t must be >= 0"):
        switching_statistics(T=5.0, rho_t=-0.1)
