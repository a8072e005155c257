"""The ladder under measurement noise, delay and model error (fdsc.paper.pays.information) and the
adaptive-regulation rung (fdsc.paper.pays.adaptive_rung): their stored results against the stored
study they were computed on, the bound, and a recomputation of their fixed parts."""

import math

import numpy as np
import pytest

from fdsc.paper.pays import adaptive_rung as ar
from fdsc.paper.pays import information as inf

EXAMPLES = ("aircraft", "generic")


def _stored(load, what):
    res = load()
    if res is None:
        pytest.skip(f"the stored {what} is not in this checkout")
    return res


@pytest.fixture(scope="module")
def info(full):
    return _stored(inf.load_information, "study under noise")


@pytest.fixture(scope="module")
def adapt(full):
    return _stored(ar.load_adaptive, "adaptive rung")


def test_the_noise_study_was_computed_on_the_stored_study(info, full):
    assert info["stored_study"] == {"commit": full["commit"], "fingerprint": full["fingerprint"]}
    assert info["levels"] == [inf._key(v) for v in inf.LEVELS]
    for e in EXAMPLES:
        assert info[e]["test_indices"] == full[e]["test_indices"][:info["n_test"]]


@pytest.mark.parametrize("e", EXAMPLES)
def test_no_rung_passes_the_limit_and_noise_only_costs(info, full, e):
    pos = {i: k for k, i in enumerate(full[e]["test_indices"])}
    for key in info["levels"]:
        row = info[e][key]
        lim = np.asarray(row["energies"]["limit"])
        for rung, v in row["energies"].items():
            assert len(v) == info["n_test"]
            assert np.all(np.asarray(v) >= lim * (1 - 1e-9)), (key, rung)
        # the stored x-only controller does not read ŵ: the noise does not reach it
        assert row["energies"]["best fixed (x)"] == [full[e]["fixed_energy"][row["best_x"]][pos[i]]
                                                     for i in info[e]["test_indices"]]
        # a fixed controller reading noisy ŵ has at least its exact energy on d
        if row["best"] in full[e]["fixed_energy"]:
            clean = np.array([full[e]["fixed_energy"][row["best"]][pos[i]] for i in info[e]["test_indices"]])
            assert np.all(np.asarray(row["energies"]["best fixed (x, ŵ)"]) >= clean * (1 - 1e-12))
        # the chosen controller has the least expected power of those recorded
        p = row["expected_power"]
        assert p[row["best"]] <= p["optimal LTI in noise"] * (1 + 1e-12)


def test_the_noise_raises_the_best_fixed_controllers_expected_power(info):
    for e in EXAMPLES:
        powers = [info[e][k]["expected_power"][info[e][k]["best"]] for k in info["levels"]]
        assert all(a <= b * (1 + 1e-9) for a, b in zip(powers, powers[1:], strict=False))


def test_the_fixed_part_recomputes_at_20_db(info, full):
    # the redesign, the choice, and the chosen controller's energy (exact plus the noise's
    # expected cost) on the first stored draw of the generic example
    row = info["generic"]["20 dB"]
    dz = inf.level_design("generic", 20.0, full)
    assert dz["best"] == row["best"]
    # the redesign's least squares rounds differently with other BLAS threading (a fresh build saw
    # 3.9e-7 relative): its value and what it achieves are checked to 1e-4, not to the rounding
    assert dz["optimal"].power == pytest.approx(row["expected_power"]["optimal LTI in noise"], rel=1e-4)
    i = info["generic"]["test_indices"][0]
    clean = (inf._fixed_energy("generic", i, info["seed"], dz["optimal"].controller)
             if dz["best"] == "optimal LTI in noise"
             else full["generic"]["fixed_energy"][dz["best"]][full["generic"]["test_indices"].index(i)])
    want = clean + info["generic"]["horizons"][0] * dz["noise"][dz["best"]]
    assert row["energies"]["best fixed (x, ŵ)"][0] == pytest.approx(want, rel=1e-4)


def test_the_summaries_read_the_stored_energies(info):
    for e in EXAMPLES:
        rows = inf.summary(info, e)
        assert [r["level"] for r in rows] == info["levels"]
        for r in rows:
            assert r[r["reference"]][:3] == (1.0, 1.0, 1.0)
            row = info[e][r["level"]]
            ratio = np.asarray(row["energies"]["predictive (confident)"]) / np.asarray(
                row["energies"][r["reference"]])
            assert r["predictive (confident)"][0] == pytest.approx(float(np.median(ratio)), rel=1e-12)
        assert {r["scale"] for r in inf.model_error_summary(info, e)} == set(inf.SCALES)


