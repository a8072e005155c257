"""Chapter 'simulations', continued: the crossover of paper Fig. 7 and the objectives (P.1), (P.2).

The ρ_p at which FDSC stops being best, bisected; the global ratio of (P.1) over each sweep and
the worst localized ratio of (P.2) over windows of several lengths; where PassC-HF, scaled as
paper Fig. 7 draws it, crosses a rival, and the first grid point at which FDSC no longer beats one.
"""

from dataclasses import dataclass

import numpy as np

from fdsc._validation import as_choice, as_positive
from fdsc.frequency import band_peak, steady_state_gain
from fdsc.paper.reproduced.nonstationary_sweeps import (
    COARSE_STEP,
    P2_WINDOWS,
    SWEEP_NAMES,
    SweepRuns,
    _tail_ratio,
    family_signal,
    sweep_cases,
)
from fdsc.paper.shared.data import (
    aircraft,
    mixed_disturbance,
    paper_bands,
    paper_data,
    paper_disturbance,
    paper_fdsc,
    paper_gains,
)
from fdsc.paper.shared.names import CONTROLLER_GAINS
from fdsc.paper.shared.results import RecordPart, entry
from fdsc.stream import simulate_batch
from fdsc.switching import DEFAULT_GAMMA_TOL

__all__ = [
    "Crossover", "P1Result", "P1Row", "P2Result", "PAPER_CROSSOVER", "crossover", "crossover_in",
    "p1_global", "p2_localized", "scaled_crossing",
]


# -- the crossover of paper Fig. 7 -----------------------------------------------------------------

#: Iteration cap of the bisections (60 halvings shrink any bracket below double precision).
MAX_BISECTIONS = 60


@dataclass(frozen=True)
class Crossover:
    """Where FDSC stops beating a fixed-gain controller along a sweep (see :func:`crossover`).

    Parameters
    ----------
    family : {"mixed", "piecewise"}
        The family of disturbances.
    rival : str
        The fixed-gain controller.
    dt : float
        Step of every run in s.
    grid : (m,) ndarray
        The sweep's grid of the parameter.
    gap : (m,) ndarray
        E_FDSC − E_rival on the grid.
    sign_changes : int
        Grid intervals over which the gap goes from < 0 to ≥ 0.
    bracket : tuple of float or None
        Final bisection bracket ``(lo, hi)`` of the first such change: FDSC beats the rival at
        ``lo``, not at ``hi``; None if FDSC beats the rival on the whole grid (or never does).
    evaluations : tuple of (float, float, float)
        ``(parameter, E_FDSC, E_rival)`` of every bisection step.
    """

    family: str
    rival: str
    dt: float
    grid: np.ndarray
    gap: np.ndarray
    sign_changes: int
    bracket: tuple | None
    evaluations: tuple

    @property
    def value(self) -> float | None:
        """Midpoint of the final bracket (None if there is no crossover on the grid)."""
        return None if self.bracket is None else 0.5 * (self.bracket[0] + self.bracket[1])

    @property
    def width(self) -> float | None:
        """Width of the final bracket."""
        return None if self.bracket is None else self.bracket[1] - self.bracket[0]


def _pair_energy(family, p, rival, dt, designs):
    d, h = family_signal(family, p)
    batch = simulate_batch(sweep_cases(d, h, dt, names=("FDSC", rival), designs=designs))
    return float(batch.energy[0]), float(batch.energy[1])


def _bisect(family, rival, grid, gap, dt, tol, lattice, designs):
    up = np.flatnonzero((gap[:-1] < 0) & (gap[1:] >= 0))
    if up.size == 0:
        return int(up.size), None, ()
    lo, hi = float(grid[up[0]]), float(grid[up[0] + 1])
    evaluations = []
    for _ in range(MAX_BISECTIONS):
        if hi - lo <= tol:
            break
        mid = round(0.5 * (lo + hi) / lattice) * lattice
        if not lo < mid < hi:  # the lattice cannot split the bracket any further
            break
        e_fdsc, e_rival = _pair_energy(family, mid, rival, dt, designs)
        evaluations.append((mid, e_fdsc, e_rival))
        lo, hi = (mid, hi) if e_fdsc < e_rival else (lo, mid)
    else:
        raise RuntimeError(f"crossover: no bracket of width {tol} after {MAX_BISECTIONS} bisections")
    return int(up.size), (lo, hi), tuple(evaluations)


