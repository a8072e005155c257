"""The figure of chapter 'ladder' (summaries in, Axes out)."""

import math

import numpy as np

from fdsc.paper.shared.plotting import _axes
from fdsc.paper.shared.plotting_axes import LEGEND_FONTSIZE
from fdsc.paper.shared.prose import times

__all__ = ["KIND", "KIND_STYLE", "SHORT", "plot_ladder", "plot_excess_by_time", "plot_noise_levels",
           "NOISE_RUNGS"]

#: The rungs' labels in the figure (the chapter's table and glossary say them in full).
SHORT = {"limit": "non-causal limit", "known tones": "tones known", "predictive": "predictive law",
         "scheduled at breaks": "feedforward per type, at the breaks",
         "scheduled": "feedforward per type, on ŵ", "best fixed (x, ŵ)": "best fixed (x, ŵ)",
         "best found (x, ŵ)": "best found (x, ŵ)",
         "best fixed (x)": "best fixed (x)", "gain switching": "gain switching on ŵ",
         "FDSC": "the paper's FDSC"}

#: What each rung is: a bound, a reference (not realizable), realizable, or a fixed controller.
KIND = {"limit": "bound", "known tones": "reference", "scheduled at breaks": "reference",
        "predictive": "realizable law", "scheduled": "realizable law",
        "gain switching": "realizable law",
        "FDSC": "realizable law", "best fixed (x, ŵ)": "fixed controller",
        "best found (x, ŵ)": "fixed controller", "best fixed (x)": "fixed controller"}
#: Marker and colour per kind (colour-blind safe; red stays PassC-LF's in the book).
KIND_STYLE = {"bound": ("k", "D"), "reference": ("#7f7f7f", "s"), "realizable law": ("#0072b2", "o"),
              "fixed controller": ("#e69f00", "^")}


# a label's white ground: the reference line at ×1 does not strike a label through
_LABEL_BOX = {"facecolor": "white", "edgecolor": "none", "pad": 0.6, "alpha": 0.85}


def plot_ladder(summary: dict, ax=None, *, xlim=None, words=None, legend=True):
    """One example's ladder: per rung (top: the limit) the median ratio to the best fixed
    controller (x, ŵ) with its bootstrap 95 % interval, on a log axis; a rung beyond the axis is
    drawn at its edge with an arrow and its median written beside it.

    Parameters
    ----------
    summary : dict
        ``{rung: {"median", "low", "high"}}`` in the ladder's order.
    ax : Axes, optional
    xlim : (float, float), optional
        Default: from just below the lowest interval to ×2 at most (rungs beyond are drawn at the
        edge).
    words : dict, optional
        The rungs' labels (default :data:`SHORT`).
    legend : bool, optional

    Returns
    -------
    Axes
    """
    ax = _axes(ax, (7, 3.6))
    words = SHORT if words is None else words
    rungs = list(summary)
    if xlim is None:
        low = min(summary[r]["low"] for r in rungs)
        high = max(summary[r]["high"] for r in rungs if summary[r]["median"] <= 2.0)
        xlim = (max(0.3, low / 1.06), min(2.0, max(1.12, high * 1.12)))
    lo, hi = xlim
    for y, rung in enumerate(rungs):
        s = summary[rung]
        color, marker = KIND_STYLE[KIND.get(rung, "realizable law")]
        m, a, b = s["median"], s["low"], s["high"]
        if m > hi or m < lo:
            edge = hi if m > hi else lo
            ax.annotate("", xy=(edge, y), xytext=(edge / 1.12 if m > hi else edge * 1.12, y),
                        arrowprops={"arrowstyle": "->", "color": color, "lw": 1.5})
            ax.text(edge / 1.14 if m > hi else edge * 1.14, y, times(m),
                    ha="right" if m > hi else "left", va="center", fontsize=8.5, color=color, bbox=_LABEL_BOX)
            continue
        ax.plot([max(a, lo), min(b, hi)], [y, y], color=color, lw=2.5, alpha=0.6, solid_capstyle="butt")
        ax.plot(m, y, marker=marker, color=color, ms=7, ls="none")
        ax.text(min(b, hi) * 1.02, y, times(m), va="center", fontsize=8.5, color=color,  # as the prose
                bbox=_LABEL_BOX)
    ax.axvline(1.0, color="k", lw=0.8)
    ax.set_xscale("log")
    ax.set_xlim(lo, hi)
    span = hi / lo
    grid = (0.3, 0.5, 0.7, 1.0, 1.5, 2.0) if span > 3 else (0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.1, 1.2, 1.5, 2.0)
    ticks = [t for t in grid if lo <= t <= hi]
    ax.set_xticks(ticks, [f"×{t:g}" for t in ticks])
    ax.minorticks_off()
    ax.set_yticks(range(len(rungs)), [words.get(r, r) for r in rungs], fontsize=8.5)
    ax.set_ylim(len(rungs) - 0.5, -0.5)
    ax.set_xlabel("energy / best fixed (x, ŵ)'s: median, 95 % interval")
    ax.grid(True, axis="x", alpha=0.3)
    if legend:
        handles = [ax.plot([], [], marker=mk, color=c, ls="none", label=k)[0]
                   for k, (c, mk) in KIND_STYLE.items()]
        ax.legend(handles=handles, fontsize=8.5, loc="lower center", bbox_to_anchor=(0.5, 1.08), ncol=4,
                  frameon=False)
    return ax


