"""Shared infrastructure, figures: the axes helpers of the plotting modules, and the check that
every figure of the book reads at the text column's width.

A new Axes when none is given, a symmetric-log axis with few ticks, the legend text of a
controller and a legend below the Axes; :func:`figure_problems` says what keeps a figure from
reading at the column's width (text too small once the figure is shrunk to the column, too many
tick labels), and :func:`check_figures` makes every figure a notebook renders pass it.
"""

import functools
import math

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.axis import Axis
from matplotlib.backend_bases import FigureCanvasBase
from matplotlib.legend import Legend
from matplotlib.text import Text
from matplotlib.ticker import FixedLocator, NullLocator

__all__ = ["LEGEND_FONTSIZE", "COLUMN_IN", "MIN_PT", "MAX_TICKS", "symlog_axis", "figure_problems",
           "check_figures"]

#: The width of the book's text column [in]: a figure wider than it is shown shrunk to it.
COLUMN_IN = 7.0
#: The smallest text size a figure may show at the column's width [pt] (the book's rule).
MIN_PT = 8.5
#: The most tick labels one axis of a figure may show.
MAX_TICKS = 10


#: Legend text size [pt] of a figure drawn at the text column's width (about 7 in): at least the
#: 8.5 pt the book asks of the text in its figures (:data:`MIN_PT`).
LEGEND_FONTSIZE = 9


def symlog_axis(ax, axis, linthresh, *, per_side=3):
    """Make an axis symmetric-log with few tick labels: 0 and at most ``per_side`` powers of ten
    on each side (a default symlog axis labels every decade, dozens of labels over a wide range).

    Call it once the data are drawn: the ticks are chosen for the axis' limits at the call.

    Parameters
    ----------
    ax : matplotlib Axes
    axis : {"x", "y"}
    linthresh : float
        The half-width of the linear range about 0 (> 0).
    per_side : int, optional
        The most powers of ten labelled on each side of 0.

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> fig, ax = plt.subplots()
    >>> _ = ax.plot([0, 1], [-1e6, 1e9])
    >>> symlog_axis(ax, "y", 1.0)
    >>> [f"{t:g}" for t in ax.get_yticks()]
    ['-1e+06', '-10000', '-100', '0', '1000', '1e+06', '1e+09']
    >>> plt.close(fig)
    """
    getattr(ax, f"set_{axis}scale")("symlog", linthresh=linthresh)
    lo, hi = getattr(ax, f"get_{axis}lim")()
    ticks = [0.0]
    for sign, end in ((1, hi), (-1, -lo)):
        if end <= linthresh:
            continue
        # the first labelled power lies a decade above the linear range, so that its label and
        # 0's do not overlap (unless the axis ends before it)
        e1 = math.floor(math.log10(end))
        e0 = min(math.ceil(math.log10(linthresh)) + 1, e1)
        step = max(1, math.ceil((e1 - e0 + 1) / per_side))
        ticks += [sign * 10.0 ** e for e in range(e1, e0 - 1, -step)]
    sub = getattr(ax, f"{axis}axis")
    sub.set_major_locator(FixedLocator(sorted(ticks)))
    sub.set_minor_locator(NullLocator())


def _label(name, factor=1.0):
    """Legend text of a controller: ẋ in mathtext (the plain glyph is missing from the fonts),
    and a scaling as the paper states it (× 1/5000)."""
    text = name.replace("ẋ", r"$\dot x$")
    if factor == 1.0:
        return text
    return f"{text} × 1/{1 / factor:g}" if factor < 1 else f"{text} × {factor:g}"


def _below_legend(ax, ncol=2, *, y=-0.16):
    """The legend under the Axes (and under their x label, ``y`` in Axes fractions), for a figure
    as narrow as the text column: a legend beside the Axes would narrow them."""
    ax.legend(fontsize=LEGEND_FONTSIZE, loc="upper center", bbox_to_anchor=(0.5, y),
              ncol=ncol, borderaxespad=0, frameon=False)


