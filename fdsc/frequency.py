"""Frequency responses, σ_max sweeps and the band peak sup_{ω∈Ω} σ_max(G(jω)).

The band peak is the quantity the gKYP lemma certifies. It is computed on a
logarithmic grid that includes the band limits and the resonance frequencies
of A, then refined locally around the best grid points. For bands that reach
ω = ∞ (HF, entire), the grid is extended until the bound

    σ_max(G(jω)) ≤ σ_max(D) + ‖C‖ ‖B‖ / (ω − ‖A‖),     ω > ‖A‖,

(from ‖(jωI − A)⁻¹‖ ≤ 1 / (ω − ‖A‖)) proves that no larger value lies beyond.
"""

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ._validation import as_count, as_positive, as_vector, check_hurwitz, check_type
from .bands import Band
from .exceptions import IterationLimitError, SingularFrequencyError
from .plant import LTISystem, as_system

__all__ = ["freqresp", "sigma_max", "BandPeak", "band_peak", "DEFAULT_GRID_POINTS",
           "check_no_pole_at", "steady_state_gain", "steady_state_gains"]

#: Grid points per decade-spanning sweep before refinement.
DEFAULT_GRID_POINTS = 4000
_MAX_EXTENSIONS = 60
#: Relative distance below which a frequency counts as sitting on an eigenvalue of A.
POLE_RTOL = 1e-10




def check_no_pole_at(A: np.ndarray, omega: ArrayLike, what: str = "G(jω)") -> None:
    """Raise if ``jω`` is (numerically) an eigenvalue of ``A`` for some ω in ``omega``.

    An eigenvalue λ counts as sitting at ω when ``|Re λ|`` and ``|Im λ − ω|`` are both at most
    ``POLE_RTOL · max(1, |λ|)``.

    Parameters
    ----------
    A : (n, n) ndarray
        Square real matrix (already validated by the caller).
    omega : (k,) array_like
        Frequencies in rad/s.
    what : str, optional
        What is undefined there (used in the message).

    Raises
    ------
    SingularFrequencyError
        If some ``jω`` is an eigenvalue of ``A``; the message names ω and the eigenvalue.

    Examples
    --------
    >>> check_no_pole_at(np.array([[0.0, 1.0], [-1.0, 0.0]]), [0.5, 1.0])  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    fdsc.exceptions.SingularFrequencyError: G(jω) is undefined at ω = 1 rad/s: A has the eigenvalue 1j ...
    """
    w = np.asarray(omega, dtype=float).reshape(-1)
    ev = np.linalg.eigvals(A) if A.size else np.zeros(0)
    for lam in ev:
        scale = max(1.0, abs(lam))
        if abs(lam.real) > POLE_RTOL * scale:
            continue
        hit = np.abs(w - lam.imag) <= POLE_RTOL * scale
        if np.any(hit):
            raise SingularFrequencyError(
                f"{what} is undefined at ω = {w[hit][0]:g} rad/s: A has the eigenvalue "
                f"{lam.imag:g}j on the imaginary axis")


def freqresp(sys: LTISystem, omega: ArrayLike) -> np.ndarray:
    """Frequency response ``G(jω) = C (jωI − A)⁻¹ B + D``.

    Parameters
    ----------
    sys : LTISystem, control.StateSpace or (A, B, C, D)
        The system (any form :func:`~fdsc.plant.as_system` accepts); it need not be stable.
    omega : (k,) array_like
        Frequencies in rad/s (finite, real).

    Returns
    -------
    (k, p, m) complex ndarray
        ``G(jω_k)`` for each frequency.

    Raises
    ------
    SingularFrequencyError
        If some ``jω`` is an eigenvalue of A (a pole on the imaginary axis).
    TypeError
        If ``sys`` is not a system.
    ValueError
        If an entry of ``omega`` is NaN, infinite, complex or not numeric.

    Notes
    -----
    The transfer function of paper eq. (6), ``G(s) = C (sI − A)⁻¹ B + D``, on the imaginary axis.

    Examples
    --------
    >>> from fdsc import LTISystem
    >>> sys = LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]])
    >>> complex(freqresp(sys, [1.0])[0, 0, 0])
    (0.5-0.5j)
    """
    sys = as_system(sys)
    w = as_vector("omega", omega)
    check_no_pole_at(sys.A, w)
    n = sys.n_states
    M = 1j * w[:, None, None] * np.eye(n) - sys.A
    X = np.linalg.solve(M, np.broadcast_to(sys.B.astype(complex), (w.size, n, sys.n_inputs)))
    return sys.C @ X + sys.D


