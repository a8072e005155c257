"""Exact-discretization simulation of LTI and switched closed loops under the paper's disturbances.

Between two samples the active mode i is an LTI system driven by a sum of sinusoids, so the
step is exact: with the steady-state (particular) solution ``x_p`` of mode i for the sinusoids
active on ``[t_k, t_{k+1})``,

    x_{k+1} = x_p(t_{k+1}) + e^{A_i Δt} (x_k − x_p(t_k)).

No quadrature of the input is involved; the only approximation of a switched run (the switched
closed loop of paper eq. (32) under the law of paper eq. (31)) is that the switching law is
evaluated on the sample grid. The whole run is one compiled numba loop
(:mod:`fdsc._simulate_kernel`): it evaluates ``x_p``, d and ḋ from the tones' phasors, rotated
from sample to sample by exact rotations (each phasor is the product of two correctly rounded
numbers), and computes ẋ and z as it goes, so no per-step array is built beforehand.
:mod:`fdsc._simulate_reference` is the same step in plain Python/NumPy with ``x_p`` from NumPy's
cos and sin on the whole grid, kept for the tests and the benchmark; the two agree to rounding.
The modes and the law's weights are read as in :mod:`fdsc.stream` (:mod:`fdsc._modes`).
"""

import math
import warnings
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from scipy.linalg import expm

from . import _divergence
from ._defaults import DEFAULT_MAX_MEMORY
from ._modes import LAWS, _as_modes, _law_weights, _shared_input
from ._simulate_kernel import PHASOR_BLOCK, _samples, _segments, check_resolved, tone_tables
from ._simulate_kernel import kernel as _compiled_kernel
from ._simulate_reference import _kernel_numpy, _particular_many, _particular_steps
from ._step_energy import mode_coordinates, trajectory_step_energies
from ._validation import as_choice, as_count, as_matrix, as_positive, as_vector, check_type
from .exceptions import EnergyOverflowError, MemoryLimitError, UnstableError, UnstableRunWarning
from .plant import LTISystem
from .rules import PRINTED, SwitchRule, rule_state
from .signals import Piecewise, Sinusoids

__all__ = ["SimResult", "particular", "simulate", "time_grid", "envelope", "estimate_memory",
           "LAWS", "KERNELS", "DEFAULT_MAX_MEMORY"]

#: Compiled kernel or its plain NumPy reference.
KERNELS = ("numba", "numpy")
#: Grid uniformity: |t_k − (t_0 + k dt)| may not exceed this fraction of dt (plus rounding of t).
GRID_RTOL = 1e-6


