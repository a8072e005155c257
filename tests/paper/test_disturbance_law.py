"""fdsc.paper.pays.disturbance_law: the non-stationary draws, the choices on the training half
(the law under its switching limit, the reference family), the summary's fields, the runs of one
draw, and the stored study against what the code recomputes."""

import math

import numpy as np
import pytest

import fdsc
from fdsc.paper.pays import disturbance_law as dl
from fdsc.paper.pays import disturbance_law_draws as dd
from fdsc.paper.pays import disturbance_law_runs as runs
from fdsc.paper.pays.fixed_designs import FixedSet
from fdsc.paper.pays.generic_example import generic_example
from fdsc.paper.reproduced.paper_cases import aircraft_example


@pytest.mark.parametrize("example", [aircraft_example, generic_example])
def test_the_draws_follow_the_stated_distribution(example):
    ex = example()
    rng = np.random.default_rng(5)
    for _ in range(40):
        dr = dd.draw(ex, rng)
        k = len(dr.dominant)
        assert 6 <= k <= 10 and len(dr.d.parts) == k == len(dr.noise)
        lengths = np.diff(dr.d.breaks)
        assert np.all(lengths >= 20.0 - 1e-9)
        np.testing.assert_allclose(dr.d.breaks * 100, np.round(dr.d.breaks * 100), atol=1e-6)
        assert dr.horizon >= dr.d.breaks[-1] and dr.horizon - dr.d.breaks[-1] < dd.DECIDE_EVERY
        for part, dom, noise in zip(dr.d.parts, dr.dominant, dr.noise, strict=True):
            assert part.power() == pytest.approx(1.0, rel=1e-12)
            share = part.dominance(ex.bands[dom])
            assert 0.8 - 1e-12 <= share <= 1.0
            assert part.frequencies.size == 2 * (dd.NOISE_TONES if noise else 3)
        assert dr.changes == sum(a != b for a, b in zip(dr.dominant[:-1], dr.dominant[1:], strict=True))


def test_the_segments_are_mixed_as_stated():
    ex = aircraft_example()
    rng = np.random.default_rng(6)
    doms, noises = [], []
    for _ in range(150):
        dr = dd.draw(ex, rng)
        doms += dr.dominant
        noises += dr.noise
    assert abs(np.mean([d == "LF" for d in doms]) - 0.5) < 0.06
    assert abs(np.mean(noises) - dd.NOISE_SHARE) < 0.06


def _fs(chosen="B"):
    return FixedSet("aircraft", 6, 1, 3, ("A", "B"), {}, {"A": "tuned", "B": "tuned"}, {},
                    {"A": 1.0, "B": 0.5},
                    chosen, [], {}, {}, {}, {}, None)


def _fake(index, fixed, law_runs, ref, changes=2):
    return {"index": index, "horizon": 100.0, "changes": changes, "segments": 3, "fixed": fixed,
            "fdsc": {"FDSC": (3.0, 100, False)}, "oracle": 1.0, "ideal": 2.0,
            "reference": {f: ref for f in runs.REFERENCE_FAMILIES}, "runs": law_runs, "input_energy": 1.0}


def test_the_law_is_chosen_on_the_training_half_under_its_switching_limit(monkeypatch):
    # x is the cheapest on the training half but switches 5 times per change; y is chosen. The
    # test half says the opposite of the training half, which must not change the choice.
    x, y, z = (runs.settings()[k] for k in (0, 1, 2))
    from fdsc.paper.pays import disturbance_law_study

    monkeypatch.setattr(disturbance_law_study, "settings", lambda: [x, y, z])
    train = [_fake(i, {"A": 2.0, "B": 1.0}, {x: (0.5, 10, False, 1.0), y: (0.8, 2, False, 0.5),
                                             z: (0.9, 0, False, 0.0)}, 0.7) for i in range(3)]
    test = [_fake(i, {"A": 1.0, "B": 2.0}, {x: (0.1, 1, False, 1.0), y: (2.0, 6, False, 3.0),
                                            z: (1.0, 0, False, 0.0)}, 1.6) for i in range(3, 6)]
    st = dl.choose("aircraft", train + test, 1, _fs())
    assert st.law == y and st.fixed_in_advance == "B"
    np.testing.assert_allclose(st.ratio(), 1.0)            # 2.0 / 2.0 on the test half
    assert st.switches_per_change() == 3.0
    np.testing.assert_allclose(st.reference_ratio(), 0.8)
    np.testing.assert_allclose(st.control_steps(), 3.0)
    np.testing.assert_allclose(st.fdsc_ratio("FDSC"), 1.5)
    # the share of the reference's log-gain: ln(1) / ln(0.8) = 0
    np.testing.assert_allclose(st.share(), 0.0, atol=1e-12)
    assert st.best_of("", constrained=False) == x


