"""An adaptive regulator for unknown, time-varying disturbances: a finite-impulse-response filter
of the estimate ŵ, its coefficients fitted online by recursive least squares.

Every Youla–Kučera controller of the plant reading x and ŵ is ``u = K x + Q(ŵ)`` with Q a stable
filter (:mod:`fdsc.optimal_lti` picks the best fixed Q for a class). Adaptive regulation fits Q to
the disturbance at hand instead (Landau, Constantinescu and Rey 2005; the benchmark of Landau et
al. 2013): here Q is the base feedforward F_b (fixed) plus an FIR filter on samples of ŵ,

    u(t) = K x(t) + F_b(ŵ)(t) + v_k,        v_k = Θ_k [ŵ(t_k), ŵ(t_{k−1}), …, ŵ(t_{k−N+1})],

held over the step ``[t_k, t_k + h)``, with K the LQ gain. The output the law sees at ``t_k``
(from what it reads: ``z = C x + D1 ŵ + D2 u``) is split by the law's own model of the loop
into the part its past inputs v made and the rest, e₀; with Θ held, z would be ``e₀ + Φ_k
vec(Θ)``, where the columns of Φ_k are ŵ filtered by the model's path from v to z and delayed
by each tap (the filtered regressors). Θ_k minimizes the exponentially forgotten sum

    Σ_{l ≤ k} λ^{k−l} ‖e₀(t_l) + Φ_l vec(Θ)‖² + δ ‖vec(Θ)‖²,      λ = e^{−h/memory},

the recursive least squares of the modified error (with an exact model the adaptation does not
feed back through the loop: e₀ does not depend on the v applied). It is realizable: it reads x
and samples of ŵ up to t_k, and uses the plant's model as :class:`fdsc.PredictiveLaw` does.

The loop is run exactly: within a step v is held and the tones of d and ŵ are known, so the
state and ``∫ ‖z‖²`` over the step are a linear map and a quadratic form of the state augmented
with the tones' oscillators and v (:func:`fdsc._blocks._gram`), one per piece of d and step
length; no quadrature.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from ._blocks import _augmented, _gram, _merged, pieces
from ._validation import as_count, as_positive, as_vector, check_type
from .exceptions import EnergyOverflowError
from .noncausal import lq_data
from .plant import as_plant
from .signals import Piecewise, Sinusoids

__all__ = ["AdaptiveRun", "AdaptiveFeedforward"]

#: Default taps of the FIR filter, memory of the least squares (s), and regularization.
DEFAULT_TAPS, DEFAULT_MEMORY, DEFAULT_REGULARIZATION = 16, 4.0, 1e-6


@dataclass(frozen=True)
class AdaptiveRun:
    """One run of an :class:`AdaptiveFeedforward`.

    Parameters
    ----------
    energy : float
        ∫₀ᴴ ‖z‖² dt, exact given the law's decisions.
    horizon : float
    steps : int
        How many times the filter was adapted (one per sampling instant in [0, H)).
    output_energy : (p,) ndarray
        ∫₀ᴴ z_r² dt per output r (they sum to ``energy``).
    pieces : (k, 3) ndarray
        ``[t0, t1, ∫ ‖z‖²]`` per piece of the disturbance (and of the estimate).
    largest_update : float
        The largest ‖v_k‖ applied (how hard the adapted filter pushed).
    """

    energy: float
    horizon: float
    steps: int
    output_energy: np.ndarray
    pieces: np.ndarray
    largest_update: float


class AdaptiveFeedforward:
    """The LQ gain, a fixed feedforward of ŵ and an FIR filter of ŵ adapted by recursive least
    squares (module docstring).

    Parameters
    ----------
    plant : Plant, control.StateSpace or tuple
        One disturbance input; D2 of full column rank (:func:`fdsc.noncausal.lq_data`).
    step : float
        The sampling interval h of ŵ and of the adaptation (s); v is held over each step.
    taps : int, optional
        N, the FIR filter's length (default 16): it spans ``N h`` seconds of ŵ.
    memory : float, optional
        The least squares' time constant (s): λ = e^{−h/memory} (default 4 s). Longer averages
        more, shorter follows a change of the disturbance sooner.
    regularization : float, optional
        δ relative to the mean diagonal of the weighted regressors' Gram matrix (default 1e-6).
    base : Controller, optional
        The fixed feedforward F_b, as for :class:`fdsc.PredictiveLaw` (its states read ŵ alone,
        ``B = 0``); default the static ``K_d − R⁻¹B2ᵀψ(0)``.

    Raises
    ------
    ValueError
        If an argument is out of range, or as :func:`fdsc.noncausal.lq_data`.
    TypeError
        If base is not an :class:`fdsc.Controller`.

    Notes
    -----
    ŵ is sampled after an ideal anti-alias filter (its tones above π/h are removed), as in
    :class:`fdsc.PredictiveLaw`. The cost of a run is linear in its number of steps (about a
    microsecond per step for a small plant).

    Examples
    --------
    On a held pair of tones the adapted filter comes within 6 % of the non-causal limit over
    100 s (the first seconds it spends adapting):

    >>> from fdsc import Plant, noncausal_limit
    >>> p = Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
    ...           [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.3]])
    >>> d = Sinusoids([1.0, 0.5], [3.0, 7.0])
    >>> run = AdaptiveFeedforward(p, 0.02, taps=16, memory=4.0).run(d, 100.0)
    >>> bool(run.energy / noncausal_limit(p, d, 100.0).energy < 1.06)
    True
    """

    def __init__(self, plant, step: float, *, taps: int = DEFAULT_TAPS, memory: float = DEFAULT_MEMORY,
                 regularization: float = DEFAULT_REGULARIZATION, base=None):
        self.plant = p = as_plant(plant)
        if p.B1.shape[1] != 1:
            raise ValueError(f"plant must have one disturbance input, but has {p.B1.shape[1]}")
        self.step = as_positive("step", step)
        self.taps = as_count("taps", taps, 1)
        self.memory = as_positive("memory", memory)
        self.regularization = as_positive("regularization", regularization)
        self.lq = lq = lq_data(p)
        self._base = Af, Ef, Cf, Ff = _base_filter(p, lq, base)
        n, k, m = p.n_states, Af.shape[0], p.n_controls
        B2, D2 = p.B2, p.D2
        # the loop without v: X = [x; base states], inputs [d, ŵ]
        self._A = np.block([[lq.A_c, B2 @ Cf], [np.zeros((k, n)), Af]])
        self._B = np.c_[np.r_[p.B1[:, 0], np.zeros(k)], np.r_[B2 @ Ff, Ef]]
        self._C = np.hstack([lq.Cz, D2 @ Cf])
        self._D = np.c_[p.D1[:, 0], D2 @ Ff]
        if np.max(np.linalg.eigvals(self._A).real) >= 0:
            raise ValueError("the LQ closed loop with the base feedforward is not stable")
        # the law's model of the path from v (held) to z at the sampling instants (left limits)
        h = self.step
        E, _ = _gram(np.block([[lq.A_c, B2], [np.zeros((m, n + m))]]), np.zeros((n + m, n + m)), h)
        self._Phis = np.ascontiguousarray(E[:n, :n] + np.eye(n))
        self._Gams = np.ascontiguousarray(E[:n, n:])
        self._Cs = np.ascontiguousarray(lq.Cz)
        self._Ds = np.ascontiguousarray(D2)
        self._lam = math.exp(-h / self.memory)

    def _forms(self, w, ch, L):
        """``(P, Qs, G)`` of a step of length L on a piece with tones w (channels ch): P maps
        η = [X; a∘c; a∘s; v] to η at the step's end, ``ηᵀ Qs[r] η`` is ∫ z_r² over the step, z = G η."""
        p = self.plant
        nX, T, m = self._A.shape[0], w.size, p.n_controls
        if ch is None:          # ŵ = d: one input, the two columns summed
            B, D = self._B.sum(axis=1, keepdims=True), self._D.sum(axis=1, keepdims=True)
        else:
            B, D = self._B, self._D
        F0, G0 = _augmented(self._A, B, self._C, D, w, ch)
        W0 = nX + 2 * T
        F = np.zeros((W0 + m, W0 + m))
        F[:W0, :W0] = F0
        F[:p.n_states, W0:] = p.B2
        G = np.hstack([G0, p.D2])
        Qs = np.empty((G.shape[0], W0 + m, W0 + m))
        for r in range(G.shape[0]):
            E, Qs[r] = _gram(F, np.outer(G[r], G[r]), L)
        P = E + np.eye(W0 + m)
        return np.ascontiguousarray(P), Qs, np.ascontiguousarray(G)

    def run(self, d, horizon: float, *, estimate=None, x0=None, noise: float = 0.0,
            seed: int = 0) -> AdaptiveRun:
        """The law on the disturbance d, reading the estimate (default ŵ = d).

        Parameters
        ----------
        d : Sinusoids or Piecewise
        horizon : float
            H > 0 (s).
        estimate : Sinusoids or Piecewise, optional
            What the law reads as ŵ; default d.
        x0 : (n,) array_like, optional
            The plant's initial state (the base filter and the adaptation start at rest).
        noise : float, optional
            The variance of white Gaussian noise added to every sample of ŵ the law reads (its
            FIR filter's input and the output it computes, ``C x + D1 ŵ + D2 u``), independent from
            sample to sample (default 0: exact samples). The base's continuous filter reads ŵ
            without it: add its expected cost as for :class:`fdsc.confident.ConfidentPredictiveLaw`.
        seed : int, optional
            Seeds the noise (:func:`numpy.random.default_rng`); the k-th sampling instant's noise
            is the k-th normal deviate, whatever the pieces of d.

        Returns
        -------
        AdaptiveRun

        Raises
        ------
        TypeError
            If d or estimate is not a Sinusoids or Piecewise.
        ValueError
            If horizon or x0 is out of range, or noise is not a finite variance ≥ 0.
        EnergyOverflowError
            If the energy is not finite (it exceeds the float range).
        """
        check_type("d", d, Sinusoids | Piecewise, "an fdsc.Sinusoids or fdsc.Piecewise")
        H = as_positive("horizon", horizon)
        var = float(noise) if isinstance(noise, (int, float)) and not isinstance(noise, bool) else math.nan
        if not (var >= 0 and math.isfinite(var)):
            raise ValueError(f"noise must be a variance (a finite number ≥ 0), but found {noise!r}")
        check_type("seed", seed, int, "an int")
        if estimate is not None:
            check_type("estimate", estimate, Sinusoids | Piecewise, "an fdsc.Sinusoids or fdsc.Piecewise")
        p, h = self.plant, self.step
        n, m, N = p.n_states, p.n_controls, self.taps
        nX = self._A.shape[0]
        x = np.zeros(n) if x0 is None else np.array(as_vector("x0", x0, n), dtype=float)
        if estimate is None:
            parts, chans = pieces(d, H), None
        else:
            parts, chans = _merged(d, estimate, H)
        nyq = math.pi / h
        # the law's state: the models' states, the regressors' history, the least squares
        st = _LawState(n, m, N, p.C.shape[0])
        X = np.r_[x, np.zeros(nX - n)]
        v = np.zeros(m)
        energy, per_output, rows = 0.0, np.zeros(p.C.shape[0]), []
        steps, vmax = 0, 0.0
        tol = 1e-9 * max(1.0, H)
        # the noise of every sampling instant in [0, H], drawn at once (0 without noise)
        n_inst = math.ceil(H / h - 1e-9) + 1
        nz = (math.sqrt(var) * np.random.default_rng(seed).standard_normal(n_inst) if var > 0
              else np.zeros(n_inst))
        d1 = np.ascontiguousarray(p.D1[:, 0], dtype=float)
        for j, (t0, t1, w, a, ph) in enumerate(parts):
            ch = None if chans is None else chans[j]
            T = w.size
            # the oscillators at t0, and the sampler's row: ŵ's tones below the Nyquist frequency
            th = w * t0 + ph
            eta = np.r_[X, a * np.cos(th), a * np.sin(th), v]
            reads = (w < nyq) if ch is None else ((w < nyq) & (ch == 1))
            wrow = np.zeros(eta.size)
            wrow[nX + T:nX + 2 * T] = reads
            P, Qs, G = self._forms(w, ch, h)
            Gread = G.copy()
            if ch is not None:                  # the law computes z with ŵ in place of d
                dcol = nX + T + np.flatnonzero(ch == 0)
                wcol = nX + T + np.flatnonzero(ch == 1)
                Gread[:, dcol] -= p.D1[:, :1]
                Gread[:, wcol] += p.D1[:, :1]
            piece_e = np.zeros(p.C.shape[0])
            # the sampling instants in [t0, t1)
            k0 = math.ceil(t0 / h - 1e-9)
            k1 = math.ceil(t1 / h - 1e-9)            # instants k0 … k1 − 1
            t = t0
            if k0 * h > t0 + tol and k0 < k1:        # a partial step up to the first instant
                eta, e = _partial(self, w, ch, eta, k0 * h - t0)
                piece_e += e
                t = k0 * h
            if k0 < k1:
                full = k1 - k0 - (1 if (k1 - 1) * h + h > t1 + tol else 0)
                eta, e_full, vm = _adapt_steps(eta, P, Qs, Gread, wrow, nX + 2 * T, m, full, k1 - k0,
                                               st.arrays(), self._Phis, self._Gams, self._Cs, self._Ds,
                                               self._lam, self.regularization, nz[k0:k1], d1)
                piece_e += e_full
                vmax = max(vmax, vm)
                steps += k1 - k0
                t = (k0 + full) * h
                if k1 - k0 > full:                   # the last instant's step ends after t1
                    eta, e = _partial(self, w, ch, eta, t1 - t)
                    piece_e += e
            elif t1 > t0 + tol:                      # no instant in the piece: v is held throughout
                eta, e = _partial(self, w, ch, eta, t1 - t0)
                piece_e += e
            X, v = eta[:nX], eta[nX + 2 * T:]
            energy += float(piece_e.sum())
            per_output += piece_e
            rows.append((t0, t1, float(piece_e.sum())))
        if not math.isfinite(energy):
            raise EnergyOverflowError("AdaptiveFeedforward: the energy is not finite (it exceeds the float "
                                      "range)")
        return AdaptiveRun(energy, H, steps, per_output, np.array(rows, dtype=float).reshape(-1, 3), vmax)


