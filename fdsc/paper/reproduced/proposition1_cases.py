"""Chapter 'frequency_selective', continued: Proposition 1 on seeded random cases.

Proposition 1 (paper eqs. (21), (22)) on seeded random systems, frequency-limited disturbances
and weights: the FD-EPF in steady state (real Ψ, MF, a Q weighting one state) and the FD-EEF
over a window from rest, each kind of case counted.
"""

from dataclasses import dataclass

import numpy as np

from fdsc._validation import as_choice, as_count
from fdsc.bands import Band
from fdsc.energy import fdeef, steady_state_power
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.prose import count, num
from fdsc.paper.shared.results import RecordPart, entry
from fdsc.plant import LTISystem
from fdsc.random_systems import random_hurwitz, random_spd
from fdsc.signals import Sinusoids
from fdsc.simulate import simulate, time_grid

__all__ = ["PROP1_KINDS", "Prop1Case", "Prop1Cases", "Prop1Summary", "prop1_cases", "prop1_summary"]


_BANDS = {"LF": Band.lf(1.0), "MF": Band.mf(1.0, 10.0), "HF": Band.hf(10.0)}


#: The kinds of random case of :func:`prop1_cases`, in the order they are drawn.
PROP1_KINDS = ("infinite, real Ψ", "infinite, MF", "window from rest",
               "infinite, Q weighting one state")


_WINDOW = "window from rest"


def _tones_in(rng, kind, k):
    lo, hi = {"LF": (0.05, 0.95), "MF": (1.1, 9.0), "HF": (11.0, 300.0)}[kind]
    w = np.sort(np.exp(rng.uniform(np.log(lo), np.log(hi), k)))
    return Sinusoids(rng.uniform(0.2, 2.0, k), w, rng.uniform(0, 2 * np.pi, k))


@dataclass(frozen=True)
class Prop1Case:
    """One random case of Proposition 1 (paper eqs. (21), (22)).

    Parameters
    ----------
    case : int
        Index of the case in the draw.
    kind : str
        One of :data:`PROP1_KINDS`.
    band_in, band_out : {"LF", "MF", "HF"}
        Ω^in (the band of the disturbance) and Ω^out (disjoint from it).
    n : int
        State dimension of the random system.
    S_in, S_out : float
        FD-EEF (paper eqs. (19), (20)) of Ω^in and Ω^out, or their steady-state averages
        (FD-EPF, paper eq. (28)) for the infinite-horizon kinds.
    periods : float or None
        Window length in periods of the slowest tone (window kind only, else None).
    """

    case: int
    kind: str
    band_in: str
    band_out: str
    n: int
    S_in: float
    S_out: float
    periods: float | None = None

    def __post_init__(self):
        as_choice("kind", self.kind, PROP1_KINDS)
        if (self.periods is None) != (self.kind != _WINDOW):
            raise ValueError(f"periods must be given for the kind {_WINDOW!r} and only for it, "
                             f"but found kind {self.kind!r} with periods {self.periods!r}")

    @property
    def passed(self) -> bool:
        """Proposition 1 holds: ``S_in > 0`` and ``S_out < 0``."""
        return bool(self.S_in > 0 and self.S_out < 0)


@dataclass(frozen=True)
class Prop1Summary:
    """Counts of the cases where Proposition 1 holds and fails, overall and per kind.

    Parameters
    ----------
    passed, failed : int
        Cases where the proposition holds / fails.
    per_kind : dict
        ``{kind: (passed, failed)}`` for every kind drawn, sorted by kind.
    longest_failing_window : float
        Longest window (in periods of the slowest tone) among the failing window cases
        (0 when none fails).
    """

    passed: int
    failed: int
    per_kind: dict
    longest_failing_window: float

    def counts(self) -> dict:
        """The record's form ``{"passed", "failed", "cases": {kind: {"passed", "failed"}}}``.

        Returns
        -------
        dict
        """
        return {"passed": self.passed, "failed": self.failed,
                "cases": {k: {"passed": p, "failed": f} for k, (p, f) in self.per_kind.items()}}

    def rows(self) -> list:
        """One row per kind: ``kind, passed, failed`` (for :func:`fdsc.paper.shared.report.html_table`).

        Returns
        -------
        list of dict
        """
        return [{"kind": k, "passed": p, "failed": f} for k, (p, f) in self.per_kind.items()]


