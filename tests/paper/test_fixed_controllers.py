"""fdsc.paper.pays.fixed_controllers: every fixed controller of the study, the choice in advance on
the training half, the fronts and their checks, and the stored choice that Parts I and II use."""

import math

import numpy as np
import pytest

import fdsc
from fdsc.paper.pays import fixed_controllers as fc
from fdsc.paper.pays.disturbance_law import stored_fixed_set
from fdsc.paper.pays.disturbance_law_draws import SEED, _example, segment_class
from fdsc.paper.pays.fixed_designs import OPTIMAL_LTI, best_found
from fdsc.paper.shared.fixed_choice import fixed_in_advance, stored_choice


@pytest.fixture(scope="module", params=["aircraft", "generic"])
def fs(request, full):
    """The stored study's fixed controllers (their design is the full study's: the designs
    themselves are tested by the slow tests below)."""
    return stored_fixed_set(full, request.param)


@pytest.fixture(scope="module", params=["aircraft", "generic"])
def designed(request):
    return fc.fixed_set(request.param, fc.N_RECORD, SEED)


def test_every_family_is_there_and_the_choice_is_the_least_training_score(fs):
    assert set(fs.family.values()) == set(fc.FAMILIES)
    assert sum(f == "static front" for f in fs.family.values()) >= fc.FRONT_POINTS - 1
    assert fs.chosen == min(fs.names, key=lambda n: fs.train_score[n])
    assert fs.chosen_found == best_found(fs.names, fs.family, fs.controllers, fs.train_score)
    assert fs.family[fs.chosen_found] != "optimal LTI" and fs.controllers[fs.chosen_found].reads_estimate
    # every controller's loop is stable and its score finite
    for name, c in fs.controllers.items():
        assert fdsc.as_controller(c, _example(fs.example).plant)
        assert math.isfinite(fs.train_score[name]) or name == "open loop", name


def test_the_optimal_lti_controller_has_the_least_expected_power(fs):
    # the Wiener–Hopf optimum over every causal LTI controller reading x and ŵ: no other fixed
    # controller reading them has less expected power under the class (to its 0.5 % convergence),
    # and each stored expected power is what the stored matrices give
    plant = _example(fs.example).plant
    cls = segment_class(fs.example)
    best = fs.info[OPTIMAL_LTI]["expected_power"]
    for name, c in fs.controllers.items():
        if c.reads_estimate and math.isfinite(fs.info[name]["expected_power"]):
            assert fs.info[name]["expected_power"] >= best * (1 - 5e-3), name
    for name in (OPTIMAL_LTI, fs.chosen_found):
        assert fdsc.expected_power(plant.closed_loop(fs.controllers[name]), cls) == pytest.approx(
            fs.info[name]["expected_power"], rel=1e-9)


@pytest.mark.slow
def test_the_tuned_designs_only_improve_on_their_starts_and_keep_their_cap(designed):
    fs = designed
    assert set(fs.family.values()) == set(fc.FAMILIES) and fs.chosen == min(fs.names, key=fs.train_score.get)
    for name, res in fs.tuning.items():
        if name == OPTIMAL_LTI:
            assert res.converged and res.wiener <= res.power
            continue
        assert res.objective <= min(res.start_objectives) + 1e-12, name
        if res.hinf_cap is not None:
            assert res.hinf <= res.hinf_cap * 1.05, name
    # a filtered search starts from the tuned gain: it does at least as well on the tuning draws
    assert fs.tuning["tuned filtered"].objective <= fs.tuning["tuned"].objective + 1e-12


def test_the_pairs_are_designed_for_each_type_of_segment(fs):
    plant = _example(fs.example).plant
    for fam, pair in fs.pairs.items():
        assert len(pair) == 2, fam
        for c in pair:
            assert plant.closed_loop(c).is_hurwitz(), c.name


def test_the_record_part_carries_the_fronts_and_the_choice(full):
    part = fc.record_part()
    ids = [e["id"] for e in part.entries]
    assert ids == ["pareto_front", "dynamic_front", "fixed_controllers"]
    front = part.entries[0]["recomputed"]
    for example in ("aircraft", "generic"):
        pts = [p for p in front[example] if p["gamma_hf"] is not None]
        assert len(pts) >= fc.FRONT_POINTS - 1
        hf = [p["gamma_hf"] for p in pts]
        assert hf == sorted(hf, reverse=True)            # a looser LF bound never costs HF gain
        fx = part.entries[2]["recomputed"][example]
        assert fx["chosen"] in fx["controllers"] and fx["best_found"] in fx["controllers"]
        # the build's recheck of the stored study: peaks and powers from the stored matrices, and
        # every controller's energy on the first test draw by the engine and by closed forms
        rc = fx["recheck"]
        assert max(rc["peaks"].values()) < 1e-6
        assert rc["draws"]["largest_difference"] < 1e-6 and rc["draws"]["second_difference"] < 1e-6


def test_the_stored_choice_fits_each_plant_and_stabilizes_it():
    data = stored_choice()
    assert {"commit", "fingerprint", "n", "seed"} <= set(data)
    for example in ("aircraft", "generic"):
        name, c = fixed_in_advance(example)
        assert name == data[example]["name"] and c.n_states == data[example]["states"]
        assert _example(example).plant.closed_loop(c).is_hurwitz()


def test_a_bad_example_is_refused_by_name():
    with pytest.raises(ValueError, match="example"):
        fixed_in_advance("boat")


def test_the_static_front_checks_name_what_beats_a_point(full):
    checks = full["generic"]["front_checks"]
    assert len(checks) == fc.FRONT_POINTS
    for c in checks:
        if c["dominated"]:
            assert c["by"][0] < c["hf"] and c["by"][1] <= c["lf"] * (1 + 1e-9)
    assert np.all([c["dominated"] in (True, False, None) for c in checks])
