"""Chapter 'nonstationary': paper Figs. 7 and 8 (the ρ_p and ρ_t sweeps), the crossover of
paper Fig. 7 bisected, and the paper's objectives (P.1) and (P.2) measured.

Every run goes through the library's streaming batch simulator (:func:`fdsc.simulate_batch`):
one batch per sweep, running integrals on a coarse grid for the windows of (P.2).
"""

from dataclasses import dataclass

import numpy as np

from .._validation import as_choice, as_count, as_positive
from ..frequency import band_peak, steady_state_gain
from ..stream import Case, simulate_batch
from ..switching import DEFAULT_GAMMA_TOL
from .cache import cached
from .data import (
    STATIONARY_DT,
    aircraft,
    mixed_disturbance,
    our_q,
    paper_bands,
    paper_data,
    paper_disturbance,
    paper_fdsc,
    paper_gains,
    piecewise_disturbance,
)
from .names import CONTROLLER_GAINS, FIGURE_IDS
from .prose import count, num, pct, times
from .results import RecordPart, entry
from .stationary import OUR_Q_NAME
from .verdict import verdict

__all__ = [
    "CANDIDATE_NAME",
    "SWEEP_NAMES",
    "COARSE_STEP",
    "P2_WINDOWS",
    "fdsc_designs",
    "sweep_cases",
    "family_signal",
    "SweepRuns",
    "RHO_T_EXTENDED",
    "PAPER_CROSSOVER",
    "mixed_sweep",
    "piecewise_sweep",
    "extended_piecewise",
    "Crossover",
    "crossover",
    "crossover_in",
    "scaled_crossing",
    "P1Row",
    "P1Result",
    "p1_global",
    "P2Result",
    "p2_localized",
    "SweepStudy",
    "sweep_study",
    "ComparatorCheck",
    "against_comparators",
    "record_part",
]


#: FDSC with the paper's gains and Q's, ẋ read as the candidate mode's (see fdsc.simulate.LAWS).
CANDIDATE_NAME = "FDSC (candidate ẋ)"

#: The controllers of both sweeps: the paper's four (FDSC: paper's Q's, measured ẋ) and two variants.
SWEEP_NAMES = ("PassC-EF", "PassC-LF", "PassC-HF", "FDSC", OUR_Q_NAME, CANDIDATE_NAME)

#: Step (s) of the coarse grid on which the running integrals are kept (windows of (P.2)).
COARSE_STEP = 0.1

#: Window lengths (s) of the localized ratio of (P.2).
P2_WINDOWS = (1.0, 10.0, 100.0)


def fdsc_designs() -> dict:
    """The FDSC designs of the sweeps, built once per sweep (certifying or designing Q's solves LMIs).

    Returns
    -------
    dict
        ``{"paper": FDSC with the printed Q's, "ours": FDSC with our Q's}``.
    """
    return {"paper": paper_fdsc("paper"), "ours": paper_fdsc(our_q().Q)}


def sweep_cases(d, horizon: float, dt: float, *, names=SWEEP_NAMES, label=None,
                designs: dict | None = None) -> list:
    """One :class:`~fdsc.stream.Case` per controller for one disturbance, from rest.

    Parameters
    ----------
    d : Sinusoids or Piecewise
        The disturbance.
    horizon, dt : float
        Run length and step in s.
    names : sequence of str, optional
        Controllers from :data:`SWEEP_NAMES`.
    label : object, optional
        Stored in each case's label as ``(name, label)``.
    designs : dict, optional
        :func:`fdsc_designs` (default: built here).

    Returns
    -------
    list of Case

    Raises
    ------
    ValueError
        If a name is not one of :data:`SWEEP_NAMES`.

    Examples
    --------
    >>> from fdsc.paper.data import paper_disturbance
    >>> [c.label[0] for c in sweep_cases(paper_disturbance("HF"), 1.0, 1e-3, names=("PassC-HF", "FDSC"))]
    ['PassC-HF', 'FDSC']
    """
    for name in names:
        as_choice("names", name, SWEEP_NAMES)
    plant, gains = aircraft(), paper_gains()
    if designs is None and any(n not in CONTROLLER_GAINS for n in names):
        designs = fdsc_designs()
    cases = []
    for name in names:
        if name in CONTROLLER_GAINS:
            cases.append(Case(plant.closed_loop(gains[CONTROLLER_GAINS[name]]), d, horizon, dt,
                              label=(name, label)))
        else:
            ctrl = designs["ours"] if name == OUR_Q_NAME else designs["paper"]
            law = "candidate" if name == CANDIDATE_NAME else "previous"
            cases.append(ctrl.case(d, horizon, dt, law=law, label=(name, label)))
    return cases


