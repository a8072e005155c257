"""The divergence monitor of every simulator: one rule, written once. Internal.

A switched loop of Hurwitz modes can diverge under its law although each mode alone is stable;
its states then stay finite for a long time, and a run that only checks for overflow would
return a finite number for it. Every simulator (:func:`fdsc.simulate.simulate`,
:func:`fdsc.stream.simulate_stream`, :func:`fdsc.stream.simulate_batch`, and
:meth:`fdsc.design.FDSC.simulate` through :func:`~fdsc.simulate.simulate`) therefore compares
the state with a bound that no single mode can exceed.

**The rule.** For a Hurwitz mode ``ẋ = A_i x + B d`` let ``P_i`` solve the Lyapunov equation
``A_iᵀ P_i + P_i A_i = −I``, with extreme eigenvalues ``λ_min ≤ λ_max``. Along the free motion
``V = xᵀ P_i x`` satisfies ``V̇ = −‖x‖² ≤ −V / λ_max``, so
``‖e^{A_i t}‖ ≤ κ_i e^{−t / (2 λ_max)}`` with ``κ_i = √(λ_max / λ_min)``, and by the variation
of constants the state of mode i alone, from ``x0`` under any disturbance with
``|d(t)| ≤ d_max``, obeys for all t ≥ 0

    ‖x(t)‖ ≤ R_i = κ_i (‖x0‖ + 2 λ_max ‖B‖ d_max).

``d_max`` is ``Σ_k |a_k|`` for a :class:`~fdsc.signals.Sinusoids` (the largest over the parts of
a :class:`~fdsc.signals.Piecewise`) and ``max_k |u_k|`` for a :class:`~fdsc.signals.Sampled`
input (a zero- or first-order hold of the samples never exceeds it). With
``R = max_i R_i`` the monitor flags a run at the first checked point where

    max_r |x_r| > SAFETY · R,     SAFETY = 1e6,

and reports the time and the growth ``‖x‖ / R``.

**Why it cannot fire on a run that stays bounded as its modes do.** ``max_r |x_r| ≤ ‖x‖₂``, so
a flag means ``‖x(t_k)‖ > 10⁶ R``. The simulators' steps are exact discretizations (rounding
aside), so an LTI run (one mode) satisfies ``‖x(t_k)‖ ≤ R`` at every grid point and can never be
flagged: the factor 10⁶ leaves twelve orders of magnitude for rounding (the step's relative
error is about 1e-13). A switched run is flagged only when switching has amplified its state to
a million times more than any of its modes can reach alone from the same initial state under the
same input: every switched run whose state stays below that bound (in particular every run that
converges without such a transient) is never flagged. A run that diverges exponentially reaches
the bound after ``ln(10⁶ R / ‖x0‖) / rate`` seconds, and is flagged from there on.

If a mode is not Hurwitz, ``R = ∞`` and the monitor is off: the simulators already warn about
such a mode (:class:`~fdsc.exceptions.UnstableRunWarning`).

**Cost.** The compiled streaming loop checks the state once per block of 1024 steps and at the
last point (n comparisons per block); :func:`fdsc.simulate.simulate` checks its whole trajectory
with one vectorized maximum after the run.
"""

import math

import numpy as np
from scipy.linalg import solve_continuous_lyapunov

from .signals import Piecewise, Sampled, Sinusoids

__all__ = []

#: The monitor's safety factor: a run is flagged when its state exceeds SAFETY times the largest
#: state any of its modes reaches alone from the same initial state under the same input.
SAFETY = 1e6


def norm(v) -> float:
    """The Euclidean norm of ``v`` without overflow on the way (``np.linalg.norm`` squares the
    entries: ``[1e200]`` would give ``inf``).

    Examples
    --------
    >>> norm([3.0 * 2.0**700, 4.0 * 2.0**700]) == 5.0 * 2.0**700, norm([0.0, 0.0])
    (True, 0.0)
    """
    v = np.asarray(v, dtype=float).ravel()
    big = float(np.abs(v).max()) if v.size else 0.0
    if big == 0.0 or not np.isfinite(big):
        return big
    e = math.frexp(big)[1]          # scaled by a power of two: exact
    return math.ldexp(float(np.sqrt(np.sum(np.ldexp(v, -e) ** 2))), e)


def input_bound(d) -> float:
    """An upper bound of ``|d(t)|`` over the whole run (see the module docstring)."""
    if isinstance(d, Sinusoids):
        return float(np.sum(np.abs(d.amplitudes)))
    if isinstance(d, Piecewise):
        return max([0.0] + [input_bound(p) for p in d.parts])
    if isinstance(d, Sampled):
        return float(np.max(np.abs(d.values))) if d.values.size else 0.0
    raise TypeError(f"d must be Sinusoids, Piecewise or Sampled, found {type(d).__name__}")


def mode_bound(A, B, x0_norm: float, d_max: float) -> float:
    """``R_i = κ_i (‖x0‖ + 2 λ_max ‖B‖ d_max)``, a bound of the state of ``ẋ = A x + B d`` for
    all t ≥ 0 (``inf`` if A is not Hurwitz).

    Examples
    --------
    >>> mode_bound(np.array([[-1.0]]), np.array([[1.0]]), 1.0, 1.0)    # P = 1/2: 1 + 1
    2.0
    >>> mode_bound(np.array([[0.0]]), np.array([[1.0]]), 1.0, 0.0)
    inf
    """
    A = np.asarray(A, dtype=float)
    if A.size == 0 or not np.all(np.isfinite(A)) or np.linalg.eigvals(A).real.max() >= 0:
        return np.inf
    n = A.shape[0]
    P = solve_continuous_lyapunov(A.T, -np.eye(n))
    lam = np.linalg.eigvalsh((P + P.T) / 2)
    if not np.all(np.isfinite(lam)) or lam[0] <= 0:
        return np.inf
    kappa = np.sqrt(lam[-1] / lam[0])
    return float(kappa * (x0_norm + 2.0 * lam[-1] * np.linalg.norm(B, 2) * d_max))


def state_bound(A_modes, B, x0, d) -> float:
    """``R = max_i R_i`` over the modes' state matrices ``A_modes`` (``inf`` if one is not
    Hurwitz).

    Examples
    --------
    >>> from fdsc.signals import Sinusoids
    >>> state_bound([np.array([[-1.0]]), np.array([[-2.0]])], np.array([[1.0]]), [1.0],
    ...             Sinusoids([0.5], [1.0]))
    1.5
    """
    x0n = norm(x0)
    dm = input_bound(d)
    B = np.asarray(B, dtype=float).reshape(len(np.asarray(A_modes[0])), -1)
    return max(mode_bound(a, B, x0n, dm) for a in A_modes)


def threshold(A_modes, B, x0, d) -> float:
    """``SAFETY · R``: the monitor flags a point whose ``max_r |x_r|`` exceeds it."""
    with np.errstate(over="ignore"):
        return float(SAFETY * state_bound(A_modes, B, x0, d))


def message(where: str, t: float, growth: float, bound: float) -> str:
    """The warning of a flagged run."""
    return (f"{where}the switched run diverges: at t = {t:.6g} s its state is {growth:.3g} times "
            f"the largest any of its modes reaches alone from the same x0 under the same "
            f"disturbance (R = {bound:.3g}; flagged above {SAFETY:.0e} R); its finite numbers "
            "do not describe a bounded run")
