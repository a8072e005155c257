"""White measurement noise on the disturbance estimate, and the best LTI controller under it.

A controller that reads the estimate ŵ reads in practice ``ŵ = d + n`` with n measurement noise.
Here n is **band-limited white noise**: a flat two-sided spectral density S on
``|ω| ≤ Ω`` (Ω = π/h, the Nyquist frequency of a sampler of step h) and nothing above, so its
variance is ``σ² = S Ω / π`` and its samples at the step h are independent with variance σ².
Its level is stated as a signal-to-noise ratio: the mean power of d over σ²
(:func:`noise_density`).

For a fixed (LTI) controller the noise adds, in expectation, exactly

    P_n = (1/π) ∫₀^Ω ‖T_n(jω)‖² S dω

to the mean output power, T_n the closed loop from the noise (entering as ŵ only) to z
(:func:`noise_loop`, :func:`noise_power`): the cross term between the responses to d and to n
has mean zero. Over a horizon H in steady state, the expected energy grows by ``H P_n``.

:func:`optimal_lti_in_noise` is :func:`fdsc.optimal_lti` with the noise counted: among the
controllers ``u = K x + Q(s) ŵ`` (K the LQ gain, Q stable), the one of least expected power

    J(Q) = (1/π) ∫₀^∞ ‖T₁ + T₂ Q‖² Φ dω + (1/π) ∫₀^Ω ‖T₂ Q‖² S dω,

still a convex quadratic in Q, solved on the same expansion of Q, refined until J converges.
Without noise this family holds every LTI controller reading x and ŵ (full information); with
noise it does not (a dynamic filter of x also carries information on d, which the family's
static gain on x ignores), so at a high noise level a controller reading x alone through a
filter can do better: compare with one.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ._validation import as_positive, check_type
from .class_spectrum import SegmentClass
from .controller import Controller
from .exceptions import IterationLimitError
from .optimal_lti import (
    _DENSITIES,
    DEFAULT_TOL,
    _balanced,
    _frequency_grid,
    _lq_gain,
    _response,
    _weights,
    expected_power,
    feedforward_basis,
)
from .plant import LTISystem, Plant, as_plant

__all__ = ["noise_density", "noise_loop", "noise_power", "optimal_lti_in_noise", "NoisyOptimalLTI"]

#: Points per decade of the grid the noise's integral is taken on.
_PER_DECADE = 400


def noise_density(signal_power: float, snr_db: float, nyquist: float) -> float:
    """The two-sided density S of band-limited white noise on ``|ω| ≤ nyquist`` whose variance is
    ``signal_power / 10^(snr_db/10)``: ``S = σ² π / nyquist``.

    Parameters
    ----------
    signal_power : float
        The mean power of the signal the noise is measured against (> 0).
    snr_db : float
        Signal-to-noise ratio in dB (any real; ``inf`` gives 0).
    nyquist : float
        Ω > 0 (rad/s): the noise's band, π/h for samples at step h.

    Returns
    -------
    float

    Examples
    --------
    >>> round(noise_density(1.0, 20.0, math.pi), 6)        # σ² = 0.01 at h = 1 s
    0.01
    """
    p = as_positive("signal_power", signal_power)
    omega = as_positive("nyquist", nyquist)
    try:
        snr = float(snr_db)
    except (TypeError, ValueError):
        raise TypeError(f"snr_db must be a real number (dB), but found {snr_db!r}") from None
    if math.isnan(snr) or snr == -math.inf:
        raise ValueError(f"snr_db must be a real number or +inf, but found {snr_db!r}")
    if snr == math.inf:
        return 0.0
    return p / 10 ** (snr / 10) * math.pi / omega


def noise_loop(plant, controller: Controller) -> LTISystem:
    """The closed loop from noise on ŵ to z: ``controller`` on ``plant`` with the noise entering
    through what the controller reads as ŵ only (d = 0).

    Parameters
    ----------
    plant : Plant, control.StateSpace or tuple
        One disturbance input.
    controller : Controller
        It must read ŵ (``reads_estimate``); one reading x alone sees no noise of ŵ.

    Returns
    -------
    LTISystem
        One input (the noise).

    Raises
    ------
    TypeError
        If controller is not a Controller.
    ValueError
        If it does not read ŵ, or the plant has several disturbance inputs.
    """
    plant = as_plant(plant)
    check_type("controller", controller, Controller, "an fdsc.Controller")
    if plant.B1.shape[1] != 1:
        raise ValueError(f"plant must have one disturbance input, but has {plant.B1.shape[1]}")
    if not controller.reads_estimate:
        raise ValueError(f"controller {controller.name!r} does not read ŵ: no noise on ŵ reaches its loop")
    quiet = Plant(plant.A, np.zeros_like(plant.B1), plant.B2, plant.C, np.zeros_like(plant.D1), plant.D2)
    return quiet.closed_loop(controller)


def _noise_grid(nyquist, lowest):
    """A log grid on (lowest, nyquist] with trapezoid weights, and the piece [0, lowest] as one
    point at ``lowest`` of weight ``lowest`` (the response is flat there)."""
    n = max(int(_PER_DECADE * math.log10(nyquist / lowest)), 2)
    w = np.geomspace(lowest, nyquist, n)
    wt = np.zeros(n)
    dw = np.diff(w)
    wt[:-1] += dw / 2
    wt[1:] += dw / 2
    wt[0] += lowest
    return w, wt


def _lowest(A):
    """A frequency well below every pole of A (where the response has flattened)."""
    ev = np.abs(np.linalg.eigvals(A)) if A.size else np.array([1.0])
    ev = ev[ev > 0]
    return 1e-3 * (float(ev.min()) if ev.size else 1.0)


def noise_power(loop: LTISystem, density: float, nyquist: float) -> float:
    """The mean output power of a stable loop driven by band-limited white noise:
    ``(1/π) ∫₀^Ω ‖T(jω)‖² S dω`` (module docstring).

    Parameters
    ----------
    loop : LTISystem
        One input (:func:`noise_loop`).
    density : float
        S ≥ 0 (:func:`noise_density`).
    nyquist : float
        Ω > 0 (rad/s).

    Returns
    -------
    float

    Raises
    ------
    ValueError
        If the loop is not stable or has several inputs.

    Examples
    --------
    A first-order lag 1/(s + 1) under white noise of density 1 up to Ω has power arctan(Ω)/π:

    >>> loop = LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]])
    >>> abs(noise_power(loop, 1.0, 50.0) - math.atan(50.0) / math.pi) < 1e-5
    True
    """
    check_type("loop", loop, LTISystem, "an fdsc.LTISystem")
    if loop.B.shape[1] != 1:
        raise ValueError(f"loop must have one input (the noise), but has {loop.B.shape[1]}")
    S = float(density)
    if not S >= 0 or not math.isfinite(S):
        raise ValueError(f"density must be a finite number ≥ 0, but found {density!r}")
    omega = as_positive("nyquist", nyquist)
    if S == 0:
        return 0.0
    if not loop.is_hurwitz():
        raise ValueError("loop must be stable (Hurwitz): an unstable loop has no steady-state noise power")
    w, wt = _noise_grid(omega, min(_lowest(loop.A), omega / 10))
    T = _response(loop.A, loop.B, loop.C, loop.D, w)[:, :, 0]
    return float(np.sum(np.sum(np.abs(T) ** 2, axis=1) * wt) * S / math.pi)


@dataclass(frozen=True)
class NoisyOptimalLTI:
    """The result of :func:`optimal_lti_in_noise`.

    Parameters
    ----------
    controller : Controller
        ``u = K x + Q(s) ŵ`` of least expected power with the noise, its Q balanced and truncated.
    density, nyquist : float
        The noise it was designed for.
    power : float
        Its expected output power: the class's part (:func:`fdsc.expected_power`) plus the
        noise's (:func:`noise_power`).
    signal_power, noise_power : float
        The two parts.
    densities : (k,) int ndarray
        Shapes per decade of each refinement.
    powers : (k,) ndarray
        The objective J at each refinement.
    converged : bool
    """

    controller: Controller
    density: float
    nyquist: float
    power: float
    signal_power: float
    noise_power: float
    densities: np.ndarray
    powers: np.ndarray
    converged: bool


def _design(plant, K, cls, per_decade, w, phi_w, wn, sn):
    """The Q in the span of the basis of least J: ``(Controller, J)`` (:func:`fdsc.optimal_lti`'s
    least squares, with the noise's rows ``√(S wt/π) T₂ Q`` below the class's)."""
    A, B1, B2, C, D1, D2 = plant.A, plant.B1, plant.B2, plant.C, plant.D1, plant.D2
    AK, CK = A + B2 @ K, C + D2 @ K
    basis = feedforward_basis(cls, per_decade)
    m, nb = B2.shape[1], 0
    rows_a, rows_m = [], []
    for grid, weight, with_d in ((w, phi_w, True), (wn, sn, False)):
        T2 = _response(AK, B2, CK, D2, grid)                          # (W, p, m)
        Psi = _response(basis.A, basis.B, basis.C, basis.D, grid)[:, :, 0]
        nb = Psi.shape[1]
        cols = (T2[:, :, :, None] * Psi[:, None, None, :]).reshape(grid.size, -1, m * nb)
        sq = np.sqrt(weight)[:, None]
        T1 = _response(AK, B1, CK, D1, grid)[:, :, 0] if with_d else np.zeros(T2.shape[:2])
        rows_a += [(sq * T1.real).ravel(), (sq * T1.imag).ravel()]
        rows_m += [(sq[:, :, None] * cols.real).reshape(-1, m * nb),
                   (sq[:, :, None] * cols.imag).reshape(-1, m * nb)]
    a, M = np.concatenate(rows_a), np.concatenate(rows_m)
    scale = np.linalg.norm(M, axis=0)
    scale[scale == 0] = 1.0
    q = np.linalg.lstsq(M / scale, -a, rcond=1e-12)[0] / scale
    J = float(np.sum((a + M @ q) ** 2))
    Qm = q.reshape(m, nb)
    ctrl = Controller(basis.A, np.zeros((basis.n_states, plant.n_states)), Qm @ basis.C, K,
                      E=basis.B, F=Qm @ basis.D, name="optimal LTI in noise")
    return ctrl, J


def _powers(plant, ctrl, cls, density, nyquist):
    """(class part, noise part) of a controller's expected power."""
    sig = expected_power(plant.closed_loop(ctrl), cls)
    return sig, noise_power(noise_loop(plant, ctrl), density, nyquist)


