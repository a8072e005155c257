"""Figure helpers: each takes data returned by :mod:`fdsc.experiments` and returns Axes.

Only the plotting modules import matplotlib (this one, :mod:`fdsc.paper.shared.plotting_axes`,
:mod:`fdsc.paper.shared.plotting_runs`, whose figures are re-exported here, and the figures of the
does-FDSC-pay chapters). No function calls ``plt.show()`` or changes rcParams.
"""

import math

import matplotlib.pyplot as plt
import numpy as np
from matplotlib import patheffects

from fdsc import envelope
from fdsc.paper.shared.plotting_axes import LEGEND_FONTSIZE, _axes, _below_legend, symlog_axis
from fdsc.paper.shared.plotting_runs import (
    plot_l2_curves,
    plot_outputs,
    plot_p1,
    plot_p2,
    plot_sigma_timeline,
    plot_sweep,
)
from fdsc.paper.shared.style import STYLES, VERDICT_COLORS, band_color, style

__all__ = [
    "plain_log_ticks",
    "plot_psi_weights",
    "plot_dominance_vs_rho",
    "plot_localized_dominance",
    "plot_sigma_sweep",
    "plot_hf_sigma_scan",
    "plot_gap",
    "plot_power_vs_alpha",
    "plot_epf_series",
    "plot_prop1_cases",
    "plot_fdsc_diagram",
    "plot_outputs",
    "plot_l2_curves",
    "plot_sigma_timeline",
    "plot_sweep",
    "plot_p1",
    "plot_p2",
]


#: ``{controller: (colour, line style)}``, from the book's one style map (:mod:`fdsc.paper.shared.style`).
CONTROLLER_STYLES = {name: (color, ls) for name, (color, _, ls) in STYLES.items()}

#: ``{band: colour}``: a band is drawn in the colour of the controller designed for it.
BAND_COLORS = {band: band_color(band) for band in ("LF", "MF", "HF", "EF")}


#: ``{band: hatch}`` of a band's shading: the bands stay apart where their colours are close
#: (MF's olive and HF's goldenrod) or printed in grey.
BAND_HATCHES = {"LF": "\\\\", "MF": "..", "HF": "//", "EF": "xx"}


def plot_psi_weights(result, kind, ax=None, *, real_part=True):
    """Weight ``[jω;1]*Ψ[jω;1]`` of one band over ±ω (symlog axes), the band shaded, hatched and
    named where it lies.

    Parameters
    ----------
    result : fdsc.paper.reproduced.frequency_ranges.PsiWeights
        Output of :func:`fdsc.paper.reproduced.frequency_ranges.psi_weights`.
    kind : {"LF", "MF", "HF"}
        The band to draw.
    ax : matplotlib Axes, optional
        Where to draw (default: a new figure).
    real_part : bool
        Also draw the weight of Re Ψ (what a real signal sees), where it differs.

    Returns
    -------
    matplotlib Axes
    """
    ax = _axes(ax)
    w, d = result.omega, result[kind]
    color = BAND_COLORS[kind]
    ax.plot(w, d.weight, color=color, lw=1.8, zorder=3, label=r"$[j\omega;1]^*\Psi[j\omega;1]$")
    if real_part and not np.allclose(d.weight, d.real_weight):
        ax.plot(w, d.real_weight, color="k", ls="--", zorder=3, label=r"weight of Re $\Psi$ (real signals)")
    ax.axhline(0, color="0.5", lw=0.8, zorder=2)
    ax.set_xscale("symlog", linthresh=1e-1)
    end = 1.5 * np.abs(w).max()
    ax.set_xlim(-end, end)
    ticks = [-1e3, -1e2, -1e1, -1, 0, 1, 1e1, 1e2, 1e3]
    ax.set_xticks(ticks, ["$-10^3$", "", "$-10$", "", "0", "", "$10$", "", "$10^3$"])
    symlog_axis(ax, "y", 1.0)
    # the band behind the curves: shaded and hatched in its colour, edged, and named in each of
    # its parts (where it lies on the page, not only in the title), at the top unless the curve
    # runs there
    hi = d.upper if math.isfinite(d.upper) else end
    parts = [(-hi, hi)] if d.lower == 0 else [(-hi, -d.lower), (d.lower, hi)]
    to_axes = ax.transAxes.inverted()
    xy = to_axes.transform(ax.transData.transform(np.c_[w, d.weight]))
    for a, b in parts:
        ax.axvspan(a, b, facecolor=color, alpha=0.22, lw=0, zorder=0)
        ax.axvspan(a, b, facecolor="none", edgecolor=color, hatch=BAND_HATCHES[kind], lw=0, alpha=0.5,
                   zorder=1)
        for edge in (a, b):
            if abs(edge) < end:
                ax.axvline(edge, color=color, lw=1.0, zorder=1)
        xa, xb = (to_axes.transform(ax.transData.transform((v, 0)))[0] for v in (max(a, -end), min(b, end)))
        mid = 0.5 * (xa + xb)
        under = xy[np.abs(xy[:, 0] - mid) < 0.08, 1]
        top = not under.size or under.max() < 0.75
        ax.text(mid, 0.96 if top else 0.04, f"{kind} band", transform=ax.transAxes, ha="center",
                va="top" if top else "bottom", fontsize=LEGEND_FONTSIZE, fontweight="bold", zorder=4,
                bbox={"boxstyle": "round,pad=0.2", "fc": "white", "ec": color, "lw": 1.0})
    ax.set_xlabel(r"$\omega$ [rad/s]")
    ax.set_ylabel("weight [(rad/s)$^2$]")
    ax.set_title(d.label)
    ax.legend(fontsize=LEGEND_FONTSIZE, loc="lower center")
    return ax


