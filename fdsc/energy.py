"""Frequency-dependent excited energy and power functions (FD-EEF, FD-EPF), Sec. III.

For a real state trajectory the quadratic form ``[ẋ; x]* (Ψ ⊗ Q) [ẋ; x]`` sees only
``Re Ψ`` (the imaginary part of a Hermitian Ψ ⊗ Q multiplies ``ẋᵀQx − xᵀQẋ = 0``), so::

    P_t(Ω, Q, t) = ψ11 ẋᵀQẋ + 2 Re ψ12 ẋᵀQx + ψ22 xᵀQx          (instantaneous FD-EPF)
    S(Ω, Q, T_l) = ∫_{T_l} P_t dt,   P_a = S / |T_l|                (FD-EEF, average FD-EPF)

(paper eqs. (19)-(20) for the FD-EEF, (28) and (29) for the FD-EPF). In the frequency domain
(Parseval, paper eq. (23)) a component at ω is weighted by the real weight
``w(ω) = Re([jω;1]*Ψ[jω;1])`` (:meth:`fdsc.Band.real_weight`): positive in band, negative out
of band for LF and HF; negative everywhere for MF.
"""

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from scipy.linalg import solve_continuous_lyapunov

from ._validation import as_matrix, as_vector, check_hurwitz, check_type
from .bands import Band
from .exceptions import DimensionError
from .plant import LTISystem, as_system
from .signals import Sinusoids

__all__ = [
    "check_weight",
    "instantaneous_power",
    "fdeef",
    "average_power",
    "PowerSplit",
    "steady_state_power",
    "fdeef_autonomous",
    "fdeef_parseval_autonomous",
]


def check_weight(Q: ArrayLike, n: int) -> np.ndarray:
    """Validate a symmetric positive-definite weight Q of size (n, n) and return it.

    Parameters
    ----------
    Q : (n, n) array_like
        The candidate weight.
    n : int
        Number of states: the expected size of Q.

    Returns
    -------
    (n, n) ndarray
        Q as a read-only float array.

    Raises
    ------
    DimensionError
        Wrong shape.
    ValueError
        Not symmetric (to a relative 1e-12), not positive definite, or not finite and real.

    Examples
    --------
    >>> check_weight([[2.0, 0.0], [0.0, 1.0]], 2)
    array([[2., 0.],
           [0., 1.]])
    >>> check_weight([[1.0, 0.0], [0.0, -1.0]], 2)
    Traceback (most recent call last):
    ...
    ValueError: Q must be positive definite; its smallest eigenvalue is -1
    """
    Q = as_matrix("Q", Q, (n, n))
    if not np.allclose(Q, Q.T, rtol=1e-12, atol=1e-12 * max(1.0, np.abs(Q).max())):
        raise ValueError("Q must be symmetric")
    qmin = float(np.linalg.eigvalsh(Q).min())
    if qmin <= 0:
        raise ValueError(f"Q must be positive definite; its smallest eigenvalue is {qmin:.3g}")
    return Q


def _band(band):
    check_type("band", band, Band)
    return band.psi.real


def _trajectory(x, xdot):
    x = as_matrix("x", x)
    xdot = as_matrix("xdot", xdot, x.shape)
    return x, xdot


def _state_matrix(sys, what):
    """A of a system given in any form :func:`~fdsc.plant.as_system` accepts, checked Hurwitz."""
    A = as_system(sys).A
    check_hurwitz("sys", A, what)
    return A


def instantaneous_power(x: ArrayLike, xdot: ArrayLike, band: Band, Q: ArrayLike) -> np.ndarray:
    """Instantaneous FD-EPF ``P_t(Ω, Q, t)`` along a trajectory.

    Parameters
    ----------
    x, xdot : (N, n) array_like
        States and state derivatives at N instants (real).
    band : Band
        The frequency range Ω (only ``Re Ψ`` acts on real signals).
    Q : (n, n) array_like
        Symmetric positive definite.

    Returns
    -------
    (N,) ndarray
        ``[ẋ; x]ᵀ (Re Ψ ⊗ Q) [ẋ; x]`` at each instant.

    Raises
    ------
    DimensionError
        If ``x`` is not 2-D, ``xdot`` differs from it in shape, or Q is not (n, n).
    ValueError
        If Q is not symmetric positive definite, or an entry is not finite and real.
    TypeError
        If ``band`` is not a :class:`~fdsc.bands.Band`.

    Notes
    -----
    Paper eq. (29); the switching law, paper eq. (31), compares it across modes.

    Examples
    --------
    >>> x = np.array([[1.0, 0.0]]); xd = np.array([[0.0, 2.0]])
    >>> float(instantaneous_power(x, xd, Band.lf(3.0), np.eye(2))[0])     # −|ẋ|² + 9|x|²
    5.0
    """
    x, xdot = _trajectory(x, xdot)
    Q = check_weight(Q, x.shape[1])
    p = _band(band)
    qx, qd = x @ Q, xdot @ Q
    return (p[0, 0] * np.sum(qd * xdot, axis=1) + 2 * p[0, 1] * np.sum(qd * x, axis=1)
            + p[1, 1] * np.sum(qx * x, axis=1))


