"""The optimal LTI controller for a class of disturbances, reading x and the past of ŵ.

For an LTI controller the expected output power under a stationary disturbance depends on the
disturbance's spectrum Φ alone (:mod:`fdsc.class_spectrum`). Which LTI controller reading the
state x and the estimate ŵ (= d for a nominal plant with x and ẋ measured) minimizes it?

**Every such controller, one free filter.** Fix a stabilizing gain K (the plant's LQ gain). A
stabilizing LTI controller that reads x and d sets ``u = K x + v`` with ``v = Q(s) d`` for a
stable Q, and every stable Q is realized by ``u = K x + Q(s) ŵ`` (full information: the
closed loops from d to z are exactly ``T(Q) = T₁ + T₂ Q``, T₁ the loop of K from d, T₂ from v).
So the expected output power

    J(Q) = (1/π) ∫₀^∞ ‖T₁(jω) + T₂(jω) Q(jω)‖² Φ(ω) dω

is a convex quadratic in Q, and its least value over stable, causal Q is the Wiener–Hopf
optimum: the optimal LTI controller of the class (in steady state, in expectation).

**Computed on the exact spectrum.** Q is expanded in stable second-order shapes (low-pass and
band-pass, centres log-spaced over the class's bands and a decade beyond, damping tied to the
spacing) and a constant; J is then a linear least-squares problem in the coefficients, on the
exact Φ (no rational fit of Φ, whose sharp band edges a spectral factor would need a high order
to follow). The expansion is refined (more shapes per decade) until J changes by less than
``tol`` between two refinements; each J is a value some causal LTI controller reaches, and the
limit is the optimum. The same design through a rational spectral factor and the augmented
Riccati equation (``u = K x + K_ξ ξ``, ξ the factor's state rebuilt from the past of d) gives
the optimum of the fitted spectrum instead of the class's.

:func:`expected_power` is J for any closed loop (a quadrature of ``‖T(jω)‖² Φ(ω)``), and
:func:`wiener_power` the least expected power of any controller that knows the whole
disturbance in advance (``(1/π) ∫₀^∞ Φ(ω) L(ω) dω`` with L the per-frequency optimum of
:func:`fdsc.noncausal.tone_limit`): a bound no LTI controller, causal or not, passes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.linalg import solve_continuous_are, solve_continuous_lyapunov

from ._validation import as_count, as_positive, check_type
from .class_spectrum import SegmentClass
from .controller import Controller
from .exceptions import IterationLimitError
from .plant import LTISystem, as_plant

__all__ = ["expected_power", "wiener_power", "feedforward_basis", "optimal_lti", "OptimalLTI",
           "DEFAULT_TOL"]

#: Relative change of the expected power between two refinements below which :func:`optimal_lti`
#: stops.
DEFAULT_TOL = 5e-3
#: Shapes per decade tried by :func:`optimal_lti`, in order.
_DENSITIES = (2, 3, 4, 6, 8, 11, 16)


def _frequency_grid(cls: SegmentClass, per_decade: int = 400) -> np.ndarray:
    """A log grid over the class's bands and their tails, refined at every band edge (where Φ
    changes over the width of the survival's kernel, about 1/μ)."""
    lo = min(b[0] for b in cls.bands) / 30.0
    hi = max(b[1] for b in cls.bands) * 30.0
    grid = [np.geomspace(lo, hi, int(per_decade * math.log10(hi / lo)) + 1)]
    width = 4.0 / cls.mean_extra + 4.0 / max(cls.mean_length, 1e-300)
    for edge in (e for b in cls.bands for e in b):
        grid.append(np.linspace(max(edge - 20 * width, lo), edge + 20 * width, 401))
    return np.unique(np.concatenate(grid))


def _weights(w):
    """Trapezoid weights of the grid w."""
    h = np.diff(w)
    out = np.zeros_like(w)
    out[:-1] += h / 2
    out[1:] += h / 2
    return out


