import json
import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from fdsc import simulate
from fdsc.paper.reproduced.bound_search import (
    ENERGY_RATIO,
    L2_RATIO,
    ROUND_HORIZONS,
    STEADY_STATE,
    TimeDomainBoundSearch,
    TimeDomainCandidate,
    first_crossing,
    match_bound,
    output_label,
    search_signals,
    time_domain_bound_search,
)
from fdsc.paper.reproduced.stationary import stationary_runs
from fdsc.paper.shared.data import STATIONARY_DT, aircraft, hf_disturbance, paper_data, paper_gains
from fdsc.paper.shared.names import GAIN_ORDER
from fdsc.simulate import time_grid


@pytest.fixture(scope="module")
def search():
    return time_domain_bound_search()


def _candidate(search, gain, signal, quantity, horizon):
    found = [c for c in search.candidates if (c.gain, c.signal, c.quantity, c.horizon)
             == (gain, signal, quantity, horizon)]
    assert len(found) == 1, (gain, signal, quantity, horizon)
    return found[0]


def _closed_form_ratio(cl, d):
    """sqrt(Σ a_k² ‖G(jω_k)‖² / Σ a_k²) with G(jω) = C (jωI − A)⁻¹ B + D solved directly (no fdsc)."""
    num = 0.0
    for a, w in zip(d.amplitudes, d.frequencies, strict=True):
        G = cl.C @ np.linalg.solve(1j * w * np.eye(cl.A.shape[0]) - cl.A, cl.B) + cl.D
        num += a**2 * np.sum(np.abs(G) ** 2)
    return math.sqrt(num / np.sum(d.amplitudes**2))


# -- the pure matching logic ---------------------------------------------------------------------

def _cands(values, gain="K"):
    return [TimeDomainCandidate(gain, "HF", L2_RATIO, float(T), v)
            for T, v in zip(ROUND_HORIZONS, values, strict=False)]


def test_a_candidate_equal_to_the_printed_value_is_a_hit():
    cands = _cands([0.25, 0.12345, 0.5, 0.12346, 0.123449])
    m = match_bound("K", 0.1235, cands)
    # 0.12345 is half a printed unit away (the rule's edge: a hit); 0.123449 is just beyond
    assert m.hits == (cands[1], cands[3]) and m.hit_values == (0.12345, 0.12346)
    assert m.best is cands[3] and m.nearest[1:3] == (cands[1], cands[4])
    assert m.n_candidates == 5 and m.n_within_close == 3
    assert [r["hit"] for r in m.rows()] == ["yes", "yes", "", "", ""]


def test_a_candidate_one_percent_away_is_no_hit():
    # after the fact, 1 % away is not "close" but no reproduction at all
    m = match_bound("K", 0.1714, _cands([0.1714 * 1.01, 0.3]))
    assert m.hits == () and m.n_within_close == 1
    assert m.best.value == pytest.approx(0.1714 * 1.01, rel=1e-12)
    assert_allclose(m.rows()[0]["abs_diff"], 0.001714, rtol=1e-9)


def test_match_bound_keeps_hits_beyond_the_nearest_in_rows():
    cands = _cands([0.17140, 0.17141, 0.17142, 0.17143, 0.17144])
    m = match_bound("K", 0.1714, cands, n_nearest=2)
    assert len(m.nearest) == 2 and len(m.hits) == 5
    assert len(m.rows()) == 5


@pytest.mark.parametrize("kwargs, match", [
    ({"candidates": []}, "at least one"),
    ({"candidates": _cands([0.1], gain="K_f1")}, "belong to gain 'K'"),
    ({"candidates": _cands([math.nan])}, "finite values"),
    ({"paper": -1.0}, "paper must be a positive"),
    ({"n_nearest": 0}, "n_nearest must be an integer >= 1"),
    ({"decimals": -1}, "decimals must be an integer >= 0"),
])
def test_match_bound_rejects_bad_input(kwargs, match):
    args = {"gain": "K", "paper": 0.1, "candidates": _cands([0.1])} | kwargs
    with pytest.raises(ValueError, match=match):
        match_bound(**args)


