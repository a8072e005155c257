"""Figures of the generic-example chapter (result in, Axes out; never shows, never sets rcParams)."""

import numpy as np

from fdsc.paper.pays.generic_example import W_H, W_L, GenericStudy
from fdsc.paper.pays.plotting_pays import STYLE
from fdsc.paper.shared.plotting import _axes as _new_axes
from fdsc.paper.shared.plotting_axes import LEGEND_FONTSIZE

__all__ = ["plot_sigma", "plot_rho_p", "plot_rho_t"]


def _axes(ax):
    return _new_axes(ax, (6.5, 3.8))


def plot_sigma(result: GenericStudy, ax=None):
    """σ_max(ω) of every fixed controller, with the band limits (the role of paper Fig. 3).

    Parameters
    ----------
    result : GenericStudy
        From :func:`~fdsc.paper.pays.generic_example.generic_study`.
    ax : matplotlib.axes.Axes, optional
        Where to draw (default a new figure).

    Returns
    -------
    matplotlib.axes.Axes
    """
    ax = _axes(ax)
    for name, s in result.sigma.items():
        color, _, ls = STYLE[name]
        ax.loglog(result.omega, s, color=color, ls=ls, label=name)
    for w, text in ((W_L, r"$\varpi_l$"), (W_H, r"$\varpi_h$")):
        ax.axvline(w, color="k", lw=0.8, ls="--")
        ax.annotate(text, (w, 1.0), xycoords=("data", "axes fraction"), xytext=(3, -12),
                    textcoords="offset points")
    ax.set_xlabel(r"frequency $\omega$ [rad/s]")
    ax.set_ylabel(r"$\sigma_{\max}(G_K(j\omega))$ [-]")
    ax.legend(fontsize=LEGEND_FONTSIZE)
    return ax


def _sweep(comp, param, ax, xlabel, log_x):
    ratio = comp.ratio()
    for name in comp.names:
        color, marker, ls = STYLE[name]
        ax.plot(param, ratio[name], color=color, ls=ls, marker=marker, ms=3, label=name)
    ax.set_yscale("log")
    if log_x:
        ax.set_xscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(r"energy ratio $\int z^\top z \,/ \int d^2$ [-]")
    ax.legend(fontsize=LEGEND_FONTSIZE, ncol=2)
    return ax


def plot_rho_p(result: GenericStudy, ax=None):
    """Energy ratio of every controller along d = d_h + ρ_p d_l (the role of paper Fig. 7).

    Parameters
    ----------
    result : GenericStudy
        From :func:`~fdsc.paper.pays.generic_example.generic_study`.
    ax : matplotlib.axes.Axes, optional
        Where to draw (default a new figure).

    Returns
    -------
    matplotlib.axes.Axes
    """
    return _sweep(result.rho_p_sweep, result.rho_p, _axes(ax), r"$\rho_p$ [-]", True)


def plot_rho_t(result: GenericStudy, ax=None):
    """Energy ratio of every controller along the piecewise family (the role of paper Fig. 8).

    Parameters
    ----------
    result : GenericStudy
        From :func:`~fdsc.paper.pays.generic_example.generic_study`.
    ax : matplotlib.axes.Axes, optional
        Where to draw (default a new figure).

    Returns
    -------
    matplotlib.axes.Axes
    """
    ax = _sweep(result.rho_t_sweep, np.asarray(result.rho_t), _axes(ax), r"$\rho_t$ [-]", False)
    ax.plot(result.rho_t, result.ideal_rho_t / result.rho_t_sweep.input_energy, color="k", ls="-.", lw=1.5,
            label="ideal segment law")
    ax.legend(fontsize=LEGEND_FONTSIZE, ncol=2)
    return ax
