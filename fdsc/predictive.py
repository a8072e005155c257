"""A causal law that predicts the disturbance: the LQ gain plus the adjoint of identified tones.

The non-causal optimum (:mod:`fdsc.noncausal`) is ``u* = K x + K_d d − R⁻¹B2ᵀ ξ(t)`` with ξ
the anti-causal filter of the future disturbance; a causal law can only predict ξ from the past
of the estimate ŵ. For a disturbance that is a sum of tones held for a while, the prediction is
exact once the tones are known: a tone ``Re(c e^{jωt})`` continued forever has the adjoint
``Re(ψ(ω) c e^{jωt})`` with ``ψ(ω) = −(jω I + A_cᵀ)⁻¹ F`` (:meth:`fdsc.noncausal.LQData.psi_gain`).
:class:`PredictiveLaw` applies

    u = K x + F_b(ŵ) + Σ_i (g*(ω̂_i) − F_b(jω̂_i)) ŷ_i(t),      g*(ω) = K_d − R⁻¹B2ᵀψ(ω),

a fixed feedforward F_b of the estimate (the *base*: by default the static ``K_d − R⁻¹B2ᵀψ(0)``,
exact for slow tones, which over the loop's memory are nearly constant; or any linear filter of
ŵ, such as the best one for the class) corrected on the tones ŷ_i identified in the band where
prediction matters, so that on those tones the feedforward is the optimal one. An identification
whose fit leaves more than ``max_residual`` of the window's power unexplained (a window across a
break of d, or noise that no few tones describe) is not used: the base acts alone until the next
one. Every ``update`` seconds the law identifies the tones of the last
``window`` seconds of ŵ, sampled at ``step``: ESPRIT (Roy and Kailath 1989) on the second
differences of the samples (which suppress the slow part), the signal subspace of the lag
covariance by an eigendecomposition with its rank set by ``rank_tol``, the frequencies from its
shift invariance, then the amplitudes by least squares with a polynomial trend
(:func:`identify_tones`, which adds a second pass for directions below ``rank_tol`` that stand
above the noise). Between updates each identified tone is continued, so the feedforward
is a sum of tones and the loop is run exactly (:mod:`fdsc._modal`), with no step.

It is realizable: it reads x and samples of ŵ, nothing of the future. The sampler is ideal
(tones of ŵ above the Nyquist frequency π/step are removed before sampling, as an anti-alias
filter would). :meth:`PredictiveLaw.run_known` is the same law with the tones of the current
piece of d known exactly (ideal identification, no break foreseen): a reference, not a bound.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from ._modal import Modal, tone_terms
from ._tones import _below_rank_tol, _esprit, _fit, _warn_unresolved
from ._validation import as_count, as_positive, as_vector, check_type
from .decisions import SCALE_RANGE, _scale_exponent, _scaled, _unscale
from .exceptions import EnergyOverflowError, EnergyUnderflowWarning
from .noncausal import lq_data
from .plant import as_plant
from .signals import Piecewise, Sinusoids

__all__ = ["ToneEstimate", "identify_tones", "PredictiveRun", "PredictiveLaw"]

#: Defaults of the identification (see :func:`identify_tones`).
DEFAULT_LAGS, DEFAULT_RANK_TOL, DEFAULT_TREND = 48, 1e-3, 3
#: A frequency estimated within this share of the window's resolution 2π/T outside the band is
#: kept: ESPRIT puts a tone that lies on an edge of the closed band within rounding of it, on
#: either side (up to about 1e-10 of the resolution), and a tone that close to the edge cannot be
#: told from one on it.
EDGE_SHARE = 1e-6
#: :func:`identify_tones` keeps the directions of the lag matrix that stand this many times above
#: its noise floor (the median singular value of the directions below ``rank_tol``).
FLOOR_FACTOR = 100.0
#: The default window of :class:`PredictiveLaw`, in seconds, unless it holds fewer than
#: :data:`MIN_WINDOW_SAMPLES` samples.
DEFAULT_WINDOW = 2.0
#: The fewest samples a window of :class:`PredictiveLaw` holds.
MIN_WINDOW_SAMPLES = 20


@dataclass(frozen=True)
class ToneEstimate:
    """Tones identified in a window of samples (see :func:`identify_tones`).

    Parameters
    ----------
    frequencies : (M,) ndarray
        ω̂_i (rad/s), ascending.
    coefficients : (M,) complex ndarray
        c_i with the tones ``Σ Re(c_i e^{jω̂_i τ})``, τ = 0 at the window's last sample.
    residual : float
        Mean square of the fit's residual over the window (tones and trend).
    """

    frequencies: np.ndarray
    coefficients: np.ndarray
    residual: float

    def __call__(self, tau) -> np.ndarray:
        """The identified tones at times τ relative to the window's last sample.

        Parameters
        ----------
        tau : (N,) array_like
            Times (s), 0 at the window's last sample.

        Returns
        -------
        (N,) ndarray

        Raises
        ------
        ValueError
            If τ is not a finite real vector.
        """
        tau = as_vector("tau", tau)
        return np.real(np.exp(1j * np.outer(tau, self.frequencies)) @ self.coefficients)


def identify_tones(samples, step: float, band, *, max_tones: int = 12, lags: int = DEFAULT_LAGS,
                   rank_tol: float = DEFAULT_RANK_TOL, trend: int = DEFAULT_TREND) -> ToneEstimate:
    """The tones of a window of uniform samples in a band (ESPRIT on the second differences,
    amplitudes by least squares with a polynomial trend).

    Parameters
    ----------
    samples : (N,) array_like
        Uniform samples, the last one at τ = 0.
    step : float
        The sampling interval (s).
    band : (float, float)
        The frequencies (rad/s) where tones are sought, ``0 < lo < hi ≤ π/step``; closed, and a
        tone estimated within :data:`EDGE_SHARE` of the resolution 2π/T outside it is kept
        (T the window's length, ``step · (N − 1)``).
    max_tones : int, optional
        At most this many tones (the signal subspace has at most twice as many dimensions); the
        window must hold ``4 max_tones + 4`` samples or more.
    lags : int, optional
        Columns of the lag matrix (its row count is the rest of the window), at least
        ``2 max_tones + 1``.
    rank_tol : float, optional
        Directions of the lag covariance whose singular value is below this fraction (in (0, 1))
        of the largest are noise.
    trend : int, optional
        Degree of the polynomial fitted beside the tones (the slow part of the window).

    Returns
    -------
    ToneEstimate

    Raises
    ------
    ValueError
        If an argument is out of range, the samples are not finite, or there are too few of them
        for ``max_tones`` (a lag matrix of ``2 max_tones + 1`` columns, two per tone and one for
        the noise, and as many rows) or for the trend.
    EnergyOverflowError
        If the residual's mean square exceeds the float range (samples above about 1e154).

    Warns
    -----
    ResolutionWarning
        If two identified tones are closer than the window's resolution 2π/T, or one lies within
        π/T of the Nyquist frequency π/step: their amplitudes and phases are ill-conditioned.
    EnergyUnderflowWarning
        If the residual's mean square is not 0 but below the smallest normal float (samples
        below about 1e-154; the tones are identified at a scale where the samples are of order
        one, and keep their digits).

    Notes
    -----
    ESPRIT keeps the directions of the lag matrix above ``rank_tol``. Directions below it that
    stand :data:`FLOOR_FACTOR` times above the matrix's noise floor (the median singular value
    of the rest) are structure, not noise: a slow part that the second differences leave (a
    quadratic trend becomes a constant), or the split of two tones closer than the window
    resolves. Left out, they bias the frequencies (by about 1e-5 of the resolution beside a
    slow drift, and two such tones come back as one); so a second pass identifies the tones with
    them, and keeps those whose share of the lag matrix (amplitude times the gain
    ``(2 sin(ω step/2))²`` of the second difference) is at least ``rank_tol`` of the largest.
    On noisy samples (a floor above ``rank_tol``/:data:`FLOOR_FACTOR`) there is no such
    direction and the first pass stands. :class:`PredictiveLaw` takes the first pass only.

    Examples
    --------
    Two tones and a slow drift, sampled at 5 ms for 2 s:

    >>> t = np.arange(-400, 1) * 0.005
    >>> y = 0.7 * np.sin(30.0 * t + 0.3) + 0.4 * np.sin(47.0 * t) + 0.5 * np.sin(0.4 * t)
    >>> est = identify_tones(y, 0.005, (10.0, 200.0))
    >>> np.round(est.frequencies, 3).tolist(), np.round(np.abs(est.coefficients), 3).tolist()
    ([30.0, 47.0], [0.7, 0.4])
    """
    y = as_vector("samples", samples)
    step = as_positive("step", step)
    lo, hi = _band(band, step)
    max_tones = as_count("max_tones", max_tones, 1)
    lags = as_count("lags", lags, 3)
    if lags < 2 * max_tones + 1:
        raise ValueError(f"lags must be at least 2 max_tones + 1 = {2 * max_tones + 1} (two columns of the "
                         f"lag matrix per tone and one for the noise), but found {lags}: raise lags or "
                         "lower max_tones")
    rank_tol = _rank_tol(rank_tol)
    trend = as_count("trend", trend, 0)
    need_trend, need_tones = 2 * (trend + 1) + 8, 4 * max_tones + 4
    if y.size < max(need_trend, need_tones):
        why = (f"for a trend of degree {trend} beside the tones" if need_trend >= need_tones else
               f"for up to max_tones = {max_tones} tones: a lag matrix of the second differences with "
               f"{2 * max_tones + 1} columns, two per tone and one for the noise, and as many rows; "
               "lengthen the window or lower max_tones")
        raise ValueError(f"samples: at least {max(need_trend, need_tones)} samples are needed ({why}), but "
                         f"found {y.size}")
    # identified at a scale (a power of two, exact) where the lag covariance and the residual's
    # mean square neither overflow nor underflow; the coefficients are linear in the samples
    mag = float(np.max(np.abs(y)))
    e = 0 if mag == 0.0 or 2.0 ** -SCALE_RANGE <= mag <= 2.0 ** SCALE_RANGE else math.frexp(mag)[1]
    y = np.ldexp(y, -e)
    w = _esprit(y, step, lo, hi, max_tones, lags, rank_tol, EDGE_SHARE)
    again = _below_rank_tol(y, step, lo, hi, max_tones, lags, rank_tol, trend, EDGE_SHARE, FLOOR_FACTOR)
    if again is not None:
        w = again
    tau = step * (np.arange(y.size) - (y.size - 1))
    c, res = _fit(tau, y, w, trend)
    _warn_unresolved(w, step, y.size)
    if e:
        c = np.ldexp(c.real, e) + 1j * np.ldexp(c.imag, e)
        with np.errstate(over="ignore", under="ignore"):
            scaled_res, res = res, float(np.ldexp(res, 2 * e))
        if not math.isfinite(res):
            raise EnergyOverflowError("identify_tones: the residual's mean square exceeds the float range "
                                      "(about 1.8e308) in the samples' units: scale the samples down")
        tiny = np.finfo(float).tiny
        if scaled_res != 0 and res < tiny:
            warnings.warn(f"identify_tones: the residual's mean square ({res:.3g}) is below the smallest "
                          f"normal float (about {tiny:.2g}) in the samples' units, where it keeps few digits "
                          "or none (the tones, identified at scale, keep theirs): scale the samples up for "
                          "its digits", EnergyUnderflowWarning, stacklevel=2)
    return ToneEstimate(w, c, res)


def _rank_tol(rank_tol):
    x = as_positive("rank_tol", rank_tol)
    if not x < 1:
        raise ValueError(f"rank_tol must lie in (0, 1) (a share of the largest singular value; at 1 or "
                         f"above no direction is signal and no tone can be found), but found {x}")
    return x


def _band(band, step=None):
    if not hasattr(band, "__len__") or len(band) != 2:
        raise ValueError(f"band must be a pair (lo, hi) of frequencies in rad/s, but found {band!r}")
    lo, hi = as_positive("band[0]", band[0]), as_positive("band[1]", band[1])
    if not lo < hi:
        raise ValueError(f"band must have lo < hi, but found {band!r}")
    if step is not None and hi > math.pi / step * (1 + 1e-12):
        raise ValueError(f"band: its upper end {hi:g} rad/s is above the Nyquist frequency π/step = "
                         f"{math.pi / step:g} rad/s")
    return lo, hi


@dataclass(frozen=True)
class PredictiveRun:
    """One run of a :class:`PredictiveLaw`.

    Parameters
    ----------
    energy : float
        ∫₀ᴴ ‖z‖² dt (exact given the law's decisions).
    horizon : float
    identifications : int
        How many times the tones were identified.
    mean_tones : float
        Tones per identification, on average.
    output_energy : (p,) ndarray
        ∫₀ᴴ z_r² dt per output r (they sum to ``energy``): the energy of u where z holds rows
        of ``D2 u`` alone.
    pieces : (k, 3) ndarray
        ``[t0, t1, ∫ ‖z‖²]`` of the pieces the run is integrated on, between the law's updates
        and the breaks of d and ŵ (their energies sum to ``energy``).
    """

    energy: float
    horizon: float
    identifications: int
    mean_tones: float
    output_energy: np.ndarray = None
    pieces: np.ndarray = None


class PredictiveLaw:
    """The LQ gain plus the adjoint of tones identified online in ŵ (module docstring).

    Parameters
    ----------
    plant : Plant, control.StateSpace or tuple
        One disturbance input; D2 of full column rank (:func:`fdsc.noncausal.lq_data`).
    band : (float, float)
        Where tones are identified (rad/s); the rest of ŵ gets the static feedforward ψ(0).
    window : float, optional
        Seconds of ŵ each identification reads, at least :data:`MIN_WINDOW_SAMPLES` (20)
        samples. Default the longer of :data:`DEFAULT_WINDOW` (2 s) and 20 samples (``20 · step``),
        so that the default fits any band.
    update : float, optional
        Seconds between identifications (the first after ``min(window, 0.5)`` s).
    step : float, optional
        The sampling interval of ŵ (default π / (1.25 · band[1])).
    max_tones, lags, rank_tol, trend : optional
        See :func:`identify_tones`.
    amplitude_cap : float, optional
        An identification whose tones are larger than this times the window's largest sample
        is discarded (a fit across a break of d can return canceling tones).
    max_residual : float, optional
        An identification whose fit leaves more than this share of the window's mean square
        unexplained is discarded (the base feedforward acts alone until the next one).
    base : Controller, optional
        The fixed feedforward the law corrects: its path from ŵ to u (``A, E, C, F``; its
        states must not read x, ``B = 0``), e.g. a controller tuned with the LQ gain held
        (:func:`fdsc.tune_controller` with ``structure="held"``). Default the static
        ``K_d − R⁻¹B2ᵀψ(0)``. The law's gain on x is the LQ gain in either case.

    Raises
    ------
    ValueError
        If an argument is out of range (a window of fewer than 20 samples at the step), or as
        :func:`fdsc.noncausal.lq_data`.

    Notes
    -----
    The law identifies the tones with ESPRIT at the rank ``rank_tol`` sets (the first pass of
    :func:`identify_tones`; it neither takes the second pass nor warns), as the book's stored
    study computed it.

    Examples
    --------
    On a held pair of tones the law comes within 2 % of the non-causal limit (the first
    identification waits half a second):

    >>> from fdsc import Plant, noncausal_limit
    >>> p = Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
    ...           [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.3]])
    >>> d = Sinusoids([1.0, 0.5], [3.0, 7.0])
    >>> run = PredictiveLaw(p, (1.0, 20.0), window=3.0, step=0.05).run(d, 100.0)
    >>> bool(run.energy / noncausal_limit(p, d, 100.0).energy < 1.02)
    True
    """

    def __init__(self, plant, band, *, window: float | None = None, update: float = 0.5,
                 step: float | None = None,
                 max_tones: int = 12, lags: int = DEFAULT_LAGS, rank_tol: float = DEFAULT_RANK_TOL,
                 trend: int = DEFAULT_TREND, amplitude_cap: float = 4.0, max_residual: float = 1.0,
                 base=None):
        self.plant = as_plant(plant)
        if self.plant.B1.shape[1] != 1:
            raise ValueError(f"plant must have one disturbance input, but has {self.plant.B1.shape[1]}")
        lo, hi = _band(band)
        self.band = (lo, hi)
        window = None if window is None else as_positive("window", window)
        self.update = as_positive("update", update)
        self.step = math.pi / (1.25 * hi) if step is None else as_positive("step", step)
        _band(band, self.step)
        shortest = MIN_WINDOW_SAMPLES * self.step
        self.window = max(DEFAULT_WINDOW, shortest) if window is None else window
        if self.window < shortest:
            where = (f"the default step π/(1.25·band[1]) = {self.step:.4g} s" if step is None
                     else f"step {self.step:.4g} s")
            raise ValueError(f"window must hold at least {MIN_WINDOW_SAMPLES} samples ({shortest:.4g} s at "
                             f"{where}), but found {window!r}: lengthen the window or shorten the step")
        self.max_tones = as_count("max_tones", max_tones, 1)
        self.lags = as_count("lags", lags, 3)
        self.rank_tol = _rank_tol(rank_tol)
        self.trend = as_count("trend", trend, 0)
        self.amplitude_cap = as_positive("amplitude_cap", amplitude_cap)
        self.max_residual = as_positive("max_residual", max_residual)
        self.lq = lq = lq_data(self.plant)
        m = self.plant.n_controls
        if base is None:
            psi0 = lq.psi_gain([0.0])[0, :, 0]
            Af, Ef, Cf, Ff = np.zeros((0, 0)), np.zeros((0, 1)), np.zeros((m, 0)), \
                (lq.K_d[:, 0] - lq.R_inv_B2T @ psi0)[:, None]
        else:
            from .controller import Controller

            check_type("base", base, Controller, "an fdsc.Controller that reads ŵ")
            if not base.reads_estimate or base.D.shape != (m, self.plant.n_states) or np.any(base.B):
                raise ValueError("base must be a controller of this plant that reads ŵ, its states driven by "
                                 "ŵ alone (B = 0)")
            if base.n_states and np.max(np.linalg.eigvals(base.A).real) >= 0:
                raise ValueError("base: its filter of ŵ is not stable")
            Af, Ef, Cf, Ff = base.A, base.E, base.C, base.F
        self._base = (Af, Ef[:, 0], Cf, Ff[:, 0])
        k, n = Af.shape[0], self.plant.n_states
        B2, D2 = self.plant.B2, self.plant.D2
        A = np.block([[lq.A_c, B2 @ Cf], [np.zeros((k, n)), Af]])
        C = np.hstack([lq.Cz, D2 @ Cf])
        self._modal = Modal(A, C, "the LQ closed loop with the base feedforward")

    def _ff_gain(self, w):
        """u per unit of an identified tone at ω: the optimal response less the base's."""
        Af, Ef, Cf, Ff = self._base
        lq = self.lq
        opt = lq.K_d[:, 0][None, :] - lq.psi_gain(w)[:, :, 0] @ lq.R_inv_B2T.T
        if Af.shape[0]:
            M = 1j * np.asarray(w)[:, None, None] * np.eye(Af.shape[0])[None] - Af[None]
            base = Ff[None, :] + np.einsum("mk,wk->wm", Cf, np.linalg.solve(M, np.broadcast_to(
                Ef, (len(w), Ef.size))[..., None])[..., 0])
        else:
            base = np.broadcast_to(Ff, (len(w), Ff.size))
        return opt - base

    def _run(self, d, horizon, estimate, x0, known):
        from ._blocks import pieces

        check_type("d", d, Sinusoids | Piecewise, "an fdsc.Sinusoids or fdsc.Piecewise")
        H = as_positive("horizon", horizon)
        what = d if estimate is None else estimate
        if estimate is not None:
            check_type("estimate", estimate, Sinusoids | Piecewise, "an fdsc.Sinusoids or fdsc.Piecewise")
            _check_covers(estimate, d, H)
        plant, n = self.plant, self.plant.n_states
        x = np.zeros(n) if x0 is None else np.array(as_vector("x0", x0, n))
        # run at a scale (a power of two, exact) where the energies and the identification's lag
        # covariance keep their digits: the loop is linear in (x0, d, ŵ), the identification
        # invariant to the scale, so the run takes the same decisions
        e_scale = _scale_exponent(x, d, estimate)
        x = np.ldexp(x, -e_scale)
        d, estimate = _scaled(d, e_scale), _scaled(estimate, e_scale)
        what = d if estimate is None else estimate
        Af, Ef, Cf, Ff = self._base
        x = np.r_[x, np.zeros(Af.shape[0])]                  # the base filter's states start at rest
        zk = np.zeros(Af.shape[0])
        pd, pw = pieces(d, H), pieces(what, H)
        nyq = math.pi / self.step
        sampled = _lowpass(what, nyq)
        first = min(self.window, 0.5)
        k0, k1 = math.ceil(first / self.update - 1e-9), math.floor(H / self.update - 1e-9)
        ups = np.arange(k0, k1 + 1) * self.update
        ups = ups[ups < H]
        edges = np.union1d(np.r_[0.0, ups, H], [p[0] for p in pd] + [p[0] for p in pw])
        edges = edges[np.r_[True, np.diff(edges) > 1e-9 * max(1.0, H)]]
        edges[-1] = H
        upset = set(np.round(ups / self.update).astype(np.int64).tolist())
        lo_d = np.array([p[0] for p in pd])
        lo_w = np.array([p[0] for p in pw])
        model = None                        # (time, ω, c, u per unit)
        energy, n_id, n_tones = 0.0, 0, 0
        per_output, rows = np.zeros(plant.C.shape[0]), []
        B1, B2, D1, D2 = plant.B1[:, 0], plant.B2, plant.D1[:, 0], plant.D2
        for t0, t1 in zip(edges[:-1], edges[1:], strict=True):
            k = round(t0 / self.update)
            if abs(t0 - k * self.update) < 1e-9 * max(1.0, H) and k in upset:
                if known:
                    _a, _b, w, a, ph = pd[int(np.searchsorted(lo_d, t0 + 1e-12, side="right") - 1)]
                    sel = (w >= self.band[0]) & (w <= self.band[1])
                    c = a[sel] * np.exp(1j * (w[sel] * t0 + ph[sel])) / 1j
                    model = (t0, w[sel], c, self._ff_gain(w[sel])) if sel.any() else None
                else:
                    model = self._identify(sampled, t0)
                n_id += 1
                n_tones += 0 if model is None else model[1].size
            L = t1 - t0
            jd = int(np.searchsorted(lo_d, t0 + 1e-12, side="right") - 1)
            jw = int(np.searchsorted(lo_w, t0 + 1e-12, side="right") - 1)
            sd, cd = tone_terms(t0, *pd[jd][2:])
            sw, cw = tone_terms(t0, *pw[jw][2:])
            vw = cw[:, None] * Ff[None, :]
            s = [sd, sw]
            b = [np.hstack([cd[:, None] * B1[None, :], np.zeros((sd.size, zk.size))]),
                 np.hstack([vw @ B2.T, cw[:, None] * Ef[None, :]])]
            dz = [cd[:, None] * D1[None, :], vw @ D2.T]
            if model is not None:
                tm, w, c, g = model
                cc = c * np.exp(1j * w * (t0 - tm)) / 2
                vm = np.vstack([cc[:, None] * g, (cc.conj())[:, None] * g.conj()])
                s.append(np.concatenate([1j * w, -1j * w]))
                b.append(np.hstack([vm @ B2.T, np.zeros((vm.shape[0], zk.size))]))
                dz.append(vm @ D2.T)
            s = np.concatenate(s)
            e, an, gz, x = self._modal.piece(x, s, np.zeros(s.size, dtype=bool), np.vstack(b),
                                             np.vstack(dz), L)
            diag = np.diag(Modal.gram(e, an, gz, L))
            energy += float(np.sum(diag))
            per_output += diag
            rows.append((t0, t1, float(np.sum(diag))))
        if not math.isfinite(energy):
            raise EnergyOverflowError("PredictiveLaw: the energy exceeds the float range (about 1.8e308)")
        energy = _unscale(energy, e_scale, where="PredictiveLaw: ")
        with np.errstate(over="ignore"):
            per_output = np.ldexp(per_output, 2 * e_scale)
            pieces_ = np.array(rows, dtype=float).reshape(-1, 3)
            pieces_[:, 2] = np.ldexp(pieces_[:, 2], 2 * e_scale)
        return PredictiveRun(energy, H, n_id, n_tones / n_id if n_id else 0.0, per_output, pieces_)

    def _identify(self, sampled, t):
        """The model at time t from the last window of samples (None if none is usable)."""
        W = min(self.window, t)
        k = int(math.floor(W / self.step + 1e-9))
        if k < 2 * (self.trend + 1) + 8:
            return None
        tt = t - self.step * np.arange(k, -1, -1)
        y = sampled(tt)
        w = _esprit(y, self.step, self.band[0], self.band[1], self.max_tones, self.lags, self.rank_tol,
                    EDGE_SHARE)
        if not w.size:
            return None
        c, res = _fit(tt - t, y, w, self.trend)
        if np.max(np.abs(c)) > self.amplitude_cap * max(float(np.max(np.abs(y))), 1e-300):
            return None
        if res > self.max_residual * float(np.mean(y ** 2)):
            return None
        return (t, w, c, self._ff_gain(w))

    def run(self, d, horizon: float, *, estimate=None, x0=None) -> PredictiveRun:
        """The law on the disturbance d, reading the estimate (default ŵ = d).

        Parameters
        ----------
        d : Sinusoids or Piecewise
            The disturbance.
        horizon : float
            H > 0 (s).
        estimate : Sinusoids or Piecewise, optional
            What the law reads as ŵ (d with measurement noise, say); default d.
        x0 : (n,) array_like, optional

        Returns
        -------
        PredictiveRun

        Raises
        ------
        TypeError
            If d or estimate is not a Sinusoids or Piecewise.
        ValueError
            If horizon or x0 is out of range, or estimate is a Piecewise whose breaks do not
            cover the part of [0, horizon] where d acts.
        EnergyOverflowError
            If the energy exceeds the float range in the units of d.

        Warns
        -----
        EnergyUnderflowWarning
            If the energy is below the smallest normal float in the units of d (the run is made
            at a scale where it keeps its digits, and its identifications stand).
        """
        return self._run(d, horizon, estimate, x0, known=False)

    def run_known(self, d, horizon: float, *, x0=None) -> PredictiveRun:
        """The same law with the tones of d's current piece in the band known exactly at every
        update (ideal identification; no break of d is foreseen): a reference for what the
        identification costs, not a realizable law.

        Parameters
        ----------
        d : Sinusoids or Piecewise
        horizon : float
        x0 : (n,) array_like, optional

        Returns
        -------
        PredictiveRun
        """
        return self._run(d, horizon, None, x0, known=True)


