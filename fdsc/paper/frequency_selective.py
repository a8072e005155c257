"""Chapter 'frequency_selective': Sec. III, FD-EEF/FD-EPF, Proposition 1 on random cases, paper
Remark 1, the FD-EPF of the aircraft loops, paper Table I.
"""

from dataclasses import dataclass

import numpy as np

from .._validation import as_choice, as_count, frozen_array
from ..bands import Band
from ..energy import fdeef, instantaneous_power, steady_state_power
from ..plant import LTISystem
from ..random_systems import random_hurwitz, random_spd
from ..signals import Sinusoids
from ..simulate import envelope, simulate, time_grid
from .cache import cached
from .data import (
    aircraft,
    hf_disturbance,
    lf_disturbance,
    paper_disturbance,
    paper_gains,
    paper_modes,
)
from .prose import count, num
from .results import RecordPart, entry
from .verdict import worst_verdict

__all__ = [
    "record_part",
    "PROP1_KINDS",
    "Prop1Case",
    "Prop1Cases",
    "Prop1Summary",
    "prop1_cases",
    "prop1_summary",
    "alpha_mix",
    "REMARK1_ALPHAS",
    "PowerVsAlpha",
    "power_vs_alpha",
    "EPFSeries",
    "epf_time_series",
    "EPFAircraft",
    "epf_aircraft",
    "Table1Check",
    "Table1Trends",
    "table1_trends",
]


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
        """One row per kind: ``kind, passed, failed`` (for :func:`fdsc.paper.report.html_table`).

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
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.prose`).

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
                  "S(Omega_in) > 0 and S(Omega_out) < 0 for frequency-limited states",
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


def alpha_mix(alpha: float) -> Sinusoids:
    """The paper's LF and HF tones mixed to dominance degree α(Ω_3) = α and unit mean power.

    ``d = √(2α/3) d_h + √(2(1 − α)/3) d_l`` with d_l, d_h the disturbances of paper eqs. (56),
    (57) (three unit tones each, mean power 3/2).

    Parameters
    ----------
    alpha : float
        Dominance degree of the HF range Ω_3, in [0, 1].

    Returns
    -------
    Sinusoids

    Raises
    ------
    ValueError
        If alpha lies outside [0, 1].

    Examples
    --------
    >>> round(alpha_mix(0.25).dominance(Band.hf(10.0)), 12)
    0.25
    """
    alpha = float(alpha)
    if not 0.0 <= alpha <= 1.0:
        raise ValueError(f"alpha must lie in [0, 1], found {alpha}")
    scale = np.sqrt(2.0 / 3.0)  # three unit tones have mean power 3/2
    return hf_disturbance().scaled(scale * np.sqrt(alpha)) + lf_disturbance().scaled(
        scale * np.sqrt(1.0 - alpha))


#: The dominance degrees of the paper Remark 1 curves: 0 to 1 in steps of 1/40.
REMARK1_ALPHAS = tuple(float(a) for a in np.linspace(0.0, 1.0, 41))


@dataclass(frozen=True)
class PowerVsAlpha:
    """Steady-state average FD-EPF of the law's terms against the dominance degree α(Ω_3).

    Parameters
    ----------
    alpha : (k,) ndarray
        Dominance degrees.
    curves : dict
        ``{label: (k,) ndarray}``: P_a of each (loop, band, Q) against α.
    in_band, out_of_band : dict
        ``{label: (k,) ndarray}``: the in-band and out-of-band parts of P_a.
    crossing : dict
        ``{label: α* or None}``: where P_a changes sign (None: no sign change in [0, 1]).
    """

    alpha: np.ndarray
    curves: dict
    in_band: dict
    out_of_band: dict
    crossing: dict

    def __post_init__(self):
        object.__setattr__(self, "alpha", frozen_array(np.asarray(self.alpha, dtype=float)))
        for name in ("curves", "in_band", "out_of_band"):
            for label, v in getattr(self, name).items():
                if np.shape(v) != self.alpha.shape:
                    raise ValueError(f"{name}[{label!r}] must have shape {self.alpha.shape} (one "
                                     f"value per alpha), but found {np.shape(v)}")

    def prose(self) -> dict:
        """The sign changes the chapter quotes, formatted (:mod:`fdsc.paper.prose`).

        Returns
        -------
        dict
            ``{"cross_<gain>_<lf|hf>": text}`` for each loop and term (``n/a``: no sign change);
            five digits, enough to tell the K_f3 loop's crossings from 1.
        """
        out = {}
        for label, a in self.crossing.items():
            key = label.split(" loop")[0] + ("_hf" if "Ω_3" in label else "_lf")
            out[f"cross_{key}"] = num(float("nan") if a is None else a, 5 if a and a > 0.99 else 3)
        return out

    def to_record(self) -> RecordPart:
        """Record entry ``remark1_crossings`` (new): the dominance degree where each term of the
        law changes sign on each loop.

        Returns
        -------
        RecordPart
        """
        return RecordPart((entry(
            "remark1_crossings", "Sec. III, paper Remark 1 (nothing printed)", None,
            dict(self.crossing), "new",
            "steady-state average FD-EPF of the law's terms (Omega_1, Q_1) and (Omega_3, Q_2), "
            "paper's Q's, on the K_f1 and K_f3 loops, disturbance mixing the paper's LF and HF "
            "tones at dominance alpha (unit mean power): P_a is affine in alpha and changes sign "
            "at alpha* = P_a(0) / (P_a(0) - P_a(1)) (null: no sign change in [0, 1]). The sign the "
            "law sees depends on the active loop, not only on the disturbance's dominance."),))


@cached
def power_vs_alpha(alphas: tuple = REMARK1_ALPHAS) -> PowerVsAlpha:
    """Paper Remark 1: steady-state average FD-EPF of both modes against the dominance degree.

    For each FDSC loop (K_f1, K_f3) and each term of the law ((Ω_1, Q_1), (Ω_3, Q_2)), ``P_a``
    is affine in α (mean powers add), so the sign change lies at ``α* = P_l / (P_l − P_h)`` with
    P_l, P_h the values at α = 0, 1.

    Parameters
    ----------
    alphas : sequence of float, optional
        Dominance degrees α(Ω_3) in [0, 1] (default :data:`REMARK1_ALPHAS`).

    Returns
    -------
    PowerVsAlpha

    Notes
    -----
    P_a is the average FD-EPF of paper eq. (28), evaluated exactly in steady state; the
    disturbance is :func:`alpha_mix`.

    Examples
    --------
    >>> pv = power_vs_alpha((0.0, 1.0))
    >>> sorted(pv.crossing)[0]
    'K_f1 loop, Ω_1, Q_1'
    """
    pm = paper_modes()
    alphas = np.asarray(alphas, dtype=float)
    curves, ins, outs, crossing = {}, {}, {}, {}
    for mname, mode in zip(pm["names"], pm["modes"], strict=True):
        for bname, band, Q in zip(("Ω_1, Q_1", "Ω_3, Q_2"), pm["bands"], pm["Q"], strict=True):
            label = f"{mname} loop, {bname}"
            splits = [steady_state_power(mode, alpha_mix(a), band, Q) for a in alphas]
            curves[label] = np.array([s.total for s in splits])
            ins[label] = np.array([s.in_band for s in splits])
            outs[label] = np.array([s.out_of_band for s in splits])
            p0 = steady_state_power(mode, alpha_mix(0.0), band, Q).total
            p1 = steady_state_power(mode, alpha_mix(1.0), band, Q).total
            crossing[label] = p0 / (p0 - p1) if (p0 - p1) != 0 and 0 <= p0 / (p0 - p1) <= 1 else None
    return PowerVsAlpha(alphas, curves, ins, outs, crossing)


@dataclass(frozen=True)
class EPFSeries:
    """Instantaneous FD-EPF of both law terms along an LTI closed loop (see
    :func:`epf_time_series`).

    Parameters
    ----------
    gain : str
        The printed gain whose closed loop was simulated (K_f1 and K_f3: the FDSC modes).
    disturbance : {"LF", "HF"}
        The paper's disturbance.
    t : (k,) ndarray
        Bin starts in s.
    bin : float
        Bin length in s.
    P_t_lo, P_t_hi : dict
        ``{"LF": (k,), "HF": (k,)}``: min/max of the instantaneous FD-EPF per bin.
    P_a : dict
        ``{"LF": (k,), "HF": (k,)}``: the running average at the bin starts.
    """

    gain: str
    disturbance: str
    t: np.ndarray
    bin: float
    P_t_lo: dict
    P_t_hi: dict
    P_a: dict

    @property
    def final_average(self) -> dict:
        """``{"LF": P_a, "HF": P_a}`` at the end of the run."""
        return {k: float(v[-1]) for k, v in self.P_a.items()}

    @property
    def selective(self) -> bool:
        """The term of the disturbance's own range ends positive and the other term negative."""
        other = "HF" if self.disturbance == "LF" else "LF"
        avg = self.final_average
        return bool(avg[self.disturbance] > 0 > avg[other])


