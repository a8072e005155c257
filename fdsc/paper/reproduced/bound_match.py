"""Appendix 'printed_bounds', continued: a printed bound against time-domain candidates.

The candidates of the search of :mod:`fdsc.paper.reproduced.bound_search` (a quantity of one gain's
closed loop under one signal, read at one horizon), how they are matched with the printed
value (hits to its precision, the nearest, how many lie within 1 % and how many hits that many
would give by chance), and the first time a running ratio crosses the printed value.
"""

import math
from dataclasses import dataclass

import numpy as np

from fdsc._validation import as_count, as_positive
from fdsc.paper.shared.prose import num
from fdsc.paper.shared.verdict import VERDICT_CLOSE_RTOL, verdict

__all__ = [
    "BoundMatch", "Crossing", "ENERGY_RATIO", "L2_RATIO", "TimeDomainCandidate", "first_crossing",
    "match_bound", "output_label",
]


#: Names of the quantities (the peak gains are named ``"peak gain of <output>"``).
L2_RATIO, ENERGY_RATIO = "L2 ratio", "energy ratio"


def output_label(name: str) -> str:
    """An output's name as the book prints it: ``"2 delta_E"`` → ``"2δ_E"``.

    Parameters
    ----------
    name : str
        The output's name in the paper's data.

    Returns
    -------
    str

    Examples
    --------
    >>> output_label("2 delta_PTV"), output_label("4 q")
    ('2δ_PTV', '4q')
    """
    return name.replace("delta", "δ").replace(" ", "")


def _seconds(h):
    return num(int(h)) if float(h).is_integer() else num(float(h))


def _signal_words(label):
    kind, _, parameter = label.partition(", ")
    return f"the {kind} disturbance" + (f" ({parameter})" if parameter else "")


@dataclass(frozen=True)
class TimeDomainCandidate:
    """One time-domain quantity of one closed loop under one signal.

    Parameters
    ----------
    gain : str
        The printed gain of the closed loop.
    signal : str
        Label of the test signal (:func:`search_signals`).
    quantity : str
        :data:`L2_RATIO`, :data:`ENERGY_RATIO` or ``"peak gain of <output>"``.
    horizon : float
        T in s, or :data:`STEADY_STATE` (∞) for the limit as T → ∞.
    value : float
        The quantity's value.
    """

    gain: str
    signal: str
    quantity: str
    horizon: float
    value: float

    @property
    def horizon_label(self) -> str | float:
        """The horizon in s, or ``"steady state"``."""
        return "steady state" if math.isinf(self.horizon) else self.horizon

    def describe(self, *, value: bool = True) -> str:
        """The candidate in words, e.g. ``"L2 ratio under the HF disturbance over T = 100 s
        (0.17135)"``.

        Parameters
        ----------
        value : bool, optional
            Append the value (five significant digits).

        Returns
        -------
        str
        """
        when = "in steady state" if math.isinf(self.horizon) else f"over T = {_seconds(self.horizon)} s"
        text = f"{self.quantity} under {_signal_words(self.signal)} {when}"
        return f"{text} ({num(self.value, 5)})" if value else text

    def to_dict(self) -> dict:
        """``{signal, quantity, horizon_s, value}`` with plain values (for the record).

        Returns
        -------
        dict
        """
        return {"signal": self.signal, "quantity": self.quantity, "horizon_s": self.horizon_label,
                "value": float(self.value)}


@dataclass(frozen=True)
class BoundMatch:
    """A printed bound against the candidates of its gain (see :func:`match_bound`).

    Parameters
    ----------
    gain : str
        The printed gain.
    paper : float
        The printed bound.
    nearest : tuple of TimeDomainCandidate
        The candidates nearest to ``paper``, nearest first.
    hits : tuple of TimeDomainCandidate
        Every candidate equal to ``paper`` to its printed precision, in the order given.
    n_candidates : int
        Candidates compared.
    n_within_close : int
        Candidates within :data:`~fdsc.paper.shared.verdict.VERDICT_CLOSE_RTOL` (1 %) of ``paper``.
    decimals : int
        Decimals printed.
    """

    gain: str
    paper: float
    nearest: tuple
    hits: tuple
    n_candidates: int
    n_within_close: int
    decimals: int

    @property
    def best(self) -> TimeDomainCandidate:
        """The nearest candidate."""
        return self.nearest[0]

    @property
    def shown(self) -> tuple:
        """The nearest candidates, then the hits not among them."""
        return self.nearest + tuple(h for h in self.hits if h not in self.nearest)

    @property
    def hit_values(self) -> tuple:
        """The distinct values among the hits (signals that agree up to T give one number)."""
        return tuple(dict.fromkeys(h.value for h in self.hits))

    @property
    def chance_hits(self) -> float:
        """Hits to expect by chance: the candidates within 1 % of ``paper``, times the width of
        the printed digits' window (one unit of the last decimal) over the width of the 1 %
        window (2 % of ``paper``), i.e. as if the candidates near the printed value were spread
        evenly over that window.

        Examples
        --------
        >>> m = BoundMatch("K", 0.25, (), (), 100, 50, 4)
        >>> round(m.chance_hits, 6)     # 50 candidates in a window 50 printed units wide
        1.0
        """
        return self.n_within_close * 10.0 ** (-self.decimals) / (2 * VERDICT_CLOSE_RTOL * self.paper)

    def rows(self) -> list:
        """The nearest candidates, then the hits not among them: ``signal, quantity, horizon,
        value, abs_diff, hit``.

        Returns
        -------
        list of dict
            For :func:`fdsc.paper.shared.report.html_table`.
        """
        return [{"signal": c.signal, "quantity": c.quantity, "horizon": c.horizon_label,
                 "value": c.value, "abs_diff": abs(c.value - self.paper),
                 "hit": "yes" if c in self.hits else ""} for c in self.shown]