def crossover(runs: SweepRuns, rival: str, *, tol: float = 1e-3) -> Crossover:
    """The parameter at which FDSC (paper's gains and Q's, measured ẋ) stops beating ``rival``,
    bisected from the first sign change of E_FDSC − E_rival on the sweep's grid.

    Each bisection step runs FDSC and the rival at the midpoint (full runs with the sweep's step;
    the gap is not interpolated). For the piecewise family the midpoints are rounded so that the
    breaks of paper eq. (58) stay on the time grid.

    Parameters
    ----------
    runs : SweepRuns
        A sweep (:func:`mixed_sweep`, :func:`piecewise_sweep` or :func:`extended_piecewise`).
    rival : {"PassC-EF", "PassC-LF", "PassC-HF"}
        The fixed-gain controller.
    tol : float, optional
        Width of the final bracket.

    Returns
    -------
    Crossover

    Raises
    ------
    ValueError
        If rival is not a fixed-gain controller, runs lack FDSC or the rival, or tol is not
        positive.
    """
    as_choice("rival", rival, tuple(CONTROLLER_GAINS))
    tol = as_positive("tol", tol)
    if not isinstance(runs, SweepRuns) or not {"FDSC", rival} <= set(runs.energy):
        raise ValueError(f"runs must be a SweepRuns with FDSC and {rival}")
    T = paper_data("simulation")["piecewise_T"]["value"]
    lattice = 1e-12 if runs.family == "mixed" else runs.dt / T
    gap = runs.energy["FDSC"] - runs.energy[rival]
    changes, bracket, evaluations = _bisect(runs.family, rival, runs.param, gap, runs.dt, tol, lattice,
                                            {"paper": paper_fdsc("paper")})
    return Crossover(runs.family, rival, runs.dt, runs.param, gap, changes, bracket, evaluations)


# -- (P.1) and (P.2) ---------------------------------------------------------------------------------

@dataclass(frozen=True)
class P1Row:
    """(P.1) under one disturbance: the long-run energy ratio of every controller.

    Parameters
    ----------
    case : str
        The disturbance.
    rho_p : float
        ρ_p of the mixed disturbance (NaN for the LF disturbance).
    alpha_in : float
        Dominance degree α(Ω_3) of the in-band (HF) range: its share of the power.
    tail_ratio : dict
        ``{controller: ∫zᵀz / ∫d² over the second half of the run}`` (the infinite-horizon ratio
        estimated after the start-up transient).
    passc_hf_limit : float
        The limit of PassC-HF's ratio as the horizon grows (closed form, steady state).
    """

    case: str
    rho_p: float
    alpha_in: float
    tail_ratio: dict
    passc_hf_limit: float


@dataclass(frozen=True)
class P1Result:
    """(P.1) measured: the long-run energy ratio against γ(Ω_in, K_in) (see :func:`p1_global`).

    Parameters
    ----------
    rows : tuple of P1Row
        The LF disturbance, then the mixed ones (ρ_p = 0: the HF disturbance).
    gamma_in : float
        γ(Ω_3, K_f3): the in-band peak of σ_max of the printed K_f3 loop.
    gamma_in_printed : float
        The bound printed beside K_f3.
    """

    rows: tuple
    gamma_in: float
    gamma_in_printed: float

    def sqrt_tail(self, controller: str) -> np.ndarray:
        """√(long-run ratio) of one controller, one value per row.

        Parameters
        ----------
        controller : str
            One of :data:`SWEEP_NAMES`.

        Returns
        -------
        ndarray
        """
        return np.sqrt([r.tail_ratio[controller] for r in self.rows])

    def table(self) -> list:
        """One row per disturbance (for :func:`fdsc.paper.shared.report.html_table`).

        Returns
        -------
        list of dict
            ``case, alpha_in``, √(long-run ratio) of every controller, PassC-HF's closed-form
            steady state, and FDSC's value over γ(Ω_in, K_in).
        """
        return [{"case": r.case, "alpha_in": r.alpha_in,
                 **{n: float(np.sqrt(r.tail_ratio[n])) for n in SWEEP_NAMES},
                 "PassC-HF, steady state": float(np.sqrt(r.passc_hf_limit)),
                 "FDSC / gamma_in": float(np.sqrt(r.tail_ratio["FDSC"]) / self.gamma_in)}
                for r in self.rows]

    def to_record(self) -> RecordPart:
        """Record entry ``p1_global`` (new: the paper states (P.1) but prints no number).

        Returns
        -------
        RecordPart
        """
        return RecordPart((entry(
            "p1_global", "Sec. II-C, objective (P.1)", None,
            {"gamma_in": self.gamma_in, "gamma_in_printed": self.gamma_in_printed,
             "rows": self.table()}, "new",
            "square roots of ∫zᵀz / ∫d² over the second half of 500 s runs (the "
            "infinite-horizon ratio after the start-up transient), against gamma(Omega_in, K_in), "
            "the HF band peak of the printed K_f3 loop; PassC-HF's closed-form steady state "
            "beside it."),))


