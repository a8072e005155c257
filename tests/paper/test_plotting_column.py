"""Figures that must read at the text column's width: legends and bands of the shared and
Part II plotting modules, and the check the book applies to every figure it renders
(:func:`~fdsc.paper.shared.plotting_axes.figure_problems`,
:func:`~fdsc.paper.shared.plotting_axes.check_figures`), on small synthetic figures and results
(no simulation)."""

import io
from types import SimpleNamespace

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib.backend_bases import FigureCanvasBase  # noqa: E402
from matplotlib.text import Text  # noqa: E402

from fdsc.paper.pays.plotting_pays import plot_family_baselines  # noqa: E402
from fdsc.paper.shared.plotting import plot_epf_series, plot_outputs, plot_sweep  # noqa: E402
from fdsc.paper.shared.plotting_axes import (  # noqa: E402
    LEGEND_FONTSIZE,
    MIN_PT,
    _end_labels,
    check_figures,
    figure_problems,
    symlog_axis,
)


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


# -- the check of every figure of the book: figure_problems and check_figures ----------------------

@pytest.fixture
def checked():
    """check_figures() installed for the test, removed afterwards even if the test fails."""
    original = FigureCanvasBase.print_figure
    remove = check_figures()
    yield
    remove()
    assert FigureCanvasBase.print_figure is original


def _readable(fig_ax):
    fig, ax = fig_ax
    ax.plot([1, 10, 100], [3, 1, 2], label="a controller")
    ax.set(xlabel="$t$ [s]", ylabel="output [-]", title="a title")
    ax.legend(fontsize=LEGEND_FONTSIZE)
    return fig, ax


def test_a_readable_figure_has_no_problems(fig_ax):
    fig, _ = _readable(fig_ax)
    assert figure_problems(fig) == []
    assert figure_problems(fig, tight=True) == []


def test_a_small_legend_is_caught_with_its_place_and_size(fig_ax):
    fig, ax = _readable(fig_ax)
    ax.legend(fontsize=7)
    (problem,) = figure_problems(fig)
    assert problem.startswith("axes 1 ('a title'): legend text at 7 pt reads at 7 pt (< 8.5 pt)")
    assert "'a controller'" in problem


def test_a_small_annotation_and_tick_labels_are_caught(fig_ax):
    fig, ax = _readable(fig_ax)
    ax.annotate("a note", (10, 2), fontsize=6)
    ax.tick_params(axis="y", labelsize=8)
    problems = figure_problems(fig)
    assert any("text at 6 pt" in p and "'a note'" in p for p in problems)
    assert any("y tick labels at 8 pt" in p for p in problems)
    assert not any("x tick labels" in p for p in problems)


def test_a_figure_wider_than_the_column_shrinks_its_text():
    # 10 pt text on a 10 in figure reads at 7 pt once the figure is shrunk to the 7 in column
    fig, ax = plt.subplots(figsize=(10, 4), layout="constrained")
    ax.plot([0, 1])
    try:
        problems = figure_problems(fig)
        assert problems[0].startswith("the figure is 10 in wide, wider than the 7 in column")
        assert "reads at 7 pt" in problems[0]
        # the same text on a figure as wide as the column reads as set
        fig.set_figwidth(7)
        assert figure_problems(fig) == []
        # a wider column, or a lower threshold, lets the wide figure pass
        fig.set_figwidth(10)
        assert figure_problems(fig, column_in=10) == []
        assert figure_problems(fig, min_pt=7) == []
    finally:
        plt.close(fig)


def test_too_many_tick_labels_are_caught_and_symlog_axis_keeps_few(fig_ax):
    fig, ax = fig_ax
    ax.plot([1, 2, 3], [-1e12, 0, 1e10])
    ax.set_yscale("symlog", linthresh=1.0)      # every decade labelled: 23 labels
    problems = figure_problems(fig)
    assert len(problems) == 1 and "tick labels on the y axis (> 10)" in problems[0]
    assert figure_problems(fig, max_ticks=30) == []
    symlog_axis(ax, "y", 1.0)
    assert figure_problems(fig) == []