def feedforward_basis(cls: SegmentClass, per_decade: int) -> LTISystem:
    """The stable shapes Q is expanded in: one input (ŵ), one output per shape.

    Second-order sections at centres ω_k log-spaced from a tenth of the lowest band to ten times
    the highest, each with a low-pass output ``ω_k² y`` and a band-pass output ``2ζω_k ẏ``
    (``ÿ = −ω_k² y − 2ζω_k ẏ + ŵ``, ζ tied to the spacing), and a last output ŵ itself (a
    static term).

    Parameters
    ----------
    cls : SegmentClass
    per_decade : int
        Sections per decade (≥ 1).

    Returns
    -------
    LTISystem
        ``2k`` states, one input, ``2k + 1`` outputs.

    Raises
    ------
    TypeError, ValueError
        If ``cls`` is not a SegmentClass or ``per_decade`` is not a whole number ≥ 1.
    """
    check_type("cls", cls, SegmentClass, "an fdsc.SegmentClass")
    per_decade = as_count("per_decade", per_decade)
    lo = min(b[0] for b in cls.bands) / 10.0
    hi = max(b[1] for b in cls.bands) * 10.0
    k = max(2, int(round(per_decade * math.log10(hi / lo))) + 1)
    centres = np.geomspace(lo, hi, k)
    rho = (hi / lo) ** (1.0 / (k - 1))
    zeta = min(0.9, max(0.1, 0.5 * (rho - 1.0 / rho)))
    A = np.zeros((2 * k, 2 * k))
    B = np.zeros((2 * k, 1))
    C = np.zeros((2 * k + 1, 2 * k))
    D = np.zeros((2 * k + 1, 1))
    for j, wc in enumerate(centres):
        A[2 * j:2 * j + 2, 2 * j:2 * j + 2] = [[0.0, 1.0], [-wc * wc, -2 * zeta * wc]]
        B[2 * j + 1, 0] = 1.0
        C[2 * j, 2 * j] = wc * wc
        C[2 * j + 1, 2 * j + 1] = 2 * zeta * wc
    D[-1, 0] = 1.0
    return LTISystem(A, B, C, D)


def expected_power(loop: LTISystem, cls: SegmentClass) -> float:
    """The mean output power ``E‖z‖²`` of a stable closed loop (one disturbance input) in steady
    state under the class: ``(1/π) ∫₀^∞ ‖T(jω)‖² Φ(ω) dω``.

    Parameters
    ----------
    loop : LTISystem
        The map from d to z (:meth:`fdsc.Plant.closed_loop`, also of a controller reading ŵ).
    cls : SegmentClass

    Returns
    -------
    float

    Raises
    ------
    TypeError
        If the arguments are not an LTISystem and a SegmentClass.
    ValueError
        If the loop has more than one input or is not stable.

    Examples
    --------
    >>> cls = SegmentClass([(1.0, 10.0)], [1.0])
    >>> loop = LTISystem([[-1e4]], [[1e4]], [[1.0]], [[0.0]])      # z ≈ d
    >>> round(expected_power(loop, cls), 4)                           # the class's power
    1.0
    """
    check_type("loop", loop, LTISystem, "an fdsc.LTISystem")
    check_type("cls", cls, SegmentClass, "an fdsc.SegmentClass")
    if loop.B.shape[1] != 1:
        raise ValueError(f"loop must have one input (d), but has {loop.B.shape[1]}")
    if not loop.is_hurwitz():
        raise ValueError("loop must be stable (Hurwitz): an unstable loop has no steady-state power")
    w = _frequency_grid(cls)
    T = _response(loop.A, loop.B, loop.C, loop.D, w)[:, :, 0]
    f = np.sum(np.abs(T) ** 2, axis=1) * cls.spectrum(w)
    # beyond the grid Φ falls like 1/ω² (its tail f ω), ‖T‖² at most its value there
    return float((np.sum(f * _weights(w)) + f[-1] * w[-1]) / math.pi)


def wiener_power(plant, cls: SegmentClass) -> float:
    """The least mean output power of any controller that knows the whole disturbance in advance:
    ``(1/π) ∫₀^∞ Φ(ω) L(ω) dω``, L the per-frequency optimum (:func:`fdsc.noncausal.tone_limit`).

    A bound for every controller of the class in steady state (linear or not, causal or not,
    in expectation over the class's second-order statistics only for LTI controllers: a
    controller that learns each segment's tones may pass it on a single draw, never the
    draw-wise non-causal limit :func:`fdsc.noncausal_limit`).

    Parameters
    ----------
    plant : Plant, control.StateSpace or tuple
        One disturbance input; D2 of full column rank.
    cls : SegmentClass

    Returns
    -------
    float

    Raises
    ------
    TypeError
        If ``cls`` is not a SegmentClass.
    ValueError
        As :func:`fdsc.noncausal.tone_limit`.
    """
    from .noncausal import tone_limit

    check_type("cls", cls, SegmentClass, "an fdsc.SegmentClass")
    plant = as_plant(plant)
    w = _frequency_grid(cls)
    f = tone_limit(plant, w) * cls.spectrum(w)
    return float((np.sum(f * _weights(w)) + f[-1] * w[-1]) / math.pi)


def _lq_gain(plant):
    """The plant's LQ gain (z = C x + D2 u weighted as the energy), u = K x."""
    R = plant.D2.T @ plant.D2
    Qx = plant.C.T @ plant.C
    S = plant.C.T @ plant.D2
    try:
        P = solve_continuous_are(plant.A, plant.B2, Qx, R, s=S)
    except (np.linalg.LinAlgError, ValueError) as exc:
        raise ValueError(f"plant: the LQ problem has no stabilizing solution: {exc}") from exc
    return -np.linalg.solve(R, plant.B2.T @ P + S.T)