def p1_global(mixed: SweepRuns) -> P1Result:
    """Objective (P.1) measured: the long-run ratio ∫zᵀz / ∫d² of every controller under the LF
    disturbance and along the ρ_p sweep, against γ(Ω_in, K_in).

    Parameters
    ----------
    mixed : SweepRuns
        :func:`mixed_sweep` (its step is used for the LF runs too).

    Returns
    -------
    P1Result

    Raises
    ------
    ValueError
        If ``mixed`` is not the ρ_p sweep with every controller.

    Notes
    -----
    (P.1) asks the ratio to approach γ(Ω_in, K_in) "over an infinite time horizon"; a run from
    rest carries a start-up transient (PassC-HF's slowest pole is at −0.0165), so the ratio is
    taken over the second half of each run.
    """
    if not isinstance(mixed, SweepRuns) or mixed.family != "mixed" or mixed.names != SWEEP_NAMES:
        raise ValueError("mixed must be the SweepRuns of mixed_sweep")
    hf_loop = aircraft().closed_loop(paper_gains()["K_f3"])
    hf_band = paper_bands()["HF"]
    lf = paper_disturbance("LF")
    lf_runs = _tail_ratios(lf, float(mixed.horizon[0]), mixed.dt)
    rows = [P1Row("LF, paper eq. (56)", float("nan"), lf.dominance(hf_band), lf_runs,
                  steady_state_gain(hf_loop, lf.frequencies, lf.amplitudes) ** 2)]
    for i, rho in enumerate(mixed.param):
        d = mixed_disturbance(rho)
        name = "HF, paper eq. (57)" if rho == 0 else f"mixed, ρ_p = {rho:.3g}"
        rows.append(P1Row(name, float(rho), d.dominance(hf_band),
                          {n: float(mixed.tail_ratio[n][i]) for n in SWEEP_NAMES},
                          steady_state_gain(hf_loop, d.frequencies, d.amplitudes) ** 2))
    cl = aircraft().closed_loop(paper_gains()["K_f3"])
    return P1Result(tuple(rows), float(band_peak(cl, hf_band).gamma),
                    float(paper_data("controllers")["K_f3"]["bound"]))


def _tail_ratios(d, horizon, dt):
    """``{controller: ∫zᵀz / ∫d² over the second half}`` of every controller under one signal."""
    batch = simulate_batch(sweep_cases(d, horizon, dt), cumulative_every=COARSE_STEP)
    return {name: _tail_ratio(r) for name, r in zip(SWEEP_NAMES, batch, strict=True)}


@dataclass(frozen=True)
class P2Result:
    """(P.2) measured along the ρ_t sweep (see :func:`p2_localized`).

    Parameters
    ----------
    windows : tuple of float
        Window lengths T_l in s.
    worst : dict
        ``{window: {controller: √(largest ∫_{T_l} zᵀz / ∫_{T_l} d²)}}``, the largest over every
        window of that length (hop :data:`COARSE_STEP`) of every run of the sweep.
    gamma_tol : float
        γ_tol (the paper prints none; ours is the one of our Q design, paper Remark 4).
    gamma_out_in : float
        γ(Ω_1, K_f3): the LF band peak of the in-band controller, of which (P.2) says γ_tol is
        "a smaller value".
    """

    windows: tuple
    worst: dict
    gamma_tol: float
    gamma_out_in: float

    def meets(self, controller: str) -> dict:
        """``{window: worst √ratio < γ_tol}`` for one controller.

        Parameters
        ----------
        controller : str
            One of :data:`SWEEP_NAMES`.

        Returns
        -------
        dict
        """
        return {w: bool(self.worst[w][controller] < self.gamma_tol) for w in self.windows}

    def table(self) -> list:
        """One row per controller: the worst √ratio per window length and the windows that meet
        γ_tol.

        Returns
        -------
        list of dict
        """
        rows = []
        for n in SWEEP_NAMES:
            ok = [f"{w:g} s" for w, met in self.meets(n).items() if met]
            rows.append({"controller": n, **{f"T_l = {w:g} s": self.worst[w][n] for w in self.windows},
                         "meets γ_tol for": ", ".join(ok) or "none"})
        return rows

    def to_record(self) -> RecordPart:
        """Record entry ``p2_localized`` (new: (P.2) is stated without a number).

        Returns
        -------
        RecordPart
        """
        return RecordPart((entry(
            "p2_localized", "Sec. II-C, objective (P.2)", None,
            {"windows_s": list(self.windows), "gamma_tol": self.gamma_tol,
             "gamma_out_in": self.gamma_out_in,
             "worst_sqrt_ratio": {f"{w:g}": {n: float(v) for n, v in self.worst[w].items()}
                                  for w in self.windows},
             "meets_gamma_tol": {n: {f"{w:g}": ok for w, ok in self.meets(n).items()}
                                 for n in SWEEP_NAMES}}, "new",
            "square root of the largest ∫zᵀz / ∫d² over sliding windows (hop 0.1 s) of "
            "every run of the rho_t sweep of paper Fig. 8, against our gamma_tol (that of our Q "
            "design). (P.2) compares the unsquared ratio with gamma_tol; we compare its square "
            "root, the quantity a gamma bounds."),))