@dataclass(frozen=True)
class SweepRuns:
    """A family of disturbances, every controller of :data:`SWEEP_NAMES` run under each.

    Parameters
    ----------
    family : {"mixed", "piecewise"}
        d_h + ρ_p d_l over [0, 500] (paper Fig. 7) or the piecewise signal of paper eq. (58) over
        [0, 2T + ρ_t T] (paper Fig. 8).
    param : (m,) ndarray
        ρ_p or ρ_t.
    horizon : (m,) ndarray
        Run length of each point in s.
    dt : float
        Step in s.
    energy : dict
        ``{controller: (m,) ndarray}`` of ∫zᵀz over the run (unscaled).
    input_energy : (m,) ndarray
        ∫d² over the run.
    switches : dict
        ``{FDSC variant: (m,) int ndarray}``.
    share_hf : dict
        ``{FDSC variant: (m,) ndarray}``: share of the run on PassC-HF (K_2 = K_f3).
    tail_ratio : dict
        ``{controller: (m,) ndarray}``: ∫zᵀz / ∫d² over the second half of the run.
    worst_window : dict
        ``{window length: {controller: (m,) ndarray}}``: the largest ∫zᵀz / ∫d² over the
        windows of that length (hop :data:`COARSE_STEP`), for :data:`P2_WINDOWS`.
    worst_window_start : dict
        Same keys: the start (s) of that window.
    """

    family: str
    param: np.ndarray
    horizon: np.ndarray
    dt: float
    energy: dict
    input_energy: np.ndarray
    switches: dict
    share_hf: dict
    tail_ratio: dict
    worst_window: dict
    worst_window_start: dict

    def __post_init__(self):
        as_choice("family", self.family, ("mixed", "piecewise"))

    @property
    def names(self) -> tuple:
        """The controllers, in order."""
        return tuple(self.energy)

    def best_fixed(self) -> np.ndarray:
        """The better (smaller) energy of PassC-EF and PassC-LF at each point: the paper's own
        comparison behind the crossover of paper Fig. 7, not the comparator set of
        :mod:`fdsc.paper.comparators` (see :func:`against_comparators`)."""
        return np.minimum(self.energy["PassC-EF"], self.energy["PassC-LF"])

    def to_figure(self) -> dict:
        """The record's figure data (``mixed_sweep`` or ``piecewise_sweep``), energies unscaled.

        Returns
        -------
        dict
        """
        sim = paper_data("simulation")
        fdsc_names = [n for n in self.names if n.startswith("FDSC")]
        data = {"paper_figure": FIGURE_IDS[f"{self.family}_sweep"]}
        if self.family == "mixed":
            data.update(rho_p=self.param.tolist(), horizon=float(self.horizon[0]))
            scale = sim["mixed_passc_hf_scale"]["value"]
        else:
            data.update(rho_t=self.param.tolist(), T=sim["piecewise_T"]["value"],
                        rho_p_star=sim["piecewise_rho_p_star"]["value"], horizon=self.horizon.tolist())
            scale = sim["piecewise_passc_hf_scale"]["value"]
        data.update(
            dt=self.dt, energy={n: self.energy[n].tolist() for n in self.names},
            input_energy=self.input_energy.tolist(),
            switches={n: self.switches[n].tolist() for n in fdsc_names},
            share_passc_hf={n: self.share_hf[n].tolist() for n in fdsc_names},
            passc_hf_scale=scale,
            units={"horizon": "s", "dt": "s", "energy": "integral of z'z over the run (unscaled)",
                   "passc_hf_scale": "factor applied to PassC-HF's energy in the paper's plot only"})
        return data


