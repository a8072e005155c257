"""The decision grid of a law on the disturbance estimate, shared by the exact engine
(:class:`fdsc.prepared.Prepared`) and the engine on sampled measurements (:mod:`fdsc._measured`):
the run's result (:class:`SupervisedRun`), the decision intervals, the two banks of monitors and
their restarts, the fading monitoring signals and the relative hysteresis.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np
from numba import njit

from ._validation import as_nonnegative
from .exceptions import EnergyOverflowError, EnergyUnderflowWarning, MemoryLimitError

__all__ = ["SupervisedRun"]


@dataclass(frozen=True)
class SupervisedRun:
    """A run of the predictive-cost supervisor (see :func:`supervise`).

    Parameters
    ----------
    horizon : float
        Run length (s).
    dt : float or None
        The step of a run by :func:`fdsc.simulate_stream` (piece by piece between switches),
        or None for a run by the exact engine; the energies are exact either way.
    energy, input_energy : float
        ``∫ zᵀz`` and ``∫ d²`` over the horizon.
    switch_times : (m,) ndarray
        Instants (s) at which the active candidate changes.
    sequence : (m + 1,) int ndarray
        The active candidate on ``[0, t_1), [t_1, t_2), …``.
    time_share : (I,) ndarray
        Fraction of the horizon spent with each candidate.
    x_final : (n,) ndarray
        State at the horizon.
    t_mu : (M,) ndarray
        The decision points (s).
    mu : (M, I) ndarray
        The monitoring signals the law read there (no rows for a run along a given sequence).
    diverged_at : float or None
        The first switch or end point (s) where the divergence monitor fired, else None.
    """

    horizon: float
    dt: float
    energy: float
    input_energy: float
    switch_times: np.ndarray
    sequence: np.ndarray
    time_share: np.ndarray
    x_final: np.ndarray
    t_mu: np.ndarray
    mu: np.ndarray
    diverged_at: float | None = None

    @property
    def switches(self) -> int:
        """Number of changes of the active candidate."""
        return int(self.switch_times.size)


def _input_energy(grid) -> float:
    """``∫ d²`` over a grid's steps, exactly."""
    return float(grid.run(grid.tables([_dummy_input()]), 0, False, np.zeros(1))[0].sum())


def _n_blocks(horizon, decide_every) -> int:
    """The decision intervals in ``horizon``, refused unless it is a whole number of them."""
    nb = round(horizon / decide_every)
    if nb < 1 or abs(nb * decide_every - horizon) > 1e-9 * horizon:
        raise ValueError(f"horizon must be a whole number of decision intervals (decide_every = "
                         f"{decide_every:g} s), but found {horizon!r}")
    return nb


