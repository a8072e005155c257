import json

import numpy as np
import pytest

from fdsc.paper.cli import main
from fdsc.paper.shared.results import to_jsonable


def test_cli_writes_the_record(tmp_path, capsys):
    assert main(["reproduce", "--out", str(tmp_path / "out")]) == 0
    data = json.loads((tmp_path / "out" / "reproduction.json").read_text())
    assert {"entries", "figures", "environment"} <= set(data)
    assert "wrote" in capsys.readouterr().out


def test_cli_refuses_an_unwritable_out_before_computing(tmp_path, monkeypatch):
    (tmp_path / "file").write_text("x")
    called = []
    monkeypatch.setattr("fdsc.paper.cli.reproduction_record", lambda: called.append(1))
    with pytest.raises(SystemExit, match=r"--out .*file/sub: cannot write there"):
        main(["reproduce", "--out", str(tmp_path / "file" / "sub")])
    assert called == []


def test_cli_help_has_no_rest_markup(capsys):
    with pytest.raises(SystemExit):
        main(["--help"])
    assert "``" not in capsys.readouterr().out


def test_to_jsonable():
    out = to_jsonable({"a": np.array([1.0, np.inf]), "b": 1 + 2j, "c": np.bool_(True),
                       "d": 0.1 + 0.2})
    assert out == {"a": [1.0, "inf"], "b": {"re": 1.0, "im": 2.0}, "c": True, "d": 0.3}
