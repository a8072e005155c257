"""Chapter 'theorem1', continued: what closes the gap in Theorem 1's proof.

(b) The gap-closing certificates of :mod:`fdsc.lyapunov_jumps` (jumps of V, the law's switch-in
set, or a common P) on the paper's example and on the search's cases. (c) The residues ε_T and
ε_∞ of statements (2) and (3) (paper eqs. (35), (36)) measured on FDSC runs from the jumps of
``xᵀ P_σ x``, and β weighted by time against β weighted by disturbance energy.
"""

from dataclasses import dataclass

import numpy as np

from fdsc.exceptions import InfeasibleError, SolverError
from fdsc.lyapunov_jumps import certify_switching, certify_switching_gain
from fdsc.paper.repairs.theorem1_cases import _LAWS, _READING, FAMILIES
from fdsc.paper.repairs.theorem1_search import counterexample_search
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.data import our_q, paper_disturbance, paper_modes
from fdsc.paper.shared.prose import count, num, pct
from fdsc.simulate import simulate, time_grid
from fdsc.switching import certify_q

__all__ = ["GapClosing", "ResidueRun", "gap_closing", "residues"]


# ---------------------------------------------------------------------------------------------
# (b) the gap-closing certificates
# ---------------------------------------------------------------------------------------------

def _try_certificate(modes, bands, Q, law, condition, gain=False):
    """``{"certified": bool, ...}``: the decay rate (or γ's) if it holds, the reason if not."""
    fn = certify_switching_gain if gain else certify_switching
    try:
        cert = fn(modes, bands, Q, law=law, condition=condition)
    except InfeasibleError as exc:
        return {"certified": False, "why": str(exc.status)}
    except SolverError as exc:
        return {"certified": False, "why": f"solver failure: {exc.status}"}
    out = {"certified": True, "decay": float(cert.decay)}
    if gain:
        out["gammas"] = [float(g) for g in cert.gammas]
    return out


@dataclass(frozen=True)
class GapClosing:
    """The gap-closing certificates on the paper's example and on the search's cases.

    Parameters
    ----------
    paper : dict
        ``{(q_label, law, condition, kind): result}`` for the paper's FDSC, q_label in
        {"paper", "ours"}, kind "stability" (:func:`~fdsc.lyapunov_jumps.certify_switching`) or
        "gain" (:func:`~fdsc.lyapunov_jumps.certify_switching_gain`); a result is
        ``{"certified": bool, "decay" | "why", "gammas"?}``.
    divergent : tuple of (str, int, str, bool)
        ``(family, seed, law, certified)`` for every divergent run of the search (jump
        condition, the run's law); a certified divergent run would contradict the certificate.
    convergent : tuple of (str, int, str, bool)
        The same for the first :data:`N_CONVERGENT_SAMPLE` convergent feasible cases of each
        family: how much of what converges the certificate proves.
    """

    paper: dict
    divergent: tuple
    convergent: tuple

    def summary(self) -> dict:
        """Counts of certified runs among the divergent and the sampled convergent ones.

        Returns
        -------
        dict
        """
        return {"divergent": len(self.divergent),
                "divergent_certified": sum(d[3] for d in self.divergent),
                "convergent_sampled": len(self.convergent),
                "convergent_certified": sum(d[3] for d in self.convergent)}

    def paper_rows(self) -> list:
        """One row per (Q's, reading of ẋ, condition, kind) on the paper's example, every cell
        text with reader-facing names (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        list of dict
        """
        qname = {"paper": "printed Q", "ours": "our Q"}
        cname = {"jump": "jump and switch-in", "common": "common P"}
        kname = {"stability": "stability (d = 0)", "gain": "L₂ gain"}
        rows = []
        for (q, law, cond, kind), r in self.paper.items():
            rows.append({"Q's": qname[q], "reading of ẋ": _READING[law], "condition": cname[cond],
                         "kind": kname[kind], "certified": "yes" if r["certified"] else "no",
                         "result": (f"decay {num(r['decay'])} 1/s" if kind == "stability" else
                                    "γ = " + ", ".join(num(g) for g in r["gammas"]))
                         if r["certified"] else "no certificate"})
        return rows


#: Convergent feasible cases per family on which the gap-closing certificate is tried.
N_CONVERGENT_SAMPLE = 5


