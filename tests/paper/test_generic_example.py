"""The generic example of issue 14: headline, public-API-only imports, cross-checks, bad inputs."""

import ast
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from numpy.testing import assert_allclose  # noqa: E402

import fdsc  # noqa: E402
from fdsc.paper.pays import generic_example as ge  # noqa: E402
from fdsc.paper.pays import plotting_generic as pg  # noqa: E402

SOURCE = Path(ge.__file__)


@pytest.fixture(scope="module")
def study():
    return ge.generic_study()


def test_lf_design_beats_hinf_in_band_and_loses_out_of_band(study):
    h = study.headline
    # measured 3.28 and 36.6: margins wide enough that solver rounding cannot flip them
    assert h.factor_lf >= 2.0
    assert h.loss_lf >= 5.0
    # H∞ is limited by the HF band on this plant: PassC-HF is no better there (measured 1.001)
    assert h.factor_hf == pytest.approx(1.0, abs=0.1)
    # PassC-HF loses in the LF band against H∞ (measured 1.32)
    assert h.loss_hf >= 1.1


def test_study_shapes_and_laws(study):
    names = ("open loop", "PassC-EF", "PassC-LF", "PassC-HF", "FDSC", "FDSC (dwell)")
    assert study.stationary.names == names
    assert study.rho_p.shape == (21,) and study.rho_t.shape == (21,)
    assert {w.law for w in study.headline.rho_p} == {"FDSC", "FDSC (dwell)"}
    assert all(p.shape == (3,) for p in study.peaks.values())


def test_generic_example_imports_only_the_public_api():
    allowed_paper = {"fdsc.paper.shared.cache", "fdsc.paper.shared.results", "fdsc.paper.shared.examples",
                     "fdsc.paper.shared.fixed_choice"}
    tree = ast.parse(SOURCE.read_text(encoding="utf-8"))
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found += [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            mod = node.module or ""
            found.append(f"fdsc.paper.{mod}" if node.level == 1 else
                         f"fdsc.{mod}" if node.level == 2 else mod)
    ours = [m for m in found if m.split(".")[0] == "fdsc"]
    assert ours, "the module should import fdsc"
    bad = [m for m in ours if m not in ("fdsc", "fdsc.plotting")
           and m not in allowed_paper]
    assert bad == []
    # and it calls only public top-level names of fdsc
    attrs = {n.attr for n in ast.walk(tree) if isinstance(n, ast.Attribute)
             and isinstance(n.value, ast.Name) and n.value.id == "fdsc"}
    assert attrs and attrs <= set(fdsc.__all__)


def test_stationary_energy_ratio_against_the_closed_form(study):
    # H∞ loop (fast poles) under the HF tones: the run from rest approaches the steady-state
    # L2 gain squared of fdsc.steady_state_gain (closed form Σ a²‖G(jω)‖² / Σ a²)
    ex = ge.generic_example()
    d = ge.hf_disturbance()
    closed = fdsc.steady_state_gain(ex.closed_loop("PassC-EF"), d.frequencies, d.amplitudes) ** 2
    assert_allclose(study.stationary.ratio()["PassC-EF"][1], closed, rtol=1e-2)


def test_band_peak_against_a_dense_sweep(study):
    # PassC-LF's HF peak (band_peak with refinement) against a dense σ_max grid on [ϖ_h, 100]
    ex = ge.generic_example()
    w = np.linspace(ge.W_H, 100.0, 200_001)
    dense = fdsc.sigma_max(ex.closed_loop("PassC-LF"), w).max()
    assert_allclose(study.peaks["PassC-LF"][2], dense, rtol=1e-4)
    assert study.peaks["PassC-LF"][2] >= dense * (1 - 1e-12)


def test_record_part(study):
    part = ge.record_part()
    (e,) = part.entries
    assert e["id"] == "generic_example" and e["verdict"] == "new" and e["paper"] is None
    assert e["recomputed"]["factor_lf"] == study.headline.factor_lf


@pytest.mark.parametrize(("call", "match"), [
    (lambda: ge.generic_plant(rho=0.0), "rho must be a positive finite number"),
    (lambda: ge.generic_plant(m2=float("nan")), "m2 must be a positive finite number"),
    (lambda: ge.mixed_disturbance(-1.0), "rho_p must be a finite number >= 0"),
    (lambda: ge.piecewise_disturbance(0.5, T=0.0), "T must be > 0"),
    (lambda: ge.piecewise_disturbance(-0.1), "rho_t must be a finite number >= 0"),
    (lambda: ge.generic_example.__wrapped__(dwell=0.0), "dwell must be a positive finite number"),
    (lambda: ge.generic_study.__wrapped__(n_omega=10), "n_omega must be an integer >= 100"),
])
def test_bad_inputs(call, match):
    with pytest.raises(ValueError, match=match):
        call()


@pytest.mark.parametrize("plot", [pg.plot_sigma, pg.plot_rho_p, pg.plot_rho_t])
def test_plots_label_their_axes(study, plot):
    fig, ax = plt.subplots()
    assert plot(study, ax) is ax
    assert ax.get_xlabel() and ax.get_ylabel() and ax.get_legend() is not None
    plt.close(fig)
