"""Chapter 'theorem1', continued: statements (2) and (3) of Theorem 1 against simulated energy ratios.

The energy ratios over windows of FDSC runs against the bound max_i γ_i² of statement (2)
(paper eq. (35)), and the long-run energy ratio against Σ_i β_i γ_i² of statement (3) (paper
eq. (36)).
"""

from dataclasses import dataclass

import numpy as np

from fdsc._validation import as_positive
from fdsc.paper.reproduced.theorem1_statement1 import _whole
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.data import our_q, paper_disturbance, paper_modes, run_controller
from fdsc.paper.shared.prose import count, num
from fdsc.paper.shared.results import RecordPart, entry, pick
from fdsc.simulate import SimResult, time_grid
from fdsc.switching import certify_q

__all__ = [
    "AsymptoticCheck", "Statement2Check", "Statement3Check", "WindowCheck", "statement2",
    "statement3", "window_ratios",
]


#: How the two sets of Q's are labelled in the results.
_Q_LABELS = ("paper", "ours")


def window_ratios(run_sim: SimResult, window: float) -> np.ndarray:
    """Energy ratio ∫zᵀz/∫d² over consecutive windows of a run (Theorem 1 statement (2)).

    Parameters
    ----------
    run_sim : SimResult
        A run on a uniform grid.
    window : float
        Window length in s (at least two steps, at most the run).

    Returns
    -------
    (k,) ndarray

    Raises
    ------
    ValueError
        If the window spans fewer than two steps or more than the run.
    """
    t = run_sim.t
    window = as_positive("window", window)
    n = round(window / (t[1] - t[0]))
    if n < 2 or n > t.size - 1:
        raise ValueError(f"window must span between 2 steps ({2 * (t[1] - t[0]):g} s) and the run "
                         f"({t[-1] - t[0]:g} s), but found {window:g} s")
    # each step's energies exactly (the output jumps at the switches: no quadrature of samples)
    ez, ed = run_sim.cumulative_energy()
    k = np.arange(0, t.size - n, n)
    return (ez[k + n] - ez[k]) / (ed[k + n] - ed[k])


def _feasible_gammas():
    """The least γ's for which Theorem 1's LMIs are feasible with the paper's Q's and with ours:
    ``{"paper": (2,), "ours": (2,)}``."""
    pm = paper_modes()
    return {"paper": np.asarray(certify_q(pm["modes"], pm["bands"], pm["Q"]).gammas),
            "ours": np.asarray(our_q().gammas)}


def _law_q(label):
    return paper_modes()["Q"] if label == "paper" else our_q().Q


@dataclass(frozen=True)
class WindowCheck:
    """Energy ratios over windows of one FDSC run against the bound max γ_i² of statement (2).

    Parameters
    ----------
    disturbance : {"LF", "HF"}
        The paper's disturbance.
    q_label : {"paper", "ours"}
        Whose Q's the law uses.
    ratios : (k,) ndarray
        ∫zᵀz/∫d² over each window.
    bound : float
        max_i γ_i² of the least γ's for which the LMIs are feasible with these Q's.
    """

    disturbance: str
    q_label: str
    ratios: np.ndarray
    bound: float

    @property
    def max_ratio(self) -> float:
        """Largest window ratio."""
        return float(self.ratios.max())

    @property
    def mean_ratio(self) -> float:
        """Mean window ratio."""
        return float(self.ratios.mean())

    @property
    def holds(self) -> bool:
        """Every window ratio is below the bound (without the residue ε_T)."""
        return bool(self.max_ratio <= self.bound)


