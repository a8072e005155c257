import json

import pytest

from fdsc.paper.reproduced.claims import ClaimRow, halving_record, stationary_claims, sweep_claims
from fdsc.paper.reproduced.nonstationary import (
    SweepStudy,
    crossover,
    extended_piecewise,
    mixed_sweep,
    p1_global,
    p2_localized,
    piecewise_sweep,
)
from fdsc.paper.reproduced.stationary import stationary_runs
from fdsc.paper.shared.verdict import CLAIM_VERDICTS

DT = 2e-3


@pytest.fixture(scope="module")
def study():
    # ρ_p on a step of 0.0625: 0.1875 ≤ 0.2 lies beyond the crossover (about 0.13)
    mixed, pw = mixed_sweep(9, dt=DT), piecewise_sweep(3, dt=DT)
    ext = extended_piecewise((0.5, 2.0), dt=DT)
    cross = {r: crossover(mixed, r, tol=0.05) for r in ("PassC-LF", "PassC-EF")}
    ext_cross = {r: crossover(ext, r, tol=0.1) for r in ("PassC-LF", "PassC-EF")}
    p1, p2 = p1_global(mixed), p2_localized(pw)
    half = mixed_sweep(9, dt=DT / 2)
    cross_half = {r: crossover(half, r, tol=0.05) for r in ("PassC-LF", "PassC-EF")}
    return SweepStudy(mixed, pw, cross, ext, ext_cross, p1, p2, half, pw, cross_half, p1_global(half), p2)


def test_claim_row_checks_its_verdict():
    with pytest.raises(ValueError, match="verdict must be one of"):
        ClaimRow("c", "s", "m", 1.0, "OK", "r")
    assert ClaimRow("c", "s", "m", (1.0, 2.0), "PASS", "r").to_dict()["value"] == [1.0, 2.0]


def test_sweep_claims(study):
    rows = sweep_claims(study)
    assert len(rows) == 9 and all(r.verdict in CLAIM_VERDICTS for r in rows)
    by_source = {}
    for r in rows:
        by_source.setdefault(r.source, []).append(r)
    assert len(by_source["Sec. IV, text on paper Fig. 7"]) == 4
    assert len(by_source["Sec. IV, text on paper Fig. 8"]) == 3
    fig7 = {r.claim[:30]: r for r in by_source["Sec. IV, text on paper Fig. 7"]}
    # PassC-HF's energy at ρ_p = 0.5 is about 3e6 (closed form: the LF gain of K_f3 is ~1e3)
    assert fig7["the energy of PassC-HF has rea"].value == pytest.approx(2.9e6, rel=0.1)
    # FDSC loses to PassC-LF before ρ_p = 0.2 (bisected near 0.12): the ≤ 0.2 claim is only partly true
    assert fig7["the proposed FDSC gives rise t"].verdict == "PARTLY"
    assert fig7["in case that the out-of-band c"].verdict == "PASS"
    # a count, as the report prints it: PASS means every grid point ρ_p > 0.2
    k, n = fig7["in case that the out-of-band c"].value.split(" of ")
    assert k == n and int(n) > 1
    p2 = by_source["Sec. II-C, objective (P.2)"][0]
    assert set(p2.value) == {"1 s", "10 s", "100 s"}
    json.dumps([r.to_dict() for r in rows], allow_nan=False)
    half = sweep_claims(study, half=True)
    assert [r.claim for r in half] == [r.claim for r in rows]
    rec = halving_record(study).entries[0]
    assert rec["id"] == "claims_step_halving" and len(rec["recomputed"]) == 9
    assert rec["all_equal"] == all(a.verdict == b.verdict for a, b in zip(rows, half, strict=True))


def test_stationary_claims_read_the_runs():
    lf, hf = stationary_runs("LF", horizon=50.0, dt=DT, with_our_q=False), stationary_runs(
        "HF", horizon=50.0, dt=DT, with_our_q=False)
    rows = stationary_claims(lf, hf)
    assert len(rows) == 9 and all(r.verdict in CLAIM_VERDICTS for r in rows)
    gap = rows[6]
    assert gap.claim.startswith("the gap between the purple [FDSC] and red")
    # the deciding ratios, recomputed from the peaks
    pk = lf.peak
    expected = abs(pk["FDSC"][1] - pk["PassC-LF"][1]) / abs(pk["PassC-HF"][1] - pk["FDSC"][1])
    assert gap.value["2 delta_E"] == pytest.approx(expected)
