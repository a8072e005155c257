"""Chapter 'theorem1': Theorem 1 (paper eqs. (33), (34)) on the aircraft, the paper's and our Q's,
statement (1) by simulation and the Lyapunov jumps, statements (2) and (3) (paper eqs. (35),
(36)) against simulated energy ratios.
"""

from dataclasses import dataclass

import numpy as np

from fdsc._validation import frozen_array
from fdsc.bands import Band
from fdsc.frequency import band_peak
from fdsc.paper.reproduced.theorem1_statement1 import (
    AutonomousRuns,
    LyapunovJumps,
    Statement1Check,
    _whole,
    autonomous_lyapunov_jumps,
    autonomous_stability,
    lyapunov_jumps,
    statement1,
)
from fdsc.paper.reproduced.theorem1_statements23 import (
    AsymptoticCheck,
    Statement2Check,
    Statement3Check,
    WindowCheck,
    statement2,
    statement3,
    window_ratios,
)
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.data import our_q, paper_data, paper_modes
from fdsc.paper.shared.prose import matrix_text, num
from fdsc.paper.shared.results import RecordPart, entry
from fdsc.switching import DEFAULT_GAMMA_TOL, certify_q, design_q

__all__ = [
    "record_part",
    "Theorem1Row",
    "Theorem1Table",
    "theorem1_table",
    "AutonomousRuns",
    "autonomous_stability",
    "LyapunovJumps",
    "lyapunov_jumps",
    "autonomous_lyapunov_jumps",
    "Statement1Check",
    "statement1",
    "window_ratios",
    "WindowCheck",
    "Statement2Check",
    "statement2",
    "AsymptoticCheck",
    "Statement3Check",
    "statement3",
    "matrix_text",
]


@dataclass(frozen=True)
class Theorem1Row:
    """The least γ's for which Theorem 1's LMIs are feasible with one pair of Q's.

    Parameters
    ----------
    source : str
        ``"printed Q's"`` or ``"paper Remark 4 design"``.
    gamma_tol : float
        γ_tol of the design (NaN for the paper's Q's).
    gamma_1, gamma_2 : float
        γ_1 (mode 1, PassC-LF) and γ_2 (mode 2, PassC-HF) of (T1-2).
    Q_1, Q_2 : (2, 2) ndarray
        The law's Q's.
    max_eig : float
        Largest eigenvalue of all LMI matrices at the solution (< 0).
    """

    source: str
    gamma_tol: float
    gamma_1: float
    gamma_2: float
    Q_1: np.ndarray
    Q_2: np.ndarray
    max_eig: float

    @property
    def gammas(self) -> np.ndarray:
        """``[γ_1, γ_2]``."""
        return np.array([self.gamma_1, self.gamma_2])