def test_first_crossing():
    t = [0.0, 1.0, 2.0, 3.0]
    assert first_crossing(t, [np.nan, 0.0, 1.0, 0.0], 0.25) == pytest.approx(1.25, abs=1e-15)
    assert first_crossing(t, [np.nan, 0.0, 0.5, 1.0], 0.5) == 2.0      # reached on a sample
    assert first_crossing(t, [1.0, 0.0, 0.5, 1.0], 0.5) == pytest.approx(0.5, abs=1e-15)
    assert math.isnan(first_crossing(t, [np.nan, 0.0, 0.1, 0.2], 0.5))
    with pytest.raises(ValueError, match="vectors of one length"):
        first_crossing(t, [0.0, 1.0], 0.5)


def test_horizons_must_fit_the_grids():
    with pytest.raises(ValueError, match=r"horizons \(0.5 s\) must be a multiple of peak_bin"):
        time_domain_bound_search((0.5,))
    with pytest.raises(ValueError, match="horizons must be a positive"):
        time_domain_bound_search((-1.0,))


def test_search_signals_cover_sec_vi():
    sig = search_signals()
    assert [s.label for s in sig][:3] == ["LF", "HF", "mixed, ρ_p = 0.1"]
    assert [s.stationary for s in sig] == [True] * 7 + [False] * 2
    # paper eq. (58): the run is [0, 2T + rho_t T) with T = 500
    assert [s.run for s in sig[-2:]] == [1050.0, 1250.0]


# -- the search on the aircraft ------------------------------------------------------------------

def test_counts_of_what_was_tried(search):
    assert isinstance(search, TimeDomainBoundSearch)
    # round horizons inside each run: LF, HF 12 (to 1500 s); mixed 10 (to 500 s); piecewise 11
    # (to 1000 s); 5 quantities each, and 2 steady-state limits under each of the 7 sums of sines
    n = (2 * 12 + 5 * 10 + 2 * 11) * 5 + 7 * 2
    assert all(b.n_candidates == n for b in search.bounds)
    assert search.tried == {"gains": 4, "signals": 9, "quantities": 5,
                            "round_horizons_s": list(ROUND_HORIZONS), "candidates_per_bound": n}
    assert len(search.crossings) == 4 * 9 * 2


def test_steady_state_ratio_is_the_closed_form(search):
    d = hf_disturbance()
    cl = aircraft().closed_loop(paper_gains()["K_f3"])
    ref = _closed_form_ratio(cl, d)
    assert_allclose(_candidate(search, "K_f3", "HF", L2_RATIO, STEADY_STATE).value, ref, rtol=1e-9)
    assert_allclose(_candidate(search, "K_f3", "HF", ENERGY_RATIO, STEADY_STATE).value, ref**2, rtol=1e-9)


def test_running_ratio_agrees_with_the_stationary_chapter(search):
    # the stationary chapter runs fdsc.simulate (full arrays, trapezoid rule); the search streams
    # (Simpson's rule) on the same exact samples. The two quadratures differ by O(dt²) end terms
    # over 500 s: measured 1.5e-9 relative, so 1e-8 leaves room without hiding a wrong sample.
    # PassC-HF is K_f3; FDSC with our Q's is not needed for it.
    ref = stationary_runs("HF", with_our_q=False).l2_final["PassC-HF"]
    ours = _candidate(search, "K_f3", "HF", L2_RATIO, 500.0).value
    assert_allclose(ours, ref, rtol=1e-8)


def test_peak_gain_agrees_with_a_full_trace():
    # independent method: fdsc.simulate keeps every sample; max over the samples in [0, T)
    s = time_domain_bound_search((1.0, 2.0))
    t = time_grid(2.0, STATIONARY_DT)
    sim = simulate(aircraft().closed_loop(paper_gains()["K_e"]), hf_disturbance(), t)
    inside = t < 2.0 - STATIONARY_DT / 2
    ref = np.abs(sim.z[inside]).max(axis=0) / np.abs(sim.d[inside]).max()
    names = aircraft().names["output_names"]
    ours = [_candidate(s, "K_e", "HF", f"peak gain of {output_label(n)}", 2.0).value for n in names]
    assert_allclose(ours, ref, rtol=1e-10)