def sigma_max(sys: LTISystem, omega: ArrayLike) -> np.ndarray:
    """Largest singular value ``σ_max(G(jω))`` for each ω.

    Parameters
    ----------
    sys : LTISystem, control.StateSpace or (A, B, C, D)
        The system (any form :func:`~fdsc.plant.as_system` accepts).
    omega : (k,) array_like
        Frequencies in rad/s (finite, real).

    Returns
    -------
    (k,) ndarray
        ``σ_max(G(jω_k))``.

    Raises
    ------
    SingularFrequencyError
        If some ``jω`` is an eigenvalue of A.
    ValueError
        If an entry of ``omega`` is NaN, infinite, complex or not numeric.

    Notes
    -----
    The quantity bounded on a band by paper eq. (11).

    Examples
    --------
    >>> from fdsc import LTISystem
    >>> sys = LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]])
    >>> round(float(sigma_max(sys, [0.0])[0]), 12)
    1.0
    """
    G = freqresp(sys, omega)
    return np.linalg.svd(G, compute_uv=False)[:, 0]


@dataclass(frozen=True)
class BandPeak:
    """Result of :func:`band_peak`: the band peak and where it was found.

    Parameters
    ----------
    gamma : float
        sup over the band of σ_max(G(jω)).
    omega : float
        Frequency (rad/s) where it is attained; ``inf`` if the supremum is the
        limit σ_max(D) at ω → ∞.
    band : Band
        The band searched.
    searched_up_to : float
        Largest frequency on the grid in rad/s (for infinite bands, the tail bound of the module
        docstring holds beyond).
    n_evaluations : int
        Number of frequency-response evaluations.

    Examples
    --------
    >>> from fdsc import LTISystem
    >>> sys = LTISystem([[0.0, 1.0], [-1.0, -0.2]], [[0.0], [1.0]], [[1.0, 0.0]], [[0.0]])
    >>> pk = band_peak(sys, Band.mf(0.5, 2.0))
    >>> # resonance of 1/(s² + 2ζs + 1), ζ = 0.1: 1/(2ζ sqrt(1 − ζ²)) at ω = sqrt(1 − 2ζ²)
    >>> round(pk.gamma, 6), round(pk.omega, 6), pk.band.kind
    (5.025189, 0.989949, 'MF')
    """

    gamma: float
    omega: float
    band: Band
    searched_up_to: float
    n_evaluations: int


def _grid(lo, hi, n, extra):
    lo_pos = max(lo, hi * 1e-8) if lo == 0 else lo
    g = np.geomspace(lo_pos, hi, n)
    pts = [g, [lo, hi], [e for e in extra if lo <= e <= hi]]
    return np.unique(np.concatenate([np.asarray(p, dtype=float) for p in pts]))


