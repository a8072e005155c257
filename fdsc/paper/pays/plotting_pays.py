"""Figures of the chapter 'simulations' (result in, Axes out)."""

import numpy as np

from fdsc.paper.shared.plotting import _axes
from fdsc.paper.shared.plotting_axes import LEGEND_FONTSIZE, _end_labels
from fdsc.paper.shared.style import STYLES, band_color, style

__all__ = ["STYLE", "plot_stationary_baselines", "plot_family_baselines"]

#: Line style of each controller of the comparisons (colour, marker, line style): the book's one
#: style map (:data:`fdsc.paper.shared.style.STYLES`).
STYLE = STYLES


def _style(name, k):
    st = style(name, k)
    return st["color"], st["marker"], st["linestyle"]


def plot_stationary_baselines(result, ax=None):
    """Energy ratio ∫zᵀz/∫d² of every controller under the stationary LF and HF disturbances.

    Parameters
    ----------
    result : Baselines
    ax : Axes, optional

    Returns
    -------
    Axes
    """
    ax = _axes(ax, (7, 4))
    lf, hf = result.family("stationary")
    y = np.arange(len(result.names))
    for off, s, color in ((-0.2, lf, band_color("LF")), (0.2, hf, band_color("HF"))):
        ax.barh(y + off, [s.energy[n] / s.input_energy for n in result.names], height=0.38, color=color,
                label=f"{s.label} disturbance (paper eq. ({56 if s.label == 'LF' else 57}))")
    ax.set_yticks(y, result.names)
    ax.invert_yaxis()
    ax.set_xscale("log")
    ax.set_xlabel(r"energy ratio $\int z^\top z\,dt \,/ \int d^2\,dt$ over 500 s [-]")
    ax.legend(fontsize=LEGEND_FONTSIZE, loc="lower right")
    ax.grid(True, axis="x", which="both", alpha=0.3)
    return ax


def plot_family_baselines(result, family, ax=None, *, names=None, log=True, legend=True, end_labels=False):
    """Energies of the controllers over the ρ_p family (paper Fig. 7) or the ρ_t family (Fig. 8),
    the latter with the ideal segment law.

    The ideal segment law is drawn last, in black with filled markers over the other controllers'
    open ones, so that it stays visible where it meets a curve (on the ρ_t family, the open
    loop's).

    Parameters
    ----------
    result : Baselines
    family : {"mixed", "piecewise"}
    ax : Axes, optional
    names : sequence of str, optional
        Controllers to draw (default all).
    log : bool, optional
        Logarithmic energy axis (a linear one tells close curves apart).
    legend : bool, optional
        Draw the legend inside the Axes (with several panels, draw one for the figure instead).
    end_labels : bool, optional
        Name each curve at its right end, in its colour, beside the Axes, instead of a legend:
        the FDSC variants (purple, pink, brown) and PassC-HF and HF best (yellow, orange) have
        close hues, which a legend leaves to be matched.

    Returns
    -------
    Axes
    """
    ax = _axes(ax)
    param, energy = result.energies(family)
    for k, n in enumerate(result.names if names is None else names):
        color, marker, ls = _style(n, k)
        ax.plot(param, energy[n], color=color, marker=marker, ls=ls, ms=4.5, mfc="none", lw=1.2,
                zorder=2, label=n)
    if family == "piecewise":
        color, marker, ls = _style("ideal segment law", 0)
        ax.plot(param, result.ideal_piecewise, color=color, marker=marker, ls=ls, ms=7, lw=1.6,
                zorder=3, label="ideal segment law")
    if log:
        ax.set_yscale("log")
    ax.set_xlabel(r"$\rho_p$ [-]" if family == "mixed" else r"$\rho_t$ [-]")
    ax.set_ylabel(r"$\int z^\top z\,dt$ over the run [-]")
    ax.grid(True, which="both", alpha=0.3)
    if end_labels:
        _end_labels(ax)
    elif legend:
        ax.legend(fontsize=LEGEND_FONTSIZE, ncol=2)
    return ax
