"""Chapter 'stationary': paper Figs. 4, 5 and 6 (stationary LF and HF disturbances, four
controllers), energies, the paper's sentences about these figures, and step halving.
"""

from dataclasses import dataclass

import numpy as np

from .._validation import as_choice, as_positive
from ..frequency import steady_state_gain
from ..simulate import envelope, time_grid
from .cache import cached
from .data import (
    STATIONARY_DT,
    STATIONARY_HORIZON,
    aircraft,
    our_q,
    paper_disturbance,
    paper_gains,
    run_controller,
)
from .names import CONTROLLER_GAINS, CONTROLLERS, FIGURE_IDS
from .prose import count, num, pct, times
from .results import RecordPart, entry
from .verdict import worst_verdict

__all__ = [
    "record_part",
    "OUR_Q_NAME",
    "StationaryRuns",
    "stationary_runs",
    "Claim",
    "LFOutputClaims",
    "lf_output_claims",
    "HFOutputClaims",
    "hf_output_claims",
    "L2Claims",
    "hf_l2_claims",
    "HalvingRow",
    "StepHalving",
    "step_halving",
    "StationaryComparison",
    "against_comparators",
]


#: The name of FDSC with our Q's beside the paper's four controllers.
OUR_Q_NAME = "FDSC (our Q)"


def _whole(x):
    """A count or a length as the prose prints it: whole numbers without decimals."""
    x = float(x)
    return count(int(x)) if x.is_integer() else num(x)


def _l2_norm_curve(sim):
    """Running L2-induced norm sqrt(∫₀ᵗ zᵀz / ∫₀ᵗ d²) on the grid (trapezoid; dt cancels)."""
    zz = np.concatenate([[0.0], np.cumsum(0.5 * (np.sum(sim.z[1:] ** 2, 1) + np.sum(sim.z[:-1] ** 2, 1)))])
    dd = np.concatenate([[0.0], np.cumsum(0.5 * (sim.d[1:] ** 2 + sim.d[:-1] ** 2))])
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = np.sqrt(np.where(dd > 0, zz / dd, np.nan))
    return ratio


