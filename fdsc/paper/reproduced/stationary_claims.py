"""Chapter 'simulations', continued: the paper's sentences about Figs. 4, 5 and 6.

The paper's sentences about paper Fig. 4 (LF disturbance), Fig. 5 (HF disturbance) and Fig. 6
(L2-induced norm, HF), each set against the number of the runs of
:mod:`fdsc.paper.reproduced.stationary_figures` that decides it.
"""

from dataclasses import dataclass

import numpy as np

from fdsc.paper.reproduced.stationary_figures import OUR_Q_NAME, StationaryRuns, _whole
from fdsc.paper.shared.data import aircraft, paper_gains
from fdsc.paper.shared.names import CONTROLLER_GAINS, CONTROLLERS
from fdsc.paper.shared.prose import num, times
from fdsc.paper.shared.results import RecordPart, entry
from fdsc.paper.shared.verdict import worst_verdict

__all__ = [
    "Claim", "HFOutputClaims", "L2Claims", "LFOutputClaims", "hf_l2_claims", "hf_output_claims",
    "lf_output_claims",
]


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
        Peak ``|z_i|`` of PassC-HF over the larger peak of PassC-EF and PassC-LF, per output.
    peak_ratio_fdsc_hf : (3,) ndarray
        Peak ``|z_i|`` of FDSC over that of PassC-HF, per output.
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
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.shared.prose`).

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
        """Smallest peak of ``|q|`` over the four controllers."""
        return min(self.q_peak.values())

    @property
    def q_max(self) -> float:
        """Largest peak of ``|q|`` over the four controllers."""
        return max(self.q_peak.values())

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``ratio_fdsc_hf`` (energy factor), ``q_range_min``,
            ``q_range_max`` (peaks of ``|q|``), ``q_ratio`` (largest over smallest), ``q_verdict``,
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
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        dict
            ``{name: text}``: the norm of each controller at the horizon (keyed by its name),
            ``ratio_min``, ``ratio_max``, ``twice_verdict`` ("holds"; "partly holds" when the
            ordering holds but not the factor; "fails"), ``slow_pole_hf``,
            ``time_constant_hf`` and ``fdsc_beats_hf`` (in words).
        """
        return {**{name: num(float(v), 4) for name, v in self.final.items()},
                "ratio_min": num(float(self.ratios.min())), "ratio_max": num(float(self.ratios.max())),
                "twice_verdict": (self.claim_twice.outcome if self.claim_twice.holds
                                  or self.claim_twice.value[0] <= 1 else "partly holds"),
                "slow_pole_hf": num(self.slow_pole_hf),
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
