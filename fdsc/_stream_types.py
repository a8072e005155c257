"""The types of :mod:`fdsc.stream`: a run to do (:class:`Case`), the result of one run
(:class:`StreamResult`, with its decimated :class:`Trace`) and of a batch (:class:`BatchResult`).

Internal module: the classes are public as ``fdsc.stream.Case`` and so on (and in
:mod:`fdsc`), which is where their ``__module__`` points.
"""

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from ._validation import as_positive
from .exceptions import UnstableError
from .rules import PRINTED, SwitchRule

__all__ = []


@dataclass(frozen=True)
class Case:
    """One run of a batch: a loop, a disturbance, a law and a grid.

    Parameters
    ----------
    modes : LTISystem or list of LTISystem
        Closed loop(s) ``(A_i, B, C_i, D)`` sharing B and D (python-control ``StateSpace`` or
        ``(A, B, C, D)`` tuples are accepted too).
    d : Sinusoids, Piecewise or Sampled
        Scalar disturbance. Breaks of a Piecewise must lie on the grid; a Sampled signal must
        have the step ``dt`` and cover the horizon (samples after it are not used).
    horizon : float
        End time in s; a multiple of ``dt``.
    dt : float
        Step in s (> 0).
    x0 : (n,) array_like, optional
        Initial state (default 0).
    law_bands : list of Band, optional
        Ω_i of the switching law (required for several modes).
    law_Q : list of (n, n) array_like, optional
        Q_i of the switching law (symmetric positive definite).
    law : {"previous", "candidate"}, optional
        How ẋ enters the law (:data:`fdsc.simulate.LAWS`).
    sigma0 : int, optional
        Mode assumed active before t = 0.
    rule : SwitchRule, optional
        Hysteresis, minimum dwell time and/or moving window (default the printed argmax); its
        window and dwell are checked against ``dt`` when the case runs
        (:meth:`SwitchRule.steps <fdsc.rules.SwitchRule.steps>`).
    law_weights : list of array_like, optional
        Instead of ``law_bands`` and ``law_Q``: one symmetric W_i per mode on ``[ẋ; x]`` (2n) or
        ``[ẍ; ẋ; x]`` (3n); see :func:`fdsc.simulate.simulate`.
    label : object, optional
        Anything that identifies the case for the caller (kept, not used).
    """

    modes: object
    d: object
    horizon: float
    dt: float
    x0: ArrayLike | None = None
    law_bands: list | None = None
    law_Q: list | None = None
    law: str = "previous"
    sigma0: int = 0
    rule: SwitchRule = PRINTED
    law_weights: list | None = None
    label: object = field(default=None, compare=False)



@dataclass(frozen=True)
class Trace:
    """Traces decimated to bins of equal length: min and max of every sample in a bin.

    Parameters
    ----------
    t : (M,) ndarray
        Start time of each bin in s.
    x_lo, x_hi : (M, n) ndarray
        Smallest and largest state components in each bin.
    z_lo, z_hi : (M, p) ndarray
        Smallest and largest regulated outputs in each bin.
    d_lo, d_hi : (M,) ndarray
        Smallest and largest disturbance sample in each bin.
    share : (M, I) ndarray
        Fraction of the bin's samples in each mode.
    """

    t: np.ndarray
    x_lo: np.ndarray
    x_hi: np.ndarray
    z_lo: np.ndarray
    z_hi: np.ndarray
    d_lo: np.ndarray
    d_hi: np.ndarray
    share: np.ndarray


