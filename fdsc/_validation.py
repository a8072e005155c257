"""Input validation shared by the public functions (one place, one message style).

Every public function of fdsc validates its arguments through these helpers, so that a bad
input gets the same kind of message everywhere: the argument's name, what was expected and what
was found. Complex input is an error (not a ``ComplexWarning``) wherever a real value is expected.
"""

import math
import numbers

import numpy as np

from .exceptions import DimensionError, UnstableError

__all__ = ["as_matrix", "as_vector", "as_positive", "as_finite_real", "as_nonnegative",
           "as_count", "as_choice", "frozen_array", "check_hurwitz", "check_type"]


def frozen_array(a):
    """Return a read-only copy of ``a``."""
    a = np.array(a, copy=True)
    a.setflags(write=False)
    return a


def _to_array(name, value, dtype, what):
    raw = value
    if not isinstance(raw, np.ndarray):
        try:
            raw = np.asarray(value)
        except (TypeError, ValueError) as exc:
            raise ValueError(f"{name} must be a numeric {what}; could not convert it: {exc}") from None
    if raw.dtype.kind in "USOV" and raw.dtype != object:
        raise ValueError(f"{name} must be a numeric {what}, but found entries of type {raw.dtype}")
    if raw.dtype.kind == "b":
        raise ValueError(f"{name} must be a numeric {what}, but found booleans")
    if dtype is not complex and np.iscomplexobj(raw):
        if np.any(np.imag(raw) != 0):
            raise ValueError(f"{name} must be real, but found complex entries "
                             f"(e.g. {raw.flat[np.flatnonzero(np.imag(raw))[0]]})")
        raw = np.real(raw)
    try:
        return np.array(raw, dtype=dtype)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a numeric {what}; could not convert it: {exc}") from None


def as_matrix(name, value, shape=None, *, dtype=float, square=False):
    """Validate a 2-D finite array and return a read-only copy.

    Parameters
    ----------
    name : str
        Argument name used in error messages.
    value : array_like
        The candidate matrix.
    shape : tuple of (int or None), optional
        Expected shape; ``None`` entries are free.
    dtype : {float, complex}, optional
        ``float`` (default: complex input is an error unless its imaginary part is exactly 0)
        or ``complex``.
    square : bool, optional
        Require a square matrix.

    Returns
    -------
    numpy.ndarray
        Read-only 2-D array.

    Raises
    ------
    DimensionError
        If the array is not 2-D, not square when required, or of the wrong shape.
    ValueError
        If an entry is NaN, infinite, complex (for ``dtype=float``) or not numeric.

    Examples
    --------
    >>> as_matrix("A", [[1, 2]], (1, 2))
    array([[1., 2.]])
    >>> as_matrix("A", [[1j]])
    Traceback (most recent call last):
    ...
    ValueError: A must be real, but found complex entries (e.g. 1j)
    """
    arr = _to_array(name, value, dtype, "matrix")
    if arr.ndim != 2:
        raise DimensionError(f"{name} must be a 2-D array, but found {arr.ndim}-D shape {arr.shape}")
    if square and arr.shape[0] != arr.shape[1]:
        raise DimensionError(f"{name} must be square, but found shape {arr.shape}")
    if shape is not None:
        expected = tuple(arr.shape[i] if s is None else s for i, s in enumerate(shape))
        if arr.shape != expected:
            raise DimensionError(f"{name}: expected shape {expected} but found {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must have finite entries (no NaN or inf)")
    arr.setflags(write=False)
    return arr


def as_vector(name, value, size=None, *, allow_scalar=True):
    """Validate a finite real 1-D array (a scalar counts as one entry) and return a read-only copy.

    Raises
    ------
    DimensionError
        If the array is not 1-D or has the wrong number of entries.
    ValueError
        If an entry is NaN, infinite, complex or not numeric.

    Examples
    --------
    >>> as_vector("x0", [1, 2], 2)
    array([1., 2.])
    """
    arr = _to_array(name, value, float, "vector")
    if arr.ndim == 0 and allow_scalar:
        arr = arr.reshape(1)
    if arr.ndim != 1:
        raise DimensionError(f"{name} must be a 1-D array, but found shape {arr.shape}")
    if size is not None and arr.size != size:
        raise DimensionError(f"{name}: expected {size} entries but found {arr.size}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must have finite entries (no NaN or inf)")
    arr.setflags(write=False)
    return arr


