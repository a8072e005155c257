import numpy as np
import pytest
from numpy.testing import assert_allclose

from fdsc import Band
from fdsc.paper.reproduced.frequency_selective import (
    PROP1_KINDS,
    EPFAircraft,
    Prop1Case,
    Prop1Cases,
    _trend,
    alpha_mix,
    epf_aircraft,
    epf_time_series,
    power_vs_alpha,
    prop1_cases,
    prop1_summary,
    table1_trends,
)
from fdsc.paper.shared.results import RecordPart
from fdsc.paper.shared.verdict import VERDICTS

REQUIRED = ("id", "source", "paper", "recomputed", "verdict", "note")


def _check_part(part, ids):
    assert isinstance(part, RecordPart)
    assert [e["id"] for e in part.entries] == list(ids)
    for e in part.entries:
        assert all(k in e for k in REQUIRED)
        assert e["verdict"] in VERDICTS


@pytest.fixture(scope="module")
def cases():
    return prop1_cases(24, seed=7)


def test_prop1_cases_are_seeded_and_cycle_through_the_kinds(cases):
    again = prop1_cases(24, seed=7)
    assert [c.S_in for c in cases.cases] == [c.S_in for c in again.cases]
    order = [PROP1_KINDS[0]] * 2 + [PROP1_KINDS[1]] + [PROP1_KINDS[2]] * 2 + [PROP1_KINDS[3]]
    assert [c.kind for c in cases.cases] == order * 4
    assert len(cases) == 24 and cases.seed == 7


def test_prop1_case_invariants(cases):
    for c in cases.cases:
        assert c.passed == (c.S_in > 0 and c.S_out < 0)
        assert (c.periods is not None) == (c.kind == "window from rest")
        assert c.band_in != c.band_out
        if c.kind == "infinite, MF":
            # for real signals the MF weight is negative at every frequency
            assert c.band_in == "MF" and c.S_in < 0 and not c.passed


def test_prop1_summary_counts_match_the_cases(cases):
    s = prop1_summary(cases)
    assert s.passed + s.failed == len(cases)
    assert s.passed == sum(c.passed for c in cases.cases)
    assert sum(p + f for p, f in s.per_kind.values()) == len(cases)
    failing = [c.periods for c in cases.cases if c.kind == "window from rest" and not c.passed]
    assert s.longest_failing_window == (max(failing) if failing else 0.0)
    # the record's form and the table's rows carry the same counts
    assert s.counts()["cases"] == {r["kind"]: {"passed": r["passed"], "failed": r["failed"]}
                                   for r in s.rows()}
    assert prop1_summary(cases.cases) == s


def test_prop1_record_entries(cases):
    part = cases.to_record()
    _check_part(part, ("prop1_checks", "prop1_short_windows"))
    checks = part.entries[0]
    assert checks["verdict"] == ("differs" if checks["recomputed"]["failed"] else "match")
    assert part.entries[1]["verdict"] == "new"


@pytest.mark.parametrize("kwargs, match", [
    ({"kind": "nonsense", "periods": None}, r"kind must be one of"),
    ({"kind": "window from rest", "periods": None}, r"periods must be given"),
    ({"kind": "infinite, MF", "periods": 1.0}, r"periods must be given"),
])
def test_bad_prop1_case(kwargs, match):
    with pytest.raises(ValueError, match=match):
        Prop1Case(0, band_in="LF", band_out="HF", n=2, S_in=1.0, S_out=-1.0, **kwargs)


def test_bad_prop1_inputs():
    with pytest.raises(ValueError, match=r"n_cases"):
        prop1_cases(0)
    with pytest.raises(ValueError, match=r"cases must be a non-empty sequence of Prop1Case"):
        Prop1Cases((), 1)


@pytest.mark.parametrize("alpha", [0.0, 0.3, 1.0])
def test_alpha_mix_has_the_dominance_and_unit_power(alpha):
    d = alpha_mix(alpha)
    # mean power of a sum of distinct sinusoids: sum of a_k^2 / 2
    power = d.amplitudes**2 / 2
    assert_allclose(power.sum(), 1.0, rtol=1e-12)
    assert_allclose(power[d.frequencies > 10].sum(), alpha, rtol=1e-12, atol=1e-15)
    assert_allclose(d.dominance(Band.hf(10.0)), alpha, rtol=1e-12, atol=1e-15)


@pytest.mark.parametrize("alpha", [-0.1, 1.5])
def test_bad_alpha(alpha):
    with pytest.raises(ValueError, match=r"alpha must lie in \[0, 1\]"):
        alpha_mix(alpha)


