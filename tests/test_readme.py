"""The README's "Use it on your own plant" example runs exactly as written."""

from pathlib import Path

import matplotlib
import numpy as np
import pytest
from readme_numbers import example_code  # tests/readme_numbers.py (also run by .ci/run)

README = Path(__file__).resolve().parent.parent / "README.md"


def _own_plant_example():
    return example_code(README)


def test_own_plant_example_runs_as_written(tmp_path, monkeypatch, capsys):
    matplotlib.use("Agg")
    monkeypatch.chdir(tmp_path)
    namespace = {}
    exec(compile(_own_plant_example(), "README.md", "exec"), namespace)  # noqa: S102
    out = capsys.readouterr().out
    ctrl, run = namespace["ctrl"], namespace["run"]
    # the plant came in as a python-control StateSpace and was split into [d; u]
    assert ctrl.plant.B1.shape == (2, 1) and ctrl.plant.B2.shape == (2, 1)
    # each synthesized gain is certified on its band, and Theorem 1's LMIs are feasible
    for res in ctrl.synthesis:
        assert res.gamma_sweep <= res.gamma_lmi * (1 + 1e-5)
    assert np.all(np.isfinite(ctrl.gammas)) and ctrl.certificate.status
    # the law uses both modes: mostly LF while d is slow, mostly HF once it is fast
    slow, fast = run.t < 60.0, run.t >= 60.0
    assert np.mean(run.sigma[slow] == 0) > 0.5 and np.mean(run.sigma[fast] == 1) > 0.5
    assert "Theorem 1's LMIs are feasible for gamma_i" in out
    # the fixed filtered controller is within 2 % of FDSC's energy on this disturbance, unswitched
    assert namespace["fixed_shaped"].energy() < 1.02 * run.energy()
    assert "energy of z with the filtered controller" in out
    assert (tmp_path / "own_plant.png").stat().st_size > 0


def test_the_example_holds_no_aircraft():
    # the example must not lean on the paper layer
    code = _own_plant_example()
    assert "fdsc.paper" not in code and "aircraft" not in code


@pytest.mark.parametrize("section", ["## Use it on your own plant", "## Layout", "## Quick start"])
def test_readme_sections_exist(section):
    assert section in README.read_text(encoding="utf-8")
