"""Shifted signals and the switched run of a law on the disturbance estimate along a decided
sequence at a given step (by :func:`fdsc.simulate_stream`), for :mod:`fdsc.prepared` and
:func:`fdsc.supervise` with ``dt``.
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from . import _divergence
from .decisions import SupervisedRun
from .exceptions import UnstableRunWarning
from .signals import Piecewise, Sinusoids

__all__ = ["shift_signal"]


def shift_signal(d, tau: float):
    """The signal ``t ↦ d(t + τ)``: tones with their phases advanced by ωτ, breaks moved by −τ.

    Parameters
    ----------
    d : Sinusoids or Piecewise
    tau : float
        The shift in s.

    Returns
    -------
    Sinusoids or Piecewise

    Raises
    ------
    TypeError
        If ``d`` is neither.
    ValueError
        If ``tau`` is not a finite real number.

    Examples
    --------
    >>> d = Sinusoids([1.0], [2.0])
    >>> bool(np.isclose(shift_signal(d, 0.5)([1.0])[0], d([1.5])[0], rtol=1e-14))
    True
    >>> p = Piecewise([0.0, 1.0, 3.0], [d, Sinusoids([1.0], [5.0])])
    >>> np.allclose(shift_signal(p, 0.5)([0.2, 0.7, 2.0]), p([0.7, 1.2, 2.5]), rtol=1e-14)
    True
    """
    if isinstance(tau, bool) or not isinstance(tau, int | float | np.integer | np.floating) \
            or not math.isfinite(tau):
        raise ValueError(f"tau must be a finite real number of seconds, but found {tau!r}")
    tau = float(tau)
    if isinstance(d, Sinusoids):
        return Sinusoids(d.amplitudes, d.frequencies, d.phases + d.frequencies * tau)
    if isinstance(d, Piecewise):
        # the parts are evaluated at absolute time: each is shifted too
        return Piecewise(np.asarray(d.breaks) - tau, [shift_signal(p, tau) for p in d.parts])
    raise TypeError(f"d must be an fdsc.Sinusoids or fdsc.Piecewise, but found {type(d).__name__}")


def _run_on_grid(prep, sigma, mu, dt):
    """The switched run along ``sigma`` (one candidate per decision interval) by
    :func:`fdsc.simulate_stream` at step dt."""
    from ._simulate_kernel import break_index
    from .stream import simulate_stream

    sup = prep.sup
    change = np.flatnonzero(np.diff(sigma)) + 1
    switch_times = change * sup.decide_every
    sequence = np.r_[sigma[:1], sigma[change]]
    block = round(sup.decide_every / dt)
    N = prep.n_blocks * block + 1
    for sig in (prep.d, prep.estimate):                 # breaks on the grid, in absolute time
        if isinstance(sig, Piecewise):
            for t in sig.breaks:
                break_index(t, 0.0, dt, N, "supervise: ")
    bounds = [0, *(change * block).tolist(), N - 1]
    x = prep._xstart.copy()                              # the run scaled (Prepared's Notes)
    limit = _divergence.threshold([lp.A for lp in prep.loops], prep.loops[0].B, x, prep._d)
    energy = input_energy = 0.0
    diverged = None
    for a, b, m in zip(bounds[:-1], bounds[1:], sequence, strict=True):
        if b <= a:
            continue
        r = simulate_stream(prep.loops[int(m)], shift_signal(prep._d, a * dt), (b - a) * dt, dt, x0=x)
        energy += r.energy
        input_energy += r.input_energy
        x = r.x_final
        big = float(np.abs(x).max())
        if big > limit and diverged is None:
            bound = limit / _divergence.SAFETY
            diverged = b * dt
            with np.errstate(over="ignore"):
                shown = float(np.ldexp(bound, prep._e))
            warnings.warn(_divergence.message("supervise: ", b * dt, big / bound, shown),
                          UnstableRunWarning, stacklevel=3)
    share = np.bincount(sigma, minlength=len(prep.loops)) / sigma.size
    with np.errstate(over="ignore"):
        x = np.ldexp(x[:sup.plant.n_states], prep._e)
    return SupervisedRun(prep.horizon, float(dt), prep._energy(energy, "supervise"),
                         prep._energy(input_energy, "supervise", "the disturbance's energy ∫d²"),
                         switch_times, sequence, share, x, prep.points, mu, diverged)
