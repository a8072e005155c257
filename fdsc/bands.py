"""Frequency ranges (LF, MF, HF, entire) and their gKYP matrices Φ and Ψ (paper Sec. II-A, Lemma 1).

A band is symmetric about ω = 0 for real signals; it is stored as the interval
``[lower, upper]`` of non-negative frequencies (rad/s) it contains.

The frequency weight of a band is ``w(ω) = [jω; 1]* Ψ [jω; 1]``, which the paper
writes as ``[(jω)* 1] Ψ [(jω)* 1]*`` (proof of Proposition 1). It is positive
inside the band and negative outside:

* LF ``|ω| ≤ ϖ_l``:  ``w = ϖ_l² − ω²``
* MF ``ϖ_1 ≤ ω ≤ ϖ_2``: ``w = −(ω − ϖ_1)(ω − ϖ_2)``
* HF ``|ω| ≥ ϖ_h``:  ``w = ω² − ϖ_h²``

The MF matrix is complex; its weight selects *positive* frequencies only, and is
negative on the mirror interval ``[−ϖ_2, −ϖ_1]``. For a real system the gain is
symmetric in ω so the gKYP lemma is unaffected, but time-domain quadratic forms
of real signals only see ``Re Ψ`` (see :meth:`Band.real_weight`).
"""

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ._validation import as_positive
from .exceptions import BandError

__all__ = ["Band", "PHI", "band_from_spec", "LIMIT_RANGE"]

#: Finite band limits must lie in this range (rad/s): Ψ holds ϖ² and ϖ_1ϖ_2, which then
#: neither underflow to 0 nor overflow to inf (and stay far from the float range's ends).
LIMIT_RANGE = (1e-100, 1e100)

#: Φ of the gKYP lemma for continuous time (the imaginary axis).
PHI = np.array([[0.0, 1.0], [1.0, 0.0]])
PHI.setflags(write=False)

_KINDS = ("LF", "MF", "HF", "EF")


