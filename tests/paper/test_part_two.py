"""The studies' shared command line (fdsc.paper.pays.study_command) and the run of every study of
Part II at one commit (fdsc.paper.pays.part_two): arguments refused by name before computing, the
smaller studies a small full study asks, and a stored study read back."""

import json

import pytest

from fdsc.paper.pays import adaptive_rung, information, observer_rung, part_two, variant_laws
from fdsc.paper.pays.study_command import load_stored, run_on_pool, study_main


def test_a_stored_study_is_read_back_and_an_absent_one_is_none(tmp_path):
    assert load_stored("book/data/no_such_study.json") is None
    f = tmp_path / "s.json"
    f.write_text(json.dumps({"a": [1, 2]}))
    assert load_stored("ignored", f) == {"a": [1, 2]}


def _echo(full, *, executor, k=1):
    return {"full": full, "k": k, "mapped": list(executor.map(abs, [-k, 2]))}


def test_a_study_runs_on_a_pool_with_its_time_and_host():
    res = run_on_pool(_echo, {"n": 4}, 1, k=3)
    assert res["full"] == {"n": 4} and res["mapped"] == [3, 2]
    assert res["seconds"] >= 0 and res["host"]["workers"] == 1 and res["host"]["cpu_seconds"] >= 0
    with pytest.raises(ValueError, match="workers"):
        run_on_pool(_echo, {}, 0)


@pytest.mark.parametrize(("argv", "message"), [
    (["--workers", "0"], "--workers must be at least 1, but found 0"),
    (["--n-test", "1"], "--n-test must be at least 2, but found 1"),
    (["--n-train", "0"], "--n-train must be at least 1, but found 0"),
])
def test_a_study_command_refuses_bad_arguments_before_computing(argv, message, capsys):
    for mod in (information, adaptive_rung, observer_rung):
        with pytest.raises(SystemExit):
            mod.main(argv)
        assert message in capsys.readouterr().err


def test_a_study_command_names_its_option_range(capsys):
    with pytest.raises(SystemExit):
        study_main(["--k", "9"], prog="p", description="d", file="book/data/x.json", study=_echo,
                   options=(("k", 1, 1, 4),))
    assert "--k must be in [1, 4], but found 9" in capsys.readouterr().err


@pytest.mark.parametrize(("argv", "message"), [
    (["--n", "3"], "--n must be at least 4, but found 3"),
    (["--workers", "0"], "--workers must be at least 1, but found 0"),
])
def test_part_two_refuses_bad_arguments_before_computing(argv, message, capsys):
    with pytest.raises(SystemExit):
        part_two.main(argv)
    assert message in capsys.readouterr().err


def test_a_smaller_full_study_asks_fewer_draws_of_the_others():
    # the default run keeps every study's own sizes; a small one fits them in the full study's test draws
    full_size = {name: part_two._sizes(getattr(__import__(m, fromlist=[f]), f), 500)
                 for name, m, f, _file in part_two.STUDIES}
    assert full_size["information"] == {"n_test": information.N_TEST, "n_train": information.N_TRAIN}
    assert full_size["variant laws"] == {"n_train": variant_laws.N_TRAIN}
    assert part_two._sizes(information.information_study, 8) == {"n_test": 2, "n_train": 2}
    assert part_two._sizes(information.information_study, 4) == {"n_test": 2, "n_train": 1}


def _two_fake_studies(monkeypatch, fake_pool, a, b):
    """Part II's studies replaced by two stand-ins, A and B, run by ``fake_pool``."""
    import sys
    import types
    from pathlib import Path

    from fdsc.paper.pays import study_command

    monkeypatch.setattr(study_command, "run_on_pool", fake_pool)
    monkeypatch.setitem(sys.modules, "fake_a", types.SimpleNamespace(a=a, FILE=Path("book/data/a.json")))
    monkeypatch.setitem(sys.modules, "fake_b", types.SimpleNamespace(b=b, FILE=Path("book/data/b.json")))
    monkeypatch.setattr(part_two, "STUDIES", (("A", "fake_a", "a", "FILE"), ("B", "fake_b", "b", "FILE")))