@cached
def epf_time_series(gain: str, disturbance: str, *, horizon: float = 200.0, dt: float = 1e-3,
                    every: int = 20) -> EPFSeries:
    """Instantaneous FD-EPF of both law terms along an LTI closed loop (from rest).

    Parameters
    ----------
    gain : {"K_f1", "K_f2", "K_f3", "K_e"}
        The printed gain whose closed loop is simulated (K_f1 and K_f3 are the FDSC modes).
    disturbance : {"LF", "HF"}
        The paper's LF (paper eq. (56)) or HF (paper eq. (57)) disturbance.
    horizon, dt : float, optional
        Run length and step in s.
    every : int, optional
        Samples per bin of the decimated record.

    Returns
    -------
    EPFSeries

    Notes
    -----
    The instantaneous FD-EPF is paper eq. (29) with the law's (Ω_1, Q_1) and (Ω_3, Q_2); the
    running average is paper eq. (28) over [0, t].
    """
    gains = paper_gains()
    as_choice("gain", gain, tuple(gains))
    pm = paper_modes()
    cl = aircraft().closed_loop(gains[gain])
    d = paper_disturbance(disturbance)
    sim = simulate(cl, d, time_grid(horizon, dt))
    lo, hi, avg = {}, {}, {}
    for kind, band, Q in zip(("LF", "HF"), pm["bands"], pm["Q"], strict=True):
        p = instantaneous_power(sim.x, sim.xdot, band, Q)
        run = np.concatenate([[p[0]], np.cumsum(0.5 * (p[1:] + p[:-1])) * dt / sim.t[1:]])
        # P_t oscillates at up to twice the fastest tone: keep its min/max per bin, not every
        # n-th sample (which would alias); the running average P_a is smooth
        _, lo[kind], hi[kind] = envelope(sim.t, p, every)
        avg[kind] = run[::every]
    return EPFSeries(gain, disturbance, sim.t[::every], every * dt, lo, hi, avg)


