"""The disturbance observer of the observer rung (:mod:`fdsc.paper.pays.observer_rung`) and the
predictive law that reads ŵ through it.

The observer is the steady-state Kalman–Bucy filter of the plant augmented with d as a random walk,
reading x through a sensor with white noise on each state and told the control it applies. As it
knows u, its error does not depend on the controller: ``ŵ = F(s) d + N(s) v`` with F and N fixed
(:func:`observer_filters`; ``F(0) = 1``). A controller reading x and ŵ becomes, with it, one
controller reading the sensor alone (:func:`with_observer`), whose loop on d is that of the
controller reading ``F(s) d`` (:func:`filtered_base`) and whose noise reaches z through
:func:`sensor_loop`. :class:`ObservedLaw` is the predictive law with a confidence check reading ŵ
through the observer.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.linalg import solve_continuous_are

from fdsc.confident import ConfidentPredictiveLaw
from fdsc.controller import Controller
from fdsc.measurement_noise import noise_power
from fdsc.plant import LTISystem
from fdsc.signals import Piecewise, Sinusoids
from fdsc.simulate import particular

__all__ = ["kalman_bucy", "observer_filters", "with_observer", "filtered_base", "sensor_loop",
           "sensor_noise_power", "ObservedLaw"]

def kalman_bucy(plant, densities, q: float) -> tuple:
    """The steady-state Kalman–Bucy filter of the plant augmented with d as a random walk.

    The augmented state ``ξ = (x, d)`` obeys ``ξ' = F_a ξ + B_u u + G ω`` (``G = [0; 1]``, ω white
    of intensity q) and is measured as ``x_m = H ξ + v`` (``H = [I, 0]``, v white of intensity
    ``diag(densities)``); the filter is ``ξ̂' = F_a ξ̂ + B_u u + L (x_m − H ξ̂)`` with
    ``L = P Hᵀ V⁻¹``, P the stabilizing solution of ``F_a P + P F_aᵀ − P Hᵀ V⁻¹ H P + q G Gᵀ = 0``.

    Parameters
    ----------
    plant : Plant
        One disturbance input.
    densities : (n,) array_like
        The noise's two-sided spectral density on each state (> 0).
    q : float
        The random walk's intensity (> 0).

    Returns
    -------
    (Ae, L, G, P) : tuple of ndarray
        The error dynamics ``Ae = F_a − L H`` (Hurwitz), the gain, G and P.
    """
    n = plant.n_states
    S = np.asarray(densities, dtype=float).reshape(-1)
    if S.shape != (n,) or not np.all(S > 0) or not np.all(np.isfinite(S)):
        raise ValueError(f"densities must be {n} finite numbers > 0 (one per state), but found {densities!r}")
    q = float(q)
    if not q > 0 or not math.isfinite(q):
        raise ValueError(f"q must be a finite number > 0, but found {q!r}")
    if plant.B1.shape[1] != 1:
        raise ValueError(f"plant must have one disturbance input, but has {plant.B1.shape[1]}")
    Fa = np.block([[plant.A, plant.B1], [np.zeros((1, n + 1))]])
    H = np.hstack([np.eye(n), np.zeros((n, 1))])
    G = np.r_[np.zeros(n), 1.0][:, None]
    V = np.diag(S)
    P = solve_continuous_are(Fa.T, H.T, q * (G @ G.T), V)
    P = (P + P.T) / 2
    L = P @ H.T / S[None, :]
    Ae = Fa - L @ H
    if np.max(np.linalg.eigvals(Ae).real) >= 0:
        raise ValueError("kalman_bucy: the filter's error dynamics are not stable")
    return Ae, L, G, P


def observer_filters(Ae, L, G) -> tuple:
    """``ŵ = F(s) d + N(s) v`` of the observer (module docstring): ``F = (Ae, G, −C_η Ae, 0)``,
    ``N = (Ae, L, C_η, 0)``, C_η reading the estimate of d (the last augmented state).

    Parameters
    ----------
    Ae, L, G : ndarray
        :func:`kalman_bucy`'s.

    Returns
    -------
    (LTISystem, LTISystem)
        F (one input, d) and N (one input per state, v).
    """
    N = Ae.shape[0]
    Ceta = np.zeros((1, N))
    Ceta[0, -1] = 1.0
    return (LTISystem(Ae, G, -Ceta @ Ae, np.zeros((1, 1))),
            LTISystem(Ae, L, Ceta, np.zeros((1, L.shape[1]))))


def with_observer(ctrl: Controller, plant, Ae, L) -> Controller:
    """A controller reading x and ŵ, with ŵ from the observer: one controller reading ``x_m``
    alone (its states: the observer's, then the controller's). A controller that does not read ŵ
    is returned as it is.

    Parameters
    ----------
    ctrl : Controller
    plant : Plant
    Ae, L : ndarray
        :func:`kalman_bucy`'s.

    Returns
    -------
    Controller
    """
    if not ctrl.reads_estimate:
        return ctrl
    N = Ae.shape[0]
    Ceta = np.zeros((1, N))
    Ceta[0, -1] = 1.0
    Bu = np.vstack([plant.B2, np.zeros((1, plant.n_controls))])
    A, B, C, D, E, F = ctrl.A, ctrl.B, ctrl.C, ctrl.D, ctrl.E, ctrl.F
    k = ctrl.n_states
    Ac = np.block([[Ae + Bu @ F @ Ceta, Bu @ C], [E @ Ceta, A]]) if k else Ae + Bu @ F @ Ceta
    Bc = np.vstack([Bu @ D + L, B]) if k else Bu @ D + L
    Cc = np.hstack([F @ Ceta, C]) if k else F @ Ceta
    return Controller(Ac, Bc, Cc, D, name=f"{ctrl.name} with the observer")


def filtered_base(ctrl: Controller, Ae, G) -> Controller:
    """The controller ``u = K x + Q(s) F(s) ŵ``: ``ctrl`` (``u = K x + Q(s) ŵ``, its states driven
    by ŵ alone) reading ŵ through the observer's F (:func:`observer_filters`). With ŵ = d it is,
    on d, the loop of ``with_observer(ctrl)`` without noise.

    Parameters
    ----------
    ctrl : Controller
        Reads ŵ; ``B = 0``.
    Ae, G : ndarray

    Returns
    -------
    Controller
    """
    N, k = Ae.shape[0], ctrl.n_states
    Ceta = np.zeros((1, N))
    Ceta[0, -1] = 1.0
    out = -Ceta @ Ae
    A = np.block([[Ae, np.zeros((N, k))], [ctrl.E @ out, ctrl.A]]) if k else Ae
    E = np.vstack([G, np.zeros((k, 1))])
    C = np.hstack([ctrl.F @ out, ctrl.C])
    return Controller(A, np.zeros((N + k, ctrl.D.shape[1])), C, ctrl.D, E, np.zeros_like(ctrl.F),
                      name=f"{ctrl.name} reading F(s) ŵ")


def sensor_loop(plant, ctrl: Controller) -> LTISystem:
    """The closed loop from the sensor's noise v (one input per state, entering where the
    controller reads x) to z, for a controller reading x alone (d = 0).

    Parameters
    ----------
    plant : Plant
    ctrl : Controller
        Reads x alone (:func:`with_observer`'s, or one that never read ŵ).

    Returns
    -------
    LTISystem
    """
    if ctrl.reads_estimate:
        raise ValueError(f"ctrl {ctrl.name!r} reads ŵ: give it with its observer (with_observer)")
    loop = plant.closed_loop(ctrl)
    Bv = np.vstack([plant.B2 @ ctrl.D, ctrl.B])
    return LTISystem(loop.A, Bv, loop.C, plant.D2 @ ctrl.D)


def sensor_noise_power(plant, ctrl: Controller, densities, nyquist: float) -> float:
    """The mean power the sensor's noise adds to z in the loop of ``ctrl`` (reading x alone):
    the sum over the states of :func:`fdsc.measurement_noise.noise_power` (the noises are
    independent).

    Parameters
    ----------
    plant : Plant
    ctrl : Controller
    densities : (n,) array_like
    nyquist : float

    Returns
    -------
    float
    """
    loop = sensor_loop(plant, ctrl)
    S = np.asarray(densities, dtype=float).reshape(-1)
    return float(sum(noise_power(LTISystem(loop.A, loop.B[:, [i]], loop.C, loop.D[:, [i]]), S[i], nyquist)
                     for i in range(S.size)))


class ObservedLaw(ConfidentPredictiveLaw):
    """:class:`fdsc.confident.ConfidentPredictiveLaw` reading ŵ from the observer (module
    docstring): its base is :func:`filtered_base`'s, its identifications read samples of
    ``F(s) d + N(s) v``, and it divides each identified tone by ``F(jω)``.

    Parameters
    ----------
    plant, band : as the parent
        The plant and the identification's band.
    observer : (Ae, L, G)
        :func:`kalman_bucy`'s.
    densities : (n,) array_like
        The sensor's noise densities.
    base : Controller
        The controller ``u = K x + Q(s) ŵ`` the law corrects, before its observer (its states
        driven by ŵ alone); the law's base is :func:`filtered_base` of it.
    **kwargs
        The parent's settings (``base`` is the controller reading ŵ before its observer).
    """

    def __init__(self, plant, band, *, observer, densities, base, **kwargs):
        Ae, L, G = observer
        super().__init__(plant, band, base=filtered_base(base, Ae, G), **kwargs)
        self._F, self._N = observer_filters(Ae, L, G)
        self._S = np.asarray(densities, dtype=float).reshape(-1)
        lam, V = np.linalg.eig(Ae)
        self._lam, self._V, self._Vi = lam, V, np.linalg.inv(V)
        # the spectrum of the samples of N(s) v: the sensor's noise is band-limited to the sampler's
        # Nyquist frequency Ω = π/step, so the samples' spectrum is Σ S_i |N_i(jθ/h)|² / h on |θ| ≤ π,
        # without aliasing; drawn by spectral synthesis on M ≥ 4 windows' worth of points
        m = int(math.floor(self.window / self.step + 1e-9)) + 1
        M = 1 << max(12, (4 * m - 1).bit_length())
        theta = 2 * np.pi * np.minimum(np.arange(M), M - np.arange(M)) / M         # |θ| on the grid
        w = theta / self.step
        R = np.linalg.solve(1j * w[:, None, None] * np.eye(Ae.shape[0])[None] - Ae[None],
                            np.broadcast_to(L, (w.size, *L.shape)))              # (M, N, n)
        resp = np.einsum("k,wkn->wn", self._N.C[0], R)                          # N_i(jω)
        self._psd = np.sum(np.abs(resp) ** 2 * self._S[None, :], axis=1) / self.step
        self._M = M
        self._d, self._seed_obs = None, 0

    def run(self, d, horizon, *, seed: int = 0, **kwargs):
        """The law on d (the parent's ``run``), its samples read through the observer.

        Parameters
        ----------
        d : Sinusoids or Piecewise
            The disturbance.
        horizon : float
            H > 0 (s).
        seed : int, optional
            The noise of the identification at update k is drawn from
            ``numpy.random.default_rng([seed, k])``.
        **kwargs
            The parent's other arguments (``x0``; ``estimate`` and ``noise`` are not used: the
            observer's output is what the law reads).

        Returns
        -------
        PredictiveRun
        """
        self._d, self._seed_obs = d, int(seed)
        self._states = self._piece_states(d, horizon)
        return super().run(d, horizon, seed=seed, **kwargs)

    def _piece_states(self, d, horizon):
        """The state of F's realization at each piece's start (from rest, exact); d is zero
        before its first break and after its last."""
        Ae, G = self._F.A, self._F.B
        zero = Sinusoids([0.0], [1.0])
        if isinstance(d, Piecewise):
            b = [float(x) for x in d.breaks]
            parts = [(min(0.0, b[0]), zero)] + list(zip(b[:-1], d.parts, strict=True)) + [(b[-1], zero)]
        else:
            parts = [(0.0, d)]
        out, f = [], np.zeros(Ae.shape[0])
        for j, (t0, part) in enumerate(parts):
            out.append((t0, part, f.copy()))
            t1 = parts[j + 1][0] if j + 1 < len(parts) else None
            if t1 is None or t1 <= t0:
                continue
            xp0 = particular(Ae, G, part, [t0])[0][0]
            xp1 = particular(Ae, G, part, [t1])[0][0]
            f = (self._V @ (np.exp(self._lam * (t1 - t0)) * (self._Vi @ (f - xp0)))).real + xp1
        return out

    def _filtered(self, tt):
        """``F(s) d`` at the times tt (exact: each piece's transient plus its tones' response)."""
        Ae, G, C = self._F.A, self._F.B, self._F.C
        out = np.empty(tt.size)
        starts = np.array([s[0] for s in self._states])
        idx = np.clip(np.searchsorted(starts, tt, side="right") - 1, 0, len(starts) - 1)
        for j in np.unique(idx):
            sel = idx == j
            t0, part, f0 = self._states[j]
            xp = particular(Ae, G, part, tt[sel])[0]
            xp0 = particular(Ae, G, part, [t0])[0][0]
            decay = np.exp(np.outer(self._lam, tt[sel] - t0))
            tr = (self._V @ (decay * (self._Vi @ (f0 - xp0))[:, None])).real
            out[sel] = (C @ (xp.T + tr))[0]
        return out

    def _noise(self, m, key):
        """m consecutive samples of ``N(s) v`` at the step, v band-limited to the sampler's Nyquist
        frequency: a stationary Gaussian sequence of the samples' spectrum (spectral synthesis on
        M points, so its covariance is the spectrum's to the grid's resolution), drawn from
        ``default_rng([seed, key])``."""
        if m > self._M:
            raise ValueError(f"m must be at most {self._M} samples, but found {m}")
        rng = np.random.default_rng([self._seed_obs, key])
        z = rng.standard_normal(self._M) + 1j * rng.standard_normal(self._M)
        x = np.fft.ifft(np.sqrt(self._psd / self._M) * z) * self._M
        return x.real[:m]

    def _identify(self, sampled, t):
        key = int(round(t / self.update))

        def observed(tt):
            tt = np.asarray(tt, dtype=float)
            return (self._filtered(tt) + self._noise(tt.size, key)) * self._unit

        model = super()._identify(observed, t)
        if model is None:
            return None
        end, w, c, g = model
        return (end, w, c / self.response(w), g)

    def response(self, w):
        """``F(jω)`` at the frequencies w: what the observer makes of a tone of d.

        Parameters
        ----------
        w : array_like
            Frequencies (rad/s).

        Returns
        -------
        ndarray
            Complex, one per frequency.
        """
        w = np.asarray(w, dtype=float).reshape(-1)
        A, B, C = self._F.A, self._F.B, self._F.C
        M = 1j * w[:, None, None] * np.eye(A.shape[0])[None] - A[None]
        return (C @ np.linalg.solve(M, np.broadcast_to(B, (w.size, *B.shape))))[:, 0, 0]
