"""Seeded random systems: the one maker used by the tests, the chapters and the cross-checks.

Every function draws from a NumPy ``Generator`` passed by the caller, in a fixed order, so a seed
fixes the system on every machine.
"""

import numpy as np

from ._validation import as_count, check_type
from .plant import LTISystem, Plant

__all__ = ["random_hurwitz", "random_system", "random_plant", "random_spd"]


def _rng(rng):
    check_type("rng", rng, np.random.Generator)
    return rng


def _abscissa(abscissa):
    lo, hi = (float(a) for a in abscissa)
    if not lo < hi < 0:
        raise ValueError(f"abscissa must be (lo, hi) with lo < hi < 0, but found {abscissa!r}")
    return lo, hi


def random_hurwitz(rng: np.random.Generator, n: int, *,
                   abscissa: tuple[float, float] = (-2.0, -0.2)) -> np.ndarray:
    """A random real (n, n) matrix shifted so that its spectral abscissa is uniform in ``abscissa``.

    Draws a standard normal matrix, then one uniform number.

    Parameters
    ----------
    rng : numpy.random.Generator
        Source of randomness.
    n : int
        Size of the matrix (≥ 1).
    abscissa : (float, float), optional
        Range ``(lo, hi)``, ``lo < hi < 0``, of the largest real part of the eigenvalues.

    Returns
    -------
    (n, n) ndarray
        A Hurwitz matrix.

    Raises
    ------
    TypeError
        If ``rng`` is not a ``numpy.random.Generator``.
    ValueError
        If ``n`` is not an integer ≥ 1 or ``abscissa`` is not ``lo < hi < 0``.

    Examples
    --------
    >>> A = random_hurwitz(np.random.default_rng(0), 3)
    >>> bool(np.linalg.eigvals(A).real.max() < -0.2 + 1e-12)
    True
    """
    rng = _rng(rng)
    n = as_count("n", n)
    lo, hi = _abscissa(abscissa)
    A = rng.standard_normal((n, n))
    return A - (np.max(np.linalg.eigvals(A).real) + rng.uniform(-hi, -lo)) * np.eye(n)


def random_system(rng: np.random.Generator, n: int, m: int = 1, p: int = 1, *,
                  abscissa: tuple[float, float] = (-2.0, -0.2), direct: bool = False) -> LTISystem:
    """A random stable :class:`~fdsc.LTISystem` with n states, m inputs and p outputs.

    Draws A by :func:`random_hurwitz`, then B (n, m), C (p, n) and, if ``direct``, D (p, m),
    all standard normal (D scaled by 0.3).

    Parameters
    ----------
    rng : numpy.random.Generator
        Source of randomness.
    n, m, p : int
        Numbers of states, inputs and outputs (≥ 1).
    abscissa : (float, float), optional
        Range of the spectral abscissa of A (see :func:`random_hurwitz`).
    direct : bool, optional
        Draw a nonzero feedthrough D (default zero).

    Returns
    -------
    LTISystem

    Raises
    ------
    TypeError
        If ``rng`` is not a ``numpy.random.Generator``.
    ValueError
        If a size is not an integer ≥ 1 or ``abscissa`` is not ``lo < hi < 0``.

    Examples
    --------
    >>> sys = random_system(np.random.default_rng(1), 4, 2, 3, direct=True)
    >>> sys.A.shape, sys.D.shape, sys.is_hurwitz()
    ((4, 4), (3, 2), True)
    """
    A = random_hurwitz(rng, n, abscissa=abscissa)
    m, p = as_count("m", m), as_count("p", p)
    B = rng.standard_normal((A.shape[0], m))
    C = rng.standard_normal((p, A.shape[0]))
    D = 0.3 * rng.standard_normal((p, m)) if direct else np.zeros((p, m))
    return LTISystem(A, B, C, D)


def random_plant(rng: np.random.Generator, n: int = 2, *, stable: bool = False,
                 abscissa: tuple[float, float] = (-1.0, -0.1)) -> Plant:
    """A random plant with n states, one disturbance, one control and ``z = [c x; u]``.

    Draws A (standard normal, shifted by :func:`random_hurwitz` if ``stable``), then B1, B2 and
    the row c.

    Parameters
    ----------
    rng : numpy.random.Generator
        Source of randomness.
    n : int, optional
        Number of states (≥ 1).
    stable : bool, optional
        Make A Hurwitz with spectral abscissa in ``abscissa``; otherwise A is drawn unrestricted
        (mostly unstable).
    abscissa : (float, float), optional
        Range of the spectral abscissa of A when ``stable``.

    Returns
    -------
    Plant
        With ``B1, B2`` of shape (n, 1), ``C = [c; 0]`` of shape (2, n), ``D1 = 0`` and
        ``D2 = [0; 1]``: the regulated output penalizes one state combination and the control.

    Raises
    ------
    TypeError
        If ``rng`` is not a ``numpy.random.Generator``.
    ValueError
        If ``n`` is not an integer ≥ 1 or, when ``stable``, ``abscissa`` is not
        ``lo < hi < 0``.

    Examples
    --------
    >>> plant = random_plant(np.random.default_rng(7), 3, stable=True)
    >>> plant.A.shape, plant.C.shape, plant.D2.ravel().tolist()
    ((3, 3), (2, 3), [0.0, 1.0])
    """
    rng = _rng(rng)
    n = as_count("n", n)
    A = random_hurwitz(rng, n, abscissa=abscissa) if stable else rng.standard_normal((n, n))
    return Plant(A, rng.standard_normal((n, 1)), rng.standard_normal((n, 1)),
                 np.vstack([rng.standard_normal((1, n)), np.zeros((1, n))]), np.zeros((2, 1)),
                 np.array([[0.0], [1.0]]))


def random_spd(rng: np.random.Generator, n: int, *, condition: float | None = None) -> np.ndarray:
    """A random symmetric positive-definite (n, n) matrix.

    Without ``condition``: ``M Mᵀ + 10⁻³ I`` with M standard normal (Wishart-like). With it: a
    random orthogonal basis and eigenvalues spaced geometrically from 1 to ``1/condition``.

    Parameters
    ----------
    rng : numpy.random.Generator
        Source of randomness.
    n : int
        Size (≥ 1).
    condition : float, optional
        Condition number of the result (≥ 1).

    Returns
    -------
    (n, n) ndarray
        Symmetric positive definite.

    Raises
    ------
    TypeError
        If ``rng`` is not a ``numpy.random.Generator``.
    ValueError
        If ``n`` is not an integer ≥ 1 or ``condition`` is below 1.

    Examples
    --------
    >>> Q = random_spd(np.random.default_rng(0), 3, condition=1e4)
    >>> round(float(np.linalg.cond(Q)), 6)
    10000.0
    """
    rng = _rng(rng)
    n = as_count("n", n)
    M = rng.standard_normal((n, n))
    Q = M @ M.T + 1e-3 * np.eye(n)
    if condition is not None:
        if not float(condition) >= 1:
            raise ValueError(f"condition must be >= 1, but found {condition!r}")
        U, _ = np.linalg.qr(rng.standard_normal((n, n)))
        Q = U @ np.diag(np.geomspace(1.0, 1.0 / condition, n)) @ U.T
    return Q