@dataclass(frozen=True)
class Band:
    """A frequency range Ω of the paper (Sec. II-A) with the Φ and Ψ of its gKYP lemma.

    Use the constructors :meth:`lf`, :meth:`mf`, :meth:`hf`, :meth:`entire`.

    Parameters
    ----------
    kind : {"LF", "MF", "HF", "EF"}
        Low, middle, high or entire frequency range.
    lower, upper : float
        Non-negative band limits in rad/s: LF ``[0, ϖ_l]``, MF ``[ϖ_1, ϖ_2]``,
        HF ``[ϖ_h, inf]``, EF ``[0, inf]``.

    Raises
    ------
    BandError
        If ``kind`` is unknown, a limit is not a real number, is NaN, negative or outside
        :data:`LIMIT_RANGE`, ``lower ≥ upper``, or the limits do not fit the kind (LF and EF
        start at 0, MF and HF above 0; HF and EF end at inf, LF and MF below it).

    Notes
    -----
    The ranges are those of paper Sec. II-A (the displayed LF, MF and HF sets after paper
    eq. (3)); Ψ is the matrix printed under the LMI of Lemma 1, paper eq. (7). The entire range
    Ω_e has Ψ = 0, which turns Lemma 1 into the bounded-real lemma.

    Examples
    --------
    >>> b = Band.lf(1.0)
    >>> b.psi.real
    array([[-1.,  0.],
           [ 0.,  1.]])
    >>> float(b.weight(0.5)), bool(b.contains(2.0))
    (0.75, False)
    """

    kind: str
    lower: float
    upper: float

    def __post_init__(self):
        if not isinstance(self.kind, str) or self.kind not in _KINDS:
            raise BandError(f"kind must be one of {_KINDS}, but found {self.kind!r}")
        lo, hi = _number("lower", self.lower), _number("upper", self.upper)
        if math.isnan(lo) or math.isnan(hi):
            raise BandError(f"band limits must not be NaN, found lower={lo}, upper={hi}")
        for name, v in (("lower", lo), ("upper", hi)):
            if v > 0 and math.isfinite(v) and not LIMIT_RANGE[0] <= v <= LIMIT_RANGE[1]:
                raise BandError(f"{name} limit must lie in [{LIMIT_RANGE[0]:g}, {LIMIT_RANGE[1]:g}] "
                                f"rad/s so that the entries of Psi neither underflow nor overflow, "
                                f"but found {v:g}")
        if lo < 0:
            raise BandError(f"lower limit must be >= 0 rad/s, but found {lo}")
        if not lo < hi:
            raise BandError(f"lower limit must be below upper limit, found lower={lo}, upper={hi}")
        expect_inf = self.kind in ("HF", "EF")
        if math.isinf(hi) != expect_inf:
            raise BandError(f"{self.kind} band must have upper={'inf' if expect_inf else 'finite'}, "
                            f"found {hi}")
        if self.kind in ("LF", "EF") and lo != 0:
            raise BandError(f"{self.kind} band must start at 0 rad/s, found lower={lo}")
        if self.kind in ("MF", "HF") and lo == 0:
            raise BandError(f"{self.kind} band must have a positive lower limit, found {lo}")
        object.__setattr__(self, "lower", lo)
        object.__setattr__(self, "upper", hi)

    # -- constructors -------------------------------------------------------------
    @classmethod
    def lf(cls, w_l: float) -> "Band":
        """Low-frequency band Ω_l: ``|ω| ≤ w_l``.

        Parameters
        ----------
        w_l : float
            Upper limit ϖ_l in rad/s (> 0, within :data:`LIMIT_RANGE`).

        Returns
        -------
        Band
            The band ``[0, w_l]`` of kind ``"LF"``.

        Raises
        ------
        BandError
            If ``w_l`` is not a positive finite number within :data:`LIMIT_RANGE`.

        Examples
        --------
        >>> Band.lf(1.0).label
        'LF [0, 1] rad/s'
        """
        return cls("LF", 0.0, _limit("w_l", w_l))

    @classmethod
    def mf(cls, w_1: float, w_2: float) -> "Band":
        """Middle-frequency band Ω_m: ``w_1 ≤ |ω| ≤ w_2``.

        Parameters
        ----------
        w_1, w_2 : float
            Lower and upper limits ϖ_1 < ϖ_2 in rad/s (> 0, within :data:`LIMIT_RANGE`).

        Returns
        -------
        Band
            The band ``[w_1, w_2]`` of kind ``"MF"``; its Ψ is complex.

        Raises
        ------
        BandError
            If a limit is not a positive finite number within :data:`LIMIT_RANGE`, or
            ``w_1 ≥ w_2``.

        Examples
        --------
        >>> Band.mf(1.0, 10.0).psi[0, 1]
        np.complex128(5.5j)
        """
        w1, w2 = _limit("w_1", w_1), _limit("w_2", w_2)
        if not w1 < w2:
            raise BandError(f"w_1 must be smaller than w_2, found w_1={w1}, w_2={w2}")
        return cls("MF", w1, w2)

    @classmethod
    def hf(cls, w_h: float) -> "Band":
        """High-frequency band Ω_h: ``|ω| ≥ w_h``.

        Parameters
        ----------
        w_h : float
            Lower limit ϖ_h in rad/s (> 0, within :data:`LIMIT_RANGE`).

        Returns
        -------
        Band
            The band ``[w_h, inf]`` of kind ``"HF"``.

        Raises
        ------
        BandError
            If ``w_h`` is not a positive finite number within :data:`LIMIT_RANGE`.

        Examples
        --------
        >>> Band.hf(10.0).psi.real
        array([[   1.,    0.],
               [   0., -100.]])
        """
        return cls("HF", _limit("w_h", w_h), math.inf)

    @classmethod
    def entire(cls) -> "Band":
        """The entire frequency range Ω_e (no restriction; Ψ = 0).

        Returns
        -------
        Band
            The band ``[0, inf]`` of kind ``"EF"``.

        Examples
        --------
        >>> bool(Band.entire().contains(1e6))
        True
        """
        return cls("EF", 0.0, math.inf)

    # -- matrices -------------------------------------------------------------------
    @property
    def phi(self) -> np.ndarray:
        """Φ = [[0, 1], [1, 0]] of paper eq. (7) (continuous time), a read-only (2, 2) array."""
        return PHI

    @property
    def psi(self) -> np.ndarray:
        """Ψ of the gKYP lemma (paper eq. (7)), a read-only complex (2, 2) Hermitian array."""
        if self.kind == "LF":
            m = [[-1.0, 0.0], [0.0, self.upper**2]]
        elif self.kind == "MF":
            wc = 0.5 * (self.lower + self.upper)
            m = [[-1.0, 1j * wc], [-1j * wc, -self.lower * self.upper]]
        elif self.kind == "HF":
            m = [[1.0, 0.0], [0.0, -self.lower**2]]
        else:
            m = [[0.0, 0.0], [0.0, 0.0]]
        out = np.array(m, dtype=complex)
        out.setflags(write=False)
        return out

    @property
    def is_complex(self) -> bool:
        """True if Ψ has a non-zero imaginary part (the MF band)."""
        return self.kind == "MF"

    @property
    def label(self) -> str:
        """Short text label, e.g. ``'LF [0, 1]'``."""
        hi = "∞" if math.isinf(self.upper) else f"{self.upper:g}"
        return f"{self.kind} [{self.lower:g}, {hi}] rad/s"

    # -- frequency functions --------------------------------------------------------
    def weight(self, omega: ArrayLike) -> np.ndarray:
        """Frequency weight ``[jω; 1]* Ψ [jω; 1]`` (real), vectorized over ``omega``.

        Positive inside the band (for MF: for positive ω inside), negative outside.

        Parameters
        ----------
        omega : float or array_like
            Frequencies in rad/s (finite, real), of any shape.

        Returns
        -------
        ndarray
            The weight, of the shape of ``omega`` (a 0-d value for a scalar).

        Raises
        ------
        ValueError
            If an entry of ``omega`` is NaN, infinite, complex or not numeric.

        Notes
        -----
        The closed forms listed in the module docstring are those of the proof of paper
        Proposition 1 (the display after paper eq. (23)).

        Examples
        --------
        >>> Band.hf(10.0).weight([5.0, 20.0])
        array([-75., 300.])
        """
        w = _omega(omega)
        p = self.psi
        # conj(jω) Ψ12 + Ψ21 jω = 2 ω Im Ψ12 because Ψ is Hermitian
        return p[0, 0].real * w**2 + p[1, 1].real + 2.0 * w * p[0, 1].imag

    def real_weight(self, omega: ArrayLike) -> np.ndarray:
        """Weight of ``Re Ψ``, i.e. what a quadratic form in a *real* signal sees.

        Equals ``(w(ω) + w(−ω)) / 2``; it coincides with :meth:`weight` except for MF,
        where it is ``−(ω² + ϖ_1 ϖ_2) < 0`` everywhere.

        Parameters
        ----------
        omega : float or array_like
            Frequencies in rad/s (finite, real), of any shape.

        Returns
        -------
        ndarray
            The weight, of the shape of ``omega`` (a 0-d value for a scalar).

        Raises
        ------
        ValueError
            If an entry of ``omega`` is NaN, infinite, complex or not numeric.

        Examples
        --------
        >>> band = Band.mf(1.0, 10.0)
        >>> float(band.weight(5.0)), float(band.real_weight(5.0))   # in band; −(25 + 10)
        (20.0, -35.0)
        """
        w = _omega(omega)
        return 0.5 * (self.weight(w) + self.weight(-w))

    def contains(self, omega: ArrayLike) -> np.ndarray:
        """True where ``|omega|`` lies in the band (limits included).

        Parameters
        ----------
        omega : float or array_like
            Frequencies in rad/s (finite, real), of any shape.

        Returns
        -------
        ndarray of bool
            Of the shape of ``omega`` (a 0-d value for a scalar).

        Raises
        ------
        ValueError
            If an entry of ``omega`` is NaN, infinite, complex or not numeric.

        Examples
        --------
        >>> Band.mf(1.0, 10.0).contains([-5.0, 0.5, 10.0])
        array([ True, False,  True])
        """
        a = np.abs(_omega(omega))
        return (a >= self.lower) & (a <= self.upper)