def optimal_lti_in_noise(plant, cls: SegmentClass, density: float, nyquist: float, *,
                         tol: float = DEFAULT_TOL, reduce_tol: float = 1e-3,
                         name: str = "optimal LTI in noise", strict: bool = True) -> NoisyOptimalLTI:
    """The controller ``u = K x + Q(s) ŵ`` of least expected power when ŵ carries band-limited
    white noise (module docstring); with ``density = 0`` it is :func:`fdsc.optimal_lti`'s.

    Parameters
    ----------
    plant : Plant, control.StateSpace or tuple
        One disturbance input; D2 of full column rank.
    cls : SegmentClass
    density : float
        The noise's two-sided density S ≥ 0 (:func:`noise_density`).
    nyquist : float
        Its band Ω > 0 (rad/s).
    tol : float, optional
        Stop when J changes by less than this (relative) between two refinements (0.5 %).
    reduce_tol : float, optional
        Q is balanced and truncated to the fewest states whose expected power (with the noise)
        is within this (relative) of the full filter's.
    name : str, optional
    strict : bool, optional
        Raise :class:`fdsc.IterationLimitError` if J has not converged (default).

    Returns
    -------
    NoisyOptimalLTI

    Raises
    ------
    TypeError
        If cls is not a SegmentClass.
    ValueError
        If an argument is out of range (as :func:`fdsc.optimal_lti`).
    IterationLimitError
        If strict and J has not converged at the densest expansion tried.

    Examples
    --------
    More noise, more power, and less use of ŵ:

    >>> from fdsc import Plant
    >>> p = Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
    ...           [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.1]])
    >>> cls = SegmentClass([(0.5, 2.0), (10.0, 30.0)], [0.5, 0.5])
    >>> quiet = optimal_lti_in_noise(p, cls, 0.0, 100.0)
    >>> loud = optimal_lti_in_noise(p, cls, noise_density(1.0, 0.0, 100.0), 100.0)
    >>> bool(quiet.power < loud.power), bool(loud.noise_power > 0)
    (True, True)
    """
    check_type("cls", cls, SegmentClass, "an fdsc.SegmentClass")
    plant = as_plant(plant)
    if plant.B1.shape[1] != 1:
        raise ValueError(f"plant must have one disturbance input, but has {plant.B1.shape[1]}")
    S = float(density)
    if not S >= 0 or not math.isfinite(S):
        raise ValueError(f"density must be a finite number ≥ 0, but found {density!r}")
    omega = as_positive("nyquist", nyquist)
    tol = as_positive("tol", tol)
    reduce_tol = as_positive("reduce_tol", reduce_tol)
    K = _lq_gain(plant)
    w = _frequency_grid(cls)
    phi_w = cls.spectrum(w) * _weights(w) / math.pi
    AK = plant.A + plant.B2 @ K
    wn, wt = _noise_grid(omega, min(_lowest(AK), omega / 10, float(w[0])))
    sn = S * wt / math.pi
    densities, powers, last = [], [], None
    for density_ in _DENSITIES:
        ctrl, J = _design(plant, K, cls, density_, w, phi_w, wn, sn)
        densities.append(density_)
        powers.append(J)
        last = ctrl
        if len(powers) >= 2 and abs(powers[-1] / powers[-2] - 1.0) < tol:
            break
    converged = len(powers) >= 2 and abs(powers[-1] / powers[-2] - 1.0) < tol
    if strict and not converged:
        raise IterationLimitError(
            f"optimal_lti_in_noise: J did not converge to tol = {tol:g} over expansions of {densities} "
            f"shapes per decade (J {[float(f'{p:.6g}') for p in powers]}); pass strict=False to take the "
            "last")
    full = Controller(last.A, last.B, last.C, last.D, E=last.E, F=last.F, name=name)
    full_total = sum(_powers(plant, full, cls, S, omega))
    ctrl = _truncated(plant, full, cls, S, omega, full_total, reduce_tol)
    sig, noi = _powers(plant, ctrl, cls, S, omega)
    return NoisyOptimalLTI(ctrl, S, omega, sig + noi, sig, noi, np.array(densities), np.array(powers),
                           converged)


def _truncated(plant, ctrl, cls, S, omega, total, tol):
    """Q balanced and truncated to the fewest states whose expected power (with the noise) is
    within ``tol`` of ``total``; the full controller if none is."""
    if ctrl.n_states == 0:
        return ctrl
    Tl, Tr, hsv = _balanced(ctrl.A, ctrl.E, ctrl.C)
    Ab, Eb, Cb = Tl.T @ ctrl.A @ Tr, Tl.T @ ctrl.E, ctrl.C @ Tr

    def cut(r):
        return Controller(Ab[:r, :r], np.zeros((r, plant.n_states)), Cb[:, :r], ctrl.D, E=Eb[:r], F=ctrl.F,
                          name=ctrl.name)

    def good(r):
        c = cut(r)
        if not plant.closed_loop(c).is_hurwitz():
            return False
        return sum(_powers(plant, c, cls, S, omega)) <= total * (1.0 + tol)

    lo, hi = 0, hsv.size
    if not good(hi):
        return ctrl
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if good(mid):
            hi = mid
        else:
            lo = mid
    return cut(hi)