def _end_labels(ax, *, fontsize=LEGEND_FONTSIZE, spacing=1.2):
    """Name each labelled line at its right end, beside the Axes and in its colour, instead of a
    legend: curves of close hues need no matching of colours against a legend. Labels that would
    overlap are moved apart (at least ``spacing`` line heights) and joined to their line's end by
    a thin line. Call it once the lines are drawn and the limits set."""
    ax.figure.draw_without_rendering()          # the Axes' height after the figure's layout
    height_pt = ax.get_window_extent().height * 72 / ax.figure.dpi
    step = spacing * fontsize / height_pt        # one label's height in Axes fractions
    to_axes = ax.transAxes.inverted()
    ends = []
    for line in ax.get_lines():
        label = line.get_label()
        x, y = (np.asarray(v, dtype=float) for v in line.get_data())
        ok = np.isfinite(x) & np.isfinite(y)
        if label.startswith("_") or not ok.any():
            continue
        fy = to_axes.transform(ax.transData.transform((x[ok][-1], y[ok][-1])))[1]
        ends.append([fy, fy, line])
    ends.sort(key=lambda e: e[0])
    # spread upwards from the lowest, then back down from the top so that all stay within the Axes
    for k, e in enumerate(ends):
        e[1] = max(e[1], step / 2 if k == 0 else ends[k - 1][1] + step)
    for k in range(len(ends) - 1, -1, -1):
        ends[k][1] = min(ends[k][1], 1 - step / 2 if k == len(ends) - 1 else ends[k + 1][1] - step)
    for fy, ty, line in ends:
        ax.annotate(line.get_label(), (1.0, fy), xycoords="axes fraction", xytext=(1.035, ty),
                    textcoords="axes fraction", ha="left", va="center", fontsize=fontsize,
                    color=line.get_color(), annotation_clip=False,
                    arrowprops={"arrowstyle": "-", "color": line.get_color(), "lw": 0.6,
                                "shrinkA": 0, "shrinkB": 1})


def _axes(ax, figsize=(7, 4)):
    if ax is None:
        _, ax = plt.subplots(figsize=figsize, layout="constrained")
    return ax


def _axes_name(ax, fig, parent=None):
    """A reader's name of an Axes in a problem: its place among the figure's Axes (or the Axes it
    is an inset of) and its title."""
    where = f"inset of {parent}" if parent else f"axes {fig.axes.index(ax) + 1}" if ax in fig.axes else "axes"
    title = next((t.get_text() for t in (ax.title, ax._left_title, ax._right_title) if t.get_text()), "")
    if len(title) > 30:
        title = title[:29] + "…"
    return f"{where} ('{title}')" if title else where


def _visible_texts(artist, fig, where, what):
    """``(where, what, Text)`` for every visible, non-empty text under ``artist``, and
    ``(where, "ticks", Axis)`` for every drawn axis (its tick labels are counted apart)."""
    for child in artist.get_children():
        if not child.get_visible():
            continue
        if isinstance(child, Axes):
            parent = where if isinstance(artist, Axes) else None
            yield from _visible_texts(child, fig, _axes_name(child, fig, parent), "text")
        elif isinstance(child, Axis):
            if child.axes.axison:      # Axes drawn without axes ("off") draw no axis
                yield where, "ticks", child
                for text, name in ((child.label, "label"), (child.offsetText, "offset text")):
                    if text.get_visible() and text.get_text().strip():
                        yield where, f"{child.axis_name} {name}", text
        elif isinstance(child, Legend):
            yield from _visible_texts(child, fig, where, "legend text")
        elif isinstance(child, Text):
            if child.get_text().strip():
                axes = artist if isinstance(artist, Axes) else None
                titles = (axes.title, axes._left_title, axes._right_title) if axes else ()
                yield where, "title" if child in titles else what, child
        else:
            yield from _visible_texts(child, fig, where, what)


def _tick_labels(axis):
    """The tick labels an axis draws: non-empty, visible, within the view (major and minor)."""
    labels = []
    for tick in axis._update_ticks():
        if tick.get_visible():
            labels += [lab for lab in (tick.label1, tick.label2)
                       if lab.get_visible() and lab.get_text().strip()]
    return labels


