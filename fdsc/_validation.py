"""Input validation shared by the public functions (one place, one message style)."""

import math

import numpy as np

from .exceptions import DimensionError

__all__ = ["as_matrix", "as_positive", "as_finite_real", "frozen_array"]


def frozen_array(a):
    """Return a read-only copy of ``a``."""
    a = np.array(a, copy=True)
    a.setflags(write=False)
    return a


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
    dtype : numpy dtype, optional
        ``float`` (default) or ``complex``.
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
        If an entry is NaN or infinite, or not numeric.
    """
    try:
        arr = np.array(value, dtype=dtype)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a numeric matrix; could not convert it: {exc}") from None
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


def as_finite_real(name, value):
    """Return ``value`` as a finite float or raise ``ValueError`` naming ``name``."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real number, but found {value!r}") from None
    if not math.isfinite(x):
        raise ValueError(f"{name} must be finite, but found {x}")
    return x


def as_positive(name, value, *, allow_inf=False):
    """Return ``value`` as a float > 0 (optionally +inf) or raise ``ValueError`` naming ``name``."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a positive number, but found {value!r}") from None
    if math.isnan(x) or x <= 0 or (math.isinf(x) and not allow_inf):
        raise ValueError(f"{name} must be a positive finite number, but found {x}")
    return x
