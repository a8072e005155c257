"""Blocks of the generalized KYP lemma, built once for Lemma 1, Theorem 1 and the synthesis LMIs.

Lemma 1 (:mod:`fdsc.lmi`) and Theorem 1 (:mod:`fdsc.switching`) are assembled here entirely; the
synthesis LMIs (:mod:`fdsc.synthesis`) take their supply rate from here.

Every frequency-domain inequality of the paper is a sum of three blocks:

* the **weight** ``W = Φ⊗P + Σ_k s_k Ψ_k⊗Q_k`` (one term, s = +1, for Lemma 1; the two terms
  ``+Ψ_i⊗Q_i`` and ``−Ψ_j⊗Q_j`` for Theorem 1);
* the **outer product** ``Fᵀ W F`` with ``F = [A B; I 0]``, or ``F = [A; I]`` when there is no
  input (the Lyapunov-type inequality (T1-1));
* the **supply rate** ``Gᵀ diag(I, −g I) G`` with ``G = [C D; 0 I]`` and ``g = γ²``.

:func:`kyp_matrix` adds them. Hermitian P and Q (complex for the MF band, whose Ψ is complex) are
passed as pairs ``(re, im)`` of real matrices, and every function returns the real and imaginary
parts separately, so that the same code builds NumPy values (to verify a certificate) and cvxpy
expressions over real variables (posed through the real embedding of :mod:`fdsc.lmi`). With
``Ψ = Ψ_re + j Ψ_im`` and ``Q = Q_re + j Q_im``::

    Ψ⊗Q = (Ψ_re⊗Q_re − Ψ_im⊗Q_im) + j (Ψ_re⊗Q_im + Ψ_im⊗Q_re).

The sums are formed left to right in the order written above (Φ⊗P first, then the terms in the
order given). The order matters beyond algebra: it decides the last bits of a NumPy value and
the order in which cvxpy numbers the variables, and an interior-point solver's answer to an
ill-conditioned LMI moves with that order.
"""

from __future__ import annotations

from collections.abc import Sequence

import cvxpy as cp
import numpy as np

from .bands import PHI
from .exceptions import DimensionError

__all__ = ["kyp_weight", "kyp_outer", "supply_parts", "kyp_matrix", "BACKENDS"]

#: Names of the array backends: NumPy values or cvxpy expressions.
BACKENDS = ("numpy", "cvxpy")

#: A matrix argument: NumPy values or a cvxpy expression.
Matrix = np.ndarray | cp.Expression


def _shape(name, value, expected):
    """Check the shape of an array or cvxpy expression without copying it."""
    found = tuple(np.shape(value))
    if found != tuple(expected):
        raise DimensionError(f"{name}: expected shape {tuple(expected)} but found {found}")


def _matrix_shape(name, value):
    """Shape of a 2-D array (checked without copying)."""
    if np.ndim(value) != 2:
        raise DimensionError(f"{name} must be a 2-D array, but found shape {np.shape(value)}")
    return np.shape(value)


def _square(name, value):
    """Size n of a square 2-D array (shape checked without copying)."""
    if np.ndim(value) != 2 or np.shape(value)[0] != np.shape(value)[1]:
        raise DimensionError(f"{name} must be a square 2-D array, but found shape {np.shape(value)}")
    return np.shape(value)[0]


def _pair(name, value, n=None):
    """``(re, im)`` of a Hermitian argument given either as one real matrix or as a pair."""
    re, im = value if isinstance(value, tuple) else (value, None)
    if not isinstance(re, cp.Expression):
        re = np.asarray(re)
    if im is not None and not isinstance(im, cp.Expression):
        im = np.asarray(im)
    if n is None:
        n = _square(f"{name} (real part)", re)
    _shape(f"{name} (real part)", re, (n, n))
    if im is not None:
        _shape(f"{name} (imaginary part)", im, (n, n))
    return re, im


def _add(acc, term, sign):
    if acc is None:
        return term if sign > 0 else -term
    return acc + term if sign > 0 else acc - term