@dataclass(frozen=True)
class Theorem1Table:
    """The γ's for which Theorem 1's LMIs are feasible with the paper's Q's and with the paper
    Remark 4 design.

    Parameters
    ----------
    feasible : tuple of Theorem1Row
        One row per pair of Q's with the LMIs feasible: the paper's Q's first, then one design
        per γ_tol.
    hinf : (2,) ndarray
        H∞ norm of each mode's closed loop (PassC-LF, PassC-HF) over all frequencies.
    band_peaks : (2,) ndarray
        Peak of σ_max of each mode's closed loop over its own range (Ω_1, Ω_3): the Lemma 1
        bound of the mode alone.
    """

    feasible: tuple
    hinf: np.ndarray
    band_peaks: np.ndarray

    def __post_init__(self):
        for name in ("hinf", "band_peaks"):
            object.__setattr__(self, name, frozen_array(np.asarray(getattr(self, name), dtype=float)))

    @property
    def paper(self) -> Theorem1Row:
        """The row of the paper's Q's."""
        return self.feasible[0]

    @property
    def designs(self) -> tuple:
        """The rows of the paper Remark 4 design, one per γ_tol."""
        return self.feasible[1:]

    def rows(self) -> list:
        """One row per pair of Q's (for :func:`fdsc.paper.shared.report.html_table`).

        Returns
        -------
        list of dict
            ``source, gamma_tol, gamma_1, gamma_2, Q_1, Q_2, max_eig``.
        """
        keys = ("source", "gamma_tol", "gamma_1", "gamma_2", "Q_1", "Q_2", "max_eig")
        return [{k: getattr(r, k) for k in keys} for r in self.feasible]

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``paper_g1``, ``paper_g2`` (the least γ's for which the LMIs are
            feasible with the printed Q's),
            ``hinf_mode1``, ``hinf_mode2`` (H∞ norms of the modes), ``hf_mode2`` (PassC-HF's
            in-band peak), ``gamma_tol`` (the default γ_tol of our Q's), ``gamma_tols`` (those
            tried).
        """
        return {"paper_g1": num(float(self.paper.gamma_1), 4), "paper_g2": num(float(self.paper.gamma_2), 4),
                "hinf_mode1": num(float(self.hinf[0])), "hinf_mode2": num(float(self.hinf[1]), 4),
                "hf_mode2": num(float(self.band_peaks[1]), 5), "gamma_tol": _whole(DEFAULT_GAMMA_TOL),
                "gamma_tols": ", ".join(_whole(r.gamma_tol) for r in self.designs)}

    def table_rows(self) -> list:
        """:meth:`rows` as the book prints them (γ's, Q's and eigenvalues formatted).

        Returns
        -------
        list of dict
        """
        def tol(x):
            return "—" if x is None or not np.isfinite(x) else _whole(x)

        def gamma(x):
            # a γ fixed at γ_tol (paper Remark 4) is whole and printed as the prose prints it;
            # a least γ found by bisection, to five significant digits
            return _whole(x) if float(x).is_integer() else num(float(x), 5)

        return [{**r, "gamma_tol": tol(r["gamma_tol"]),
                 "gamma_1": gamma(r["gamma_1"]), "gamma_2": gamma(r["gamma_2"]),
                 "Q_1": matrix_text(r["Q_1"]), "Q_2": matrix_text(r["Q_2"]),
                 "max_eig": num(float(r["max_eig"]), 2)} for r in self.rows()]

    def to_record(self) -> RecordPart:
        """Record entries ``thm1_gammas`` and ``thm1_mode_reference`` (new).

        Returns
        -------
        RecordPart
        """
        p = self.paper
        design_g2 = [r.gamma_2 for r in self.designs]
        above = bool(np.all(p.gammas > self.hinf))
        return RecordPart((
            entry("thm1_gammas", "Theorem 1, paper Remark 4 (gammas not printed)", None,
                  {"paper_Q": [p.gamma_1, p.gamma_2],
                   "ours": {f"gamma_tol={r.gamma_tol:g}": [r.gamma_1, r.gamma_2] for r in self.designs}},
                  "new", "the paper prints no gammas; these are the least gammas for which "
                         "Theorem 1's LMIs are feasible."),
            entry("thm1_mode_reference", "Theorem 1 against Lemma 1 for each mode alone", None,
                  {"hinf": {"PassC-LF": self.hinf[0], "PassC-HF": self.hinf[1]},
                   "own_band_peak": {"PassC-LF": self.band_peaks[0], "PassC-HF": self.band_peaks[1]},
                   "paper_Q_gammas": [p.gamma_1, p.gamma_2], "paper_Q_gammas_above_hinf": above,
                   "design_gamma_2_range": [min(design_g2), max(design_g2)]},
                  "new",
                  "reference gains of each FDSC loop alone: its H∞ norm and its peak over its own "
                  "range (the best in-band bound Lemma 1 gives). "
                  + ("Each least γ_i for which Theorem 1's LMIs are feasible with the printed Q's "
                     "exceeds the H∞ norm of its own loop (no useful attenuation). " if above else "")
                  + "The Remark 4 design attains PassC-HF's Ω_3 peak as γ_2 for every γ_tol tried."),
        ))


@cached
def theorem1_table(gamma_tols: tuple = (1.0, 10.0, 100.0, 1000.0)) -> Theorem1Table:
    """γ's for which Theorem 1's LMIs are feasible with the paper's Q's and the paper Remark 4 design
    over γ_tol.

    Parameters
    ----------
    gamma_tols : sequence of float, optional
        The γ_tol's of the design.

    Returns
    -------
    Theorem1Table

    Notes
    -----
    The LMIs are (T1-1) and (T1-2), paper eqs. (33) and (34); the design fixes γ_j = γ_tol for
    the out-of-band mode and minimizes γ_i of the in-band mode (paper Remark 4, paper eq. (53)).
    """
    pm = paper_modes()
    paper = certify_q(pm["modes"], pm["bands"], pm["Q"])
    rows = [Theorem1Row("printed Q's", np.nan, paper.gammas[0], paper.gammas[1],
                        paper.Q[0], paper.Q[1], max(paper.max_eigs.values()))]
    for gt in gamma_tols:
        r = design_q(pm["modes"], pm["bands"], 1, gamma_tol=gt)
        rows.append(Theorem1Row("paper Remark 4 design", gt, r.gammas[0], r.gammas[1], r.Q[0],
                                r.Q[1], max(r.max_eigs.values())))
    return Theorem1Table(tuple(rows), [band_peak(m, Band.entire()).gamma for m in pm["modes"]],
                         [band_peak(m, b).gamma for m, b in zip(pm["modes"], pm["bands"], strict=True)])


def _q_entries(table):
    sw = paper_data("switching")
    ours = our_q()
    p = table.paper
    return RecordPart(tuple(entry(
        name, f"Sec. IV, {name}", sw[name]["value"], ours.Q[k], "not reproducible",
        "the paper prints the Q's but not γ_tol nor the Q's scale, which the Remark 4 design "
        "needs (Q enters Theorem 1 only through differences); ours: Remark 4 design with "
        f"γ_tol = {DEFAULT_GAMMA_TOL:g} (in-band mode PassC-HF): it reaches γ_2 = "
        f"{ours.gammas[1]:.4f} by driving Q_1 to the margin. With the printed Q's, Theorem 1's "
        f"LMIs are feasible only for γ_1 ≥ {num(float(p.gamma_1), 4)} and "
        f"γ_2 ≥ {num(float(p.gamma_2), 4)}.")
        for k, name in enumerate(("Q_1", "Q_2"))))


def record_part() -> RecordPart:
    """Record entries of the chapter.

    ``Q_1``, ``Q_2`` (the law's Q's), ``thm1_gammas`` (the least γ's for which Theorem 1's LMIs are feasible),
    and the new
    ``thm1_mode_reference``, ``thm1_statement1``, ``thm1_lyapunov_jumps``,
    ``thm1_statement2``, ``thm1_statement3``.

    Returns
    -------
    RecordPart
    """
    table = theorem1_table()
    return (_q_entries(table) + table.to_record() + statement1().to_record()
            + statement2().to_record() + statement3().to_record())
