"""Chapter 'nonstationary', continued: the ρ_p and ρ_t sweeps of paper Figs. 7 and 8.

The controllers of both sweeps, the disturbance of each family member, and one streamed batch
(:func:`fdsc.simulate_batch`) per sweep: the mixed sweep (ρ_p, paper Fig. 7), the piecewise
sweep (ρ_t, paper Fig. 8) and the piecewise sweep beyond the paper's range of ρ_t.
"""

from dataclasses import dataclass

import numpy as np

from fdsc._validation import as_choice, as_count, as_positive
from fdsc.paper.reproduced.stationary_figures import OUR_Q_NAME
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.data import (
    STATIONARY_DT,
    aircraft,
    mixed_disturbance,
    our_q,
    paper_data,
    paper_fdsc,
    paper_gains,
    piecewise_disturbance,
)
from fdsc.paper.shared.names import CONTROLLER_GAINS, FIGURE_IDS
from fdsc.stream import Case, simulate_batch

__all__ = [
    "CANDIDATE_NAME", "COARSE_STEP", "P2_WINDOWS", "RHO_T_EXTENDED", "SWEEP_NAMES", "SweepRuns",
    "extended_piecewise", "family_signal", "fdsc_designs", "mixed_sweep", "piecewise_sweep",
    "sweep_cases",
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
    >>> from fdsc.paper.shared.data import paper_disturbance
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
        :mod:`fdsc.paper.shared.comparators` (see :func:`against_comparators`)."""
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
        Grid points of ρ_p (≥ 2; the paper's range, :func:`~fdsc.paper.shared.data.paper_data`).
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
