"""Disturbances (sums of sinusoids, piecewise signals) and the dominance degree α of Definitions 2 and 3.

Sums of sinusoids are represented exactly (:class:`Sinusoids`), so that their
dominance degree has a closed form: for distinct frequencies the mean power of
``Σ a_k sin(ω_k t + φ_k)`` is ``Σ a_k² / 2``, and the in-band share of it is the
infinite-horizon α(Ω) (paper Definition 2, the ratio after paper eq. (4)). For sampled records,
α is estimated by the FFT (:func:`dominance_degree`) and its time-localized version α(Ω, T_l)
(paper Definition 3, paper eq. (5)) by the short-time Fourier transform
(:func:`localized_dominance`, ``scipy.signal.ShortTimeFFT``). The paper's test signals, paper
eqs. (56)-(58), are :class:`Sinusoids` and :class:`Piecewise` signals.
"""

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ._validation import as_choice, as_finite_real, as_positive, as_vector, check_type
from .bands import Band
from .exceptions import DimensionError

__all__ = [
    "Sinusoids",
    "Piecewise",
    "Sampled",
    "HOLDS",
    "dominance_degree",
    "localized_dominance",
    "LocalizedDominance",
]


def _vector(name, value, size=None):
    try:
        return as_vector(name, value, size)
    except DimensionError as exc:
        if size is None:
            raise
        raise DimensionError(f"{exc} (one per sinusoid)") from None


def _times(t):
    """Finite real times of any shape (a scalar stays a scalar)."""
    arr = np.asarray(t)
    flat = as_vector("t", arr.reshape(-1))
    return flat.reshape(arr.shape)