def kyp_weight(P: Matrix | tuple, terms: Sequence[tuple] = (), *,
               backend: str = "numpy") -> tuple[Matrix, Matrix | None]:
    """Real and imaginary parts of the weight ``Φ⊗P + Σ_k s_k Ψ_k⊗Q_k``.

    Parameters
    ----------
    P : (n, n) array_like, cvxpy.Expression, or tuple (re, im) of them
        The Hermitian multiplier of Φ; a single matrix is real, a pair holds the real part and
        the (skew-symmetric) imaginary part, ``im`` may be None.
    terms : sequence of (psi, Q, sign)
        The band terms: ``psi`` a (2, 2) array_like (complex for MF, e.g. :attr:`Band.psi`),
        ``Q`` given like ``P``, ``sign`` +1 or −1. Empty for the entire frequency range.
    backend : {"numpy", "cvxpy"}, optional
        Kronecker products by :func:`numpy.kron` (values) or :func:`cvxpy.kron` (expressions;
        numeric operands become cvxpy constants).

    Returns
    -------
    re : (2n, 2n) ndarray or cvxpy.Expression
        Real part.
    im : (2n, 2n) ndarray, cvxpy.Expression or None
        Imaginary part; None if neither P, any Q nor any Ψ has one.

    Raises
    ------
    ValueError
        If ``backend`` is not one of :data:`BACKENDS` or a ``sign`` is not ±1.
    DimensionError
        If a Ψ is not (2, 2) or a Q does not have P's shape.

    Notes
    -----
    Φ = [[0, 1], [1, 0]] is continuous time (:data:`fdsc.PHI`). The weight is the middle factor of
    Lemma 1 (paper eq. (7)) and of Theorem 1 (paper eqs. (33) and (34)).

    Examples
    --------
    The LF weight with ϖ_l = 2 and P = Q = 1 is ``[[−1, 1], [1, 4]]``:

    >>> from fdsc import Band
    >>> re, im = kyp_weight(np.eye(1), [(Band.lf(2.0).psi, np.eye(1), 1)])
    >>> re, im
    (array([[-1.,  1.],
           [ 1.,  4.]]), None)

    The MF Ψ is complex, so the weight has an imaginary part:

    >>> re, im = kyp_weight(np.eye(1), [(Band.mf(1.0, 3.0).psi, np.eye(1), 1)])
    >>> im
    array([[ 0.,  2.],
           [-2.,  0.]])
    """
    if backend not in BACKENDS:
        raise ValueError(f"backend must be one of {BACKENDS}, but found {backend!r}")
    kron = cp.kron if backend == "cvxpy" else np.kron
    P_re, P_im = _pair("P", P)
    n = P_re.shape[0]
    re = kron(PHI, P_re)
    im = None if P_im is None else kron(PHI, P_im)
    for k, (psi, Q, sign) in enumerate(terms):
        if sign not in (1, -1):
            raise ValueError(f"terms[{k}]: sign must be 1 or -1, but found {sign!r}")
        psi = np.asarray(psi)
        _shape(f"terms[{k}] psi", psi, (2, 2))
        Q_re, Q_im = _pair(f"terms[{k}] Q", Q, n)
        psi_re = psi.real
        psi_im = psi.imag if np.iscomplexobj(psi) and np.any(psi.imag != 0) else None
        re = _add(re, kron(psi_re, Q_re), sign)
        if psi_im is not None and Q_im is not None:
            re = _add(re, kron(psi_im, Q_im), -sign)
        if Q_im is not None:
            im = _add(im, kron(psi_re, Q_im), sign)
        if psi_im is not None:
            im = _add(im, kron(psi_im, Q_re), sign)
    return re, im


def kyp_outer(W: Matrix, A: np.ndarray, B: np.ndarray | None = None) -> Matrix:
    """The outer product ``Fᵀ W F`` with ``F = [A B; I 0]``, or ``F = [A; I]`` if B is None.

    Parameters
    ----------
    W : (2n, 2n) ndarray or cvxpy.Expression
        The weight (one real part of :func:`kyp_weight`).
    A : (n, n) array_like
        State matrix.
    B : (n, m) array_like, optional
        Input matrix; None for the input-free form ``[A; I]ᵀ W [A; I]`` of (T1-1).

    Returns
    -------
    (n + m, n + m) or (n, n) ndarray or cvxpy.Expression
        Like ``W``.

    Raises
    ------
    DimensionError
        If A is not square, B has not n rows, or W is not (2n, 2n).

    Notes
    -----
    The first term of Lemma 1 (paper eq. (7)) and of paper eqs. (33) and (34).

    Examples
    --------
    With Φ⊗P alone the outer product is the Lyapunov form ``AᵀP + PA``:

    >>> A = np.array([[-1.0, 2.0], [0.0, -3.0]])
    >>> W, _ = kyp_weight(np.eye(2))
    >>> kyp_outer(W, A)
    array([[-2.,  2.],
           [ 2., -6.]])
    """
    A = np.asarray(A)
    n = _square("A", A)
    _shape("W", W, (2 * n, 2 * n))
    if B is None:
        F = np.vstack([A, np.eye(n)])
    else:
        B = np.asarray(B)
        m = _matrix_shape("B", B)[1]
        _shape("B", B, (n, m))
        F = np.block([[A, B], [np.eye(n), np.zeros((n, m))]])
    return F.T @ W @ F