def match_bound(gain: str, paper: float, candidates, *, decimals: int = 4, n_nearest: int = 5) -> BoundMatch:
    """Compare a printed bound with candidates picked after the fact.

    Parameters
    ----------
    gain : str
        The printed gain; every candidate must belong to it.
    paper : float
        The printed bound (> 0).
    candidates : sequence of TimeDomainCandidate
        The quantities tried (finite values).
    decimals : int, optional
        Decimals printed.
    n_nearest : int, optional
        How many nearest candidates to keep.

    Returns
    -------
    BoundMatch
        A hit is a candidate with ``verdict(paper, value, decimals, after_the_fact=True) ==
        "match"``; ties in distance keep the order given.

    Raises
    ------
    ValueError
        If there is no candidate, one belongs to another gain or has a value that is not finite,
        ``paper`` is not positive, ``decimals`` is negative or ``n_nearest`` is below 1.

    Examples
    --------
    >>> c = [TimeDomainCandidate("K", "HF", L2_RATIO, T, v) for T, v in ((1.0, 0.5), (2.0, 0.34426))]
    >>> m = match_bound("K", 0.3443, c)
    >>> m.best.horizon, len(m.hits)
    (2.0, 1)
    """
    paper = as_positive("paper", paper)
    decimals, n_nearest = as_count("decimals", decimals, 0), as_count("n_nearest", n_nearest)
    candidates = tuple(candidates)
    if not candidates:
        raise ValueError("candidates must hold at least one TimeDomainCandidate")
    for c in candidates:
        if c.gain != gain:
            raise ValueError(f"candidates must all belong to gain {gain!r}, but found one of {c.gain!r}")
        if not math.isfinite(c.value):
            raise ValueError(f"candidates must have finite values, but found {c.value} ({c.quantity}, "
                             f"{c.signal}, T = {c.horizon_label})")
    diffs = [abs(c.value - paper) for c in candidates]
    order = sorted(range(len(candidates)), key=lambda i: diffs[i])
    hits = tuple(c for c in candidates if verdict(paper, c.value, decimals, after_the_fact=True) == "match")
    near = sum(d <= VERDICT_CLOSE_RTOL * paper for d in diffs)
    return BoundMatch(gain, paper, tuple(candidates[i] for i in order[:n_nearest]), hits,
                      len(candidates), near, decimals)


def first_crossing(t, curve, level: float) -> float:
    """First time at which a sampled curve reaches ``level`` (linear between samples).

    Parameters
    ----------
    t : (M,) array_like
        Increasing times in s.
    curve : (M,) array_like
        Values at ``t``; NaN samples (e.g. a ratio at t = 0) are skipped.
    level : float
        The value looked for.

    Returns
    -------
    float
        In s; NaN if the curve never reaches ``level``.

    Raises
    ------
    ValueError
        If ``t`` and ``curve`` are not vectors of one length.

    Examples
    --------
    >>> first_crossing([0.0, 1.0, 2.0, 3.0], [np.nan, 0.0, 1.0, 0.0], 0.25)
    1.25
    """
    t, c = np.asarray(t, dtype=float), np.asarray(curve, dtype=float)
    if t.shape != c.shape or t.ndim != 1:
        raise ValueError(f"t and curve must be vectors of one length, but found {t.shape} and {c.shape}")
    ok = np.isfinite(c)
    t, s = t[ok], c[ok] - level
    at = np.flatnonzero(s == 0)
    between = np.flatnonzero(s[:-1] * s[1:] < 0)
    k_at = at[0] if at.size else s.size
    if between.size and between[0] < k_at:
        k = between[0]
        return float(t[k] + (t[k + 1] - t[k]) * s[k] / (s[k] - s[k + 1]))
    return float(t[k_at]) if at.size else math.nan


@dataclass(frozen=True)
class Crossing:
    """First time a running ratio of one loop under one signal reaches the printed bound.

    Parameters
    ----------
    gain : str
        The printed gain.
    signal : str
        Label of the test signal.
    quantity : str
        :data:`L2_RATIO` or :data:`ENERGY_RATIO`.
    t : float
        In s (coarse grid, linear in between); NaN if the curve never reaches the bound.
    """

    gain: str
    signal: str
    quantity: str
    t: float
