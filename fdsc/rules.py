"""Well-posed variants of the switching law: hysteresis, minimum dwell time and a moving window.

The printed law (paper eq. (31)) picks, at every sample, the mode with the largest score
``s_i = [ẋ; x]ᵀ (Ψ_i ⊗ Q_i) [ẋ; x]``. With the measured ẋ the scores depend on the mode active
just before the sample, and the law chatters at the sampling rate where every mode prefers
another (paper Remark 7 assumes this away; it names hysteresis and a minimum dwell time as
remedies, and paper Remark 6 suggests the FD-EEF, an average of the score over time, as the
switching quantity). A :class:`SwitchRule` adds any combination of three modifications, applied
in this order at every sample k:

1. **Moving window** (``window = T_w > 0``): the score of mode i is replaced by its mean over
   the last ``L = T_w / dt`` samples (fewer at the start of the run), the FD-EEF of the
   recent past, paper eq. (19), per unit time. The scores entering the window are those of the
   law at each sample (same reading of ẋ). ``T_w`` must be a whole number L ≥ 2 of steps; a
   window longer than the run averages every sample since t = 0.
2. **Minimum dwell time** (``dwell = τ_d > 0``): no switch happens less than
   ``ceil(τ_d / dt) ≥ 2`` samples after the previous one; the mode ``sigma0`` counts as
   switched on at t = 0, so the first switch comes at t ≥ τ_d too (a dwell longer than the
   horizon gives the fixed-gain run of ``sigma0``: no switch at all).
3. **Hysteresis** (``margin = h > 0``): the best mode j replaces the active mode a only if
   ``s_j − s_a > h`` (absolute) or ``s_j − s_a > h · (|s_j| + |s_a|)`` (relative: scale-free,
   since the scores scale with the Q's; the ratio lies in (0, 1], so a relative margin must be
   below 1, where it never switches).

A window or dwell of one step or less would change nothing (the law decides at every sample
anyway), and a window off the grid would be rounded to another length: both are refused when
the rule is turned into steps (:meth:`SwitchRule.steps`, by the simulators). Lengths beyond the
run are clamped to ``n_steps + 1`` samples, which is the same run as any longer one.

With all three off the rule is the printed argmax (ties to the lowest index). The same compiled
functions apply the rule in :func:`fdsc.simulate.simulate` (through ``apply_rule``) and in the
streaming simulator :mod:`fdsc.stream`: ``window_scores`` for step 1 and ``decide``, a function
of scalars only, for steps 2 and 3 (the stream's loop does the argmax itself, so that its hot
path passes no array to a function: numba reference-counts arrays at every such call, which
had doubled the cost of a step under hysteresis or a dwell time).
"""

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from ._validation import as_nonnegative, as_positive

__all__ = ["SwitchRule", "PRINTED", "MAX_RULE_STEPS"]