def test_no_reference_gain_means_no_share():
    x = runs.settings()[0]
    flat = [_fake(i, {"A": 1.0, "B": 1.0}, {k: (1.0, 0, False, 0.0) for k in runs.settings()}, 1.0)
            for i in range(4)]
    st = dl.Study("aircraft", 1, tuple(flat), _fs(), x, runs.REFERENCE_FAMILIES[0])
    assert np.all(np.isnan(st.share()))


def test_the_targets_are_judged_on_the_test_draws():
    x = runs.settings()[0]
    good = [_fake(i, {"A": 1.0, "B": 1.0}, {x: (0.8, 1, False, 0.1)}, 0.7) for i in range(8)]
    st = dl.Study("generic", 1, tuple(good), _fs(), x, runs.REFERENCE_FAMILIES[0])
    assert st.meets()["met"] and st.meets()["got"]["median"] == pytest.approx(0.8)
    bad = [_fake(i, {"A": 1.0, "B": 1.0}, {x: (0.95, 1, False, 0.1)}, 0.7) for i in range(8)]
    assert not dl.Study("generic", 1, tuple(bad), _fs(), x, runs.REFERENCE_FAMILIES[0]).meets()["met"]


def test_the_test_draws_need_only_the_settings_chosen_on_the_training_half(monkeypatch):
    # the study runs every setting on its training draws and, on its test draws, only those
    # scored_settings names: the law choose() picks (first), then each family's best
    from fdsc.paper.pays import disturbance_law_study

    x, y, z = (runs.settings()[k] for k in (0, 1, 2))
    monkeypatch.setattr(disturbance_law_study, "settings", lambda: [x, y, z])
    train = [_fake(i, {"A": 2.0, "B": 1.0}, {x: (0.5, 10, False, 1.0), y: (0.8, 2, False, 0.5),
                                             z: (0.9, 0, False, 0.0)}, 0.7) for i in range(3)]
    keys = disturbance_law_study.scored_settings("aircraft", train, 1, _fs())
    test = [_fake(i, {"A": 1.0, "B": 2.0}, {k: (1.0, 0, False, 0.0) for k in keys}, 1.6) for i in range(3, 6)]
    st = dl.choose("aircraft", train + test, 1, _fs())
    # x is cheapest but over the switching limit: y is the law and the gains family's best
    assert keys == (y,) and st.law == keys[0]
    assert st.best_of("gains/cost") in keys and st.law == st.best_of("") == y


@pytest.fixture(scope="module")
def fs():
    full = dl.load_full()
    if full is None:
        pytest.skip("the full study is not in this checkout")
    return dl.stored_fixed_set(full, "generic")


def test_a_draw_is_the_same_on_two_runs_its_baselines_are_consistent_and_a_part_runs_alone(fs):
    a = runs.draw_result("generic", 4, dd.SEED, fs)
    b = runs.draw_result("generic", 4, dd.SEED, fs)
    assert a == b
    assert set(a["fixed"]) == set(fs.names) and set(a["runs"]) == set(runs.settings())
    names = runs.candidates("generic")[0]
    # the open loop (a resonance of time constant ~50 s) is a fixed baseline, not a candidate
    assert "open loop" not in names and "open loop" in a["fixed"]
    air = runs.candidates("aircraft")[0]
    assert "open loop" in air and "PassC-HF" not in air        # PassC-HF: a pole at −0.0165 /s
    assert all(math.isfinite(e) and e > 0 for e, _s, _d, _j in a["runs"].values())
    assert not any(d for _e, _s, d, _j in a["runs"].values())
    # a fixed controller held by the law through copies, from rest, is its fixed run
    assert set(a["reference"]) == set(runs.REFERENCE_FAMILIES)
    # the switches the law makes move u; a law that does not switch moves it not at all
    assert all(j == 0.0 for _e, s, _d, j in a["runs"].values() if s == 0)
    assert any(j > 0 for _e, s, _d, j in a["runs"].values() if s > 0)
    # a test draw runs only the settings asked, and gives them the same numbers as the whole draw
    every = a
    keys = runs.settings()[5:7]
    part = runs.draw_result("generic", 4, dd.SEED, fs, keys, keys[:1])
    assert set(part["runs"]) == set(keys)
    assert part["runs"][keys[0]] == every["runs"][keys[0]]
    e, s, d, step = part["runs"][keys[1]]
    assert (e, s, d) == every["runs"][keys[1]][:3] and math.isnan(step)      # its step not measured
    assert part["fixed"] == every["fixed"] and part["ideal"] == every["ideal"]
    with pytest.raises(ValueError, match="keys must be settings"):
        runs.draw_result("generic", 4, dd.SEED, fs, ["gains/cost/copies/9/9"])
    with pytest.raises(ValueError, match="steps must be among keys"):
        runs.draw_result("generic", 4, dd.SEED, fs, keys[:1], keys[1:])


def test_a_law_held_on_one_controller_of_a_pair_is_that_controllers_fixed_run(fs):
    key = "tuned filtered pair/cost/copies/0.2/1"
    sup, _names, _lam, _h = runs.law_supervisor("generic", key, fs)
    _ex, dr = dd.seeded_draw("generic", 0)
    prep = sup.prepare(dr.d, dr.horizon)
    for i, c in enumerate(fs.pairs["tuned filtered"]):
        assert prep.fixed(i) == pytest.approx(prep.energy_of(c), rel=1e-9)


