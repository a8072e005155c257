"""Figures of the chapters 'ladder' and 'disturbance_law' (result in, Axes out)."""

import math

import numpy as np

from fdsc.paper.shared.plotting import _axes, _minor_label, plain_log_ticks
from fdsc.paper.shared.plotting_axes import LEGEND_FONTSIZE
from fdsc.paper.shared.prose import times
from fdsc.paper.shared.style import FAMILY_STYLES, MARK_COLOR, band_color, family_style, style

__all__ = ["plot_law_run", "plot_ratio_cdf", "plot_fixed_plane", "plot_family_ratios",
           "plot_switch_tradeoff", "plot_law_rho_t"]


def plot_law_run(lr, axes):
    """A draw under the law: the monitoring signals of the candidates (log scale) over the
    pieces of the disturbance, shaded by the band that dominates each, and the active candidate.

    Parameters
    ----------
    lr : LawRun
    axes : (Axes, Axes)
        Top: monitoring signals; bottom: active candidate.

    Returns
    -------
    (Axes, Axes)
    """
    top, bottom = axes
    d = lr.draw
    for a, b, dom in zip(d.d.breaks[:-1], d.d.breaks[1:], d.dominant, strict=True):
        for ax in (top, bottom):
            ax.axvspan(a, b, color=band_color(dom), alpha=0.12, lw=0)
    t, mu = lr.run.t_mu, lr.run.mu
    keep = np.any(mu > 0, axis=0)
    for i, name in enumerate(lr.names):
        if keep[i]:
            st = style(name, i)
            top.semilogy(t[1:], np.maximum(mu[1:, i], 1e-300), color=st["color"],
                         ls=("-", "--", "-.", ":")[i % 4], lw=1.2, label=name)
    lo = np.quantile(mu[1:][mu[1:] > 0], 0.02)
    top.set_ylim(lo, mu.max() * 3)
    top.set_ylabel(r"monitoring signal $\mu_i$ [-]")
    top.legend(fontsize=LEGEND_FONTSIZE, ncol=2, loc="lower right")
    edges = np.r_[0.0, lr.run.switch_times, lr.run.horizon]
    bottom.stairs(list(lr.run.sequence), edges, color="k", lw=1.2, baseline=None)
    bottom.set_yticks(range(len(lr.names)), lr.names, fontsize=LEGEND_FONTSIZE)
    bottom.set_ylim(-0.5, len(lr.names) - 0.5)
    bottom.set_xlabel("t [s]")
    bottom.set_ylabel("active controller")
    for ax in (top, bottom):
        ax.set_xlim(0, lr.run.horizon)
        ax.grid(True, alpha=0.3)
    return top, bottom


def plot_ratio_cdf(series, reference, ax=None, *, xlim=None):
    """Empirical distributions, over test draws, of energies over the fixed controller chosen
    in advance's; a curve beyond the axis is named in its label with its median.

    Parameters
    ----------
    series : dict
        ``{label: ratios}``, drawn in this order with one colour and line style each.
    reference : str
        The name of the fixed controller chosen in advance (the axis label).
    ax : Axes, optional
    xlim : (float, float), optional
        The axis' range (default: from the 1st to the 99th percentile of the curves whose median
        lies in [¼, 4], with 1 included, so that curves close to 1 are told apart).

    Returns
    -------
    Axes
    """
    ax = _axes(ax, (7, 4))
    if xlim is None:
        xlim = _ratio_range(series)
    colors = ("darkgreen", "#1b9e77", "k", "#7570b3", "tab:purple", "tab:brown", "0.5", "tab:orange")
    styles = ("-", "--", ":", "-.", "-", "--", ":", "-.")
    for k, (name, v) in enumerate(series.items()):
        v = np.sort(np.asarray(v, dtype=float))
        med = float(np.median(v))
        label = name if xlim[0] <= med <= xlim[1] else f"{name} (median {times(med)}, off the axis)"
        ax.step(v, np.arange(1, v.size + 1) / v.size, where="post", color=colors[k % len(colors)],
                ls=styles[k % len(styles)], lw=1.5, label=label)
    ax.axvline(1.0, color="0.3", lw=0.8)
    ax.set_xscale("log")
    ax.set_xlim(*xlim)
    # fine ticks for a narrow axis (curves near 1), coarse ones for a wide one
    ticks = [t for t in (_TICKS if xlim[1] / xlim[0] < 2.5 else _COARSE) if xlim[0] <= t <= xlim[1]]
    while len(ticks) > 7:                          # keep 1 and every other tick about it
        k = ticks.index(1.0)
        ticks = [t for i, t in enumerate(ticks) if (i - k) % 2 == 0]
    ax.set_xticks(ticks, [f"{t:g}" for t in ticks])
    ax.minorticks_off()
    ax.set_xlabel(f"energy / energy of {reference} [-]")
    ax.set_ylabel("share of test draws [-]")
    ax.set_ylim(0, 1)
    ax.grid(True, which="both", alpha=0.3)
    # below the axes: inside, it would cover the far curves of one example or another
    ax.legend(fontsize=LEGEND_FONTSIZE, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=2)
    return ax


