"""Shared infrastructure, figures: the time-domain figures of the chapters on the law and on runs.

Chapters 'switching_law', 'simulations' 'nonstationary': the outputs and the running
L2-induced norm of paper Figs. 4-6, σ(t) of each law variant against the piecewise disturbance,
the sweeps of paper Figs. 7 and 8, and the objectives (P.1) and (P.2). Each takes a chapter's
result and returns the Axes.
"""

import matplotlib.pyplot as plt
import numpy as np

from fdsc.paper.shared.plotting_axes import (
    LEGEND_FONTSIZE,
    _axes,
    _below_legend,
    _label,
    symlog_axis,
)
from fdsc.paper.shared.style import style

__all__ = [
    "plot_l2_curves", "plot_outputs", "plot_p1", "plot_p2", "plot_sigma_timeline", "plot_sweep",
]


def plot_outputs(data, component: int, ax: plt.Axes | None = None, *, scale: dict | None = None,
                 names: list | None = None, head: bool = False,
                 linthresh: float | None = None) -> plt.Axes:
    """One output of z over time for each controller (paper Figs. 4 and 5).

    The whole run is drawn as the min/max envelope of each bin of the decimated record (a band
    that holds every sample, so oscillations faster than the bins are not aliased into a false
    slow wave); with ``head=True`` the start of the run is drawn sample by sample instead. The
    switched loops' bands are pale, with thin translucent edges, and drawn below the fixed
    controllers' lines; every band lies behind every line, so that no band hides a line. Where several
    fixed controllers are drawn, the first is drawn dashed on top of the wider later ones, so that
    near-equal outputs both show. The legend goes above the axes, once for a column of axes (on
    its top row).

    Parameters
    ----------
    data : StationaryRuns
        Result of :func:`fdsc.paper.reproduced.stationary.stationary_runs`.
    component : int
        0: 4q, 1: 2δ_E, 2: 2δ_PTV (the rows of z).
    ax : matplotlib Axes, optional
        Axes to draw on (default: a new figure).
    scale : dict, optional
        ``{controller: factor}`` applied before drawing (stated in the legend).
    names : list of str, optional
        Controllers to draw (default all).
    head : bool, optional
        Draw the full-resolution start of the run (``data.t_head``) instead of the envelope.
    linthresh : float, optional
        A symmetric-log vertical axis, linear within ±``linthresh``, with few ticks (default:
        linear).

    Returns
    -------
    matplotlib Axes
    """
    ax = _axes(ax)
    labels = ["$4q$ (pitch rate)", r"$2\delta_E$ (tail deflection)", r"$2\delta_{PTV}$ (nozzle deflection)"]
    n_fixed = 0
    for k, name in enumerate(data.z_lo):
        if names is not None and name not in names:
            continue
        st = style(name, k)
        color, ls = st["color"], st["linestyle"]
        # the switched loops' spikes are drawn lighter and below, so that the fixed gains'
        # smaller outputs stay visible on top of them; each later fixed gain is drawn below
        # and wider than the one before, so that near-equal outputs both show; every band lies
        # below every line (zorder 1 and 2 against 3 and up)
        fixed = not name.startswith("FDSC")
        z = 10 - n_fixed if fixed else 3
        n_fixed += fixed
        several = sum(not n.startswith("FDSC") for n in data.z_lo if names is None or n in names) > 1
        if fixed and n_fixed == 1 and several:
            ls = (0, (4, 2))
        f = (scale or {}).get(name, 1.0)
        lab = _label(name) if f == 1.0 else f"{_label(name)} × {f:g}"
        if head:
            ax.plot(data.t_head, f * data.z_head[name][:, component], color=color, ls=ls,
                    lw=0.9 if not fixed else 0.8 + 0.8 * n_fixed, zorder=z, label=lab)
        else:
            lo, hi = f * data.z_lo[name][:, component], f * data.z_hi[name][:, component]
            # a switched loop's band is pale and its edges thin and translucent, so that its
            # spikes do not swamp the fixed gains' lines drawn on top of it
            ax.fill_between(data.t, lo, hi, step="post", color=color, alpha=0.35 if fixed else 0.12,
                            lw=0, zorder=2 if fixed else 1)
            lw = 0.6 + 0.8 * n_fixed if fixed else 0.5
            for j, edge in enumerate((lo, hi)):  # edges keep a thin band visible where lo ≈ hi
                ax.plot(data.t, edge, color=color, ls=ls, lw=lw, alpha=1.0 if fixed else 0.55,
                        zorder=z, drawstyle="steps-post", label=None if j else lab)
    ax.set_xlabel("$t$ [s]")
    ax.set_ylabel(f"$z_{component + 1}$ = {labels[component]} [-]", fontsize=9)
    if linthresh is not None:
        symlog_axis(ax, "y", linthresh)
    spec = ax.get_subplotspec()
    if spec is not None and not spec.is_last_row():   # a column of axes shares the bottom's t
        ax.set_xlabel("")
    if spec is None or spec.is_first_row():
        handles, labels_ = ax.get_legend_handles_labels()
        leg = ax.legend(handles, labels_, fontsize=LEGEND_FONTSIZE, loc="lower center",
                        bbox_to_anchor=(0.5, 1.01), ncol=min(4, len(labels_)), borderaxespad=0,
                        frameon=False)
        for h in leg.legend_handles:   # the pale bands' colours at full strength in the legend
            h.set_alpha(1.0)
            h.set_linewidth(max(h.get_linewidth(), 1.2))
    return ax


