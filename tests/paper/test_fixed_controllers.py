"""fdsc.paper.pays.fixed_controllers: every fixed controller of the study, the choice in advance on
the training half, the fronts and their checks, and the stored choice that Parts I and II use."""

import math

import numpy as np
import pytest

import fdsc
from fdsc.paper.pays import fixed_controllers as fc
from fdsc.paper.pays.disturbance_law_draws import SEED, _example
from fdsc.paper.shared.fixed_choice import fixed_in_advance, stored_choice


@pytest.fixture(scope="module", params=["aircraft", "generic"])
def fs(request):
    return fc.fixed_set(request.param, fc.N_RECORD, SEED)


def test_every_family_is_there_and_the_choice_is_the_least_training_score(fs):
    assert set(fs.family.values()) == set(fc.FAMILIES)
    assert sum(f == "static front" for f in fs.family.values()) >= fc.FRONT_POINTS - 1
    assert fs.chosen == min(fs.names, key=lambda n: fs.train_score[n])
    # every controller's loop is stable and its score finite
    for name, c in fs.controllers.items():
        assert fdsc.as_controller(c, _example(fs.example).plant)
        assert math.isfinite(fs.train_score[name]) or name == "open loop", name


def test_the_tuned_designs_only_improve_on_their_starts_and_keep_their_cap(fs):
    for name, res in fs.tuning.items():
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


def test_the_record_part_carries_the_fronts_and_the_choice():
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
        assert fx["chosen"] in fx["controllers"]


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


def test_the_static_front_checks_name_what_beats_a_point():
    _front, checks = fc.static_front("generic")
    assert len(checks) == fc.FRONT_POINTS
    for c in checks:
        if c["dominated"]:
            assert c["by"][0] < c["hf"] and c["by"][1] <= c["lf"] * (1 + 1e-9)
    assert np.all([c["dominated"] in (True, False, None) for c in checks])
