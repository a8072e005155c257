"""Artefacts of Sec. III and the first half of Sec. IV: Theorem 1 on the aircraft, the switching law
in action, and the stationary-disturbance runs of paper Figs. 4, 5 and 6.

Plain-data functions called by the book and the reproduction record.
"""

import numpy as np

from ._validation import as_choice, as_positive
from .frequency import steady_state_gain
from .plant import aircraft, paper_gains
from .selectiveness import paper_modes
from .signals import Sinusoids, paper_disturbance, piecewise_disturbance
from .simulate import envelope, simulate, time_grid
from .switching import DEFAULT_GAMMA_TOL, certify_q, design_q

__all__ = [
    "CONTROLLERS",
    "CONTROLLER_GAINS",
    "STATIONARY_HORIZON",
    "STATIONARY_DT",
    "theorem1_table",
    "our_q",
    "run_controller",
    "stationary_runs",
    "step_halving",
    "switching_statistics",
    "autonomous_stability",
    "lyapunov_jumps",
    "window_ratios",
    "law_conflict",
]

#: Controllers compared in paper Figs. 4-8 (the paper's names).
CONTROLLERS = ("PassC-EF", "PassC-LF", "PassC-HF", "FDSC")
#: The printed gain of each fixed-gain controller.
CONTROLLER_GAINS = {"PassC-EF": "K_e", "PassC-LF": "K_f1", "PassC-HF": "K_f3"}
#: Our choice for the horizon of paper Figs. 4-6 (not printed): 500 s, the horizon of paper Fig. 7.
STATIONARY_HORIZON = 500.0
#: Our time step: 1 ms (0.3 rad per step at the fastest tone; the step is exact, the law is
#: sampled and the energy integral is Simpson's rule with a relative error of order (ω dt)⁴/180).
STATIONARY_DT = 1e-3


def our_q(gamma_tol=DEFAULT_GAMMA_TOL):
    """Q_1, Q_2 from the paper Remark 4 design on the paper's modes (in-band mode: HF, index 1)."""
    pm = paper_modes()
    return design_q(pm["modes"], pm["bands"], 1, gamma_tol=gamma_tol)


def theorem1_table(gamma_tols=(1.0, 10.0, 100.0, 1000.0)):
    """γ's certified by Theorem 1 with the paper's Q's and with the paper Remark 4 design over γ_tol.

    Returns
    -------
    list of dict
        ``source, gamma_tol, gamma_1, gamma_2, Q_1, Q_2, max_eig`` (largest LMI eigenvalue,
        < 0).
    """
    pm = paper_modes()
    rows = []
    paper = certify_q(pm["modes"], pm["bands"], pm["Q"])
    rows.append({"source": "paper's Q's (certified)", "gamma_tol": np.nan,
                 "gamma_1": paper.gammas[0], "gamma_2": paper.gammas[1], "Q_1": paper.Q[0],
                 "Q_2": paper.Q[1], "max_eig": max(paper.max_eigs.values())})
    for gt in gamma_tols:
        r = design_q(pm["modes"], pm["bands"], 1, gamma_tol=gt)
        rows.append({"source": "paper Remark 4 design", "gamma_tol": gt, "gamma_1": r.gammas[0],
                     "gamma_2": r.gammas[1], "Q_1": r.Q[0], "Q_2": r.Q[1],
                     "max_eig": max(r.max_eigs.values())})
    return rows


def run_controller(name, d, t, *, Q=None, law="previous", x0=None):
    """Simulate one of :data:`CONTROLLERS` (FDSC with the given Q's, default the paper's).

    Parameters
    ----------
    name : {"PassC-EF", "PassC-LF", "PassC-HF", "FDSC"}
    d : Sinusoids or Piecewise
    t : (N,) array_like
        Uniform grid.
    Q : list of (2, 2) array_like, optional
        Q's of the FDSC law (default the paper's).
    law : {"previous", "candidate"}
    x0 : (2,) array_like, optional

    Returns
    -------
    SimResult
    """
    as_choice("name", name, CONTROLLERS)
    plant, gains = aircraft(), paper_gains()
    if name == "FDSC":
        pm = paper_modes()
        return simulate(pm["modes"], d, t, law_bands=pm["bands"], law_Q=pm["Q"] if Q is None else Q,
                        law=law, x0=x0)
    return simulate(plant.closed_loop(gains[CONTROLLER_GAINS[name]]), d, t, x0=x0)


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


