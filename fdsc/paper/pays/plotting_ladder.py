"""The figure of chapter 'ladder' (summaries in, Axes out)."""

from fdsc.paper.shared.plotting import _axes

__all__ = ["KIND", "KIND_STYLE", "SHORT", "plot_ladder"]

#: The rungs' labels in the figure (the chapter's table and glossary say them in full).
SHORT = {"limit": "non-causal limit", "known tones": "tones known", "predictive": "predictive law",
         "scheduled at breaks": "feedforward per type, at the breaks",
         "scheduled": "feedforward per type, on ŵ", "best fixed (x, ŵ)": "best fixed (x, ŵ)",
         "best fixed (x)": "best fixed (x)", "gain switching": "gain switching on ŵ",
         "FDSC": "the paper's FDSC"}

#: What each rung is: a bound, a reference (not realizable), realizable, or a fixed controller.
KIND = {"limit": "bound", "known tones": "reference", "scheduled at breaks": "reference",
        "predictive": "realizable law", "scheduled": "realizable law",
        "gain switching": "realizable law",
        "FDSC": "realizable law", "best fixed (x, ŵ)": "fixed controller",
        "best fixed (x)": "fixed controller"}
#: Marker and colour per kind (colour-blind safe; red stays PassC-LF's in the book).
KIND_STYLE = {"bound": ("k", "D"), "reference": ("#7f7f7f", "s"), "realizable law": ("#0072b2", "o"),
              "fixed controller": ("#e69f00", "^")}


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
            ax.text(edge / 1.14 if m > hi else edge * 1.14, y, f"×{m:.3g}",
                    ha="right" if m > hi else "left", va="center", fontsize=8.5, color=color)
            continue
        ax.plot([max(a, lo), min(b, hi)], [y, y], color=color, lw=2.5, alpha=0.6, solid_capstyle="butt")
        ax.plot(m, y, marker=marker, color=color, ms=7, ls="none")
        ax.text(min(b, hi) * 1.02, y, f"×{m:.3f}", va="center", fontsize=8.5, color=color)
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
