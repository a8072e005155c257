"""Chapter 'theorem1': Theorem 1 (paper eqs. (33), (34)) on the aircraft, the paper's and our Q's,
statement (1) by simulation and the Lyapunov jumps, statement (2) over windows.
"""


import numpy as np

from .._validation import as_count, as_positive, check_type
from ..signals import Sinusoids
from ..simulate import simulate, time_grid
from ..switching import Theorem1Result, certify_q, design_q
from .data import (
    STATIONARY_DT,
    our_q,
    paper_data,
    paper_disturbance,
    paper_modes,
)
from .results import RecordPart

__all__ = [
    "record_part",
    "theorem1_table",
    "autonomous_stability",
    "lyapunov_jumps",
    "window_ratios",
    "autonomous_lyapunov_jumps",
]


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


def autonomous_lyapunov_jumps(result, n_initial=40, *, horizon=60.0, dt=1e-3, seed=3, Q=None):
    """Jumps of ``V = xᵀ P^s_σ x`` at the switches of the autonomous switched loop (d = 0).

    Theorem 1 statement (1) is about d = 0; its proof differentiates V between switches and
    never compares V across a switch. The runs start from the same random initial states as
    :func:`fdsc.scenarios.autonomous_stability` (same ``seed``).

    Parameters
    ----------
    result : Theorem1Result
        Supplies P^s_1, P^s_2 and (unless ``Q`` is given) the law's Q's.
    n_initial : int
        Number of initial states (standard normal).
    horizon, dt : float
        Length and step of each run in s.
    seed : int
    Q : list of (n, n) array_like, optional
        Q's of the switching law.

    Returns
    -------
    dict
        ``ratios`` V(t⁺)/V(t⁻) at all switches of all runs, ``max_ratio``, ``frac_up`` (share
        of switches at which V increases), ``n_switches``, ``n_runs``, ``horizon``,
        ``final_ratio`` (‖x(T)‖/‖x(0)‖ per run).

    Examples
    --------
    >>> from fdsc.paper.data import our_q
    >>> j = autonomous_lyapunov_jumps(our_q(), 3, horizon=5.0)
    >>> j["n_runs"], bool(j["max_ratio"] > 1)
    (3, True)
    """
    check_type("result", result, Theorem1Result)
    n_initial = as_count("n_initial", n_initial)
    pm = paper_modes()
    Q = result.Q if Q is None else Q
    Ps = np.array(result.Ps)
    rng = np.random.default_rng(seed)
    t = time_grid(horizon, dt)
    zero = Sinusoids([0.0], [1.0])
    ratios, final = [], []
    for _ in range(n_initial):
        x0 = rng.standard_normal(Ps.shape[1])
        sim = simulate(pm["modes"], zero, t, x0=x0, law_bands=pm["bands"], law_Q=Q)
        k = np.flatnonzero(np.diff(sim.sigma)) + 1
        x = sim.x[k]
        before = np.einsum("ki,kij,kj->k", x, Ps[sim.sigma[k - 1]], x)
        after = np.einsum("ki,kij,kj->k", x, Ps[sim.sigma[k]], x)
        ratios.append(after / before)
        final.append(float(np.linalg.norm(sim.x[-1]) / np.linalg.norm(x0)))
    ratios = np.concatenate(ratios)
    return {"ratios": ratios, "max_ratio": float(ratios.max()) if ratios.size else 1.0,
            "frac_up": float(np.mean(ratios > 1)) if ratios.size else 0.0,
            "n_switches": int(ratios.size), "n_runs": n_initial, "horizon": float(horizon),
            "final_ratio": np.array(final)}


def record_part():
    """Record entries Q_1, Q_2 (the law's Q's) and thm1_gammas (what Theorem 1 certifies).

    Returns
    -------
    RecordPart
    """
    sw = paper_data("switching")
    ours = our_q()
    table = theorem1_table()
    paper_row = table[0]
    entries = []
    for k, name in enumerate(("Q_1", "Q_2")):
        entries.append({
            "id": name, "source": f"Sec. IV, {name}", "paper": sw[name]["value"],
            "recomputed": ours.Q[k], "verdict": "not reproducible",
            "note": ("the paper prints the Q's but not gamma_tol nor the Q's scale, which the "
                     "Remark 4 design needs (Q enters Theorem 1 only through differences); ours: "
                     "Remark 4 design with gamma_tol = "
                     f"{table[2]['gamma_tol']:g} (in-band mode PassC-HF): it reaches gamma_2 = "
                     f"{ours.gammas[1]:.4f} by driving Q_1 to the margin; the printed Q's certify "
                     f"only gamma = ({paper_row['gamma_1']:.4g}, {paper_row['gamma_2']:.4g}).")})
    entries.append({
        "id": "thm1_gammas", "source": "Theorem 1, paper Remark 4 (gammas not printed)",
        "paper": None,
        "recomputed": {"paper_Q": [paper_row["gamma_1"], paper_row["gamma_2"]],
                       "ours": {f"gamma_tol={r['gamma_tol']:g}": [r["gamma_1"], r["gamma_2"]]
                                for r in table[1:]}},
        "verdict": "new",
        "note": "the paper prints no gammas; these are the values Theorem 1 certifies."})
    return RecordPart(tuple(entries))
