"""Chapter 'stationary': paper Figs. 4, 5 and 6 (stationary LF and HF disturbances, four
controllers), energies, and step halving.
"""


import numpy as np

from .._validation import as_positive
from ..frequency import steady_state_gain
from ..simulate import envelope, time_grid
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
from .results import RecordPart

__all__ = [
    "record_part",
    "stationary_runs",
    "step_halving",
]


def _l2_norm_curve(sim):
    """Running L2-induced norm sqrt(∫₀ᵗ zᵀz / ∫₀ᵗ d²) on the grid (trapezoid; dt cancels)."""
    zz = np.concatenate([[0.0], np.cumsum(0.5 * (np.sum(sim.z[1:] ** 2, 1) + np.sum(sim.z[:-1] ** 2, 1)))])
    dd = np.concatenate([[0.0], np.cumsum(0.5 * (sim.d[1:] ** 2 + sim.d[:-1] ** 2))])
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = np.sqrt(np.where(dd > 0, zz / dd, np.nan))
    return ratio


def stationary_runs(kind, *, horizon=STATIONARY_HORIZON, dt=STATIONARY_DT, every=50,
                    head=2.0, with_our_q=True):
    """Paper Figs. 4 (kind="LF"), 5 and 6 (kind="HF"): the four controllers under a stationary
    disturbance, from rest.

    Parameters
    ----------
    kind : {"LF", "HF"}
        The paper's LF (eq. (56)) or HF (eq. (57)) disturbance.
    horizon, dt : float
        Run length and step in s.
    every : int
        Samples per bin of the decimated traces (min/max envelope, so nothing is aliased).
    head : float
        Length in s of the start of the run kept at full resolution.
    with_our_q : bool
        Add FDSC with our Q's ("FDSC (our Q)").

    Returns
    -------
    dict
        ``t`` (bin starts), ``z_lo``/``z_hi`` {controller: (k, 3) min/max per bin},
        ``t_head``/``z_head`` (full resolution over ``[0, head]``), ``energy`` {controller:
        ∫zᵀz dt}, ``l2`` {controller: (k,) running L2-induced norm at the bin starts} and its
        min/max per bin ``l2_lo``/``l2_hi`` at the times ``t_l2`` (the ratio is undefined at
        t = 0), ``l2_steady`` {fixed-gain controller: the limit of its running ratio, closed
        form}, ``peak`` {controller: (3,) max |z_i| over the run}, ``switches`` and ``share``
        of FDSC, ``horizon``, ``dt``.
    """
    d = paper_disturbance(kind)
    t = time_grid(horizon, dt)
    names = list(CONTROLLERS) + (["FDSC (our Q)"] if with_our_q else [])
    Qours = our_q().Q if with_our_q else None
    n_head = int(round(as_positive("head", head) / dt)) + 1
    out = {"t": t[::every], "z_lo": {}, "z_hi": {}, "t_head": t[:n_head], "z_head": {},
           "energy": {}, "l2": {}, "l2_lo": {}, "l2_hi": {}, "switches": {}, "share": {},
           "every": every, "peak": {},
           "l2_steady": {c: steady_state_gain(aircraft().closed_loop(paper_gains()[g]), d.frequencies,
                                              d.amplitudes) for c, g in CONTROLLER_GAINS.items()},
           "horizon": horizon, "dt": dt, "kind": kind, "input_energy": None}
    for name in names:
        sim = run_controller("FDSC", d, t, Q=Qours) if name == "FDSC (our Q)" else run_controller(name, d, t)
        _, out["z_lo"][name], out["z_hi"][name] = envelope(sim.t, sim.z, every)
        out["z_head"][name] = sim.z[:n_head]
        out["peak"][name] = np.abs(sim.z).max(axis=0)
        out["energy"][name] = sim.energy()
        l2 = _l2_norm_curve(sim)
        out["l2"][name] = l2[::every]
        out["t_l2"], out["l2_lo"][name], out["l2_hi"][name] = envelope(sim.t[1:], l2[1:], every)
        out["input_energy"] = sim.input_energy()
        if name.startswith("FDSC"):
            out["switches"][name] = int(sim.switch_times.size)
            out["share"][name] = sim.time_share().tolist()
    return out


def step_halving(kind, *, horizon=100.0, dt=STATIONARY_DT):
    """Energies and switch counts with dt and dt/2 for every controller (the law is sampled)."""
    d = paper_disturbance(kind)
    rows = []
    for name in CONTROLLERS:
        s1 = run_controller(name, d, time_grid(horizon, dt))
        s2 = run_controller(name, d, time_grid(horizon, dt / 2))
        e1, e2 = s1.energy(), s2.energy()
        rows.append({"controller": name, "energy_dt": e1, "energy_dt2": e2,
                     "rel_change": abs(e2 - e1) / abs(e1), "switches_dt": int(s1.switch_times.size),
                     "switches_dt2": int(s2.switch_times.size)})
    return rows


def record_part():
    """Record figures lf_outputs, hf_outputs (paper Figs. 4 and 5: energies and switch counts) and
    hf_l2 (paper Fig. 6: the L2-induced norm).

    Returns
    -------
    RecordPart
    """
    figures = {}
    for fig, kind in (("lf_outputs", "LF"), ("hf_outputs", "HF")):
        runs = stationary_runs(kind)
        figures[fig] = {"paper_figure": FIGURE_IDS[fig], "disturbance": kind,
                        "horizon": STATIONARY_HORIZON, "dt": STATIONARY_DT,
                        "energy": {k: v for k, v in runs["energy"].items() if k != "FDSC (our Q)"},
                        "energy_fdsc_our_q": runs["energy"]["FDSC (our Q)"],
                        "switches": runs["switches"],
                        "units": {"horizon": "s", "dt": "s",
                                  "energy": "integral of z'z over [0, horizon] (z as printed, s)"}}
        if kind == "HF":
            figures["hf_l2"] = {
                "paper_figure": FIGURE_IDS["hf_l2"], "horizon": STATIONARY_HORIZON,
                "l2_induced_norm_final": {k: float(v[-1]) for k, v in runs["l2"].items()},
                "l2_induced_norm_steady_state": runs["l2_steady"],
                "units": {"horizon": "s", "l2_induced_norm": "1 (sqrt of an energy ratio)"},
                "note": "running ratio from rest at the horizon; steady state = its limit for the "
                        "fixed gains (closed form); FDSC has no closed form"}
    return RecordPart(figures=figures)