def family_signal(family: str, p: float) -> tuple:
    """The disturbance of one point of a family and its run length (paper Fig. 7 or Fig. 8).

    Parameters
    ----------
    family : {"mixed", "piecewise"}
    p : float
        ρ_p or ρ_t.

    Returns
    -------
    d : Sinusoids or Piecewise
    horizon : float
        Run length in s (500 s, or 2T + ρ_t T).
    """
    sim = paper_data("simulation")
    if family == "mixed":
        return mixed_disturbance(p), sim["mixed_horizon"]["value"]
    T = sim["piecewise_T"]["value"]
    return piecewise_disturbance(T, p, sim["piecewise_rho_p_star"]["value"]), 2 * T + p * T


def _tail_ratio(r):
    """∫zᵀz / ∫d² over the second half of a streamed run (from its coarse running integrals)."""
    half = r.t_cum.size // 2
    ez, ed = r.energy_cum, r.input_energy_cum
    return float((ez[-1] - ez[half]) / (ed[-1] - ed[half]))


def _run_family(family, params, dt, names=SWEEP_NAMES, windows=True):
    designs = fdsc_designs() if OUR_Q_NAME in names else {"paper": paper_fdsc("paper")}
    cases, horizons = [], []
    for p in params:
        d, h = family_signal(family, p)
        horizons.append(h)
        cases += sweep_cases(d, h, dt, names=names, label=float(p), designs=designs)
    batch = simulate_batch(cases, cumulative_every=COARSE_STEP if windows else None)
    m, k = len(params), len(names)
    energy = {n: batch.energy[j::k].copy() for j, n in enumerate(names)}
    fdsc = [n for n in names if n.startswith("FDSC")]
    switches = {n: batch.switches[names.index(n)::k].astype(int) for n in fdsc}
    share_hf = {n: batch.time_share[names.index(n)::k, 1].copy() for n in fdsc}
    tail = {n: np.full(m, np.nan) for n in names}
    worst = {w: {n: np.full(m, np.nan) for n in names} for w in P2_WINDOWS} if windows else {}
    start = {w: {n: np.full(m, np.nan) for n in names} for w in P2_WINDOWS} if windows else {}
    for i in range(m if windows else 0):
        for j, n in enumerate(names):
            r = batch[i * k + j]
            tail[n][i] = _tail_ratio(r)
            for w in P2_WINDOWS:
                t0, ez, ed = r.window_energies(w)
                at = int(np.argmax(ez / ed))
                worst[w][n][i], start[w][n][i] = ez[at] / ed[at], t0[at]
    return SweepRuns(family, np.asarray(params, float), np.asarray(horizons, float), float(dt), energy,
                     batch.input_energy.copy()[::k], switches, share_hf, tail, worst, start)


@cached
def mixed_sweep(n: int = 21, *, dt: float = STATIONARY_DT) -> SweepRuns:
    """Paper Fig. 7: d = d_h + ρ_p d_l over [0, 500] for ρ_p on a uniform grid of [0, 0.5].

    Parameters
    ----------
    n : int, optional
        Grid points of ρ_p (≥ 2; the paper's range, :func:`~fdsc.paper.data.paper_data`).
    dt : float, optional
        Step in s.

    Returns
    -------
    SweepRuns
    """
    lo, hi = paper_data("simulation")["rho_p_range"]["value"]
    return _run_family("mixed", np.linspace(lo, hi, as_count("n", n, minimum=2)), as_positive("dt", dt))


