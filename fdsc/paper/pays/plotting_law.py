"""Figures of the chapter 'disturbance_law' (result in, Axes out)."""

import numpy as np

from fdsc.paper.shared.plotting import _axes
from fdsc.paper.shared.style import band_color, style

__all__ = ["plot_law_run", "plot_law_cdf", "plot_front", "plot_law_rho_t"]


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
            top.semilogy(t[1:], np.maximum(mu[1:, i], 1e-300), color=st["color"], ls=st["linestyle"],
                         lw=1, label=name)
    lo = np.quantile(mu[1:][mu[1:] > 0], 0.02)
    top.set_ylim(lo, mu.max() * 3)
    top.set_ylabel(r"monitoring signal $\mu_i$ [-]")
    top.legend(fontsize=7, ncol=3, loc="lower right")
    edges = np.r_[0.0, lr.run.switch_times, lr.run.horizon]
    y = [lr.names.index(lr.names[s]) for s in lr.run.sequence]
    bottom.stairs(y, edges, color="k", lw=1.2, baseline=None)
    bottom.set_yticks(range(len(lr.names)), lr.names, fontsize=7)
    bottom.set_ylim(-0.5, len(lr.names) - 0.5)
    bottom.set_xlabel("t [s]")
    bottom.set_ylabel("active gain")
    for ax in (top, bottom):
        ax.set_xlim(0, lr.run.horizon)
        ax.grid(True, alpha=0.3)
    return top, bottom


def plot_law_cdf(full, example, ax=None):
    """Empirical distribution, over the test draws, of the energy over the fixed gain chosen in
    advance: the law, the band-power law, the least-energy fixed gain of each draw, the clairvoyant
    oracle and the ideal segment law.

    Parameters
    ----------
    full : dict
        The full study (:func:`fdsc.paper.pays.disturbance_law.load_full`).
    example : str
    ax : Axes, optional

    Returns
    -------
    Axes
    """
    ax = _axes(ax, (7, 4))
    r = full[example]
    adv = r["fixed_in_advance"]
    fixed = r["fixed_ratio_vs_fixed_in_advance"]
    best = np.min(np.array(list(fixed.values())), axis=0)
    series = (("law on ŵ", r["ratio_vs_fixed_in_advance"]),
              ("band-power law", r["band_power_ratio_vs_fixed_in_advance"]),
              ("least-energy fixed gain of each draw", best),
              ("clairvoyant oracle", r["oracle_ratio"]),
              ("ideal segment law", r["ideal_ratio"]))
    for k, (name, v) in enumerate(series):
        v = np.sort(np.asarray(v))
        st = style(name if name != "least-energy fixed gain of each draw" else "front 2", k)
        ax.step(v, np.arange(1, v.size + 1) / v.size, where="post", color=st["color"],
                ls=st["linestyle"], lw=1.4, label=name)
    ax.axvline(1.0, color="0.3", lw=0.8)
    ax.set_xscale("log")
    ticks = [0.25, 0.5, 1.0, 2.0, 4.0]
    ax.set_xticks(ticks, [f"{t:g}" for t in ticks])
    ax.minorticks_off()
    ax.set_xlabel(f"energy / energy of {adv} (chosen in advance) [-]")
    ax.set_ylabel("share of test draws [-]")
    ax.set_ylim(0, 1)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="lower right")
    return ax


def plot_front(front, peaks, ax=None):
    """The Pareto front in the (LF peak, HF peak) plane with the comparator set's gains.

    Parameters
    ----------
    front : fdsc.ParetoFront
    peaks : dict
        ``{name: (LF peak, HF peak)}`` of the other fixed gains.
    ax : Axes, optional

    Returns
    -------
    Axes
    """
    ax = _axes(ax, (6, 4))
    pts = [p for p in front.points if p is not None]
    ax.plot([p.peak[1] for p in pts], [p.peak[0] for p in pts], color="#3182bd", lw=1, zorder=1)
    for j, p in enumerate(pts):
        st = style(f"front {j + 1}", j)
        ax.plot(p.peak[1], p.peak[0], marker=st["marker"], color=st["color"], ls="none",
                label=f"front {j + 1} (β = {p.beta:.3g})")
    for k, (name, (lf, hf)) in enumerate(peaks.items()):
        st = style(name, k)
        ax.plot(lf, hf, marker=st["marker"], color=st["color"], ls="none", label=name)
    ax.set_xlabel(r"LF band peak $\gamma_{LF}$ [-]")
    ax.set_ylabel(r"HF band peak $\gamma_{HF}$ [-]")
    ax.margins(0.15)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=6, loc="best")
    return ax


def plot_law_rho_t(entries, ax=None):
    """The law's energy over the best fixed gain of the comparator set along the ρ_t family of
    each example.

    Parameters
    ----------
    entries : dict
        ``{example: {"rho_t": [...], "ratio_vs_best_fixed": [...]}}``.
    ax : Axes, optional

    Returns
    -------
    Axes
    """
    ax = _axes(ax, (7, 3.5))
    marks = {"aircraft": ("tab:red", "o"), "generic": ("tab:blue", "s")}
    for name, e in entries.items():
        color, m = marks.get(name, ("k", "."))
        ax.plot(e["rho_t"], e["ratio_vs_best_fixed"], color=color, marker=m, ms=4, lw=1, label=name)
    ax.axhline(1.0, color="0.3", lw=0.8)
    ax.set_xlabel(r"$\rho_t$ [-]")
    ax.set_ylabel("energy / best fixed [-]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    return ax