def _span(d, H):
    """Where in [0, H] the signal d may be nonzero (a Piecewise is zero outside its breaks)."""
    if isinstance(d, Sinusoids):
        return 0.0, H
    return min(max(float(d.breaks[0]), 0.0), H), max(min(float(d.breaks[-1]), H), 0.0)


def _check_covers(estimate, d, H):
    """Refuse an estimate that is zero (its breaks' end) where d is not."""
    a, b = _span(d, H)
    e0, e1 = _span(estimate, H)
    if b > a and (e0 > a or e1 < b):
        e0, e1 = float(estimate.breaks[0]), float(estimate.breaks[-1])
        raise ValueError(f"estimate must cover [{a:g}, {b:g}] s, where d acts within the horizon {H:g} s, "
                         f"but its breaks span [{e0:g}, {e1:g}] s (a Piecewise is zero outside them, so the "
                         "law would read ŵ = 0 there): give an estimate over the whole horizon")


def _lowpass(d, nyquist):
    """d without its tones above ``nyquist`` (an ideal anti-alias filter before the sampler)."""
    if isinstance(d, Sinusoids):
        keep = d.frequencies < nyquist
        return Sinusoids(d.amplitudes[keep], d.frequencies[keep], d.phases[keep])
    return Piecewise(d.breaks, [_lowpass(p, nyquist) for p in d.parts])
