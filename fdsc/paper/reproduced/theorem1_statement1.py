"""Chapter 'theorem1', continued: statement (1) of Theorem 1, stability with d = 0.

Runs of the autonomous switched loop (d = 0) from random initial states with the paper's and
our Q's, and the jumps of ``V = xᵀ P^s_σ x`` (paper eq. (37)) at the switching instants.
"""

from dataclasses import dataclass

import numpy as np

from fdsc._validation import as_count, check_type, frozen_array
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.data import STATIONARY_DT, our_q, paper_disturbance, paper_modes
from fdsc.paper.shared.prose import count, num, pct
from fdsc.paper.shared.results import RecordPart, entry
from fdsc.signals import Sinusoids
from fdsc.simulate import simulate, time_grid
from fdsc.switching import Theorem1Result

__all__ = [
    "AutonomousRuns", "LyapunovJumps", "Statement1Check", "autonomous_lyapunov_jumps",
    "autonomous_stability", "lyapunov_jumps", "statement1", "PROOF_STATEMENT1",
]


def _whole(x):
    """A count or a length as the prose prints it: whole numbers without decimals."""
    x = float(x)
    return count(int(x)) if x.is_integer() else num(x)


@dataclass(frozen=True)
class AutonomousRuns:
    """Runs of the autonomous switched loop (d = 0) from random initial states.

    Parameters
    ----------
    final_ratio : (k,) ndarray
        ‖x(T)‖/‖x(0)‖ per run.
    max_growth : (k,) ndarray
        max over t of ‖x(t)‖/‖x(0)‖ per run.
    switches : (k,) int ndarray
        Number of switches per run.
    horizon : float
        Length of each run in s.
    """

    final_ratio: np.ndarray
    max_growth: np.ndarray
    switches: np.ndarray
    horizon: float

    def __post_init__(self):
        for name in ("final_ratio", "max_growth", "switches"):
            object.__setattr__(self, name, frozen_array(getattr(self, name)))
        if not self.final_ratio.shape == self.max_growth.shape == self.switches.shape:
            raise ValueError("final_ratio, max_growth and switches must have one shape (one value "
                             f"per run), but found {self.final_ratio.shape}, "
                             f"{self.max_growth.shape}, {self.switches.shape}")

    @property
    def n_runs(self) -> int:
        """Number of runs."""
        return int(self.final_ratio.size)

    def summary(self) -> dict:
        """``{"max_final_ratio", "max_growth", "median_switches"}`` over the runs.

        Returns
        -------
        dict
        """
        return {"max_final_ratio": float(self.final_ratio.max()),
                "max_growth": float(self.max_growth.max()),
                "median_switches": float(np.median(self.switches))}


_ZERO = Sinusoids([0.0], [1.0])

#: The step of the proof of statement (1) that the book checks, in the paper's words (paper
#: eqs. (37)–(40)).
PROOF_STATEMENT1 = ("V(t) = x*(t) Pˢ_σ(t) x(t) (paper eq. (37)) has V̇ < 0 on every interval between "
                    "two switching instants (paper eq. (40)), 'which implies that closed-loop "
                    "switched system is asymptotically stable if no sliding motion occurs'")


def autonomous_stability(n_initial: int = 40, *, horizon: float = 60.0, dt: float = 1e-3,
                         seed: int = 3, Q=None) -> AutonomousRuns:
    """Statement (1) of Theorem 1: the autonomous switched loop (d = 0) from random initial states.

    Parameters
    ----------
    n_initial : int, optional
        Number of initial states (standard normal).
    horizon, dt : float, optional
        Length and step of each run in s.
    seed : int, optional
        Seed of the initial states.
    Q : list of (2, 2) array_like, optional
        Q's of the switching law (default the paper's).

    Returns
    -------
    AutonomousRuns

    Examples
    --------
    >>> runs = autonomous_stability(2, horizon=5.0)
    >>> runs.n_runs, bool(np.all(runs.final_ratio < 1))
    (2, True)
    """
    n_initial = as_count("n_initial", n_initial)
    rng = np.random.default_rng(seed)
    pm = paper_modes()
    Q = pm["Q"] if Q is None else Q
    t = time_grid(horizon, dt)
    ratios, growth, switches = [], [], []
    for _ in range(n_initial):
        x0 = rng.standard_normal(2)
        sim = simulate(pm["modes"], _ZERO, t, x0=x0, law_bands=pm["bands"], law_Q=Q)
        nrm = np.linalg.norm(sim.x, axis=1) / np.linalg.norm(x0)
        ratios.append(float(nrm[-1]))
        growth.append(float(nrm.max()))
        switches.append(int(sim.switch_times.size))
    return AutonomousRuns(np.array(ratios), np.array(growth), np.array(switches), float(horizon))