_TICKS = (0.25, 0.5, 0.75, 0.8, 0.85, 0.9, 0.95, 1.0, 1.05, 1.1, 1.2, 1.3, 1.5, 1.75, 2.0, 3.0, 4.0)
_COARSE = (0.25, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 4.0)


def _ratio_range(series):
    """The axis range of :func:`plot_ratio_cdf`: the 1st–99th percentiles of the curves whose
    median lies in [¼, 4] (1 included), widened by 3 % on the log scale, within [¼, 4]."""
    lo, hi = 1.0, 1.0
    for v in series.values():
        v = np.asarray(v, dtype=float)
        v = v[np.isfinite(v) & (v > 0)]
        if v.size and 0.25 <= np.median(v) <= 4.0:
            lo, hi = min(lo, float(np.quantile(v, 0.01))), max(hi, float(np.quantile(v, 0.99)))
    pad = 0.03 * math.log(hi / lo) if hi > lo else 0.05
    return max(0.25, lo * math.exp(-pad)), min(4.0, hi * math.exp(pad))


def plot_fixed_plane(points, chosen, ax=None, *, top=None, zoom=None, zoom_at=(0.3, 0.42, 0.42, 0.5),
                     named=None):
    """Every fixed controller in the plane of its LF and HF band peaks, by family; the static and
    dynamic fronts joined by lines, the one chosen in advance ringed.

    Parameters
    ----------
    points : dict
        ``{name: (family, LF peak, HF peak)}``.
    chosen : str
    ax : Axes, optional
    top : float, optional
        Peaks above it are off the axes (the caller names them in the caption).
    zoom : (float, float, float, float), optional
        ``(LF low, LF high, HF low, HF high)``: an inset magnifies this box (linear axes), its
        place marked on the main axes.
    zoom_at : (float, float, float, float), optional
        Where the inset sits, in axes fractions ``(x, y, width, height)``.
    named : str, optional
        A family whose members are labelled by name where they are drawn (in the inset where the
        inset shows them); members that coincide on the page share one label.

    Returns
    -------
    (Axes, list of str)
        The axes and the names left off.

    Raises
    ------
    KeyError
        If a point's family has no style (:data:`fdsc.paper.shared.style.FAMILY_STYLES`).
    """
    ax = _axes(ax, (6, 4.5))
    unknown = sorted({f for f, _lf, _hf in points.values()} - set(FAMILY_STYLES))
    if unknown:
        # a family without a style would be left out of a figure that says it shows every controller
        raise KeyError(f"points: the families {unknown} have no style "
                       f"(FAMILY_STYLES has {list(FAMILY_STYLES)})")
    off, seen = [], set()
    for fam in FAMILY_STYLES:
        members = [(n, lf, hf) for n, (f, lf, hf) in points.items() if f == fam]
        inside = [(n, lf, hf) for n, lf, hf in members
                  if np.isfinite(lf) and np.isfinite(hf) and (top is None or max(lf, hf) <= top)]
        off += [n for n, _lf, _hf in members if (n, _lf, _hf) not in inside]
        if not inside:
            continue
        st = family_style(fam)
        xs, ys = [p[1] for p in inside], [p[2] for p in inside]
        if fam in ("static front", "dynamic front"):
            order = np.argsort(xs)
            ax.plot(np.array(xs)[order], np.array(ys)[order], color=st["color"], lw=0.8, zorder=1)
        ax.plot(xs, ys, ls="none", marker=st["marker"], color=st["color"], ms=6,
                label=fam if fam not in seen else None, zorder=2)
        seen.add(fam)
    if chosen in points and np.isfinite(points[chosen][1]):
        _f, lf, hf = points[chosen]
        ax.plot(lf, hf, ls="none", marker="o", ms=14, mfc="none", mec=MARK_COLOR, mew=1.5,
                label="chosen in advance", zorder=3)
    ax.set_xscale("log")
    ax.set_yscale("log")
    # plain numbers on the log axes (0.4, not 4 × 10⁻¹)
    from matplotlib.ticker import FuncFormatter, MaxNLocator

    plain = FuncFormatter(lambda v, _pos: f"{v:g}")
    for axis in (ax.xaxis, ax.yaxis):
        axis.set_major_formatter(plain)
        axis.set_minor_formatter(FuncFormatter(_minor_label))
    ax.set_xlabel(r"LF band peak $\gamma_{LF}$ [-]")
    ax.set_ylabel(r"HF band peak $\gamma_{HF}$ [-]")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=LEGEND_FONTSIZE, loc="best")
    if zoom is not None:
        inset = ax.inset_axes(list(zoom_at))
        box = {n: p for n, p in points.items()
               if zoom[0] <= p[1] <= zoom[1] and zoom[2] <= p[2] <= zoom[3]}
        plot_fixed_plane(box, chosen, inset)
        inset.set_xscale("linear")
        inset.set_yscale("linear")
        inset.set_xlim(zoom[0], zoom[1])
        inset.set_ylim(zoom[2], zoom[3])
        inset.set_xlabel("")
        inset.set_ylabel("")
        # few ticks, at the size of the book's text: the inset is small
        inset.xaxis.set_major_locator(MaxNLocator(3))
        inset.yaxis.set_major_locator(MaxNLocator(3))
        inset.tick_params(labelsize=LEGEND_FONTSIZE)
        inset.get_legend().remove()
        ax.indicate_inset_zoom(inset, edgecolor="0.4")
        if named is not None:
            _name_members(inset, points, named)
    if named is not None:
        _name_members(ax, points, named)
    return ax, off