def figure_problems(fig, column_in=COLUMN_IN, min_pt=MIN_PT, max_ticks=MAX_TICKS, *, tight=False):
    """What keeps a figure from reading at the text column's width, in a reader's words.

    A figure wider than the column is shown shrunk to it, so a text of ``s`` pt reads at
    ``s * min(1, column_in / width)`` pt. Every visible text counts: titles, axis labels, tick
    labels, legend texts, annotations and figure texts.

    Parameters
    ----------
    fig : matplotlib Figure
        The figure as it will be rendered (it is laid out here, without rendering).
    column_in : float, optional
        The width of the text column [in].
    min_pt : float, optional
        The smallest text size allowed at the column's width [pt].
    max_ticks : int, optional
        The most tick labels one axis may show.
    tight : bool, optional
        The figure is saved cropped to its content (``bbox_inches="tight"``, as IPython shows
        figures): its width is that of its content where that is wider than the figure.

    Returns
    -------
    list of str
        One sentence per problem: the figure too wide for its text, a group of texts too small
        (where, what, size and up to three of the texts), an axis with too many tick labels.
        Empty for a readable figure.

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> fig, ax = plt.subplots(figsize=(7, 4), layout="constrained")
    >>> _ = ax.plot([1, 2], label="a line")
    >>> _ = ax.legend(fontsize=7)
    >>> figure_problems(fig)
    ["axes 1: legend text at 7 pt reads at 7 pt (< 8.5 pt): 'a line'"]
    >>> _ = ax.legend(fontsize=9)
    >>> figure_problems(fig)
    []
    >>> plt.close(fig)
    """
    fig.draw_without_rendering()
    width = fig.get_figwidth()
    if tight:
        width = max(width, fig.get_tightbbox().width)
    scale = min(1.0, column_in / width)
    small, ticks, sizes = {}, [], []
    for where, what, obj in _visible_texts(fig, fig, "figure", "figure text"):
        texts = _tick_labels(obj) if what == "ticks" else [obj]
        if what == "ticks":
            if len(texts) > max_ticks:
                ticks.append(f"{where}: {len(texts)} tick labels on the {obj.axis_name} axis (> {max_ticks})")
            what = f"{obj.axis_name} tick labels"
        for text in texts:
            size = text.get_fontsize()
            sizes.append(size)
            if size * scale < min_pt:
                small.setdefault((where, what, size), []).append(text.get_text().replace(r"\mathdefault", ""))
    problems = []
    if sizes and width > column_in and min(sizes) * scale < min_pt:
        problems.append(f"the figure is {width:.3g} in wide, wider than the {column_in:g} in column: "
                        f"shrunk to it, its {min(sizes):g} pt text reads at {min(sizes) * scale:.3g} pt "
                        f"(< {min_pt:g} pt)")
    for (where, what, size), texts in small.items():
        shown = ", ".join(repr(t if len(t) <= 30 else t[:29] + "…") for t in texts[:3])
        more = f" and {len(texts) - 3} more" if len(texts) > 3 else ""
        problems.append(f"{where}: {what} at {size:g} pt reads at {size * scale:.3g} pt (< {min_pt:g} pt): "
                        f"{shown}{more}")
    return problems + ticks


def check_figures(column_in=COLUMN_IN, min_pt=MIN_PT, max_ticks=MAX_TICKS):
    """Make every figure rendered from now on in this process pass :func:`figure_problems`.

    Wraps ``FigureCanvasBase.print_figure``, which ``savefig`` and IPython's inline backend (a
    notebook's shown or glued figure) call to render a figure: a figure with problems raises
    instead of being rendered, so that a book built with warnings as errors stops at it. Called
    again, it replaces the thresholds of the earlier call.

    Parameters
    ----------
    column_in : float, optional
        The width of the text column [in].
    min_pt : float, optional
        The smallest text size allowed at the column's width [pt].
    max_ticks : int, optional
        The most tick labels one axis may show.

    Returns
    -------
    callable
        Called without arguments, removes the check.

    Raises
    ------
    ValueError
        When a figure with problems is rendered (not at this call): the message lists them.

    Examples
    --------
    >>> import io
    >>> import matplotlib.pyplot as plt
    >>> remove = check_figures()
    >>> fig, ax = plt.subplots(figsize=(10, 4))
    >>> fig.savefig(io.BytesIO())
    Traceback (most recent call last):
    ...
    ValueError: a figure does not read at the 7 in column: the figure is 10 in wide, ...
    >>> remove()
    >>> fig.savefig(io.BytesIO())
    >>> plt.close(fig)
    """
    current = FigureCanvasBase.print_figure
    original = getattr(current, "_unchecked", current)

    @functools.wraps(original)
    def print_figure(self, filename, *args, **kwargs):
        problems = figure_problems(self.figure, column_in, min_pt, max_ticks,
                                   tight=kwargs.get("bbox_inches") == "tight")
        if problems:
            raise ValueError(f"a figure does not read at the {column_in:g} in column: " + "; ".join(problems))
        return original(self, filename, *args, **kwargs)

    print_figure._unchecked = original
    FigureCanvasBase.print_figure = print_figure

    def remove():
        FigureCanvasBase.print_figure = original

    return remove
