"""One state-feedback gain for several frequency ranges: multi-band synthesis and its Pareto front.

A band-limited design (:func:`fdsc.synthesize`) makes one range quiet and says nothing about the
others; a switching law pays only against what one fixed gain cannot do on all ranges at once.
The strongest fixed baselines are therefore the gains that trade the ranges off optimally:
minimize the certified gain on one range subject to bounds on the others,

    minimize γ_0  subject to  γ_k ≤ β_k  (k ≥ 1),

with the band LMIs of :func:`fdsc.synthesize` sharing one slack ``X`` and one ``Y`` (so one gain
``K = Y X⁻¹``), each with its own ``P``, ``Q`` and ``γ_k``, and the stability LMI. Sharing the
slack makes the design only sufficient: each ``γ_k`` is a certified bound of its band's peak
(checked after the solve against a sweep), but the front may lie above the best one achievable
by a single gain. Sweeping β traces the front (:func:`pareto_front`); at a loose bound the
design is the objective band's own, at the tightest feasible bound it approaches the
constrained band's own.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import cvxpy as cp
import numpy as np
from scipy.optimize import minimize

from ._validation import as_count, as_matrix, as_nonnegative, as_positive, as_vector, check_type
from .bands import Band
from .exceptions import SolverError, VerificationError
from .frequency import band_peak, sigma_max
from .lmi import DEFAULT_MARGIN, solve_checked
from .plant import Plant
from .synthesis import (
    DEFAULT_EPSILON,
    DEFAULT_SIGMA,
    SWEEP_RTOL,
    _band_lmi,
    _check,
    _herm_pair,
    _neg_def,
    _objective_grid,
    _pos_def,
    _stability_lmis,
    check_stabilizable,
    synthesize,
)

__all__ = ["MultibandResult", "FrontPoint", "ParetoFront", "synthesize_multiband", "pareto_front",
           "dominating_gain"]


@dataclass(frozen=True)
class MultibandResult:
    """A state-feedback gain designed for several bands at once (see :func:`synthesize_multiband`).

    Parameters
    ----------
    K : (m_u, n) ndarray
        The gain, ``u = K x``.
    bands : tuple of Band
        The objective band first, then the constrained bands.
    bounds : (k,) ndarray
        The bound β on each constrained band (in the order of ``bands[1:]``).
    gamma_lmi : (k + 1,) ndarray
        The certified gain on each band (in the order of ``bands``).
    gamma_sweep : (k + 1,) ndarray
        The band peak of σ_max of the closed loop on each band, after the solve (each ≤ its
        ``gamma_lmi`` to the solver's accuracy).
    poles : (n,) ndarray
        Closed-loop poles.
    status : str
        cvxpy status.
    solve_time : float
        Wall-clock seconds of the solve.
    epsilon, sigma : float
        ε of the stability LMI and σ of the HF slack (as in :func:`fdsc.synthesize`).
    """

    K: np.ndarray
    bands: tuple
    bounds: np.ndarray
    gamma_lmi: np.ndarray
    gamma_sweep: np.ndarray
    poles: np.ndarray
    status: str
    solve_time: float
    epsilon: float
    sigma: float


def _constraints(constraints):
    if isinstance(constraints, tuple) and len(constraints) == 2 and isinstance(constraints[0], Band):
        constraints = [constraints]
    out = []
    for k, item in enumerate(constraints):
        if not (isinstance(item, tuple | list) and len(item) == 2):
            raise TypeError(f"constraints[{k}] must be a pair (Band, bound), but found {item!r}")
        band, beta = item
        check_type(f"constraints[{k}][0]", band, Band)
        out.append((band, as_positive(f"constraints[{k}][1]", beta)))
    if not out:
        raise ValueError("constraints must hold at least one (Band, bound) pair")
    return out


def synthesize_multiband(plant: Plant, objective: Band, constraints, *,
                         epsilon: float = DEFAULT_EPSILON, sigma: float = DEFAULT_SIGMA,
                         margin: float = DEFAULT_MARGIN) -> MultibandResult:
    """One state-feedback gain minimizing the certified gain on one band subject to bounds on
    others.

    Parameters
    ----------
    plant : Plant
        The open-loop plant; the closed loop is ``(A + B2 K, B1, C + D2 K, D1)``.
    objective : Band
        The band whose certified gain γ_0 is minimized (LF, MF or HF).
    constraints : (Band, float) or sequence of (Band, float)
        Bands with a bound β_k > 0 on their certified gain γ_k (LF, MF or HF each).
    epsilon, sigma, margin : float, optional
        As in :func:`fdsc.synthesize` (σ applies to every HF band).

    Returns
    -------
    MultibandResult

    Raises
    ------
    TypeError
        If ``objective`` or a constrained band is not a :class:`~fdsc.Band`, or a constraint is
        not a pair.
    ValueError
        If a band is the entire range (use :func:`fdsc.synthesize_hinf`), a bound is not a
        positive number, or ``constraints`` is empty.
    InfeasibleError
        If the plant cannot be stabilized (PBH test, before solving) or no gain of this form meets
        the bounds (the solver reports the LMIs infeasible).
    SolverError
        If the solve fails (the message names Clarabel's status).
    VerificationError
        If the returned gain fails its a-posteriori checks (Hurwitz, each band's sweep ≤ its
        certified gain).

    Notes
    -----
    Every band LMI is that of :func:`fdsc.synthesize` with the same ``X`` and ``Y``; with a
    single band and no bound this is :func:`fdsc.synthesize` itself. The bound enters as
    ``γ_k² ≤ β_k²`` on the LMI's ``γ_k²``.

    Examples
    --------
    >>> from fdsc import Band, random_plant, synthesize
    >>> plant = random_plant(np.random.default_rng(3))
    >>> res = synthesize_multiband(plant, Band.hf(10.0), (Band.lf(1.0), 10.0))
    >>> bool(res.gamma_lmi[1] <= 10.0 * (1 + 1e-6)), bool(np.all(res.poles.real < 0))
    (True, True)
    """
    check_type("objective", objective, Band)
    plant = _check(plant, objective)
    cons_bands = _constraints(constraints)
    bands = [objective] + [b for b, _ in cons_bands]
    for k, band in enumerate(bands):
        if band.kind == "EF":
            where = "objective" if k == 0 else f"constraints[{k - 1}][0]"
            raise ValueError(f"{where} is the entire range: use fdsc.synthesize_hinf for it; the "
                             "multi-band design takes LF, MF and HF bands")
    epsilon = as_positive("epsilon", epsilon)
    sigma = as_nonnegative("sigma", sigma)
    margin = as_positive("margin", margin)
    check_stabilizable(plant)
    n, mu = plant.n_states, plant.n_controls
    X = cp.Variable((n, n), name="X")
    Y = cp.Variable((mu, n), name="Y")
    gs, cons = [], []
    for k, band in enumerate(bands):
        g = cp.Variable(name=f"gamma_sq_{k}", nonneg=True)
        P = _herm_pair(n, f"P{k}", band.is_complex)
        Q = _herm_pair(n, f"Q{k}", band.is_complex)
        re, im = _band_lmi(plant, band, X, Y, P, Q, g, sigma)
        cons += [_neg_def(re, im, margin), _pos_def(*Q, margin)]
        if band.is_complex:
            cons += [P[1] + P[1].T == 0, Q[1] + Q[1].T == 0]
        gs.append(g)
    betas = np.array([beta for _, beta in cons_bands])
    cons += [g <= beta**2 for g, beta in zip(gs[1:], betas, strict=True)]
    Ps = cp.Variable((n, n), symmetric=True, name="P_s")
    cons += _stability_lmis(plant, X, Y, Ps, epsilon, margin)
    prob = cp.Problem(cp.Minimize(gs[0]), cons)
    what = (f"multi-band synthesis ({objective.label} subject to "
            + ", ".join(f"{b.label} ≤ {beta:g}" for b, beta in cons_bands) + ")")
    t0 = time.perf_counter()
    status = solve_checked(prob, what)
    elapsed = time.perf_counter() - t0
    K = np.linalg.solve(X.value.T, Y.value.T).T
    cl = plant.closed_loop(K)
    if not cl.is_hurwitz():
        raise VerificationError(f"{what}: the returned gain does not stabilize the plant "
                                f"(poles {np.round(cl.poles(), 4)})", status)
    gamma_lmi = np.sqrt(np.array([float(g.value) for g in gs]))
    gamma_sweep = np.array([band_peak(cl, b).gamma for b in bands])
    for b, gl, gw in zip(bands, gamma_lmi, gamma_sweep, strict=True):
        if gw > gl * (1 + SWEEP_RTOL):
            raise VerificationError(f"{what}: the {b.label} sweep gain {gw:.6g} exceeds its LMI "
                                    f"bound {gl:.6g}", status)
    return MultibandResult(K, tuple(bands), betas, gamma_lmi, gamma_sweep, cl.poles(), status,
                           elapsed, epsilon, sigma if any(b.kind == "HF" for b in bands) else math.nan)


#: Relative margin by which the search aims below each bound: its grids see slightly less than the
#: refined sweeps that decide whether a gain meets the bound.
BOUND_MARGIN = 1e-3


@dataclass(frozen=True)
class FrontPoint:
    """One gain of a Pareto front (see :func:`pareto_front`).

    Parameters
    ----------
    beta : float
        The bound on the constrained band's peak.
    K : (m_u, n) ndarray
        The gain.
    peak : (2,) ndarray
        Band peaks of σ_max of its closed loop: ``[objective, constrained]`` (refined sweeps).
    gamma_lmi : (2,) ndarray
        The same gains certified by Lemma 1 (:func:`fdsc.gkyp_gamma`) on the closed loop; NaN
        where the solver failed on that band (then only the swept peak stands: see
        :attr:`certified`).
    """

    beta: float
    K: np.ndarray
    peak: np.ndarray
    gamma_lmi: np.ndarray

    @property
    def certified(self) -> bool:
        """Lemma 1 certified a bound of both band gains. Each bound is at least the swept peak;
        it equals it when the solve is accurate (Lemma 1 is lossless), and may lie above it for
        the badly conditioned closed loops of high gains."""
        return bool(np.all(np.isfinite(self.gamma_lmi)))


@dataclass(frozen=True)
class ParetoFront:
    """Single gains trading two bands off (see :func:`pareto_front`).

    Parameters
    ----------
    objective, constrained : Band
        The band whose peak is minimized and the band whose peak is bounded.
    betas : (m,) ndarray
        The bounds, increasing.
    points : tuple of FrontPoint or None
        One per bound, in increasing order of the bound; None where no gain was found that
        meets it.
    ends : tuple of SynthesisResult
        The single-band designs of ``objective`` and ``constrained`` (:func:`fdsc.synthesize`),
        the front's starting points.
    n_evaluations : int
        Evaluations of the search's objective over all bounds.
    """

    objective: Band
    constrained: Band
    betas: np.ndarray
    points: tuple
    ends: tuple
    n_evaluations: int

    @property
    def feasible(self) -> np.ndarray:
        """(m,) bool: a gain meeting the bound was found."""
        return np.array([p is not None for p in self.points])

    def peaks(self) -> np.ndarray:
        """(m, 2) band peaks ``[objective, constrained]`` per bound (NaN where none was found)."""
        return np.array([[np.nan, np.nan] if p is None else p.peak for p in self.points])

    def gains(self) -> list:
        """The gains of the points found, in increasing order of the bound."""
        return [p.K for p in self.points if p is not None]


def _certified(cl, band):
    """Lemma 1's γ of a closed loop on a band, NaN if its solve fails (the point is then not
    certified; its swept peak stands)."""
    from .lmi import gkyp_gamma

    try:
        return gkyp_gamma(cl, band).gamma
    except SolverError:
        return math.nan


def _peak_on_grid(plant, K, w_obj, w_con):
    cl = plant.closed_loop(K)
    worst = float(np.max(np.linalg.eigvals(cl.A).real))
    if worst >= 0:
        return None
    return float(sigma_max(cl, w_obj).max()), float(sigma_max(cl, w_con).max())


def pareto_front(plant: Plant, objective: Band, constrained: Band, betas, *, n_grid: int = 300,
                 maxiter: int = 3000, penalty: float = 1e3, epsilon: float = DEFAULT_EPSILON,
                 sigma: float = DEFAULT_SIGMA) -> ParetoFront:
    """The front of single state-feedback gains between two bands: for each bound β, a gain
    minimizing the band peak on ``objective`` with its peak on ``constrained`` at most β.

    The search is direct (Nelder–Mead over K on fixed frequency grids, the bound as a penalty),
    started from the two single-band LMI designs (:func:`fdsc.synthesize`) and from the best gain
    known to meet the bound; every gain met on the way is kept as a candidate, and each bound's
    point is the candidate with the least objective peak among those whose refined sweep meets
    it (so the front's objective peak never rises as β grows, and it exists from the smallest
    bound a single-band design meets). Each point is certified by Lemma 1 on its closed loop
    (:func:`fdsc.gkyp_gamma`). It is an achievable front, not a proven optimum: a gain
    below it may exist. The LMI design of :func:`synthesize_multiband` certifies a front as
    well, but sharing one slack between bands makes it far more conservative.

    Parameters
    ----------
    plant : Plant
    objective, constrained : Band
        LF, MF or HF each.
    betas : array_like
        Bounds β > 0 on the constrained band's peak (sorted increasing here).
    n_grid : int, optional
        Frequencies per band of the search's grids (the points are swept exactly afterwards).
    maxiter : int, optional
        Nelder–Mead iterations per start.
    penalty : float, optional
        Weight of the relative excess of the bound in the search's objective.
    epsilon, sigma : float, optional
        Of the single-band designs (:func:`fdsc.synthesize`).

    Returns
    -------
    ParetoFront
        A bound below what the search reaches gives None (not an error).

    Raises
    ------
    ValueError
        If ``betas`` is empty or holds a bound that is not positive and finite, or a band is
        the entire range.
    InfeasibleError
        If the plant cannot be stabilized (PBH test).

    Examples
    --------
    >>> from fdsc import Band, random_plant
    >>> front = pareto_front(random_plant(np.random.default_rng(3)), Band.hf(10.0), Band.lf(1.0),
    ...                      [1.2, 2.0, 5.0], maxiter=100)
    >>> p = front.peaks()
    >>> bool(np.all(p[:, 1] <= front.betas * (1 + 1e-6))), bool(np.all(np.diff(p[:, 0]) <= 1e-9))
    (True, True)
    """

    plant = _check(plant, objective)
    check_type("constrained", constrained, Band)
    for name, band in (("objective", objective), ("constrained", constrained)):
        if band.kind == "EF":
            raise ValueError(f"{name} is the entire range; the front takes LF, MF and HF bands")
    check_stabilizable(plant)
    betas = np.sort(as_vector("betas", betas))
    if betas.size == 0 or not np.all(np.isfinite(betas)) or np.any(betas <= 0):
        raise ValueError(f"betas must be positive finite bounds, at least one, but found {betas.tolist()}")
    n_grid, maxiter = as_count("n_grid", n_grid, 2), as_count("maxiter", maxiter)
    penalty = as_positive("penalty", penalty)
    ends = (synthesize(plant, objective, epsilon=epsilon, sigma=sigma),
            synthesize(plant, constrained, epsilon=epsilon, sigma=sigma))
    w_obj, w_con = _objective_grid(objective, n_grid), _objective_grid(constrained, n_grid)
    shape = ends[0].K.shape
    scale = max(1.0, float(np.linalg.norm(ends[0].K)), float(np.linalg.norm(ends[1].K)))
    evals = 0

    def exact(K):
        cl = plant.closed_loop(K)
        if not cl.is_hurwitz():
            return None
        return np.array([band_peak(cl, objective).gamma, band_peak(cl, constrained).gamma])

    # the candidates every bound may fall back on: the two designs, then each point found
    known = [(e.K, exact(e.K)) for e in ends]
    points = []
    for beta in betas:
        target = beta * (1.0 - BOUND_MARGIN)      # the grids see slightly less than the sweeps

        def f(u, target=target):
            nonlocal evals
            evals += 1
            pk = _peak_on_grid(plant, (scale * u).reshape(shape), w_obj, w_con)
            if pk is None:
                return 1e12
            return pk[0] * (1.0 + penalty * max(0.0, pk[1] / target - 1.0))

        feasible = [(K, pk) for K, pk in known if pk is not None and pk[1] <= beta]
        starts = [e.K for e in ends] + ([min(feasible, key=lambda c: c[1][0])[0]] if feasible else [])
        for K0 in starts:
            res = minimize(f, K0.ravel() / scale, method="Nelder-Mead",
                           options={"xatol": 1e-8, "fatol": 1e-12, "maxiter": maxiter})
            K = (scale * res.x).reshape(shape)
            pk = exact(K)
            if pk is not None and pk[1] <= beta:
                feasible.append((K, pk))
                known.append((K, pk))
        if not feasible:
            points.append(None)          # neither the search nor a known gain meets the bound
            continue
        K, peak = min(feasible, key=lambda c: c[1][0])
        lmi = np.array([_certified(plant.closed_loop(K), b) for b in (objective, constrained)])
        points.append(FrontPoint(float(beta), K, peak, lmi))
    return ParetoFront(objective, constrained, betas, tuple(points), ends, evals)


def dominating_gain(plant: Plant, objective: Band, constrained: Band, peak, starts, *, n_grid: int = 300,
                    maxiter: int = 2000, penalty: float = 1e3, tol: float = 1e-3):
    """Search for a gain that beats a given pair of band peaks in both bands: the check of a
    front point (or of a band design) against a direct search.

    Minimizes the objective band's peak with the constrained band's at most ``peak[1]`` (as
    :func:`pareto_front` does), by Nelder–Mead from each start, and keeps the best gain whose
    refined sweeps meet ``peak[1]`` and beat ``peak[0]`` by more than ``tol`` (relative).

    Parameters
    ----------
    plant : Plant
    objective, constrained : Band
    peak : (2,) array_like
        ``[objective peak, constrained peak]`` to beat.
    starts : sequence of (m_u, n) array_like
        Where the search starts (e.g. every point of the front, other designs).
    n_grid, maxiter, penalty : optional
        As :func:`pareto_front`.
    tol : float, optional
        The least relative improvement of the objective peak that counts.

    Returns
    -------
    (K, peaks) or None
        The dominating gain and its peaks ``[objective, constrained]``, or None if the search
        found none (which proves nothing: a local search).

    Raises
    ------
    DimensionError
        If a start is not of shape ``(m_u, n)`` (the message names ``starts[k]``).
    ValueError
        If ``starts`` is empty or an entry of ``starts[k]`` is not finite and real, or ``peak``
        is not two positive finite peaks.

    Examples
    --------
    >>> from fdsc import random_plant, synthesize
    >>> plant = random_plant(np.random.default_rng(3))
    >>> lf, hf = Band.lf(1.0), Band.hf(10.0)
    >>> K = synthesize(plant, hf).K
    >>> cl = plant.closed_loop(2 * K)                     # a worse gain: something beats it
    >>> found = dominating_gain(plant, hf, lf, [band_peak(cl, hf).gamma, band_peak(cl, lf).gamma],
    ...                         [K], maxiter=300)
    >>> found is not None
    True
    """
    plant = _check(plant, objective)
    check_type("constrained", constrained, Band)
    peak = as_vector("peak", peak)
    if peak.size != 2 or not np.all(np.isfinite(peak)) or np.any(peak <= 0):
        raise ValueError(f"peak must be two positive finite peaks [objective, constrained], but found "
                         f"{peak.tolist()}")
    if not hasattr(starts, "__len__") or len(starts) == 0:
        raise ValueError("starts must hold at least one gain")
    shape = (plant.n_controls, plant.n_states)
    starts = [as_matrix(f"starts[{k}]", s, shape) for k, s in enumerate(starts)]
    n_grid, maxiter = as_count("n_grid", n_grid, 2), as_count("maxiter", maxiter)
    penalty, tol = as_positive("penalty", penalty), as_nonnegative("tol", tol)
    w_obj, w_con = _objective_grid(objective, n_grid), _objective_grid(constrained, n_grid)
    scale = max(1.0, max(float(np.linalg.norm(s)) for s in starts))
    target = peak[1] * (1.0 - BOUND_MARGIN)

    def f(u):
        pk = _peak_on_grid(plant, (scale * u).reshape(shape), w_obj, w_con)
        if pk is None:
            return 1e12
        return pk[0] * (1.0 + penalty * max(0.0, pk[1] / target - 1.0))

    best = None
    for K0 in starts:
        res = minimize(f, K0.ravel() / scale, method="Nelder-Mead",
                       options={"xatol": 1e-8, "fatol": 1e-12, "maxiter": maxiter})
        K = (scale * res.x).reshape(shape)
        cl = plant.closed_loop(K)
        if not cl.is_hurwitz():
            continue
        pk = np.array([band_peak(cl, objective).gamma, band_peak(cl, constrained).gamma])
        if pk[1] <= peak[1] and pk[0] < peak[0] * (1.0 - tol) and (best is None or pk[0] < best[1][0]):
            best = (K, pk)
    return best