def plot_l2_curves(data, ax: plt.Axes | None = None) -> plt.Axes:
    """Paper Fig. 6: the running L2-induced norm sqrt(∫zᵀz / ∫d²) over time for each controller,
    drawn as its min/max per bin of the decimated record (so its early oscillation is not aliased).

    Parameters
    ----------
    data : StationaryRuns
        Result of :func:`fdsc.paper.reproduced.stationary.stationary_runs` (HF disturbance for paper Fig. 6).
    ax : matplotlib Axes, optional
        Axes to draw on (default: a new figure).

    Returns
    -------
    matplotlib Axes
    """
    ax = _axes(ax)
    t = data.t_l2
    for k, name in enumerate(data.l2_lo):
        st = style(name, k)
        lo, hi = data.l2_lo[name], data.l2_hi[name]
        # translucent bands behind every line, so that no band covers another curve
        ax.fill_between(t, lo, hi, step="post", color=st["color"], alpha=0.12, lw=0, zorder=1)
        ax.plot(t, hi, color=st["color"], ls=st["linestyle"], lw=1.4, drawstyle="steps-post",
                zorder=3, label=_label(name))
    ax.set_xlabel("$t$ [s]")
    ax.set_ylabel(r"$\sqrt{\int_0^t z^\top z / \int_0^t d^2}$ [-]")
    ax.set_yscale("log")
    _below_legend(ax, ncol=3)
    return ax


def plot_sigma_timeline(data, ax: plt.Axes | None = None) -> plt.Axes:
    """σ(t) of each law variant (paper eq. (31)) against the piecewise disturbance (paper eq.
    (58)): stacked rows, segments marked.

    Parameters
    ----------
    data : SwitchingStatistics
        Result of :func:`fdsc.paper.reproduced.switching_law.switching_statistics`.
    ax : matplotlib Axes, optional
        Axes to draw on (default: a new figure).

    Returns
    -------
    matplotlib Axes
    """
    ax = _axes(ax, figsize=(7, 3.2))
    variants = list(data.variants.items())
    as_controller = {"paper Q, measured ẋ": "FDSC", "paper Q, candidate ẋ": "FDSC (candidate ẋ)",
                     "our Q, measured ẋ": "FDSC (our Q)"}
    for k, (label, v) in enumerate(variants):
        ax.fill_between(data.t, k, k + 0.8 * v.sigma, step="post", alpha=0.8, lw=0,
                        color=style(as_controller.get(label, label), k)["color"])
    for b in data.breaks[1:-1]:
        ax.axvline(b, color="k", ls=":", lw=1)
    # each row named beside it, with its count of switches (no legend to match colours against)
    names = [f"{_label(lab)}\n{v.switches:,} switches" for lab, v in variants]
    ax.set_yticks([k + 0.4 for k in range(len(variants))], names, fontsize=LEGEND_FONTSIZE)
    ax.set_ylim(-0.15, len(variants) - 0.05)
    ax.set_xlabel("$t$ [s]  (dotted: disturbance switches HF → LF → HF)")
    ax.set_title(f"share of each {data.bin * 1e3:g} ms bin on PassC-HF ($K_2$): full bar = all of it,\n"
                 "no bar = all on PassC-LF ($K_1$)", fontsize=LEGEND_FONTSIZE)
    return ax