def _partial(law, w, ch, eta, L):
    """η after a step of length L with v held, and the step's energy per output."""
    P, Qs, _G = law._forms(w, ch, L)
    return P @ eta, np.einsum("i,rij,j->r", eta, Qs, eta)


@njit(cache=True)
def _adapt_steps(eta, P, Qs, Gread, wrow, vcol, m, full, count, state, Phis, Gams, Cs, Ds, lam, reg, nz, d1):
    """``count`` sampling instants of the law on one piece: at each, the adaptation and v; the
    first ``full`` of them followed by a whole step of the loop. The law reads ŵ plus ``nz[i]`` at
    the i-th (in its FIR filter and in the output ``C x + D1 ŵ + D2 u`` it computes, D1 = d1).
    Returns η, the energy per output of the whole steps and the largest ‖v‖."""
    xi_v, v_prev, xi_r, w_prev, hist, wdelay, R, g = state
    N = wdelay.size
    M = m * N
    p = Gread.shape[0]
    out = np.zeros(p)
    vmax = 0.0
    eta = eta.copy()
    Phi = np.empty((p, M))
    for i in range(count):
        e0 = Gread @ eta + d1 * nz[i] - (Cs @ xi_v + Ds @ v_prev)
        for j in range(N - 1, 0, -1):
            hist[j] = hist[j - 1]
        for c in range(m):
            hist[0, c] = Cs @ xi_r[c] + Ds[:, c] * w_prev[0]
        for c in range(m):
            for j in range(N):
                Phi[:, c * N + j] = hist[j, c]
        R *= lam
        R += Phi.T @ Phi
        g *= lam
        g += Phi.T @ e0
        delta = reg * np.trace(R) / M + 1e-300
        theta = -np.linalg.solve(R + delta * np.eye(M), g)
        wk = wrow @ eta + nz[i]
        for j in range(N - 1, 0, -1):
            wdelay[j] = wdelay[j - 1]
        wdelay[0] = wk
        v = np.zeros(m)
        for c in range(m):
            v[c] = theta[c * N:(c + 1) * N] @ wdelay
        vmax = max(vmax, math.sqrt(v @ v))
        xi_v[:] = Phis @ xi_v + Gams @ v
        for c in range(m):
            xi_r[c] = Phis @ xi_r[c] + Gams[:, c] * wk
        v_prev[:] = v
        w_prev[0] = wk
        eta[vcol:vcol + m] = v
        if i < full:
            for r in range(p):
                out[r] += eta @ (Qs[r] @ eta)
            eta = P @ eta
    return eta, out, vmax