@dataclass(frozen=True)
class StationaryRuns:
    """The controllers under one stationary disturbance, from rest (see :func:`stationary_runs`).

    Parameters
    ----------
    kind : {"LF", "HF"}
        The disturbance.
    horizon, dt : float
        Run length and step in s.
    every : int
        Samples per bin of the decimated traces.
    t : (k,) ndarray
        Bin starts in s.
    z_lo, z_hi : dict
        ``{controller: (k, 3) ndarray}``: min/max of z per bin.
    t_head : (h,) ndarray
        Times of the start of the run kept at full resolution.
    z_head : dict
        ``{controller: (h, 3) ndarray}``: z over ``t_head``.
    energy : dict
        ``{controller: ∫zᵀz dt}`` over the run.
    input_energy : float
        ∫d² dt over the run.
    l2 : dict
        ``{controller: (k,) ndarray}``: running L2-induced norm at the bin starts.
    t_l2 : (k,) ndarray
        Bin starts of ``l2_lo``/``l2_hi`` (the ratio is undefined at t = 0).
    l2_lo, l2_hi : dict
        ``{controller: (k,) ndarray}``: min/max of the running norm per bin.
    l2_steady : dict
        ``{fixed-gain controller: the limit of its running ratio}`` (closed form).
    peak : dict
        ``{controller: (3,) ndarray}``: max |z_i| over the run.
    switches : dict
        ``{FDSC variant: number of switches}``.
    share : dict
        ``{FDSC variant: [share of mode 1, share of mode 2]}``.
    """

    kind: str
    horizon: float
    dt: float
    every: int
    t: np.ndarray
    z_lo: dict
    z_hi: dict
    t_head: np.ndarray
    z_head: dict
    energy: dict
    input_energy: float
    l2: dict
    t_l2: np.ndarray
    l2_lo: dict
    l2_hi: dict
    l2_steady: dict
    peak: dict
    switches: dict
    share: dict

    def __post_init__(self):
        as_choice("kind", self.kind, ("LF", "HF"))

    @property
    def names(self) -> tuple:
        """The controllers run, in order."""
        return tuple(self.energy)

    @property
    def l2_final(self) -> dict:
        """``{controller: running L2-induced norm at the horizon}``."""
        return {k: float(v[-1]) for k, v in self.l2.items()}

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``horizon``, ``dt_ms``, ``bin_ms``, ``head_s``; per controller
            ``E_<name>`` (∫zᵀz) and ``l2_ss_<name>`` (steady-state L2-induced norm, fixed gains);
            per switched controller ``sw_<name>`` (switches), ``share_hf_<name>`` (time on the HF
            gain) and ``peak_dE_<name>`` (peak of 2δ_E); ``sw_paper``, ``sw_ours``,
            ``share_paper`` and ``fdsc_peak_dE`` for FDSC with the paper's and our Q's.
        """
        out = {"horizon": _whole(self.horizon), "dt_ms": _whole(round(self.dt * 1e3, 9)),
               "bin_ms": _whole(round(self.every * self.dt * 1e3, 9)),
               "head_s": _whole(round(float(self.t_head[-1]), 9))}
        out.update({f"E_{name}": num(float(e), 4) for name, e in self.energy.items()})
        out.update({f"l2_ss_{name}": num(float(v), 4) for name, v in self.l2_steady.items()})
        for name, n in self.switches.items():
            out.update({f"sw_{name}": count(int(n)), f"share_hf_{name}": pct(float(self.share[name][1]), 1),
                        f"peak_dE_{name}": num(float(self.peak[name][1]))})
        return {**out, "sw_paper": out["sw_FDSC"], "sw_ours": out[f"sw_{OUR_Q_NAME}"],
                "share_paper": out["share_hf_FDSC"], "fdsc_peak_dE": out["peak_dE_FDSC"]}

    def to_record(self) -> RecordPart:
        """Record figures ``lf_outputs`` (LF) or ``hf_outputs`` and ``hf_l2`` (HF).

        Returns
        -------
        RecordPart
        """
        fig = {"LF": "lf_outputs", "HF": "hf_outputs"}[self.kind]
        data = {"paper_figure": FIGURE_IDS[fig], "disturbance": self.kind,
                "horizon": self.horizon, "dt": self.dt,
                "energy": {k: v for k, v in self.energy.items() if k != OUR_Q_NAME}}
        if OUR_Q_NAME in self.energy:
            data["energy_fdsc_our_q"] = self.energy[OUR_Q_NAME]
        data["switches"] = self.switches
        data["units"] = {"horizon": "s", "dt": "s",
                         "energy": "integral of z'z over [0, horizon] (z as printed, s)"}
        figures = {fig: data}
        if self.kind == "HF":
            figures["hf_l2"] = {
                "paper_figure": FIGURE_IDS["hf_l2"], "horizon": self.horizon,
                "l2_induced_norm_final": self.l2_final,
                "l2_induced_norm_steady_state": self.l2_steady,
                "units": {"horizon": "s", "l2_induced_norm": "1 (sqrt of an energy ratio)"},
                "note": "running ratio from rest at the horizon; steady state = its limit for the "
                        "fixed gains (closed form); FDSC has no closed form"}
        return RecordPart(figures=figures)


@cached
def stationary_runs(kind: str, *, horizon: float = STATIONARY_HORIZON, dt: float = STATIONARY_DT,
                    every: int = 50, head: float = 2.0, with_our_q: bool = True) -> StationaryRuns:
    """Paper Figs. 4 (kind="LF"), 5 and 6 (kind="HF"): the four controllers under a stationary
    disturbance, from rest.

    Parameters
    ----------
    kind : {"LF", "HF"}
        The paper's LF (paper eq. (56)) or HF (paper eq. (57)) disturbance.
    horizon, dt : float, optional
        Run length and step in s.
    every : int, optional
        Samples per bin of the decimated traces (min/max envelope, so nothing is aliased).
    head : float, optional
        Length in s of the start of the run kept at full resolution.
    with_our_q : bool, optional
        Add FDSC with our Q's (:data:`OUR_Q_NAME`).

    Returns
    -------
    StationaryRuns

    Raises
    ------
    ValueError
        If kind is not "LF" or "HF", or head is not positive.

    Notes
    -----
    The controllers are PassC-EF (K_e), PassC-LF (K_f1), PassC-HF (K_f3) and FDSC (law of paper
    eq. (31), paper's Q's), Sec. IV; the horizon is not printed (we use
    :data:`~fdsc.paper.data.STATIONARY_HORIZON`).
    """
    d = paper_disturbance(kind)
    t = time_grid(horizon, dt)
    names = list(CONTROLLERS) + ([OUR_Q_NAME] if with_our_q else [])
    Qours = our_q().Q if with_our_q else None
    n_head = int(round(as_positive("head", head) / dt)) + 1
    z_lo, z_hi, z_head, energy, l2, l2_lo, l2_hi, peak, switches, share = ({} for _ in range(10))
    l2_steady = {c: steady_state_gain(aircraft().closed_loop(paper_gains()[g]), d.frequencies,
                                      d.amplitudes) for c, g in CONTROLLER_GAINS.items()}
    t_l2, input_energy = None, None
    for name in names:
        sim = run_controller("FDSC", d, t, Q=Qours) if name == OUR_Q_NAME else run_controller(name, d, t)
        _, z_lo[name], z_hi[name] = envelope(sim.t, sim.z, every)
        z_head[name] = sim.z[:n_head]
        peak[name] = np.abs(sim.z).max(axis=0)
        energy[name] = sim.energy()
        curve = _l2_norm_curve(sim)
        l2[name] = curve[::every]
        t_l2, l2_lo[name], l2_hi[name] = envelope(sim.t[1:], curve[1:], every)
        input_energy = sim.input_energy()
        if name.startswith("FDSC"):
            switches[name] = int(sim.switch_times.size)
            share[name] = sim.time_share().tolist()
    return StationaryRuns(kind, horizon, dt, every, t[::every], z_lo, z_hi, t[:n_head], z_head,
                          energy, input_energy, l2, t_l2, l2_lo, l2_hi, l2_steady, peak, switches,
                          share)


@dataclass(frozen=True)
class Claim:
    """A sentence of the paper set against the number that decides it.

    Parameters
    ----------
    sentence : str
        The paper's words.
    reading : str
        How we read them: the criterion applied to ``value``.
    value : float or tuple of float
        The deciding number(s).
    holds : bool
        Whether the criterion holds.
    """

    sentence: str
    reading: str
    value: float | tuple
    holds: bool

    @property
    def verdict(self) -> str:
        """``"match"`` if the sentence holds, else ``"differs"``."""
        return "match" if self.holds else "differs"

    @property
    def outcome(self) -> str:
        """``"holds"`` or ``"fails"`` (the word the book prints)."""
        return "holds" if self.holds else "fails"

    def to_dict(self) -> dict:
        """``{"sentence", "reading", "value", "holds", "verdict"}`` for the record.

        Returns
        -------
        dict
        """
        return {"sentence": self.sentence, "reading": self.reading, "value": self.value,
                "holds": self.holds, "verdict": self.verdict}


def _claims_entry(id_, source, claims, note, **extra):
    return entry(id_, source, [c.sentence for c in claims],
                 {**{c.sentence: c.to_dict() for c in claims}, **extra},
                 worst_verdict([c.verdict for c in claims]), note)


def _check_kind(runs, kind):
    if not isinstance(runs, StationaryRuns) or runs.kind != kind:
        raise ValueError(f"runs must be the StationaryRuns of the {kind} disturbance, but found "
                         f"{getattr(runs, 'kind', type(runs).__name__)!r}")


@dataclass(frozen=True)
class LFOutputClaims:
    """The paper's sentences about paper Fig. 4 (LF disturbance) against our numbers.

    Parameters
    ----------
    smallest, largest : str
        The controllers (of the paper's four) with the smallest and the largest energy.
    ratio_fdsc_lf : float
        Energy of FDSC over that of PassC-LF.
    ratio_hf_fdsc : float
        Energy of PassC-HF over that of FDSC.
    ratio_ours_lf : float
        Energy of FDSC with our Q's over that of PassC-LF (NaN if not run).
    peak_ratio_hf : (3,) ndarray
        Peak |z_i| of PassC-HF over the larger peak of PassC-EF and PassC-LF, per output.
    peak_ratio_fdsc_hf : (3,) ndarray
        Peak |z_i| of FDSC over that of PassC-HF, per output.
    claim_smallest, claim_thousand, claim_similar : Claim
        "PassC-LF is the smallest"; "PassC-HF is up to a thousand times greater"; "FDSC …
        similar to PassC-LF".
    """

    smallest: str
    largest: str
    ratio_fdsc_lf: float
    ratio_hf_fdsc: float
    ratio_ours_lf: float
    peak_ratio_hf: np.ndarray
    peak_ratio_fdsc_hf: np.ndarray
    claim_smallest: Claim
    claim_thousand: Claim
    claim_similar: Claim

    @property
    def claims(self) -> tuple:
        """The claims, in the paper's order."""
        return (self.claim_smallest, self.claim_thousand, self.claim_similar)

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.prose`).

        Returns
        -------
        dict
            ``{name: text}``: energy factors ``ratio_fdsc_lf``, ``ratio_hf_fdsc``,
            ``ratio_ours_lf``; peak factors ``peak_ratio_min``, ``peak_ratio_max`` (PassC-HF
            against the better of PassC-EF and PassC-LF) and ``fdsc_peak_vs_hf_max``; the
            outcomes ``smallest_verdict``, ``thousand_verdict``, ``similar_verdict``.
        """
        return {"ratio_fdsc_lf": times(self.ratio_fdsc_lf), "ratio_hf_fdsc": times(self.ratio_hf_fdsc),
                "ratio_ours_lf": times(self.ratio_ours_lf),
                "peak_ratio_min": times(float(self.peak_ratio_hf.min())),
                "peak_ratio_max": times(float(self.peak_ratio_hf.max())),
                "fdsc_peak_vs_hf_max": times(float(self.peak_ratio_fdsc_hf.max()), 2),
                "smallest_verdict": self.claim_smallest.outcome,
                "thousand_verdict": self.claim_thousand.outcome,
                "similar_verdict": self.claim_similar.outcome}

    def to_record(self) -> RecordPart:
        """Record entry ``lf_outputs_claims``.

        Returns
        -------
        RecordPart
        """
        return RecordPart((_claims_entry(
            "lf_outputs_claims", "Sec. IV, text on paper Fig. 4", self.claims,
            "energies and peak outputs of the runs of paper Fig. 4 (our horizon); each sentence "
            "read as the stated criterion.",
            energy_ratio_fdsc_to_passc_lf=self.ratio_fdsc_lf,
            energy_ratio_passc_hf_to_fdsc=self.ratio_hf_fdsc,
            energy_ratio_fdsc_our_q_to_passc_lf=self.ratio_ours_lf,
            peak_ratio_fdsc_to_passc_hf=self.peak_ratio_fdsc_hf),))


def lf_output_claims(runs: StationaryRuns) -> LFOutputClaims:
    """Set the paper's sentences about paper Fig. 4 against the LF runs.

    The paper: "the fluctuation range of PassC-LF is the smallest … PassC-HF is up to a
    thousand times greater … FDSC provides pretty good anti-disturbance performance that is
    similar to PassC-LF".

    Parameters
    ----------
    runs : StationaryRuns
        The runs of :func:`stationary_runs` under the LF disturbance (paper eq. (56)).

    Returns
    -------
    LFOutputClaims

    Raises
    ------
    ValueError
        If runs are not those of the LF disturbance.
    """
    _check_kind(runs, "LF")
    e, pk = runs.energy, runs.peak
    four = {n: e[n] for n in CONTROLLERS}
    smallest, largest = min(four, key=four.get), max(four, key=four.get)
    ratio_fdsc_lf = e["FDSC"] / e["PassC-LF"]
    # the fixed-gain lines; FDSC is discussed on its own
    peak_ratio = pk["PassC-HF"] / np.max([pk[n] for n in ("PassC-EF", "PassC-LF")], axis=0)
    next_smallest = min(v for n, v in four.items() if n != "PassC-LF")
    smallest_claim, thousand, similar = (
        Claim("the fluctuation range of PassC-LF is the smallest",
              "PassC-LF has the smallest energy of the four controllers (value: the next "
              "smallest energy over PassC-LF's)", next_smallest / e["PassC-LF"],
              smallest == "PassC-LF"),
        Claim("PassC-HF is up to a thousand times greater",
              "the largest ratio of PassC-HF's peak output to the larger of PassC-EF's and "
              "PassC-LF's lies between 300 and 3000", float(peak_ratio.max()),
              bool(300 <= peak_ratio.max() <= 3000)),
        Claim("FDSC provides pretty good anti-disturbance performance that is similar to PassC-LF",
              "FDSC's energy within a factor 2 of PassC-LF's", ratio_fdsc_lf,
              bool(ratio_fdsc_lf <= 2)),
    )
    return LFOutputClaims(smallest, largest, ratio_fdsc_lf, e["PassC-HF"] / e["FDSC"],
                          e[OUR_Q_NAME] / e["PassC-LF"] if OUR_Q_NAME in e else np.nan,
                          peak_ratio, pk["FDSC"] / pk["PassC-HF"], smallest_claim, thousand, similar)


@dataclass(frozen=True)
class HFOutputClaims:
    """The paper's sentences about paper Fig. 5 (HF disturbance) against our numbers.

    Parameters
    ----------
    q_peak : dict
        ``{controller: max |q|}`` over the run for the paper's four controllers (q = z_1 / 4).
    q_ratio : float
        Largest over smallest of ``q_peak``.
    ratio_fdsc_hf : float
        Energy of FDSC over that of PassC-HF.
    claim_range, claim_coincident : Claim
        "the fluctuation range of these lines is less than 0.15"; "the four lines are almost
        coincident".
    """

    q_peak: dict
    q_ratio: float
    ratio_fdsc_hf: float
    claim_range: Claim
    claim_coincident: Claim

    @property
    def claims(self) -> tuple:
        """The claims, in the order of :meth:`to_record`."""
        return (self.claim_range, self.claim_coincident)

    @property
    def q_min(self) -> float:
        """Smallest peak of |q| over the four controllers."""
        return min(self.q_peak.values())

    @property
    def q_max(self) -> float:
        """Largest peak of |q| over the four controllers."""
        return max(self.q_peak.values())

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``ratio_fdsc_hf`` (energy factor), ``q_range_min``,
            ``q_range_max`` (peaks of |q|), ``q_ratio`` (largest over smallest), ``q_verdict``,
            ``coincident_verdict``.
        """
        return {"ratio_fdsc_hf": times(self.ratio_fdsc_hf), "q_range_min": num(self.q_min),
                "q_range_max": num(self.q_max), "q_ratio": times(self.q_ratio, 2),
                "q_verdict": self.claim_range.outcome,
                "coincident_verdict": self.claim_coincident.outcome}

    def to_record(self) -> RecordPart:
        """Record entry ``hf_outputs_claims``.

        Returns
        -------
        RecordPart
        """
        return RecordPart((_claims_entry(
            "hf_outputs_claims", "Sec. IV, text on paper Fig. 5", self.claims,
            "peak |q| (paper Fig. 5 a plots q; z_1 = 4q) of the runs of paper Fig. 5 (our "
            "horizon); each sentence read as the stated criterion.",
            q_peak=self.q_peak, energy_ratio_fdsc_to_passc_hf=self.ratio_fdsc_hf),))


def hf_output_claims(runs: StationaryRuns) -> HFOutputClaims:
    """Set the paper's sentences about paper Fig. 5 against the HF runs.

    The paper: "the four lines are almost coincident and the fluctuation range of these lines
    is less than 0.15".

    Parameters
    ----------
    runs : StationaryRuns
        The runs of :func:`stationary_runs` under the HF disturbance (paper eq. (57)).

    Returns
    -------
    HFOutputClaims

    Raises
    ------
    ValueError
        If runs are not those of the HF disturbance.
    """
    _check_kind(runs, "HF")
    # the paper's Fig. 5 a plots q itself; z_1 = 4q
    q = {n: float(runs.peak[n][0]) / 4 for n in CONTROLLERS}
    q_ratio = max(q.values()) / min(q.values())
    in_range, coincident = (
        Claim("the fluctuation range of these lines is less than 0.15",
              "the largest peak of |q| over the four controllers is below 0.15",
              max(q.values()), bool(max(q.values()) < 0.15)),
        Claim("the four lines are almost coincident",
              "the largest peak of |q| is within a factor 1.5 of the smallest", q_ratio,
              bool(q_ratio <= 1.5)),
    )
    return HFOutputClaims(q, q_ratio, runs.energy["FDSC"] / runs.energy["PassC-HF"], in_range,
                          coincident)


@dataclass(frozen=True)
class L2Claims:
    """The paper's sentence about paper Fig. 6 (L2-induced norm, HF) against our numbers.

    Parameters
    ----------
    final : dict
        ``{controller: running L2-induced norm at the horizon}``.
    ratios : (4,) ndarray
        Norms of PassC-EF and PassC-LF over those of PassC-HF and FDSC (EF/HF, EF/FDSC, LF/HF,
        LF/FDSC).
    slow_pole_hf : float
        Real part of the slowest pole of the PassC-HF loop.
    fdsc_beats_hf : str
        Whether FDSC's norm is below PassC-HF's: ``"at this horizon only"``, ``"also against
        the steady state"`` or ``"not even at this horizon"``.
    claim_twice : Claim
        "… nearly twice that of PassC-HF and FDSC".
    """

    final: dict
    ratios: np.ndarray
    slow_pole_hf: float
    fdsc_beats_hf: str
    claim_twice: Claim

    @property
    def claims(self) -> tuple:
        """The claims (one)."""
        return (self.claim_twice,)

    @property
    def time_constant_hf(self) -> float:
        """Time constant ``−1/slow_pole_hf`` of the PassC-HF loop in s."""
        return -1.0 / self.slow_pole_hf

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.prose`).

        Returns
        -------
        dict
            ``{name: text}``: the norm of each controller at the horizon (keyed by its name),
            ``ratio_min``, ``ratio_max``, ``twice_verdict``, ``slow_pole_hf``,
            ``time_constant_hf`` and ``fdsc_beats_hf`` (in words).
        """
        return {**{name: num(float(v), 4) for name, v in self.final.items()},
                "ratio_min": num(float(self.ratios.min())), "ratio_max": num(float(self.ratios.max())),
                "twice_verdict": self.claim_twice.outcome, "slow_pole_hf": num(self.slow_pole_hf),
                "time_constant_hf": _whole(round(self.time_constant_hf)),
                "fdsc_beats_hf": self.fdsc_beats_hf}

    def to_record(self) -> RecordPart:
        """Record entry ``hf_l2_claims``.

        Returns
        -------
        RecordPart
        """
        return RecordPart((_claims_entry(
            "hf_l2_claims", "Sec. IV, text on paper Fig. 6", self.claims,
            "running L2-induced norms at the horizon of the runs of paper Fig. 6; PassC-HF's "
            "slowest pole keeps its start-up transient in the ratio at that horizon, so FDSC's "
            "advantage over PassC-HF is compared with PassC-HF's steady-state limit too.",
            l2_final=self.final, passc_hf_slowest_pole=self.slow_pole_hf,
            fdsc_below_passc_hf=self.fdsc_beats_hf),))


def hf_l2_claims(runs: StationaryRuns) -> L2Claims:
    """Set the paper's sentence about paper Fig. 6 against the HF runs.

    The paper: "the L2 induced norm of PassC-EF and PassC-LF is nearly twice that of PassC-HF
    and FDSC".

    Parameters
    ----------
    runs : StationaryRuns
        The runs of :func:`stationary_runs` under the HF disturbance (paper eq. (57)).

    Returns
    -------
    L2Claims

    Raises
    ------
    ValueError
        If runs are not those of the HF disturbance.
    """
    _check_kind(runs, "HF")
    final = runs.l2_final
    ratios = np.array([final[a] / final[b] for a in ("PassC-EF", "PassC-LF")
                       for b in ("PassC-HF", "FDSC")])
    slow = float(aircraft().closed_loop(paper_gains()[CONTROLLER_GAINS["PassC-HF"]]).poles().real.max())
    beats_now = final["FDSC"] < final["PassC-HF"]
    beats_limit = final["FDSC"] < runs.l2_steady["PassC-HF"]
    beats = ("at this horizon only" if beats_now and not beats_limit else
             ("also against the steady state" if beats_now else "not even at this horizon"))
    twice = Claim("the L2 induced norm of PassC-EF and PassC-LF is nearly twice that of PassC-HF "
                  "and FDSC", "every ratio of the four lies in [1.5, 2.5]",
                  (float(ratios.min()), float(ratios.max())),
                  bool(np.all((ratios >= 1.5) & (ratios <= 2.5))))
    return L2Claims(final, ratios, slow, beats, twice)


@dataclass(frozen=True)
class HalvingRow:
    """Energy and switch count of one controller with the step dt and dt/2.

    Parameters
    ----------
    controller : str
        One of the paper's four controllers.
    energy_dt, energy_dt2 : float
        ∫zᵀz with dt and with dt/2.
    switches_dt, switches_dt2 : int
        Number of switches with dt and with dt/2.
    """

    controller: str
    energy_dt: float
    energy_dt2: float
    switches_dt: int
    switches_dt2: int

    @property
    def rel_change(self) -> float:
        """``|E(dt/2) − E(dt)| / |E(dt)|``."""
        return abs(self.energy_dt2 - self.energy_dt) / abs(self.energy_dt)


@dataclass(frozen=True)
class StepHalving:
    """Energies and switch counts with dt and dt/2 (see :func:`step_halving`).

    Parameters
    ----------
    kind : {"LF", "HF"}
        The disturbance.
    horizon, dt : float
        Run length and the coarser step in s.
    controllers : tuple of HalvingRow
        One per controller.
    """

    kind: str
    horizon: float
    dt: float
    controllers: tuple

    @property
    def max_rel_change(self) -> float:
        """Largest relative change of an energy."""
        return max(r.rel_change for r in self.controllers)

    def row(self, controller: str) -> HalvingRow:
        """The row of one controller.

        Parameters
        ----------
        controller : str
            One of the paper's four controllers.

        Returns
        -------
        HalvingRow
        """
        for r in self.controllers:
            if r.controller == controller:
                return r
        raise KeyError(f"controller must be one of {[r.controller for r in self.controllers]}, "
                       f"but found {controller!r}")

    def rows(self) -> list:
        """One row per controller (for :func:`fdsc.paper.report.html_table`).

        Returns
        -------
        list of dict
            ``disturbance, controller, energy_dt, energy_dt2, rel_change, switches_dt,
            switches_dt2``.
        """
        return [{"disturbance": self.kind, "controller": r.controller, "energy_dt": r.energy_dt,
                 "energy_dt2": r.energy_dt2, "rel_change": r.rel_change,
                 "switches_dt": r.switches_dt, "switches_dt2": r.switches_dt2}
                for r in self.controllers]

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``horizon``, ``max`` (largest relative change), and FDSC's
            ``sw1`` and ``sw2`` (switches with dt and dt/2) and ``fdsc`` (relative change).
        """
        r = self.row("FDSC")
        return {"horizon": _whole(self.horizon), "max": num(self.max_rel_change, 2),
                "sw1": count(int(r.switches_dt)), "sw2": count(int(r.switches_dt2)),
                "fdsc": num(r.rel_change, 2)}

    def table_rows(self) -> list:
        """:meth:`rows` as the book prints them (energies to 7 digits, changes to 2).

        Returns
        -------
        list of dict
        """
        return [{**r, "energy_dt": num(r["energy_dt"], 7), "energy_dt2": num(r["energy_dt2"], 7),
                 "rel_change": num(r["rel_change"], 2), "switches_dt": count(int(r["switches_dt"])),
                 "switches_dt2": count(int(r["switches_dt2"]))} for r in self.rows()]

    def to_record(self) -> RecordPart:
        """Record entry ``step_halving_lf`` or ``step_halving_hf`` (new).

        Returns
        -------
        RecordPart
        """
        rec = {r.controller: {"rel_change": r.rel_change, "switches_dt": r.switches_dt,
                              "switches_dt2": r.switches_dt2} for r in self.controllers}
        return RecordPart((entry(
            f"step_halving_{self.kind.lower()}", f"our check (step dt and dt/2, {self.kind} "
            "disturbance; nothing printed)", None, rec, "new",
            f"{self.horizon:g} s runs with dt = {self.dt:g} s and dt/2: relative change of the "
            "energy (quadrature error for the fixed gains; the sampled law for FDSC) and the "
            "switch counts (a count that scales with the sampling rate is chattering).",
            max_rel_change=self.max_rel_change),))