def test_the_findings(search):
    bound = {k: v["bound"] for k, v in paper_data("controllers").items() if k in GAIN_ORDER}
    assert [b.paper for b in search.bounds] == [bound[g] for g in GAIN_ORDER]
    # the L2 ratio at T = 100 s under the in-band signal reproduces K_f1's and K_f3's bounds (the
    # piecewise signals equal HF on [0, 500), hence the same number twice more)
    assert [(h.signal, h.quantity, h.horizon) for h in search["K_f1"].hits] == [("LF", L2_RATIO, 100.0)]
    assert [(h.signal, h.horizon) for h in search["K_f3"].hits] == [
        ("HF", 100.0), ("piecewise, ρ_t = 0.1", 100.0), ("piecewise, ρ_t = 0.5", 100.0)]
    assert [len(b.hit_values) for b in search.bounds] == [1, 0, 1, 0]   # K_f3's three hits: one number
    # about one hit each was to be expected by chance among that many candidates near the value
    assert [round(b.chance_hits, 1) for b in search.bounds] == [1.2, 0.1, 1.0, 0.0]
    for b in search.bounds:
        assert all(abs(h.value - b.paper) <= 0.5e-4 for h in b.hits)
        assert b.best == min((c for c in search.candidates if c.gain == b.gain),
                             key=lambda c: abs(c.value - b.paper))
    # for information: the running L2 ratio of K_f3 under HF sweeps through 0.1714 just before 100 s
    cross = {(c["gain"], c["signal"], c["quantity"]): c["t"] for c in search.crossing_rows()}
    assert 99.0 < cross[("K_f3", "HF", L2_RATIO)] < 100.0


def test_chance_hits_against_a_uniform_spread():
    # 2,000 values spread evenly over ±1 % of 0.25 (a window 50 printed units wide): 40 per unit,
    # so 40 hits to expect by chance, and a count of the actual hits agrees
    values = 0.25 * (1 + np.linspace(-0.01, 0.01, 2001)[:-1])
    cands = [TimeDomainCandidate("K", "HF", L2_RATIO, float(k), float(v)) for k, v in enumerate(values)]
    m = match_bound("K", 0.25, cands)
    assert m.chance_hits == pytest.approx(40.0, rel=1e-3)
    # (a window of the printed digits holds 40 or 41 evenly spaced values, by where its ends fall)
    assert abs(len(m.hits) - m.chance_hits) <= 1.5


def test_readings_of_one_bound(search):
    r = search.readings("K_f3")
    assert r["searched"] == search["K_f3"].n_candidates and r["within_1pct"] == search["K_f3"].n_within_close
    assert r["hits"][0] == {"signal": "HF", "quantity": L2_RATIO, "horizon_s": 100.0,
                            "value": search["K_f3"].hits[0].value}
    assert r["nearest"] == search["K_f3"].best.to_dict()
    assert 99.0 < r["first_crossings_s"]["L2 ratio, HF"] < 100.0
    text = json.dumps(r, allow_nan=False)      # finite, plain values only
    assert json.loads(text) == r
    settings = search.settings()
    assert settings["horizons_s"] == list(ROUND_HORIZONS) and len(settings["signals"]) == 9


def test_candidates_in_words():
    c = TimeDomainCandidate("K", "piecewise, ρ_t = 0.5", "peak gain of 2δ_E", 1000.0, 0.448907)
    assert c.describe() == ("peak gain of 2δ_E under the piecewise disturbance (ρ_t = 0.5) over "
                            "T = 1,000 s (0.44891)")
    s = TimeDomainCandidate("K", "HF", L2_RATIO, STEADY_STATE, 0.2)
    assert s.describe(value=False) == "L2 ratio under the HF disturbance in steady state"