#: The (gain, disturbance) pairs of the aircraft FD-EPF figure.
_EPF_PAIRS = (("K_f1", "LF"), ("K_f1", "HF"), ("K_f3", "LF"), ("K_f3", "HF"))


@dataclass(frozen=True)
class EPFAircraft:
    """The FD-EPF of the two FDSC loops under the paper's two disturbances.

    Parameters
    ----------
    series : tuple of EPFSeries
        One per (gain, disturbance) in the order K_f1/LF, K_f1/HF, K_f3/LF, K_f3/HF.
    horizon : float
        Run length in s.
    """

    series: tuple
    horizon: float

    def get(self, gain: str, disturbance: str) -> EPFSeries:
        """The series of one loop under one disturbance.

        Parameters
        ----------
        gain : {"K_f1", "K_f3"}
            The loop.
        disturbance : {"LF", "HF"}
            The disturbance.

        Returns
        -------
        EPFSeries
        """
        for s in self.series:
            if (s.gain, s.disturbance) == (gain, disturbance):
                return s
        raise KeyError(f"no series for gain {gain!r} and disturbance {disturbance!r}")

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``epf_horizon``, ``epf_n_selective``, ``epf_n_runs`` and the
            running averages at the horizon ``pa_<gain>_<disturbance>_<term>``.
        """
        out = {"epf_horizon": num(float(self.horizon)) if not float(self.horizon).is_integer()
               else count(int(self.horizon)),
               "epf_n_selective": count(sum(s.selective for s in self.series)),
               "epf_n_runs": count(len(self.series))}
        for s in self.series:
            for kind, value in s.final_average.items():
                out[f"pa_{s.gain}_{s.disturbance}_{kind}"] = num(value)
        return out

    def to_record(self) -> RecordPart:
        """Record entry ``epf_aircraft_signs`` (new): the running averages at the horizon and
        whether each run is frequency-selective.

        Returns
        -------
        RecordPart
        """
        rec = {f"{s.gain}, {s.disturbance} disturbance": {**s.final_average, "selective": s.selective}
               for s in self.series}
        n_sel = sum(s.selective for s in self.series)
        return RecordPart((entry(
            "epf_aircraft_signs", "Sec. III, Proposition 1 on the aircraft loops (nothing printed)",
            None, rec, "new",
            f"running average FD-EPF of the law's LF term (Omega_1, Q_1) and HF term (Omega_3, Q_2) "
            f"at t = {self.horizon:g} s, from rest; selective = the term of the disturbance's range "
            f"positive, the other negative: {n_sel} of {len(self.series)} runs."),))


@cached
def epf_aircraft(*, horizon: float = 200.0) -> EPFAircraft:
    """:func:`epf_time_series` for both FDSC loops under both paper disturbances.

    Parameters
    ----------
    horizon : float, optional
        Run length in s.

    Returns
    -------
    EPFAircraft

    Notes
    -----
    Proposition 1 (paper eqs. (21), (22)) predicts the signs of the running averages (paper
    eq. (28)) in steady state.
    """
    return EPFAircraft(tuple(epf_time_series(g, d, horizon=horizon) for g, d in _EPF_PAIRS),
                       float(horizon))


@dataclass(frozen=True)
class Table1Check:
    """One row of paper Table I against the dominance degree α_i.

    Parameters
    ----------
    quantity : str
        The quantity of the row.
    claimed : {"up", "down"}
        The trend the paper claims as α_i grows.
    values : (k,) ndarray
        The quantity at each α_i.
    observed : str
        ``"up"``, ``"down"``, ``"non-decreasing"``, ``"non-increasing"`` or ``"not monotone"``.
    verdict : {"match", "differs"}
        Whether the observed trend is the claimed one.
    """

    quantity: str
    claimed: str
    values: np.ndarray
    observed: str
    verdict: str


def _trend(values):
    diffs = np.diff(values)
    if np.all(diffs > 0):
        return "up"
    if np.all(diffs < 0):
        return "down"
    if np.all(diffs >= 0):
        return "non-decreasing"
    if np.all(diffs <= 0):
        return "non-increasing"
    return "not monotone"


@dataclass(frozen=True)
class Table1Trends:
    """The rows of paper Table I checked against the dominance degree (see :func:`table1_trends`).

    Parameters
    ----------
    alpha : (k,) ndarray
        The dominance degrees α_i.
    checks : tuple of Table1Check
        One per row of the table.
    horizon, dt : float
        Length and step in s of the switched simulations.
    """

    alpha: np.ndarray
    checks: tuple
    horizon: float
    dt: float

    def check(self, quantity: str) -> Table1Check:
        """The check of one row.

        Parameters
        ----------
        quantity : str
            The row's quantity (e.g. ``"β_i"``).

        Returns
        -------
        Table1Check
        """
        for c in self.checks:
            if c.quantity == quantity:
                return c
        raise KeyError(f"quantity must be one of {[c.quantity for c in self.checks]}, but found "
                       f"{quantity!r}")

    @property
    def n_match(self) -> int:
        """Number of rows whose observed trend is the claimed one."""
        return sum(c.verdict == "match" for c in self.checks)

    @property
    def beta_range(self) -> tuple:
        """Smallest and largest time share β_i of the in-band mode over α_i."""
        beta = self.check("β_i").values
        return float(beta.min()), float(beta.max())

    def rows(self) -> list:
        """One row per check: ``quantity, claimed, observed, values`` (text), ``verdict``.

        Returns
        -------
        list of dict
        """
        return [{"quantity": c.quantity, "claimed": c.claimed, "observed": c.observed,
                 "values": ", ".join(num(float(v), 4) for v in c.values), "verdict": c.verdict}
                for c in self.checks]

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``t1_alphas``, ``t1_horizon``, ``t1_match``, ``t1_rows``,
            ``t1_beta_min``, ``t1_beta_max``.
        """
        lo, hi = self.beta_range
        horizon = float(self.horizon)
        return {"t1_alphas": ", ".join(num(float(a), 2) for a in self.alpha),
                "t1_horizon": count(int(horizon)) if horizon.is_integer() else num(horizon),
                "t1_match": count(self.n_match), "t1_rows": count(len(self.checks)),
                "t1_beta_min": num(lo), "t1_beta_max": num(hi)}

    def to_record(self) -> RecordPart:
        """Record entry ``table1_checks``.

        Returns
        -------
        RecordPart
        """
        t1 = {c.quantity: {"claimed": c.claimed, "observed": c.observed, "values": c.values,
                           "verdict": c.verdict} for c in self.checks}
        return RecordPart((entry(
            "table1_checks", "Sec. III, Table I", {c.quantity: c.claimed for c in self.checks},
            t1, worst_verdict([c.verdict for c in self.checks]),
            "mode i = PassC-HF (Omega_3, Q_2), mode j = PassC-LF (Omega_1, Q_1), disturbance "
            "mixing the paper's LF and HF tones at dominance alpha_i; steady-state rows exact, "
            f"time shares from switched simulations of {self.horizon:g} s (paper's Q's).",
            alpha=self.alpha),))