def test_hidden_and_empty_texts_do_not_count(fig_ax):
    fig, ax = _readable(fig_ax)
    ax.text(1, 1, "hidden", fontsize=5, visible=False)
    ax.text(1, 1, "   ", fontsize=5)
    ax.get_legend().set_visible(False)
    ax.legend(fontsize=5).set_visible(False)
    inset = ax.inset_axes([0.6, 0.6, 0.3, 0.3])
    inset.tick_params(labelsize=5)
    inset.axis("off")
    assert figure_problems(fig) == []


def test_an_inset_is_named_after_its_axes(fig_ax):
    fig, ax = _readable(fig_ax)
    inset = ax.inset_axes([0.6, 0.6, 0.3, 0.3])
    inset.tick_params(labelsize=7)
    problems = figure_problems(fig)
    assert problems and all(p.startswith("inset of axes 1 ('a title'): ") for p in problems)


def test_rendering_a_figure_with_problems_raises_under_check_figures(fig_ax, checked):
    from IPython.core.pylabtools import print_figure as ipython_print_figure

    fig, ax = _readable(fig_ax)
    fig.savefig(io.BytesIO(), format="png")           # readable: rendered
    ax.legend(fontsize=7)
    with pytest.raises(ValueError, match=r"does not read at the 7 in column: .*legend text at 7 pt"):
        fig.savefig(io.BytesIO(), format="png")
    # what a notebook's inline backend calls to show (or glue) a figure: cropped to its content
    with pytest.raises(ValueError, match="legend text at 7 pt"):
        ipython_print_figure(fig, "png")


def test_check_figures_called_again_replaces_its_thresholds(fig_ax):
    original = FigureCanvasBase.print_figure
    fig, ax = _readable(fig_ax)
    ax.legend(fontsize=7)
    check_figures(min_pt=6)
    try:
        fig.savefig(io.BytesIO(), format="png")           # 7 pt passes a 6 pt threshold
        remove = check_figures()                          # the book's threshold, not both
        with pytest.raises(ValueError, match="legend text at 7 pt"):
            fig.savefig(io.BytesIO(), format="png")
        remove()
        assert FigureCanvasBase.print_figure is original
        fig.savefig(io.BytesIO(), format="png")
    finally:
        FigureCanvasBase.print_figure = original


def test_end_labels_of_close_curves_stay_apart_in_their_colours(fig_ax):
    fig, ax = fig_ax
    x = np.linspace(0, 0.5, 11)
    ends = {"PassC-HF": 3e6, "FDSC": 2000, "FDSC (dwell)": 1500, "FDSC (HF best)": 1000, "open loop": 500}
    for k, (name, end) in enumerate(ends.items()):
        ax.semilogy(x, np.linspace(10, end, x.size), color=f"C{k}", label=name)
    _end_labels(ax)
    texts = {t.get_text(): t for t in ax.texts}
    assert set(texts) == set(ends)
    assert all(texts[n].get_color() == f"C{k}" for k, n in enumerate(ends))
    assert all(t.get_fontsize() >= MIN_PT for t in texts.values())
    fig.draw_without_rendering()
    # the texts' own boxes (an annotation's box holds its connecting line too)
    boxes = sorted((Text.get_window_extent(t) for t in texts.values()), key=lambda b: b.y0)
    assert all(lo.y1 <= hi.y0 + 0.5 for lo, hi in zip(boxes, boxes[1:], strict=False))
    assert figure_problems(fig) == []


def test_every_chapter_that_draws_checks_its_figures_before_it_draws():
    import json
    import re
    from pathlib import Path

    book = Path(__file__).resolve().parents[2] / "book"
    draws = re.compile(r"\bplt\.|\bplot_\w+\(|\.subplots\(")
    unchecked = []
    for path in sorted(book.glob("*.ipynb")):
        code = ["".join(c["source"]) for c in json.loads(path.read_text(encoding="utf-8"))["cells"]
                if c["cell_type"] == "code"]
        first_draw = next((i for i, src in enumerate(code) if draws.search(src)), None)
        first_check = next((i for i, src in enumerate(code) if "check_figures()" in src), None)
        if first_draw is not None and (first_check is None or first_check > first_draw):
            unchecked.append(path.stem)
    assert unchecked == [], f"chapters that draw figures without check_figures() first: {unchecked}"