@dataclass(frozen=True)
class Statement2Check:
    """Statement (2) of Theorem 1 (paper eq. (35)) over windows of FDSC runs (see
    :func:`statement2`).

    Parameters
    ----------
    horizon, window, dt : float
        Run length, window length and step in s.
    cases : tuple of WindowCheck
        One per (disturbance, Q's).
    """

    horizon: float
    window: float
    dt: float
    cases: tuple

    def case(self, disturbance: str, q_label: str) -> WindowCheck:
        """The check of one run.

        Parameters
        ----------
        disturbance : {"LF", "HF"}
            The disturbance.
        q_label : {"paper", "ours"}
            Whose Q's.

        Returns
        -------
        WindowCheck
        """
        for c in self.cases:
            if (c.disturbance, c.q_label) == (disturbance, q_label):
                return c
        raise KeyError(f"no run with disturbance {disturbance!r} and Q's {q_label!r}")

    def bound(self, q_label: str) -> float:
        """The bound max_i γ_i² of one set of Q's.

        Parameters
        ----------
        q_label : {"paper", "ours"}
            Whose Q's.

        Returns
        -------
        float
        """
        return pick(self.cases, "q_label", q_label).bound

    def rows(self) -> list:
        """One row per run: ``disturbance, Q's, max ratio, mean ratio, bound max γ²``.

        Returns
        -------
        list of dict
        """
        return [{"disturbance": c.disturbance, "Q's": c.q_label, "max ratio": c.max_ratio,
                 "mean ratio": c.mean_ratio, "bound max γ²": c.bound} for c in self.cases]

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``s2_horizon``, ``s2_window``, ``bound_paper``, ``bound_ours``,
            ``wr_max_lf_paper``.
        """
        return {"s2_horizon": _whole(self.horizon), "s2_window": _whole(self.window),
                "bound_paper": num(self.bound("paper")), "bound_ours": num(self.bound("ours"), 4),
                "wr_max_lf_paper": num(self.case("LF", "paper").max_ratio, 4)}

    def to_record(self) -> RecordPart:
        """Record entry ``thm1_statement2`` (new).

        Returns
        -------
        RecordPart
        """
        rec = {f"{c.disturbance}, {c.q_label} Q": {"max_ratio": c.max_ratio, "bound": c.bound,
                                                   "below_bound": c.holds} for c in self.cases}
        return RecordPart((entry(
            "thm1_statement2", "Theorem 1, statement (2), paper eq. (35) (nothing printed)", None,
            rec, "new",
            f"FDSC from rest, {self.horizon:g} s runs, energy ratio ∫zᵀz / ∫d² over "
            f"{self.window:g} s windows against max_i γ_i² (the residue ε_T is not "
            "computable a priori and is left out).", window=self.window, horizon=self.horizon),))


@cached
def statement2(*, horizon: float = 100.0, window: float = 10.0, dt: float = 1e-3) -> Statement2Check:
    """Statement (2) of Theorem 1: windowed energy ratios of FDSC runs against max_i γ_i².

    FDSC runs from rest under the paper's LF and HF disturbances, with the paper's and with our
    Q's; each run's ratios over consecutive windows (:func:`window_ratios`) set against the
    largest γ_i² for which Theorem 1's LMIs are feasible with its Q's.

    Parameters
    ----------
    horizon, window, dt : float, optional
        Run length, window length and step in s.

    Returns
    -------
    Statement2Check

    Notes
    -----
    Statement (2), paper eq. (35), bounds the ratio by ``max_i γ_i² + ε_T``; ε_T involves the
    law's own terms and V at the window ends and is not computable a priori.
    """
    t = time_grid(horizon, dt)
    gammas = _feasible_gammas()
    cases = []
    for kind in ("LF", "HF"):
        d = paper_disturbance(kind)
        for label in _Q_LABELS:
            ratios = window_ratios(run_controller("FDSC", d, t, Q=_law_q(label)), window)
            cases.append(WindowCheck(kind, label, ratios, float(gammas[label].max() ** 2)))
    return Statement2Check(float(horizon), float(window), float(dt), tuple(cases))


@dataclass(frozen=True)
class AsymptoticCheck:
    """The long-run energy ratio of one FDSC run against Σ_i β_i γ_i² of statement (3).

    Parameters
    ----------
    disturbance : {"LF", "HF"}
        The paper's disturbance.
    q_label : {"paper", "ours"}
        Whose Q's the law uses.
    ratio : float
        ∫zᵀz/∫d² over the run.
    beta : (2,) ndarray
        Time share β_i of each mode.
    gammas : (2,) ndarray
        The least γ_i for which the LMIs are feasible with these Q's.
    """

    disturbance: str
    q_label: str
    ratio: float
    beta: np.ndarray
    gammas: np.ndarray

    @property
    def bound(self) -> float:
        """Σ_i β_i γ_i²."""
        return float(self.beta @ self.gammas**2)

    @property
    def below(self) -> bool:
        """The ratio lies below Σ_i β_i γ_i² (without the residue ε_∞)."""
        return bool(self.ratio < self.bound)


@dataclass(frozen=True)
class Statement3Check:
    """Statement (3) of Theorem 1 (paper eq. (36)) on long FDSC runs (see :func:`statement3`).

    Parameters
    ----------
    horizon, dt : float
        Run length and step in s.
    cases : tuple of AsymptoticCheck
        One per (disturbance, Q's).
    """

    horizon: float
    dt: float
    cases: tuple

    @property
    def n_below(self) -> int:
        """Number of runs whose ratio lies below Σ_i β_i γ_i²."""
        return sum(c.below for c in self.cases)

    def case(self, disturbance: str, q_label: str) -> AsymptoticCheck:
        """The check of one run.

        Parameters
        ----------
        disturbance : {"LF", "HF"}
            The disturbance.
        q_label : {"paper", "ours"}
            Whose Q's.

        Returns
        -------
        AsymptoticCheck
        """
        for c in self.cases:
            if (c.disturbance, c.q_label) == (disturbance, q_label):
                return c
        raise KeyError(f"no run with disturbance {disturbance!r} and Q's {q_label!r}")

    @property
    def ratio_label(self) -> str:
        """Column header of the ratio in :meth:`rows`."""
        return f"ratio over {self.horizon:g} s"

    def rows(self) -> list:
        """One row per run: ``disturbance, Q's, ratio over T s, β₁, β₂, Σ βᵢγᵢ²``.

        Returns
        -------
        list of dict
        """
        return [{"disturbance": c.disturbance, "Q's": c.q_label, self.ratio_label: c.ratio,
                 "β₁": c.beta[0], "β₂": c.beta[1], "Σ βᵢγᵢ²": c.bound} for c in self.cases]

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``s3_horizon``, ``s3_ours_hf_ratio``, ``s3_ours_hf_bound``,
            ``s3_n_below``, ``s3_n``.
        """
        hf = self.case("HF", "ours")
        return {"s3_horizon": _whole(self.horizon), "s3_ours_hf_ratio": num(hf.ratio, 4),
                "s3_ours_hf_bound": num(hf.bound, 4), "s3_n_below": count(self.n_below),
                "s3_n": count(len(self.cases))}

    def to_record(self) -> RecordPart:
        """Record entry ``thm1_statement3`` (new).

        Returns
        -------
        RecordPart
        """
        rec = {f"{c.disturbance}, {c.q_label} Q": {"ratio": c.ratio, "beta": c.beta,
                                                   "sum_beta_gamma2": c.bound, "below": c.below}
               for c in self.cases}
        return RecordPart((entry(
            "thm1_statement3", "Theorem 1, statement (3), paper eq. (36) (nothing printed)", None,
            rec, "new",
            f"FDSC from rest over {self.horizon:g} s: the energy ratio lies below "
            f"Σ_i β_i γ_i² (β_i measured time shares) in {self.n_below} of "
            f"{len(self.cases)} runs without the residue ε_∞.", horizon=self.horizon),))


@cached
def statement3(*, horizon: float = 500.0, dt: float = 1e-3) -> Statement3Check:
    """Statement (3) of Theorem 1: the long-run energy ratio against Σ_i β_i γ_i².

    FDSC runs from rest under the paper's LF and HF disturbances, with the paper's and with our
    Q's; β_i is the measured time share of mode i and γ_i the least value for which the LMIs
    are feasible with the run's Q's.

    Parameters
    ----------
    horizon, dt : float, optional
        Run length and step in s.

    Returns
    -------
    Statement3Check

    Notes
    -----
    Statement (3), paper eq. (36), bounds the asymptotic ratio by ``Σ_i β_i γ_i² + ε_∞``.
    """
    t = time_grid(horizon, dt)
    gammas = _feasible_gammas()
    cases = []
    for kind in ("LF", "HF"):
        d = paper_disturbance(kind)
        for label in _Q_LABELS:
            sim = run_controller("FDSC", d, t, Q=_law_q(label))
            cases.append(AsymptoticCheck(kind, label, sim.energy() / sim.input_energy(),
                                         np.asarray(sim.time_share()), gammas[label]))
    return Statement3Check(float(horizon), float(dt), tuple(cases))