def switching_statistics(*, T=100.0, rho_t=0.2, rho_p_star=0.1, dt=STATIONARY_DT, laws=None):
    """σ(t) along the piecewise disturbance of paper Fig. 8 (shortened to T), for several law variants.

    Returns
    -------
    dict
        ``t`` (bin starts), ``bin`` (bin length, s), ``breaks``, and per variant ``sigma`` (share
        of each bin spent in the HF mode, so chattering is not aliased), ``switches``,
        ``share`` (fraction in the HF mode per disturbance segment), ``single_sample_dwell``
        (fraction of dwell intervals lasting one sample: the signature of chattering).
    """
    d = piecewise_disturbance(T, rho_t, rho_p_star)
    t = time_grid(d.breaks[-1], dt)
    pm = paper_modes()
    laws = laws or {"paper Q, measured ẋ": (pm["Q"], "previous"),
                    "paper Q, candidate ẋ": (pm["Q"], "candidate"),
                    "our Q, measured ẋ": (our_q().Q, "previous")}
    every = 20
    starts = np.arange(0, t.size, every)
    out = {"t": t[starts], "breaks": d.breaks, "variants": {}, "bin": every * dt}
    for label, (Q, law) in laws.items():
        sim = simulate(pm["modes"], d, t, law_bands=pm["bands"], law_Q=Q, law=law)
        seg = d.segment_of(t)
        share = [float(np.mean(sim.sigma[seg == k] == 1)) for k in range(len(d.parts))]
        sw = np.flatnonzero(np.diff(sim.sigma)) + 1
        dwell = np.diff(np.concatenate([[0], sw, [t.size - 1]]))
        out["variants"][label] = {
            # the share of each bin spent in mode 1: σ chatters at the sampling rate, so every
            # n-th sample of σ would alias; the per-bin share holds every sample
            "sigma": np.add.reduceat(sim.sigma, starts) / np.diff(np.append(starts, t.size)),
            "switches": int(sw.size), "share_hf": share,
            "single_sample_dwell": float(np.mean(dwell <= 1)) if dwell.size else 0.0,
            "energy": sim.energy()}
    return out


def autonomous_stability(n_initial=40, *, horizon=60.0, dt=1e-3, seed=3, Q=None):
    """Statement (1): the autonomous switched loop (d = 0) from random initial states.

    Returns
    -------
    dict
        ``final_ratio`` (‖x(T)‖/‖x(0)‖ per run), ``max_growth`` (max over t of ‖x(t)‖/‖x(0)‖),
        ``switches`` per run.
    """
    rng = np.random.default_rng(seed)
    pm = paper_modes()
    Q = pm["Q"] if Q is None else Q
    t = time_grid(horizon, dt)
    zero = Sinusoids([0.0], [1.0])
    ratios, growth, switches = [], [], []
    for _ in range(int(n_initial)):
        x0 = rng.standard_normal(2)
        sim = simulate(pm["modes"], zero, t, x0=x0, law_bands=pm["bands"], law_Q=Q)
        nrm = np.linalg.norm(sim.x, axis=1) / np.linalg.norm(x0)
        ratios.append(float(nrm[-1]))
        growth.append(float(nrm.max()))
        switches.append(int(sim.switch_times.size))
    return {"final_ratio": np.array(ratios), "max_growth": np.array(growth),
            "switches": np.array(switches), "horizon": horizon}