def plot_dominance_vs_rho(result, ax=None):
    """α(Ω_3) of ``d_h + ρ_p d_l`` against ρ_p: closed form and FFT estimate.

    Parameters
    ----------
    result : fdsc.paper.reproduced.frequency_ranges.DominanceVsRho
        Output of :func:`fdsc.paper.reproduced.frequency_ranges.dominance_vs_rho`.
    ax : matplotlib Axes, optional
        Where to draw (default: a new figure).

    Returns
    -------
    matplotlib Axes
    """
    ax = _axes(ax)
    ax.plot(result.rho_p, result.exact, "k-", label="closed form (mean powers)")
    ax.plot(result.rho_p, result.fft, "o", mfc="none", color="tab:orange",
            label=f"FFT of a {result.horizon:g} s record (Hann)")
    ax.set_xlabel(r"$\rho_p$ [-]")
    ax.set_ylabel(r"dominance degree $\alpha(\Omega_3)$ [-]")
    ax.legend()
    return ax


def plot_localized_dominance(result, ax=None):
    """α(Ω_1, T_l) and α(Ω_3, T_l) along the piecewise disturbance, segment limits marked.

    Parameters
    ----------
    result : fdsc.paper.reproduced.frequency_ranges.PiecewiseDominance
        Output of :func:`fdsc.paper.reproduced.frequency_ranges.localized_dominance_piecewise`.
    ax : matplotlib Axes, optional
        Where to draw (default: a new figure).

    Returns
    -------
    matplotlib Axes
    """
    ax = _axes(ax)
    for kind, name in (("LF", r"$\alpha(\Omega_1, T_l)$"), ("HF", r"$\alpha(\Omega_3, T_l)$")):
        ax.plot(result.t, result.alpha[kind], color=BAND_COLORS[kind], label=name)
    for b in result.breaks[1:-1]:
        ax.axvline(b, color="0.4", ls=":", lw=1)
    ax.set_xlabel("window centre $t$ [s]")
    ax.set_ylabel("time-localized dominance [-]")
    ax.set_ylim(-0.05, 1.05)
    ax.legend(title=f"windows of {result.window_length:g} s")
    return ax


