"""Chapter section 'dwell time': a certified dwell-time bound for the paper's two FDSC modes.

The FDSC loop (paper eq. (32)) switches between the closed loops of K_f1 (eigenvalues ≈ −1.12,
−303) and K_f3 (≈ −1.08, −0.0165). Theorem 1 (paper eqs. (33), (34)) does not bound the jumps of
its Lyapunov function at the switches; the classical dwell-time theorem (Liberzon 2003,
Ch. 3; Hespanha & Morse 1999) does, for switching signals whose switches are at least τ*
apart. This module computes τ* (:func:`fdsc.dwell.dwell_time_bound`), sets it beside the
periodic-switching margin and beside what Theorem 1's own P^s_i certify, and checks the bound
along seeded random switching signals realised exactly with matrix exponentials (d = 0).
"""

from dataclasses import dataclass

import numpy as np

from fdsc.dwell import (
    DwellTimeBound,
    LyapunovDwell,
    PeriodicDwellMargin,
    check_dwell_bound,
    dwell_time_bound,
    lyapunov_dwell,
    periodic_dwell_margin,
    random_dwell_signal,
)
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.data import our_q, paper_modes
from fdsc.switching import certify_q

__all__ = ["DwellRuns", "DwellCertificate", "dwell_certificate", "dwell_runs", "FAST_HORIZON"]

#: Length in s of the runs with fast switching (dwells of 0.01 to 0.1 s, not covered by τ*).
FAST_HORIZON = 30.0


@dataclass(frozen=True)
class DwellRuns:
    """Checks of the dwell-time envelope along random switching signals from random initial states.

    Parameters
    ----------
    label : str
        What the signals are (e.g. ``"dwell in [1.01, 3] tau*"``).
    min_dwell, max_dwell : float
        Range of the dwells in s.
    checks : tuple of DwellCheck
        One per run.
    """

    label: str
    min_dwell: float
    max_dwell: float
    checks: tuple

    @property
    def all_hold(self) -> bool:
        """Whether the envelope V ≤ μ^N e^{−2λt} V(0) holds on every run (and, for dwells above
        τ*, the guaranteed decay)."""
        return all(c.max_ratio <= 1 + 1e-9 for c in self.checks) and all(
            c.holds() for c in self.checks if c.rate_bound > 0)

    def summary(self) -> dict:
        """Plain summary of the runs.

        Returns
        -------
        dict
            ``label, n_runs, min_dwell, max_dwell, n_switches, max_envelope_ratio,
            max_final_norm_ratio, all_hold``.
        """
        return {"label": self.label, "n_runs": len(self.checks), "min_dwell": self.min_dwell,
                "max_dwell": self.max_dwell,
                "n_switches": int(sum(c.n_switches for c in self.checks)),
                "max_envelope_ratio": max(c.max_ratio for c in self.checks),
                "max_final_norm_ratio": max(c.final_norm_ratio for c in self.checks),
                "all_hold": self.all_hold}


def dwell_runs(bound: DwellTimeBound, modes, min_dwell: float, max_dwell: float, label: str, *,
               n_runs: int = 20, horizon: float = 300.0, dt: float = 0.1,
               seed: int = 11) -> DwellRuns:
    """Seeded random switching signals with dwells in [min_dwell, max_dwell], from random x(0).

    Parameters
    ----------
    bound : DwellTimeBound
        The certificate checked.
    modes : list of LTISystem
        Its modes.
    min_dwell, max_dwell : float
        Range of the dwells in s.
    label : str
        Name of the set of runs.
    n_runs : int, optional
        Number of runs.
    horizon, dt : float, optional
        Length of each run and spacing of the samples in s (the switching instants are added).
    seed : int, optional
        Seed of the initial states (standard normal) and the signals.

    Returns
    -------
    DwellRuns
    """
    rng = np.random.default_rng(seed)
    t = np.arange(0.0, horizon + dt / 2, dt)
    checks = []
    for _ in range(n_runs):
        x0 = rng.standard_normal(bound.P[0].shape[0])
        st, seq = random_dwell_signal(rng, len(modes), min_dwell, horizon, max_dwell=max_dwell)
        checks.append(check_dwell_bound(bound, modes, x0, st, seq, t))
    return DwellRuns(label, float(min_dwell), float(max_dwell), tuple(checks))