@dataclass(frozen=True)
class Sinusoids:
    """A scalar sum of sinusoids ``d(t) = Σ a_k sin(ω_k t + φ_k)``.

    Instances add (``d1 + d2`` concatenates the terms) and are called on times.

    Parameters
    ----------
    amplitudes : (K,) array_like
        a_k (finite, real).
    frequencies : (K,) array_like
        Angular frequencies ω_k ≥ 0 in rad/s.
    phases : (K,) array_like, optional
        φ_k in rad (default 0).

    Raises
    ------
    DimensionError
        If an argument is not 1-D, or ``frequencies`` or ``phases`` has not one entry per
        amplitude.
    ValueError
        If a frequency is negative, or an entry is not finite and real.

    Notes
    -----
    The paper's LF and HF disturbances, paper eqs. (56) and (57), are sums of three such terms.

    Examples
    --------
    >>> d = Sinusoids([1, 1, 1], [0.1, 0.2, 0.3])
    >>> round(float(d(np.array([1.0]))[0]), 6)
    0.594023
    >>> d.dominance(Band.lf(1.0))
    1.0
    """

    amplitudes: np.ndarray
    frequencies: np.ndarray
    phases: np.ndarray = None

    def __post_init__(self):
        a = _vector("amplitudes", self.amplitudes)
        w = _vector("frequencies", self.frequencies, a.size)
        if np.any(w < 0):
            raise ValueError("frequencies must be >= 0 rad/s")
        ph = np.zeros(a.size) if self.phases is None else self.phases
        ph = _vector("phases", ph, a.size)
        object.__setattr__(self, "amplitudes", a)
        object.__setattr__(self, "frequencies", w)
        object.__setattr__(self, "phases", ph)

    def __call__(self, t: ArrayLike) -> np.ndarray:
        """Values ``d(t)``.

        Parameters
        ----------
        t : float or array_like
            Times in s (finite, real), of any shape.

        Returns
        -------
        ndarray
            Of the shape of ``t`` (a 0-d value for a scalar).

        Raises
        ------
        ValueError
            If an entry of ``t`` is NaN, infinite, complex or not numeric.
        """
        t = _times(t)
        return np.sin(np.multiply.outer(t, self.frequencies) + self.phases) @ self.amplitudes

    def derivative(self, t: ArrayLike) -> np.ndarray:
        """Time derivative ``ḋ(t) = Σ a_k ω_k cos(ω_k t + φ_k)``.

        Parameters
        ----------
        t : float or array_like
            Times in s (finite, real), of any shape.

        Returns
        -------
        ndarray
            Of the shape of ``t``.

        Raises
        ------
        ValueError
            If an entry of ``t`` is NaN, infinite, complex or not numeric.

        Examples
        --------
        >>> Sinusoids([2.0], [3.0]).derivative([0.0])
        array([6.])
        """
        t = _times(t)
        return (np.cos(np.multiply.outer(t, self.frequencies) + self.phases)
                @ (self.amplitudes * self.frequencies))

    def __add__(self, other):
        if not isinstance(other, Sinusoids):
            return NotImplemented
        return Sinusoids(np.concatenate([self.amplitudes, other.amplitudes]),
                         np.concatenate([self.frequencies, other.frequencies]),
                         np.concatenate([self.phases, other.phases]))

    def scaled(self, factor: float) -> "Sinusoids":
        """The same sum with every amplitude multiplied by ``factor``.

        Parameters
        ----------
        factor : float
            Finite real scale (ρ_p of the paper's mixed disturbance, for instance).

        Returns
        -------
        Sinusoids

        Raises
        ------
        ValueError
            If ``factor`` is not a finite real number.

        Examples
        --------
        >>> Sinusoids([1.0, 2.0], [1.0, 3.0]).scaled(0.5).amplitudes
        array([0.5, 1. ])
        """
        return Sinusoids(self.amplitudes * as_finite_real("factor", factor),
                         self.frequencies, self.phases)

    def power(self) -> float:
        """Mean power ``lim 1/T ∫ d² dt`` (distinct frequencies; a DC term counts a² sin² φ).

        Returns
        -------
        float

        Examples
        --------
        >>> Sinusoids([1.0, 2.0], [0.0, 3.0], [np.pi / 2, 0.0]).power()   # 1 + 4 / 2
        3.0
        """
        return float(np.sum(self._powers()))

    def _powers(self):
        dc = self.frequencies == 0
        return np.where(dc, (self.amplitudes * np.sin(self.phases)) ** 2, 0.5 * self.amplitudes**2)

    def dominance(self, band: Band) -> float:
        """Exact infinite-horizon dominance degree α(Ω) (paper Definition 2) of the sum.

        Frequencies must be distinct for the mean powers to add.

        Parameters
        ----------
        band : Band
            The frequency range Ω.

        Returns
        -------
        float
            In-band share of the mean power, in [0, 1].

        Raises
        ------
        ValueError
            If a frequency repeats or the signal has zero power.
        TypeError
            If ``band`` is not a :class:`~fdsc.bands.Band`.

        Examples
        --------
        >>> Sinusoids([1.0, 2.0], [0.5, 3.0]).dominance(Band.lf(1.0))   # 0.5 / (0.5 + 2)
        0.2
        """
        check_type("band", band, Band)
        if np.unique(self.frequencies).size != self.frequencies.size:
            raise ValueError("dominance needs distinct frequencies; merge equal ones first")
        p = self._powers()
        total = p.sum()
        if total == 0:
            raise ValueError("the signal has zero power; its dominance degree is undefined")
        return float(p[band.contains(self.frequencies)].sum() / total)