def band_peak(sys: LTISystem, band: Band, *, n_grid: int = DEFAULT_GRID_POINTS,
              xtol: float = 1e-10) -> BandPeak:
    """The band peak ``sup_{ω∈Ω} σ_max(G(jω))`` with local refinement.

    Parameters
    ----------
    sys : LTISystem, control.StateSpace or (A, B, C, D)
        A stable system (A Hurwitz): the band peak is then the L2 gain for inputs in the band.
    band : Band
        The frequency range Ω.
    n_grid : int, optional
        Points of the initial logarithmic grid (≥ 10).
    xtol : float, optional
        Tolerance in log ω of the local refinement (> 0).

    Returns
    -------
    BandPeak

    Raises
    ------
    UnstableError
        If A is not Hurwitz (the peak of an unstable loop's frequency response bounds no energy).
    IterationLimitError
        If an infinite band could not be closed off by the tail bound.
    TypeError
        If ``band`` is not a :class:`~fdsc.bands.Band`.
    ValueError
        If ``n_grid`` is not an integer ≥ 10 or ``xtol`` is not positive.

    Notes
    -----
    This is the a-posteriori quantity bounded in paper eq. (11) and certified by Lemma 1
    (paper eq. (7)).

    Examples
    --------
    >>> from fdsc import LTISystem
    >>> sys = LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]])
    >>> pk = band_peak(sys, Band.hf(10.0))
    >>> round(pk.gamma, 6), pk.omega   # 1/|j10 + 1| = 1/sqrt(101), at the band edge
    (0.099504, 10.0)
    """
    sys = as_system(sys)
    check_type("band", band, Band)
    n_grid = as_count("n_grid", n_grid, 10)
    xtol = as_positive("xtol", xtol)
    ev = check_hurwitz("sys", sys.A, "the band peak (an L2 gain)")
    return _peak(sys, band, ev, n_grid, xtol)