def p2_localized(piecewise: SweepRuns, *, gamma_tol: float = DEFAULT_GAMMA_TOL) -> P2Result:
    """Objective (P.2) measured: the worst localized ratio of every controller over sliding windows
    of the lengths :data:`P2_WINDOWS`, along the ρ_t sweep of paper Fig. 8.

    Parameters
    ----------
    piecewise : SweepRuns
        :func:`piecewise_sweep`.
    gamma_tol : float, optional
        The tolerance of (P.2) (not printed; default: the γ_tol of our Q design).

    Returns
    -------
    P2Result

    Raises
    ------
    ValueError
        If ``piecewise`` is not the ρ_t sweep with windows, or gamma_tol is not positive.

    Notes
    -----
    A window inside the LF segment holds little disturbance energy (ρ*_p = 0.1, tones of periods
    21–63 s), so the shortest windows weigh whatever output is left from the preceding HF segment
    against a small ∫d²: that is what (P.2) asks about "an arbitrarily selected time window".
    """
    gamma_tol = as_positive("gamma_tol", gamma_tol)
    if not isinstance(piecewise, SweepRuns) or piecewise.family != "piecewise" or not piecewise.worst_window:
        raise ValueError("piecewise must be the SweepRuns of piecewise_sweep")
    worst = {w: {n: float(np.sqrt(piecewise.worst_window[w][n].max())) for n in piecewise.names}
             for w in P2_WINDOWS}
    cl = aircraft().closed_loop(paper_gains()["K_f3"])
    return P2Result(P2_WINDOWS, worst, float(gamma_tol), float(band_peak(cl, paper_bands()["LF"]).gamma))


#: The printed threshold of paper Fig. 7's text: FDSC is best "for ρ_p ≤ 0.2".
PAPER_CROSSOVER = 0.2


def scaled_crossing(runs: SweepRuns, scale: float, rival: str = "PassC-LF") -> float | None:
    """The ρ_p at which PassC-HF's energy times ``scale`` (as the paper draws it) equals ``rival``'s.

    A fixed-gain loop is linear, so its output under d_h + ρ_p d_l is z_h + ρ_p z_l and its
    energy is exactly a quadratic in ρ_p; the quadratics are fitted to the whole grid and the
    crossing solved in closed form.

    Parameters
    ----------
    runs : SweepRuns
        :func:`mixed_sweep` (at least three points).
    scale : float
        The drawing factor of PassC-HF (1/5000 in paper Fig. 7).
    rival : str, optional
        A fixed-gain controller.

    Returns
    -------
    float or None
        The smallest crossing inside the grid's range, None if the curves do not cross there.

    Raises
    ------
    ValueError
        If ``runs`` is not a mixed sweep of at least three points with PassC-HF and the rival.
    """
    if (not isinstance(runs, SweepRuns) or runs.family != "mixed" or runs.param.size < 3
            or not {"PassC-HF", rival} <= set(runs.energy)):
        raise ValueError(f"runs must be a mixed sweep of at least 3 points with PassC-HF and {rival}")
    scale = as_positive("scale", scale)
    poly = (scale * np.polyfit(runs.param, runs.energy["PassC-HF"], 2)
            - np.polyfit(runs.param, runs.energy[rival], 2))
    roots = [r.real for r in np.roots(poly) if abs(r.imag) < 1e-12
             and runs.param[0] <= r.real <= runs.param[-1]]
    return float(min(roots)) if roots else None


def crossover_in(runs: SweepRuns, rival: str) -> float | None:
    """The first grid point at which FDSC no longer beats ``rival`` (no bisection), or None.

    Parameters
    ----------
    runs : SweepRuns
        A sweep.
    rival : str
        A fixed-gain controller of the sweep.

    Returns
    -------
    float or None
    """
    worse = np.flatnonzero(runs.energy["FDSC"] >= runs.energy[rival])
    return float(runs.param[worse[0]]) if worse.size else None