def test_the_record_entry_carries_every_field():
    full = dl.load_full()
    if full is None:
        pytest.skip("the full study is not in this checkout")
    (law,) = dl.record_part().entries
    assert law["id"] == "supervisor"
    for example in ("aircraft", "generic"):
        s = law["recomputed"][example]
        assert s["law"] == full[example]["law"] and s["fixed_in_advance"] == full[example]["fixed_in_advance"]
        assert 0.0 <= s["win_rate_vs_fixed_in_advance"] <= 1.0
        # the build recomputes the chosen law on the first stored test draws: the same ratios
        assert s["recheck"]["draws"] == dl.N_RECHECK_LAW and s["recheck"]["largest_difference"] < 1e-6
        assert len(s["rho_t_ratio_vs_fixed_in_advance"]) == (11 if example == "aircraft" else 21)


def test_a_stored_choice_matches_the_stored_study():
    from fdsc.paper.shared.fixed_choice import stored_choice

    full = dl.load_full()
    if full is None:
        pytest.skip("the full study is not in this checkout")
    choice = stored_choice()
    for e in ("aircraft", "generic"):
        assert choice[e]["name"] == full[e]["fixed_in_advance"]
        assert choice[e]["matrices"] == full[e]["fixed_controllers"][choice[e]["name"]]["matrices"]
    assert choice["commit"] == full["commit"] and choice["n"] == full["n"] == dl.N_FULL


@pytest.mark.parametrize("example", ["aircraft", "generic"])
def test_the_code_recomputes_a_stored_test_draw(example):
    # the stored study's first test draw, recomputed now from its stored controllers: every fixed
    # controller's ratio and the chosen law's, to 1e-6 (the engines are exact; what differs
    # between machines is rounding)
    full = dl.load_full()
    if full is None:
        pytest.skip("the full study is not in this checkout")
    r = full[example]
    fs = dl.stored_fixed_set(full, example)
    i = r["test_indices"][0]
    d = runs.draw_result(example, i, full["seed"], fs)
    ref = d["fixed"][fs.chosen]
    law = d["runs"][dl.law_key(r["law"])][0] / ref
    assert law == pytest.approx(r["ratio_vs_fixed_in_advance"][0], rel=1e-6)
    for name, ratios in r["fixed_ratio"].items():
        assert d["fixed"][name] / ref == pytest.approx(ratios[0], rel=1e-6), name
    for fam, ratios in r["reference_ratio"].items():
        assert d["reference"][fam] / ref == pytest.approx(ratios[0], rel=1e-6), fam


def test_a_draw_on_sampled_measurements_reports_every_variant(monkeypatch, fs):
    from fdsc.paper.pays import disturbance_law_robust as rb

    ex = generic_example()
    full = dd.draw(ex, np.random.default_rng([dd.SEED, 0]))
    short = dd.Draw(fdsc.Piecewise(full.d.breaks[:3], full.d.parts[:2]), 30.0, full.dominant[:2],
                    full.noise[:2])
    monkeypatch.setattr(rb, "seeded_draw", lambda example, index, seed=dd.SEED: (ex, short))
    names, gains = runs.candidates("generic")
    cert = fdsc.min_switching([ex.plant.closed_loop(K) for K in gains], rates=(316.2,))
    monkeypatch.setattr(rb, "min_switching_certificate", lambda example: cert)
    r = rb.measured_result("generic", 0, "tuned filtered pair/cost/copies/0.2/0.3", fs)
    assert set(r) == {"exact", *rb.MEASURED_VARIANTS, "min_switching"}
    assert not any(v["diverged"] for v in ("exact", "sampled") for v in [r[v]])
    assert r["sampled"]["ratio"] == pytest.approx(r["exact"]["ratio"], rel=0.05)
    assert r["A+10%"]["ratio"] != r["sampled"]["ratio"]


def test_the_build_time_recheck_of_the_stored_study_catches_a_changed_number():
    import copy

    full = dl.load_full()
    if full is None:
        pytest.skip("the full study is not in this checkout")
    ok = dl.recheck_stored(full, "generic", 2)
    assert ok["draws"] == 2 and ok["controllers"] == len(full["generic"]["fixed_ratio"])
    assert ok["largest_difference"] < 1e-6
    bad = copy.deepcopy(full)
    name = next(iter(bad["generic"]["fixed_ratio"]))
    bad["generic"]["fixed_ratio"][name][1] *= 1.01
    assert dl.recheck_stored(bad, "generic", 2)["largest_difference"] == pytest.approx(1 - 1 / 1.01, rel=1e-3)
    with pytest.raises(ValueError, match="k must be at most"):
        dl.recheck_stored(full, "generic", len(full["generic"]["test_indices"]) + 1)
