"""Fifth bad-input probe, paper-layer cases: the stored study's reader on damaged copies, the
ladder's recheck on bad arguments, and the command line on an empty --out or a file that is not a
study. Every case is refused before any computing."""

import copy
import json
import re

import pytest

from fdsc.paper.cli import main
from fdsc.paper.pays import disturbance_law_full as dlf
from fdsc.paper.pays import ladder as ld
from fdsc.paper.pays.stored_study import load_full, stored_fixed_set


@pytest.fixture(scope="module")
def full():
    study = load_full()
    if study is None or "ladder" not in study.get("aircraft", {}):
        pytest.skip("the stored study with the ladder is not in this checkout")
    return study


@pytest.fixture(scope="module")
def dynamic(full):
    """The name of a stored aircraft controller with states."""
    return next(k for k, v in full["aircraft"]["fixed_controllers"].items() if v["matrices"]["A"])


@pytest.fixture
def not_computed(monkeypatch):
    """Every way to start computing replaced by one that fails the test if it is reached."""
    def computed(*args, **kwargs):
        raise AssertionError("the computation started before the arguments were checked")

    monkeypatch.setattr("fdsc.paper.cli.reproduction_record", computed)
    monkeypatch.setattr("fdsc.paper.pays.disturbance_law.full_study", computed)
    monkeypatch.setattr("fdsc.paper.pays.disturbance_law.robustness", computed)
    monkeypatch.setattr("fdsc.paper.pays.disturbance_law.measured_robustness", computed)
    monkeypatch.setattr("concurrent.futures.ProcessPoolExecutor", computed)
    monkeypatch.setattr("fdsc.paper.pays.ladder.ladder_draw", computed)


# --- A. the ladder's recheck on bad arguments ------------------------------------------------------

@pytest.mark.parametrize(("example", "k", "err", "match"), [
    # before: k = 0 reported a clean recheck of zero draws
    ("aircraft", 0, ValueError, r"k must be an integer >= 1, but found 0"),
    # before: TypeError: slice indices must be integers
    ("aircraft", 1.5, ValueError, r"k must be an integer >= 1, but found 1.5"),
    # before: every stored draw recomputed (k = None slices all)
    ("aircraft", None, ValueError, r"k must be an integer >= 1, but found None"),
    ("aircraft", 10 ** 6, ValueError, r"k must be at most the \d+ stored test draws of the ladder, but "
                                      r"found 1000000"),
    # before: KeyError: 'boeing'
    ("boeing", 1, ValueError, r"example must be one of \('aircraft', 'generic'\), but found 'boeing'"),
])
def test_recheck_ladder_names_a_bad_argument(full, not_computed, example, k, err, match):
    with pytest.raises(err, match=match):
        ld.recheck_ladder(full, example, k)


def test_recheck_ladder_names_a_study_without_its_ladder(full, not_computed):
    # before: KeyError: 'ladder'
    old = copy.deepcopy(full)
    del old["generic"]["ladder"]
    with pytest.raises(KeyError, match=r"full\['generic'\]: the stored study has no key 'ladder'"):
        ld.recheck_ladder(old, "generic", 1)
    with pytest.raises(TypeError, match=r"full must be the stored full study .* found NoneType"):
        ld.recheck_ladder(None, "generic", 1)


# --- B. the stored study's reader on damaged copies ----------------------------------------------------

def test_load_full_names_a_path_that_is_not_one():
    # before: pathlib's TypeError "expected str, bytes or os.PathLike object, not int"
    with pytest.raises(TypeError, match=r"path must be the stored study's file \(a str or os.PathLike\), "
                                        r"but found int"):
        load_full(12)


def test_load_full_names_a_binary_file(tmp_path):
    # before: UnicodeDecodeError without the file's name
    path = tmp_path / "study.json"
    path.write_bytes(b"\xff\xfe\x00\x01 not a study")
    with pytest.raises(ValueError, match=rf"path: the stored study {re.escape(str(path))} is not UTF-8 text"):
        load_full(path)


def test_load_full_names_json_that_is_not_a_study(tmp_path):
    # before: the list was returned, and the next reader failed on it
    path = tmp_path / "study.json"
    path.write_text("[1, 2]")
    with pytest.raises(ValueError, match=rf"path: {re.escape(str(path))} holds JSON but not a stored study "
                                         r"\(a list"):
        load_full(path)