def plot_sigma_sweep(result, ax=None, *, bands=None, labels=None, marks=None):
    """σ_max(G(jω)) curves on log-log axes, with band limits marked (paper Fig. 3).

    Parameters
    ----------
    result : fdsc.paper.reproduced.passive_controllers.SigmaCurves
        Output of :func:`fdsc.paper.reproduced.passive_controllers.sigma_curves`.
    ax : matplotlib Axes, optional
        Where to draw (default: a new figure).
    bands : iterable of float, optional
        Frequencies of band limits to mark (default the result's ``band_limits``).
    labels : dict, optional
        ``{gain name: legend label}`` (default: the gain with its controller, e.g.
        ``"K_f1 (PassC-LF)"``, for the printed gains' names, else the name).
    marks : iterable of (float, float), optional
        Points ``(ω, σ_max)`` to mark with dots (e.g. band peaks).

    Returns
    -------
    matplotlib Axes
    """
    from fdsc.paper.shared.names import GAIN_BANDS

    ax = _axes(ax)
    styles = ("-", "--", "-.", ":")
    for k, (name, s) in enumerate(result.sigma.items()):
        if labels is not None:
            label = labels[name]
        else:
            label = f"{name} (PassC-{GAIN_BANDS[name]})" if name in GAIN_BANDS else name
        # curves of near-equal gains (K_f2 and K_e) would hide each other without distinct styles
        ax.loglog(result.omega, s, ls=styles[k % len(styles)], lw=1.6, label=label)
    for wb in result.band_limits if bands is None else bands:
        ax.axvline(wb, color="0.5", ls=":", lw=1)
    for w, v in marks or ():
        ax.plot(w, v, "k.", ms=4)
    ax.set_xlabel(r"$\omega$ [rad/s]")
    ax.set_ylabel(r"$\sigma_{max}(G(j\omega))$ [-]")
    ax.legend()
    return ax


def plot_hf_sigma_scan(result, ax=None, *, reference=True):
    """HF designs against σ: LMI γ, in-band sweep γ and out-of-band peak (log axes).

    Parameters
    ----------
    result : fdsc.paper.reproduced.passive_controllers.HFBest
        Output of :func:`fdsc.paper.reproduced.passive_controllers.hf_best` (σ = 0 is not drawn on the
        log axis).
    ax : matplotlib Axes, optional
        Where to draw (default: a new figure).
    reference : bool, optional
        Draw the in-band and out-of-band peaks of the printed K_f3 as horizontal lines.

    Returns
    -------
    matplotlib Axes
    """
    ax = _axes(ax)
    scan = result.scan
    pos = scan.sigma > 0
    s = scan.sigma[pos]
    # the designs over σ in greys (data of one family), K_f3 (PassC-HF) in its own colour
    ax.loglog(s, scan.gamma_lmi[pos], "o-", color="k", label=r"LMI bound $\gamma$ (in band)")
    ax.loglog(s, scan.gamma_sweep[pos], "s--", color="0.4", label="in-band peak (sweep)")
    ax.loglog(s, scan.out_of_band[pos], "^:", color="0.6",
              label=rf"out-of-band peak ($|\omega| \leq {scan.band_edge:g}$)")
    if reference:
        ax.axhline(result.K_f3_in_band, color=style("K_f3")["color"], lw=1, label="K_f3 in band")
        ax.axhline(result.K_f3_out_of_band, color=style("K_f3")["color"], lw=1, ls=":",
                   label="K_f3 out of band")
    ax.set_xlabel(r"fictitious-pole parameter $\sigma$ [rad/s]")
    ax.set_ylabel(r"$\sigma_{max}$ peak [-]")
    ax.legend(fontsize=LEGEND_FONTSIZE)
    return ax


def plain_log_ticks(axis, nbins=6):
    """Plain tick labels on a log axis (1.2, 1.4, … or 0.5, 1, 2, not 2 × 10⁰): on a range of less
    than a factor 3, evenly spaced ticks; on a wider one, the decades and the 2, 3 and 5 between.

    Parameters
    ----------
    axis : matplotlib Axis
        A log-scaled axis whose data limits are set.
    nbins : int, optional
        The most ticks on a narrow range.
    """
    from matplotlib.ticker import FuncFormatter, MaxNLocator, NullFormatter

    lo, hi = sorted(axis.get_view_interval())
    if lo > 0 and hi / lo < 3:
        axis.set_major_locator(MaxNLocator(nbins))
        axis.set_major_formatter(FuncFormatter(lambda v, _pos: f"{v:g}"))
        axis.set_minor_formatter(NullFormatter())
    else:
        axis.set_major_formatter(FuncFormatter(lambda v, _pos: f"{v:g}"))
        axis.set_minor_formatter(FuncFormatter(_minor_label))