def _name_members(ax, points, family):
    """Label the members of ``family`` drawn inside ``ax`` (not those an inset of ``ax`` shows)."""
    def inside(a, lf, hf):
        (x0, x1), (y0, y1) = a.get_xlim(), a.get_ylim()
        return x0 <= lf <= x1 and y0 <= hf <= y1

    groups = {}
    for name, (fam, lf, hf) in points.items():
        if fam != family or not inside(ax, lf, hf) or any(inside(c, lf, hf) for c in ax.child_axes):
            continue
        fx, fy = ax.transAxes.inverted().transform(ax.transData.transform((lf, hf)))
        near = next((k for k in groups if abs(k[0] - fx) < 0.03 and abs(k[1] - fy) < 0.03), (fx, fy))
        groups.setdefault(near, []).append((name, lf, hf, fx))
    order = sorted(groups.values(), key=lambda m: m[0][3])
    placed = []          # (fx, fy, above) of the labels drawn so far, in axes fractions
    for k, members in enumerate(order):
        _name, lf, hf, fx = members[0]
        fy = ax.transAxes.inverted().transform(ax.transData.transform((lf, hf)))[1]
        crowded = k + 1 < len(order) and order[k + 1][0][3] - fx < 0.12   # a label follows close by
        # left of a point near the left edge, right-aligned near the right edge or before a close
        # neighbour, below and to the right elsewhere
        dx, dy, ha = ((6, -3, "left") if fx < 0.12 else (-5, -3, "right") if fx < 0.35
                      else (-4, -10, "right") if fx > 0.6 or crowded else (4, -10, "left"))
        # a label near one already drawn goes to the other side of its point (above or below)
        clash = [a for x, y, a in placed if abs(x - fx) < 0.15 and abs(y - fy) < 0.08]
        above = bool(clash) and not clash[-1]
        if above:
            dy = 8
        placed.append((fx, fy, above))
        ax.annotate(", ".join(m[0] for m in members), (lf, hf), xytext=(dx, dy),
                    textcoords="offset points", fontsize=LEGEND_FONTSIZE, ha=ha)