@cached
def gap_closing() -> GapClosing:
    """The gap-closing certificates on the paper's example and on the search's cases.

    Returns
    -------
    GapClosing

    Notes
    -----
    The conditions are those of :mod:`fdsc.lyapunov_jumps`: Theorem 1's (T1-1)/(T1-2) (paper
    eqs. (33), (34)) with free multipliers, plus the jump condition on the switching set and the
    flow condition on the switch-in set of the law (paper eq. (31)), or a common P.
    """
    pm = paper_modes()
    paper = {}
    for q_label, Q in (("paper", pm["Q"]), ("ours", our_q().Q)):
        for law in _LAWS:
            for cond in ("jump", "common"):
                for kind in ("stability", "gain"):
                    paper[q_label, law, cond, kind] = _try_certificate(
                        pm["modes"], pm["bands"], Q, law, cond, gain=kind == "gain")
    search = counterexample_search()
    div = tuple((o.family, o.seed, o.law, _try_certificate(
        (c := search.case(o.family, o.seed)).modes, c.bands, c.Q, o.law, "jump")["certified"])
        for o in search.divergent())
    conv = []
    for fam in FAMILIES:
        ok = [o for o in search.outcomes if o.family == fam and not o.grew_coarse
              and o.law == "previous"]
        for o in ok[:N_CONVERGENT_SAMPLE]:
            c = search.case(o.family, o.seed)
            for law in _LAWS:
                conv.append((o.family, o.seed, law,
                             _try_certificate(c.modes, c.bands, c.Q, law, "jump")["certified"]))
    return GapClosing(paper, div, tuple(conv))


# ---------------------------------------------------------------------------------------------
# (c) the residues ε_T and ε_∞ and the two β's
# ---------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class ResidueRun:
    """The terms of the proof of statements (2) and (3) measured on one FDSC run from rest.

    The energies ``∫zᵀz`` and ``∫dᵀd`` are exact per step (sample k carries mode σ_k on
    ``[t_k, t_{k+1})``); the law's term is a left Riemann sum of its samples; all are divided by
    ``E_d = ∫ dᵀd``.

    Parameters
    ----------
    q_label : {"paper", "ours"}
        Whose Q's the law uses (and whose (T1-2) certificate supplies P_i, γ_i).
    disturbance : {"LF", "HF"}
        The paper's disturbance (paper eqs. (56), (57)).
    horizon, dt, window : float
        Run length, step and window of statement (2) (s).
    ratio : float
        ``∫zᵀz / ∫dᵀd`` over the run.
    gammas : (2,) ndarray
        γ_i of (T1-2) for these Q's.
    beta_time, beta_energy : (2,) ndarray
        Share of the time, and of ``∫dᵀd``, spent in each mode.
    jumps : float
        J / E_d: the jumps of ``xᵀ P_σ x`` at the switches, summed.
    jumps_up : float
        The upward jumps only, summed, / E_d.
    boundary : float
        −ΔV / E_d with ΔV = V at the end − V at the start.
    law_term : float
        −∫(s_σ − s_other) / E_d (the law's own term of the proof; ≤ 0 where the active mode
        scores best).
    switches : int
        Number of switches.
    window_excess : float
        Largest excess of a window's ratio over ``max γ_i²`` (statement (2) without ε_T).
    window_eps : float
        Largest ε_T of the proof over the same windows.
    """

    q_label: str
    disturbance: str
    horizon: float
    dt: float
    window: float
    ratio: float
    gammas: np.ndarray
    beta_time: np.ndarray
    beta_energy: np.ndarray
    jumps: float
    jumps_up: float
    boundary: float
    law_term: float
    switches: int
    window_excess: float
    window_eps: float

    @property
    def eps(self) -> float:
        """ε of the proof, ``max(0, J − ΔV − ∫Δs) / E_d`` (ε_T over the run, ε_∞ as T grows)."""
        return max(0.0, self.jumps + self.boundary + self.law_term)

    @property
    def bound_max(self) -> float:
        """max γ_i² (statement (2))."""
        return float(np.max(self.gammas**2))

    @property
    def bound_time(self) -> float:
        """Σ β_i γ_i² with β by time (statement (3) as printed)."""
        return float(self.beta_time @ self.gammas**2)

    @property
    def bound_energy(self) -> float:
        """Σ β_i γ_i² with β by disturbance energy (what the proof integrates)."""
        return float(self.beta_energy @ self.gammas**2)

    def row(self) -> dict:
        """The run as a table row.

        Returns
        -------
        dict
        """
        return {"Q's": self.q_label, "d": self.disturbance, "switches": self.switches,
                "ratio": self.ratio, "max γ²": self.bound_max, "Σβγ² (time)": self.bound_time,
                "Σβγ² (energy)": self.bound_energy, "J/E_d": self.jumps,
                "−ΔV/E_d": self.boundary, "−∫Δs/E_d": self.law_term, "ε (proof)": self.eps,
                "ratio − Σβγ² (energy)": self.ratio - self.bound_energy}


    def table_row(self) -> dict:
        """:meth:`row` as text (:mod:`fdsc.paper.shared.prose`), the Q's by their reader-facing name.

        Returns
        -------
        dict
        """
        q = {"paper": "printed Q", "ours": "our Q"}[self.q_label]
        return {k: (q if k == "Q's" else v if isinstance(v, str) else
                    count(v) if isinstance(v, int) else num(float(v)))
                for k, v in self.row().items()}

    def prose(self) -> dict:
        """The numbers the chapter quotes of this run, as text (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        dict of str
            ``T`` and ``window`` (s), ``ratio``, ``eps``, ``bound_time`` and ``bound_energy``
            (Σβγ² by time and by energy), ``beta_t`` and ``beta_e`` (mode 1's share of the time
            and of the disturbance energy).
        """
        return {"T": num(self.horizon), "window": num(self.window), "ratio": num(self.ratio),
                "eps": num(self.eps), "bound_time": num(self.bound_time),
                "bound_energy": num(self.bound_energy), "beta_t": pct(float(self.beta_time[0]), 1),
                "beta_e": pct(float(self.beta_energy[0]), 2)}


