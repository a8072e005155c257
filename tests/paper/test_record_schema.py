"""The record's JSON Schema: valid itself, met by the real record, and strict where it must be."""

import copy
import json
from pathlib import Path

import jsonschema
import pytest
from jsonschema import Draft202012Validator

import fdsc.paper
from fdsc.paper.appendix.reproduction_report import record_schema
from fdsc.paper.record import reproduction_record
from fdsc.paper.shared.results import entry, to_jsonable
from fdsc.paper.shared.verdict import CLAIM_VERDICTS, VERDICTS

SCHEMA_FILE = Path(fdsc.paper.__file__).resolve().parent / "data" / "record.schema.json"
CONTROLLERS = ("PassC-EF", "PassC-LF", "PassC-HF", "FDSC", "FDSC (our Q)", "FDSC (candidate ẋ)")


@pytest.fixture(scope="module")
def validator():
    return Draft202012Validator(record_schema())


def _sweep(n):
    return {"dt": 0.001, "energy": {c: [1.0] * n for c in CONTROLLERS}, "input_energy": [2.0] * n,
            "switches": {"FDSC": [3] * n}, "units": {"horizon": "s"}}


def synthetic_record():
    """A small record that meets the schema: two entries, three figures, ten claims."""
    mixed = {"paper_figure": 7, "rho_p": [i / 40 for i in range(21)], "horizon": 500.0, **_sweep(21),
             "crossover": {"PassC-LF": 0.05, "PassC-EF": None, "tolerance": 0.001, "paper": 0.2},
             "passc_hf_scale": 0.0002}
    piecewise = {"paper_figure": 8, "rho_t": [i / 20 for i in range(11)], "T": 500.0, "rho_p_star": 0.1,
                 "horizon": [1000.0 + 50.0 * i for i in range(11)], **_sweep(11), "passc_hf_scale": 0.01}
    claims = [{"claim": f"claim {i}", "source": "Sec. IV, text on paper Fig. 7", "measure": "m",
               "value": [0.1, 0.2] if i % 2 else None, "verdict": CLAIM_VERDICTS[i % 3], "reason": "r"}
              for i in range(10)]
    return {"entries": [entry("K_f1", "Sec. IV", [[0.1048, 15.0897]], [[0.1049, 15.098]], "close", "n"),
                        entry("model", "Sec. IV", {"A_long": [[1.0]]}, {"A_long": [[1.0]]}, "input", "n")],
            "figures": {"sigma_max": {"paper_figure": 3, "omega": [1.0]}, "mixed_sweep": mixed,
                        "piecewise_sweep": piecewise},
            "claims": claims, "environment": {"python": "3.11"}}


def test_the_schema_is_a_valid_draft_2020_12_schema():
    schema = record_schema()
    Draft202012Validator.check_schema(schema)
    assert schema == json.loads(SCHEMA_FILE.read_text(encoding="utf-8"))
    assert schema["$schema"] == "https://json-schema.org/draft/2020-12/schema"
    assert schema["title"] and schema["description"]
    # the enums are the verdicts of the code, not a copy that could drift
    assert tuple(schema["$defs"]["entry_verdict"]["enum"]) == VERDICTS
    assert tuple(schema["$defs"]["claim_verdict"]["enum"]) == CLAIM_VERDICTS


def test_the_synthetic_record_is_valid(validator):
    validator.validate(synthetic_record())
    validator.validate(json.loads(json.dumps(synthetic_record())))


def _errors(validator, record):
    """Every violation, one line each ("where: what"), so that a failure lists them all."""
    def short(msg):            # a long instance is cut in the middle: the verdict is at the end
        return msg if len(msg) <= 300 else msg[:150] + " … " + msg[-140:]

    return "\n".join(short(f"{'/'.join(map(str, e.absolute_path)) or '(top)'}: {e.message}")
                     for e in validator.iter_errors(record))


@pytest.fixture(scope="module")
def real_record():
    return reproduction_record()


def test_the_real_record_meets_the_schema(validator, real_record):
    errors = _errors(validator, to_jsonable(real_record))
    assert not errors, f"the record breaks its schema:\n{errors}"


def test_the_record_written_by_the_cli_meets_the_schema(validator, real_record):
    # what `python -m fdsc reproduce` writes: the record through to_jsonable and JSON
    written = json.loads(json.dumps(to_jsonable(real_record), indent=1))
    errors = _errors(validator, written)
    assert not errors, f"the written record breaks its schema:\n{errors}"


def _without(path):
    def change(rec):
        *parents, last = path
        for key in parents:
            rec = rec[key]
        del rec[last]
    return change


def _set(path, value):
    def change(rec):
        *parents, last = path
        for key in parents:
            rec = rec[key]
        rec[last] = value
    return change