def fdeef(t: ArrayLike, x: ArrayLike, xdot: ArrayLike, band: Band, Q: ArrayLike) -> float:
    """FD-EEF ``S(Ω, Q, T_l)`` over the sampled window ``[t[0], t[-1]]`` (Simpson's rule).

    A quadrature of the given samples: accurate for a smooth trajectory (an LTI run under a
    smooth disturbance; Simpson's error falls like the step to the fourth). The ẋ of a switched
    run jumps at every switch, where a quadrature of samples is wrong by up to a step's worth
    of the integrand; do not use it on such samples.

    Parameters
    ----------
    t : (N,) array_like
        Increasing sample times in s (uniform spacing recommended; N ≥ 3).
    x, xdot : (N, n) array_like
        States and state derivatives at the times ``t``.
    band : Band
        The frequency range Ω.
    Q : (n, n) array_like
        Symmetric positive definite.

    Returns
    -------
    float

    Raises
    ------
    ValueError
        If ``t`` is not increasing or has fewer than 3 samples, or Q is not symmetric positive
        definite.
    DimensionError
        If ``t`` and ``x`` have different numbers of samples, or the shapes of ``x``, ``xdot``
        and Q do not fit.

    Notes
    -----
    Paper eq. (20), the localized-time FD-EEF.

    Examples
    --------
    >>> t = np.linspace(0.0, 2 * np.pi, 2001)
    >>> x, xd = np.sin(t)[:, None], np.cos(t)[:, None]
    >>> round(fdeef(t, x, xd, Band.lf(2.0), [[1.0]]) / np.pi, 9)   # ∫(4 sin² − cos²) = 3π
    3.0
    """
    t = as_vector("t", t)
    if t.size < 3 or np.any(np.diff(t) <= 0):
        raise ValueError("t must be an increasing 1-D array of at least 3 samples (the window)")
    p = instantaneous_power(x, xdot, band, Q)
    if p.size != t.size:
        raise DimensionError(f"t has {t.size} samples but x has {p.size} rows")
    from scipy.integrate import simpson  # here: a simulation needs no scipy.integrate

    return float(simpson(p, x=t))


def average_power(t: ArrayLike, x: ArrayLike, xdot: ArrayLike, band: Band, Q: ArrayLike) -> float:
    """Average FD-EPF ``P_a = S(Ω, Q, T_l) / |T_l|`` over the sampled window.

    Parameters
    ----------
    t : (N,) array_like
        Increasing sample times in s (uniform spacing recommended; N ≥ 3).
    x, xdot : (N, n) array_like
        States and state derivatives at the times ``t``.
    band : Band
        The frequency range Ω.
    Q : (n, n) array_like
        Symmetric positive definite.

    Returns
    -------
    float

    Raises
    ------
    ValueError, DimensionError
        As for :func:`fdeef`.

    Notes
    -----
    Paper eq. (28).

    Examples
    --------
    >>> t = np.linspace(0.0, 2 * np.pi, 2001)
    >>> float(round(average_power(t, np.sin(t)[:, None], np.cos(t)[:, None], Band.lf(2.0), [[1.0]]), 9))
    1.5
    """
    t = as_vector("t", t)
    return fdeef(t, x, xdot, band, Q) / (t[-1] - t[0])


@dataclass(frozen=True)
class PowerSplit:
    """Steady-state average FD-EPF of a sum of sinusoids and its in-band/out-of-band split.

    Returned by :func:`steady_state_power`.

    Parameters
    ----------
    total : float
        ``P_a`` (in-band + out-of-band).
    in_band : float
        Contribution of components where the weight is positive (> 0).
    out_of_band : float
        Contribution of components where the weight is negative (< 0).
    per_component : (K,) ndarray
        Contribution of each sinusoid.

    Notes
    -----
    The split of paper Remark 1 (paper eq. (26)), for power instead of energy.
    """

    total: float
    in_band: float
    out_of_band: float
    per_component: np.ndarray


