"""Chapter 'stationary', continued: the runs behind paper Figs. 4, 5 and 6.

The four controllers under a stationary disturbance, from rest: the LF disturbance of paper
Fig. 4 and the HF disturbance of paper Figs. 5 and 6, with the energies and the running
L2-induced ratio the figures plot.
"""

from dataclasses import dataclass

import numpy as np

from fdsc._validation import as_choice, as_positive
from fdsc.frequency import steady_state_gain
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.data import (
    STATIONARY_DT,
    STATIONARY_HORIZON,
    aircraft,
    our_q,
    paper_disturbance,
    paper_gains,
    run_controller,
)
from fdsc.paper.shared.names import CONTROLLER_GAINS, CONTROLLERS, FIGURE_IDS
from fdsc.paper.shared.prose import count, num, pct
from fdsc.paper.shared.results import RecordPart
from fdsc.simulate import envelope, time_grid

__all__ = ["OUR_Q_NAME", "StationaryRuns", "stationary_runs"]


#: The name of FDSC with our Q's beside the paper's four controllers.
OUR_Q_NAME = "FDSC (our Q)"


def _whole(x):
    """A count or a length as the prose prints it: whole numbers without decimals."""
    x = float(x)
    return count(int(x)) if x.is_integer() else num(x)


def _l2_norm_curve(sim):
    """Running L2-induced norm sqrt(∫₀ᵗ zᵀz / ∫₀ᵗ d²) on the grid (each step's energy exact)."""
    zz, dd = sim.cumulative_energy()
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
        ``{controller: (3,) ndarray}``: max ``|z_i|`` over the run.
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
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.shared.prose`).

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
    :data:`~fdsc.paper.shared.data.STATIONARY_HORIZON`).
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