def _minor_label(v, _pos=None):
    """A minor tick of a log axis labelled at mantissas 2, 3 and 5 (0.2, 0.3, 0.5, 2, 3, 5, …)."""
    if v <= 0:
        return ""
    mantissa = v / 10 ** np.floor(np.log10(v))
    return f"{v:g}" if round(mantissa) in (2, 3, 5) and abs(mantissa - round(mantissa)) < 1e-6 else ""


def _gain_tex(label):
    """Gain names of a legend in math type: ``K_out = K_f1`` -> ``$K^{out}$ = $K_{f_1}$``.

    Examples
    --------
    >>> _gain_tex("K_out = K_f1"), _gain_tex("K_out = K_e")
    ('$K^{out}$ = $K_{f_1}$', '$K^{out}$ = $K_e$')
    """
    import re

    label = label.replace("K_out", "$K^{out}$")
    label = re.sub(r"K_f(\d)", r"$K_{f_\1}$", label)
    return re.sub(r"K_e\b", "$K_e$", label)


def plot_gap(result, ax=None, *, band_limits=None):
    """paper Remark 3's gap function for each candidate out-of-band gain (semilog-x, zero marked).

    Parameters
    ----------
    result : fdsc.paper.reproduced.passive_controllers.GapCurves
        Output of :func:`fdsc.paper.reproduced.passive_controllers.gap_curves` or
        :func:`fdsc.paper.reproduced.passive_controllers.remark3_gap`.
    ax : matplotlib Axes, optional
        Where to draw (default: a new figure).
    band_limits : iterable of float, optional
        Frequencies of band limits to mark (default the result's ``band_limits``).

    Returns
    -------
    matplotlib Axes
    """
    ax = _axes(ax)
    # curves that coincide over most frequencies: each drawn thinner and with its own dashes on top
    # of the previous ones, so that a curve under another still shows
    dashes = ("-", "--", ":", "-.")
    widths = (3.2, 2.2, 1.6, 1.2)
    for k, (label, g) in enumerate(result.gap.items()):
        ax.semilogx(result.omega, g, label=_gain_tex(label), ls=dashes[k % len(dashes)],
                    lw=widths[k % len(widths)])
    ax.axhline(0, color="0.4", lw=0.8)
    for wb in result.band_limits if band_limits is None else band_limits:
        ax.axvline(wb, color="0.5", ls=":", lw=1)
    symlog_axis(ax, "y", 1e-1)
    ax.set_xlabel(r"$\omega$ [rad/s]")
    ax.set_ylabel(r"gap$(K^{in}, K^{out}, \omega)$ [-]")
    ax.legend(fontsize=LEGEND_FONTSIZE)
    return ax


def plot_power_vs_alpha(data, ax: plt.Axes | None = None) -> plt.Axes:
    """Steady-state average FD-EPF against α(Ω_3) (symlog y), sign changes marked (paper Remark 1).

    Parameters
    ----------
    data : PowerVsAlpha
        Result of :func:`fdsc.paper.reproduced.frequency_selective.power_vs_alpha`.
    ax : matplotlib Axes, optional
        Axes to draw on (default: a new figure).

    Returns
    -------
    matplotlib Axes
    """
    ax = _axes(ax)
    for label, v in data.curves.items():
        # the colour of the loop's gain (K_f1: PassC-LF, K_f3: PassC-HF), the line of the term
        st = style(label.split(" loop")[0])
        line, = ax.plot(data.alpha, v, color=st["color"],
                        ls="-" if "Ω_3" in label else "--", label=label)
        a = data.crossing.get(label)
        if a is not None:
            ax.axvline(a, color=line.get_color(), ls=":", lw=1)
    ax.axhline(0, color="0.4", lw=0.8)
    symlog_axis(ax, "y", 1.0)
    ax.set_xlabel(r"dominance degree $\alpha(\Omega_3)$ of the disturbance [-]")
    ax.set_ylabel(r"average FD-EPF $P_a$ [-]")
    _below_legend(ax, ncol=2, y=-0.18)
    return ax


