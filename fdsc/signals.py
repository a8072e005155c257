"""The paper's disturbances and the dominance degree α of Definitions 2 and 3.

Sums of sinusoids are represented exactly (:class:`Sinusoids`), so that their
dominance degree has a closed form: for distinct frequencies the mean power of
``Σ a_k sin(ω_k t + φ_k)`` is ``Σ a_k² / 2``, and the in-band share of it is the
infinite-horizon α(Ω). For sampled records, α is estimated by the FFT
(:func:`dominance_degree`) and its time-localized version α(Ω, T_l) by the
short-time Fourier transform (:func:`localized_dominance`, ``scipy.signal.ShortTimeFFT``).
"""

from dataclasses import dataclass

import numpy as np
from scipy.signal import ShortTimeFFT, get_window

from ._validation import as_finite_real, as_positive, as_vector, check_type
from .bands import Band
from .exceptions import DimensionError

__all__ = [
    "Sinusoids",
    "Piecewise",
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

    Parameters
    ----------
    amplitudes : (K,) array_like
    frequencies : (K,) array_like
        Angular frequencies ω_k ≥ 0 in rad/s.
    phases : (K,) array_like, optional
        φ_k in rad (default 0).

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

    def __call__(self, t):
        """Values at times ``t`` (array_like, s)."""
        t = _times(t)
        return np.sin(np.multiply.outer(t, self.frequencies) + self.phases) @ self.amplitudes

    def derivative(self, t):
        """Time derivative at times ``t``."""
        t = _times(t)
        return (np.cos(np.multiply.outer(t, self.frequencies) + self.phases)
                @ (self.amplitudes * self.frequencies))

    def __add__(self, other):
        if not isinstance(other, Sinusoids):
            return NotImplemented
        return Sinusoids(np.concatenate([self.amplitudes, other.amplitudes]),
                         np.concatenate([self.frequencies, other.frequencies]),
                         np.concatenate([self.phases, other.phases]))

    def scaled(self, factor):
        """The same sum with every amplitude multiplied by ``factor``."""
        return Sinusoids(self.amplitudes * as_finite_real("factor", factor),
                         self.frequencies, self.phases)

    def power(self):
        """Mean power ``lim 1/T ∫ d² dt`` (distinct frequencies; a DC term counts a² sin² φ)."""
        return float(np.sum(self._powers()))

    def _powers(self):
        dc = self.frequencies == 0
        return np.where(dc, (self.amplitudes * np.sin(self.phases)) ** 2, 0.5 * self.amplitudes**2)

    def dominance(self, band):
        """Exact infinite-horizon dominance degree α(Ω) (Definition 2) of the sum.

        Frequencies must be distinct for the mean powers to add.
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
        Increasing times; the signal is zero outside ``[breaks[0], breaks[-1])``.
    parts : sequence of Sinusoids
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

    def __call__(self, t):
        """Values at times ``t`` (array_like, s); zero outside ``[breaks[0], breaks[-1])``."""
        t = np.asarray(_times(t), dtype=float)
        out = np.zeros_like(t)
        for k, part in enumerate(self.parts):
            sel = (t >= self.breaks[k]) & (t < self.breaks[k + 1])
            out[sel] = part(t[sel])
        return out

    def segment_of(self, t):
        """Index of the part active at each time (−1 outside)."""
        t = _times(t)
        k = np.searchsorted(self.breaks, t, side="right") - 1
        return np.where((k >= 0) & (k < len(self.parts)), k, -1)















def _record(x, dt):
    x = as_vector("x", x, allow_scalar=False)
    if x.size < 8:
        raise ValueError(f"x must be a record of at least 8 samples, found {x.size}")
    return x, as_positive("dt", dt)


def dominance_degree(x, dt, band, *, window="hann"):
    """Dominance degree α(Ω) of a sampled record, by the FFT (Definition 2).

    Parameters
    ----------
    x : (N,) array_like
        Samples ``d(k dt)``.
    dt : float
        Sampling step in s. Frequencies above π/dt are not represented (aliasing).
    band : Band
    window : str, optional
        Taper applied before the FFT (``"boxcar"`` for none); a taper limits the
        leakage of a finite record into neighbouring bins.

    Returns
    -------
    float
        In-band share of the energy, in [0, 1].

    Examples
    --------
    >>> t = np.arange(0, 500, 0.002)
    >>> x = Sinusoids([1.0, 0.5], [100.0, 0.2])(t)   # in-band share 1 / (1 + 0.25) = 0.8
    >>> round(dominance_degree(x, 0.002, Band.hf(10.0)), 3)
    0.8
    """
    x, dt = _record(x, dt)
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
    """Time-localized dominance degree α(Ω, T_l) (Definition 3).

    Attributes
    ----------
    t : (L,) ndarray
        Window centres in s.
    alpha : (L,) ndarray
        In-band share of each window's energy.
    window_length : float
        Window length in s.
    """

    t: np.ndarray
    alpha: np.ndarray
    window_length: float


def localized_dominance(x, dt, band, *, window_length, hop=None, window="hann"):
    """α(Ω, T_l) over sliding windows, by the short-time Fourier transform.

    Parameters
    ----------
    x : (N,) array_like
        Samples of d.
    dt : float
        Sampling step in s.
    band : Band
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
    """
    x, dt = _record(x, dt)
    window_length = as_positive("window_length", window_length)
    hop = window_length / 8 if hop is None else as_positive("hop", hop)
    nwin = int(round(window_length / dt))
    nhop = max(1, int(round(hop / dt)))
    if nwin < 8 or nwin > x.size:
        raise ValueError(f"window_length must span between 8 samples and the record "
                         f"({x.size * dt:g} s), found {window_length:g} s")
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