@dataclass(frozen=True)
class LyapunovJumps:
    """Jumps of ``V = xᵀ P^s_σ x`` (paper eq. (37)) at the switching instants of some runs.

    Parameters
    ----------
    ratios : (k,) ndarray
        V(t⁺)/V(t⁻) at every switch of every run.
    n_runs : int
        Number of runs.
    horizon : float
        Length of each run in s.
    final_ratio : (n_runs,) ndarray
        ‖x(T)‖/‖x(0)‖ per run (empty for runs from rest).
    """

    ratios: np.ndarray
    n_runs: int
    horizon: float
    final_ratio: np.ndarray

    def __post_init__(self):
        object.__setattr__(self, "ratios", frozen_array(np.asarray(self.ratios, dtype=float)))
        object.__setattr__(self, "final_ratio",
                           frozen_array(np.asarray(self.final_ratio, dtype=float)))

    @property
    def n_switches(self) -> int:
        """Number of switches of all runs."""
        return int(self.ratios.size)

    @property
    def max_ratio(self) -> float:
        """Largest jump ratio (1 when nothing switches)."""
        return float(self.ratios.max()) if self.ratios.size else 1.0

    @property
    def frac_up(self) -> float:
        """Share of the switches at which V increases."""
        return float(np.mean(self.ratios > 1)) if self.ratios.size else 0.0


def _jump_ratios(sim, Ps):
    k = np.flatnonzero(np.diff(sim.sigma)) + 1
    x = sim.x[k]
    before = np.einsum("ki,kij,kj->k", x, Ps[sim.sigma[k - 1]], x)
    after = np.einsum("ki,kij,kj->k", x, Ps[sim.sigma[k]], x)
    return after / before


def lyapunov_jumps(result: Theorem1Result, *, kind: str = "HF", horizon: float = 20.0,
                   dt: float = STATIONARY_DT, Q=None) -> LyapunovJumps:
    """Jumps of V = xᵀ P^s_σ x at the switching instants of an FDSC run from rest.

    Parameters
    ----------
    result : Theorem1Result
        Supplies P^s_1, P^s_2 (and, unless ``Q`` is given, the law's Q's).
    kind : {"LF", "HF"}, optional
        The paper's disturbance (paper eqs. (56), (57)).
    horizon, dt : float, optional
        Length and step of the run in s.
    Q : list of (2, 2) array_like, optional
        Q's of the switching law.

    Returns
    -------
    LyapunovJumps
        One run (``final_ratio`` empty: the run starts from rest).
    """
    check_type("result", result, Theorem1Result)
    pm = paper_modes()
    d = paper_disturbance(kind)
    t = time_grid(horizon, dt)
    sim = simulate(pm["modes"], d, t, law_bands=pm["bands"], law_Q=result.Q if Q is None else Q)
    return LyapunovJumps(_jump_ratios(sim, np.array(result.Ps)), 1, float(horizon), np.empty(0))


def autonomous_lyapunov_jumps(result: Theorem1Result, n_initial: int = 40, *,
                              horizon: float = 60.0, dt: float = 1e-3, seed: int = 3,
                              Q=None) -> LyapunovJumps:
    """Jumps of ``V = xᵀ P^s_σ x`` at the switches of the autonomous switched loop (d = 0).

    Theorem 1 statement (1) is about d = 0; its proof differentiates V (paper eq. (37)) between
    switches and never compares V across a switch. The runs start from the same random initial
    states as :func:`autonomous_stability` (same ``seed``).

    Parameters
    ----------
    result : Theorem1Result
        Supplies P^s_1, P^s_2 and (unless ``Q`` is given) the law's Q's.
    n_initial : int, optional
        Number of initial states (standard normal).
    horizon, dt : float, optional
        Length and step of each run in s.
    seed : int, optional
        Seed of the initial states.
    Q : list of (n, n) array_like, optional
        Q's of the switching law.

    Returns
    -------
    LyapunovJumps

    Examples
    --------
    >>> from fdsc.paper.shared.data import our_q
    >>> j = autonomous_lyapunov_jumps(our_q(), 3, horizon=5.0)
    >>> j.n_runs, bool(j.max_ratio > 1)
    (3, True)
    """
    check_type("result", result, Theorem1Result)
    n_initial = as_count("n_initial", n_initial)
    pm = paper_modes()
    Q = result.Q if Q is None else Q
    Ps = np.array(result.Ps)
    rng = np.random.default_rng(seed)
    t = time_grid(horizon, dt)
    ratios, final = [], []
    for _ in range(n_initial):
        x0 = rng.standard_normal(Ps.shape[1])
        sim = simulate(pm["modes"], _ZERO, t, x0=x0, law_bands=pm["bands"], law_Q=Q)
        ratios.append(_jump_ratios(sim, Ps))
        final.append(float(np.linalg.norm(sim.x[-1]) / np.linalg.norm(x0)))
    return LyapunovJumps(np.concatenate(ratios), n_initial, float(horizon), np.array(final))