@dataclass(frozen=True)
class DwellCertificate:
    """The dwell-time bound of the paper's FDSC modes, its conservatism and its checks.

    Parameters
    ----------
    bound : DwellTimeBound
        τ*, λ, μ (tight and crude), the P_i and the λ grid (:func:`fdsc.dwell.dwell_time_bound`).
    periodic : PeriodicDwellMargin
        Spectral radius of periodic switching K_f1 → K_f3 → K_f1 over a grid of dwells.
    theorem1 : dict
        ``{"paper": LyapunovDwell, "ours": LyapunovDwell}``: what Theorem 1's P^s_i (with the
        paper's and with our Q's) certify as dwell-time Lyapunov matrices.
    slow : DwellRuns
        Runs with every dwell in [1.01 τ*, 3 τ*] (covered by the bound).
    fast : DwellRuns
        Runs with dwells far below τ* (not covered: the envelope still holds, decay is not
        guaranteed).
    """

    bound: DwellTimeBound
    periodic: PeriodicDwellMargin
    theorem1: dict
    slow: DwellRuns
    fast: DwellRuns

    def prose(self) -> dict:
        """The numbers the chapter quotes, as text (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        dict of str
            The bound: ``tau`` (τ*, s), ``decay`` (λ, 1/s), ``mu``, ``mu_crude``, ``tau_crude``
            (at the same λ) and ``tau_crude_best`` (over the grid), ``lim_1``/``lim_2`` (the
            modes' decay limits, 1/s), ``n_decays``, ``n_solves``, ``max_eig``. Theorem 1's
            P^s_i: ``t1_paper_tau``, ``t1_paper_mu`` (printed Q's), ``t1_ours_rate`` (the K_f3
            mode's decay rate with our Q's, 1/s) and ``t1_ours_growth`` (−2 × that rate). The
            periodic margin: ``per_n`` dwells from ``per_tmin`` (ms) to ``per_tmax`` (s),
            ``per_rho_max``, ``lower`` (s). The runs: ``slow_*`` and ``fast_*`` with ``n`` runs
            of ``T`` s, ``sw`` switches, ``env`` (largest envelope ratio) and ``final``
            (largest ‖x(T)‖/‖x(0)‖); ``fast_dwells``, the range of the fast runs' dwells (s).
        """
        from fdsc.paper.shared.prose import count, num, span

        b, p, t1 = self.bound, self.periodic, self.theorem1
        out = {"tau": num(b.tau), "decay": num(b.decay), "mu": num(b.mu), "mu_crude": num(b.mu_crude),
               "tau_crude": num(b.tau_crude), "tau_crude_best": num(float(np.min(b.taus_crude))),
               "lim_1": num(float(b.decay_limits[0])), "lim_2": num(float(b.decay_limits[1])),
               "n_decays": count(int(b.decays.size)), "n_solves": count(b.n_solves),
               "max_eig": num(float(b.max_eigs.max())),
               "t1_paper_tau": num(t1["paper"].tau), "t1_paper_mu": num(t1["paper"].mu),
               "t1_ours_rate": num(float(t1["ours"].rates[1])),
               "t1_ours_growth": num(-2 * float(t1["ours"].rates[1])),
               "per_n": count(int(p.taus.size)), "per_tmin": num(float(p.taus[0]) * 1e3, 2),
               "per_tmax": num(float(p.taus[-1]), 2), "per_rho_max": num(float(p.rho_worst.max()), 5),
               "lower": num(p.lower_bound, 2)}
        for name, runs in (("slow", self.slow), ("fast", self.fast)):
            s = runs.summary()
            out |= {f"{name}_n": count(s["n_runs"]), f"{name}_sw": count(s["n_switches"]),
                    f"{name}_env": num(s["max_envelope_ratio"], 7),
                    f"{name}_final": num(s["max_final_norm_ratio"]),
                    f"{name}_T": num(runs.checks[0].horizon, 2)}
        # the fast runs' dwells are set, not measured: print them as set
        out["fast_dwells"] = span(self.fast.min_dwell, self.fast.max_dwell, 1, sep=" to ")
        return out

    def record_dict(self) -> dict:
        """Plain JSON-able summary for the record (entry ``hysteresis_dwell``).

        Returns
        -------
        dict
        """
        b, p = self.bound, self.periodic

        def t1(r: LyapunovDwell):
            return {"rates": r.rates.tolist(), "decay": r.decay, "mu": r.mu,
                    "mu_crude": r.mu_crude, "tau": r.tau if np.isfinite(r.tau) else None}

        return {
            "tau_star": b.tau, "decay": b.decay, "mu": b.mu, "mu_crude": b.mu_crude,
            "tau_crude": b.tau_crude, "tau_crude_best": float(np.min(b.taus_crude)),
            "decay_limits": b.decay_limits.tolist(), "n_decays": int(b.decays.size),
            "max_lmi_eig": float(b.max_eigs.max()), "n_solves": b.n_solves, "n_failed": b.n_failed,
            "periodic": {"tau_min": float(p.taus[0]), "tau_max": float(p.taus[-1]),
                         "n_tau": int(p.taus.size), "lower_bound": p.lower_bound,
                         "max_rho_equal": float(p.rho.max()),
                         "max_rho_worst_pair": float(p.rho_worst.max()),
                         "max_growth_worst_pair": float(p.growth_worst.max())},
            "theorem1_Ps": {k: t1(v) for k, v in self.theorem1.items()},
            "checks": {"slow": self.slow.summary(), "fast": self.fast.summary()},
        }