class _LawState:
    """The adaptation's memory, carried from piece to piece."""

    def __init__(self, n, m, N, p):
        self.xi_v = np.zeros(n)             # the model's state driven by the applied v
        self.v_prev = np.zeros(m)
        self.xi_r = np.zeros((m, n))        # the regressor filters' states (ŵ into each input)
        self.w_prev = np.zeros(1)
        self.hist = np.zeros((N, m, p))     # filtered regressors r_i at t_k, t_{k−1}, …
        self.wdelay = np.zeros(N)           # ŵ(t_k), ŵ(t_{k−1}), …
        self.R = np.zeros((m * N, m * N))
        self.g = np.zeros(m * N)

    def arrays(self):
        return (self.xi_v, self.v_prev, self.xi_r, self.w_prev, self.hist, self.wdelay, self.R, self.g)


def _base_filter(plant, lq, base):
    """``(A, E, C, F)`` of the base feedforward's path from ŵ to u (E and F as vectors): the
    static ``K_d − R⁻¹B2ᵀψ(0)`` for None, else the filter of the controller ``base`` (checked),
    as :class:`fdsc.PredictiveLaw` takes its base."""
    m = plant.n_controls
    if base is None:
        psi0 = lq.psi_gain([0.0])[0, :, 0]
        return np.zeros((0, 0)), np.zeros(0), np.zeros((m, 0)), (lq.K_d[:, 0] - lq.R_inv_B2T @ psi0).real
    from .controller import Controller

    check_type("base", base, Controller, "an fdsc.Controller that reads ŵ")
    if not base.reads_estimate or base.D.shape != (m, plant.n_states) or np.any(base.B):
        raise ValueError("base must be a controller of this plant that reads ŵ, its states driven by "
                         "ŵ alone (B = 0)")
    if base.n_states and np.max(np.linalg.eigvals(base.A).real) >= 0:
        raise ValueError("base: its filter of ŵ is not stable")
    return base.A, base.E[:, 0], base.C, base.F[:, 0]