def _residue_run(q_label, kind, horizon, dt, window):
    pm = paper_modes()
    cert = our_q() if q_label == "ours" else certify_q(pm["modes"], pm["bands"], pm["Q"])
    sim = simulate(pm["modes"], paper_disturbance(kind), time_grid(horizon, dt),
                   law_bands=pm["bands"], law_Q=cert.Q)
    P = np.array(cert.P)
    g2 = np.asarray(cert.gammas) ** 2
    s, x = sim.sigma[:-1], sim.x
    # each step's energies exactly (its output jumps at the switches: no quadrature of samples)
    ed, ez = sim.step_input_energy, sim.step_energy
    v_start = np.einsum("ki,kij,kj->k", x[:-1], P[s], x[:-1])
    v_end = np.einsum("ki,kij,kj->k", x[1:], P[s], x[1:])
    jump = np.concatenate([[0.0], v_start[1:] - v_end[:-1]])
    v = np.hstack([sim.xdot, sim.x])[:-1]
    W = [np.kron(b.psi.real, q) for b, q in zip(pm["bands"], cert.Q, strict=True)]
    score = np.array([np.einsum("kr,rc,kc->k", v, w, v) for w in W])
    k = np.arange(s.size)
    law = (score[s, k] - score[1 - s, k]) * dt
    Ed = ed.sum()
    beta_t = np.array([np.mean(s == i) for i in range(2)])
    beta_e = np.array([ed[s == i].sum() for i in range(2)]) / Ed
    # windows of statement (2): consecutive, of `window` seconds
    n = round(window / dt)
    w_exc, w_eps = -np.inf, 0.0
    for k0 in range(0, s.size - n + 1, n):
        sl = slice(k0, k0 + n)
        e = ed[sl].sum()
        w_exc = max(w_exc, ez[sl].sum() / e - g2.max())
        w_eps = max(w_eps, (jump[k0 + 1:k0 + n].sum() - (v_end[k0 + n - 1] - v_start[k0])
                            - law[sl].sum()) / e)
    return ResidueRun(q_label, kind, float(horizon), float(dt), float(window), float(ez.sum() / Ed),
                      np.sqrt(g2), beta_t, beta_e, float(jump.sum() / Ed),
                      float(jump[jump > 0].sum() / Ed), float(-(v_end[-1] - v_start[0]) / Ed),
                      float(-law.sum() / Ed), int(np.count_nonzero(np.diff(sim.sigma))),
                      float(w_exc), float(w_eps))


@cached
def residues(*, horizon: float = 50.0, dt: float = 1e-3, window: float = 10.0) -> tuple:
    """ε_T, ε_∞ and the two β's on FDSC runs from rest (paper's modes and law, both Q's).

    Parameters
    ----------
    horizon, dt, window : float, optional
        Run length, step and the window of statement (2) in s.

    Returns
    -------
    tuple of ResidueRun
        Paper's and our Q's under the LF and the HF disturbance.

    Notes
    -----
    Integrating (T1-2) (paper eq. (34)) along a run, with the jumps of ``xᵀ P_σ x`` written out,
    gives ``ratio ≤ Σ_i β^E_i γ_i² + (J − ΔV − ∫Δs)/E_d`` with β^E_i the share of the
    disturbance energy in mode i; the paper's ε_T and ε_∞ (paper eqs. (35), (36)) are this
    residue with the jumps hidden in ``x*P_i x|``.
    """
    return tuple(_residue_run(q, kind, horizon, dt, window) for q in ("paper", "ours")
                 for kind in ("LF", "HF"))