def plot_excess_by_time(excess: dict, ax=None, *, label=None, color="#0072b2", offset=0.0, width=0.38):
    """Where the predictive law's excess over its tones known goes: per bin of time since the last
    break, the share of the whole excess energy (bars), with the excess per unit of the
    reference's energy in that bin written above each bar.

    Parameters
    ----------
    excess : dict
        ``{"edges", "excess", "reference", "seconds"}`` as the stored study keeps them (per draw
        and bin; an edge None is infinity).
    ax : Axes, optional
    label : str, optional
    color : str, optional
    offset, width : float, optional
        The bars' place within a bin's slot (two examples side by side).

    Returns
    -------
    Axes
    """
    ax = _axes(ax, (7, 3.2))
    edges = [math.inf if e is None else float(e) for e in excess["edges"]]
    ex = np.sum(np.asarray(excess["excess"], dtype=float), axis=0)
    ref = np.sum(np.asarray(excess["reference"], dtype=float), axis=0)
    share = ex / ex.sum()
    x = np.arange(share.size) + offset
    ax.bar(x, 100 * share, width=width, color=color, label=label)
    for xi, sh, e, r in zip(x, share, ex, ref, strict=True):
        if r > 0:
            ax.annotate(f"{100 * e / r:+.0f} %", (xi, 100 * max(sh, 0.0)), xytext=(0, 2),
                        textcoords="offset points", ha="center", va="bottom", fontsize=LEGEND_FONTSIZE,
                        rotation=90, color=color)
    # room above the tallest bar for its label (about 4 characters at the book's text size)
    ax.set_ylim(0, max(ax.get_ylim()[1], 100 * share.max() * 1.3))
    labels = [f"{_fmt(a)}–{_fmt(b)}" if math.isfinite(b) else f"≥ {_fmt(a)}"
              for a, b in zip(edges[:-1], edges[1:], strict=True)]
    ax.set_xticks(np.arange(share.size))
    ax.set_xticklabels(labels, rotation=30, ha="right")
    ax.set_xlabel("time since the last break of the disturbance (s)")
    ax.set_ylabel("share of the excess energy (%)")
    ax.axhline(0.0, color="k", lw=0.6)
    return ax


def _fmt(v):
    return f"{v:g}"


#: The rungs of :func:`plot_noise_levels`: label, kind (:data:`KIND_STYLE`) and line style.
NOISE_RUNGS = {"limit": ("non-causal limit (exact d)", "bound", ":"),
               "predictive (confident)": ("predictive law with a confidence check", "realizable law", "-"),
               "best fixed (x, ŵ)": ("best fixed (x, ŵ) at this noise", "fixed controller", "-"),
               "best fixed (x)": ("best fixed (x)", "fixed controller", "--")}


def plot_noise_levels(rows: list, ax=None, *, title=None, legend=True):
    """One example's ladder against the noise level: per rung the median ratio to the best fixed
    controller at that level with its bootstrap 95 % interval (bars), levels from the exact
    estimate (left) to the noisiest (right), on a log axis.

    Parameters
    ----------
    rows : list of dict
        :func:`fdsc.paper.pays.information.summary`: ``{"level", rung: (median, lo, hi, wins)}``.
    ax : Axes, optional
    title : str, optional
    legend : bool, optional

    Returns
    -------
    Axes
    """
    ax = _axes(ax, (7, 3.6))
    x = np.arange(len(rows))
    for k, (rung, (label, kind, ls)) in enumerate(NOISE_RUNGS.items()):
        if not all(rung in r for r in rows):
            continue
        color, marker = KIND_STYLE[kind]
        med = np.array([r[rung][0] for r in rows])
        lo = np.array([r[rung][1] for r in rows])
        hi = np.array([r[rung][2] for r in rows])
        dx = (k - 1.5) * 0.06                       # side by side where intervals would overlap
        mfc = "white" if ls == "--" else color
        ax.errorbar(x + dx, med, yerr=[med - lo, hi - med], color=color, marker=marker, ls=ls, lw=1.4, ms=6,
                    mfc=mfc, capsize=3, label=label)
    ax.axhline(1.0, color="#bbbbbb", lw=0.8, zorder=0)
    ax.set_yscale("log")
    ax.set_xticks(x, [r["level"] for r in rows])
    ax.set_xlabel("white noise on what the controllers sample (signal-to-noise ratio)")
    ax.set_ylabel("energy / best fixed at this noise")
    low = min(min(r[rung][1] for rung in NOISE_RUNGS if rung in r) for r in rows)
    ticks = [t for t in (0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.1, 1.2, 1.3) if t >= low * 0.95]
    ax.set_yticks(ticks, [f"{t:g}" for t in ticks])
    ax.minorticks_off()
    if title:
        ax.set_title(title, fontsize=10, loc="left")
    if legend:
        ax.legend(fontsize=LEGEND_FONTSIZE, loc="lower left", ncol=2, frameon=False)
    return ax