def test_the_files_wait_untracked_until_the_last_study_ends(tmp_path, monkeypatch):
    # every study records whether the tree was clean: no output may land in the folder before the end
    seen = []

    def fake_pool(study, full, workers, **kwargs):
        seen.append(sorted(p.name for p in tmp_path.iterdir()))        # what the folder holds now
        res = ({"commit": "c", "fingerprint": "f", "n": kwargs.get("n")} if full is None
               else {"study": study.__name__, "read": full["commit"]})
        return res | {"seconds": 1.0, "host": {"cpu_seconds": 2.0}}

    def a(full, *, executor=None):
        return {}

    def b(full, *, executor=None, n_test=24, n_train=4):
        return {}

    _two_fake_studies(monkeypatch, fake_pool, a, b)
    rec = part_two.part_two(8, 1, tmp_path)
    assert seen == [[part_two.PENDING]] * 3                               # only the pending folder, each time
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.json", "b.json", "disturbance_law_full.json"]
    assert json.loads((tmp_path / "b.json").read_text())["read"] == "c"   # the studies read the full study
    assert rec["commit"] == "c" and set(rec["studies"]) == {"full study", "A", "B"}
    assert rec["studies"]["B"] == {"file": "b.json", "seconds": 1.0, "cpu_seconds": 2.0}


def test_a_stopped_run_is_taken_up_from_its_first_missing_or_stale_study(tmp_path, monkeypatch):
    from fdsc.paper.shared import cache, environment

    computed, fail = [], {"B"}
    prints = {"fake_a": "fa", "fake_b": "fb", "fdsc.paper.pays.disturbance_law_full": "ff"}

    def fake_pool(study, full, workers, **kwargs):
        name = "full" if full is None else study.__name__.upper()
        if name in fail:
            raise KeyboardInterrupt                                       # the machine stops here
        computed.append(name)
        module = "fdsc.paper.pays.disturbance_law_full" if full is None else f"fake_{name.lower()}"
        return {"commit": "c", "fingerprint": prints[module], "n": kwargs.get("n"), "seconds": 5.0,
                "host": {"cpu_seconds": 9.0}}

    def a(full, *, executor=None):
        return {}

    def b(full, *, executor=None):
        return {}

    _two_fake_studies(monkeypatch, fake_pool, a, b)
    monkeypatch.setattr(environment, "build_commit", lambda: "c")
    monkeypatch.setattr(cache, "study_fingerprint", lambda module: prints[module])
    with pytest.raises(KeyboardInterrupt):
        part_two.part_two(8, 1, tmp_path)
    assert computed == ["full", "A"] and (tmp_path / part_two.PENDING / "a.json").is_file()

    # taken up: the full study and A are read back, B is computed
    computed.clear(), fail.clear()
    rec = part_two.part_two(8, 1, tmp_path, resume=True)
    assert computed == ["B"] and rec["resumed"] == ["full study", "A"]
    assert rec["seconds"] == 15.0 and rec["studies"]["A"]["cpu_seconds"] == 9.0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.json", "b.json", "disturbance_law_full.json"]

    # a stale study (its sources changed) is computed again, and so is every study after it, even a fresh one
    for f in ("disturbance_law_full.json", "a.json", "b.json"):
        (tmp_path / part_two.PENDING).mkdir(exist_ok=True)
        (tmp_path / f).replace(tmp_path / part_two.PENDING / f)
    computed.clear()
    prints["fake_a"] = "fa2"
    assert part_two.part_two(8, 1, tmp_path, resume=True)["resumed"] == ["full study"]
    assert computed == ["A", "B"]

    # a full study of another size is not read back; without resume nothing is
    computed.clear()
    (tmp_path / part_two.PENDING).mkdir()
    for f in ("disturbance_law_full.json", "a.json", "b.json"):
        (tmp_path / f).replace(tmp_path / part_two.PENDING / f)
    assert part_two.part_two(6, 1, tmp_path, resume=True)["resumed"] == []
    assert part_two.part_two(8, 1, tmp_path)["resumed"] == [] and computed == ["full", "A", "B"] * 2