def plot_family_ratios(ratios, reference, ax=None):
    """Box plots, over test draws, of the best member of each family over the fixed controller
    chosen in advance (log scale).

    Parameters
    ----------
    ratios : dict
        ``{label: ratios}`` in the order drawn.
    reference : str
    ax : Axes, optional

    Returns
    -------
    Axes
    """
    ax = _axes(ax, (7, 3.8))
    labels = list(ratios)
    ax.boxplot([np.asarray(ratios[k], dtype=float) for k in labels], vert=False, whis=(5, 95),
               showfliers=False, medianprops={"color": "k"})
    ax.set_yticks(range(1, len(labels) + 1), labels, fontsize=LEGEND_FONTSIZE)
    ax.axvline(1.0, color=MARK_COLOR, lw=0.8)
    ax.set_xscale("log")
    plain_log_ticks(ax.xaxis)
    ax.set_xlabel(f"energy / energy of {reference} (5–95 % whiskers) [-]")
    ax.grid(True, which="both", axis="x", alpha=0.3)
    return ax


#: The names of a law setting's parts in the legends, as in the law chapter's tables.
_LAW_LABEL = {"cost": "predictive-cost supervisor", "band_power": "band-power law"}
_CAND_LABEL = {"gains": "gains", "ideal pair": "PassC-LF/HF", "tuned pair": "tuned gains",
               "tuned filtered pair": "tuned filtered"}


def plot_switch_tradeoff(table, chosen, limit, ax=None, *, top=2.0):
    """Every law setting on the training draws: energy against switches per change of the
    dominating band, one marker per candidate set and law; the switching limit and the chosen
    setting marked. Settings above ``top`` are left off the axes (named in the returned list).

    Parameters
    ----------
    table : list of dict
        ``{"law", "log_ratio", "switches_per_change"}`` per setting.
    chosen : str
    limit : float
    ax : Axes, optional
    top : float, optional
        The axis' upper end (geometric-mean ratio).

    Returns
    -------
    (Axes, list of str)
    """
    ax = _axes(ax, (7, 4))
    groups = {}
    for row in table:
        cand, law = row["law"].split("/")[:2]
        groups.setdefault(f"{_LAW_LABEL.get(law, law)}, {_CAND_LABEL.get(cand, cand)}", []).append(row)
    marks = ("o", "s", "^", "D", "v", "P")
    colors = ("0.45", "goldenrod", "tab:blue", "tab:cyan", "darkgreen", "#1b9e77")
    off, low = [], []
    for k, (label, rows) in enumerate(groups.items()):
        keep = [r for r in rows if np.exp(r["log_ratio"]) <= top]
        if len(keep) < len(rows):
            off.append(label)
        if not keep:
            continue
        low += [np.exp(r["log_ratio"]) for r in keep]
        ax.plot([r["switches_per_change"] for r in keep], [np.exp(r["log_ratio"]) for r in keep],
                ls="none", marker=marks[k % len(marks)], color=colors[k % len(colors)], ms=6, label=label)
    pick = next(r for r in table if r["law"] == chosen)
    ax.plot(pick["switches_per_change"], np.exp(pick["log_ratio"]), ls="none", marker="o", ms=14,
            mfc="none", mec=MARK_COLOR, mew=1.5, label="chosen")
    ax.axvline(limit, color=MARK_COLOR, lw=0.8, ls="--", label="switching limit")
    ax.axhline(1.0, color="0.3", lw=0.8)
    ax.set_xscale("symlog", linthresh=1.0)
    ax.set_xlim(left=0)
    ax.set_ylim(0.98 * min(low + [1.0]), top)
    ax.set_xlabel("switches per change of the dominating band [-]")
    ax.set_ylabel("geometric-mean energy ratio [-]")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=LEGEND_FONTSIZE, loc="upper left")   # off the switching limit and the costly laws
    return ax, off


def plot_law_rho_t(entries, ax=None):
    """The law's energy over the fixed controller chosen in advance along the ρ_t family of
    each example.

    Parameters
    ----------
    entries : dict
        ``{example: {"rho_t": [...], "ratio_vs_fixed_in_advance": [...]}}``.
    ax : Axes, optional

    Returns
    -------
    Axes
    """
    ax = _axes(ax, (7, 3.5))
    marks = {"aircraft": ("tab:blue", "o"), "generic": ("0.3", "s")}
    for name, e in entries.items():
        color, m = marks.get(name, ("k", "."))
        ax.plot(e["rho_t"], e["ratio_vs_fixed_in_advance"], color=color, marker=m, ms=4, lw=1, label=name)
    ax.axhline(1.0, color="0.3", lw=0.8)
    ax.set_xlabel(r"$\rho_t$ [-]")
    ax.set_ylabel("energy / chosen in advance [-]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=LEGEND_FONTSIZE)
    return ax