def _peak(sys, band, ev, n_grid, xtol):
    """The search of :func:`band_peak` for a validated system with eigenvalues ``ev``, none on the
    imaginary axis (stable or not: :meth:`fdsc.Controller.size` searches unstable controllers)."""
    normA = float(np.linalg.norm(sys.A, 2)) if sys.n_states else 0.0
    scale = max(normA, float(np.max(np.abs(ev), initial=0.0)), 1.0)
    extra = list(np.abs(ev.imag)) + list(np.abs(ev))
    lo = band.lower
    hi = band.upper if math.isfinite(band.upper) else max(100.0 * scale, 10.0 * lo)
    w = _grid(lo, hi, int(n_grid), extra)
    s = sigma_max(sys, w)
    n_eval = w.size
    s_inf = float(np.linalg.svd(sys.D, compute_uv=False)[0]) if sys.D.size else 0.0
    if math.isinf(band.upper):
        tail = float(np.linalg.norm(sys.C, 2) * np.linalg.norm(sys.B, 2))
        for _ in range(_MAX_EXTENSIONS):
            peak = float(s.max())
            if tail == 0.0 or peak <= s_inf:
                break
            w_safe = normA + tail / (peak - s_inf)
            if w_safe <= hi:
                break
            new_hi = min(w_safe * 1.01, hi * 1e3)
            w_ext = np.geomspace(hi, new_hi, max(200, int(n_grid) // 4))[1:]
            w, s = np.concatenate([w, w_ext]), np.concatenate([s, sigma_max(sys, w_ext)])
            n_eval += w_ext.size
            hi = new_hi
        else:
            raise IterationLimitError(
                f"band_peak: the tail bound did not close the {band.kind} band after "
                f"{_MAX_EXTENSIONS} extensions (searched up to {hi:.3g} rad/s)")
    best_w, best_s = _refine(sys, w, s, xtol)
    n_eval += 200
    if math.isinf(band.upper) and s_inf >= best_s:
        return BandPeak(s_inf, math.inf, band, float(hi), n_eval)
    return BandPeak(best_s, best_w, band, float(hi), n_eval)


def _refine(sys, w, s, xtol, n_candidates=4):
    """Refine the best local maxima of the sampled curve by bounded scalar search in log ω."""
    idx = np.argsort(s)[::-1]
    chosen = []
    for i in idx:
        if all(abs(i - j) > 2 for j in chosen):
            chosen.append(i)
        if len(chosen) == n_candidates:
            break
    from scipy.optimize import minimize_scalar  # here: a simulation needs no scipy.optimize

    best_w, best_s = float(w[idx[0]]), float(s[idx[0]])
    for i in chosen:
        a, b = w[max(i - 1, 0)], w[min(i + 1, w.size - 1)]
        if a == b:
            continue
        if a == 0.0:
            a = min(b * 1e-6, 1e-12)
        res = minimize_scalar(lambda u: -sigma_max(sys, [math.exp(u)])[0],
                              bounds=(math.log(a), math.log(b)), method="bounded",
                              options={"xatol": xtol, "maxiter": 200})
        val = -float(res.fun)
        if val > best_s:
            best_w, best_s = math.exp(float(res.x)), val
    return best_w, best_s


def steady_state_gain(sys: LTISystem, frequencies: ArrayLike, amplitudes: ArrayLike) -> float:
    """Steady-state L2-induced ratio ``lim_T sqrt(∫₀ᵀ zᵀz / ∫₀ᵀ dᵀd)`` of a stable system driven
    by a scalar sum of sinusoids with distinct positive frequencies.

    Cross terms of distinct frequencies average out, so the ratio is
    ``sqrt(Σ a_k² ‖G(jω_k)‖² / Σ a_k²)`` (G is a column: one disturbance input). It is the limit
    that a running ratio from rest approaches as the transient of every pole decays.

    Parameters
    ----------
    sys : LTISystem, control.StateSpace or (A, B, C, D)
        Stable, with one input.
    frequencies : (K,) array_like
        Distinct ω_k > 0 in rad/s.
    amplitudes : (K,) array_like
        a_k (the phases do not matter).

    Returns
    -------
    float
        The ratio (not its square).

    Raises
    ------
    UnstableError
        If A is not Hurwitz (no steady state).
    ValueError
        If ``sys`` has more than one input, or a frequency is not positive or repeated.
    DimensionError
        If ``amplitudes`` does not have one entry per frequency.

    Notes
    -----
    Its square is the long-run energy ratio ``∫zᵀz / ∫dᵀd`` that objective (P.1), paper eq. (14),
    and paper Remark 5, paper eq. (54), compare with the gain of the in-band controller.

    Examples
    --------
    >>> from fdsc import LTISystem
    >>> sys = LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]])
    >>> round(steady_state_gain(sys, [1.0], [2.0]), 12)   # |1/(j + 1)| = 1/sqrt(2)
    0.707106781187
    """
    return float(steady_state_gains(sys, [(frequencies, amplitudes)])[0])


def steady_state_gains(sys: LTISystem, tones) -> np.ndarray:
    """:func:`steady_state_gain` for many disturbances at once (one frequency-response call).

    Parameters
    ----------
    sys : LTISystem, control.StateSpace or (A, B, C, D)
        Stable, with one input.
    tones : sequence of (frequencies, amplitudes)
        One pair per disturbance, each as :func:`steady_state_gain` takes it.

    Returns
    -------
    (len(tones),) ndarray
        The ratio of each disturbance (equal, bit for bit, to :func:`steady_state_gain` of it).

    Raises
    ------
    UnstableError, ValueError, DimensionError
        As :func:`steady_state_gain` (the message names the disturbance's index).

    Examples
    --------
    >>> from fdsc import LTISystem
    >>> sys = LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]])
    >>> steady_state_gains(sys, [([1.0], [2.0]), ([1.0, 3.0], [1.0, 0.0])]).round(6)
    array([0.707107, 0.707107])
    """
    sys = as_system(sys)
    if sys.n_inputs != 1:
        raise ValueError(f"sys must have one input, found {sys.n_inputs}")
    tones = list(tones)
    if not tones:
        raise ValueError("tones must hold at least one (frequencies, amplitudes) pair")
    pairs = []
    for i, pair in enumerate(tones):
        where = "" if len(tones) == 1 else f"tones[{i}]: "
        if len(pair) != 2:
            raise ValueError(f"{where}each entry of tones must be (frequencies, amplitudes)")
        w = as_vector(f"{where}frequencies", pair[0])
        a = as_vector(f"{where}amplitudes", pair[1], w.size)
        if np.any(w <= 0) or np.unique(w).size != w.size:
            raise ValueError(f"{where}frequencies must be distinct and > 0 rad/s")
        pairs.append((w, a))
    check_hurwitz("sys", sys.A, "a steady state")
    g2 = np.sum(np.abs(freqresp(sys, np.concatenate([w for w, _ in pairs]))[:, :, 0]) ** 2, axis=1)
    ends = np.cumsum([w.size for w, _ in pairs])[:-1]
    return np.array([np.sqrt(np.sum(a**2 * g) / np.sum(a**2))
                     for (_, a), g in zip(pairs, np.split(g2, ends), strict=True)])