@pytest.mark.parametrize(("change", "message"), [
    (_without(("figures", "mixed_sweep")), "'mixed_sweep' is a required property"),
    (_without(("figures", "piecewise_sweep")), "'piecewise_sweep' is a required property"),
    (_without(("claims",)), "'claims' is a required property"),
    (_set(("claims", 3, "verdict"), "OK"), r"'OK' is not one of \['PASS', 'PARTLY', 'FAIL'\]"),
    (_without(("claims", 0, "measure")), "'measure' is a required property"),
    (_set(("claims",), [{"claim": "c", "source": "s", "measure": "m", "value": 1, "verdict": "PASS",
                         "reason": "r"}] * 9), "should be non-empty|is too short"),
    (_without(("entries", 1, "note")), "'note' is a required property"),
    (_set(("entries", 0, "verdict"), "ok"), "'ok' is not one of"),
    (_set(("figures", "mixed_sweep", "rho_p"), [0.0, 0.1, 0.2, 0.3, 0.4]), "is too short"),
    (_set(("figures", "piecewise_sweep", "rho_t"), [0.0, 0.5]), "is too short"),
    (_set(("figures", "mixed_sweep", "paper_figure"), 6), "7 was expected"),
    (_set(("figures", "sigma_max", "paper_figure"), 9), "9 is greater than the maximum of 8"),
    (_set(("figures", "mixed_sweep", "energy", "FDSC"), [1.0, "nan"]), "'nan' is not of type 'number'"),
    (_without(("figures", "mixed_sweep", "energy", "PassC-HF")), "'PassC-HF' is a required property"),
    (_without(("figures", "mixed_sweep", "crossover")), "'crossover' is a required property"),
    (_without(("figures", "piecewise_sweep", "rho_p_star")), "'rho_p_star' is a required property"),
])
def test_a_record_that_breaks_the_format_is_rejected(validator, change, message):
    bad = copy.deepcopy(synthetic_record())
    change(bad)
    with pytest.raises(jsonschema.ValidationError, match=message):
        validator.validate(bad)


def test_the_merged_entries_have_their_shape(validator):
    """A printed bound carries its readings; the comparator set names its members and counts."""
    record = synthetic_record()
    bound = entry("bound_f3", "Sec. IV", 0.1714, 1.605, "not reproducible", "n")
    record["entries"].append(bound)
    assert "readings" in _errors(validator, record)
    bound["readings"] = {"band peak of the printed gain (the stated quantity)": 1.605,
                         "Lemma 1's gamma for the printed gain": 1.605,
                         "frequency-domain candidates": {}, "time domain, nearest of the quantities "
                         "searched": {}, "time domain, equal to the printed value": [],
                         "time domain, quantities searched": 494}
    assert "'inequality' is a required property" in _errors(validator, record)
    bound["inequality"] = {"statement": "s", "quantity": 1.605, "bound": 0.1714, "holds": "no"}
    assert "'no' is not of type 'boolean'" in _errors(validator, record)
    bound["inequality"]["holds"] = False
    validator.validate(record)
    more = {"every_fixed_controller": {"tuned": ["tuned"]}, "chosen_in_advance": "tuned"}
    comparators = entry("comparators", "ours", None, {"aircraft": {"names": ["open loop"], "best": {
        "stationary": {"open loop": -1}}, **more}, "generic": {"names": ["open loop"], "best": {}, **more}},
        "new", "n")
    record["entries"].append(comparators)
    assert "-1 is less than the minimum of 0" in _errors(validator, record)
    comparators["recomputed"]["aircraft"]["best"]["stationary"]["open loop"] = 2
    validator.validate(record)


def test_the_law_entries_have_their_shape(validator):
    """The Pareto front lists its points; the law's entry holds every field, per example."""
    record = synthetic_record()
    point = {"beta": 0.4, "gamma_hf": 0.40, "gamma_lf": 0.39, "certified": True, "dominated_by_search": False}
    nine = [dict(point, beta=0.4 + k) for k in range(9)]
    front = entry("pareto_front", "ours", None, {"aircraft": nine, "generic": nine[:3]}, "new", "n")
    record["entries"].append(front)
    assert "is too short" in _errors(validator, record)              # at least nine points
    front["recomputed"]["generic"] = [dict(point, beta=-1.0)] + nine[1:]
    assert "less than or equal to the minimum of 0" in _errors(validator, record)
    bare = {k: v for k, v in point.items() if k != "dominated_by_search"}
    front["recomputed"]["generic"] = [bare] + nine[1:]
    assert "'dominated_by_search' is a required property" in _errors(validator, record)
    front["recomputed"]["generic"] = nine
    validator.validate(record)
    one = {"draws_test": 8, "fixed_in_advance": "tuned filtered", "fixed_in_advance_family": "tuned",
           "median_ratio_vs_fixed_in_advance": 0.99, "p95_ratio_vs_fixed_in_advance": 1.0,
           "win_rate_vs_fixed_in_advance": 0.75, "reference_family": "tuned", "reference_median_ratio": 0.98,
           "reference_share_median": None, "fdsc_median_ratio": {"FDSC": 40.0},
           "switches_per_change": 3.0, "largest_control_step_median": 0.5, "diverged": 0,
           "rho_t_ratio_vs_fixed_in_advance": [1.0, 0.9], "certified": True,
           "certificate": {"checks": {"A + B2 K0 is Hurwitz": True}, "assumptions": ["exact"],
                           "l2_bound": 5.0},
           "meets_targets": False,
           "law": {"candidates": "tuned pair", "law": "cost", "realization": "copies", "forgetting": 0.2,
                   "hysteresis": 0.1}}
    law = entry("supervisor", "ours", None, {"aircraft": one, "generic": dict(one, law={})}, "new", "n")
    record["entries"].append(law)
    assert "'law' is a required property" in _errors(validator, record)
    law["recomputed"]["generic"] = dict(one, win_rate_vs_fixed_in_advance=1.5)
    assert "1.5 is greater than the maximum of 1" in _errors(validator, record)
    law["recomputed"]["generic"] = {k: v for k, v in one.items() if k != "certified"}
    assert "'certified' is a required property" in _errors(validator, record)
    law["recomputed"]["generic"] = one
    validator.validate(record)