def steady_state_power(sys: LTISystem, d: Sinusoids, band: Band, Q: ArrayLike) -> PowerSplit:
    """Exact steady-state average FD-EPF of ``dx/dt = A x + B d`` for a sum of sinusoids.

    For ``d = Σ a_k sin(ω_k t + φ_k)`` with distinct ω_k and A Hurwitz, the steady state is
    ``x = Σ Im(X_k e^{j(ω_k t + φ_k)})`` with ``X_k = (jω_k I − A)⁻¹ B a_k``, and cross terms of
    distinct frequencies average to zero (Parseval for power signals), so

        P_a = Σ_k w(ω_k) X_k* Q X_k / 2       (ω_k > 0; a constant term counts fully).

    Parameters
    ----------
    sys : LTISystem, control.StateSpace or (A, B, C, D)
        The system ``dx/dt = A x + B d`` with A Hurwitz and one disturbance input (C and D
        are not used).
    d : Sinusoids
        The disturbance, with distinct frequencies.
    band : Band
        The frequency range Ω.
    Q : (n, n) array_like
        Symmetric positive definite.

    Returns
    -------
    PowerSplit

    Raises
    ------
    UnstableError
        If A is not Hurwitz (no steady state exists).
    DimensionError
        If the system has more than one disturbance input, or Q is not (n, n).
    ValueError
        If ``d`` repeats a frequency, or Q is not symmetric positive definite.
    TypeError
        If ``d`` is not :class:`~fdsc.signals.Sinusoids` or ``band`` not a :class:`Band`.

    Notes
    -----
    The limit of the average FD-EPF, paper eq. (28), as the window grows; the proof of paper
    Theorem 1(3) writes the same sum (the in-band part ``P_a^in`` and out-of-band part
    ``P_a^out`` after paper eq. (51)).

    Examples
    --------
    >>> from fdsc import LTISystem, Sinusoids
    >>> sys = LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]])
    >>> ps = steady_state_power(sys, Sinusoids([1.0, 1.0], [0.5, 4.0]), Band.lf(2.0), [[1.0]])
    >>> # |X|² = 1/(1 + ω²), weight 4 − ω²: 3.75 · 0.8 / 2 and −12 / 17 / 2
    >>> round(ps.in_band, 12), round(ps.out_of_band, 12)
    (1.5, -0.352941176471)
    """
    A = _state_matrix(sys, "a steady state")
    n = A.shape[0]
    B = as_system(sys).B
    if B.shape[1] != 1:
        raise DimensionError(f"sys must have one disturbance input, but B has shape {B.shape}")
    Q = check_weight(Q, n)
    check_type("d", d, Sinusoids, "an fdsc.signals.Sinusoids")
    check_type("band", band, Band)
    if np.unique(d.frequencies).size != d.frequencies.size:
        raise ValueError("d must have distinct frequencies")
    contrib = np.empty(d.frequencies.size)
    for k, (a, w, ph) in enumerate(zip(d.amplitudes, d.frequencies, d.phases, strict=True)):
        X = np.linalg.solve(1j * w * np.eye(n) - A, B[:, 0] * a)
        if w == 0:
            xr = (X * np.exp(1j * ph)).imag
            contrib[k] = band.real_weight(0.0) * xr @ Q @ xr
        else:
            contrib[k] = band.real_weight(w) * float((X.conj() @ Q @ X).real) / 2
    wts = band.real_weight(d.frequencies)
    return PowerSplit(float(contrib.sum()), float(contrib[wts > 0].sum()),
                      float(contrib[wts < 0].sum()), contrib)


def _psi_matrix(A, band, Q):
    p = _band(band)
    return p[0, 0] * A.T @ Q @ A + p[0, 1] * (A.T @ Q + Q @ A) + p[1, 1] * Q


