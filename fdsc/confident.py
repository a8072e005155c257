"""A predictive law that corrects its base only as far as its prediction is confirmed.

:class:`fdsc.PredictiveLaw` corrects a fixed feedforward of ŵ (its *base*) to the optimal one on
the tones it identifies in the last seconds of ŵ. On exact samples that pays; on noisy samples,
or where the past does not predict the future (a break of d, a disturbance that is not a few
tones), a wrong correction costs more than the base alone. :class:`ConfidentPredictiveLaw` is the
same law with three changes, each a setting:

* **identification near the Cramér–Rao bound on noisy samples**: ESPRIT on the samples
  themselves (not on their second differences, which multiply white noise by 6 on average and
  a tone low in the band by ``(2 sin(ωh/2))²`` ≪ 1), its lags a third of the window (at most
  ``max_lags``), its rank set by the noise floor of the lag covariance (the eigenvalues that stand
  ``floor_factor`` times above the largest a white noise of the median eigenvalue's level would
  give; :func:`fdsc.tone_bound.frequency_bound` is the bound);
* **a check on held-out samples**: the tones are identified on the window less its last
  ``holdout`` share, their prediction of that share is compared with what was sampled there
  (after a straight line, which carries the slow part), and the least-squares weight
  ``α = ⟨y, p⟩ / ⟨p, p⟩`` of the prediction p in the held-out samples y is the law's
  confidence (1 for a prediction that the samples confirm, near 0 for one they do not); the
  correction, on the tones refitted to the whole window, is applied where α is at least
  ``confidence``, and not at all elsewhere: the base acts alone until the next identification
  (scaling the correction by α instead was tried: a noisy α then shrinks good corrections);
* **measurement noise, delay and model error**: :meth:`ConfidentPredictiveLaw.run` adds white
  Gaussian noise of a stated variance to every sample it reads (seeded, independent at each
  sample); ``delay`` seconds of computation separate the last sample an identification reads
  from the time its correction starts; ``true_A`` runs the law, designed on the plant's model,
  on a plant whose A differs (the estimate it reads stays d itself, as if measured directly).

With the base the best fixed controller of the form ``u = K x + Q(s) ŵ`` (K the LQ gain;
:func:`fdsc.optimal_lti`, or :func:`fdsc.measurement_noise.optimal_lti_in_noise` for a noisy ŵ),
the law falls back to that controller wherever its prediction is not confirmed. Its energy on a
run counts the noise of the samples (through the corrections they set); the noise the base's
continuous filter reads is not simulated: add its expectation
(:func:`fdsc.measurement_noise.noise_power` of the base's loop times the horizon).
"""

from __future__ import annotations

import math

import numpy as np

from ._modal import Modal
from ._tones import _fit, _frequencies, _hankel_gram
from ._validation import as_count, as_matrix, as_positive, check_type
from .decisions import _scale_exponent
from .exceptions import UnstableError
from .predictive import EDGE_SHARE, PredictiveLaw, PredictiveRun
from .signals import Piecewise, Sinusoids

__all__ = ["ConfidentPredictiveLaw", "raw_esprit", "DEFAULT_MAX_LAGS", "DEFAULT_FLOOR_FACTOR"]

#: The most lags of :func:`raw_esprit` (a third of the window, at most this).
DEFAULT_MAX_LAGS = 160
#: Eigenvalues of the lag covariance kept as signal: above this times the largest that white
#: noise at the median eigenvalue's level gives (the Marchenko–Pastur edge).
DEFAULT_FLOOR_FACTOR = 2.0