@dataclass(frozen=True)
class Piecewise:
    """A signal that equals ``parts[k]`` on ``[breaks[k], breaks[k+1])``.

    Parameters
    ----------
    breaks : (K + 1,) array_like
        Non-decreasing times in s; the signal is zero outside ``[breaks[0], breaks[-1])``.
    parts : sequence of Sinusoids
        The K pieces (each evaluated at absolute time t, not at time since its break).

    Raises
    ------
    TypeError
        If a part is not :class:`Sinusoids`.
    ValueError
        If ``breaks`` does not have ``len(parts) + 1`` entries, decreases, or is not finite.

    Notes
    -----
    The paper's piecewise disturbance, paper eq. (58), is a Piecewise of three parts.

    Examples
    --------
    >>> one, two = Sinusoids([1.0], [0.0], [np.pi / 2]), Sinusoids([2.0], [0.0], [np.pi / 2])
    >>> d = Piecewise([0.0, 1.0, 3.0], [one, two])       # 1 on [0, 1), 2 on [1, 3)
    >>> d([-1.0, 0.5, 1.0, 2.5, 3.0])
    array([0., 1., 2., 2., 0.])
    """

    breaks: np.ndarray
    parts: tuple

    def __post_init__(self):
        b = _vector("breaks", self.breaks)
        if not all(isinstance(p, Sinusoids) for p in self.parts):
            raise TypeError("parts must be a sequence of fdsc.signals.Sinusoids")
        if b.size != len(self.parts) + 1:
            raise ValueError(f"breaks must have len(parts) + 1 = {len(self.parts) + 1} entries, "
                             f"found {b.size}")
        if np.any(np.diff(b) < 0):
            raise ValueError("breaks must be non-decreasing")
        object.__setattr__(self, "breaks", b)
        object.__setattr__(self, "parts", tuple(self.parts))

    def __call__(self, t: ArrayLike) -> np.ndarray:
        """Values ``d(t)``; zero outside ``[breaks[0], breaks[-1])``.

        Parameters
        ----------
        t : float or array_like
            Times in s (finite, real), of any shape.

        Returns
        -------
        ndarray
            Of the shape of ``t``.

        Raises
        ------
        ValueError
            If an entry of ``t`` is NaN, infinite, complex or not numeric.
        """
        t = np.asarray(_times(t), dtype=float)
        out = np.zeros_like(t)
        for k, part in enumerate(self.parts):
            sel = (t >= self.breaks[k]) & (t < self.breaks[k + 1])
            out[sel] = part(t[sel])
        return out

    def segment_of(self, t: ArrayLike) -> np.ndarray:
        """Index of the part active at each time (−1 outside ``[breaks[0], breaks[-1])``).

        Parameters
        ----------
        t : float or array_like
            Times in s (finite, real), of any shape.

        Returns
        -------
        int ndarray
            Of the shape of ``t``.

        Raises
        ------
        ValueError
            If an entry of ``t`` is NaN, infinite, complex or not numeric.

        Examples
        --------
        >>> one = Sinusoids([1.0], [0.0], [np.pi / 2])
        >>> Piecewise([0.0, 1.0, 3.0], [one, one]).segment_of([-1.0, 0.5, 1.0, 3.0])
        array([-1,  0,  1, -1])
        """
        t = _times(t)
        k = np.searchsorted(self.breaks, t, side="right") - 1
        return np.where((k >= 0) & (k < len(self.parts)), k, -1)


#: Interpolation of a :class:`Sampled` signal between its samples: zero-order hold (constant) or
#: first-order hold (linear).
HOLDS = ("zoh", "foh")


