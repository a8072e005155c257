"""The mean spectrum of a class of disturbances made of independent segments of tones.

A class of the kind Part II of the book studies: the disturbance is a sequence of independent
segments; a segment lasts ``m + E`` seconds (``E`` exponential of mean μ) and is a sum of tones
whose frequencies are log-uniform in a few bands, band b carrying a mean share ``s_b`` of the
segment's power P, with random phases. For an LTI controller only the class's second-order
statistics matter (its expected output power is linear in the disturbance's autocovariance), so
the best LTI controller for the class is the optimal one for this mean spectrum
(:mod:`fdsc.optimal_lti`).

**Autocovariance.** Within a segment with tones ``a_j sin(ω_j t + φ_j)`` (random phases),
``E[d(t) d(t+τ)] = Σ a_j²/2 cos(ω_j τ)``; its mean over the tones' laws is

    c(τ) = P Σ_b s_b (Ci(h_b τ) − Ci(l_b τ)) / ln(h_b / l_b),

Ci the cosine integral, ``[l_b, h_b]`` the band (a log-uniform frequency has density
``1 / (ω ln(h/l))``). Two instants in different segments are independent, so in the stationary
renewal process of the segments

    R(τ) = c(τ) S(τ),   S(τ) = P(no break in (t, t + τ]) = (1/L̄) ∫_τ^∞ P(length > s) ds,

which for lengths ``m + Exp(μ)`` (mean ``L̄ = m + μ``) is ``1 − τ/L̄`` for ``τ ≤ m`` and
``(μ/L̄) e^{−(τ−m)/μ}`` beyond.

**Spectrum.** ``Φ(ω) = ∫ R(τ) e^{−jωτ} dτ`` (two-sided: the power is ``(1/2π) ∫ Φ dω = P``)
is the tones' density smoothed by the kernel ``K(ω) = ∫ S(τ) e^{−jωτ} dτ`` of the segments'
survival, ``Φ(ω) = ∫₀^∞ p(ν) ½ (K(ω − ν) + K(ω + ν)) dν`` with ``p`` the tones' power density:
inside a band ``Φ ≈ π p(ω)``, outside it falls off like ``2P / (L̄ ω²)`` (S has a corner at 0).
It is computed here from R on a fine grid of lags (trapezoid, by FFT) and checked against the
direct convolution and a Monte Carlo of draws by the tests.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike
from scipy.special import sici

from ._validation import as_nonnegative, as_positive, as_vector

__all__ = ["SegmentClass"]

#: Lags of the FFT grid: the survival is below e^(−this) of its start beyond m + this · μ.
_TAIL = 30.0
#: Samples of the lag grid per period of the highest frequency the grid resolves, which is
#: :data:`_OVER` times the class's highest tone.
_OVER = 4.0


@dataclass(frozen=True)
class SegmentClass:
    """A class of disturbances: independent segments of tones (module docstring).

    Parameters
    ----------
    bands : sequence of (float, float)
        The frequency ranges ``(l_b, h_b)`` (rad/s, ``0 < l_b < h_b``) in which a segment's tone
        frequencies are log-uniform.
    shares : sequence of float
        The mean share of a segment's power in each band (≥ 0, summing to 1).
    power : float, optional
        The mean power P of a segment (default 1).
    min_length : float, optional
        m (s, ≥ 0): every segment lasts at least this long (default 20).
    mean_extra : float, optional
        μ (s, > 0): the mean of the exponential part of a segment's length (default 80).

    Raises
    ------
    ValueError
        If a band is not ``0 < l < h`` (finite), the shares are negative, of another number than
        the bands or do not sum to 1 (to 1e-9), or a length or the power is out of range.

    Examples
    --------
    >>> cls = SegmentClass([(0.1, 1.0), (10.0, 300.0)], [0.5, 0.5])
    >>> cls.mean_length, float(cls.autocovariance(0.0)), round(float(cls.survival(20.0)), 3)
    (100.0, 1.0, 0.8)
    >>> w = np.array([0.3, 3.0, 50.0])
    >>> np.round(cls.spectrum(w) * w, 3)     # ≈ π P s_b / ln(h_b/l_b) in a band, small between
    array([0.681, 0.004, 0.462])
    """

    bands: tuple
    shares: tuple
    power: float = 1.0
    min_length: float = 20.0
    mean_extra: float = 80.0
    _grid: dict = field(default=None, init=False, repr=False, compare=False)

    def __post_init__(self):
        try:
            bands = tuple((float(lo), float(hi)) for lo, hi in self.bands)
        except (TypeError, ValueError):
            raise ValueError(f"bands must be a sequence of (low, high) frequency pairs (rad/s), but "
                             f"found {self.bands!r}") from None
        if not bands or any(not (0 < lo < hi < math.inf) for lo, hi in bands):
            raise ValueError(f"bands must be pairs 0 < low < high < inf (rad/s), found {bands}")
        shares = as_vector("shares", self.shares)
        if shares.size != len(bands):
            raise ValueError(f"shares must have one entry per band ({len(bands)}), found {shares.size}")
        if np.any(shares < 0) or abs(float(shares.sum()) - 1.0) > 1e-9:
            raise ValueError(f"shares must be non-negative and sum to 1, found {shares.tolist()}")
        object.__setattr__(self, "bands", bands)
        object.__setattr__(self, "shares", tuple(float(s) for s in shares))
        object.__setattr__(self, "power", as_positive("power", self.power))
        object.__setattr__(self, "min_length", as_nonnegative("min_length", self.min_length))
        object.__setattr__(self, "mean_extra", as_positive("mean_extra", self.mean_extra))

    @property
    def mean_length(self) -> float:
        """The mean length of a segment, ``m + μ`` (s)."""
        return self.min_length + self.mean_extra

    def survival(self, tau: ArrayLike) -> np.ndarray:
        """S(τ): the probability that ``t`` and ``t + |τ|`` lie in one segment.

        Parameters
        ----------
        tau : array_like
            Lags (s).

        Returns
        -------
        ndarray
            Of the shape of ``tau``.
        """
        t = np.abs(np.asarray(tau, dtype=float))
        m, mu, L = self.min_length, self.mean_extra, self.mean_length
        with np.errstate(over="ignore"):
            return np.where(t <= m, 1.0 - t / L, (mu / L) * np.exp(-(t - m) / mu))

    def tone_covariance(self, tau: ArrayLike) -> np.ndarray:
        """c(τ): the mean covariance of one segment's tones at lag τ (module docstring).

        Parameters
        ----------
        tau : array_like
            Lags (s).

        Returns
        -------
        ndarray
        """
        t = np.abs(np.asarray(tau, dtype=float))
        out = np.zeros_like(t)
        pos = t > 0
        for (lo, hi), s in zip(self.bands, self.shares, strict=True):
            band = np.full_like(t, math.log(hi / lo))           # the limit at τ = 0
            band[pos] = sici(hi * t[pos])[1] - sici(lo * t[pos])[1]
            out += s * band / math.log(hi / lo)
        return self.power * out

    def autocovariance(self, tau: ArrayLike) -> np.ndarray:
        """R(τ) = c(τ) S(τ) of the stationary class (module docstring).

        Parameters
        ----------
        tau : array_like
            Lags (s).

        Returns
        -------
        ndarray
        """
        return self.tone_covariance(tau) * self.survival(tau)

    def kernel(self, omega: ArrayLike) -> np.ndarray:
        """K(ω) = ∫ S(τ) e^{−jωτ} dτ, the smoothing of the tones' lines by the segments' survival
        (closed form; ``(1/2π) ∫ K = 1``).

        Parameters
        ----------
        omega : array_like
            Frequencies (rad/s).

        Returns
        -------
        ndarray
        """
        w = np.abs(np.asarray(omega, dtype=float))
        m, mu, L = self.min_length, self.mean_extra, self.mean_length
        small = w * max(m, mu) < 1e-4
        ws = np.where(small, 1.0, w)
        # ∫₀^m (1 − τ/L) cos ωτ dτ and (μ/L) ∫_m^∞ e^{−(τ−m)/μ} cos ωτ dτ
        i1 = np.sin(ws * m) / ws - (m * np.sin(ws * m) / ws + (np.cos(ws * m) - 1.0) / ws**2) / L
        i2 = (mu / L) * (np.cos(ws * m) / mu - ws * np.sin(ws * m)) / (1.0 / mu**2 + ws**2)
        limit = m - m * m / (2 * L) + mu * mu / L          # ∫₀^∞ S
        return 2.0 * np.where(small, limit, i1 + i2)

    def _spectrum_grid(self):
        """Φ on a uniform frequency grid up to 1.25 times the highest tone, from R on a uniform lag grid
        resolving :data:`_OVER` times more (trapezoid, by one real FFT); computed once."""
        if self._grid is None:
            top = max(hi for _, hi in self.bands)
            dtau = math.pi / (2.0 * _OVER * top)                  # Nyquist: 2 · _OVER · top
            tmax = self.min_length + _TAIL * self.mean_extra
            n = int(math.ceil(tmax / dtau)) + 1
            size = 1 << int(math.ceil(math.log2(n)))              # ω step 2π / (size dτ) ≤ 2π / tmax
            R = self.autocovariance(np.arange(n) * dtau)
            spec = 2.0 * dtau * (np.fft.rfft(R, n=size).real - 0.5 * R[0])
            w = 2.0 * math.pi * np.arange(spec.size) / (size * dtau)
            keep = w <= 1.25 * top          # far below Nyquist: little aliasing of the tails
            object.__setattr__(self, "_grid", {"w": w[keep], "phi": spec[keep]})
        return self._grid

    def spectrum(self, omega: ArrayLike) -> np.ndarray:
        """Φ(ω), the two-sided power spectral density of the class (``(1/2π) ∫ Φ dω = P``).

        Parameters
        ----------
        omega : array_like
            Frequencies (rad/s); Φ is even. Beyond 1.25 times the highest tone the density is its
            tail ``∫ p(ν) ½ (K(ω − ν) + K(ω + ν)) dν``, K far from its peak (a quadrature in ν).

        Returns
        -------
        ndarray
            Of the shape of ``omega``.
        """
        w0 = np.abs(np.asarray(omega, dtype=float))
        w = np.atleast_1d(w0).ravel()
        g = self._spectrum_grid()
        out = np.interp(w, g["w"], g["phi"])
        far = w > g["w"][-1]
        if np.any(far):
            out[far] = self._tail(w[far])
        return out.reshape(w0.shape)

    def _tail(self, w):
        """Φ at frequencies far above every band: the tones' density against K on a grid of ν
        (in chunks of frequencies, so that memory stays small)."""
        out = np.zeros_like(w)
        for (lo, hi), s in zip(self.bands, self.shares, strict=True):
            nu = np.geomspace(lo, hi, 2001)
            p = self.power * s / (nu * math.log(hi / lo))
            for c0 in range(0, w.size, 256):
                wc = w[c0:c0 + 256, None]
                f = 0.5 * (self.kernel(wc - nu[None, :]) + self.kernel(wc + nu[None, :]))
                out[c0:c0 + 256] += np.trapezoid(f * p[None, :], nu, axis=1)
        return out