@dataclass(frozen=True)
class SimResult:
    """A simulated run on the grid ``t``, as returned by :func:`simulate`.

    Parameters
    ----------
    t : (N,) ndarray
        Uniform time grid in s.
    x, xdot : (N, n) ndarray
        State and its derivative under the mode active on ``[t_k, t_{k+1})``.
    z : (N, p) ndarray
        Regulated output.
    d : (N,) ndarray
        Disturbance samples.
    sigma : (N,) int ndarray
        Active mode index (0-based) on ``[t_k, t_{k+1})``.
    step_energy, step_input_energy : (N − 1,) ndarray
        ``∫ zᵀz`` and ``∫ d²`` over each step ``[t_k, t_{k+1})``, exact (a quadratic form of the
        state and the tones' oscillators at ``t_k`` per step; :mod:`fdsc._step_energy`). The
        output of a switched run jumps at every switch, so no quadrature of the samples ``z``
        gives its energy: these do. None only for a result made by hand.
    """

    t: np.ndarray
    x: np.ndarray
    xdot: np.ndarray
    z: np.ndarray
    d: np.ndarray
    sigma: np.ndarray
    step_energy: np.ndarray | None = None
    step_input_energy: np.ndarray | None = None

    @property
    def switch_times(self) -> np.ndarray:
        """Instants (s) at which the active mode changes, a (S,) ndarray."""
        return self.t[1:][np.diff(self.sigma) != 0]

    def energy(self) -> float:
        """∫ zᵀz dt over the run, exact (the sum of :attr:`step_energy`).

        Returns
        -------
        float

        Raises
        ------
        EnergyOverflowError
            If the energy exceeds the float range (the samples themselves are finite: every
            step's energy is formed at a scale of a power of two and scaled back, so a finite
            energy is never lost to an overflow on the way).
        ValueError
            If the result carries no step energies (made by hand, not by :func:`simulate`).

        Notes
        -----
        The numerator of the energy ratios of paper eqs. (14), (15) and (35).
        """
        return _total(self.step_energy, self.z, "energy: ∫zᵀz")

    def input_energy(self) -> float:
        """∫ d² dt over the run, exact (the sum of :attr:`step_input_energy`).

        Returns
        -------
        float

        Raises
        ------
        EnergyOverflowError, ValueError
            As :meth:`energy`.
        """
        return _total(self.step_input_energy, self.d, "input_energy: ∫d²")

    def cumulative_energy(self) -> tuple[np.ndarray, np.ndarray]:
        """``∫₀^{t_k} zᵀz`` and ``∫₀^{t_k} d²`` at every grid point, exact.

        Returns
        -------
        ez, ed : (N,) ndarray
            Running integrals (0 at the first point).

        Raises
        ------
        ValueError
            If the result carries no step energies (made by hand).
        """
        if self.step_energy is None or self.step_input_energy is None:
            raise ValueError("this SimResult carries no step energies (it was not made by simulate)")
        return (np.concatenate([[0.0], np.cumsum(self.step_energy)]),
                np.concatenate([[0.0], np.cumsum(self.step_input_energy)]))

    def time_share(self) -> np.ndarray:
        """Fraction of the horizon spent in each mode (β_i of Theorem 1(3), paper eq. (36)).

        Returns
        -------
        (I,) ndarray
            One share per mode up to the largest mode index visited; the shares sum to 1.
        """
        n_modes = int(self.sigma.max()) + 1
        dt = np.diff(self.t)
        return np.array([dt[self.sigma[:-1] == i].sum() for i in range(n_modes)]) / (
            self.t[-1] - self.t[0])


def _total(steps, samples, what):
    """The compensated sum of the step energies ``steps``; an overflow of a run whose samples are
    finite raised by name."""
    if steps is None:
        raise ValueError(f"{what.split(':')[0]}: this SimResult carries no step energies (it was "
                         "not made by simulate), and its energy is not a quadrature of samples")
    with np.errstate(over="ignore", invalid="ignore"):
        total = math.fsum(steps) if np.all(np.isfinite(steps)) else math.inf
    big = float(np.abs(samples).max()) if samples.size else 0.0
    if np.isfinite(big) and not math.isfinite(total):
        raise EnergyOverflowError(f"{what} over the run exceeds the float range (about 1.8e308) "
                                  f"although every sample is finite (largest {big:.3g})")
    return total


def time_grid(horizon: float, dt: float) -> np.ndarray:
    """Uniform grid ``0, dt, …, horizon``; ``horizon`` must be a multiple of ``dt``.

    Parameters
    ----------
    horizon : float
        End time in s (> 0).
    dt : float
        Step in s (> 0).

    Returns
    -------
    (N,) ndarray
        ``N = horizon / dt + 1`` points; :func:`simulate` accepts every grid made here.

    Raises
    ------
    ValueError
        If ``dt ≤ 0``, ``horizon ≤ 0`` or the horizon is not a multiple of dt (to a relative
        1e-9).

    Examples
    --------
    >>> time_grid(1.0, 0.25)
    array([0.  , 0.25, 0.5 , 0.75, 1.  ])
    """
    horizon, dt = as_positive("horizon", horizon), as_positive("dt", dt)
    n = round(horizon / dt)
    if abs(n * dt - horizon) > 1e-9 * horizon:
        raise ValueError(f"horizon ({horizon:g}) must be a multiple of dt ({dt:g})")
    return np.linspace(0.0, horizon, n + 1)