@dataclass(frozen=True)
class SwitchRule:
    """A well-posed modification of the argmax switching law (see the module docstring).

    Parameters
    ----------
    margin : float, optional
        Hysteresis margin h ≥ 0 (0: none); below 1 if relative.
    relative : bool, optional
        Whether the margin is relative to ``|s_j| + |s_a|`` (default; h in [0, 1)) or
        absolute (in the units of the scores).
    dwell : float, optional
        Minimum dwell time τ_d ≥ 0 in s (0: none); more than one step of the run's dt (checked
        by :meth:`steps`).
    window : float, optional
        Length T_w ≥ 0 (s) of the moving window over which the scores are averaged (0: the
        instantaneous scores); a whole number ≥ 2 of steps of the run's dt, or longer than the
        run (checked by :meth:`steps`).

    Raises
    ------
    ValueError
        If a parameter is negative or not finite, ``relative`` is not a bool, or a relative
        ``margin`` is ≥ 1 (the relative lead is at most 1: the rule would never switch).

    Examples
    --------
    >>> SwitchRule.hysteresis(0.2)
    SwitchRule(margin=0.2, relative=True, dwell=0.0, window=0.0)
    >>> SwitchRule().is_printed, SwitchRule.dwell_time(0.5).is_printed
    (True, False)
    """

    margin: float = 0.0
    relative: bool = True
    dwell: float = 0.0
    window: float = 0.0

    def __post_init__(self):
        for name in ("margin", "dwell", "window"):
            object.__setattr__(self, name, as_nonnegative(name, getattr(self, name)))
        if not isinstance(self.relative, bool | np.bool_):
            raise ValueError(f"relative must be a bool, but found {self.relative!r}")
        object.__setattr__(self, "relative", bool(self.relative))
        if self.relative and self.margin >= 1:
            raise ValueError(f"margin must be < 1 for a relative hysteresis margin (the relative "
                             f"lead (s_j - s_a)/(|s_j| + |s_a|) is at most 1, so the rule would "
                             f"never switch), but found {self.margin!r}; give relative=False for "
                             f"a margin in the units of the scores")

    @classmethod
    def hysteresis(cls, margin: float, *, relative: bool = True) -> "SwitchRule":
        """Switch only when the best score beats the active one by ``margin``.

        Parameters
        ----------
        margin : float
            h ≥ 0, relative to ``|s_j| + |s_a|`` (then h < 1) or absolute.
        relative : bool, optional
            Relative (default) or absolute margin.

        Returns
        -------
        SwitchRule

        Raises
        ------
        ValueError
            If ``margin`` is negative or not finite, or ≥ 1 and relative.

        Examples
        --------
        >>> SwitchRule.hysteresis(1.0)
        Traceback (most recent call last):
        ...
        ValueError: margin must be < 1 for a relative hysteresis margin (the relative lead \
(s_j - s_a)/(|s_j| + |s_a|) is at most 1, so the rule would never switch), but found 1.0; give \
relative=False for a margin in the units of the scores
        """
        return cls(margin=margin, relative=relative)

    @classmethod
    def dwell_time(cls, tau: float) -> "SwitchRule":
        """Keep every mode at least ``tau`` seconds (the initial mode too).

        Parameters
        ----------
        tau : float
            Minimum dwell time τ_d ≥ 0 in s; more than one step of the run's dt (see
            :meth:`steps`). A dwell longer than the run keeps ``sigma0`` throughout.

        Returns
        -------
        SwitchRule
        """
        return cls(dwell=tau)

    @classmethod
    def moving_window(cls, T_w: float) -> "SwitchRule":  # noqa: N803  (the paper-style symbol)
        """Switch on the scores averaged over the last ``T_w`` seconds (an FD-EEF law).

        Parameters
        ----------
        T_w : float
            Window length ≥ 0 in s: a whole number ≥ 2 of steps of the run's dt, or longer than
            the run (see :meth:`steps`).

        Returns
        -------
        SwitchRule
        """
        return cls(window=T_w)

    @property
    def is_printed(self) -> bool:
        """True if the rule is the printed argmax (no margin, dwell or window)."""
        return self.margin == 0 and self.dwell == 0 and self.window == 0

    def steps(self, dt: float, n_steps: int | None = None) -> tuple[int, int]:
        """The dwell and the window in samples of the step ``dt``.

        Parameters
        ----------
        dt : float
            Step in s (> 0).
        n_steps : int, optional
            Steps of the run (horizon / dt). Given, a dwell or a window longer than the run is
            clamped to ``n_steps + 1`` samples, the same run as any longer one (and such a
            window need not lie on the grid); otherwise to :data:`MAX_RULE_STEPS`.

        Returns
        -------
        dwell_steps, window_steps : int
            ``ceil(τ_d / dt)`` (0 without dwell; a relative 1e-9 of rounding tolerated) and
            ``T_w / dt`` (1 without window), each at most the clamp.

        Raises
        ------
        ValueError
            If ``dt`` is not positive; if ``window`` (not longer than the run) is not a whole
            number of steps of ``dt`` (to a relative 1e-9, as the simulators' other grid
            lengths); or if ``dwell`` or ``window`` is one step or less (it would have no
            effect: the law decides at every sample anyway).

        Examples
        --------
        >>> SwitchRule(dwell=0.25, window=0.3).steps(0.1)
        (3, 3)
        >>> SwitchRule.dwell_time(1e16).steps(1e-3, n_steps=1000)      # longer than the run
        (1001, 1)
        >>> SwitchRule.moving_window(0.14).steps(0.1)
        Traceback (most recent call last):
        ...
        ValueError: rule.window (0.14 s) must be a multiple of dt (0.1 s): the window averages whole samples
        """
        return _rule_steps(self, dt, n_steps, "")

    def describe(self) -> str:
        """A short label (for tables and legends).

        Returns
        -------
        str

        Examples
        --------
        >>> SwitchRule(margin=0.1, dwell=0.5).describe()
        'hysteresis 0.1 (relative), dwell 0.5 s'
        """
        parts = []
        if self.window > 0:
            parts.append(f"window {self.window:g} s")
        if self.margin > 0:
            parts.append(f"hysteresis {self.margin:g} ({'relative' if self.relative else 'absolute'})")
        if self.dwell > 0:
            parts.append(f"dwell {self.dwell:g} s")
        return ", ".join(parts) if parts else "printed argmax"


#: The printed law of paper eq. (31).
PRINTED = SwitchRule()

#: Clamp of :meth:`SwitchRule.steps` without a run length: more steps than any run has (the
#: simulators' step index is a 64-bit integer and a run has fewer than 2^62 steps).
MAX_RULE_STEPS = 2**62