def supply_parts(C: np.ndarray, D: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The two constant parts of the supply rate ``Gᵀ diag(I, −g I) G``, ``G = [C D; 0 I]``.

    The supply rate is affine in ``g = γ²``: it equals ``out − g·inn``. Returning the parts keeps
    ``g`` free to be a number or a cvxpy variable.

    Parameters
    ----------
    C : (p, n) array_like
        Output matrix.
    D : (p, m) array_like
        Feedthrough matrix.

    Returns
    -------
    out : (n + m, n + m) ndarray
        ``Gᵀ diag(I_p, 0) G = [C D]ᵀ [C D]``.
    inn : (n + m, n + m) ndarray
        ``Gᵀ diag(0, I_m) G = diag(0, I_m)``.

    Raises
    ------
    DimensionError
        If C is not 2-D or D does not have C's number of rows.

    Notes
    -----
    The second term of Lemma 1 (paper eq. (7)) and of paper eq. (34).

    Examples
    --------
    >>> out, inn = supply_parts(np.array([[1.0, 2.0]]), np.array([[0.5]]))
    >>> out
    array([[1.  , 2.  , 0.5 ],
           [2.  , 4.  , 1.  ],
           [0.5 , 1.  , 0.25]])
    >>> np.diag(inn)
    array([0., 0., 1.])
    """
    C, D = np.asarray(C), np.asarray(D)
    p, n = _matrix_shape("C", C)
    m = _matrix_shape("D", D)[1]
    _shape("D", D, (p, m))
    G = np.block([[C, D], [np.zeros((m, n)), np.eye(m)]])
    Z = np.zeros((m, p))
    pi_out = np.block([[np.eye(p), Z.T], [Z, np.zeros((m, m))]])
    pi_in = np.block([[np.zeros((p, p)), Z.T], [Z, np.eye(m)]])
    return G.T @ pi_out @ G, G.T @ pi_in @ G


def kyp_matrix(A: np.ndarray, B: np.ndarray, C: np.ndarray, D: np.ndarray, P: Matrix | tuple,
               terms: Sequence[tuple], g: float | cp.Expression, *,
               backend: str = "numpy") -> tuple[Matrix, Matrix | None]:
    """Real and imaginary parts of ``Fᵀ(Φ⊗P + Σ_k s_k Ψ_k⊗Q_k)F + Gᵀ diag(I, −g I) G``.

    Parameters
    ----------
    A : (n, n) array_like
        State matrix.
    B : (n, m) array_like
        Input matrix.
    C : (p, n) array_like
        Output matrix.
    D : (p, m) array_like
        Feedthrough matrix.
    P : (n, n) array_like, cvxpy.Expression, or tuple (re, im) of them
        Multiplier of Φ (see :func:`kyp_weight`).
    terms : sequence of (psi, Q, sign)
        Band terms (see :func:`kyp_weight`).
    g : float or cvxpy.Expression
        γ², the squared gain bound (a scalar variable when minimized).
    backend : {"numpy", "cvxpy"}, optional
        See :func:`kyp_weight`.

    Returns
    -------
    re : (n + m, n + m) ndarray or cvxpy.Expression
        Real part (symmetric in value; a cvxpy expression need not be symmetric as written).
    im : (n + m, n + m) ndarray, cvxpy.Expression or None
        Imaginary part (skew-symmetric), None for real data.

    Raises
    ------
    ValueError, DimensionError
        As for :func:`kyp_weight`, :func:`kyp_outer` and :func:`supply_parts`.

    Notes
    -----
    With one term ``(Ψ, Q, 1)`` this is the matrix of Lemma 1, paper eq. (7) (no term: the bounded
    real lemma); with the terms ``(Ψ_i, Q_i, 1)`` and ``(Ψ_j, Q_j, −1)`` it is Theorem 1's
    (T1-2), paper eq. (34).

    Examples
    --------
    ``G(s) = 1/(s + 1)`` on the entire range with P = 1 and γ² = 2:

    >>> re, im = kyp_matrix([[-1.0]], [[1.0]], [[1.0]], [[0.0]], np.eye(1), [], 2.0)
    >>> re
    array([[-1.,  1.],
           [ 1., -2.]])
    >>> bool(np.linalg.eigvalsh(re).max() < 0), im is None
    (True, True)
    """
    n = _square("A", A)
    _pair("P", P, n)
    W_re, W_im = kyp_weight(P, terms, backend=backend)
    m = _matrix_shape("B", B)[1]
    p = _matrix_shape("C", C)[0]
    _shape("C", C, (p, n))
    _shape("D", D, (p, m))
    out, inn = supply_parts(C, D)
    re = kyp_outer(W_re, A, B) + out - g * inn
    im = None if W_im is None else kyp_outer(W_im, A, B)
    return re, im