@dataclass(frozen=True)
class Sampled:
    """A scalar signal given by samples ``values[k]`` at ``t_k = k dt``, held between them.

    For inputs that are not sums of sinusoids (coloured noise, measured records). The
    streaming simulator (:func:`fdsc.stream.simulate_stream`) integrates the held signal exactly:
    with the zero-order hold the input is ``values[k]`` on ``[t_k, t_{k+1})``, with the
    first-order hold it is the straight line from ``values[k]`` to ``values[k+1]``.

    Parameters
    ----------
    values : (N,) array_like
        Samples (finite, real), at least 2.
    dt : float
        Sample spacing in s (> 0); a simulation must use the same step.
    hold : {"zoh", "foh"}, optional
        Interpolation between samples (default ``"zoh"``).

    Raises
    ------
    ValueError
        If ``values`` has fewer than 2 entries or is not finite and real, ``dt ≤ 0``, or
        ``hold`` is not one of :data:`HOLDS`.

    Notes
    -----
    The state of a simulation under the held signal is exact to rounding; what differs from an
    underlying continuous signal s(t) is the hold itself: at most ``dt · max|ṡ|`` for the
    zero-order hold and ``dt² / 8 · max|s̈|`` for the first-order hold. Energies (``∫ zᵀz``,
    ``∫ d²``) are the exact integrals of the run under the held signal (each step's a quadratic
    form of the state and the held samples).

    Examples
    --------
    >>> d = Sampled([0.0, 1.0, 3.0], 0.5, hold="foh")
    >>> d([0.0, 0.25, 0.75, 1.0, 2.0])           # zero after the last sample
    array([0. , 0.5, 2. , 3. , 0. ])
    >>> Sampled([0.0, 1.0, 3.0], 0.5)([0.25, 0.75])
    array([0., 1.])
    """

    values: np.ndarray
    dt: float
    hold: str = "zoh"

    def __post_init__(self):
        v = as_vector("values", self.values, allow_scalar=False)
        if v.size < 2:
            raise ValueError(f"values must hold at least 2 samples, found {v.size}")
        object.__setattr__(self, "values", v)
        object.__setattr__(self, "dt", as_positive("dt", self.dt))
        object.__setattr__(self, "hold", as_choice("hold", self.hold, HOLDS))

    @property
    def duration(self) -> float:
        """Time of the last sample, ``(N − 1) dt`` in s."""
        return (self.values.size - 1) * self.dt

    def __call__(self, t: ArrayLike) -> np.ndarray:
        """Values of the held signal; zero before 0 and after the last sample.

        Parameters
        ----------
        t : float or array_like
            Times in s (finite, real), of any shape.

        Returns
        -------
        ndarray
            Of the shape of ``t``.

        Raises
        ------
        ValueError
            If an entry of ``t`` is NaN, infinite, complex or not numeric.
        """
        t = np.asarray(_times(t), dtype=float)
        pos = t / self.dt
        k = np.floor(pos + 1e-9).astype(np.int64)
        inside = (t >= 0) & (k <= self.values.size - 1) & (pos <= self.values.size - 1 + 1e-9)
        kc = np.clip(k, 0, self.values.size - 1)
        out = self.values[kc].copy()
        if self.hold == "foh":
            k1 = np.clip(kc + 1, 0, self.values.size - 1)
            frac = np.clip(pos - kc, 0.0, 1.0)
            out = out + frac * (self.values[k1] - out)
        return np.where(inside, out, 0.0)


def _record(x, dt):
    x = as_vector("x", x, allow_scalar=False)
    if x.size < 8:
        raise ValueError(f"x must be a record of at least 8 samples, found {x.size}")
    return x, as_positive("dt", dt)


def dominance_degree(x: ArrayLike, dt: float, band: Band, *, window: str = "hann") -> float:
    """Dominance degree α(Ω) of a sampled record, by the FFT (Definition 2).

    Parameters
    ----------
    x : (N,) array_like
        Samples ``d(k dt)``.
    dt : float
        Sampling step in s. Frequencies above π/dt are not represented (aliasing).
    band : Band
        The frequency range Ω.
    window : str, optional
        Taper applied before the FFT (``"boxcar"`` for none); a taper limits the
        leakage of a finite record into neighbouring bins.

    Returns
    -------
    float
        In-band share of the energy, in [0, 1].

    Raises
    ------
    ValueError
        If ``x`` has fewer than 8 samples, is identically zero or not finite, or ``dt`` is not
        positive.
    DimensionError
        If ``x`` is not 1-D.

    Notes
    -----
    The ratio α(Ω_i) of paper Definition 2 (after paper eq. (4)), with the integrals over
    frequency replaced by sums over the bins of the record's discrete Fourier transform.

    Examples
    --------
    >>> t = np.arange(0, 500, 0.002)
    >>> x = Sinusoids([1.0, 0.5], [100.0, 0.2])(t)   # in-band share 1 / (1 + 0.25) = 0.8
    >>> round(dominance_degree(x, 0.002, Band.hf(10.0)), 3)
    0.8
    """
    x, dt = _record(x, dt)
    from scipy.signal import get_window  # here: a simulation needs no scipy.signal

    win = get_window(window, x.size, fftbins=False)
    X = np.fft.rfft(x * win)
    w = 2 * np.pi * np.fft.rfftfreq(x.size, dt)
    weight = np.full(w.size, 2.0)
    weight[0] = 1.0
    if x.size % 2 == 0:
        weight[-1] = 1.0
    p = weight * np.abs(X) ** 2
    total = p.sum()
    if total == 0:
        raise ValueError("x is identically zero; its dominance degree is undefined")
    return float(p[band.contains(w)].sum() / total)


