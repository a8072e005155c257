"""Figures of a simulated run: an output and the active mode over time (data in, Axes out).

Both functions decimate by bins (min/max of the output, time share of each mode), so that a
fast oscillation or a chattering law is drawn as the band it fills at the plotted scale, never
aliased into a slow wave.
"""

import matplotlib.pyplot as plt
import numpy as np

from ._validation import as_count, check_type
from .simulate import SimResult, envelope

__all__ = ["plot_run", "plot_modes"]


def _axes(ax):
    if ax is None:
        _, ax = plt.subplots(figsize=(7, 3))
    return ax


def _every(sim, bins):
    return max(1, int(np.ceil(sim.t.size / as_count("bins", bins))))


def plot_run(sim, ax=None, *, component=0, bins=1000, label=None, color=None):
    """One regulated output ``z_k(t)`` of a run, drawn as its min–max band per time bin.

    Parameters
    ----------
    sim : SimResult
        The run (:func:`~fdsc.simulate.simulate` or :meth:`fdsc.FDSC.simulate`).
    ax : matplotlib.axes.Axes, optional
        Where to draw (default: a new figure).
    component : int, optional
        Index k of the output.
    bins : int, optional
        Number of time bins (each draws the smallest and largest sample it holds).
    label : str, optional
        Legend label.
    color : matplotlib colour, optional
        The band's colour (default: the axes' next colour).

    Returns
    -------
    matplotlib.axes.Axes

    Raises
    ------
    ValueError
        If ``component`` is not an output index.

    Examples
    --------
    >>> from fdsc import LTISystem, Sinusoids, simulate, time_grid
    >>> sim = simulate(LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]]), Sinusoids([1.0], [50.0]),
    ...                time_grid(10.0, 1e-3))
    >>> ax = plot_run(sim, bins=200, label="z")
    >>> ax.get_xlabel()
    't (s)'
    """
    check_type("sim", sim, SimResult)
    component = as_count("component", component, 0)
    if component >= sim.z.shape[1]:
        raise ValueError(f"component must be an output index below {sim.z.shape[1]}, but found "
                         f"{component}")
    ax = _axes(ax)
    tb, lo, hi = envelope(sim.t, sim.z[:, component], _every(sim, bins))
    ax.fill_between(tb, lo, hi, step="post", alpha=0.6, label=label, linewidth=0.5, color=color)
    ax.set_xlabel("t (s)")
    ax.set_ylabel(f"z[{component}]")
    if label is not None:
        ax.legend(loc="upper right")
    return ax


def plot_modes(sim, ax=None, *, bins=1000, names=None, colors=None):
    """The switching signal σ(t) of a run, as the share of each time bin spent in each mode.

    Parameters
    ----------
    sim : SimResult
        A switched run.
    ax : matplotlib.axes.Axes, optional
        Where to draw (default: a new figure).
    bins : int, optional
        Number of time bins.
    names : sequence of str, optional
        The modes' names in the legend, one per mode (default ``"mode 0"``, ``"mode 1"``, …).
    colors : sequence of matplotlib colours, optional
        One per mode (default: the axes' colour cycle).

    Returns
    -------
    matplotlib.axes.Axes
        One stacked area per mode, from 0 to 1.

    Raises
    ------
    ValueError
        If ``names`` or ``colors`` does not give one entry per mode of the run.

    Examples
    --------
    >>> from fdsc import LTISystem, Sinusoids, simulate, time_grid
    >>> sim = simulate(LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]]), Sinusoids([1.0], [1.0]),
    ...                time_grid(5.0, 1e-2))
    >>> plot_modes(sim, bins=50).get_ylabel()
    'share of the bin in mode i'
    """
    check_type("sim", sim, SimResult)
    ax = _axes(ax)
    every = _every(sim, bins)
    starts = np.arange(0, sim.t.size, every)
    counts = np.diff(np.append(starts, sim.t.size))
    n_modes = int(sim.sigma.max()) + 1
    for arg, given in (("names", names), ("colors", colors)):
        if given is not None and (isinstance(given, str) or len(given) < n_modes):
            raise ValueError(f"{arg} must give one entry per mode of the run (at least {n_modes}), "
                             f"but found {given!r}")
    labels = [f"mode {i}" for i in range(n_modes)] if names is None else [str(n) for n in names[:n_modes]]
    shares = [np.add.reduceat((sim.sigma == i).astype(float), starts) / counts for i in range(n_modes)]
    ax.stackplot(sim.t[starts], *shares, step="post", labels=labels,
                 colors=None if colors is None else list(colors[:n_modes]))
    ax.set_ylim(0, 1)
    ax.set_xlabel("t (s)")
    ax.set_ylabel("share of the bin in mode i" if names is None else "share of the bin [-]")
    ax.legend(loc="upper right")
    return ax
