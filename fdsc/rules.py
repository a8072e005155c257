"""Well-posed variants of the switching law: hysteresis, minimum dwell time and a moving window.

The printed law (paper eq. (31)) picks, at every sample, the mode with the largest score
``s_i = [ẋ; x]ᵀ (Ψ_i ⊗ Q_i) [ẋ; x]``. With the measured ẋ the scores depend on the mode active
just before the sample, and the law chatters at the sampling rate where every mode prefers
another (paper Remark 7 assumes this away; it names hysteresis and a minimum dwell time as
remedies, and paper Remark 6 suggests the FD-EEF, an average of the score over time, as the
switching quantity). A :class:`SwitchRule` adds any combination of three modifications, applied
in this order at every sample k:

1. **Moving window** (``window = T_w > 0``): the score of mode i is replaced by its mean over
   the last ``L = round(T_w / dt)`` samples (fewer at the start of the run), the FD-EEF of the
   recent past, paper eq. (19), per unit time. The scores entering the window are those of the
   law at each sample (same reading of ẋ).
2. **Minimum dwell time** (``dwell = τ_d > 0``): no switch happens less than
   ``ceil(τ_d / dt)`` samples after the previous one; the mode ``sigma0`` counts as switched on
   at t = 0, so the first switch comes at t ≥ τ_d too (a dwell longer than the horizon gives the
   fixed-gain run of ``sigma0``).
3. **Hysteresis** (``margin = h > 0``): the best mode j replaces the active mode a only if
   ``s_j − s_a > h`` (absolute) or ``s_j − s_a > h · (|s_j| + |s_a|)`` (relative: scale-free,
   since the scores scale with the Q's; the ratio lies in (0, 1], so a relative margin h ≥ 1
   never switches).

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

from ._validation import as_nonnegative

__all__ = ["SwitchRule", "PRINTED"]


@dataclass(frozen=True)
class SwitchRule:
    """A well-posed modification of the argmax switching law (see the module docstring).

    Parameters
    ----------
    margin : float, optional
        Hysteresis margin h ≥ 0 (0: none).
    relative : bool, optional
        Whether the margin is relative to ``|s_j| + |s_a|`` (default; h in [0, 1) is useful) or
        absolute (in the units of the scores).
    dwell : float, optional
        Minimum dwell time τ_d ≥ 0 in s (0: none).
    window : float, optional
        Length T_w ≥ 0 (s) of the moving window over which the scores are averaged (0: the
        instantaneous scores).

    Raises
    ------
    ValueError
        If a parameter is negative, not finite, or ``relative`` is not a bool.

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

    @classmethod
    def hysteresis(cls, margin: float, *, relative: bool = True) -> "SwitchRule":
        """Switch only when the best score beats the active one by ``margin``.

        Parameters
        ----------
        margin : float
            h ≥ 0, relative to ``|s_j| + |s_a|`` or absolute.
        relative : bool, optional
            Relative (default) or absolute margin.

        Returns
        -------
        SwitchRule
        """
        return cls(margin=margin, relative=relative)

    @classmethod
    def dwell_time(cls, tau: float) -> "SwitchRule":
        """Keep every mode at least ``tau`` seconds (the initial mode too).

        Parameters
        ----------
        tau : float
            Minimum dwell time τ_d ≥ 0 in s.

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
            Window length ≥ 0 in s.

        Returns
        -------
        SwitchRule
        """
        return cls(window=T_w)

    @property
    def is_printed(self) -> bool:
        """True if the rule is the printed argmax (no margin, dwell or window)."""
        return self.margin == 0 and self.dwell == 0 and self.window == 0

    def steps(self, dt: float) -> tuple[int, int]:
        """The dwell and the window in samples of the step ``dt``.

        Parameters
        ----------
        dt : float
            Step in s.

        Returns
        -------
        dwell_steps, window_steps : int
            ``ceil(τ_d / dt)`` (0 without dwell; a relative 1e-9 of rounding tolerated) and
            ``max(1, round(T_w / dt))``.

        Examples
        --------
        >>> SwitchRule(dwell=0.25, window=0.1).steps(0.1)
        (3, 1)
        """
        dwell_steps = math.ceil(self.dwell / dt * (1 - 1e-9)) if self.dwell > 0 else 0
        return dwell_steps, max(1, round(self.window / dt))

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


def rule_state(rule: SwitchRule, dt: float, n_modes: int):
    """Kernel parameters and zeroed state of ``rule`` for one run (internal).

    Returns ``params`` (float64: margin, relative, dwell steps, window steps) and ``ring``
    ((L, I) window samples), ``ring_sum`` ((I,)), ``istate`` (int64: position, count, last
    switch).
    """
    dwell_steps, L = rule.steps(dt)
    params = np.array([rule.margin, float(rule.relative), float(dwell_steps), float(L)])
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