def _omega(omega):
    from ._validation import as_vector

    arr = np.asarray(omega)
    out = as_vector("omega", arr.reshape(-1) if arr.ndim else arr)
    return out.reshape(arr.shape) if arr.ndim else out[0]


def _number(name, value):
    import numbers

    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise BandError(f"{name} must be a real number in rad/s, but found {value!r}")
    return float(value)


def _limit(name, value):
    try:
        x = as_positive(name, value)
    except ValueError as exc:
        raise BandError(str(exc)) from None
    if not LIMIT_RANGE[0] <= x <= LIMIT_RANGE[1]:
        raise BandError(f"{name} must lie in [{LIMIT_RANGE[0]:g}, {LIMIT_RANGE[1]:g}] rad/s so that "
                        f"the entries of Psi neither underflow nor overflow, but found {x:g}")
    return x


def band_from_spec(spec: dict) -> Band:
    """Build a :class:`Band` from a dict such as the paper layer stores in its data files.

    Parameters
    ----------
    spec : dict
        ``{"kind": "LF", "w_l": 1}``, ``{"kind": "MF", "w_1": 1, "w_2": 10}``,
        ``{"kind": "HF", "w_h": 10}`` or ``{"kind": "EF"}`` (limits in rad/s).

    Returns
    -------
    Band

    Raises
    ------
    BandError
        If ``spec`` is not a dict, its kind is unknown, it lacks a limit of its kind, or a
        limit is invalid (see :meth:`Band.lf`, :meth:`Band.mf`, :meth:`Band.hf`).

    Examples
    --------
    >>> band_from_spec({"kind": "MF", "w_1": 1, "w_2": 10}).label
    'MF [1, 10] rad/s'
    """
    if not isinstance(spec, dict):
        raise BandError(f"spec must be a dict such as {{'kind': 'LF', 'w_l': 1.0}}, but found "
                        f"{type(spec).__name__}")
    kind = spec.get("kind")
    try:
        if kind == "LF":
            return Band.lf(spec["w_l"])
        if kind == "MF":
            return Band.mf(spec["w_1"], spec["w_2"])
        if kind == "HF":
            return Band.hf(spec["w_h"])
        if kind == "EF":
            return Band.entire()
    except KeyError as exc:
        raise BandError(f"band spec of kind {kind!r} lacks the key {exc.args[0]!r}") from None
    raise BandError(f"spec['kind'] must be one of {_KINDS}, but found {kind!r}")