def lyapunov_jumps(result, *, kind="HF", horizon=20.0, dt=STATIONARY_DT, Q=None):
    """Jumps of V = xᵀ P^s_σ x at the switching instants of an FDSC run.

    Parameters
    ----------
    result : Theorem1Result
        Supplies P^s_1, P^s_2 (and, unless ``Q`` is given, the law's Q's).

    Returns
    -------
    dict
        ``ratios`` V(t⁺)/V(t⁻) at every switch, ``max_ratio``, ``n_switches``.
    """
    pm = paper_modes()
    d = paper_disturbance(kind)
    t = time_grid(horizon, dt)
    sim = simulate(pm["modes"], d, t, law_bands=pm["bands"], law_Q=result.Q if Q is None else Q)
    k = np.flatnonzero(np.diff(sim.sigma)) + 1
    x = sim.x[k]
    before = np.einsum("ki,kij,kj->k", x, np.array(result.Ps)[sim.sigma[k - 1]], x)
    after = np.einsum("ki,kij,kj->k", x, np.array(result.Ps)[sim.sigma[k]], x)
    ratios = after / before
    return {"ratios": ratios, "max_ratio": float(ratios.max()) if ratios.size else 1.0,
            "n_switches": int(k.size)}


def window_ratios(run_sim, window):
    """Energy ratio ∫zᵀz/∫d² over consecutive windows of a run (Theorem 1 statement (2)).

    Parameters
    ----------
    run_sim : SimResult
    window : float
        Window length in s (at least two steps, at most the run).

    Returns
    -------
    (k,) ndarray
    """
    t = run_sim.t
    window = as_positive("window", window)
    n = round(window / (t[1] - t[0]))
    if n < 2 or n > t.size - 1:
        raise ValueError(f"window must span between 2 steps ({2 * (t[1] - t[0]):g} s) and the run "
                         f"({t[-1] - t[0]:g} s), but found {window:g} s")
    zz = np.sum(run_sim.z**2, axis=1)
    out = []
    for k0 in range(0, t.size - n, n):
        sl = slice(k0, k0 + n + 1)
        out.append(float(np.trapezoid(zz[sl], t[sl]) / np.trapezoid(run_sim.d[sl] ** 2, t[sl])))
    return np.array(out)



def law_conflict(sim, modes, law_bands, law_Q):
    """Where the printed law with the measured ẋ cannot settle, along a simulated run.

    With ẋ = A_σ(t⁻) x + B d the score of every candidate depends on the mode active just before
    t. At a sample, mode i "prefers" the mode with the best score computed with ẋ = A_i x + B d. The
    law cannot settle where every mode prefers another (for two modes: mode 1 prefers mode 2 and
    mode 2 prefers mode 1): whichever is active, the next sample switches. That set is a region of
    the (x, d) space, not the surface where two scores are equal.

    Parameters
    ----------
    sim : SimResult
        A run of the switched loop.
    modes : list of LTISystem
    law_bands : list of Band
    law_Q : list of (n, n) array_like

    Returns
    -------
    dict
        ``in_region`` (fraction of samples in the region), ``switches_in_region`` (fraction of
        switches taken at a sample in the region), ``n_switches``.
    """
    n_modes = len(modes)
    scores = np.empty((n_modes, n_modes, sim.t.size))  # [active i, candidate j, k]
    for i, m in enumerate(modes):
        xdot = sim.x @ m.A.T + np.outer(sim.d, m.B[:, 0])
        v = np.hstack([xdot, sim.x])
        for j, (b, Q) in enumerate(zip(law_bands, law_Q, strict=True)):
            W = np.kron(b.psi.real, np.asarray(Q, dtype=float))
            scores[i, j] = np.einsum("kr,rc,kc->k", v, W, v)
    prefers = scores.argmax(axis=1)  # [active i, k]
    region = np.all(prefers != np.arange(n_modes)[:, None], axis=0)
    sw = np.flatnonzero(np.diff(sim.sigma)) + 1
    return {"in_region": float(region.mean()),
            "switches_in_region": float(region[sw].mean()) if sw.size else 0.0,
            "n_switches": int(sw.size)}