def test_power_vs_alpha_is_affine_and_crosses_zero_at_the_recorded_alpha():
    alphas = (0.0, 0.25, 0.5, 1.0)
    pv = power_vs_alpha(alphas)
    assert pv.alpha.shape == (4,)
    for label, v in pv.curves.items():
        # mean powers add, so P_a(alpha) = (1 - alpha) P_a(0) + alpha P_a(1)
        assert_allclose(v, (1 - pv.alpha) * v[0] + pv.alpha * v[-1], rtol=1e-9,
                        atol=1e-12 * np.abs(v).max())
        assert_allclose(pv.in_band[label] + pv.out_of_band[label], v, rtol=1e-9,
                        atol=1e-12 * np.abs(v).max())
        a = pv.crossing[label]
        if a is not None:
            assert 0.0 <= a <= 1.0
            assert abs((1 - a) * v[0] + a * v[-1]) <= 1e-9 * np.abs(v).max()
        else:
            assert v[0] * v[-1] > 0
    _check_part(pv.to_record(), ("remark1_crossings",))


def test_power_vs_alpha_checks_shapes():
    pv = power_vs_alpha((0.0, 1.0))
    with pytest.raises(ValueError, match=r"curves\[.*\] must have shape \(3,\)"):
        type(pv)(np.array([0.0, 0.5, 1.0]), pv.curves, pv.in_band, pv.out_of_band, pv.crossing)


def test_epf_time_series_envelope_and_average():
    s = epf_time_series("K_f1", "HF", horizon=2.0, every=20)
    assert s.t.shape == s.P_a["LF"].shape == s.P_t_lo["HF"].shape
    assert s.bin == pytest.approx(0.02, rel=1e-12)
    for kind in ("LF", "HF"):
        assert np.all(s.P_t_lo[kind] <= s.P_t_hi[kind])
    assert set(s.final_average) == {"LF", "HF"}


def test_bad_epf_inputs():
    with pytest.raises(ValueError, match=r"gain must be one of"):
        epf_time_series("K_x", "LF", horizon=1.0)
    with pytest.raises(ValueError, match=r"kind must be one of"):
        epf_time_series("K_f1", "MF", horizon=1.0)


def test_epf_aircraft_series_and_record():
    res = epf_aircraft(horizon=2.0)
    assert isinstance(res, EPFAircraft)
    assert [(s.gain, s.disturbance) for s in res.series] == [
        ("K_f1", "LF"), ("K_f1", "HF"), ("K_f3", "LF"), ("K_f3", "HF")]
    assert res.get("K_f3", "LF") is res.series[2]
    with pytest.raises(KeyError, match=r"no series"):
        res.get("K_e", "LF")
    part = res.to_record()
    _check_part(part, ("epf_aircraft_signs",))
    rec = part.entries[0]["recomputed"]
    for s in res.series:
        assert rec[f"{s.gain}, {s.disturbance} disturbance"]["selective"] == s.selective


def test_trend_names():
    assert _trend(np.array([1.0, 2.0, 3.0])) == "up"
    assert _trend(np.array([3.0, 2.0, 1.0])) == "down"
    assert _trend(np.array([1.0, 1.0, 2.0])) == "non-decreasing"
    assert _trend(np.array([2.0, 2.0, 1.0])) == "non-increasing"
    assert _trend(np.array([1.0, 3.0, 2.0])) == "not monotone"


def test_table1_trends_rows_and_record():
    tt = table1_trends((0.2, 0.8), horizon=2.0)
    assert len(tt.checks) == 7
    for c in tt.checks:
        ok = c.observed == c.claimed or (c.claimed, c.observed) in {
            ("up", "non-decreasing"), ("down", "non-increasing")}
        assert c.verdict == ("match" if ok else "differs")
        assert c.values.shape == (2,)
    assert tt.n_match == sum(c.verdict == "match" for c in tt.checks)
    lo, hi = tt.beta_range
    assert 0.0 <= lo <= hi <= 1.0
    # T_i + sum_j T_j is the horizon
    assert_allclose(tt.check("T_i (time in mode i)").values + tt.check("Σ_j T_j").values, 2.0,
                    rtol=1e-12)
    assert [r["quantity"] for r in tt.rows()] == [c.quantity for c in tt.checks]
    with pytest.raises(KeyError, match=r"quantity must be one of"):
        tt.check("nothing")
    part = tt.to_record()
    _check_part(part, ("table1_checks",))
    assert part.entries[0]["verdict"] in ("match", "differs")
