"""Figures that must read at the text column's width: legends and bands of the shared and
Part II plotting modules, on small synthetic results (no simulation)."""

from types import SimpleNamespace

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from fdsc.paper.pays.plotting_pays import plot_family_baselines  # noqa: E402
from fdsc.paper.shared.plotting import plot_epf_series, plot_outputs, plot_sweep  # noqa: E402
from fdsc.paper.shared.plotting_axes import LEGEND_FONTSIZE  # noqa: E402

#: The smallest text size the book allows in a figure drawn at the column's width [pt].
MIN_PT = 8.5


@pytest.fixture
def fig_ax():
    fig, ax = plt.subplots(figsize=(7, 4), layout="constrained")
    yield fig, ax
    plt.close(fig)


def _epf(n=10_001, bin_s=0.02):
    t = np.arange(n) * bin_s
    wave = np.sin(40 * t)             # changes sign from one bin to the next: a wide band
    return SimpleNamespace(gain="K_f3", disturbance="HF", t=t, bin=bin_s,
                           P_t_lo={"LF": -1e3 + wave, "HF": -0.1 + 0 * t},
                           P_t_hi={"LF": 1e2 + wave, "HF": 10 + 0 * t},
                           P_a={"LF": -1e3 + 0 * t, "HF": 5 + 0 * t})


def test_legend_text_is_readable_at_the_column_width():
    assert LEGEND_FONTSIZE >= MIN_PT


def test_epf_bands_merge_bins_to_about_a_pixel_each_and_lie_behind_the_averages(fig_ax):
    _, ax = fig_ax
    plot_epf_series(_epf(), ax, legend=True, bins=400)
    bands = [c for c in ax.collections if c.get_label().startswith("$P_t$")]
    assert len(bands) == 2
    # merged by 25: 10,000 bins of 20 ms become 400 of 0.5 s (and the run's last sample)
    assert all("per 0.5 s" in b.get_label() for b in bands)
    edges = [ln for ln in ax.lines if len(ln.get_xdata()) > 2 and ln.get_linewidth() < 1]
    assert len(edges) == 4 and all(len(ln.get_xdata()) <= 401 for ln in edges)
    averages = [ln for ln in ax.lines if ln.get_label().startswith("running")]
    assert min(a.get_zorder() for a in averages) > max(b.get_zorder() for b in bands)
    # the two terms' bands are told apart where they overlap: one filled, one hatched
    assert sorted(bool(b.get_hatch()) for b in bands) == [False, True]
    assert all(t.get_fontsize() >= MIN_PT for t in ax.get_legend().get_texts())


def test_sweep_legend_below_the_axes_keeps_them_the_figures_width(fig_ax):
    _, ax = fig_ax
    data = SimpleNamespace(family="mixed", names=("PassC-EF", "FDSC"), param=np.linspace(0, 0.5, 5),
                           energy={"PassC-EF": np.full(5, 100.0), "FDSC": np.linspace(10, 2000, 5)})
    plot_sweep(data, ax, log=True, legend="below")
    leg = ax.get_legend()
    _, y = leg.get_bbox_to_anchor().transformed(ax.transAxes.inverted()).p0
    assert y < 0, "the legend must sit under the Axes"
    assert all(t.get_fontsize() >= MIN_PT for t in leg.get_texts())


def test_ideal_segment_law_is_drawn_over_the_open_loop(fig_ax):
    _, ax = fig_ax
    param = np.linspace(0, 0.5, 6)
    energy = {"open loop": 20.0 + 10 * param, "PassC-HF": 3e4 + param}
    result = SimpleNamespace(names=tuple(energy), energies=lambda family: (param, energy),
                             ideal_piecewise=np.full(6, 21.0))
    plot_family_baselines(result, "piecewise", ax)
    by = {ln.get_label(): ln for ln in ax.lines}
    ideal, open_loop = by["ideal segment law"], by["open loop"]
    assert ideal.get_zorder() > open_loop.get_zorder()
    assert open_loop.get_markerfacecolor() == "none"
    assert ideal.get_markerfacecolor() != "none"
    assert ax.get_yscale() == "log"


def test_switched_loops_bands_are_pale_and_below_the_fixed_gains_lines(fig_ax):
    _, ax = fig_ax
    t = np.linspace(0, 10, 101)
    z = np.c_[np.sin(t), np.cos(t), t]
    data = SimpleNamespace(t=t, z_lo={"PassC-LF": z, "FDSC": z - 5}, z_hi={"PassC-LF": z, "FDSC": z + 5})
    plot_outputs(data, 0, ax)
    fill = {c.get_facecolor()[0][3]: c.get_zorder() for c in ax.collections}
    (fdsc_alpha, fdsc_z), (fixed_alpha, fixed_z) = sorted(fill.items())
    assert fdsc_alpha < 0.2 < fixed_alpha
    fixed_lines = [ln for ln in ax.lines if ln.get_color() == "tab:red"]
    assert min(ln.get_zorder() for ln in fixed_lines) > fdsc_z
