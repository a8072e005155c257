"""Matrix products to about twice the working precision (error-free transformations).

Internal: the similarities into a stiff loop's separated coordinates (:mod:`fdsc._blocks`) and
into its modal coordinates (:mod:`fdsc._closed_energy`). In such coordinates the slow entries of
``S⁻¹ A S`` and ``C S`` are small sums of large terms (a pole at −2·10⁵ /s beside poles near
−2 /s: terms of 10⁷, results of 1), and an ordinary product leaves them with an absolute error
of ε times the terms; here every product ``a b`` and every partial sum carries its rounding error
along (Dekker's splitting, Knuth's two-sum: Ogita, Rump and Oishi's Dot2), so the result is the
exact product rounded, plus about ε² times the terms. Entries must stay below about 10³⁰⁰ (the
splitting multiplies them by 2²⁷ + 1).
"""

import numpy as np

__all__ = []

# Dekker's splitting constant for binary64: 2^27 + 1
_SPLIT = 134217729.0


def _two_product(a, b):
    """``(p, e)`` with ``p = fl(a b)`` and ``a b = p + e`` exactly (elementwise)."""
    p = a * b
    c = _SPLIT * a
    ah = c - (c - a)
    c = _SPLIT * b
    bh = c - (c - b)
    al, bl = a - ah, b - bh
    return p, ((ah * bh - p) + ah * bl + al * bh) + al * bl


def product(X, Y):
    """``(hi, lo)`` with ``hi + lo = X Y`` to about ε² of ``|X| |Y|``; ``hi`` is the product
    rounded. X (m, k) and Y (k, r), real."""
    X, Y = np.asarray(X, dtype=float), np.asarray(Y, dtype=float)
    if X.shape[1] == 0:
        z = np.zeros((X.shape[0], Y.shape[1]))
        return z, z.copy()
    p, e = _two_product(X[:, :, None], Y[None, :, :])
    hi, lo = p[:, 0, :], e[:, 0, :].copy()
    for j in range(1, X.shape[1]):
        t = hi + p[:, j, :]
        z = t - hi
        lo += ((hi - (t - z)) + (p[:, j, :] - z)) + e[:, j, :]
        hi = t
    t = hi + lo
    return t, lo - (t - hi)


def dot(X, Y):
    """``X Y`` rounded once (see :func:`product`)."""
    return product(X, Y)[0]


def similar(Si, A, S):
    """``S⁻¹ A S`` (given S⁻¹), the intermediate ``A S`` kept to twice the precision."""
    hi, lo = product(A, S)
    a, b = product(Si, hi)
    return a + (b + Si @ lo)


def refined_inverse(S, Si=None):
    """S⁻¹ (given, or ``np.linalg.inv(S)``) refined by one Newton step ``X ← X + X (I − S X)``,
    the residual formed by :func:`product`: the similarity ``S⁻¹ A S`` is then one of A to
    rounding, rather than to the inverse's own error (about ε times S's condition number)."""
    Si = np.linalg.inv(S) if Si is None else Si
    hi, lo = product(S, Si)
    return Si + Si @ ((np.eye(S.shape[0]) - hi) - lo)