@cached
def step_halving(kind: str, *, horizon: float = 100.0, dt: float = STATIONARY_DT) -> StepHalving:
    """Energies and switch counts with dt and dt/2 for every controller (the law is sampled).

    Parameters
    ----------
    kind : {"LF", "HF"}
        The paper's LF (paper eq. (56)) or HF (paper eq. (57)) disturbance.
    horizon, dt : float, optional
        Run length and the coarser step in s.

    Returns
    -------
    StepHalving
    """
    d = paper_disturbance(kind)
    rows = []
    for name in CONTROLLERS:
        s1 = run_controller(name, d, time_grid(horizon, dt))
        s2 = run_controller(name, d, time_grid(horizon, dt / 2))
        rows.append(HalvingRow(name, s1.energy(), s2.energy(), int(s1.switch_times.size),
                               int(s2.switch_times.size)))
    return StepHalving(kind, float(horizon), float(dt), tuple(rows))


@dataclass(frozen=True)
class StationaryComparison:
    """FDSC against the comparator set (:mod:`fdsc.paper.comparators`) in one stationary case.

    Parameters
    ----------
    kind : {"LF", "HF"}
        The paper's disturbance.
    best : str
        The best fixed controller: the member of the comparator set of least energy.
    best_energy, fdsc : float
        ∫zᵀz of the best fixed controller and of FDSC (paper's gains and Q's).
    """

    kind: str
    best: str
    best_energy: float
    fdsc: float

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``best`` (its name), ``best_energy``, ``ratio`` (FDSC's energy
            over the best fixed one's, as a factor).

        Examples
        --------
        >>> StationaryComparison("HF", "open loop", 8.74, 9.05).prose()["ratio"]
        '×1.04'
        """
        return {"best": self.best, "best_energy": num(self.best_energy, 4),
                "ratio": times(self.fdsc / self.best_energy)}


def against_comparators() -> dict:
    """FDSC against the best fixed controller of the paper's two stationary cases.

    The energies come from :func:`fdsc.paper.baselines.baselines`, which runs the stationary
    cases with every member of the comparator set (the open loop and the best certified HF design
    included).

    Returns
    -------
    dict
        ``{"LF": StationaryComparison, "HF": StationaryComparison}``.
    """
    from .baselines import baselines
    from .comparators import best_fixed

    out = {}
    for scen in baselines().family("stationary"):
        name, energy = best_fixed(scen.energy, "aircraft")
        out[scen.label] = StationaryComparison(scen.label, name, float(energy), float(scen.energy["FDSC"]))
    return out


def record_part() -> RecordPart:
    """Record figures and entries of the chapter.

    Figures ``lf_outputs``, ``hf_outputs`` (paper Figs. 4 and 5: energies and switch counts) and
    ``hf_l2`` (paper Fig. 6: the L2-induced norm); entries ``lf_outputs_claims``,
    ``hf_outputs_claims``, ``hf_l2_claims`` (the paper's sentences about these figures),
    ``step_halving_lf`` and ``step_halving_hf`` (new).

    Returns
    -------
    RecordPart
    """
    lf, hf = stationary_runs("LF"), stationary_runs("HF")
    return (lf.to_record() + hf.to_record() + lf_output_claims(lf).to_record()
            + hf_output_claims(hf).to_record() + hf_l2_claims(hf).to_record()
            + step_halving("LF").to_record() + step_halving("HF").to_record())