def plot_epf_series(data, ax: plt.Axes | None = None, *, legend: bool = True, bins: int = 400) -> plt.Axes:
    """Instantaneous FD-EPF (paper eq. (29)) of both law terms (min–max band per bin) and their
    running averages (paper eq. (28), thick).

    The two bands overlap where both terms swing through zero, so they are told apart by their
    fill: the LF term's band is filled, the HF term's hatched, both translucent and behind the
    running averages, which carry a white halo.

    Parameters
    ----------
    data : EPFSeries
        Result of :func:`fdsc.paper.reproduced.frequency_selective.epf_time_series`.
    ax : matplotlib Axes, optional
        Axes to draw on (default: a new figure).
    legend : bool, optional
        Draw a legend below the Axes (off the data); with several panels, one is enough.
    bins : int, optional
        Largest number of bands drawn across the run: consecutive bins of the result are merged
        (the smallest of their minima, the largest of their maxima) until there are at most this
        many, about one per pixel of a panel at the column width, so that a band's edge does not
        zigzag between neighbouring bins into a solid block.

    Returns
    -------
    matplotlib Axes
    """
    ax = _axes(ax)
    every = max(1, math.ceil((data.t.size - 1) / bins))   # t holds both ends of the run
    halo = [patheffects.withStroke(linewidth=4.0, foreground="white")]
    for kind, hatched in (("LF", False), ("HF", True)):
        color = BAND_COLORS[kind]
        t, lo, _ = envelope(data.t, data.P_t_lo[kind], every)
        _, _, hi = envelope(data.t, data.P_t_hi[kind], every)
        band = f"$P_t$, {kind} term (min–max per {every * data.bin:.3g} s)"
        if hatched:
            ax.fill_between(t, lo, hi, step="post", facecolor="none", edgecolor=color,
                            hatch="////", lw=0, alpha=0.7, zorder=2, label=band)
        else:
            ax.fill_between(t, lo, hi, step="post", color=color, alpha=0.22, lw=0, zorder=1,
                            label=band)
        for edge in (lo, hi):  # a smooth P_t has a thin band
            ax.plot(t, edge, color=color, lw=0.5, alpha=0.7, drawstyle="steps-post", zorder=2)
        ax.plot(data.t, data.P_a[kind], color=color, lw=2.2, path_effects=halo, zorder=4,
                label=f"running $P_a$, {kind} term")
    ax.axhline(0, color="0.4", lw=0.8, zorder=3)
    symlog_axis(ax, "y", 1e-3)
    ax.set_xlabel("$t$ [s]")
    ax.set_ylabel("FD-EPF [-]")
    gain = f"$K_{{f_{data.gain[3:]}}}$" if data.gain.startswith("K_f") else data.gain
    ax.set_title(f"{gain} loop, {data.disturbance} disturbance", fontsize=LEGEND_FONTSIZE + 1)
    if legend:
        ax.legend(fontsize=LEGEND_FONTSIZE, ncol=2, loc="upper center", bbox_to_anchor=(0.5, -0.2))
    return ax