@cached
def piecewise_sweep(n: int = 11, *, dt: float = STATIONARY_DT) -> SweepRuns:
    """Paper Fig. 8: the piecewise disturbance of paper eq. (58) (T = 500, ρ*_p = 0.1) over
    [0, 2T + ρ_t T] for ρ_t on a uniform grid of [0, 0.5].

    Parameters
    ----------
    n : int, optional
        Grid points of ρ_t (≥ 2; the grid must put the breaks on the time grid).
    dt : float, optional
        Step in s.

    Returns
    -------
    SweepRuns
    """
    lo, hi = paper_data("simulation")["rho_t_range"]["value"]
    return _run_family("piecewise", np.linspace(lo, hi, as_count("n", n, minimum=2)),
                       as_positive("dt", dt))


#: ρ_t beyond the paper's range at which FDSC is set against PassC-EF and PassC-LF (the paper's
#: "with the increase of the ratio … EF or LF may be a better option" has no crossing in [0, 0.5]).
RHO_T_EXTENDED = (0.5, 1.0, 1.5, 2.0, 3.0)


@cached
def extended_piecewise(grid: tuple = RHO_T_EXTENDED, *, dt: float = STATIONARY_DT) -> SweepRuns:
    """The family of paper Fig. 8 beyond the paper's range of ρ_t: PassC-EF, PassC-LF and FDSC
    only, energies only (no windows).

    Parameters
    ----------
    grid : tuple of float, optional
        Values of ρ_t (each ρ_t T a multiple of dt).
    dt : float, optional
        Step in s.

    Returns
    -------
    SweepRuns
        With ``tail_ratio`` NaN and ``worst_window`` empty.
    """
    grid = np.asarray(grid, float)
    if grid.ndim != 1 or grid.size < 2 or np.any(grid < 0) or np.any(np.diff(grid) <= 0):
        raise ValueError(f"grid must be at least two increasing values >= 0, but found {grid.tolist()}")
    return _run_family("piecewise", grid, as_positive("dt", dt), ("PassC-EF", "PassC-LF", "FDSC"),
                       windows=False)


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
        """One row per disturbance (for :func:`fdsc.paper.report.html_table`).

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
            "square roots of int z'z / int d^2 over the second half of 500 s runs (the "
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
        name = "HF, paper eq. (57)" if rho == 0 else f"mixed, rho_p = {rho:.3g}"
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
                         "meets gamma_tol for": ", ".join(ok) or "none"})
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
            "square root of the largest int z'z / int d^2 over sliding windows (hop 0.1 s) of "
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


# -- everything at dt and dt/2, and the record ------------------------------------------------------

@dataclass(frozen=True)
class SweepStudy:
    """Both sweeps, the crossovers, (P.1), (P.2), each with the step dt and, for the verdicts,
    dt/2 (see :func:`sweep_study`).

    Parameters
    ----------
    mixed, piecewise : SweepRuns
        The sweeps of paper Figs. 7 and 8 with dt.
    crossover : dict
        ``{"PassC-LF": Crossover, "PassC-EF": Crossover}`` along ρ_p with dt.
    extended : SweepRuns
        :func:`extended_piecewise` with dt.
    extended_crossover : dict
        ``{"PassC-LF": Crossover, "PassC-EF": Crossover}`` along the extended ρ_t grid.
    p1 : P1Result
    p2 : P2Result
    mixed_half, piecewise_half : SweepRuns
        The sweeps with dt/2.
    crossover_half : dict
        The crossovers along ρ_p with dt/2.
    p1_half, p2_half : P1Result, P2Result
        (P.1) and (P.2) with dt/2.
    """

    mixed: SweepRuns
    piecewise: SweepRuns
    crossover: dict
    extended: SweepRuns
    extended_crossover: dict
    p1: P1Result
    p2: P2Result
    mixed_half: SweepRuns
    piecewise_half: SweepRuns
    crossover_half: dict
    p1_half: P1Result
    p2_half: P2Result

    @property
    def dt(self) -> float:
        """The step of the main runs in s."""
        return self.mixed.dt

    def max_rel_change(self) -> dict:
        """``{family: {controller: largest |E(dt/2) − E(dt)| / E(dt) over the grid}}``.

        Returns
        -------
        dict
        """
        return {a.family: {n: float(np.max(np.abs(b.energy[n] - a.energy[n]) / a.energy[n]))
                           for n in a.names}
                for a, b in ((self.mixed, self.mixed_half), (self.piecewise, self.piecewise_half))}

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.prose`).

        Returns
        -------
        dict
            ``{name: text}``: the choices (``dt_ms``, ``dt2_ms``, ``n_rho_p``, ``n_rho_t``,
            ``n_runs``, ``coarse_step``, ``scale7``, ``scale8``), paper Fig. 7 (dominance,
            crossovers, PassC-HF's growth, the variants, switches), paper Fig. 8 (``pw_*``),
            (P.1) (``gamma_in``, ``p1_*``), (P.2) (``gamma_tol``, ``p2_*``) and the step halving
            (``halving_*``; ``halving_same`` needs the claims and is glued by the chapter).
        """
        mixed, pw, p1, p2 = self.mixed, self.piecewise, self.p1, self.p2
        sim = paper_data("simulation")
        scale7, scale8 = sim["mixed_passc_hf_scale"]["value"], sim["piecewise_passc_hf_scale"]["value"]
        hf = paper_bands()["HF"]
        e, ep = mixed.energy, pw.energy
        cross = {r: c.value for r, c in self.crossover.items()}
        half = self.crossover_half["PassC-LF"].value
        i02 = int(np.argmin(np.abs(mixed.param - 0.2)))
        hf_loop = aircraft().closed_loop(paper_gains()[CONTROLLER_GAINS["PassC-HF"]])
        chg = self.max_rel_change()
        out = {
            "dt_ms": _whole(round(self.dt * 1e3, 9)), "dt2_ms": num(self.dt * 1e3 / 2, 2),
            "n_rho_p": count(mixed.param.size), "n_rho_t": count(pw.param.size),
            "n_runs": count((mixed.param.size + pw.param.size) * len(SWEEP_NAMES)),
            "coarse_step": num(COARSE_STEP, 1), "scale7": _whole(1 / scale7), "scale8": _whole(1 / scale8),
            "alpha_02": num(mixed_disturbance(0.2).dominance(hf), 4),
            "alpha_05": num(mixed_disturbance(0.5).dominance(hf), 2),
            "cross_lf": num(cross["PassC-LF"]), "cross_lf_approx": num(cross["PassC-LF"], 2),
            "cross_lf_fine": num(cross["PassC-LF"], 4), "cross_ef": num(cross["PassC-EF"]),
            "cross_width": num(self.crossover["PassC-LF"].width, 2),
            "cross_lf_half": num(half), "cross_lf_half_fine": num(half, 4),
            "cross_scaled": num(scaled_crossing(mixed, scale7), 4), "cross_paper": num(PAPER_CROSSOVER, 1),
            "cross_changes": count(self.crossover["PassC-LF"].sign_changes),
            "hf_slow_pole": num(float(hf_loop.poles().real.max())),
            "hf_at0": num(float(e["PassC-HF"][0])), "hf_max": num(float(e["PassC-HF"].max())),
            "hf_1e6_from": _grid(mixed.param[np.argmax(e["PassC-HF"] >= 1e6)]),
            "alpha_cross": _pct(mixed_disturbance(cross["PassC-LF"]).dominance(hf), 1),
            "fdsc_over_lf_02": times(float(e["FDSC"][i02] / e["PassC-LF"][i02])),
            "hf_over_fdsc_02": times(float(e["PassC-HF"][i02] / e["FDSC"][i02])),
            "ours_over_lf_max": times(float(np.max(e[OUR_Q_NAME] / e["PassC-LF"]))),
            "halving_ours_early": _pct(max(v[OUR_Q_NAME] for v in chg.values())),
            "cand_over_hf_max": _pct(float(np.max(np.abs(e[CANDIDATE_NAME] / e["PassC-HF"] - 1))), 1),
            "sw_mixed_min": count(int(mixed.switches["FDSC"][1:].min())),
            "sw_mixed_max": count(int(mixed.switches["FDSC"].max())),
        }
        T = sim["piecewise_T"]["value"]
        xc = {r: c.value for r, c in self.extended_crossover.items()}
        first_loss = crossover_in(pw, "PassC-LF")
        out.update({
            "pw_hf_0": num(float(ep["PassC-HF"][0])), "pw_hf_1": num(float(ep["PassC-HF"][1])),
            "pw_window_1": _whole(round(float(pw.param[1] * T), 9)),
            "pw_fdsc_over_lf_max": times(float(np.max(ep["FDSC"] / ep["PassC-LF"]))),
            "pw_in_range_text": ("Within the paper's range PassC-LF never beats FDSC." if first_loss is None
                                 else f"Within the paper's range PassC-LF beats FDSC from ρ_t = "
                                      f"{num(first_loss, 2)} on."),
            "pw_ext_lf": num(xc["PassC-LF"], 2), "pw_ext_ef": num(xc["PassC-EF"], 2),
            "pw_ext_lf_s": _whole(round(xc["PassC-LF"] * T)),
            "pw_ours_over_lf": times(float(np.max(ep[OUR_Q_NAME] / ep["PassC-LF"]))),
            "pw_hf_max": num(float(ep["PassC-HF"].max())),
        })
        hf_row = next(r for r in p1.rows if r.alpha_in == 1.0)
        first = p1.rows[2]  # the smallest ρ_p > 0 of the grid
        out.update({
            "gamma_in": num(p1.gamma_in, 4), "gamma_in_printed": num(p1.gamma_in_printed),
            "p1_inherit": times(float(np.sqrt(hf_row.tail_ratio["FDSC"] / hf_row.tail_ratio["PassC-HF"])), 4),
            "p1_max_over_gamma": _pct(float(p1.sqrt_tail("FDSC")[1:].max() / p1.gamma_in), 1),
            "p1_lf_fdsc": num(float(np.sqrt(p1.rows[0].tail_ratio["FDSC"]))),
            "p1_lf_lf": num(float(np.sqrt(p1.rows[0].tail_ratio["PassC-LF"]))),
            "p1_in_band": num(float(np.sqrt(hf_row.tail_ratio["PassC-HF"])), 4),
            "p1_first_rho": _grid(first.rho_p), "p1_first_alpha": num(first.alpha_in, 4),
            "p1_first_ratio": times(float(np.sqrt(first.tail_ratio["FDSC"] / hf_row.tail_ratio["PassC-HF"]))),
            "p1_over_printed": _grid(min(r.rho_p for r in p1.rows[1:]
                                       if np.sqrt(r.tail_ratio["FDSC"]) > p1.gamma_in_printed)),
        })
        starts = np.array([[pw.worst_window_start[w]["FDSC"][i] for w in P2_WINDOWS]
                           for i in range(1, pw.param.size)])
        inside = (starts >= T) & (starts < T + pw.param[1:, None] * T)
        longest = min([w for w, ok in p2.meets("FDSC").items() if ok], default=None)
        out.update({
            "gamma_tol": _whole(p2.gamma_tol), "gamma_out_in": num(p2.gamma_out_in, 4),
            "windows": ", ".join(_whole(w) for w in P2_WINDOWS),
            **{f"p2_fdsc_{w:g}": num(p2.worst[w]["FDSC"]) for w in P2_WINDOWS},
            "p2_lf_max": num(max(p2.worst[w][n] for w in P2_WINDOWS for n in ("PassC-EF", "PassC-LF"))),
            "p2_fdsc_max": num(max(p2.worst[w]["FDSC"] for w in P2_WINDOWS)),
            "p2_in_lf": count(int(inside.sum())), "p2_n_worst": count(int(inside.size)),
            "p2_longest": "none" if longest is None else _whole(longest),
            "halving_fdsc_mixed": _pct(chg["mixed"]["FDSC"], 1),
            "halving_fdsc_pw": _pct(chg["piecewise"]["FDSC"], 1),
            "halving_ours": _pct(max(chg[f][OUR_Q_NAME] for f in chg)),
            "halving_fixed": num(max(chg[f][n] for f in chg
                                     for n in ("PassC-EF", "PassC-LF", "PassC-HF")), 2),
        })
        return out

    def to_record(self) -> RecordPart:
        """Figures ``mixed_sweep`` and ``piecewise_sweep``; entries ``mixed_crossover``,
        ``piecewise_crossover``, ``p1_global``, ``p2_localized``, ``sweep_step_halving``.

        Returns
        -------
        RecordPart
        """
        paper = PAPER_CROSSOVER
        lf = self.crossover["PassC-LF"]
        fig7 = self.mixed.to_figure()
        fig7["crossover"] = {"PassC-LF": lf.value, "PassC-EF": self.crossover["PassC-EF"].value,
                             "tolerance": lf.width, "paper": paper}
        in_range = {r: crossover_in(self.piecewise, r) for r in ("PassC-LF", "PassC-EF")}
        entries = (
            entry("mixed_crossover", "Sec. IV, text on paper Fig. 7: 'rho_p <= 0.2'", paper,
                  {r: c.value for r, c in self.crossover.items()},
                  "not reproducible" if lf.value is None else verdict(paper, lf.value, decimals=1),
                  "rho_p at which FDSC's energy over [0, 500] reaches PassC-LF's (PassC-LF has the "
                  "smaller energy of PassC-EF and PassC-LF at every rho_p), bisected by full runs to "
                  "a bracket of width <= 1e-3; compared with the printed 0.2 to its one decimal.",
                  brackets={r: list(c.bracket) if c.bracket else None for r, c in self.crossover.items()},
                  with_half_step={r: c.value for r, c in self.crossover_half.items()},
                  passc_hf_scaled_crossing=scaled_crossing(
                      self.mixed, paper_data("simulation")["mixed_passc_hf_scale"]["value"]),
                  grid_sign_changes={r: c.sign_changes for r, c in self.crossover.items()}),
            entry("piecewise_crossover", "Sec. IV, text on paper Fig. 8: 'with the increase of the "
                  "ratio ... EF or LF may be a better option'", None,
                  {"in_paper_range": in_range,
                   "extended": {r: c.value for r, c in self.extended_crossover.items()},
                   "extended_grid": self.extended.param.tolist()}, "new",
                  "rho_t at which FDSC's energy reaches PassC-LF's or PassC-EF's: on the paper's "
                  "grid of [0, 0.5] (null: FDSC is better at every point) and, beyond it, bisected "
                  "to a bracket of width <= 1e-2."),
            entry("sweep_step_halving", "our check (both sweeps with dt and dt/2; nothing printed)",
                  None, {"dt": self.dt, "max_rel_change": self.max_rel_change(),
                         "crossover": {r: [self.crossover[r].value, self.crossover_half[r].value]
                                       for r in self.crossover}}, "new",
                  "the sweeps of paper Figs. 7 and 8 and the bisected crossover repeated with half "
                  "the step: the fixed gains change by their quadrature error only, FDSC by its "
                  "sampled law."),
        )
        return (RecordPart(entries, {"mixed_sweep": fig7, "piecewise_sweep": self.piecewise.to_figure()})
                + self.p1.to_record() + self.p2.to_record())


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