def particular(A: ArrayLike, B: ArrayLike, d: Sinusoids, t: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Steady-state response ``x_p`` and ``ẋ_p`` of ``dx/dt = A x + B d`` to ``d`` (Sinusoids).

    ``x_p(t) = Σ Im(X_k e^{j(ω_k t + φ_k)})`` with ``X_k = (jω_k I − A)⁻¹ B a_k``. Requires
    ``jω_k`` not to be an eigenvalue of A (A need not be Hurwitz).

    Parameters
    ----------
    A : (n, n) array_like
        State matrix.
    B : (n, 1) array_like
        Disturbance input matrix (one input).
    d : Sinusoids
        The disturbance.
    t : (N,) array_like
        Times in s.

    Returns
    -------
    x_p, xdot_p : (N, n) ndarray
        The particular solution and its derivative at the times ``t``.

    Raises
    ------
    SingularFrequencyError
        If a tone's ``jω_k`` is an eigenvalue of A (resonance: no bounded particular solution).
    DimensionError
        If A is not square or B is not (n, 1).
    TypeError
        If ``d`` is not :class:`~fdsc.signals.Sinusoids`.

    Examples
    --------
    >>> xp, xdp = particular([[-1.0]], [[1.0]], Sinusoids([1.0], [1.0]), [0.0, np.pi / 2])
    >>> xp.ravel(), xdp.ravel()          # x_p = (sin t − cos t) / 2
    (array([-0.5,  0.5]), array([0.5, 0.5]))
    """
    A = as_matrix("A", A, square=True)
    B = as_matrix("B", B, (A.shape[0], 1))
    check_type("d", d, Sinusoids, "an fdsc.signals.Sinusoids")
    (xp,), (xdp,) = _particular_many([A], B, d, as_vector("t", t), derivative=True)
    return xp, xdp


def estimate_memory(n_steps: int, n_states: int, n_outputs: int, n_modes: int, n_tones: int = 1,
                    *, n_pieces: int = 1, longest_piece: int | None = None,
                    kernel: str = "numba") -> int:
    """Bytes :func:`simulate` needs for a run of ``n_steps`` samples (peak working memory).

    The compiled kernel needs the returned trajectories (x, ẋ, z, d, σ, t, and the two energies
    of every step) and, per piece of the disturbance, its tone tables: rotations for
    ``min(PHASOR_BLOCK, longest_piece + 1)`` steps
    (:data:`fdsc._simulate_kernel.PHASOR_BLOCK`) and each mode's particular-solution
    coefficients. The NumPy reference also holds the particular solutions at both ends of every
    step for every mode and the per-tone temporaries of their evaluation.

    Parameters
    ----------
    n_steps, n_states, n_outputs, n_modes : int
        Grid points N, states n, regulated outputs p and modes I of the run.
    n_tones : int, optional
        Largest number of sinusoids in one segment of the disturbance.
    n_pieces : int, optional
        Pieces of the disturbance (those of a Piecewise and the stretches where it is off).
    longest_piece : int, optional
        Steps of the longest piece (default ``n_steps − 1``, the whole run).
    kernel : {"numba", "numpy"}, optional
        The kernel of the run (see :func:`simulate`).

    Returns
    -------
    int
        Bytes (8 per float).

    Raises
    ------
    ValueError
        If ``kernel`` is not one of :data:`KERNELS`.

    Examples
    --------
    >>> estimate_memory(10**7, 2, 3, 2) / 2**30 < 1
    True
    >>> estimate_memory(10**7, 2, 3, 2, kernel="numpy") / 2**30 < 4
    True
    """
    as_choice("kernel", kernel, KERNELS)
    per_step = 2 * n_states + n_outputs + 5           # x, ẋ, z, d, σ, t, two step energies
    if kernel == "numba":
        rows = min(PHASOR_BLOCK, (n_steps - 1 if longest_piece is None else longest_piece) + 1)
        tables = n_pieces * (n_tones * (2 * rows + 2 * n_modes * n_states + 3) + 2)
        return int(8 * per_step * n_steps) + int(8 * tables)
    per_step += (2 * n_modes * n_states               # particular solutions, left and right
                 + n_modes * n_states + 2             # one segment's x_p per mode, cos and sin
                 + n_states + n_outputs)              # per-mode products when assembling ẋ, z
    return int(8 * per_step * n_steps) + int(8 * n_tones * n_steps)


def _check_grid(t):
    t = as_vector("t", t)
    if t.size < 2:
        raise ValueError("t must be a 1-D grid of at least 2 points")
    dt = (t[-1] - t[0]) / (t.size - 1)
    if not dt > 0:
        raise ValueError("t must be increasing (dt > 0)")
    dev = float(np.max(np.abs(t - (t[0] + dt * np.arange(t.size)))))
    if dev > GRID_RTOL * dt + 16 * np.finfo(float).eps * float(np.max(np.abs(t))):
        raise ValueError(f"t must be a uniform grid (use time_grid): a point deviates from "
                         f"t_0 + k dt by {dev:.3g} s with dt = {dt:.6g} s")
    return t, dt


def envelope(t: ArrayLike, y: ArrayLike, every: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Min/max of ``y`` over consecutive bins of ``every`` samples: a decimation that keeps
    everything a plot at the coarse scale must show (no aliasing of fast oscillations).

    Parameters
    ----------
    t : (N,) array_like
        Sample times.
    y : (N,) or (N, p) array_like
        Samples.
    every : int
        Samples per bin (≥ 1). The last bin may be shorter.

    Returns
    -------
    t_bin : (M,) ndarray
        Start time of each bin.
    lo, hi : (M,) or (M, p) ndarray
        Smallest and largest sample of each bin.

    Raises
    ------
    ValueError
        If ``y`` has not one row per time, ``every`` is not an integer ≥ 1, or ``t`` is not
        finite and real.

    Examples
    --------
    >>> t = np.arange(6.0); y = np.array([0.0, 2.0, -1.0, 5.0, 3.0, 3.0])
    >>> envelope(t, y, 2)
    (array([0., 2., 4.]), array([ 0., -1.,  3.]), array([2., 5., 3.]))
    """
    t = as_vector("t", t)
    y = np.asarray(y, dtype=float)
    if y.shape[:1] != t.shape:
        raise ValueError(f"y must have {t.size} rows (one per time), found shape {y.shape}")
    every = as_count("every", every)
    starts = np.arange(0, t.size, every)
    return t[starts], np.minimum.reduceat(y, starts, axis=0), np.maximum.reduceat(y, starts, axis=0)


def _monitor(x, t, A, B, x0, d, where):
    """The divergence monitor (:mod:`fdsc._divergence`) on a whole trajectory: warn at the first
    point whose largest state component exceeds SAFETY times the modes' bound."""
    if len(A) < 2:
        return      # one mode: its state never exceeds the bound (see fdsc._divergence)
    limit = _divergence.threshold(A, B, x0, d)
    if not np.max(np.abs(x)) > limit:
        return
    k = int(np.argmax(np.max(np.abs(x), axis=1) > limit))
    bound = limit / _divergence.SAFETY
    warnings.warn(_divergence.message(where, float(t[k]), float(np.linalg.norm(x[k])) / bound, bound),
                  UnstableRunWarning, stacklevel=3)


def simulate(modes: LTISystem | list, d: Sinusoids | Piecewise, t: ArrayLike, *,
             x0: ArrayLike | None = None, law_bands: list | None = None, law_Q: list | None = None,
             law: str = "previous", sigma0: int = 0, rule: SwitchRule = PRINTED,
             law_weights: list | None = None, kernel: str = "numba",
             max_memory: float = DEFAULT_MAX_MEMORY) -> SimResult:
    """Simulate an LTI (one mode) or switched (several modes) closed loop exactly on a grid.

    Parameters
    ----------
    modes : LTISystem or list of LTISystem
        Closed loops ``(A_i, B, C_i, D)``; all share B and D (state feedback). Each may also be a
        python-control ``StateSpace`` or an ``(A, B, C, D)`` tuple.
    d : Sinusoids or Piecewise
        Scalar disturbance; Piecewise breaks must lie on the grid.
    t : (N,) array_like
        Uniform grid (see :func:`time_grid`).
    x0 : (n,) array_like, optional
        Initial state (real, finite; default 0).
    law_bands : list of Band, optional
        Ω_i of the switching law (required for several modes).
    law_Q : list of (n, n) array_like, optional
        Q_i of the switching law (symmetric positive definite).
    law : {"previous", "candidate"}, optional
        How ẋ enters the law (see :data:`LAWS`).
    sigma0 : int, optional
        Mode assumed active before t = 0 (used for ẋ at t = 0).
    rule : SwitchRule, optional
        Hysteresis, minimum dwell time and/or moving window applied to the law
        (:class:`~fdsc.rules.SwitchRule`; default the printed argmax). Its window must be a
        whole number ≥ 2 of steps, its dwell more than one step; either longer than the run is
        clamped to it (a dwell beyond the horizon gives the fixed-gain run of ``sigma0``). With
        a single mode a rule has no effect (a warning says so).
    law_weights : list of array_like, optional
        Instead of ``law_bands`` and ``law_Q``: one symmetric weight W_i per mode, (2n, 2n) on
        ``[ẋ; x]`` or (3n, 3n) on ``[ẍ; ẋ; x]``; the law picks ``argmax_i vᵀ W_i v``. The measured
        ẍ is ``A_σ(t⁻) ẋ + B ḋ`` (each candidate's own with ``law="candidate"``), ḋ exact.
    kernel : {"numba", "numpy"}, optional
        Compiled kernel or its plain NumPy reference.
    max_memory : float, optional
        Refuse runs whose estimated working memory (:func:`estimate_memory`, plus the moving
        window's samples) exceeds this many bytes (default :data:`DEFAULT_MAX_MEMORY`, 4 GiB).

    Returns
    -------
    SimResult

    Raises
    ------
    ValueError
        On mismatched mode/law counts, modes that do not share B and D, modes without a
        regulated output (C with 0 rows), a disturbance with more than one input, a non-uniform
        grid, breaks of a Piecewise off the grid, an MF range in ``law_bands`` (the law takes
        real Ψ only), non-PD Q, law weights that are not symmetric or given together with
        ``law_bands``/``law_Q``, an unknown law or kernel, ``sigma0`` not a mode index, or a
        ``rule`` whose window is off the grid or whose window or dwell is one step or less
        (:meth:`SwitchRule.steps <fdsc.rules.SwitchRule.steps>`).
    TypeError
        If ``modes``, ``d``, ``law_bands`` or ``rule`` are not of the accepted types.
    DimensionError
        If a law weight is neither (2n, 2n) nor (3n, 3n).
    SingularFrequencyError
        If a disturbance tone sits at an eigenvalue of a mode (resonance).
    MemoryLimitError
        If the run would need more than ``max_memory`` bytes (:func:`estimate_memory` and the
        window's (L, I) samples); raised before any array of the run is allocated (the grid
        check's temporaries, about 3 N floats, come first).
    UnstableError
        If the state overflows (the loop diverges) during the run.

    Warns
    -----
    UnstableRunWarning
        If a mode is not Hurwitz but the run stayed finite (its energies grow with the horizon);
        or if the divergence monitor flags a switched run (:mod:`fdsc._divergence`: a state
        exceeds 10⁶ times the largest any of its modes reaches alone from the same x0 under the
        same disturbance; the message names the time and the growth).
    UserWarning
        If ``rule`` is not the printed law but there is a single mode (it has no effect).

    Notes
    -----
    Several modes form the switched closed loop of paper eq. (32) (with ``C + D2 K_i``), switched by
    the law of paper eq. (31), ``σ = argmax_i [ẋ; x]ᵀ (Re Ψ_i ⊗ Q_i) [ẋ; x]``, evaluated at every
    grid point (modified by ``rule``); the new mode holds until the next one.

    Examples
    --------
    >>> from fdsc import LTISystem, Sinusoids
    >>> loop = LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]])
    >>> run = simulate(loop, Sinusoids([1.0], [1.0]), time_grid(10.0, 0.01))
    >>> exact = (np.sin(run.t) - np.cos(run.t) + np.exp(-run.t)) / 2   # from x(0) = 0
    >>> run.x.shape, bool(np.allclose(run.x[:, 0], exact, rtol=0, atol=1e-12))
    ((1001, 1), True)
    """
    modes = _as_modes(modes)
    n, B, D = _shared_input(modes)
    check_type("d", d, Sinusoids | Piecewise, "an fdsc.signals.Sinusoids or Piecewise")
    as_choice("law", law, LAWS)
    as_choice("kernel", kernel, KERNELS)
    max_memory = as_positive("max_memory", max_memory)
    n_modes = len(modes)
    W = _law_weights(n, n_modes, law_bands, law_Q, law_weights)
    check_type("rule", rule, SwitchRule)
    if n_modes == 1 and not rule.is_printed:
        warnings.warn(f"simulate: rule ({rule.describe()}) has no effect on a single mode: the "
                      "run is the fixed-gain run", UserWarning, stacklevel=2)
    sigma0 = as_count("sigma0", sigma0, 0)
    if sigma0 >= n_modes:
        raise ValueError(f"sigma0 must be a mode index in [0, {n_modes}), found {sigma0}")
    t, dt = _check_grid(t)
    # the window's length in steps (clamped to the run) before anything is allocated
    window_steps = rule.steps(dt, t.size - 1)[1]
    x0 = np.zeros(n) if x0 is None else np.array(as_vector("x0", x0, n))
    n_tones = max(p.frequencies.size for p in (d.parts if isinstance(d, Piecewise) else (d,)))
    check_resolved(d, dt)
    pieces = _segments(d, t)
    need = estimate_memory(t.size, n, modes[0].n_outputs, n_modes, n_tones, n_pieces=len(pieces),
                           longest_piece=max(k1 - k0 for k0, k1, _ in pieces), kernel=kernel)
    ring = 8 * n_modes * window_steps if window_steps > 1 else 0
    if need + ring > max_memory:
        window = f" (rule.window = {rule.window!r} s: {ring / 2**30:.3g} GiB)" if ring else ""
        raise MemoryLimitError(
            f"simulate: {t.size} steps of {n_modes} mode(s) need about {(need + ring) / 2**30:.2f} "
            f"GiB{window}, more than max_memory = {max_memory / 2**30:.2f} GiB; shorten the "
            "horizon, enlarge dt or raise max_memory")
    Phi = np.array([expm(m.A * dt) for m in modes])
    A = np.array([m.A for m in modes])
    rparams, ring, ring_sum, istate = rule_state(rule, dt, n_modes, t.size - 1)
    with np.errstate(over="ignore", invalid="ignore"):
        if kernel == "numba":
            tab = tone_tables(pieces, t, A, B[:, 0], dt)
            C = np.array([m.C for m in modes])
            x, sigma, xdot, z, dvals = _compiled_kernel(
                Phi, A, np.ascontiguousarray(B[:, 0]), C, np.ascontiguousarray(D[:, 0]), W, x0,
                int(sigma0), law == "candidate", rparams, ring, ring_sum, istate, t,
                tab["seg_start"], tab["seg_nt"], tab["omega"], tab["amp"], tab["phase"], tab["Xr"],
                tab["Xi"], tab["Rre"], tab["Rim"], float(_samples(d, t, points=[t.size - 1])[0]),
                float(_samples(d, t, derivative=True, points=[t.size - 1])[0]))
        else:
            dvals = _samples(d, t)
            left, right = _particular_steps(list(A), B, pieces, t)
            ddvals = _samples(d, t, derivative=True) if W.shape[1] == 3 * n else np.zeros_like(dvals)
            x, sigma = _kernel_numpy(Phi, left, right, A, np.ascontiguousarray(B[:, 0]), dvals,
                                     ddvals, W, x0, int(sigma0), law == "candidate", rparams, ring,
                                     ring_sum, istate)
    finite = np.isfinite(x).all(axis=1)
    if not finite.all():
        k = int(np.argmin(finite))
        raise UnstableError(f"simulate: the state overflowed at t = {t[k]:g} s (step {k}); the loop "
                            "diverges and no finite energy summarizes it")
    _monitor(x, t, A, B, x0, d, "simulate: ")
    for i, m in enumerate(modes):
        ev = np.linalg.eigvals(m.A)
        if ev.real.max() >= 0 and np.any(sigma == i):
            worst = ev[np.argmax(ev.real)]
            warnings.warn(f"simulate: mode {i} is not Hurwitz (eigenvalue {worst:.6g}) and is "
                          "active in this run; its energies grow with the horizon",
                          UnstableRunWarning, stacklevel=2)
    if kernel == "numpy":
        xdot = np.empty_like(x)
        z = np.empty((t.size, modes[0].n_outputs))
        for i, m in enumerate(modes):
            sel = sigma == i
            xdot[sel] = x[sel] @ m.A.T + np.outer(dvals[sel], B[:, 0])
            z[sel] = x[sel] @ m.C.T + np.outer(dvals[sel], D[:, 0])
    # every step's energy, exact; formed at a power-of-two scale that keeps squares in range
    big = max([float(np.abs(x).max())] + [float(np.abs(p.amplitudes).max())
                                          for _, _, p in pieces if p is not None and p.amplitudes.size])
    scale = max(0, math.frexp(big)[1] - 400) if np.isfinite(big) else 0
    ez, ed = trajectory_step_energies(x, sigma, t, pieces, mode_coordinates(modes), dt, scale)
    return SimResult(t, x, xdot, z, dvals, sigma, ez, ed)