def _response(A, B, C, D, w):
    """``C (jωI − A)⁻¹ B + D`` on the frequencies w: (len(w), p, m), by the eigenvalues of A
    where they are well conditioned."""
    ev, V = np.linalg.eig(A)
    if np.linalg.cond(V) < 1e8:
        Bm = np.linalg.solve(V, B)
        Cm = C @ V
        G = np.einsum("pk,wk,km->wpm", Cm, 1.0 / (1j * w[:, None] - ev[None, :]), Bm)
    else:
        n = A.shape[0]
        G = np.array([C @ np.linalg.solve(1j * x * np.eye(n) - A, B) for x in w])
    return G + D[None, :, :]


def _design(plant, K, cls, per_decade, w, phi_w):
    """The best Q in the span of :func:`feedforward_basis`: ``(Controller, J)``."""
    A, B1, B2, C, D1, D2 = plant.A, plant.B1, plant.B2, plant.C, plant.D1, plant.D2
    AK, CK = A + B2 @ K, C + D2 @ K
    T1 = _response(AK, B1, CK, D1, w)[:, :, 0]                 # (W, p)
    T2 = _response(AK, B2, CK, D2, w)                          # (W, p, m)
    basis = feedforward_basis(cls, per_decade)
    Psi = _response(basis.A, basis.B, basis.C, basis.D, w)[:, :, 0]     # (W, nb)
    m, nb = B2.shape[1], Psi.shape[1]
    # z = T1 d + Σ_{j,k} q_jk T2[:, j] ψ_k d: the columns of the least-squares problem
    cols = (T2[:, :, :, None] * Psi[:, None, None, :]).reshape(w.size, -1, m * nb)
    sq = np.sqrt(phi_w)[:, None]
    a = np.concatenate([(sq * T1.real).ravel(), (sq * T1.imag).ravel()])
    M = np.concatenate([(sq[:, :, None] * cols.real).reshape(-1, m * nb),
                        (sq[:, :, None] * cols.imag).reshape(-1, m * nb)])
    scale = np.linalg.norm(M, axis=0)
    scale[scale == 0] = 1.0
    q = np.linalg.lstsq(M / scale, -a, rcond=1e-12)[0] / scale
    J = float(np.sum((a + M @ q) ** 2))
    Qm = q.reshape(m, nb)                                      # v = Qm ψ(s) ŵ
    ctrl = Controller(basis.A, np.zeros((basis.n_states, plant.n_states)), Qm @ basis.C, K,
                      E=basis.B, F=Qm @ basis.D, name="optimal LTI")
    return ctrl, J


def _sqrt_psd(W):
    """A square root L of a symmetric positive semi-definite W (W = L Lᵀ)."""
    ev, V = np.linalg.eigh(0.5 * (W + W.T))
    return V * np.sqrt(np.maximum(ev, 0.0))[None, :]


def _balanced(A, B, C):
    """The balanced realization of a stable (A, B, C), states ordered by Hankel singular value:
    ``(T_l, T_r, hsv)`` with ``x = T_r x_b`` and ``x_b = T_lᵀ x``."""
    Wc = solve_continuous_lyapunov(A, -B @ B.T)
    Wo = solve_continuous_lyapunov(A.T, -C.T @ C)
    Lc, Lo = _sqrt_psd(Wc), _sqrt_psd(Wo)
    U, hsv, Vt = np.linalg.svd(Lo.T @ Lc)
    keep = hsv > hsv[0] * 1e-14
    U, hsv, V = U[:, keep], hsv[keep], Vt[keep].T
    s = 1.0 / np.sqrt(hsv)
    return Lo @ U * s[None, :], Lc @ V * s[None, :], hsv


def _reduced(plant, ctrl: Controller, cls, power: float, tol: float):
    """The controller with its filter Q(s) balanced and truncated to the fewest states whose
    expected power is within ``tol`` (relative) of ``power``; the full one if none is."""
    Tl, Tr, hsv = _balanced(ctrl.A, ctrl.E, ctrl.C)
    Ab, Eb, Cb = Tl.T @ ctrl.A @ Tr, Tl.T @ ctrl.E, ctrl.C @ Tr

    def truncated(r):
        return Controller(Ab[:r, :r], np.zeros((r, plant.n_states)), Cb[:, :r], ctrl.D, E=Eb[:r],
                          F=ctrl.F, name=ctrl.name)

    def good(r):
        loop = plant.closed_loop(truncated(r))
        return loop.is_hurwitz() and expected_power(loop, cls) <= power * (1.0 + tol)

    # the power falls as states are kept (not strictly: bisect, then confirm)
    lo, hi = 0, hsv.size
    if not good(hi):
        return ctrl
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if good(mid):
            hi = mid
        else:
            lo = mid
    return truncated(hi)