def _bank_starts(nb, restart_blocks) -> tuple:
    """The decision intervals at which each of the two banks of monitors restarts from rest:
    every R intervals, the second bank half a period later (a period beyond twice the horizon
    restarts neither bank after t = 0)."""
    R = min(restart_blocks, 2 * (nb + 1))
    half = max(1, R // 2)
    return (np.arange(0, nb, R), np.r_[0, np.arange(half, nb, R)])


def _older_bank(starts, nb) -> np.ndarray:
    """(nb + 1,) the bank the law reads at each decision point: the one restarted longer ago
    (bank 0 on a tie)."""
    k = np.arange(nb + 1)
    ages = [k - st[np.searchsorted(st, k, side="right") - 1] for st in starts]
    return np.where(ages[0] >= ages[1], 0, 1).astype(np.int64)


def _schedule(nb, step, warmup, min_dwell, sigma0, n_candidates) -> tuple:
    """``(first, dwell)`` in decision intervals (clamped to the run), with ``sigma0`` checked."""
    if isinstance(sigma0, bool) or not isinstance(sigma0, int | np.integer) \
            or not 0 <= sigma0 < n_candidates:
        raise ValueError(f"sigma0 must be a candidate's index in [0, {n_candidates}), but found {sigma0!r}")
    first = min(nb + 1, max(1, math.ceil(as_nonnegative("warmup", warmup) / step - 1e-9)))
    dwell = min(nb + 1, math.ceil(as_nonnegative("min_dwell", min_dwell) / step - 1e-9))
    return first, dwell


@njit(cache=True)
def _fading(E, fresh, decay):
    """μ_k = 0 where the bank restarts, else e^{−λΔ} μ_{k−1} + E_{k−1}."""
    mu = np.zeros((E.shape[0] + 1, E.shape[1]))
    for k in range(1, E.shape[0] + 1):
        if not fresh[k]:
            for i in range(E.shape[1]):
                mu[k, i] = decay * mu[k - 1, i] + E[k - 1, i]
    return mu


@njit(cache=True)
def _decide(cost, n_blocks, q, first, dwell, h):
    """From q to the cheapest p when (1 + h) c_p < c_q (strict), not before ``first`` nor within
    ``dwell`` intervals of the last switch."""
    sigma = np.empty(n_blocks, dtype=np.int64)
    last = -dwell
    for k in range(n_blocks):
        if k >= first and k - last >= dwell:
            p = int(np.argmin(cost[k]))
            if p != q and (1.0 + h) * cost[k, p] < cost[k, q]:
                q = p
                last = k
        sigma[k] = q
    return sigma


#: The engines of the law on the estimate run scaled by a power of two when the largest entry of
#: the disturbance, its estimate or x0 lies outside [2^−SCALE_RANGE, 2^SCALE_RANGE]: their energies
#: (quadratic) and monitoring signals then stay far from the float range's ends.
SCALE_RANGE = 200


def _largest(d) -> float:
    """The largest amplitude of a signal (Sinusoids, or Piecewise of them)."""
    from .signals import Piecewise, Sinusoids

    if isinstance(d, Sinusoids):
        return float(np.max(np.abs(d.amplitudes))) if np.size(d.amplitudes) else 0.0
    if isinstance(d, Piecewise):
        return max([0.0] + [_largest(p) for p in d.parts])
    return 0.0


def _scale_exponent(x0, *signals) -> int:
    """The exponent e by which an engine of the law runs scaled (x0 and the signals times 2^−e):
    0 unless the largest of their entries lies outside [2^−SCALE_RANGE, 2^SCALE_RANGE], else the
    one that brings it into [½, 1).

    The runs are linear in (x0, d, ŵ), the monitoring signals and energies quadratic, and the law
    compares monitoring signals relative to each other (relative hysteresis; ŵ below the rounding
    of its own terms counts as 0), so a run scaled by a power of two takes the same decisions and
    its results are the unscaled ones times 2^−e (states) and 2^−2e (energies), exactly.
    """
    mags = [float(np.max(np.abs(x0))) if np.size(x0) else 0.0]
    mags += [_largest(s) for s in signals if s is not None]
    mag = max(mags)
    if mag == 0.0 or 2.0 ** -SCALE_RANGE <= mag <= 2.0 ** SCALE_RANGE:
        return 0
    return math.frexp(mag)[1]


def _scaled(d, e):
    """The signal ``d`` times 2^−e (``d`` itself for e = 0 or None)."""
    from .signals import Piecewise, Sinusoids

    if e == 0 or d is None:
        return d
    if isinstance(d, Sinusoids):
        return Sinusoids(np.ldexp(d.amplitudes, -e), d.frequencies, d.phases)
    return Piecewise(d.breaks, [_scaled(p, e) for p in d.parts])


#: What :func:`_unscale` is told it unscales when it brings back monitoring signals: they may
#: underflow silently (documented: the law decides on the scaled ones); an energy that does is
#: returned with an EnergyUnderflowWarning.
MONITORING_SIGNAL = "a monitoring signal"


def _unscale(value, e, power=2, where="", what="the energy"):
    """``value`` times 2^(power·e) (an energy: power 2; a state: power 1), refused by name if it
    leaves the float range above (EnergyOverflowError); an energy that is not 0 but falls below
    the smallest normal float, where it keeps few digits or none, is returned with an
    EnergyUnderflowWarning (the decisions were taken at scale, and stand)."""
    with np.errstate(over="ignore", under="ignore"):
        out = np.ldexp(value, power * e) if e else value
    if e and np.all(np.isfinite(value)) and not np.all(np.isfinite(out)):
        raise EnergyOverflowError(f"{where}{what} exceeds the float range (about 1.8e308) in the "
                                  "disturbance's units: scale the disturbance (or x0) down")
    tiny = np.finfo(float).tiny
    if what != MONITORING_SIGNAL and np.any((np.asarray(value) != 0) & (np.abs(out) < tiny)):
        warnings.warn(f"{where}{what} is below the smallest normal float (about {tiny:.2g}) in the "
                      f"disturbance's units, where it keeps few digits or none (found "
                      f"{float(np.max(np.abs(out))):.3g}); the decisions, taken at scale, stand: "
                      "scale the disturbance (or x0) up for its digits", EnergyUnderflowWarning,
                      stacklevel=3)
    return float(out) if np.ndim(out) == 0 else out


def _check_memory(sup, d, estimate, nb, where="prepare"):
    """Refuse by name a run whose exact engine would allocate more than DEFAULT_MAX_MEMORY: per
    step of the grid (a decision interval, cut at the breaks of d and ŵ) its edges, oscillators
    and energies, per decision interval the monitors' energies of two banks."""
    from ._defaults import DEFAULT_MAX_MEMORY
    from .signals import Piecewise

    def count(s):
        if s is None:
            return 0, 0
        if isinstance(s, Piecewise):
            return len(s.breaks), max([int(np.size(p.amplitudes)) for p in s.parts] + [0])
        return 0, int(np.size(s.amplitudes))

    (bd, td), (be, te) = count(d), count(estimate)
    steps = float(nb) + bd + be
    need = 8.0 * steps * (2 * (td + te) + 8 + 4 * len(sup.gains))
    if need > DEFAULT_MAX_MEMORY:
        raise MemoryLimitError(f"{where}: {nb} decision intervals (horizon / decide_every) need about "
                               f"{need / 2**30:.3g} GiB, more than the limit of "
                               f"{DEFAULT_MAX_MEMORY / 2**30:.3g} GiB; shorten the horizon or raise "
                               "decide_every")


def _dummy_input():
    """A system whose output is its input: its energy is ∫d²."""
    return (np.array([[-1.0]]), np.zeros((1, 1)), np.zeros((1, 1)), np.array([[1.0]]))


def _abcd(sys):
    return (sys.A, sys.B, sys.C, sys.D)


def _check_mu(mu, where):
    """Refuse monitoring signals that overflowed (the fading sum of finite energies)."""
    if not np.all(np.isfinite(mu)):
        raise EnergyOverflowError(f"{where}: a monitoring signal exceeds the float range (about 1.8e308), "
                                  "so the law cannot compare them: scale the disturbance (or x0) down")