@cached
def dwell_certificate(n_runs: int = 20, horizon: float = 200.0, seed: int = 11) -> DwellCertificate:
    """The dwell-time bound for the paper's FDSC modes (K_f1 and K_f3 closed loops), checked.

    Parameters
    ----------
    n_runs : int, optional
        Runs of each set of random switching signals.
    horizon : float, optional
        Length of each run with dwells above τ* in s (samples every 0.1 s).
    seed : int, optional
        Seed of the runs.

    Returns
    -------
    DwellCertificate

    Notes
    -----
    The λ grid spans (0, 0.0165): the K_f3 loop's slow eigenvalue −0.0165 bounds the common
    decay rate. The periodic margin uses 300 dwells from 1 ms to 100 s (all 300² unequal pairs).
    The fast runs (dwells of 0.01 to 0.1 s, half as many runs, :data:`FAST_HORIZON` long) are
    not covered by τ*: they show what the bound does not promise.
    """
    pm = paper_modes()
    modes = pm["modes"]
    bound = dwell_time_bound(modes)
    periodic = periodic_dwell_margin(modes, np.geomspace(1e-3, 100.0, 300))
    theorem1 = {"paper": lyapunov_dwell(modes, certify_q(modes, pm["bands"], pm["Q"]).Ps),
                "ours": lyapunov_dwell(modes, our_q().Ps)}
    slow = dwell_runs(bound, modes, 1.01 * bound.tau, 3.0 * bound.tau,
                      "every dwell in [1.01, 3] tau*", n_runs=n_runs, horizon=horizon, seed=seed)
    # fast switching has ~20 switches per second: shorter runs keep the matrix exponentials few
    fast = dwell_runs(bound, modes, 0.01, 0.1, "every dwell in [0.01, 0.1] s",
                      n_runs=max(n_runs // 2, 1), horizon=FAST_HORIZON, dt=0.01, seed=seed + 1)
    return DwellCertificate(bound, periodic, theorem1, slow, fast)
