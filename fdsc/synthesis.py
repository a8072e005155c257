"""State-feedback synthesis of the passive controllers (band-limited and H∞).

The paper prints four gains but not how they were computed. The LMIs below are derived
for this companion (the book's passive-controller chapter shows the steps):

1. ``G`` and ``Gᵀ`` have the same singular values, so Lemma 1 is applied to the dual
   realization ``(A_Kᵀ, C_Kᵀ, B1ᵀ, D1ᵀ)``;
2. Finsler's lemma with the slack ``[αI; βI; 0] Xᵀ`` makes the LMI affine in
   ``Z_A = A X + B2 Y`` and ``Z_C = C X + D2 Y``, ``K = Y X⁻¹``;
3. by the projection lemma the restriction of the slack is lossless when the fictitious pole
   ``λ = −β/α`` is outside the band: exact for LF and MF (α = 0, β = 1), only sufficient for
   HF (α = 1, β = σ ≥ 0, a user choice).

A band LMI alone does not make ``A_K`` Hurwitz; the Lyapunov LMI (dual form, slack
``[εI; I] Xᵀ``) shares X and Y and enforces it. The supply rate of the dual realization comes
from :func:`fdsc.kyp.supply_parts`, the builder shared with Lemma 1 and Theorem 1.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import cvxpy as cp
import numpy as np
from scipy.optimize import minimize

from ._plant_scaling import normalize_plant
from ._validation import as_count, as_matrix, as_nonnegative, as_positive, check_type
from .bands import Band
from .exceptions import InfeasibleError, IterationLimitError, VerificationError
from .frequency import band_peak, sigma_max
from .kyp import supply_parts
from .lmi import DEFAULT_MARGIN, MARGIN_RETRIES, _sym, real_embedding_parts, solve_checked
from .plant import Plant, as_plant

__all__ = ["SynthesisResult", "DirectResult", "synthesize", "synthesize_hinf", "optimize_gain",
           "check_stabilizable", "DEFAULT_EPSILON", "DEFAULT_SIGMA", "SWEEP_RTOL", "PBH_RTOL"]

#: ε of the stability LMI (slack [εI; I]Xᵀ); the chapter shows its influence.
DEFAULT_EPSILON = 1e-2
#: σ ≥ 0 of the HF slack [I; σI; 0]Xᵀ (fictitious pole at −σ); the chapter scans it.
DEFAULT_SIGMA = 0.0
#: Relative tolerance allowed between the sweep γ and the LMI γ (solver accuracy).
SWEEP_RTOL = 1e-5
#: PBH rank test: [A − λI, B2] counts as rank deficient when its smallest singular value is below
#: PBH_RTOL · ‖[A, B2]‖₂.
PBH_RTOL = 1e-9


def check_stabilizable(plant: Plant, *, rtol: float = PBH_RTOL) -> None:
    """PBH test: raise if ``(A, B2)`` has an uncontrollable eigenvalue with real part ≥ 0.

    No state feedback can move such an eigenvalue. The test runs before every synthesis that
    asks for a stabilizing gain, so that a specification that is infeasible for this reason is
    reported the same way on every machine (the LMIs are homogeneous; without the test the
    solver's verdict would hang on its strictness margin).

    Parameters
    ----------
    plant : Plant
        The open-loop plant (A, B1, B2, C, D1, D2).
    rtol : float, optional
        Relative rank tolerance (see :data:`PBH_RTOL`).

    Returns
    -------
    None
        If every eigenvalue with real part ≥ 0 is controllable from B2.

    Raises
    ------
    TypeError
        If ``plant`` is not a :class:`~fdsc.Plant`.
    ValueError
        If ``rtol`` is not a positive finite number.
    InfeasibleError
        Naming the uncontrollable unstable eigenvalue; ``status`` is ``"not solved (PBH test)"``.

    Notes
    -----
    Eigenvalue λ is uncontrollable when ``[A − λI, B2]`` loses rank (Popov–Belevitch–Hautus).

    Examples
    --------
    >>> from fdsc import Plant
    >>> p = Plant([[1.0, 0.0], [0.0, -1.0]], [[1.0], [1.0]], [[0.0], [1.0]], [[1.0, 1.0]],
    ...           [[0.0]], [[0.0]])
    >>> check_stabilizable(p)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    fdsc.exceptions.InfeasibleError: plant: the eigenvalue 1 of A is not controllable from B2 ...
    """
    plant = as_plant(plant)
    rtol = as_positive("rtol", rtol)
    A, B2 = plant.A, plant.B2
    n = A.shape[0]
    scale = max(float(np.linalg.norm(np.hstack([A, B2]), 2)), np.finfo(float).tiny)
    for lam in np.linalg.eigvals(A):
        if lam.real < 0:
            continue
        smin = float(np.linalg.svd(np.hstack([A - lam * np.eye(n), B2]), compute_uv=False)[-1]) \
            if n else 1.0
        if smin <= rtol * scale:
            name = f"{lam.real:.6g}" if lam.imag == 0 else f"{lam:.6g}"
            raise InfeasibleError(
                f"plant: the eigenvalue {name} of A is not controllable from B2 (PBH test, smallest "
                f"singular value of [A - lambda I, B2] = {smin:.3g}), so no state feedback "
                f"stabilizes the loop", "not solved (PBH test)")


@dataclass(frozen=True)
class SynthesisResult:
    """A synthesized state-feedback gain and its certificates.

    Parameters
    ----------
    K : (m_u, n) ndarray
        The gain, ``u = K x``.
    band : Band
        The band designed for (the entire range for :func:`synthesize_hinf`).
    gamma_lmi : float
        γ certified by the synthesis LMI.
    gamma_sweep : float
        A-posteriori band peak of σ_max for the closed loop with K (always ≤ gamma_lmi).
    poles : (n,) ndarray
        Closed-loop poles.
    status : str
        cvxpy status.
    solve_time : float
        Wall-clock seconds of the solve.
    iterations : int
        Interior-point iterations.
    epsilon : float
        ε of the stability LMI (NaN for :func:`synthesize_hinf`, which needs none).
    sigma : float
        σ of the HF slack (NaN except for HF).

    Notes
    -----
    ``gamma_lmi`` bounds the in-band gain through Lemma 1 (paper eq. (7)) applied to the dual
    realization; ``gamma_sweep`` is its a-posteriori value.
    """

    K: np.ndarray
    band: Band
    gamma_lmi: float
    gamma_sweep: float
    poles: np.ndarray
    status: str
    solve_time: float
    iterations: int
    epsilon: float
    sigma: float


def _check(plant, band):
    check_type("band", band, Band)
    return as_plant(plant)


def _herm_pair(n, name, cplx):
    re = cp.Variable((n, n), symmetric=True, name=f"{name}_re")
    im = cp.Variable((n, n), name=f"{name}_im") if cplx else None
    return re, im


def _neg_def(re, im, margin):
    E = real_embedding_parts(re, im) if im is not None else re
    return _sym(E) << -margin * np.eye(E.shape[0])


def _pos_def(re, im, margin):
    E = real_embedding_parts(re, im) if im is not None else re
    return _sym(E) >> margin * np.eye(E.shape[0])


def _finish(plant, band, X, Y, g, prob, what, t0, epsilon, sigma, stability=True, scaling=None):
    status = solve_checked(prob, what)
    elapsed = time.perf_counter() - t0
    Xv = X.value
    K = np.linalg.solve(Xv.T, Y.value.T).T  # K = Y X⁻¹
    gamma_lmi = float(np.sqrt(g.value))
    if scaling is not None:      # solved in normalized units (synthesize_hinf): back to the plant's
        K, gamma_lmi = scaling.gain(K), scaling.gamma(gamma_lmi)
    cl = plant.closed_loop(K)
    if not cl.is_hurwitz():
        if stability:
            raise VerificationError(f"{what}: the returned gain does not stabilize the plant "
                                    f"(poles {np.round(cl.poles(), 4)})", status)
        gamma_sweep = np.inf
    else:
        gamma_sweep = band_peak(cl, band).gamma
        if gamma_sweep > gamma_lmi * (1 + SWEEP_RTOL):
            raise VerificationError(f"{what}: sweep gain {gamma_sweep:.6g} exceeds the LMI bound "
                                    f"{gamma_lmi:.6g}", status)
    return SynthesisResult(K, band, gamma_lmi, gamma_sweep, cl.poles(), status, elapsed,
                           int(prob.solver_stats.num_iters or 0), epsilon, sigma)


def _band_lmi(plant, band, X, Y, P, Q, g, sigma):
    """``(re, im)`` of the band LMI of :func:`synthesize` (the dual gKYP inequality after Finsler).

    ``P`` and ``Q`` are pairs (re, im) with ``im`` None for a real band. The top-left 2n×2n block is
    ``Φ⊗P + Ψ⊗Q``, written block by block rather than by :func:`fdsc.kyp.kyp_weight`: cvxpy
    numbers the variables in the order it meets them, and the solver's answer for these
    ill-conditioned problems (K poorly determined) moves with that order: built by the builder,
    the MF and HF gains of the reproduction record move by up to 4e-3 (relative), so this
    layout is kept. ``tests/test_kyp.py`` checks that the projection of
    this matrix onto the kernel of the slack is :func:`fdsc.kyp.kyp_matrix` of the dual
    realization.
    """
    n, p = plant.n_states, plant.C.shape[0]
    cplx = band.is_complex
    ZA = plant.A @ X + plant.B2 @ Y
    ZC = plant.C @ X + plant.D2 @ Y
    B1, D1 = plant.B1, plant.D1
    psi = band.psi
    zpn, zpp = np.zeros((n, p)), np.zeros((p, p))
    # supply rate of the dual realization (B1ᵀ, D1ᵀ) in the last n + p rows and columns; it
    # holds constants and g only, so adding it leaves cvxpy's order of the variables unchanged
    out, inn = supply_parts(B1.T, D1.T)
    supply = cp.bmat([[np.zeros((n, n)), np.zeros((n, n + p))],
                      [np.zeros((n + p, n)), out - g * inn]])
    if band.kind in ("LF", "MF"):
        # slack [0; I; 0] Xᵀ (fictitious pole at infinity, outside LF and MF: lossless)
        # ψ12 Q = (Re ψ12 Q_re − Im ψ12 Q_im) + j (Im ψ12 Q_re + Re ψ12 Q_im)
        r12 = P[0] + psi[0, 1].real * Q[0] - X
        if cplx:
            r12 = r12 - psi[0, 1].imag * Q[1]
        re = cp.bmat([
            [-Q[0], r12, zpn],
            [r12.T, psi[1, 1].real * Q[0] + ZA + ZA.T, ZC.T],
            [zpn.T, ZC, zpp]]) + supply
        im = None
        if cplx:
            # imaginary parts: Ψ12 = jϖ_c multiplies Q_re; X, Y, Z are real
            i12 = P[1] + psi[0, 1].imag * Q[0] + psi[0, 1].real * Q[1]
            i22 = psi[1, 1].real * Q[1]
            im = cp.bmat([[-Q[1], i12, zpn], [-i12.T, i22, zpn], [zpn.T, zpn.T, zpp]])
    else:  # HF, slack [I; σI; 0] Xᵀ
        r12 = P[0] + ZA.T - sigma * X
        re = cp.bmat([
            [Q[0] - X - X.T, r12, ZC.T],
            [r12.T, -band.lower**2 * Q[0] + sigma * (ZA + ZA.T), sigma * ZC.T],
            [ZC, sigma * ZC, zpp]]) + supply
        im = None
    return re, im


def _stability_lmis(plant, X, Y, Ps, epsilon, margin):
    """The Lyapunov LMIs (dual form, slack ``[εI; I] Xᵀ``) that make ``A + B2 Y X⁻¹`` Hurwitz,
    sharing X and Y with the band LMIs."""
    n = plant.n_states
    ZA = plant.A @ X + plant.B2 @ Y
    stab = cp.bmat([[-epsilon * (X + X.T), Ps - X + epsilon * ZA.T],
                    [Ps - X.T + epsilon * ZA, ZA + ZA.T]])
    return [Ps >> margin * np.eye(n), _sym(stab) << -margin * np.eye(2 * n)]


def synthesize(plant: Plant, band: Band, *, epsilon: float = DEFAULT_EPSILON,
               sigma: float = DEFAULT_SIGMA, margin: float = DEFAULT_MARGIN,
               stability: bool = True) -> SynthesisResult:
    """Band-limited state feedback minimizing the certified in-band gain γ.

    Parameters
    ----------
    plant : Plant
        The open-loop plant; the closed loop is ``(A + B2 K, B1, C + D2 K, D1)``.
    band : Band
        LF, MF or HF (use :func:`synthesize_hinf` for the entire range).
    epsilon : float, optional
        ε > 0 of the stability LMI; default :data:`DEFAULT_EPSILON`.
    sigma : float, optional
        σ ≥ 0 of the HF slack (ignored for LF and MF); default :data:`DEFAULT_SIGMA`.
    margin : float, optional
        Strictness margin of every LMI; default :data:`~fdsc.lmi.DEFAULT_MARGIN`.
    stability : bool, optional
        Add the Lyapunov LMI sharing X and Y (default). Without it the band LMI alone may
        return a destabilizing gain (then ``gamma_sweep`` is inf); it shows what the shared
        slack costs.

    Returns
    -------
    SynthesisResult
        The gain K = Y X⁻¹, the LMI bound and the swept in-band gain.

    Raises
    ------
    TypeError
        If ``plant`` is not a :class:`~fdsc.Plant`, ``band`` not a :class:`~fdsc.Band` or
        ``stability`` not a bool.
    ValueError
        If ``band`` is the entire range, or ``epsilon``, ``sigma`` or ``margin`` is out of range.
    InfeasibleError
        If ``stability`` is set and the PBH test finds an uncontrollable eigenvalue with real
        part ≥ 0 (decided before the solver runs), or if the solver reports the LMIs infeasible.
    SolverError
        If the solve fails (the message names Clarabel's status).
    VerificationError
        If the returned gain fails its a-posteriori checks (Hurwitz, sweep ≤ LMI bound).

    Notes
    -----
    Lemma 1 (paper eq. (7)) for the dual realization ``(A_Kᵀ, C_Kᵀ, B1ᵀ, D1ᵀ)``, made affine in
    ``Z_A = A X + B2 Y``, ``Z_C = C X + D2 Y`` by Finsler's lemma (see the module docstring).
    Exact for LF and MF; for HF only sufficient, with σ placing the fictitious pole at −σ.

    Examples
    --------
    >>> from fdsc import random_plant
    >>> res = synthesize(random_plant(np.random.default_rng(7)), Band.lf(1.0))
    >>> bool(res.gamma_sweep <= res.gamma_lmi * (1 + 1e-5)), bool(np.all(res.poles.real < 0))
    (True, True)
    """
    plant = _check(plant, band)
    if band.kind == "EF":
        raise ValueError("band: use synthesize_hinf for the entire frequency range")
    epsilon = as_positive("epsilon", epsilon)
    sigma = as_nonnegative("sigma", sigma)
    margin = as_positive("margin", margin)
    if not isinstance(stability, bool):
        raise TypeError(f"stability must be True or False, but found {stability!r}")
    if stability:
        check_stabilizable(plant)
    n, mu = plant.n_states, plant.n_controls
    cplx = band.is_complex
    X = cp.Variable((n, n), name="X")
    Y = cp.Variable((mu, n), name="Y")
    g = cp.Variable(name="gamma_sq", nonneg=True)
    P = _herm_pair(n, "P", cplx)
    Q = _herm_pair(n, "Q", cplx)
    Ps = cp.Variable((n, n), symmetric=True, name="P_s")
    re, im = _band_lmi(plant, band, X, Y, P, Q, g, sigma)
    cons = [_neg_def(re, im, margin), _pos_def(*Q, margin)]
    if stability:
        cons += _stability_lmis(plant, X, Y, Ps, epsilon, margin)
    if cplx:
        cons += [P[1] + P[1].T == 0, Q[1] + Q[1].T == 0]
    prob = cp.Problem(cp.Minimize(g), cons)
    t0 = time.perf_counter()
    return _finish(plant, band, X, Y, g, prob, f"synthesis on the {band.label} band", t0,
                   epsilon, sigma if band.kind == "HF" else float("nan"), stability)


def _hinf_lmi(plant, X, Y, g):
    """The dual bounded real lemma of :func:`synthesize_hinf`.

    ``Fᵀ (Φ⊗X) F`` with ``F = [A_Kᵀ C_Kᵀ; I 0]`` is ``[[He(Z_A), Z_Cᵀ], [Z_C, 0]]``, affine in
    ``Z_A = A X + B2 Y`` and ``Z_C = C X + D2 Y``; the supply rate is that of (B1ᵀ, D1ᵀ).
    """
    p = plant.C.shape[0]
    ZA = plant.A @ X + plant.B2 @ Y
    ZC = plant.C @ X + plant.D2 @ Y
    out, inn = supply_parts(plant.B1.T, plant.D1.T)
    return cp.bmat([[ZA + ZA.T, ZC.T], [ZC, np.zeros((p, p))]]) + out - g * inn


def synthesize_hinf(plant: Plant, *, margin: float = DEFAULT_MARGIN) -> SynthesisResult:
    """H∞ state feedback (entire frequency range), minimizing ‖G‖∞.

    Dual bounded-real lemma with ``X = Xᵀ > 0``:
    ``[[He(Z_A) + B1B1ᵀ, Z_Cᵀ + B1D1ᵀ], [·, D1D1ᵀ − γ²I]] < 0``, ``K = Y X⁻¹``.

    Parameters
    ----------
    plant : Plant
        The open-loop plant; the closed loop is ``(A + B2 K, B1, C + D2 K, D1)``.
    margin : float, optional
        Strictness margin of the LMI in normalized units (B1, B2 and ``[C, D1, D2]`` of unit
        norm); default :data:`~fdsc.lmi.DEFAULT_MARGIN`. Multiplied by 10 and then 100 when an
        inaccurate solve fails its checks.

    Returns
    -------
    SynthesisResult
        With ``band`` the entire range and ``epsilon``, ``sigma`` NaN.

    Raises
    ------
    TypeError
        If ``plant`` is not a :class:`~fdsc.Plant`.
    ValueError
        If ``margin`` is not a positive finite number.
    InfeasibleError
        If the PBH test finds an uncontrollable eigenvalue with real part ≥ 0 (before solving),
        or if the solver reports the LMI infeasible.
    SolverError
        If the solve fails (the message names Clarabel's status).
    VerificationError
        If the returned gain fails its a-posteriori checks (Hurwitz, sweep ≤ LMI bound).

    Notes
    -----
    Lemma 1 (paper eq. (7)) on the entire range (Ψ = 0, the bounded real lemma) for the dual
    realization; with P = X the matrix is ``Fᵀ(Φ⊗X)F + supply`` of
    :func:`fdsc.kyp.kyp_matrix`, affine in ``Z_A`` and ``Z_C``.

    The LMI is solved for the plant in normalized units (d, u and z divided by the norms of B1,
    B2 and the output) and the gain mapped back, so that a change of the units of z, d or u
    gives the same gain in the new units and γ scaled by the change, up to the solver's
    tolerance.

    Examples
    --------
    >>> from fdsc import random_plant
    >>> res = synthesize_hinf(random_plant(np.random.default_rng(7)))
    >>> bool(res.gamma_sweep <= res.gamma_lmi * (1 + 1e-5))
    True
    """
    plant = as_plant(plant)
    margin = as_positive("margin", margin)
    check_stabilizable(plant)
    # solved in units where B1, B2 and the output have unit norm (fdsc._plant_scaling): the
    # margin and the solver's tolerances are absolute, so the plant's units must be taken out
    scaling = normalize_plant(plant)
    for k, factor in enumerate(MARGIN_RETRIES):
        X, Y, g, prob = _hinf_problem(scaling.plant, margin * factor)
        t0 = time.perf_counter()
        try:
            return _finish(plant, Band.entire(), X, Y, g, prob, "H-infinity synthesis", t0,
                           float("nan"), float("nan"), scaling=scaling)
        except VerificationError as exc:
            # as in Lemma 1 (fdsc.lmi): an 'optimal_inaccurate' point can sit just outside the
            # cone (singular problems put X on its margin); a larger margin moves it inward
            if exc.status != cp.OPTIMAL_INACCURATE or k == len(MARGIN_RETRIES) - 1:
                raise


def _hinf_problem(plant, margin):
    """``(X, Y, g, problem)`` of the H∞ synthesis LMI for ``plant`` (normalized units)."""
    n, mu, p = plant.n_states, plant.n_controls, plant.C.shape[0]
    X = cp.Variable((n, n), symmetric=True, name="X")
    Y = cp.Variable((mu, n), name="Y")
    g = cp.Variable(name="gamma_sq", nonneg=True)
    M = _hinf_lmi(plant, X, Y, g)
    cons = [_sym(M) << -margin * np.eye(n + p), X >> margin * np.eye(n)]
    return X, Y, g, cp.Problem(cp.Minimize(g), cons)


@dataclass(frozen=True)
class DirectResult:
    """Result of :func:`optimize_gain` (direct minimization of the band peak over K).

    Parameters
    ----------
    K : (m_u, n) ndarray
        The best gain found, ``u = K x``.
    band : Band
        The band whose peak was minimized.
    gamma_sweep : float
        Band peak of σ_max for the closed loop with K (refined sweep).
    n_evaluations : int
        Objective evaluations over all starts.

    Notes
    -----
    Uncertified: a cross-check of :class:`SynthesisResult`, whose bound comes from Lemma 1
    (paper eq. (7)).
    """

    K: np.ndarray
    band: Band
    gamma_sweep: float
    n_evaluations: int


def _objective_grid(band, n_grid):
    if band.lower == 0 and not np.isfinite(band.upper):     # the entire range: 0 and 1e-3 … 1e5
        return np.concatenate([[0.0], np.geomspace(1e-3, 1e5, n_grid)])
    if np.isfinite(band.upper):
        lo = band.lower if band.lower > 0 else band.upper * 1e-4
        w = np.geomspace(lo, band.upper, n_grid)
        return np.concatenate([[0.0], w]) if band.lower == 0 else w
    return np.geomspace(band.lower, band.lower * 1e4, n_grid)


def optimize_gain(plant: Plant, band: Band, K0: np.ndarray, *, n_starts: int = 4,
                  spread: float = 0.5, n_grid: int = 400, maxiter: int = 4000,
                  k_max: float | None = None,
                  rng: np.random.Generator | None = None) -> DirectResult:
    """Minimize the band peak of σ_max directly over K (Nelder–Mead, several starts).

    A non-convex, uncertified search used to cross-check the synthesis LMIs: on each start the
    peak is evaluated on a fixed grid; the best K is then swept with refinement. Unstable
    closed loops are rejected by a penalty.

    Parameters
    ----------
    plant : Plant
        The open-loop plant.
    band : Band
        The band whose peak of σ_max is minimized.
    K0 : (m_u, n) array_like
        First start (e.g. the LMI gain); further starts perturb it by ``spread`` (relative).
    n_starts : int, optional
        Number of starts (≥ 1).
    spread : float, optional
        Relative size (≥ 0) of the normal perturbations of K0 for starts after the first.
    n_grid : int, optional
        Grid points of the objective (≥ 2).
    maxiter : int, optional
        Cap on Nelder–Mead iterations per start.
    k_max : float, optional
        Bound on ‖K‖_F (default ``100 · max(1, ‖K0‖_F)``). The peak often keeps falling as the
        gain grows (high-gain directions), so an unbounded search need not converge.
    rng : numpy.random.Generator, optional
        Source of the perturbations (seeded by the caller for reproducibility; default
        ``numpy.random.default_rng(0)``).

    Returns
    -------
    DirectResult
        The best gain and its refined band peak.

    Raises
    ------
    TypeError
        If ``plant``, ``band`` or ``rng`` has the wrong type.
    DimensionError
        If ``K0`` is not (m_u, n).
    ValueError
        If a count, ``spread`` or ``k_max`` is out of range.
    IterationLimitError
        If no start converged within ``maxiter`` iterations.

    Notes
    -----
    A cross-check of the synthesis LMIs (Lemma 1, paper eq. (7), for the dual realization): it
    certifies nothing.

    Examples
    --------
    >>> from fdsc import random_plant
    >>> plant = random_plant(np.random.default_rng(11), stable=True)
    >>> K0 = synthesize(plant, Band.lf(1.0)).K
    >>> res = optimize_gain(plant, Band.lf(1.0), K0, n_starts=1, rng=np.random.default_rng(0))
    >>> bool(res.gamma_sweep <= band_peak(plant.closed_loop(K0), Band.lf(1.0)).gamma)
    True
    """
    plant = _check(plant, band)
    K0 = np.array(as_matrix("K0", K0, (plant.n_controls, plant.n_states)))
    n_starts = as_count("n_starts", n_starts)
    spread = as_nonnegative("spread", spread)
    n_grid = as_count("n_grid", n_grid, 2)
    maxiter = as_count("maxiter", maxiter)
    if rng is None:
        rng = np.random.default_rng(0)
    check_type("rng", rng, np.random.Generator, "a numpy.random.Generator")
    w = _objective_grid(band, n_grid)
    k_max = 100.0 * max(1.0, float(np.linalg.norm(K0))) if k_max is None else as_positive(
        "k_max", k_max)
    evals = 0

    # search in units of ‖K0‖ so that the simplex tolerances are relative to the gain's size
    scale = max(1.0, float(np.linalg.norm(K0)))

    def f(u):
        nonlocal evals
        evals += 1
        k = scale * u
        size = float(np.linalg.norm(k))
        if size > k_max:
            return 1e6 * (1.0 + size / k_max)
        cl = plant.closed_loop(k.reshape(K0.shape))
        worst_pole = float(np.max(np.linalg.eigvals(cl.A).real))
        if worst_pole >= 0:
            return 1e6 * (1.0 + worst_pole)
        return float(sigma_max(cl, w).max())

    best, converged = None, False
    u0 = K0.ravel() / scale
    for s in range(int(n_starts)):
        start = u0 * (1 + spread * rng.standard_normal(K0.size)) if s else u0
        res = minimize(f, start, method="Nelder-Mead",
                       options={"xatol": 1e-7, "fatol": 1e-10, "maxiter": int(maxiter)})
        converged |= bool(res.success)
        if best is None or res.fun < best.fun:
            best = res
    if not converged:
        raise IterationLimitError(f"optimize_gain: no start converged within maxiter={maxiter}")
    K = scale * best.x.reshape(K0.shape)
    gamma = band_peak(plant.closed_loop(K), band).gamma
    if plant.closed_loop(K0).is_hurwitz():
        # the search ran on a grid; keep the start if the refined sweep rates it better
        gamma0 = band_peak(plant.closed_loop(K0), band).gamma
        if gamma0 < gamma:
            K, gamma = K0, gamma0
    return DirectResult(K, band, gamma, evals)