@cached
def table1_trends(alphas: tuple = (0.2, 0.5, 0.8, 0.95, 0.99), *, horizon: float = 100.0,
                  dt: float = 1e-3) -> Table1Trends:
    """The rows of paper Table I checked against the dominance degree α_i of the in-band range Ω_3.

    Mode i is the HF controller K_f3 with (Ω_3, Q_2), mode j the LF controller K_f1 with
    (Ω_1, Q_1); the disturbance is :func:`alpha_mix`. Steady-state rows are exact; the time
    shares come from switched simulations (default law: measured ẋ) over ``horizon``.

    Parameters
    ----------
    alphas : sequence of float, optional
        Increasing dominance degrees in [0, 1].
    horizon, dt : float, optional
        Length and step in s of the switched simulations.

    Returns
    -------
    Table1Trends

    Notes
    -----
    Paper Table I lists how the FD-EPF terms (paper eq. (28)) and the time shares β_i of the
    law (paper eq. (31)) move as α_i grows; a row matches when the observed trend is the
    claimed one (non-strict monotony counts).
    """
    pm = paper_modes()
    (cl_j, cl_i), (band_j, band_i), (Q_j, Q_i) = pm["modes"], pm["bands"], pm["Q"]
    alphas = np.asarray(alphas, dtype=float)
    pin, pout, pa, pj, Ti, Tj = [], [], [], [], [], []
    t = time_grid(horizon, dt)
    for a in alphas:
        d = alpha_mix(a)
        s = steady_state_power(cl_i, d, band_i, Q_i)
        pin.append(abs(s.in_band))
        pout.append(abs(s.out_of_band))
        pa.append(s.total)
        pj.append(steady_state_power(cl_j, d, band_j, Q_j).total)
        sim = simulate(pm["modes"], d, t, law_bands=pm["bands"], law_Q=pm["Q"])
        share = sim.time_share()
        Ti.append(share[1] * horizon)
        Tj.append(share[0] * horizon)
    beta = np.array(Ti) / horizon
    spec = [("|P_a^in(Ω_i, Q_i, A_i, B_i)|", "up", pin), ("|P_a^out(Ω_i, Q_i, A_i, B_i)|", "down", pout),
            ("P_a(Ω_i, Q_i, A_i, B_i)", "up", pa), ("max_j P_a(Ω_j, Q_j, A_j, B_j)", "down", pj),
            ("T_i (time in mode i)", "up", Ti), ("Σ_j T_j", "down", Tj), ("β_i", "up", beta)]
    checks = []
    for name, claim, vals in spec:
        v = np.asarray(vals, dtype=float)
        observed = _trend(v)
        ok = observed == claim or (claim == "up" and observed == "non-decreasing") or (
            claim == "down" and observed == "non-increasing")
        checks.append(Table1Check(name, claim, v, observed, "match" if ok else "differs"))
    return Table1Trends(alphas, tuple(checks), horizon, dt)


def record_part() -> RecordPart:
    """Record entries of the chapter (Sec. III).

    ``prop1_checks``, ``prop1_short_windows`` (new), ``table1_checks``,
    ``remark1_crossings`` (new) and ``epf_aircraft_signs`` (new).

    Returns
    -------
    RecordPart
    """
    return (prop1_cases(144).to_record() + table1_trends().to_record()
            + power_vs_alpha().to_record() + epf_aircraft().to_record())