@dataclass(frozen=True)
class OptimalLTI:
    """The result of :func:`optimal_lti`.

    Parameters
    ----------
    controller : Controller
        The optimal LTI controller reading x and ŵ (``u = K x + Q(s) ŵ``) at the last
        refinement, its filter Q balanced and truncated to the fewest states that keep the
        expected power within ``reduce_tol`` of the full filter's.
    gain : ndarray
        K, the plant's LQ gain the controller is built on.
    power : float
        Its expected output power under the class (:func:`expected_power`).
    full_power : float
        The expected power of the full (not truncated) filter of the last refinement.
    densities : (k,) int ndarray
        The shapes per decade of each refinement.
    powers : (k,) ndarray
        The expected power at each refinement (each reached by a causal LTI controller).
    wiener : float
        The non-causal bound (:func:`wiener_power`).
    converged : bool
        Whether the last two powers differ by less than the tolerance (relative).
    """

    controller: Controller
    gain: np.ndarray
    power: float
    full_power: float
    densities: np.ndarray
    powers: np.ndarray
    wiener: float
    converged: bool

    @property
    def change(self) -> float:
        """The relative change of the expected power between the last two refinements."""
        if self.powers.size < 2:
            return math.inf
        return abs(self.powers[-1] / self.powers[-2] - 1.0)


def optimal_lti(plant, cls: SegmentClass, *, tol: float = DEFAULT_TOL, reduce_tol: float = 1e-3,
                name: str = "optimal LTI", strict: bool = True) -> OptimalLTI:
    """The optimal LTI controller of a class, reading x and the past of ŵ (module docstring).

    Parameters
    ----------
    plant : Plant, control.StateSpace or tuple
        One disturbance input; ``(A, B2)`` stabilizable, D2 of full column rank.
    cls : SegmentClass
        The class of disturbances.
    tol : float, optional
        Stop when the expected power changes by less than this (relative) between two
        refinements of the expansion of Q (default :data:`DEFAULT_TOL`, 0.5 %).
    reduce_tol : float, optional
        The filter Q of the last refinement is balanced and truncated to the fewest states
        whose expected power is within this (relative) of the full filter's (default 0.1 %).
    name : str, optional
        The controller's name.
    strict : bool, optional
        Raise if the refinements tried do not converge (default); else return the last with
        ``converged`` False.

    Returns
    -------
    OptimalLTI

    Raises
    ------
    TypeError
        If ``cls`` is not a SegmentClass.
    ValueError
        If the plant has several disturbances or the LQ problem has no stabilizing solution, or
        ``tol`` is not positive.
    IterationLimitError
        If ``strict`` and the expected power has not converged at the densest expansion tried.

    Examples
    --------
    >>> from fdsc import Plant
    >>> p = Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
    ...           [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.1]])
    >>> res = optimal_lti(p, SegmentClass([(0.5, 2.0), (10.0, 30.0)], [0.5, 0.5]))
    >>> res.converged, bool(res.wiener <= res.power), res.controller.reads_estimate
    (True, True, True)
    """
    check_type("cls", cls, SegmentClass, "an fdsc.SegmentClass")
    plant = as_plant(plant)
    if plant.B1.shape[1] != 1:
        raise ValueError(f"plant must have one disturbance input, but has {plant.B1.shape[1]}")
    tol = as_positive("tol", tol)
    reduce_tol = as_positive("reduce_tol", reduce_tol)
    K = _lq_gain(plant)
    w = _frequency_grid(cls)
    phi_w = cls.spectrum(w) * _weights(w) / math.pi
    densities, powers, last = [], [], None
    for density in _DENSITIES:
        ctrl, J = _design(plant, K, cls, density, w, phi_w)
        densities.append(density)
        powers.append(J)
        last = ctrl
        if len(powers) >= 2 and abs(powers[-1] / powers[-2] - 1.0) < tol:
            break
    converged = len(powers) >= 2 and abs(powers[-1] / powers[-2] - 1.0) < tol
    if strict and not converged:
        raise IterationLimitError(
            f"optimal_lti: the expected power did not converge to tol = {tol:g} over expansions of "
            f"{densities} shapes per decade (powers {[float(f'{p:.6g}') for p in powers]}); pass "
            "strict=False to take the last")
    full = Controller(last.A, last.B, last.C, last.D, E=last.E, F=last.F, name=name)
    full_power = expected_power(plant.closed_loop(full), cls)
    ctrl = _reduced(plant, full, cls, full_power, reduce_tol)
    return OptimalLTI(ctrl, K, expected_power(plant.closed_loop(ctrl), cls), full_power,
                      np.array(densities), np.array(powers), wiener_power(plant, cls), converged)