@pytest.mark.parametrize("e", EXAMPLES)
def test_the_laws_setting_is_the_best_on_its_training_draws_and_not_predicting_is_the_reference(info, e):
    assert info["windows"] == list(inf.WINDOWS) and info["fallback"] == inf.FALLBACK
    for key in info["levels"]:
        row = info[e][key]
        assert set(row["train_scores"]) == {f"{w:g}" for w in inf.WINDOWS} | {inf.FALLBACK}
        best = min(row["train_scores"], key=row["train_scores"].get)
        assert row["window"] == (inf.FALLBACK if best == inf.FALLBACK else float(best))
        # the controller the law runs when it does not predict is the reference of the summary
        assert row["fallback"] == inf.reference_name(row)
        (r,) = [r for r in inf.summary(info, e) if r["level"] == key]
        assert r["reference"] == ("best fixed (x, ŵ)" if row["fallback"] == row["best"] else "best fixed (x)")
        if row["window"] == inf.FALLBACK:
            assert row["energies"]["predictive (confident)"] == row["energies"][r["reference"]]
            assert r["predictive (confident)"][:3] == (1.0, 1.0, 1.0)


def test_the_reference_is_the_controller_of_least_expected_power():
    row = {"best": "a", "best_x": "b", "expected_power": {"a": 2.0, "b": 1.0}}
    assert inf.reference_name(row) == "b"
    assert inf.reference_name(row | {"expected_power": {"a": 1.0, "b": 1.0}}) == "a"   # a tie reads ŵ


def test_the_adaptive_rung_chose_its_setting_on_training_draws(adapt, full):
    assert adapt["stored_study"] == {"commit": full["commit"], "fingerprint": full["fingerprint"]}
    for e in EXAMPLES:
        r = adapt[e]
        best = min(r["train_scores"], key=r["train_scores"].get)
        assert best == "/".join(f"{v:g}" for v in r["setting"])
        n = len(r["test_indices"])
        assert r["reference_energies"] == full[e]["ladder"]["energies"]["best fixed (x, ŵ)"][:n]
        assert all(math.isfinite(x) for x in r["energies"])
        assert np.all(np.asarray(r["energies"]) >= np.asarray(r["limit_energies"]) * (1 - 1e-9))
        s = ar.summary(adapt, e)
        assert s["limit"][0] < 1.0 and set(s) == {"adaptive", "predictive", "limit"}


def test_the_adaptive_rung_under_noise_chose_its_regularization_on_training_draws(adapt, full):
    # its taps and memory are the exact estimate's, its regularization the best of the grid's on
    # the training draws with the noise; the reference is the best fixed (x, ŵ) at that level
    if "noise" not in adapt["aircraft"]:
        pytest.skip("the stored adaptive rung predates its run under noise")
    for e in EXAMPLES:
        r, nz = adapt[e], adapt[e]["noise"]
        assert nz["setting"][:2] == r["setting"][:2]
        assert {float(k.split("/")[2]) for k in nz["train_scores"]} == {g[2] for g in ar.GRID}
        best = min(nz["train_scores"], key=nz["train_scores"].get)
        assert best == "/".join(f"{v:g}" for v in nz["setting"])
        n = len(r["test_indices"])
        assert len(nz["energies"]) == len(nz["reference_energies"]) == len(nz["horizons"]) == n
        # no causal law passes the non-causal limit, noise or not
        assert np.all(np.asarray(nz["energies"]) >= np.asarray(r["limit_energies"]))
        med, lo, hi, wins = ar.noise_summary(adapt, e)
        assert lo <= med <= hi and 0.0 <= wins <= 1.0


def test_the_adaptive_laws_noisy_energy_recomputes_on_a_stored_draw(adapt, full):
    if "noise" not in adapt["generic"]:
        pytest.skip("the stored adaptive rung predates its run under noise")
    nz = adapt["generic"]["noise"]
    dz = inf.level_design("generic", adapt["noise_level"], full)
    i = adapt["generic"]["test_indices"][0]
    e = ar.adaptive_energy("generic", i, full["seed"], tuple(nz["setting"]), dz["optimal"].controller,
                           nz["variance"], nz["base_noise_power"])
    # the base is redesigned here (an H2 design and a reduction, whose rounding differs between hosts
    # and BLAS threads), as the optimal controller's energies above: agreement to 1e-4, not to the last digits
    assert e == pytest.approx(nz["energies"][0], rel=1e-4)


def test_the_recheck_of_a_level_where_the_law_does_not_predict_recomputes_the_reference(info, full):
    # a copy of the stored study with the law set not to predict at 20 dB on the generic example:
    # the recheck then recomputes the reference controller's energy, which the stored row holds
    import copy

    bad = copy.deepcopy(info)
    row = bad["generic"]["20 dB"]
    row["window"] = inf.FALLBACK
    ref = "best fixed (x, ŵ)" if inf.reference_name(row) == row["best"] else "best fixed (x)"
    out = inf.recheck(bad, full, "generic", "20 dB", 0)
    assert out["law"][1] == pytest.approx(row["energies"][ref][0], rel=1e-6)
    assert out["fixed"][1] == pytest.approx(out["fixed"][0], rel=1e-6)