def plot_sweep(data, ax: plt.Axes | None = None, *, names: list | None = None, scale: dict | None = None,
               log: bool = False, crossover: dict | None = None, legend: str | None = "inside") -> plt.Axes:
    """Output energy against the sweep parameter (paper Figs. 7 and 8), one line per controller.

    Parameters
    ----------
    data : SweepRuns
        :func:`fdsc.paper.reproduced.nonstationary.mixed_sweep`,
        :func:`~fdsc.paper.reproduced.nonstationary.piecewise_sweep` or
        :func:`~fdsc.paper.reproduced.nonstationary.extended_piecewise`.
    ax : matplotlib Axes, optional
        Axes to draw on (default: a new figure).
    names : list of str, optional
        Controllers to draw (default all).
    scale : dict, optional
        ``{controller: factor}`` applied before drawing (stated in the legend), as the paper
        scales PassC-HF.
    log : bool, optional
        Logarithmic energy axis.
    crossover : dict, optional
        ``{label: parameter value}`` drawn as vertical lines.
    legend : {"inside", "below", None}, optional
        Where to put the legend: inside the Axes where it covers the fewest points, below them
        (for a figure as narrow as the text column), or nowhere (None: no labels either, for a
        second call on the same Axes).

    Returns
    -------
    matplotlib Axes
    """
    ax = _axes(ax)
    for k, name in enumerate(names or data.names):
        st = style(name, k)
        f = (scale or {}).get(name, 1.0)
        ax.plot(data.param, f * data.energy[name], ms=4, mfc="none",
                label=None if legend is None else _label(name, f), **st)
    line_styles = (("0.2", "--"), ("tab:olive", "-."), ("tab:cyan", ":"))
    for (label, x), (color, ls) in zip((crossover or {}).items(), line_styles, strict=False):
        if x is not None:
            ax.axvline(x, color=color, ls=ls, lw=1.2, label=label)
    sym = r"\rho_p" if data.family == "mixed" else r"\rho_t"
    span = (r"$[0, 500]$" if data.family == "mixed" else r"$[0, 1000 + 500\rho_t]$")
    ax.set_xlabel(f"${sym}$ [-]")
    ax.set_ylabel(rf"$\int z^\top z\,dt$ over {span} [-]")
    if log:
        ax.set_yscale("log")
    if legend == "below":
        _below_legend(ax)
    elif legend == "inside":
        ax.legend(fontsize=LEGEND_FONTSIZE, loc="best")
    return ax


def plot_p1(data, ax: plt.Axes | None = None, *, names: tuple | None = None) -> plt.Axes:
    """(P.1): long-run √(∫zᵀz/∫d²) along the ρ_p sweep, with γ(Ω_in, K_in), the printed bound and
    the in-band controller's own ratio under the in-band disturbance.

    Parameters
    ----------
    data : P1Result
        :func:`fdsc.paper.reproduced.nonstationary.p1_global`.
    ax : matplotlib Axes, optional
        Axes to draw on (default: a new figure).
    names : tuple of str, optional
        Controllers to draw (default every controller of the result).

    Returns
    -------
    matplotlib Axes
    """
    ax = _axes(ax)
    rows = data.rows[1:]  # the ρ_p sweep (the first row is the LF disturbance)
    rho = np.array([r.rho_p for r in rows])
    for k, name in enumerate(names or tuple(rows[0].tail_ratio)):
        ax.plot(rho, np.sqrt([r.tail_ratio[name] for r in rows]), ms=4, mfc="none",
                label=_label(name), **style(name, k))
    ax.axhline(data.gamma_in, color="k", ls="--", lw=1,
               label=rf"$\gamma(\Omega_{{in}}, K_{{in}})$ = {data.gamma_in:.4f} "
                     r"(band peak, printed $K_{f_3}$)")
    ax.axhline(data.gamma_in_printed, color="k", ls=":", lw=1,
               label=f"bound printed beside $K_{{f_3}}$: {data.gamma_in_printed:g}")
    ax.axhline(np.sqrt(rows[0].tail_ratio["PassC-HF"]), color=style("PassC-HF")["color"], ls="-.", lw=1,
               label=r"PassC-HF under the HF tones alone ($\rho_p = 0$)")
    ax.set_xlabel(r"$\rho_p$ [-]  (in-band dominance $\alpha(\Omega_3) = 1/(1 + \rho_p^2)$)")
    ax.set_ylabel(r"$\sqrt{\int z^\top z / \int d^2}$ over $[250, 500]$ [-]")
    ax.set_yscale("log")
    _below_legend(ax, ncol=2, y=-0.18)
    return ax


def plot_p2(data, ax: plt.Axes | None = None) -> plt.Axes:
    """(P.2): the worst localized √(∫zᵀz/∫d²) against the window length, with γ_tol.

    Parameters
    ----------
    data : P2Result
        :func:`fdsc.paper.reproduced.nonstationary.p2_localized`.
    ax : matplotlib Axes, optional
        Axes to draw on (default: a new figure).

    Returns
    -------
    matplotlib Axes
    """
    ax = _axes(ax)
    w = np.array(data.windows)
    for k, name in enumerate(data.worst[data.windows[0]]):
        st = style(name, k)
        # markers only: three window lengths, nothing is known between them
        ax.plot(w, [data.worst[x][name] for x in data.windows], color=st["color"], ls="none",
                marker=st["marker"], ms=6, label=_label(name))
    ax.axhline(data.gamma_tol, color="k", ls="--", lw=1,
               label=rf"$\gamma_{{tol}}$ = {data.gamma_tol:g} (ours)")
    ax.axhline(data.gamma_out_in, color="k", ls=":", lw=1,
               label=rf"$\gamma(\Omega_1, K_{{f_3}})$ = {data.gamma_out_in:.4g}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("window length $T_l$ [s]")
    ax.set_ylabel(r"largest $\sqrt{\int_{T_l} z^\top z / \int_{T_l} d^2}$ [-]")
    _below_legend(ax, ncol=3, y=-0.2)
    return ax