@dataclass(frozen=True)
class Statement1Check:
    """Statement (1) of Theorem 1 by simulation, with the paper's and our Q's, and the jumps of V.

    Parameters
    ----------
    paper, ours : AutonomousRuns
        The autonomous runs with the paper's and with our Q's (same initial states).
    jumps : LyapunovJumps
        The jumps of V on the runs with our Q's (whose solution of Theorem 1's LMIs supplies
        the Pˢ_i).

    Raises
    ------
    ValueError
        If the jumps were not measured on the runs of ``ours``.
    """

    paper: AutonomousRuns
    ours: AutonomousRuns
    jumps: LyapunovJumps

    def __post_init__(self):
        if self.jumps.final_ratio.shape != self.ours.final_ratio.shape or not np.allclose(
                self.jumps.final_ratio, self.ours.final_ratio, rtol=1e-12, atol=0.0):
            raise ValueError("jumps must be measured on the runs of ours (same initial states, "
                             "same final states)")

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``stab_n``, ``stab_T``; for ``paper`` and ``ours``
            ``stab_<q>_final`` (largest ‖x(T)‖/‖x(0)‖), ``stab_<q>_growth``,
            ``stab_<q>_switches`` (median); ``jump_max``, ``jump_n``, ``jump_runs``, ``jump_up``.
        """
        out = {"stab_n": count(self.paper.n_runs), "stab_T": _whole(self.paper.horizon)}
        for key, runs in (("paper", self.paper), ("ours", self.ours)):
            sm = runs.summary()
            out.update({f"stab_{key}_final": num(sm["max_final_ratio"], 2),
                        f"stab_{key}_growth": num(sm["max_growth"], 4),
                        f"stab_{key}_switches": _whole(sm["median_switches"])})
        j = self.jumps
        return {**out, "jump_max": num(j.max_ratio), "jump_n": count(j.n_switches),
                "jump_runs": count(j.n_runs), "jump_up": pct(j.frac_up)}

    def to_record(self) -> RecordPart:
        """Record entries ``thm1_statement1`` (new: statement (1) on the paper's example) and
        ``thm1_lyapunov_jumps`` (a proof step that differs: the proof of statement (1) does not
        cover the jumps of V at the switches).

        Returns
        -------
        RecordPart
        """
        j = self.jumps
        return RecordPart((
            entry("thm1_statement1", "Theorem 1, statement (1) on the paper's example (d = 0)", None,
                  {"paper_Q": self.paper.summary(), "ours": self.ours.summary(),
                   "n_runs": self.paper.n_runs, "horizon": self.paper.horizon},
                  "new",
                  "the aircraft's autonomous switched loop from random initial states: every run "
                  "decays (largest final ratio ‖x(T)‖/‖x(0)‖ < 1) with the paper's Q's and with "
                  "ours; a numerical check on this example, not a proof. Statement (1) itself is "
                  "false: see its counterexample, computed in the chapter “Theorem 1”."),
            entry("thm1_lyapunov_jumps", "Theorem 1, proof of statement (1), paper eqs. (37)–(40)",
                  PROOF_STATEMENT1,
                  {"max_ratio": j.max_ratio, "frac_up": j.frac_up, "n_switches": j.n_switches,
                   "n_runs": j.n_runs},
                  "differs",
                  "The proof does not cover the switches: V jumps wherever σ switches, since Pˢ_σ "
                  "changes from Pˢ_i to Pˢ_j there, and the proof never compares V across a switch. "
                  "A multiple Lyapunov function needs V not to increase at the switches (a jump "
                  "condition), or a dwell time that absorbs the increase. On the aircraft's "
                  f"autonomous runs with our Q's (d = 0) V jumps up at {pct(j.frac_up)} of the "
                  f"{count(j.n_switches)} switches, by up to a factor {num(j.max_ratio)}: computed in "
                  "the chapter “Theorem 1”. The jump condition that closes the gap, and runs whose "
                  "V decreases between switches but diverges through its jumps, are in that "
                  "chapter."),
        ))


@cached
def statement1(n_initial: int = 40, *, horizon: float = 60.0, dt: float = 1e-3,
               seed: int = 3) -> Statement1Check:
    """Statement (1) of Theorem 1 with the paper's and our Q's, and the jumps of V on our runs.

    Parameters
    ----------
    n_initial : int, optional
        Number of initial states.
    horizon, dt : float, optional
        Length and step of each run in s.
    seed : int, optional
        Seed of the initial states.

    Returns
    -------
    Statement1Check

    Notes
    -----
    Statement (1) claims stability of the autonomous loop; its proof uses the multiple
    Lyapunov function of paper eq. (37).
    """
    ours = our_q()
    return Statement1Check(
        autonomous_stability(n_initial, horizon=horizon, dt=dt, seed=seed),
        autonomous_stability(n_initial, horizon=horizon, dt=dt, seed=seed, Q=ours.Q),
        autonomous_lyapunov_jumps(ours, n_initial, horizon=horizon, dt=dt, seed=seed))