@dataclass(frozen=True)
class StreamResult:
    """Reductions of one streamed run (see :func:`simulate_stream`).

    Parameters
    ----------
    horizon, dt : float
        The grid ``0, dt, …, horizon`` (s).
    energy, input_energy : float
        ``∫ zᵀz`` and ``∫ d²`` over the horizon, exact: the sum of every step's energy, a
        quadratic form of the state and the disturbance's oscillators (or held samples) at the
        step's start (:mod:`fdsc._step_energy`), as :meth:`SimResult.energy
        <fdsc.simulate.SimResult.energy>`; ``inf`` and ``nan`` if the run diverged. The output
        of a switched run jumps at every switch, so no quadrature of its samples would do.
    switches : int
        Number of changes of the active mode.
    time_share : (I,) ndarray
        Fraction of the horizon spent in each mode (of the nominal horizon: if the run diverged,
        the shares sum to less than 1).
    dwell_edges : (B + 1,) ndarray
        Edges (s) of the dwell-time histogram; a dwell of L steps counts in bin b if
        ``edges[b] ≤ L dt < edges[b + 1]``.
    dwell_counts : (B,) int ndarray
        Completed dwell intervals (ended by a switch) per bin.
    x_final : (n,) ndarray
        State at the horizon (at the divergence if the run diverged).
    sigma_final : int
        Mode chosen at the last point.
    t_cum : (M,) ndarray
        Coarse grid (s) of the running integrals (empty if none was asked for).
    energy_cum, input_energy_cum : (M,) ndarray
        ``∫₀ᵗ zᵀz`` and ``∫₀ᵗ d²`` at ``t_cum``.
    trace : Trace or None
        Decimated traces, if asked for.
    diverged_at : float or None
        Time (s) at which the state overflowed, None if it stayed finite.
    grew_at : float or None
        Time (s) at which the divergence monitor (:mod:`fdsc._divergence`) flagged the run: its
        state exceeded 10⁶ times the largest state any of its modes reaches alone from the same
        x0 under the same disturbance (checked every 1024 steps and at the last point). None if
        it never did; a run of one mode never is. The run's other numbers are still those of
        the (diverging) run.
    growth : float or None
        ``max_r |x_r| / R`` at ``grew_at`` (R the modes' bound; > 10⁶), None if not flagged.
    """

    horizon: float
    dt: float
    energy: float
    input_energy: float
    switches: int
    time_share: np.ndarray
    dwell_edges: np.ndarray
    dwell_counts: np.ndarray
    x_final: np.ndarray
    sigma_final: int
    t_cum: np.ndarray
    energy_cum: np.ndarray
    input_energy_cum: np.ndarray
    trace: Trace | None = None
    diverged_at: float | None = None
    grew_at: float | None = None
    growth: float | None = None

    @property
    def n_steps(self) -> int:
        """Number of steps (grid points − 1)."""
        return round(self.horizon / self.dt)

    def l2_ratio(self) -> float:
        """The L2-induced ratio ``√(∫zᵀz / ∫d²)`` over the horizon.

        Returns
        -------
        float

        Raises
        ------
        UnstableError
            If the run diverged.
        ValueError
            If the disturbance has zero energy.
        """
        if self.diverged_at is not None:
            raise UnstableError(f"the run diverged at t = {self.diverged_at:g} s; it has no L2 ratio")
        if not self.input_energy > 0:
            raise ValueError("the disturbance has zero energy: the L2-induced ratio is undefined")
        return math.sqrt(self.energy / self.input_energy)

    def running_l2(self) -> tuple[np.ndarray, np.ndarray]:
        """``√(∫₀ᵗ zᵀz / ∫₀ᵗ d²)`` on the coarse grid (nan where ``∫₀ᵗ d² = 0``).

        Returns
        -------
        t, ratio : (M,) ndarray

        Raises
        ------
        ValueError
            If the run kept no coarse grid (``cumulative_every`` was not given).
        """
        self._need_cum("running_l2")
        with np.errstate(invalid="ignore", divide="ignore"):
            ratio = np.sqrt(self.energy_cum / np.where(self.input_energy_cum > 0,
                                                       self.input_energy_cum, np.nan))
        return self.t_cum, ratio

    def window_energies(self, length: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``∫ zᵀz`` and ``∫ d²`` over every window ``[t, t + length]`` starting on the coarse grid.

        Parameters
        ----------
        length : float
            Window length in s, a multiple of the coarse grid's step, at most the horizon.

        Returns
        -------
        t_start, energy, input_energy : (M − L,) ndarray
            The sliding windows (hop = the coarse step).

        Raises
        ------
        ValueError
            If the run kept no coarse grid, or ``length`` is not a positive multiple of its step
            no longer than the horizon.
        """
        self._need_cum("window_energies")
        length = as_positive("length", length)
        step = self.t_cum[1] - self.t_cum[0]
        L = round(length / step)
        if L < 1 or abs(L * step - length) > 1e-9 * length or L >= self.t_cum.size:
            raise ValueError(f"length must be a multiple of the coarse step {step:g} s and at most "
                             f"{(self.t_cum.size - 1) * step:g} s, found {length:g}")
        return (self.t_cum[:-L], self.energy_cum[L:] - self.energy_cum[:-L],
                self.input_energy_cum[L:] - self.input_energy_cum[:-L])

    def _need_cum(self, what):
        if self.t_cum.size < 2:
            raise ValueError(f"{what} needs the coarse grid: run with cumulative_every=…")


class BatchResult:
    """The results of :func:`simulate_batch`: arrays over cases, and one
    :class:`StreamResult` per case by indexing (``batch[c]``).

    Parameters
    ----------
    cases : sequence of Case
        The cases, in order.
    results : sequence of StreamResult
        One result per case.

    Attributes
    ----------
    cases : list of Case
    energy, input_energy : (C,) ndarray
        ``∫ zᵀz`` and ``∫ d²`` of every case (``inf``/``nan`` where the state overflowed).
    switches : (C,) int ndarray
    time_share : (C, I_max) ndarray
        Zero for modes a case does not have.
    diverged : (C,) bool ndarray
        True where the state overflowed (``diverged_at``) or the divergence monitor flagged the
        run (``grew_at``; its energy is finite, but the run diverges).
    """

    def __init__(self, cases, results):
        self.cases = list(cases)
        self._results = list(results)
        self.energy = np.array([r.energy for r in results])
        self.input_energy = np.array([r.input_energy for r in results])
        self.switches = np.array([r.switches for r in results], dtype=np.int64)
        width = max(r.time_share.size for r in results)
        self.time_share = np.array([np.pad(r.time_share, (0, width - r.time_share.size))
                                    for r in results])
        self.diverged = np.array([r.diverged_at is not None or r.grew_at is not None
                                  for r in results])

    def __len__(self):
        return len(self._results)

    def __getitem__(self, c) -> StreamResult:
        return self._results[c]

    def __iter__(self):
        return iter(self._results)

    def __repr__(self):
        return (f"BatchResult({len(self)} cases, {int(self.diverged.sum())} diverged, "
                f"energies {np.array2string(self.energy, precision=4, threshold=6)})")


for _cls in (Case, Trace, StreamResult, BatchResult):
    _cls.__module__ = "fdsc.stream"