@dataclass(frozen=True)
class Prop1Cases:
    """Proposition 1 on seeded random cases (see :func:`prop1_cases`).

    Parameters
    ----------
    cases : tuple of Prop1Case
        The cases, in the order drawn.
    seed : int
        Seed of the draw.
    """

    cases: tuple
    seed: int

    def __post_init__(self):
        object.__setattr__(self, "cases", tuple(self.cases))
        if not self.cases or not all(isinstance(c, Prop1Case) for c in self.cases):
            raise ValueError("cases must be a non-empty sequence of Prop1Case")

    def __len__(self):
        return len(self.cases)

    def summary(self) -> Prop1Summary:
        """The counts of :func:`prop1_summary`.

        Returns
        -------
        Prop1Summary
        """
        return prop1_summary(self)

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``total``, ``passed``, ``failed``, per kind ``{key}_passed`` and
            ``{key}_failed`` (key ``real``, ``mf``, ``win``, ``q1``), ``win_max_fail_periods``.
        """
        sm = self.summary()
        keys = {"infinite, real Ψ": "real", "infinite, MF": "mf", "window from rest": "win",
                "infinite, Q weighting one state": "q1"}
        out = {"total": count(len(self)), "passed": count(sm.passed), "failed": count(sm.failed)}
        for kind, (passed, failed) in sm.per_kind.items():
            out[f"{keys[kind]}_passed"] = count(passed)
            out[f"{keys[kind]}_failed"] = count(failed)
        return {**out, "win_max_fail_periods": num(sm.longest_failing_window)}

    def to_record(self) -> RecordPart:
        """Record entries ``prop1_checks`` (the counts) and ``prop1_short_windows`` (new).

        Returns
        -------
        RecordPart
        """
        summ = self.summary()
        windows = [c for c in self.cases if c.kind == _WINDOW]
        return RecordPart((
            entry("prop1_checks", "Sec. III, Proposition 1",
                  "S(Ω_in) > 0 and S(Ω_out) < 0 for frequency-limited states",
                  summ.counts(), "differs" if summ.failed else "match",
                  "seeded random stable systems (n = 2, 3), frequency-limited sums of sinusoids and "
                  "random positive-definite Q's. Holds for every steady state with LF/HF ranges; "
                  "fails for MF as in-band range (for real signals the MF weight is negative at "
                  "every frequency) and for short windows that contain the transient."),
            entry("prop1_short_windows", "Sec. III, Proposition 1, statement 2) (finite windows)",
                  None,
                  {"windows": len(windows), "failed": sum(not c.passed for c in windows),
                   "longest_failing_window_periods": summ.longest_failing_window,
                   "shortest_passing_window_periods":
                       min((c.periods for c in windows if c.passed), default=float("nan"))},
                  "new",
                  "windows [0, T_l] from rest, T_l in periods of the slowest tone: the proposition "
                  "fails only on short windows, where x is still near 0 while xdot = B d is not."),
        ))


@cached
def prop1_cases(n_cases: int = 120, *, seed: int = 2026) -> Prop1Cases:
    """Proposition 1 on seeded random systems, signals and weights.

    Each case draws a stable ``(A, B)`` (n = 2 or 3), a frequency-limited disturbance in a band
    Ω_i (so the steady state is frequency-limited too), Ω^in = Ω_i and an Ω^out disjoint from it,
    and random positive-definite ``Q^in``, ``Q^out``. The kinds of case (:data:`PROP1_KINDS`),
    drawn in turn:

    * ``"infinite, real Ψ"``: Ω_i ∈ {LF, HF}, steady-state average FD-EPF (exact);
    * ``"infinite, MF"``: Ω_i = MF (complex Ψ), steady state;
    * ``"infinite, Q weighting one state"``: as the first kind with Q's of condition number 1e8;
    * ``"window from rest"``: Ω_i ∈ {LF, HF}, x(0) = 0, the FD-EEF over a window
      ``[0, T_l]`` that contains the transient, T_l from 0.02 to 20 periods of the slowest tone.

    Parameters
    ----------
    n_cases : int, optional
        Number of cases.
    seed : int, optional
        Seed of the random draw.

    Returns
    -------
    Prop1Cases

    Notes
    -----
    Proposition 1 (paper eqs. (21), (22)) claims ``S(Ω^in, Q^in) > 0 > S(Ω^out, Q^out)`` for a
    state frequency-limited in Ω^in; S is the FD-EEF of paper eqs. (19), (20) and, over an
    infinite horizon, its average (FD-EPF, paper eq. (28)).

    Examples
    --------
    >>> res = prop1_cases(4)
    >>> len(res), res.cases[0].kind
    (4, 'infinite, real Ψ')
    """
    n_cases = as_count("n_cases", n_cases)
    rng = np.random.default_rng(seed)
    rows = []
    kinds = ([PROP1_KINDS[0]] * 2 + [PROP1_KINDS[1]] + [_WINDOW] * 2 + [PROP1_KINDS[3]])
    for c in range(n_cases):
        kind = kinds[c % len(kinds)]
        n = int(rng.integers(2, 4))
        A, B = random_hurwitz(rng, n), rng.standard_normal((n, 1))
        sys = LTISystem(A, B, np.eye(n), np.zeros((n, 1)))
        if kind == "infinite, Q weighting one state":
            # nearly rank one: condition number 1e8, so Q effectively sees one direction
            Qin, Qout = random_spd(rng, n, condition=1e8), random_spd(rng, n, condition=1e8)
        else:
            Qin, Qout = random_spd(rng, n), random_spd(rng, n)
        if kind == "infinite, MF":
            band_in, band_out = "MF", str(rng.choice(["LF", "HF"]))
        else:
            band_in = str(rng.choice(["LF", "HF"]))
            band_out = "HF" if band_in == "LF" else str(rng.choice(["LF", "MF"]))
        d = _tones_in(rng, band_in, int(rng.integers(1, 4)))
        periods = None
        if kind.startswith("infinite"):
            s_in = steady_state_power(sys, d, _BANDS[band_in], Qin).total
            s_out = steady_state_power(sys, d, _BANDS[band_out], Qout).total
        else:
            periods = float(np.exp(rng.uniform(np.log(0.02), np.log(20.0))))
            horizon = periods * 2 * np.pi / d.frequencies.min()
            dt = min(0.02 / d.frequencies.max(), horizon / 2000)
            horizon = dt * max(200, round(horizon / dt))
            sim = simulate(sys, d, time_grid(horizon, dt))
            s_in = fdeef(sim.t, sim.x, sim.xdot, _BANDS[band_in], Qin)
            s_out = fdeef(sim.t, sim.x, sim.xdot, _BANDS[band_out], Qout)
        rows.append(Prop1Case(c, kind, band_in, band_out, n, float(s_in), float(s_out), periods))
    return Prop1Cases(tuple(rows), int(seed))


def prop1_summary(rows: Prop1Cases) -> Prop1Summary:
    """Counts of passed/failed cases, overall and per kind.

    Parameters
    ----------
    rows : Prop1Cases or sequence of Prop1Case
        The cases of :func:`prop1_cases`.

    Returns
    -------
    Prop1Summary

    Examples
    --------
    >>> s = prop1_summary(prop1_cases(6))
    >>> s.passed + s.failed, sorted(s.per_kind) == sorted(PROP1_KINDS)
    (6, True)
    """
    cases = rows.cases if isinstance(rows, Prop1Cases) else tuple(rows)
    kinds = sorted({c.kind for c in cases})
    per = {k: (sum(c.passed for c in cases if c.kind == k),
               sum(not c.passed for c in cases if c.kind == k)) for k in kinds}
    failing = [c.periods for c in cases if c.kind == _WINDOW and not c.passed]
    return Prop1Summary(sum(c.passed for c in cases), sum(not c.passed for c in cases), per,
                        float(max(failing)) if failing else 0.0)
