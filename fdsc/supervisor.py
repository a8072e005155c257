"""A switching law that decides on the disturbance, not on the closed-loop state.

The printed law (paper eq. (31)) scores the closed-loop state, whose spectrum depends on the gain
that is active, so its decision feeds back on itself (and chatters). With the state and its
derivative measured, as the paper assumes, the disturbance is known too: for a nominal plant
``ŵ = B1⁺ (ẋ − A x − B2 u)`` equals ``d`` exactly when ``B1`` has full column rank, whatever gain
is active. A law that decides on ŵ therefore cannot feed back on itself.

:func:`supervise` runs such a law, a predictive-cost supervisor (Hespanha, Liberzon and Morse,
Automatica 2003): one copy of each candidate closed loop is driven by ŵ, a monitoring signal

    μ_i(t) = ∫ e^{−λ (t − s)} ‖z_i(s)‖² ds

weighs each copy's output energy with a fading memory of rate λ, and the law switches from the
active candidate q to the cheapest p when ``(1 + h) μ_p < μ_q``: a hysteresis relative to the
costs, so it does not depend on the disturbance's scale. A copy run from t = 0 would carry the
slow transients of long-past pieces of ŵ (a loop with a pole at −0.0165 /s remembers them for
minutes), so the copies are restarted from rest every ``restart`` seconds, in two banks half a
period apart: the law reads the bank whose copies are older (between ``restart / 2`` and
``restart`` seconds), and μ counts from that bank's restart.

Because ŵ = d does not depend on the active gain, the switching signal is a function of ``d``
alone: it is computed first, from the copies (exact LTI runs), and the switched loop is then run
exactly along it, piece by piece from the carried-over state (:func:`fdsc.simulate_stream` on
each piece). Decisions are taken at the samples of the grid.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from . import _divergence
from ._validation import as_nonnegative, as_positive, as_vector, check_type
from .exceptions import UnstableRunWarning
from .signals import Piecewise, Sinusoids

__all__ = ["SupervisedRun", "supervise", "shift_signal", "lqr_gain"]


@dataclass(frozen=True)
class SupervisedRun:
    """A run of the predictive-cost supervisor (see :func:`supervise`).

    Parameters
    ----------
    horizon, dt : float
        The grid ``0, dt, …, horizon`` (s).
    energy, input_energy : float
        ``∫ zᵀz`` and ``∫ d²`` over the horizon (Simpson's rule on each piece between switches).
    switch_times : (m,) ndarray
        Instants (s) at which the active candidate changes.
    sequence : (m + 1,) int ndarray
        The active candidate on ``[0, t_1), [t_1, t_2), …``.
    time_share : (I,) ndarray
        Fraction of the horizon spent with each candidate.
    x_final : (n,) ndarray
        State at the horizon.
    t_mu : (M,) ndarray
        The decision points (s).
    mu : (M, I) ndarray
        The monitoring signals the law read there.
    """

    horizon: float
    dt: float
    energy: float
    input_energy: float
    switch_times: np.ndarray
    sequence: np.ndarray
    time_share: np.ndarray
    x_final: np.ndarray
    t_mu: np.ndarray
    mu: np.ndarray

    @property
    def switches(self) -> int:
        """Number of changes of the active candidate."""
        return int(self.switch_times.size)


def shift_signal(d, tau: float):
    """The signal ``t ↦ d(t + τ)``: tones with their phases advanced by ωτ, breaks moved by −τ.

    Parameters
    ----------
    d : Sinusoids or Piecewise
    tau : float
        The shift in s.

    Returns
    -------
    Sinusoids or Piecewise

    Raises
    ------
    TypeError
        If ``d`` is neither.

    Examples
    --------
    >>> d = Sinusoids([1.0], [2.0])
    >>> bool(np.isclose(shift_signal(d, 0.5)([1.0])[0], d([1.5])[0], rtol=1e-14))
    True
    """
    if isinstance(d, Sinusoids):
        return Sinusoids(d.amplitudes, d.frequencies, d.phases + d.frequencies * tau)
    if isinstance(d, Piecewise):
        return Piecewise(np.asarray(d.breaks) - tau, list(d.parts))
    raise TypeError(f"d must be an fdsc.Sinusoids or fdsc.Piecewise, but found {type(d).__name__}")


def _bank(modes, d, n_blocks, block, dt, decay, starts):
    """μ of every candidate at the decision points 0, block, 2 block, … (in steps of dt) for
    copies restarted from rest at the decision points ``starts`` (indices)."""
    from .stream import simulate_stream

    mu = np.zeros((n_blocks + 1, len(modes)))
    for a, b in zip(starts, [*starts[1:], n_blocks], strict=True):
        if b <= a:
            continue
        d_seg = shift_signal(d, a * block * dt)
        for i, m in enumerate(modes):
            r = simulate_stream(m, d_seg, (b - a) * block * dt, dt, cumulative_every=block * dt)
            cum = r.energy_cum                               # ∫₀ᵗ ‖z‖² at the decision points
            if cum.size == b - a:                            # the grid stops before the end
                cum = np.append(cum, r.energy)
            blocks = np.diff(cum)                            # energy of each decision interval
            acc = np.zeros(b - a + 1)
            for k, e in enumerate(blocks, start=1):          # μ_k = e^{−λΔ} μ_{k−1} + E_k
                acc[k] = decay * acc[k - 1] + e
            mu[a:b + 1, i] = acc
    return mu


def _monitor(modes, d, n_blocks, block, dt, lam, restart_blocks):
    """μ of every candidate at every decision point: two banks of copies restarted from rest
    every ``restart_blocks`` decision intervals, half a period apart (both from 0 at first); at
    each point the bank whose copies are older."""
    decay = math.exp(-lam * block * dt)
    half = max(1, restart_blocks // 2)
    starts0 = list(range(0, n_blocks, restart_blocks))
    starts1 = [0, *range(half, n_blocks, restart_blocks)]
    k = np.arange(n_blocks + 1)
    age0 = k - np.array(starts0)[np.searchsorted(starts0, k, side="right") - 1]
    age1 = k - np.array(starts1)[np.searchsorted(starts1, k, side="right") - 1]
    mu0 = _bank(modes, d, n_blocks, block, dt, decay, starts0)
    mu1 = _bank(modes, d, n_blocks, block, dt, decay, starts1)
    return np.where((age0 >= age1)[:, None], mu0, mu1)


def lqr_gain(plant) -> np.ndarray:
    """The LQR gain of ``(A, B2)`` for the cost ``∫ ‖C x + D2 u‖² dt`` (a gentle stabilizing
    gain for :func:`supervise`'s ``K0``; ``D2ᵀD2`` is regularized by 1e-9 of its norm if
    singular).

    Parameters
    ----------
    plant : Plant

    Returns
    -------
    (m_u, n) ndarray
        ``u = K x``.

    Examples
    --------
    >>> from fdsc import Plant
    >>> K = lqr_gain(Plant([[1.0]], [[1.0]], [[1.0]], [[1.0], [0.0]], [[0.0], [0.0]], [[0.0], [1.0]]))
    >>> bool(np.isclose(K[0, 0], -1.0 - np.sqrt(2.0)))      # ẋ = x + u, cost ∫ x² + u²
    True
    """
    from scipy.linalg import solve_continuous_are

    from .plant import as_plant

    plant = as_plant(plant)
    C, D2 = plant.C, plant.D2
    R = D2.T @ D2
    if np.linalg.matrix_rank(R) < R.shape[0]:
        R = R + 1e-9 * max(1.0, float(np.linalg.norm(R))) * np.eye(R.shape[0])
    S = C.T @ D2
    P = solve_continuous_are(plant.A, plant.B2, C.T @ C, R, s=S)
    return -np.linalg.solve(R, plant.B2.T @ P + S.T)


def _augmented(plant, gains, K0, m):
    """The loop with candidate m active in the realization through copies: state
    ``[x; x̂_0; …; x̂_{I−1}]``, ``u = K0 x + (K_m − K0) x̂_m``, each copy ``ẋ̂_i = (A + B2 K_i) x̂_i
    + B1 d``, output ``z = C x + D1 d + D2 u``."""
    from .plant import LTISystem

    A, B1, B2, C, D1, D2 = plant.A, plant.B1, plant.B2, plant.C, plant.D1, plant.D2
    n, nm = A.shape[0], len(gains)
    N = n * (nm + 1)
    Aa = np.zeros((N, N))
    Aa[:n, :n] = A + B2 @ K0
    Aa[:n, n * (m + 1):n * (m + 2)] = B2 @ (gains[m] - K0)
    Ca = np.zeros((C.shape[0], N))
    Ca[:, :n] = C + D2 @ K0
    Ca[:, n * (m + 1):n * (m + 2)] = D2 @ (gains[m] - K0)
    for i, K in enumerate(gains):
        Aa[n * (i + 1):n * (i + 2), n * (i + 1):n * (i + 2)] = A + B2 @ K
    return LTISystem(Aa, np.tile(B1, (nm + 1, 1)), Ca, D1)


def supervise(plant, gains, d, horizon: float, dt: float, *, forgetting: float = 0.5,
              hysteresis: float = 0.2, restart: float = 20.0, decide_every: float = 0.1,
              warmup: float = 0.0, K0=None, x0=None, sigma0: int = 0) -> SupervisedRun:
    """Run the predictive-cost supervisor on the disturbance estimate (module docstring).

    Parameters
    ----------
    plant : Plant
        The open-loop plant (one disturbance input, ``B1`` of full column rank, so that the
        estimate ŵ = B1⁺(ẋ − A x − B2 u) of the nominal plant is d).
    gains : sequence of (m_u, n) array_like
        The candidate state-feedback gains (two or more), each stabilizing.
    d : Sinusoids or Piecewise
        The disturbance (scalar).
    horizon, dt : float
        Run length and step (s); ``horizon`` a multiple of ``dt``.
    forgetting : float, optional
        λ > 0 (1/s), the monitoring signals' rate of forgetting.
    hysteresis : float, optional
        h ≥ 0: switch from q to p when ``(1 + h) μ_p < μ_q`` (strict, so that equal costs, such
        as those of copies at rest, keep the active candidate).
    restart : float, optional
        Period (s) of the monitoring copies' restarts (at least two decision intervals): the law
        forgets ŵ older than this, and reads copies that have run at least ``restart / 2``
        (except in the first ``restart / 2`` seconds).
    warmup : float, optional
        No decision before this time (s; ``sigma0`` is active until then). Early on the copies'
        costs reflect their rise from rest as much as the disturbance, so the first decisions
        may be revised; waiting costs the time spent with ``sigma0``. Default 0: decide from
        the first decision point.
    decide_every : float, optional
        The law decides every this many seconds (a multiple of ``dt``; ``horizon`` a multiple
        of it). The monitoring signals are updated there, each decision interval's energy
        weighed as a whole: ``μ_k = e^{−λΔ} μ_{k−1} + ∫ over the interval of ‖z_i‖²``.
    K0 : (m_u, n) array_like, optional
        None (default): the active gain acts directly, ``u = K_σ x``; at a switch to a high gain
        the state the previous gain left turns into a spike of u. Given (a gentle stabilizing
        gain, e.g. :func:`lqr_gain`): ``u = K0 x + (K_σ − K0) x̂_σ`` with x̂_i the state of a copy of
        loop i driven by ŵ from x0 (Hespanha and Morse, Automatica 2002); the error x − x̂_σ
        decays under A + B2 K0 whatever σ does, so a switch moves u only by what the copies'
        states differ.
    x0 : (n,) array_like, optional
        Initial state of the plant (default 0); the monitoring copies start from rest.
    sigma0 : int, optional
        The candidate active at t = 0.

    Returns
    -------
    SupervisedRun

    Raises
    ------
    TypeError
        If ``plant`` is not a plant or ``d`` is not Sinusoids or Piecewise.
    ValueError
        If fewer than two gains are given, a gain has the wrong shape or does not stabilize
        the plant, ``B1`` is not of full column rank or the disturbance not scalar,
        ``horizon`` is not a multiple of ``dt``, a parameter is out of range, or ``sigma0`` is
        not a candidate's index.
    UnstableError
        If a piece of the run overflows.

    Warns
    -----
    UnstableRunWarning
        If the state at a switch or at the end exceeds the divergence monitor's bound
        (:mod:`fdsc._divergence`: 10⁶ times what any of the run's loops reaches alone from x0).

    Examples
    --------
    The README's oscillator with its LF and HF gains, under a slow tone that turns fast at 60 s:

    >>> from fdsc import Plant
    >>> plant = Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
    ...               [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.1]])
    >>> gains = [[[-21.85, -22.27]], [[0.495, -1.473]]]          # LF design, HF design
    >>> d = Piecewise([0.0, 60.0, 200.0], [Sinusoids([1.0], [0.2]), Sinusoids([1.0], [12.0])])
    >>> run = supervise(plant, gains, d, 120.0, 1e-2, warmup=5.0)
    >>> run.sequence.tolist(), bool(60.0 < run.switch_times[-1] < 70.0)
    ([0, 1], True)
    """
    from ._validation import as_matrix
    from .plant import as_plant
    from .simulate import time_grid
    from .stream import simulate_stream

    plant = as_plant(plant)
    n, mu_ = plant.n_states, plant.n_controls
    if plant.B1.shape[1] != 1:
        raise ValueError("plant must have one disturbance input (B1 of shape (n, 1)), found "
                         f"{plant.B1.shape}")
    if not np.any(plant.B1):
        raise ValueError("plant: B1 is zero, so the disturbance cannot be estimated from ẋ − A x − B2 u")
    if isinstance(gains, np.ndarray) and gains.ndim == 2 or not hasattr(gains, "__len__"):
        raise TypeError("gains must be a sequence of gains (each (m_u, n)), not one gain")
    if len(gains) < 2:
        raise ValueError(f"gains must hold at least two candidate gains, but found {len(gains)}")
    gains = [np.array(as_matrix(f"gains[{k}]", K, (mu_, n))) for k, K in enumerate(gains)]
    modes = []
    for k, K in enumerate(gains):
        loop = plant.closed_loop(K)
        worst = float(np.max(np.linalg.eigvals(loop.A).real))
        if worst >= 0:
            raise ValueError(f"gains[{k}] must stabilize the plant, but its closed loop has an "
                             f"eigenvalue with real part {worst:.4g}")
        modes.append(loop)
    check_type("d", d, Sinusoids | Piecewise, "an fdsc.Sinusoids or fdsc.Piecewise")
    lam = as_positive("forgetting", forgetting)
    h = as_nonnegative("hysteresis", hysteresis)
    t = time_grid(horizon, dt)
    N = t.size
    block = round(as_positive("decide_every", decide_every) / dt)
    if block < 1 or abs(block * dt - decide_every) > 1e-9 * decide_every:
        raise ValueError(f"decide_every must be a whole number of steps of dt = {dt:g} s, but found "
                         f"{decide_every!r}")
    if (N - 1) % block:
        raise ValueError(f"horizon must be a whole number of decision intervals (decide_every = "
                         f"{decide_every:g} s), but found {horizon!r}")
    n_blocks = (N - 1) // block
    restart_blocks = round(as_positive("restart", restart) / (block * dt))
    if restart_blocks < 2:
        raise ValueError(f"restart must be at least two decision intervals ({2 * block * dt:g} s), "
                         f"but found {restart!r}")
    x = np.zeros(n) if x0 is None else as_vector("x0", x0, n)
    if isinstance(sigma0, bool) or not isinstance(sigma0, int | np.integer) or not 0 <= sigma0 < len(modes):
        raise ValueError(f"sigma0 must be a candidate's index in [0, {len(modes)}), but found {sigma0!r}")
    if K0 is not None:
        K0 = np.array(as_matrix("K0", K0, (mu_, n)))
        worst = float(np.max(np.linalg.eigvals(plant.A + plant.B2 @ K0).real))
        if worst >= 0:
            raise ValueError(f"K0 must stabilize the plant, but A + B2 K0 has an eigenvalue with "
                             f"real part {worst:.4g}")
        x = np.tile(x, len(gains) + 1)           # the plant and the copies, all from x0
    mu = _monitor(modes, d, n_blocks, block, dt, lam, restart_blocks)
    # the law at the decision points: from q to the cheapest p when (1 + h) μ_p < μ_q
    sigma = np.empty(n_blocks + 1, dtype=np.int64)
    q = int(sigma0)
    first = max(1, math.ceil(as_nonnegative("warmup", warmup) / (block * dt) - 1e-9))
    for k in range(n_blocks + 1):
        p = int(np.argmin(mu[k]))
        if k < first:
            sigma[k] = q
            continue
        if p != q and (1.0 + h) * mu[k, p] < mu[k, q]:    # strict: equal costs (at rest) keep q
            q = p
        sigma[k] = q
    sigma = sigma[:-1]                                      # the last point decides nothing
    change = np.flatnonzero(np.diff(sigma)) + 1            # first interval of each new candidate
    bounds = [0, *(change * block).tolist(), N - 1]        # in steps of dt
    seq = [int(sigma[0]), *sigma[change].tolist()]
    energy = input_energy = 0.0
    loops = {m: modes[m] if K0 is None else _augmented(plant, gains, K0, m) for m in set(seq)}
    # the divergence monitor's rule (fdsc._divergence) on the state at the switches and the end
    limit = _divergence.threshold([lp.A for lp in loops.values()], next(iter(loops.values())).B, x, d)
    for a, b, m in zip(bounds[:-1], bounds[1:], seq, strict=True):
        if b <= a:
            continue
        r = simulate_stream(loops[m], shift_signal(d, a * dt), (b - a) * dt, dt, x0=x)
        energy += r.energy
        input_energy += r.input_energy
        x = r.x_final
        big = float(np.abs(x).max())
        if big > limit:
            bound = limit / _divergence.SAFETY
            warnings.warn(_divergence.message("supervise: ", b * dt, big / bound, bound),
                          UnstableRunWarning, stacklevel=2)
            limit = math.inf
    share = np.bincount(seq, weights=np.diff(bounds), minlength=len(modes)) / (N - 1)
    return SupervisedRun(float(horizon), float(dt), float(energy), float(input_energy),
                         change * block * dt, np.array(seq), share, x[:n],
                         np.arange(n_blocks + 1) * block * dt, mu)