def _damaged(full, name, how):
    out = copy.deepcopy(full)
    fc = out["aircraft"]["fixed_controllers"][name]
    m = fc["matrices"]
    if how == "no A":
        del m["A"]
    elif how == "no matrices":
        del fc["matrices"]
    elif how == "no train_score":
        del fc["train_score"]
    elif how == "NaN":
        m["A"][0][0] = float("nan")
    elif how == "string":
        m["B"][0][0] = "1.5"
    elif how == "shape":
        m["C"] = [[1.0]]
    elif how == "score":
        fc["train_score"] = "low"
    return out


@pytest.mark.parametrize(("how", "err", "match"), [
    # before: a bare KeyError 'A', 'matrices' or 'train_score'
    ("no A", KeyError, r"\['matrices'\]: the stored study has no matrix 'A'"),
    ("no matrices", KeyError, r": the stored study has no key 'matrices'"),
    ("no train_score", KeyError, r": the stored study has no key 'train_score'"),
    # before: "A must have finite entries", "could not convert string to float", "cannot reshape
    # array of size 1 into shape (2,newaxis)": which of the controllers was not said
    ("NaN", ValueError, r"\['matrices'\]: the stored matrices of .* do not make a controller \(A must have "
                        r"finite entries"),
    ("string", ValueError, r"\['matrices'\]: the stored matrices of .* do not make a controller \(B must be "
                           r"a numeric matrix"),
    ("shape", ValueError, r"\['matrices'\]: the stored matrices of .* do not make a controller \(C: expected "
                          r"shape \(2, \d+\) but found \(1, 1\)"),
    ("score", ValueError, r"\['train_score'\] must be a real number, but found 'low'"),
])
def test_a_damaged_stored_controller_is_named(full, dynamic, tmp_path, not_computed, how, err, match):
    # the damaged copy is written and read back, as a reader meets it
    path = tmp_path / "study.json"
    path.write_text(json.dumps(_damaged(full, dynamic, how)))
    study = load_full(path)
    where = re.escape(f"full['aircraft']['fixed_controllers'][{dynamic!r}]")
    for read in (lambda: stored_fixed_set(study, "aircraft"),
                 lambda: dlf.recheck_stored(study, "aircraft", 1),
                 lambda: ld.recheck_ladder(study, "aircraft", 1)):
        with pytest.raises(err, match=where + match):
            read()


# --- C. the command line ----------------------------------------------------------------------------

def test_reproduce_refuses_an_empty_out(not_computed, capsys):
    # before: --out '' is the current folder, and the whole reproduction started there
    with pytest.raises(SystemExit):
        main(["reproduce", "--out", ""])
    assert "argument --out: must name a path, but found an empty string" in capsys.readouterr().err


@pytest.mark.parametrize("flag", ["--robustness-only", "--measured-only"])
@pytest.mark.parametrize(("text", "why"), [
    # before: json.decoder.JSONDecodeError, a traceback without the file's name
    ('{"n": 4, "seed"', r"is not valid JSON \(Expecting ':' delimiter at line 1, column 16\)"),
    # before: TypeError "full must be the stored full study ..., but found list"
    ("[1, 2]", r"holds JSON but not a stored study \(a list"),
    # before: KeyError "full: the stored study has no key 'n'"
    ('{"a": 1}', r"full: the stored study has no key 'n'"),
])
def test_disturbance_law_names_a_file_that_is_not_a_study(tmp_path, not_computed, capsys, flag, text, why):
    path = tmp_path / "study.json"
    path.write_text(text)
    with pytest.raises(SystemExit):
        main(["disturbance-law", flag, "--out", str(path), "--workers", "1"])
    err = capsys.readouterr().err
    assert re.search(rf"error: --out {re.escape(str(path))}: not a full study that --robustness-only or "
                     rf"--measured-only can extend \(.*{why}", err), err


def test_disturbance_law_names_a_damaged_controller_of_the_study(full, dynamic, tmp_path, not_computed,
                                                                   capsys):
    path = tmp_path / "study.json"
    path.write_text(json.dumps(_damaged(full, dynamic, "NaN")))
    with pytest.raises(SystemExit):
        main(["disturbance-law", "--robustness-only", "--out", str(path), "--workers", "1"])
    err = capsys.readouterr().err
    assert f"--out {path}: not a full study" in err
    assert f"full['aircraft']['fixed_controllers'][{dynamic!r}]['matrices']" in err
