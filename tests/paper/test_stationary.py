import numpy as np
import pytest
from numpy.testing import assert_allclose

from fdsc.paper.reproduced.stationary import (
    OUR_Q_NAME,
    Claim,
    HalvingRow,
    hf_l2_claims,
    hf_output_claims,
    lf_output_claims,
    stationary_runs,
    step_halving,
)
from fdsc.paper.shared.data import paper_disturbance, run_controller
from fdsc.paper.shared.names import CONTROLLERS
from fdsc.paper.shared.results import RecordPart
from fdsc.paper.shared.verdict import VERDICTS
from fdsc.simulate import time_grid

HORIZON = 5.0


@pytest.fixture(scope="module")
def lf():
    return stationary_runs("LF", horizon=HORIZON)


@pytest.fixture(scope="module")
def hf():
    return stationary_runs("HF", horizon=HORIZON)


def _check_entries(part, ids):
    assert isinstance(part, RecordPart)
    assert [e["id"] for e in part.entries] == list(ids)
    for e in part.entries:
        assert all(k in e for k in ("id", "source", "paper", "recomputed", "verdict", "note"))
        assert e["verdict"] in VERDICTS


def test_runs_hold_every_controller_and_a_faithful_envelope(lf):
    assert lf.names == (*CONTROLLERS, OUR_Q_NAME)
    for name in lf.names:
        assert lf.z_lo[name].shape == lf.z_hi[name].shape == (lf.t.size, 3)
        assert np.all(lf.z_lo[name] <= lf.z_hi[name])
        # the envelope holds every sample, so its extremes are the run's peaks
        assert_allclose(np.maximum(np.abs(lf.z_lo[name]), np.abs(lf.z_hi[name])).max(axis=0),
                        lf.peak[name], rtol=1e-12)
    assert set(lf.switches) == {"FDSC", OUR_Q_NAME}


def test_energies_are_those_of_a_plain_run(lf):
    d, t = paper_disturbance("LF"), time_grid(HORIZON, lf.dt)
    assert_allclose(lf.energy["PassC-LF"], run_controller("PassC-LF", d, t).energy(), rtol=1e-12)


def test_running_l2_norm_ends_at_the_energy_ratio(hf):
    # trapezoid running ratio against Simpson energies: the same quantity to quadrature error
    for name in CONTROLLERS:
        assert_allclose(hf.l2_final[name] ** 2, hf.energy[name] / hf.input_energy, rtol=1e-3)


def test_record_figures(lf, hf):
    assert list(lf.to_record().figures) == ["lf_outputs"]
    figs = hf.to_record().figures
    assert list(figs) == ["hf_outputs", "hf_l2"]
    assert figs["hf_outputs"]["energy_fdsc_our_q"] == hf.energy[OUR_Q_NAME]
    assert OUR_Q_NAME not in figs["hf_outputs"]["energy"]


@pytest.mark.parametrize("call, match", [
    (lambda: stationary_runs("MF", horizon=1.0), r"kind must be one of"),
    (lambda: stationary_runs("LF", horizon=1.0, head=0.0), r"head"),
])
def test_bad_run_inputs(call, match):
    with pytest.raises(ValueError, match=match):
        call()


def test_lf_claims_agree_with_the_runs(lf):
    c = lf_output_claims(lf)
    assert_allclose(c.ratio_fdsc_lf, lf.energy["FDSC"] / lf.energy["PassC-LF"], rtol=1e-12)
    assert_allclose(c.ratio_ours_lf, lf.energy[OUR_Q_NAME] / lf.energy["PassC-LF"], rtol=1e-12)
    assert c.claim_similar.holds == (c.ratio_fdsc_lf <= 2)
    assert c.claim_thousand.value == pytest.approx(c.peak_ratio_hf.max(), rel=1e-12)
    assert c.smallest == min(CONTROLLERS, key=lf.energy.get)
    assert c.claim_smallest.holds == (c.smallest == "PassC-LF")
    part = c.to_record()
    _check_entries(part, ("lf_outputs_claims",))
    assert part.entries[0]["verdict"] == ("match" if all(x.holds for x in c.claims) else "differs")


def test_hf_claims_agree_with_the_runs(hf):
    c = hf_output_claims(hf)
    q = [hf.peak[n][0] / 4 for n in CONTROLLERS]  # z_1 = 4q
    assert_allclose((c.q_min, c.q_max), (min(q), max(q)), rtol=1e-12)
    assert c.claim_range.holds == (max(q) < 0.15)
    assert c.claim_coincident.holds == (c.q_ratio <= 1.5)
    _check_entries(c.to_record(), ("hf_outputs_claims",))
    l2 = hf_l2_claims(hf)
    f = hf.l2_final
    assert_allclose(l2.ratios, [f["PassC-EF"] / f["PassC-HF"], f["PassC-EF"] / f["FDSC"],
                                f["PassC-LF"] / f["PassC-HF"], f["PassC-LF"] / f["FDSC"]], rtol=1e-12)
    assert l2.slow_pole_hf < 0 and l2.time_constant_hf == pytest.approx(-1 / l2.slow_pole_hf)
    assert l2.fdsc_beats_hf in ("at this horizon only", "also against the steady state",
                                "not even at this horizon")
    _check_entries(l2.to_record(), ("hf_l2_claims",))


def test_claims_need_the_right_disturbance(lf, hf):
    with pytest.raises(ValueError, match=r"StationaryRuns of the LF disturbance"):
        lf_output_claims(hf)
    with pytest.raises(ValueError, match=r"StationaryRuns of the HF disturbance"):
        hf_output_claims(lf)
    with pytest.raises(ValueError, match=r"StationaryRuns of the HF disturbance"):
        hf_l2_claims({"kind": "HF"})


def test_claim_verdicts():
    yes, no = Claim("s", "r", 1.0, True), Claim("s", "r", (1.0, 2.0), False)
    assert (yes.verdict, yes.outcome, no.verdict, no.outcome) == ("match", "holds", "differs", "fails")
    assert set(yes.to_dict()) == {"sentence", "reading", "value", "holds", "verdict"}


def test_step_halving():
    h = step_halving("HF", horizon=1.0)
    assert [r.controller for r in h.controllers] == list(CONTROLLERS)
    for name in ("PassC-EF", "PassC-LF", "PassC-HF"):
        r = h.row(name)
        # fixed gains: the step is exact; only Simpson's rule changes, by about (ω dt)⁴/180
        # = 4.5e-5 at the fastest tone (300 rad/s, dt = 1 ms)
        assert r.switches_dt == r.switches_dt2 == 0 and r.rel_change < 1e-4
    assert h.max_rel_change == max(r.rel_change for r in h.controllers)
    assert [r["controller"] for r in h.rows()] == list(CONTROLLERS)
    with pytest.raises(KeyError, match=r"controller must be one of"):
        h.row("FDSC (our Q)")
    _check_entries(h.to_record(), ("step_halving_hf",))
    assert HalvingRow("x", 2.0, 2.5, 0, 0).rel_change == 0.25
