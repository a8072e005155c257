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

The **band-power law** (``law="band_power"``) is the paper's frequency selectiveness applied to
the disturbance instead of the state: monitor i filters ŵ through a second-order Butterworth
filter of band i (:func:`band_filter`), μ_i is the filtered ŵ's fading energy (a fading-memory
FD-EEF of ŵ), and the law picks the gain meant for the band with the largest μ, with the same
relative hysteresis.

Because ŵ = d does not depend on the active gain, the switching signal is a function of ``d``
alone: the monitors are exact LTI runs, integrated exactly between decision points
(:mod:`fdsc._blocks`, no quadrature), so the decisions do not depend on a simulation step. The
switched loop is then run along them, exactly as well by default, or by
:func:`fdsc.simulate_stream` at a given step. :class:`Supervisor` prepares one disturbance once
(:meth:`Supervisor.prepare`), after which many settings of the law, fixed candidates, segment
laws and the clairvoyant per-segment oracle each cost one pass over the decision grid.

**Realizations.** Direct, ``u = K_σ x``: a switch applies the new gain to the state the previous
gain left, which under a high gain (the generic example's H∞ gain is ~2·10⁷) is a spike of u;
stability under the law then needs a dwell time (``min_dwell``, certified by
:func:`fdsc.geromel_colaneri_dwell`). Through copies, ``u = K0 x + (K_σ − K0) x̂_σ`` (Hespanha
and Morse, Automatica 2002): with every copy x̂_i a stable loop driven by ŵ, the error x − x̂_σ
obeys ė = (A + B2 K0) e between switches and jumps by x̂_q − x̂_p at a switch, so with
switches at most once per decision interval the state stays bounded and, for d = 0, decays,
whatever the law does.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np
from numba import njit

from . import _divergence
from ._defaults import DEFAULT_MAX_MEMORY
from ._validation import as_nonnegative, as_positive, as_vector, check_type
from .exceptions import (
    DimensionError,
    EnergyOverflowError,
    MemoryLimitError,
    UnstableError,
    UnstableRunWarning,
)
from .signals import Piecewise, Sinusoids

__all__ = ["SupervisedRun", "Supervisor", "Prepared", "LAWS", "supervise", "band_filter",
           "shift_signal", "lqr_gain"]


@dataclass(frozen=True)
class SupervisedRun:
    """A run of the predictive-cost supervisor (see :func:`supervise`).

    Parameters
    ----------
    horizon : float
        Run length (s).
    dt : float or None
        The step of a run by :func:`fdsc.simulate_stream` (energies by Simpson's rule on each
        piece between switches), or None for an exact run (energies integrated exactly).
    energy, input_energy : float
        ``∫ zᵀz`` and ``∫ d²`` over the horizon.
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
        The monitoring signals the law read there (no rows for a run along a given sequence).
    diverged_at : float or None
        The first switch or end point (s) where the divergence monitor fired, else None.
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
    diverged_at: float | None = None

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
    ValueError
        If ``tau`` is not a finite real number.

    Examples
    --------
    >>> d = Sinusoids([1.0], [2.0])
    >>> bool(np.isclose(shift_signal(d, 0.5)([1.0])[0], d([1.5])[0], rtol=1e-14))
    True
    >>> p = Piecewise([0.0, 1.0, 3.0], [d, Sinusoids([1.0], [5.0])])
    >>> np.allclose(shift_signal(p, 0.5)([0.2, 0.7, 2.0]), p([0.7, 1.2, 2.5]), rtol=1e-14)
    True
    """
    if isinstance(tau, bool) or not isinstance(tau, int | float | np.integer | np.floating) \
            or not math.isfinite(tau):
        raise ValueError(f"tau must be a finite real number of seconds, but found {tau!r}")
    tau = float(tau)
    if isinstance(d, Sinusoids):
        return Sinusoids(d.amplitudes, d.frequencies, d.phases + d.frequencies * tau)
    if isinstance(d, Piecewise):
        # the parts are evaluated at absolute time: each is shifted too
        return Piecewise(np.asarray(d.breaks) - tau, [shift_signal(p, tau) for p in d.parts])
    raise TypeError(f"d must be an fdsc.Sinusoids or fdsc.Piecewise, but found {type(d).__name__}")


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

    Raises
    ------
    ValueError
        If the Riccati equation has no stabilizing solution, or its gain does not stabilize
        A + B2 K (a mode the cost does not see).

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
    try:
        P = solve_continuous_are(plant.A, plant.B2, C.T @ C, R, s=S)
    except (np.linalg.LinAlgError, ValueError) as exc:
        raise ValueError(f"plant: the LQR problem of (A, B2, C, D2) has no stabilizing solution "
                         f"((A, B2) not stabilizable or (A, C) not detectable on the imaginary "
                         f"axis): {exc}") from exc
    K = -np.linalg.solve(R, plant.B2.T @ P + S.T)
    worst = float(np.max(np.linalg.eigvals(plant.A + plant.B2 @ K).real))
    if not worst < 0:
        raise ValueError(f"plant: the LQR gain of (A, B2, C, D2) does not stabilize A + B2 K (an "
                         f"eigenvalue has real part {worst:.3g}): the cost ∫‖C x + D2 u‖² does not "
                         f"see every unstable mode; choose K0 yourself")
    return K


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


def band_filter(band):
    """The monitoring filter of a band for the band-power law: a second-order Butterworth
    low-pass at ϖ_l (LF band), high-pass at ϖ_h (HF), their cascade (MF), or the identity (EF);
    unit gain in the pass band.

    Parameters
    ----------
    band : Band

    Returns
    -------
    LTISystem
        Input ŵ, output the filtered ŵ.

    Raises
    ------
    TypeError
        If ``band`` is not a Band.
    ValueError
        If an edge lies outside [1e-6, 1e6] rad/s, where the filter's output is lost to
        rounding (its pass band is then a vanishing part of what it is fed).

    Examples
    --------
    >>> from fdsc import Band, freqresp
    >>> f = band_filter(Band.hf(10.0))
    >>> g = np.abs(freqresp(f, [1.0, 10.0, 1000.0])[:, 0, 0])
    >>> [round(float(v), 4) for v in g]                 # −3 dB at the edge
    [0.01, 0.7071, 1.0]
    """
    from .bands import Band
    from .plant import LTISystem

    check_type("band", band, Band, "an fdsc.Band")
    edges = [w for w in (band.lower, band.upper) if 0 < w < math.inf]
    if any(w > MAX_FILTER_EDGE or w < 1.0 / MAX_FILTER_EDGE for w in edges):
        raise ValueError(f"band: the monitoring filter resolves band edges in [1e-6, 1e6] rad/s, "
                         f"but {band.label} has edges {edges}")

    def section(w, high):
        A = np.array([[0.0, 1.0], [-w * w, -math.sqrt(2.0) * w]])
        B = np.array([[0.0], [1.0]])
        if high:                        # s² / (s² + √2 ω s + ω²) = 1 − (√2 ω s + ω²) / (…)
            return A, B, np.array([[-w * w, -math.sqrt(2.0) * w]]), np.array([[1.0]])
        return A, B, np.array([[w * w, 0.0]]), np.array([[0.0]])

    parts = []
    if band.lower > 0:
        parts.append(section(band.lower, True))
    if math.isfinite(band.upper):
        parts.append(section(band.upper, False))
    if not parts:
        return LTISystem(np.array([[-1.0]]), np.zeros((1, 1)), np.zeros((1, 1)), np.array([[1.0]]))
    A, B, C, D = parts[0]
    for A2, B2, C2, D2 in parts[1:]:                # the second driven by the first's output
        A = np.block([[A, np.zeros((A.shape[0], A2.shape[0]))], [B2 @ C, A2]])
        B = np.vstack([B, B2 @ D])
        C = np.hstack([D2 @ C, C2])
        D = D2 @ D
    return LTISystem(A, B, C, D)


LAWS = ("cost", "band_power")
#: A stepped run (``supervise(dt=...)``) warns when a loop's fastest mode λ has |λ| dt above this:
#: the transients at the switches are then shorter than a step.
STIFF_STEP = 0.5
#: The band edges (rad/s) a monitoring filter resolves: [1 / MAX_FILTER_EDGE, MAX_FILTER_EDGE].
MAX_FILTER_EDGE = 1e6


class Supervisor:
    """A switching law that decides on the disturbance estimate ŵ (module docstring).

    Parameters
    ----------
    plant : Plant
        The open-loop plant (one disturbance input, ``B1`` nonzero, so that the estimate
        ŵ = B1⁺(ẋ − A x − B2 u) of the nominal plant is d).
    gains : sequence of (m_u, n) array_like
        The candidate state-feedback gains (two or more), each stabilizing.
    law : {"cost", "band_power"}, optional
        ``"cost"`` (default): the predictive-cost supervisor; monitor i is a copy of closed loop
        i driven by ŵ, μ_i its fading output energy, and the law picks the least μ.
        ``"band_power"``: monitor i is :func:`band_filter` of ``bands[i]`` driven by ŵ (the
        fading FD-EEF of ŵ in that band), and the law picks the largest μ, i.e. the gain meant
        for the band that holds most of ŵ's recent power.
    bands : sequence of Band, optional
        One band per gain (``law="band_power"`` only).
    decide_every : float, optional
        Δ (s): the law decides at ``0, Δ, 2Δ, …``; the monitoring signals are updated there,
        ``μ_k = e^{−λΔ} μ_{k−1} + ∫ over the interval of ‖z_i‖²``.
    restart : float, optional
        Period (s, at least 2Δ, rounded to a whole number of decision intervals, which
        ``.restart`` then holds) of the monitors' restarts: two banks restarted from rest half
        a period apart; the law reads the bank whose copies are older, so it forgets ŵ older
        than ``restart`` and never reads copies younger than ``restart / 2`` (after the first
        ``restart / 2`` seconds).
    K0 : (m_u, n) array_like, optional
        None (default): the active gain acts directly, ``u = K_σ x``. Given (a gentle
        stabilizing gain, e.g. :func:`lqr_gain`): ``u = K0 x + (K_σ − K0) x̂_σ`` with x̂_i a
        copy of loop i driven by ŵ from x0 (Hespanha and Morse, Automatica 2002); the error
        x − x̂_σ decays under A + B2 K0 whatever σ does, so a switch moves u only by what the
        copies' states differ.

    Raises
    ------
    TypeError
        If ``plant`` is not a plant, ``gains`` is one gain, or a band is not a Band.
    ValueError
        If fewer than two gains are given, a gain has the wrong shape or does not stabilize,
        the plant has more than one disturbance input or ``B1 = 0``, ``law`` is unknown,
        ``bands`` is missing or has the wrong length for the band-power law (or is given for
        the cost law), or a parameter is out of range.
    """

    def __init__(self, plant, gains, *, law: str = "cost", bands=None, decide_every: float = 0.1,
                 restart: float = 20.0, K0=None):
        from ._validation import as_choice, as_matrix
        from .plant import as_plant

        plant = as_plant(plant)
        n, mu_ = plant.n_states, plant.n_controls
        if plant.B1.shape[1] != 1:
            raise ValueError("plant must have one disturbance input (B1 of shape (n, 1)), found "
                             f"{plant.B1.shape}")
        if not np.any(plant.B1):
            raise ValueError("plant: B1 is zero, so the disturbance cannot be estimated from "
                             "ẋ − A x − B2 u")
        if isinstance(gains, np.ndarray) and gains.ndim == 2 or not hasattr(gains, "__len__"):
            raise TypeError("gains must be a sequence of gains (each (m_u, n)), not one gain")
        if len(gains) < 2:
            raise ValueError(f"gains must hold at least two candidate gains, but found {len(gains)}")
        gains = [np.array(as_matrix(f"gains[{k}]", K, (mu_, n))) for k, K in enumerate(gains)]
        loops = []
        for k, K in enumerate(gains):
            loop = plant.closed_loop(K)
            worst = float(np.max(np.linalg.eigvals(loop.A).real))
            if worst >= 0:
                raise ValueError(f"gains[{k}] must stabilize the plant, but its closed loop has an "
                                 f"eigenvalue with real part {worst:.4g}")
            loops.append(loop)
        self.law = as_choice("law", law, LAWS)
        if self.law == "band_power":
            if bands is None or not hasattr(bands, "__len__") or len(bands) != len(gains):
                raise ValueError(f"bands must give one Band per gain ({len(gains)}) for the "
                                 f"band-power law, but found {bands!r}")
            self.monitors = []
            for k, b in enumerate(bands):
                try:
                    self.monitors.append(band_filter(b))
                except (TypeError, ValueError) as exc:
                    raise type(exc)(f"bands[{k}]: {exc}") from exc
        elif bands is not None:
            raise ValueError("bands is used by the band-power law only (law='band_power')")
        else:
            self.monitors = loops
        self.bands = None if bands is None else tuple(bands)
        self.decide_every = as_positive("decide_every", decide_every)
        self.restart = as_positive("restart", restart)
        self.restart_blocks = round(self.restart / self.decide_every)
        if self.restart_blocks < 2:
            raise ValueError(f"restart must be at least two decision intervals "
                             f"({2 * self.decide_every:g} s), but found {restart!r}")
        self.restart = self.restart_blocks * self.decide_every     # the period used
        if K0 is not None:
            K0 = np.array(as_matrix("K0", K0, (mu_, n)))
            worst = float(np.max(np.linalg.eigvals(plant.A + plant.B2 @ K0).real))
            if worst >= 0:
                raise ValueError(f"K0 must stabilize the plant, but A + B2 K0 has an eigenvalue "
                                 f"with real part {worst:.4g}")
        self.plant, self.gains, self.loops, self.K0 = plant, gains, loops, K0

    @property
    def realization(self) -> str:
        """``"direct"`` (u = K_σ x) or ``"copies"`` (u = K0 x + (K_σ − K0) x̂_σ)."""
        return "direct" if self.K0 is None else "copies"

    def switched_loops(self) -> list:
        """The loop with each candidate active: the closed loops (direct), or the plant with
        every copy, ``[x; x̂_0; …]`` (copies)."""
        if self.K0 is None:
            return list(self.loops)
        return [_augmented(self.plant, self.gains, self.K0, m) for m in range(len(self.gains))]

    def prepare(self, d, horizon: float, *, x0=None, estimate=None) -> Prepared:
        """The monitors' interval energies and the loops' step tables for one disturbance, from
        which :meth:`Prepared.run` evaluates the law for any forgetting and hysteresis.

        Parameters
        ----------
        d : Sinusoids or Piecewise
            The disturbance (scalar).
        horizon : float
            Run length (s), a whole number of decision intervals.
        x0 : (n,) array_like, optional
            Initial state of the plant (default 0); the monitors start from rest.
        estimate : Sinusoids or Piecewise, optional
            The signal the monitors are driven by, if not ``d`` itself: an estimate ŵ with
            errors (e.g. ``d`` plus measurement noise). Only the decisions see it; the plant and
            the copies of the realization are driven by ``d``.

        Returns
        -------
        Prepared
        """
        return Prepared(self, d, horizon, x0, estimate)

    def run(self, d, horizon: float, *, x0=None, **law) -> SupervisedRun:
        """One run of the law: ``self.prepare(d, horizon, x0=x0).run(**law)``.

        Parameters
        ----------
        d : Sinusoids or Piecewise
        horizon : float
        x0 : (n,) array_like, optional
        **law
            ``forgetting``, ``hysteresis``, ``warmup``, ``min_dwell``, ``sigma0``
            (:meth:`Prepared.run`).

        Returns
        -------
        SupervisedRun
        """
        return self.prepare(d, horizon, x0=x0).run(**law)

    def run_measured(self, d, horizon: float, dt: float, *, derivative: str = "exact", true_A=None,
                     x0=None, forgetting: float = 0.5, hysteresis: float = 0.2, warmup: float = 0.0,
                     min_dwell: float = 0.0, sigma0: int = 0) -> SupervisedRun:
        """Run the law as a controller would: ŵ formed at every step from the measured state.

        At ``t_k = k dt`` the controller reads ``x_k`` and ``ẋ_k``, forms
        ``ŵ_k = B1⁺ (ẋ_k − A x_k − B2 u_k)`` with the plant's ``A`` (its model), and holds ŵ_k
        until the next sample; the monitors and the copies step under the held ŵ, the plant
        under the true disturbance, all exactly between samples, and the law decides every
        ``decide_every`` as :meth:`Prepared.run` does. When the estimate's error depends on the
        state (a wrong model, a finite-difference derivative), the decisions depend on the run,
        so nothing can be prepared: each call runs the whole loop (:mod:`fdsc._measured`).

        Parameters
        ----------
        d : Sinusoids or Piecewise
            The disturbance (scalar); every break a multiple of ``dt``, every tone below the
            Nyquist frequency ``π / dt``.
        horizon : float
            Run length (s), a whole number of decision intervals.
        dt : float
            The sampling step (s); ``decide_every`` must be a whole number of steps.
        derivative : {"exact", "backward"}, optional
            ``"exact"``: the plant's true derivative at the sample; ``"backward"``:
            ``(x_k − x_{k−1}) / dt``.
        true_A : (n, n) array_like, optional
            The state matrix of the plant that is run, if not the model's (e.g. ``1.1 A`` for
            a 10 % model error); the estimate, the copies and the monitors keep the model's.
        x0 : (n,) array_like, optional
            Initial state of the plant (default 0); monitors and copies start from rest.
        forgetting, hysteresis, warmup, min_dwell, sigma0
            See :meth:`Prepared.run`.

        Returns
        -------
        SupervisedRun
            With ``dt`` set and the monitoring signals the law read; the energy is integrated
            exactly along the run.

        Raises
        ------
        ValueError
            If an argument is out of range, ``decide_every`` is not a whole number of steps,
            ``horizon`` not a whole number of decision intervals, a break of ``d`` is off the
            grid or a tone at or above the Nyquist frequency.
        EnergyOverflowError
            If the state stays finite but the energy exceeds the float range.

        Warns
        -----
        UnstableRunWarning
            If a candidate does not stabilize the plant that is run (``true_A``), or the state
            at a decision point exceeds the divergence monitor's bound (:mod:`fdsc._divergence`).

        Examples
        --------
        The README's oscillator under a slow tone that turns fast at 60 s, its estimate from
        a backward difference at 1 ms and a plant 10 % faster than the model:

        >>> from fdsc import Plant
        >>> plant = Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
        ...               [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.1]])
        >>> sup = Supervisor(plant, [[[-21.85, -22.27]], [[0.495, -1.473]]])
        >>> d = Piecewise([0.0, 60.0, 200.0], [Sinusoids([1.0], [0.2]), Sinusoids([1.0], [12.0])])
        >>> run = sup.run_measured(d, 120.0, 1e-3, derivative="backward", true_A=1.1 * plant.A,
        ...                        warmup=5.0)
        >>> run.sequence.tolist(), bool(60.0 < run.switch_times[-1] < 70.0)
        ([0, 1], True)
        """
        from . import _measured
        from ._blocks import Grid
        from ._simulate_kernel import check_resolved
        from ._validation import as_choice, as_matrix

        check_type("d", d, Sinusoids | Piecewise, "an fdsc.Sinusoids or fdsc.Piecewise")
        horizon = as_positive("horizon", horizon)
        dt = as_positive("dt", dt)
        derivative = as_choice("derivative", derivative, _measured.DERIVATIVES)
        n = self.plant.n_states
        A_t = self.plant.A if true_A is None else np.array(as_matrix("true_A", true_A, (n, n)))
        block = round(self.decide_every / dt)
        if block < 1 or abs(block * dt - self.decide_every) > 1e-9 * self.decide_every:
            raise ValueError(f"dt must divide decide_every = {self.decide_every:g} s into whole steps, "
                             f"but found {dt!r}")
        nb = _n_blocks(horizon, self.decide_every)
        check_resolved(d, dt, "run_measured: ")
        x0 = np.zeros(n) if x0 is None else np.array(as_vector("x0", x0, n))
        lam = as_positive("forgetting", forgetting)
        h = as_nonnegative("hysteresis", hysteresis)
        nm = len(self.gains)
        first, dwell = _schedule(nb, self.decide_every, warmup, min_dwell, sigma0, nm)
        need = 8.0 * nb * (len(self.gains) + 4)
        if need > DEFAULT_MAX_MEMORY:
            raise MemoryLimitError(f"run_measured: {nb} decision intervals need about {need / 2**30:.3g} GiB "
                                   f"for the monitoring signals, over the limit of "
                                   f"{DEFAULT_MAX_MEMORY / 2**30:.3g} GiB; shorten the horizon")
        A_modes, B_modes = _measured.modes(self, A_t)
        worst = max(float(np.max(np.linalg.eigvals(M).real)) for M in A_modes)
        if worst >= 0:
            warnings.warn(f"run_measured: a candidate's loop with the plant that is run (true_A) and "
                          f"the estimate it feeds back has an eigenvalue with real part {worst:.4g} ≥ 0; "
                          "the divergence monitor is off", UnstableRunWarning, stacklevel=2)
        e, sigma, mu, big, x = _measured.run(self, A_t, d, horizon, dt, x0, derivative,
                                             math.exp(-lam * self.decide_every), h, first, dwell,
                                             int(sigma0))
        start = x0 if self.K0 is None else np.tile(x0, 2)
        limit = _divergence.threshold(A_modes, B_modes, start, d)
        change = np.flatnonzero(np.diff(sigma)) + 1
        diverged = None
        if not np.all(np.isfinite(big)):
            k = int(np.flatnonzero(~np.isfinite(big))[0])
            t = (k + 1) * self.decide_every
            raise UnstableError(f"run_measured: the state overflowed by t = {t:g} s; the loop diverges and "
                                "no finite energy summarizes it")
        over = np.flatnonzero(~(big <= limit))
        if not np.all(np.isfinite(mu)):
            if worst >= 0 or over.size:
                raise UnstableError("run_measured: a monitoring signal overflowed while the loop diverges "
                                    "(the estimate carries the growing state); no finite energy "
                                    "summarizes it")
            raise EnergyOverflowError("run_measured: a monitoring signal exceeds the float range (about "
                                      "1.8e308), so the law cannot compare them: scale the disturbance "
                                      "(or x0) down")
        if over.size:
            diverged = float((over[0] + 1) * self.decide_every)
            bound = limit / _divergence.SAFETY
            warnings.warn(_divergence.message("run_measured: ", diverged, float(big[over[0]]) / bound,
                                              bound), UnstableRunWarning, stacklevel=2)
        elif not np.all(np.isfinite(e)):
            raise EnergyOverflowError("run_measured: the state stays finite but the energy exceeds the "
                                      "float range (about 1.8e308): scale the disturbance (or x0) down")
        points = np.arange(nb + 1) * self.decide_every
        points[-1] = horizon
        share = np.bincount(sigma, minlength=nm) / sigma.size
        input_energy = _input_energy(Grid(d, np.array([0.0, horizon])))
        return SupervisedRun(horizon, dt, float(e.sum()), input_energy,
                             change * self.decide_every, np.r_[sigma[:1], sigma[change]], share, x,
                             points, mu, diverged)


def _input_energy(grid) -> float:
    """``∫ d²`` over a grid's steps, exactly."""
    return float(grid.run(grid.tables([_dummy_input()]), 0, False, np.zeros(1))[0].sum())


def _n_blocks(horizon, decide_every) -> int:
    """The decision intervals in ``horizon``, refused unless it is a whole number of them."""
    nb = round(horizon / decide_every)
    if nb < 1 or abs(nb * decide_every - horizon) > 1e-9 * horizon:
        raise ValueError(f"horizon must be a whole number of decision intervals (decide_every = "
                         f"{decide_every:g} s), but found {horizon!r}")
    return nb


def _bank_starts(nb, restart_blocks) -> tuple:
    """The decision intervals at which each of the two banks of monitors restarts from rest:
    every R intervals, the second bank half a period later (a period beyond twice the horizon
    restarts neither bank after t = 0)."""
    R = min(restart_blocks, 2 * (nb + 1))
    half = max(1, R // 2)
    return (np.arange(0, nb, R), np.r_[0, np.arange(half, nb, R)])


def _older_bank(starts, nb) -> np.ndarray:
    """(nb + 1,) the bank the law reads at each decision point: the one restarted longer ago
    (bank 0 on a tie)."""
    k = np.arange(nb + 1)
    ages = [k - st[np.searchsorted(st, k, side="right") - 1] for st in starts]
    return np.where(ages[0] >= ages[1], 0, 1).astype(np.int64)


def _schedule(nb, step, warmup, min_dwell, sigma0, n_candidates) -> tuple:
    """``(first, dwell)`` in decision intervals (clamped to the run), with ``sigma0`` checked."""
    if isinstance(sigma0, bool) or not isinstance(sigma0, int | np.integer) \
            or not 0 <= sigma0 < n_candidates:
        raise ValueError(f"sigma0 must be a candidate's index in [0, {n_candidates}), but found {sigma0!r}")
    first = min(nb + 1, max(1, math.ceil(as_nonnegative("warmup", warmup) / step - 1e-9)))
    dwell = min(nb + 1, math.ceil(as_nonnegative("min_dwell", min_dwell) / step - 1e-9))
    return first, dwell


@njit(cache=True)
def _fading(E, fresh, decay):
    """μ_k = 0 where the bank restarts, else e^{−λΔ} μ_{k−1} + E_{k−1}."""
    mu = np.zeros((E.shape[0] + 1, E.shape[1]))
    for k in range(1, E.shape[0] + 1):
        if not fresh[k]:
            for i in range(E.shape[1]):
                mu[k, i] = decay * mu[k - 1, i] + E[k - 1, i]
    return mu


@njit(cache=True)
def _decide(cost, n_blocks, q, first, dwell, h):
    """From q to the cheapest p when (1 + h) c_p < c_q (strict), not before ``first`` nor within
    ``dwell`` intervals of the last switch."""
    sigma = np.empty(n_blocks, dtype=np.int64)
    last = -dwell
    for k in range(n_blocks):
        if k >= first and k - last >= dwell:
            p = int(np.argmin(cost[k]))
            if p != q and (1.0 + h) * cost[k, p] < cost[k, q]:
                q = p
                last = k
        sigma[k] = q
    return sigma


def _dummy_input():
    """A system whose output is its input: its energy is ∫d²."""
    return (np.array([[-1.0]]), np.zeros((1, 1)), np.zeros((1, 1)), np.array([[1.0]]))


def _abcd(sys):
    return (sys.A, sys.B, sys.C, sys.D)


class Prepared:
    """A :class:`Supervisor` prepared for one disturbance (see :meth:`Supervisor.prepare`).

    Everything here is exact (:mod:`fdsc._blocks`): the monitors' energies over each decision
    interval and every run's energy are integrals of the exact solution, not quadratures, so the
    law's decisions do not depend on any simulation step.

    Parameters
    ----------
    sup : Supervisor
    d : Sinusoids or Piecewise
    horizon : float
        A whole number of decision intervals (s).
    x0 : (n,) array_like or None
        Initial state of the plant.
    estimate : Sinusoids or Piecewise or None, optional
        What the monitors are driven by (default ``d``; see :meth:`Supervisor.prepare`).

    Raises
    ------
    TypeError
        If ``d`` is not Sinusoids or Piecewise.
    ValueError
        If ``horizon`` is not a whole number of decision intervals or ``x0`` has the wrong size.
    """

    def __init__(self, sup: Supervisor, d, horizon, x0, estimate=None):
        from ._blocks import Grid

        check_type("d", d, Sinusoids | Piecewise, "an fdsc.Sinusoids or fdsc.Piecewise")
        horizon = as_positive("horizon", horizon)
        nb = _n_blocks(horizon, sup.decide_every)
        n = sup.plant.n_states
        self.sup, self.d, self.horizon, self.n_blocks = sup, d, float(horizon), nb
        self.x0 = np.zeros(n) if x0 is None else np.array(as_vector("x0", x0, n))
        self.points = np.arange(nb + 1) * sup.decide_every
        self.points[-1] = horizon
        g = self.grid = Grid(d, self.points)
        if estimate is not None:
            check_type("estimate", estimate, Sinusoids | Piecewise, "an fdsc.Sinusoids or fdsc.Piecewise")
        gm = g if estimate is None else Grid(estimate, self.points)
        # the monitors' energies per decision interval, for each bank of restarts
        self.starts = _bank_starts(nb, sup.restart_blocks)
        self.E = np.zeros((2, nb, len(sup.monitors)))
        if sup.law == "cost":                    # the monitors are the closed loops: one table
            shared = gm.tables([_abcd(m) for m in sup.monitors])
            tables = [(shared, i) for i in range(len(sup.monitors))]
        else:
            tables = [(gm.tables([_abcd(m)]), 0) for m in sup.monitors]
        for b, st in enumerate(self.starts):
            at = np.zeros(nb + 1, dtype=bool)
            at[st] = True
            restart = at[gm.block] & np.r_[True, gm.block[1:] != gm.block[:-1]]
            for i, (m, (tab, j)) in enumerate(zip(sup.monitors, tables, strict=True)):
                e, _big, _x = gm.run(tab, j, restart, np.zeros(m.A.shape[0]))
                self.E[b, :, i] = gm.per_block(e)
        if not np.all(np.isfinite(self.E)):
            raise EnergyOverflowError("prepare: a monitor's energy is not finite (a candidate's "
                                      "loop, or the disturbance's scale, is beyond what floats "
                                      "integrate: its energy exceeds about 1e308)")
        self.input_energy = _input_energy(g)
        self.loops = sup.switched_loops()
        if sup.law == "cost" and sup.K0 is None and estimate is None:
            self.tables = shared
        else:
            self.tables = g.tables([_abcd(lp) for lp in self.loops])
        self.xstart = self.x0 if sup.K0 is None else np.tile(self.x0, len(sup.gains) + 1)

    def with_K0(self, K0) -> Prepared:
        """The same disturbance and monitors with another realization (only the switched loops'
        tables are recomputed).

        Parameters
        ----------
        K0 : (m_u, n) array_like or None
            None: direct; a stabilizing gain: through copies.

        Returns
        -------
        Prepared
        """
        sup = Supervisor.__new__(Supervisor)
        sup.__dict__.update(self.sup.__dict__)
        other = Supervisor(self.sup.plant, self.sup.gains, K0=K0)
        sup.K0 = other.K0
        new = Prepared.__new__(Prepared)
        new.__dict__.update(self.__dict__)
        new.sup = sup
        new.loops = sup.switched_loops()
        new.tables = self.grid.tables([_abcd(lp) for lp in new.loops])
        new.xstart = new.x0 if sup.K0 is None else np.tile(new.x0, len(sup.gains) + 1)
        return new

    def mu(self, forgetting: float) -> np.ndarray:
        """The monitoring signals the law reads at the decision points: at each point those of
        the bank whose monitors are older (μ = 0 where it has just restarted).

        Parameters
        ----------
        forgetting : float
            λ > 0 (1/s).

        Returns
        -------
        (n_blocks + 1, I) ndarray
        """
        lam = as_positive("forgetting", forgetting)
        decay = math.exp(-lam * self.sup.decide_every)
        nb = self.n_blocks
        out = []
        for b, st in enumerate(self.starts):
            fresh = np.zeros(nb + 1, dtype=np.bool_)
            fresh[st] = True
            out.append(_fading(self.E[b], fresh, decay))
        return np.where((_older_bank(self.starts, nb) == 0)[:, None], out[0], out[1])

    def decide(self, mu, *, hysteresis: float = 0.2, warmup: float = 0.0, min_dwell: float = 0.0,
               sigma0: int = 0) -> np.ndarray:
        """The candidate active on each decision interval.

        Parameters
        ----------
        mu : (n_blocks + 1, I) ndarray
            The monitoring signals (:meth:`mu`).
        hysteresis, warmup, min_dwell, sigma0
            See :meth:`run`.

        Returns
        -------
        (n_blocks,) int ndarray
        """
        h = as_nonnegative("hysteresis", hysteresis)
        nm = len(self.sup.gains)
        mu = np.asarray(mu)
        if mu.shape != (self.n_blocks + 1, nm) or not np.issubdtype(mu.dtype, np.floating):
            raise ValueError(f"mu must be a float array of shape {(self.n_blocks + 1, nm)} (one row "
                             f"per decision point, one column per candidate), but found "
                             f"{mu.dtype} of shape {mu.shape}")
        if not np.all(np.isfinite(mu)) or np.any(mu < 0):
            raise ValueError("mu must hold finite, non-negative monitoring signals")
        first, dwell = _schedule(self.n_blocks, self.sup.decide_every, warmup, min_dwell, sigma0, nm)
        # the cost law compares μ (least wins); the band-power law compares 1/μ (largest μ wins)
        with np.errstate(divide="ignore"):
            cost = mu if self.sup.law == "cost" else 1.0 / mu
        return _decide(np.ascontiguousarray(cost), self.n_blocks, int(sigma0), first, dwell, h)

    def run_sequence(self, sigma, *, where: str = "supervise") -> SupervisedRun:
        """The switched loop run exactly along a given sequence.

        Parameters
        ----------
        sigma : (n_blocks,) array_like of int
            One candidate per decision interval.
        where : str, optional
            Prefix of the divergence monitor's warning.

        Returns
        -------
        SupervisedRun
            Without monitoring signals.

        Raises
        ------
        ValueError
            If ``sigma`` has the wrong shape or names no candidate.

        Warns
        -----
        UnstableRunWarning
            If the state at a switch or at the end exceeds the divergence monitor's bound.
        """
        g = self.grid
        sigma = np.asarray(sigma)
        if sigma.shape != (self.n_blocks,) or not np.issubdtype(sigma.dtype, np.integer):
            raise ValueError(f"sigma must be an integer array of one candidate index per decision "
                             f"interval ({self.n_blocks}), but found {sigma.dtype} of shape "
                             f"{sigma.shape}")
        if sigma.min() < 0 or sigma.max() >= len(self.loops):
            raise ValueError(f"sigma must hold candidate indices in [0, {len(self.loops)}), but "
                             f"found {int(sigma.min())} to {int(sigma.max())}")
        sigma = sigma.astype(np.int64)
        e, big, x = g.run(self.tables, sigma[g.block], False, self.xstart)
        change = np.flatnonzero(np.diff(sigma)) + 1
        # the divergence monitor's rule (fdsc._divergence) at the switches and at the end
        limit = _divergence.threshold([lp.A for lp in self.loops], self.loops[0].B, self.xstart, self.d)
        ends = np.r_[np.searchsorted(g.block, change) - 1, e.size - 1]
        ends = ends[ends >= 0]
        over = np.flatnonzero(big[ends] > limit)
        if not over.size and np.all(np.isfinite(big)) and not np.all(np.isfinite(e)):
            raise EnergyOverflowError(f"{where}: the state stays finite but the energy exceeds the "
                                      "float range (about 1.8e308): scale the disturbance down")
        diverged = None
        if over.size or not np.all(np.isfinite(e)):
            s = int(ends[over[0]]) if over.size else int(np.flatnonzero(~np.isfinite(e))[0])
            diverged = float(g.edges[s + 1])
            bound = limit / _divergence.SAFETY
            warnings.warn(_divergence.message(f"{where}: ", diverged, float(big[s]) / bound, bound),
                          UnstableRunWarning, stacklevel=3)
        seq = np.r_[sigma[:1], sigma[change]]
        share = np.bincount(sigma, minlength=len(self.loops)) / sigma.size
        return SupervisedRun(self.horizon, None, float(e.sum()), self.input_energy,
                             change * self.sup.decide_every, seq, share,
                             x[:self.sup.plant.n_states], self.points, np.zeros((0, len(self.loops))),
                             diverged)

    def run(self, *, forgetting: float = 0.5, hysteresis: float = 0.2, warmup: float = 0.0,
            min_dwell: float = 0.0, sigma0: int = 0) -> SupervisedRun:
        """Run the law.

        Parameters
        ----------
        forgetting : float, optional
            λ > 0 (1/s), the monitoring signals' rate of forgetting.
        hysteresis : float, optional
            h ≥ 0: switch from q to p when ``(1 + h) μ_p < μ_q`` (cost law) or
            ``μ_p > (1 + h) μ_q`` (band-power law); strict, so equal signals (monitors at rest)
            keep the active candidate. Relative, so the law does not depend on ŵ's scale.
        warmup : float, optional
            No decision before this time (s; ``sigma0`` is active until then).
        min_dwell : float, optional
            No switch within this time (s) of the previous one: the dwell time a certificate
            (:func:`fdsc.geromel_colaneri_dwell`) asks of the direct realization.
        sigma0 : int, optional
            The candidate active at t = 0.

        Returns
        -------
        SupervisedRun
        """
        mu = self.mu(forgetting)
        _check_mu(mu, "run")
        sigma = self.decide(mu, hysteresis=hysteresis, warmup=warmup, min_dwell=min_dwell, sigma0=sigma0)
        r = self.run_sequence(sigma)
        return SupervisedRun(r.horizon, r.dt, r.energy, r.input_energy, r.switch_times, r.sequence,
                             r.time_share, r.x_final, self.points, mu, r.diverged_at)

    def fixed(self, i: int) -> float:
        """∫zᵀz of one candidate held throughout, from x0 (by the same exact engine).

        Parameters
        ----------
        i : int
            The candidate.

        Returns
        -------
        float
        """
        return self.run_sequence(np.full(self.n_blocks, self._index("i", i))).energy

    def _index(self, name, i):
        nm = len(self.loops)
        if isinstance(i, bool) or not isinstance(i, int | np.integer) or not 0 <= i < nm:
            raise ValueError(f"{name} must be a candidate's index in [0, {nm}), but found {i!r}")
        return int(i)

    def energy_of(self, loop) -> float:
        """∫zᵀz of any other loop from x0, by the same exact engine.

        Parameters
        ----------
        loop : LTISystem
            Of the plant's state size (e.g. the closed loop of a gain that is not a candidate).

        Returns
        -------
        float

        Raises
        ------
        TypeError, DimensionError, ValueError
            If ``loop`` is not an LTISystem of the plant's size with one input, or not stable.
        """
        from .plant import LTISystem

        check_type("loop", loop, LTISystem, "an fdsc.LTISystem")
        n = self.x0.size
        if loop.A.shape != (n, n) or loop.B.shape[1] != 1:
            raise DimensionError(f"loop must have the plant's {n} states and one input, but found "
                                 f"A {loop.A.shape} and B {loop.B.shape}")
        worst = float(np.max(np.linalg.eigvals(loop.A).real))
        if worst >= 0:
            raise ValueError(f"loop must be stable, but A has an eigenvalue with real part {worst:.4g}")
        g = self.grid
        e = float(g.run(g.tables([_abcd(loop)]), 0, False, self.x0)[0].sum())
        if not math.isfinite(e):
            raise EnergyOverflowError("energy_of: the energy exceeds the float range (about 1.8e308)")
        return e

    def piece_steps(self) -> list:
        """The steps of every piece of d (zero stretches included).

        Returns
        -------
        list of (int, int)
            ``(first step, end step)`` per piece.
        """
        g = self.grid
        cut = np.r_[0, np.flatnonzero(np.diff(g.piece)) + 1, g.piece.size]
        return list(zip(cut[:-1], cut[1:], strict=True))

    def segment_law(self, choice) -> float:
        """∫zᵀz of a law that holds one candidate per piece of d, the state carried over.

        Parameters
        ----------
        choice : sequence of int
            The candidate on each piece of :meth:`piece_steps`.

        Returns
        -------
        float

        Raises
        ------
        ValueError
            If ``choice`` does not name one candidate per piece.
        """
        g, x, total = self.grid, self.xstart.copy(), 0.0
        spans = self.piece_steps()
        if isinstance(choice, str) or not hasattr(choice, "__len__"):
            raise TypeError(f"choice must be a sequence of candidate indices, but found {choice!r}")
        if len(choice) != len(spans):
            raise ValueError(f"choice must name one candidate per piece ({len(spans)}), but found "
                             f"{len(choice)}")
        choice = [self._index(f"choice[{k}]", c) for k, c in enumerate(choice)]
        for (a, b), c in zip(spans, choice, strict=True):
            e, _big, x = g.run(self.tables, c, False, x, a, b)
            total += float(e.sum())
        return total

    def clairvoyant(self) -> tuple:
        """The clairvoyant per-segment oracle: on each piece of d the candidate with the least
        energy on that piece from the carried-over state.

        Returns
        -------
        energy : float
        choice : list of int
            The candidate on each piece.
        """
        g, x, total, choice = self.grid, self.xstart.copy(), 0.0, []
        for a, b in self.piece_steps():
            best = None
            for i in range(len(self.loops)):
                e, _big, xi = g.run(self.tables, i, False, x, a, b)
                if best is None or e.sum() < best[0]:
                    best = (float(e.sum()), i, xi)
            total += best[0]
            choice.append(best[1])
            x = best[2]
        return total, choice


def supervise(plant, gains, d, horizon: float, dt: float | None = None, *, law: str = "cost",
              bands=None, forgetting: float = 0.5, hysteresis: float = 0.2, restart: float = 20.0,
              decide_every: float = 0.1, warmup: float = 0.0, min_dwell: float = 0.0, K0=None,
              x0=None, sigma0: int = 0) -> SupervisedRun:
    """Run a switching law that decides on the disturbance estimate (module docstring).

    Parameters
    ----------
    plant, gains, law, bands, decide_every, restart, K0
        The law (:class:`Supervisor`).
    d : Sinusoids or Piecewise
        The disturbance (scalar).
    horizon : float
        Run length (s), a whole number of decision intervals.
    dt : float, optional
        None (default): the switched run is integrated exactly (:mod:`fdsc._blocks`). Given:
        it is run by :func:`fdsc.simulate_stream` at this step, piece by piece between switches
        (energies by Simpson's rule on the grid, like every fixed-gain run of the simulator);
        ``decide_every`` must be a multiple of ``dt``. The decisions are the same either way.
    forgetting, hysteresis, warmup, min_dwell, sigma0
        See :meth:`Prepared.run`.
    x0 : (n,) array_like, optional
        Initial state of the plant (default 0); the monitors start from rest.

    Returns
    -------
    SupervisedRun

    Raises
    ------
    TypeError, ValueError
        See :class:`Supervisor`; also if ``d`` is not Sinusoids or Piecewise, ``horizon`` is
        not a whole number of decision intervals, ``decide_every`` is not a whole number of
        steps ``dt``, or ``sigma0`` is not a candidate's index.
    UnstableError
        If a piece of a run with ``dt`` overflows.

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
    >>> run = supervise(plant, gains, d, 120.0, warmup=5.0)
    >>> run.sequence.tolist(), bool(60.0 < run.switch_times[-1] < 70.0)
    ([0, 1], True)
    """
    sup = Supervisor(plant, gains, law=law, bands=bands, decide_every=decide_every, restart=restart,
                     K0=K0)
    prep = sup.prepare(d, horizon, x0=x0)
    if dt is None:
        return prep.run(forgetting=forgetting, hysteresis=hysteresis, warmup=warmup,
                        min_dwell=min_dwell, sigma0=sigma0)
    dt = as_positive("dt", dt)
    block = round(sup.decide_every / dt)
    if block < 1 or abs(block * dt - sup.decide_every) > 1e-9 * sup.decide_every:
        raise ValueError(f"decide_every must be a whole number of steps of dt = {dt:g} s, but found "
                         f"{sup.decide_every!r}")
    mu = prep.mu(forgetting)
    _check_mu(mu, "supervise")
    sigma = prep.decide(mu, hysteresis=hysteresis, warmup=warmup, min_dwell=min_dwell, sigma0=sigma0)
    return _run_on_grid(prep, sigma, mu, dt)


def _check_mu(mu, where):
    """Refuse monitoring signals that overflowed (the fading sum of finite energies)."""
    if not np.all(np.isfinite(mu)):
        raise EnergyOverflowError(f"{where}: a monitoring signal exceeds the float range (about 1.8e308), "
                                  "so the law cannot compare them: scale the disturbance (or x0) down")


def _run_on_grid(prep, sigma, mu, dt):
    """The switched run along ``sigma`` (one candidate per decision interval) by
    :func:`fdsc.simulate_stream` at step dt."""
    from .stream import simulate_stream

    sup = prep.sup
    change = np.flatnonzero(np.diff(sigma)) + 1
    switch_times = change * sup.decide_every
    sequence = np.r_[sigma[:1], sigma[change]]
    block = round(sup.decide_every / dt)
    # the modes a switch excites: those of the loop switched to (direct); through copies only the
    # plant's own loop A + B2 K0 (the copies run on ŵ whatever σ does)
    if sup.K0 is None:
        excited = [prep.loops[int(m)].A for m in set(sequence[1:].tolist())]
    else:
        excited = [sup.plant.A + sup.plant.B2 @ sup.K0] if change.size else []
    fastest = max([float(np.abs(np.linalg.eigvals(M)).max()) for M in excited] + [0.0])
    if fastest * dt > STIFF_STEP:
        warnings.warn(f"supervise: a loop the law switches to has a mode at {fastest:.3g} /s, so "
                      f"|λ| dt = {fastest * dt:.3g} > {STIFF_STEP:g}: the transient that follows the switch "
                      "is shorter than a step, and Simpson's rule on the grid misses its energy; run it "
                      "exactly (dt=None)", RuntimeWarning, stacklevel=3)
    N = prep.n_blocks * block + 1
    bounds = [0, *(change * block).tolist(), N - 1]
    x = prep.xstart.copy()
    limit = _divergence.threshold([lp.A for lp in prep.loops], prep.loops[0].B, x, prep.d)
    energy = input_energy = 0.0
    diverged = None
    for a, b, m in zip(bounds[:-1], bounds[1:], sequence, strict=True):
        if b <= a:
            continue
        r = simulate_stream(prep.loops[int(m)], shift_signal(prep.d, a * dt), (b - a) * dt, dt, x0=x)
        energy += r.energy
        input_energy += r.input_energy
        x = r.x_final
        big = float(np.abs(x).max())
        if big > limit and diverged is None:
            bound = limit / _divergence.SAFETY
            diverged = b * dt
            warnings.warn(_divergence.message("supervise: ", b * dt, big / bound, bound),
                          UnstableRunWarning, stacklevel=3)
    share = np.bincount(sigma, minlength=len(prep.loops)) / sigma.size
    return SupervisedRun(prep.horizon, float(dt), float(energy), float(input_energy), switch_times,
                         sequence, share, x[:sup.plant.n_states], prep.points, mu, diverged)