def _rule_steps(rule, dt, n_steps, where):
    """:meth:`SwitchRule.steps` with the messages prefixed by ``where`` (a batch's case)."""
    dt = as_positive(f"{where}dt", dt)
    cap = MAX_RULE_STEPS if n_steps is None else int(n_steps) + 1
    dwell_steps = 0
    if rule.dwell > 0:
        ratio = rule.dwell / dt
        # compared before rounding: a dwell far beyond the run (or inf after the division)
        # must neither overflow the step counter nor be dropped
        dwell_steps = cap if ratio >= cap else min(cap, math.ceil(ratio * (1 - 1e-9)))
        if dwell_steps <= 1:
            raise ValueError(f"{where}rule.dwell ({rule.dwell!r} s) is at most one step of dt "
                             f"({dt!r} s): the law may switch at every step anyway, so it would "
                             "have no effect; give at least two steps, or 0 for none")
    window_steps = 1
    if rule.window > 0:
        ratio = rule.window / dt
        if ratio > cap:
            window_steps = cap          # longer than the run: the mean of every sample so far
        else:
            k = round(ratio)
            if abs(k * dt - rule.window) > 1e-9 * rule.window:
                raise ValueError(f"{where}rule.window ({rule.window!r} s) must be a multiple of dt "
                                 f"({dt!r} s): the window averages whole samples")
            if k <= 1:
                raise ValueError(f"{where}rule.window ({rule.window!r} s) is one step of dt "
                                 f"({dt!r} s): the mean over one sample is the instantaneous "
                                 "score, so it would have no effect; give at least two steps, "
                                 "or 0 for none")
            window_steps = k
    return dwell_steps, window_steps


def rule_state(rule: SwitchRule, dt: float, n_modes: int, n_steps: int, where: str = ""):
    """Kernel parameters and zeroed state of ``rule`` for a run of ``n_steps`` steps (internal).

    Returns ``params`` (float64: margin, relative, dwell steps, window steps; both step counts
    at most ``n_steps + 1``, see :meth:`SwitchRule.steps`) and ``ring`` ((L, I) window samples),
    ``ring_sum`` ((I,)), ``istate`` (int64: position, count, last switch). Raises ValueError
    (prefixed by ``where``) as :meth:`SwitchRule.steps`.
    """
    dwell_steps, L = _rule_steps(rule, dt, n_steps, where)
    # the kernels read the dwell back as an integer: it must not round below n_steps + 1
    dwell = float(dwell_steps)
    if dwell < dwell_steps:
        dwell = math.nextafter(dwell, math.inf)
    params = np.array([rule.margin, float(rule.relative), dwell, float(L)])
    return params, np.zeros((L if L > 1 else 0, n_modes)), np.zeros(n_modes), np.zeros(3, np.int64)


@njit(cache=True)
def window_scores(scores, nm, L, ring, ring_sum, istate, eff):
    """Step 1 of the rule for a window of ``L > 1`` samples (internal): push the ``scores`` of the
    first ``nm`` modes into the ring and write their window means into ``eff``."""
    pos = istate[0]
    if istate[1] == L:
        for i in range(nm):
            ring_sum[i] -= ring[pos, i]
    for i in range(nm):
        ring[pos, i] = scores[i]
        ring_sum[i] += scores[i]
    pos += 1
    if pos == L:
        pos = 0
        # recompute the sums exactly once per window so that rounding cannot accumulate
        for i in range(nm):
            acc = 0.0
            for r in range(L):
                acc += ring[r, i]
            ring_sum[i] = acc
    istate[0] = pos
    if istate[1] < L:
        istate[1] += 1
    for i in range(nm):
        eff[i] = ring_sum[i] / istate[1]


@njit(cache=True)
def decide(best, prev, s_best, s_prev, k, last_switch, margin, relative, dwell_steps):
    """Steps 2 and 3 of the rule (internal): the mode kept at sample k when ``best`` (score
    ``s_best``) leads and ``prev`` (score ``s_prev``) is active, the last switch having been at
    sample ``last_switch``. Scalars only: a compiled caller keeps its arrays to itself, which
    costs nothing per call (arrays passed on would be reference-counted at every sample)."""
    if dwell_steps > 0 and k - last_switch < dwell_steps:
        return prev
    if margin > 0 and best != prev:
        scale = abs(s_best) + abs(s_prev) if relative else 1.0
        if not s_best - s_prev > margin * scale:
            return prev
    return best


@njit(cache=True)
def apply_rule(scores, nm, prev, k, params, ring, ring_sum, istate, eff):
    """The mode chosen at sample k from the instantaneous ``scores`` of the first ``nm`` modes
    (internal; see the module docstring): :func:`window_scores` (if the window is longer than
    a sample), the argmax (ties to the lowest index), :func:`decide`. ``eff`` receives the scores
    the decision used; the state arrays are updated."""
    L = int(params[3])
    if L > 1:
        window_scores(scores, nm, L, ring, ring_sum, istate, eff)
    else:
        for i in range(nm):
            eff[i] = scores[i]
    best = prev
    top = -np.inf
    for i in range(nm):
        if eff[i] > top:
            top = eff[i]
            best = i
    choice = decide(best, prev, eff[best], eff[prev], k, istate[2], params[0], params[1] > 0,
                    int(params[2]))
    if choice != prev:
        istate[2] = k
    return choice