@dataclass(frozen=True)
class LocalizedDominance:
    """Time-localized dominance degree α(Ω, T_l) (paper Definition 3), from :func:`localized_dominance`.

    Parameters
    ----------
    t : (L,) ndarray
        Window centres in s.
    alpha : (L,) ndarray
        In-band share of each window's energy (NaN for a window without energy).
    window_length : float
        Window length in s (the requested length rounded to whole samples).
    """

    t: np.ndarray
    alpha: np.ndarray
    window_length: float


def localized_dominance(x: ArrayLike, dt: float, band: Band, *, window_length: float,
                        hop: float | None = None, window: str = "hann") -> LocalizedDominance:
    """α(Ω, T_l) over sliding windows, by the short-time Fourier transform.

    Parameters
    ----------
    x : (N,) array_like
        Samples of d.
    dt : float
        Sampling step in s.
    band : Band
        The frequency range Ω.
    window_length : float
        Length of each window T_l in s (resolves frequencies down to ~2π / window_length).
    hop : float, optional
        Distance between window centres in s (default ``window_length / 8``).
    window : str, optional
        Window shape (``scipy.signal.get_window`` name).

    Returns
    -------
    LocalizedDominance
        Only windows lying entirely inside the record are returned.

    Raises
    ------
    ValueError
        If ``x`` has fewer than 8 samples or is not finite, ``dt``, ``window_length`` or ``hop``
        is not positive, or a window spans fewer than 8 samples or more than the record.
    DimensionError
        If ``x`` is not 1-D.

    Notes
    -----
    The ratio α(Ω_i, T_l) after paper eq. (5), each window T_l's pseudo spectrum taken as the
    windowed Fourier transform of the record.

    Examples
    --------
    >>> t = np.arange(0.0, 100.0, 0.01)
    >>> x = np.where(t < 50.0, np.sin(20.0 * t), np.sin(2.0 * t))   # HF, then out of band
    >>> ld = localized_dominance(x, 0.01, Band.hf(10.0), window_length=10.0)
    >>> float(ld.t[0]), float(ld.t[-1]), bool(ld.alpha[0] > 0.99), bool(ld.alpha[-1] < 0.01)
    (5.0, 95.0, True, True)
    """
    x, dt = _record(x, dt)
    window_length = as_positive("window_length", window_length)
    hop = window_length / 8 if hop is None else as_positive("hop", hop)
    nwin = int(round(window_length / dt))
    nhop = max(1, int(round(hop / dt)))
    if nwin < 8 or nwin > x.size:
        raise ValueError(f"window_length must span between 8 samples and the record "
                         f"({x.size * dt:g} s), found {window_length:g} s")
    from scipy.signal import ShortTimeFFT, get_window

    sft = ShortTimeFFT(get_window(window, nwin, fftbins=False), hop=nhop, fs=1.0 / dt,
                       fft_mode="onesided")
    p0 = sft.lower_border_end[1]
    p1 = sft.upper_border_begin(x.size)[1]
    if p1 <= p0:
        raise ValueError("window_length leaves no window entirely inside the record")
    S = sft.stft(x, p0=p0, p1=p1)
    power = np.abs(S) ** 2
    power[1:] *= 2.0  # one-sided spectrum: count negative frequencies (Nyquist slightly over)
    w = 2 * np.pi * sft.f
    total = power.sum(axis=0)
    with np.errstate(invalid="ignore", divide="ignore"):
        alpha = np.where(total > 0, power[band.contains(w)].sum(axis=0) / total, np.nan)
    t = sft.t(x.size, p0=p0, p1=p1)
    return LocalizedDominance(t, alpha, nwin * dt)