@cached
def sweep_study(*, dt: float = STATIONARY_DT) -> SweepStudy:
    """Everything of the chapter: both sweeps, the crossovers (bisected to 1e-3 along ρ_p, 1e-2
    along the extended ρ_t grid), (P.1), (P.2), and the sweeps and crossovers again with dt/2.

    Parameters
    ----------
    dt : float, optional
        Step in s.

    Returns
    -------
    SweepStudy
    """
    rivals = ("PassC-LF", "PassC-EF")
    mixed, piecewise, ext = mixed_sweep(dt=dt), piecewise_sweep(dt=dt), extended_piecewise(dt=dt)
    mixed_half, piecewise_half = mixed_sweep(dt=dt / 2), piecewise_sweep(dt=dt / 2)
    return SweepStudy(mixed, piecewise, {r: crossover(mixed, r) for r in rivals}, ext,
                      {r: crossover(ext, r, tol=1e-2) for r in rivals}, p1_global(mixed),
                      p2_localized(piecewise), mixed_half, piecewise_half,
                      {r: crossover(mixed_half, r) for r in rivals}, p1_global(mixed_half),
                      p2_localized(piecewise_half))


def _whole(x):
    """A count or a length as the prose prints it: whole numbers without decimals."""
    x = float(x)
    return count(int(x)) if x.is_integer() else num(x)