def _real_number(name, value, what):
    if isinstance(value, bool | np.bool_) or not isinstance(value, numbers.Real):
        if isinstance(value, np.ndarray) and value.ndim == 0 and value.dtype.kind in "iuf":
            return float(value)
        raise ValueError(f"{name} must be {what}, but found {value!r} of type {type(value).__name__}")
    return float(value)


def as_finite_real(name, value):
    """Return ``value`` as a finite float or raise ``ValueError`` naming ``name``.

    Strings, booleans and complex numbers are rejected (no silent conversion).
    """
    x = _real_number(name, value, "a real number")
    if not math.isfinite(x):
        raise ValueError(f"{name} must be finite, but found {x}")
    return x


def as_positive(name, value, *, allow_inf=False):
    """Return ``value`` as a float > 0 (optionally +inf) or raise ``ValueError`` naming ``name``."""
    x = _real_number(name, value, "a positive number")
    if math.isnan(x) or x <= 0 or (math.isinf(x) and not allow_inf):
        raise ValueError(f"{name} must be a positive finite number, but found {x}")
    return x


def as_nonnegative(name, value):
    """Return ``value`` as a finite float ≥ 0 or raise ``ValueError`` naming ``name``."""
    x = as_finite_real(name, value)
    if x < 0:
        raise ValueError(f"{name} must be >= 0, but found {x}")
    return x


def as_count(name, value, minimum=1):
    """Return ``value`` as an int ≥ ``minimum`` (integral numbers only) or raise ``ValueError``."""
    integral = isinstance(value, numbers.Integral) or (
        isinstance(value, numbers.Real) and float(value).is_integer())
    if isinstance(value, bool | np.bool_) or not integral:
        raise ValueError(f"{name} must be an integer >= {minimum}, but found {value!r}")
    k = int(value)
    if k < minimum:
        raise ValueError(f"{name} must be an integer >= {minimum}, but found {k}")
    return k


def as_choice(name, value, choices):
    """Return ``value`` if it is one of ``choices``, else raise ``ValueError`` listing them.

    Examples
    --------
    >>> as_choice("kernel", "numpy", ("numba", "numpy"))
    'numpy'
    """
    try:
        ok = value in choices
    except TypeError:
        ok = False
    if not ok:
        raise ValueError(f"{name} must be one of {tuple(choices)}, but found {value!r}")
    return value


def check_type(name, value, cls, what=None):
    """Raise ``TypeError`` naming ``name`` unless ``value`` is an instance of ``cls``."""
    if not isinstance(value, cls):
        what = what or f"an fdsc.{cls.__name__}"
        raise TypeError(f"{name} must be {what}, but found {type(value).__name__}")
    return value


def check_hurwitz(name, A, what="this computation"):
    """Raise :class:`UnstableError` naming the eigenvalue with the largest real part unless every
    eigenvalue of ``A`` has a negative real part.

    Examples
    --------
    >>> check_hurwitz("sys", np.array([[1.0]]), "the band peak")
    Traceback (most recent call last):
    ...
    fdsc.exceptions.UnstableError: sys is not stable: A has the eigenvalue 1 with real part >= 0; \
the band peak needs a Hurwitz A
    """
    ev = np.linalg.eigvals(np.asarray(A, dtype=float))
    if ev.size and ev.real.max() >= 0:
        worst = ev[np.argmax(ev.real)]
        lam = f"{worst.real:.6g}" if worst.imag == 0 else f"{worst:.6g}"
        raise UnstableError(f"{name} is not stable: A has the eigenvalue {lam} with real part >= 0; "
                            f"{what} needs a Hurwitz A", complex(worst))
    return ev