def fdeef_autonomous(sys: LTISystem, x0: ArrayLike, band: Band, Q: ArrayLike) -> float:
    """Infinite-horizon FD-EEF of ``x = e^{At} x0`` in closed form (a Lyapunov equation).

    ``S = ∫₀^∞ [Ax; x]ᵀ (Re Ψ ⊗ Q) [Ax; x] dt = x0ᵀ L x0`` with ``AᵀL + LA + M = 0`` and
    ``M = ψ11 AᵀQA + ψ12 (AᵀQ + QA) + ψ22 Q``.

    Parameters
    ----------
    sys : LTISystem, control.StateSpace or (A, B, C, D)
        The system whose free motion ``x = e^{At} x0`` is weighed (A Hurwitz; B, C, D are
        not used).
    x0 : (n,) array_like
        Initial state (real).
    band : Band
        The frequency range Ω.
    Q : (n, n) array_like
        Symmetric positive definite.

    Returns
    -------
    float

    Raises
    ------
    UnstableError
        If A is not Hurwitz (the integral diverges).
    DimensionError
        If ``x0`` does not have n entries or Q is not (n, n).
    ValueError
        If Q is not symmetric positive definite, or an entry is not finite and real.

    Notes
    -----
    Paper eq. (19), the infinite-horizon FD-EEF, for the free motion (``d = 0``).

    Examples
    --------
    >>> from fdsc import LTISystem
    >>> sys = LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]])
    >>> round(fdeef_autonomous(sys, [1.0], Band.lf(2.0), [[1.0]]), 12)   # ∫ 3 e^{−2t} dt
    1.5
    """
    A = _state_matrix(sys, "the infinite-horizon FD-EEF")
    x0 = as_vector("x0", x0, A.shape[0])
    Q = check_weight(Q, A.shape[0])
    check_type("band", band, Band)
    L = solve_continuous_lyapunov(A.T, -_psi_matrix(A, band, Q))
    return float(x0 @ L @ x0)


def fdeef_parseval_autonomous(sys: LTISystem, x0: ArrayLike, band: Band, Q: ArrayLike) -> float:
    """The same FD-EEF through Parseval's theorem, by quadrature over frequency.

    With ``X(jω) = (jωI − A)⁻¹ x0`` the transform of ``ẋ`` on [0, ∞) is ``jωX − x0 = AX`` (the
    initial value enters), so ``S = (1/2π) ∫ [AX; X]* (Re Ψ ⊗ Q) [AX; X] dω``. Replacing ``AX`` by
    ``jωX``, as the proof of Proposition 1 does, is valid only for ``x(0) = 0``.

    Parameters
    ----------
    sys : LTISystem, control.StateSpace or (A, B, C, D)
        The system whose free motion is weighed (A Hurwitz; B, C, D are not used).
    x0 : (n,) array_like
        Initial state (real).
    band : Band
        The frequency range Ω.
    Q : (n, n) array_like
        Symmetric positive definite.

    Returns
    -------
    float

    Raises
    ------
    UnstableError
        If A is not Hurwitz: the transform of an unstable trajectory does not exist on the
        imaginary axis, and the quadrature would return the value of the stable mirror image.
    DimensionError
        If ``x0`` does not have n entries or Q is not (n, n).
    ValueError
        If Q is not symmetric positive definite, or an entry is not finite and real.

    Notes
    -----
    Paper eq. (23), the frequency-domain form in the proof of Proposition 1, with ``AX`` in
    place of ``jωX`` (the initial value enters). Adaptive quadrature (``scipy.integrate.quad``)
    to a relative 1e-11 per interval.

    Examples
    --------
    >>> from fdsc import LTISystem
    >>> sys = LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]])
    >>> round(fdeef_parseval_autonomous(sys, [1.0], Band.lf(2.0), [[1.0]]), 9)   # = the time domain
    1.5
    """
    A = _state_matrix(sys, "the Parseval form of the FD-EEF")
    x0 = as_vector("x0", x0, A.shape[0])
    Q = check_weight(Q, A.shape[0])
    n = A.shape[0]
    p = _band(band)

    from scipy.integrate import quad  # here: a simulation needs no scipy.integrate

    def integrand(w):
        X = np.linalg.solve(1j * w * np.eye(n) - A, x0)
        Xd = A @ X
        return float((p[0, 0] * (Xd.conj() @ Q @ Xd) + 2 * p[0, 1] * (Xd.conj() @ Q @ X)
                      + p[1, 1] * (X.conj() @ Q @ X)).real)

    scale = max(1.0, float(np.abs(np.linalg.eigvals(A)).max()))
    edges = [0.0, band.lower, band.upper, scale]
    edges = sorted({e for e in edges if np.isfinite(e)})
    total = 0.0
    for a, b in zip(edges[:-1], edges[1:], strict=True):
        if b > a:
            total += quad(integrand, a, b, limit=200, epsabs=0, epsrel=1e-11)[0]
    total += quad(integrand, edges[-1], np.inf, limit=200, epsabs=0, epsrel=1e-11)[0]
    return total / np.pi  # (1/2π) ∫_{-∞}^{∞} = (1/π) ∫_0^∞ for the even real weight