def _grid(x):
    """A point of a sweep's grid as it was chosen (0.025, 0.3), without trailing zeros."""
    return f"{round(float(x), 9):g}".replace("-", "−")


def _pct(x, digits=0):
    """A relative change or share as a percentage (changes may exceed 100 %)."""
    x = float(x)
    return pct(x, digits) if 0.0 <= x <= 1.0 else f"{num(100 * x)} %"


@dataclass(frozen=True)
class ComparatorCheck:
    """FDSC against the comparator set (:mod:`fdsc.paper.comparators`) along one sweep.

    Parameters
    ----------
    family : {"mixed", "piecewise"}
        The sweep (paper Fig. 7 or 8).
    param : (m,) ndarray
        ρ_p or ρ_t.
    best : tuple of str
        The best fixed controller at each point: the member of the comparator set of least
        energy.
    best_energy, fdsc, open_loop : (m,) ndarray
        ∫zᵀz of the best fixed controller, of FDSC (paper's gains and Q's) and of the open loop
        at each point.
    """

    family: str
    param: np.ndarray
    best: tuple
    best_energy: np.ndarray
    fdsc: np.ndarray
    open_loop: np.ndarray

    @property
    def n_fdsc_better(self) -> int:
        """Number of points at which FDSC has less energy than the best fixed controller."""
        return int(np.sum(self.fdsc < self.best_energy))

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``n_better``, ``n`` (points), ``winners`` (which member is best how
            often, in words), ``ratio`` (FDSC's energy over the best fixed one's, as a range of
            factors), ``open_loop_better`` (points at which the open loop alone has less energy
            than FDSC).
        """
        names, counts = np.unique(np.asarray(self.best), return_counts=True)
        order = np.argsort(-counts, kind="stable")
        ratio = self.fdsc / self.best_energy
        lo, hi = float(ratio.min()), float(ratio.max())
        return {"n_better": count(self.n_fdsc_better), "n": count(len(self.best)),
                "winners": ", ".join(f"{names[k]} at {count(int(counts[k]))}" for k in order),
                "ratio": times(lo) if times(lo) == times(hi) else f"{times(lo)} to {times(hi)}",
                "open_loop_better": count(int(np.sum(self.open_loop < self.fdsc)))}


def against_comparators() -> dict:
    """FDSC against the best fixed controller of each point of both sweeps.

    The energies come from :func:`fdsc.paper.baselines.baselines`, whose mixed and piecewise
    scenarios are the points of paper Figs. 7 and 8 with every controller of the comparator set
    (the open loop and the best certified HF design included).

    Returns
    -------
    dict
        ``{"mixed": ComparatorCheck, "piecewise": ComparatorCheck}``.
    """
    from .baselines import baselines
    from .comparators import best_fixed

    base = baselines()
    out = {}
    for family in ("mixed", "piecewise"):
        scen = base.family(family)
        best = [best_fixed(s.energy, "aircraft") for s in scen]
        out[family] = ComparatorCheck(family, np.array([s.param for s in scen]), tuple(b[0] for b in best),
                                      np.array([b[1] for b in best]),
                                      np.array([s.energy["FDSC"] for s in scen]),
                                      np.array([s.energy["open loop"] for s in scen]))
    return out


def record_part() -> RecordPart:
    """Record figures and entries of the chapter (see :meth:`SweepStudy.to_record`).

    Returns
    -------
    RecordPart
    """
    return sweep_study().to_record()