def plot_prop1_cases(rows, ax: plt.Axes | None = None) -> plt.Axes:
    """S(Ω^in) against S(Ω^out) for every case (symlog axes); the quadrant Proposition 1 (paper
    eqs. (21), (22)) claims shaded.

    Parameters
    ----------
    rows : Prop1Cases
        Result of :func:`fdsc.paper.reproduced.frequency_selective.prop1_cases`.
    ax : matplotlib Axes, optional
        Axes to draw on (default: a new figure).

    Returns
    -------
    matplotlib Axes
    """
    ax = _axes(ax)
    markers = {"infinite, real Ψ": "o", "infinite, MF": "s", "window from rest": "^",
               "infinite, Q weighting one state": "D"}
    for kind, m in markers.items():
        sel = [c for c in rows.cases if c.kind == kind]
        if sel:
            ax.scatter([c.S_in for c in sel], [c.S_out for c in sel], marker=m, s=18,
                       facecolors="none", edgecolors=[VERDICT_COLORS[bool(c.passed)] for c in sel],
                       label=kind)
    symlog_axis(ax, "x", 1e-4)
    symlog_axis(ax, "y", 1e-4)
    ax.axvline(0, color="0.4", lw=0.8)
    ax.axhline(0, color="0.4", lw=0.8)
    x0, x1 = ax.get_xlim()
    y0, y1 = ax.get_ylim()
    ax.fill_between([0, x1], y0, 0, color="0.5", alpha=0.08, lw=0)
    ax.set_xlabel(r"$S(\Omega^{in}, Q^{in})$ (or its average) [-]")
    ax.set_ylabel(r"$S(\Omega^{out}, Q^{out})$ [-]")
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    _below_legend(ax, ncol=2, y=-0.14)
    ax.get_legend().set_title("dark: holds, magenta: fails", prop={"size": LEGEND_FONTSIZE})
    return ax


def plot_fdsc_diagram(ax: plt.Axes | None = None) -> plt.Axes:
    """Paper Fig. 1: the closed loop with FDSC, drawn as a block diagram (no data).

    Parameters
    ----------
    ax : matplotlib Axes, optional
        Axes to draw on (default: a new figure).

    Returns
    -------
    matplotlib Axes
    """
    from matplotlib.patches import FancyArrowPatch, FancyBboxPatch

    ax = _axes(ax, figsize=(7, 4))
    ax.set_xlim(0, 10)
    ax.set_ylim(0, 5)
    ax.axis("off")

    def box(x, y, w, h, text, color):
        ax.add_patch(FancyBboxPatch((x, y), w, h, boxstyle="round,pad=0.05", fc=color, ec="k"))
        ax.text(x + w / 2, y + h / 2, text, ha="center", va="center", fontsize=LEGEND_FONTSIZE)

    def arrow(a, b, text=None, off=(0, 0.15)):
        ax.add_patch(FancyArrowPatch(a, b, arrowstyle="-|>", mutation_scale=12, lw=1.2))
        if text:
            ax.text((a[0] + b[0]) / 2 + off[0], (a[1] + b[1]) / 2 + off[1], text, ha="center",
                    fontsize=LEGEND_FONTSIZE)

    box(3.6, 3.3, 2.8, 1.1, "plant\n$\\dot x = Ax + B_1 d + B_2 u$\n$z = Cx + D_1 d + D_2 u$", "#e8f0fb")
    box(0.4, 1.0, 2.6, 1.2, "passive gains\n$K_1 = K_{f_1}$ (LF)\n$K_2 = K_{f_3}$ (HF)", "#fdf1e0")
    box(3.7, 0.6, 2.6, 1.6, "switching law\n$\\sigma(t) = \\arg\\max_i$\n"
        "$[\\dot x; x]^*(\\Psi_i \\otimes Q_i)[\\dot x; x]$", "#eaf6ea")
    box(7.0, 1.0, 2.4, 1.2, "FD-EPF of each range\n$P_t(\\Omega_i, Q_i, t)$", "#f5eaf6")
    arrow((1.2, 3.85), (3.6, 3.85), "$d(t)$")
    arrow((6.4, 3.85), (9.2, 3.85), "$z(t)$")
    arrow((6.4, 3.55), (8.2, 2.2), "$x, \\dot x$", off=(0.5, 0.0))
    arrow((7.0, 1.6), (6.3, 1.4), "")
    arrow((3.7, 1.4), (3.0, 1.6), "$\\sigma(t)$", off=(0, 0.2))
    arrow((1.7, 2.2), (3.6, 3.5), "$u = K_{\\sigma(t)} x$", off=(-0.6, 0.1))
    return ax