def raw_esprit(y, step: float, band, *, max_tones: int = 12, max_lags: int = DEFAULT_MAX_LAGS,
               floor_factor: float = DEFAULT_FLOOR_FACTOR, rank_tol: float = 1e-5) -> np.ndarray:
    """The frequencies in ``band`` of the tones in the samples y, by ESPRIT on the samples.

    Parameters
    ----------
    y : (N,) array_like
        Samples at the step, oldest first.
    step : float
        h > 0 (s).
    band : (float, float)
        Where frequencies are kept (rad/s), ``0 ≤ lo < hi ≤ π/h``.
    max_tones : int, optional
        The most tones in the band; the subspace holds twice as many directions plus those of
        the slow part (up to four more).
    max_lags : int, optional
        Lags of the lag matrix: a third of N, at most this.
    floor_factor : float, optional
        Module docstring.
    rank_tol : float, optional
        Directions below ``rank_tol`` times the largest singular value of the lag matrix are
        dropped in any case (exact samples have no noise floor but rounding's; default 1e-5,
        which keeps a slow trend's second direction).

    Returns
    -------
    (k,) ndarray
        Sorted; empty if none is found.

    Raises
    ------
    ValueError
        If an argument is out of range, or y has fewer than 12 samples.

    Examples
    --------
    >>> t = 0.01 * np.arange(400)
    >>> y = np.cos(7.0 * t + 0.3) + 0.5 * np.cos(19.0 * t) + 3.0 + 0.1 * t
    >>> np.round(raw_esprit(y, 0.01, (2.0, 100.0)), 6).tolist()
    [7.0, 19.0]
    """
    y = np.asarray(y, dtype=float)
    if y.ndim != 1 or y.size < 12:
        raise ValueError(f"y must be a vector of at least 12 samples, but has shape {y.shape}")
    if not np.all(np.isfinite(y)):
        raise ValueError("y must be finite")
    h = as_positive("step", step)
    lo, hi = (float(v) for v in band)
    if not 0 <= lo < hi or hi > math.pi / h * (1 + 1e-12):
        raise ValueError(f"band must be (lo, hi) with 0 ≤ lo < hi ≤ π/step = {math.pi / h:.6g}, but found "
                         f"{band!r}")
    max_tones = as_count("max_tones", max_tones, 1)
    max_lags = as_count("max_lags", max_lags, 3)
    floor_factor = as_positive("floor_factor", floor_factor)
    rank_tol = as_positive("rank_tol", rank_tol)
    L = max(3, min(max_lags, y.size // 3))
    rows = y.size - L + 1
    ev, vec = np.linalg.eigh(_hankel_gram(y, L))
    ev, vec = ev[::-1], vec[:, ::-1]
    if not ev[0] > 0:
        return np.zeros(0)
    cap = min(2 * max_tones + 4, L - 1)
    floor = float(np.median(ev[cap:])) if ev.size > cap else 0.0
    edge = floor * (1.0 + math.sqrt(L / rows)) ** 2
    r = int(min(cap, np.sum((ev > floor_factor * edge) & (ev > rank_tol ** 2 * ev[0]))))
    if r < 1:
        return np.zeros(0)
    return _frequencies(vec[:, :r], h, lo, hi, h * (y.size - 1), EDGE_SHARE)


class ConfidentPredictiveLaw(PredictiveLaw):
    """:class:`fdsc.PredictiveLaw` with raw-sample identification, a confidence from held-out
    samples, measurement noise and delay (module docstring).

    Parameters
    ----------
    plant, band : as :class:`fdsc.PredictiveLaw`
    holdout : float, optional
        The share of each window held out to check the prediction (0 < holdout < 1; default
        0.25).
    confidence : float, optional
        The least confidence α (module docstring) at which the correction is applied (default
        0.5; 0 applies every correction times max(α, 0)).
    delay : float, optional
        Seconds between the last sample an identification reads and the start of its
        correction (≥ 0, less than ``window``; default 0; one update, ``update``, models a
        computation that takes until the next identification).
    true_A : (n, n) array_like, optional
        The A of the plant the law runs on, where it differs from the model's (``plant``), on
        which the law's gain, base and adjoint stay designed; the loop ``true_A + B2 K`` with
        the base must be stable.
    max_lags, floor_factor : optional
        See :func:`raw_esprit`.
    **kwargs
        The other settings of :class:`fdsc.PredictiveLaw` (``window``, ``update``, ``step``,
        ``max_tones``, ``trend``, ``amplitude_cap``, ``max_residual``, ``base``; ``lags`` and
        ``rank_tol`` are not used).

    Examples
    --------
    On a held pair of tones read through 20 dB of white noise it takes most of the way from its
    base alone (the static feedforward, 1.99 times the non-causal limit) to the limit:

    >>> from fdsc import Plant, noncausal_limit
    >>> p = Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
    ...           [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.3]])
    >>> d = Sinusoids([1.0, 0.5], [3.0, 7.0])
    >>> law = ConfidentPredictiveLaw(p, (1.0, 20.0), window=3.0, step=0.05)
    >>> run = law.run(d, 100.0, noise=0.625 / 100, seed=1)
    >>> bool(run.energy / noncausal_limit(p, d, 100.0).energy < 1.3)
    True
    """

    def __init__(self, plant, band, *, holdout: float = 0.25, confidence: float = 0.5, delay: float = 0.0,
                 true_A=None, max_lags: int = DEFAULT_MAX_LAGS, floor_factor: float = DEFAULT_FLOOR_FACTOR,
                 **kwargs):
        super().__init__(plant, band, **kwargs)
        if true_A is not None:
            n = self.plant.n_states
            A = as_matrix("true_A", true_A, (n, n))
            Af, _Ef, Cf, _Ff = self._base
            k, B2 = Af.shape[0], self.plant.B2
            try:
                self._modal = Modal(np.block([[A + B2 @ self.lq.K, B2 @ Cf], [np.zeros((k, n)), Af]]),
                                    np.hstack([self.lq.Cz, self.plant.D2 @ Cf]),
                                    "the loop on true_A (true_A + B2 K with the base)")
            except UnstableError as exc:
                raise ValueError(f"true_A: {exc}") from None
        holdout = float(holdout)
        if not 0 < holdout < 1:
            raise ValueError(f"holdout must be a share strictly between 0 and 1, but found {holdout!r}")
        self.holdout = holdout
        c = float(confidence)
        if not 0 <= c <= 1:
            raise ValueError(f"confidence must lie in [0, 1], but found {confidence!r}")
        self.confidence = c
        delay = float(delay)
        if not 0 <= delay < self.window:
            raise ValueError(f"delay must lie in [0, window = {self.window:g}) s, but found {delay!r}")
        self.delay = delay
        self.max_lags = as_count("max_lags", max_lags, 3)
        self.floor_factor = as_positive("floor_factor", floor_factor)
        self._noise_sd, self._seed, self._unit = 0.0, 0, 1.0
        self.confidences: list = []

    def run(self, d, horizon: float, *, estimate=None, x0=None, noise: float = 0.0,
            seed: int = 0) -> PredictiveRun:
        """The law on d, reading samples of the estimate (default ŵ = d) with white noise.

        Parameters
        ----------
        d, horizon, estimate, x0 : as :meth:`fdsc.PredictiveLaw.run`
        noise : float, optional
            The variance σ² ≥ 0 of the white Gaussian noise added to each sample, in the units of
            d squared (default 0).
        seed : int, optional
            The noise of the identification at update k is drawn from
            ``numpy.random.default_rng([seed, k])``.

        Returns
        -------
        PredictiveRun
            After the run, :attr:`confidences` holds each identification's ``(time, α)`` (α
            NaN where no tone was found).
        """
        v = float(noise)
        if not v >= 0 or not math.isfinite(v):
            raise ValueError(f"noise must be a variance (a finite number ≥ 0), but found {noise!r}")
        check_type("seed", seed, int, "an int")
        check_type("d", d, Sinusoids | Piecewise, "an fdsc.Sinusoids or fdsc.Piecewise")
        n = self.plant.n_states
        x = np.zeros(n) if x0 is None else np.asarray(x0, dtype=float)
        # _run works at a power-of-two scale of d (exact); the noise is scaled with it
        try:
            e = _scale_exponent(x, d, estimate)
        except (TypeError, ValueError):
            e = 0
        self._noise_sd, self._seed, self._unit = math.sqrt(v), seed, math.ldexp(1.0, -e)
        self.confidences = []
        return super().run(d, horizon, estimate=estimate, x0=x0)

    def _identify(self, sampled, t):
        """The model at time t from the window ending ``delay`` before it (None if none is
        usable or confirmed)."""
        end = t - self.delay
        W = min(self.window, end)
        k = int(math.floor(W / self.step + 1e-9))
        m = int(round(self.holdout * (k + 1)))
        if k + 1 - m < 36 or m < 2 * (self.trend + 1) + 2:
            return None
        tt = end - self.step * np.arange(k, -1, -1)
        y = sampled(tt)
        if self._noise_sd > 0:
            rng = np.random.default_rng([self._seed, int(round(t / self.update))])
            y = y + self._noise_sd * self._unit * rng.standard_normal(y.size)
        fit_t, fit_y, held_t, held_y = tt[:-m], y[:-m], tt[-m:], y[-m:]
        w = raw_esprit(fit_y, self.step, self.band, max_tones=self.max_tones, max_lags=self.max_lags,
                       floor_factor=self.floor_factor)
        if not w.size:
            self.confidences.append((t, math.nan))
            return None
        c, _res = _fit(fit_t - fit_t[-1], fit_y, w, self.trend)
        tau = held_t - fit_t[-1]
        p = np.real(np.exp(1j * np.outer(tau, w)) @ c)
        # the held-out samples and the prediction without their slow part (a polynomial trend)
        s = (held_t - held_t[0]) / max(held_t[-1] - held_t[0], 1e-300)
        P = np.vander(s, 2)
        Pp = np.linalg.pinv(P)
        yp, pp = held_y - P @ (Pp @ held_y), p - P @ (Pp @ p)
        den = float(pp @ pp)
        alpha = float(yp @ pp) / den if den > 0 else 0.0
        self.confidences.append((t, alpha))
        if alpha < self.confidence or alpha <= 0:
            return None
        c, res = _fit(tt - end, y, w, self.trend)
        if np.max(np.abs(c)) > self.amplitude_cap * max(float(np.max(np.abs(y))), 1e-300):
            return None
        if res > self.max_residual * float(np.mean(y ** 2)):
            return None
        return (end, w, c, self._ff_gain(w))
