"""Shared infrastructure, figures: the axes helpers of the plotting modules.

A new Axes when none is given, a symmetric-log axis with few ticks, the legend text of a
controller and a legend outside the Axes (to their right or below them).
"""

import math

import matplotlib.pyplot as plt
from matplotlib.ticker import FixedLocator, NullLocator

__all__ = []

#: Legend text size [pt] of a figure drawn at the text column's width (about 7 in): at least the
#: 8.5 pt the book asks of the text in its figures.
LEGEND_FONTSIZE = 9


def _symlog(ax, axis, linthresh, *, per_side=3):
    """A symmetric-log axis with few ticks: 0 and at most ``per_side`` powers of ten on each side
    (a default symlog axis labels every decade, dozens of labels over a wide range)."""
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


def _outside_legend(ax):
    ax.legend(fontsize=8.5, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)


def _below_legend(ax, ncol=2):
    """The legend under the Axes (and under their x label), for a figure too narrow for a legend
    beside it."""
    ax.legend(fontsize=LEGEND_FONTSIZE, loc="upper center", bbox_to_anchor=(0.5, -0.16),
              ncol=ncol, borderaxespad=0, frameon=False)


def _axes(ax, figsize=(7, 4)):
    if ax is None:
        _, ax = plt.subplots(figsize=figsize, layout="constrained")
    return ax
