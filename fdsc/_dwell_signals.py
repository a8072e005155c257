"""The switching-signal side of :mod:`fdsc.dwell`: the periodic-switching margin, exact runs of
given switching signals (d = 0), random signals with a minimum dwell, and the check of a bound
on them. Internal: the public names are ``fdsc.dwell.periodic_dwell_margin`` and so on, which is
where their ``__module__`` points.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.linalg import expm

from ._dwell_bound import DwellTimeBound
from ._dwell_lmi import _decay_eigs, _mode_matrices
from ._validation import (
    as_count,
    as_nonnegative,
    as_positive,
    as_vector,
    check_type,
    frozen_array,
)

__all__ = []

#: Most switches :func:`random_dwell_signal` draws: it refuses a ``horizon / min_dwell`` above
#: this (the signal's lists grow by one entry per switch).
MAX_SWITCHES = 10**7
#: Relative tolerance of :func:`check_dwell_bound`'s comparison of the modes it is given with the
#: certificate's (the same matrices, up to the rounding of recomputing a closed loop).
MODES_RTOL = 1e-9


@dataclass(frozen=True)
class PeriodicDwellMargin:
    """Spectral radii of periodic switching 1 → 2 → … → I → 1 against the dwell time.

    Parameters
    ----------
    taus : (k,) ndarray
        Dwell times τ in s (positive, increasing).
    rho : (k,) ndarray
        Spectral radius of e^{A_I τ} ⋯ e^{A_1 τ} (every dwell = τ).
    growth : (k,) ndarray
        ln(rho) / (I τ) in 1/s: the exponential rate of the periodic solution (> 0: unstable).
    rho_worst : (k,) ndarray
        Two modes: the largest spectral radius of e^{A_2 τ_2} e^{A_1 τ_1} over the pairs
        (τ_1, τ_2) of ``taus`` with both ≥ τ; NaN for more than two modes.
    growth_worst : (k,) ndarray
        Two modes: the largest ln(ρ) / (τ_1 + τ_2) over the same pairs; NaN otherwise.
    n_modes : int
        Number of modes I.
    """

    taus: np.ndarray
    rho: np.ndarray
    growth: np.ndarray
    rho_worst: np.ndarray
    growth_worst: np.ndarray
    n_modes: int

    def __post_init__(self):
        for name in ("taus", "rho", "growth", "rho_worst", "growth_worst"):
            object.__setattr__(self, name, frozen_array(np.asarray(getattr(self, name), dtype=float)))

    @property
    def lower_bound(self) -> float:
        """The longest dwell τ of ``taus`` at which some periodic switching diverges (ρ > 1).

        Every valid dwell-time bound exceeds it; 0.0 if no periodic switching on the grid
        diverges.

        Returns
        -------
        float
        """
        worst = self.rho if self.n_modes > 2 else self.rho_worst
        bad = np.flatnonzero(worst > 1.0)
        return float(self.taus[bad[-1]]) if bad.size else 0.0


def _spectral_radius(M):
    return np.abs(np.linalg.eigvals(M)).max(axis=-1)


#: Largest ‖A_i‖₁ τ accepted: the logarithm of ‖e^{A_i τ}‖ (at most this) and the 2^k of the
#: squaring in :func:`_log_expm` stay floats.
MAX_NORM_TAU = 2.0**1000


_SPAN = "a mode's exponential, even normalized, spans more than the float range (its entries' ratio)"


def _unrepresentable(tau, why):
    return ValueError(f"taus must be short enough for e^(A_i tau) to be represented, but at tau = "
                      f"{tau:g} s {why}; shorten the largest dwell")


def _check_taus(A, taus):
    """Refuse a τ for which ``‖A_i‖₁ τ`` or ``I τ`` leaves what :func:`_log_expm` can carry."""
    for a in A:
        norm = float(np.abs(a).sum(axis=0).max())
        for tau in taus.tolist():         # Python floats: an overflow is inf, not a warning
            if not (norm * tau <= MAX_NORM_TAU and math.isfinite(len(A) * tau)):
                raise _unrepresentable(tau, f"‖A_i‖₁ tau = {norm * tau:.3g} exceeds {MAX_NORM_TAU:.3g}, "
                                            "beyond what floats carry even as a logarithm")


def _log_expm(a, tau):
    """``(F, g)`` with ``e^{aτ} = e^g F`` and ‖F‖ = 1 (Frobenius): e^{aτ/2^k} with
    ‖a‖₁τ/2^k ≤ 1, squared k times with the norm moved into g at each squaring."""
    norm = float(np.abs(a).sum(axis=0).max()) * tau
    k = max(0, math.ceil(math.log2(norm))) if norm > 1 else 0
    F, g = expm(a * (tau / 2.0**k)), 0.0
    for _ in range(k + 1):
        s = float(np.linalg.norm(F))
        if not (s > 0 and math.isfinite(s)):
            raise _unrepresentable(tau, _SPAN)
        F, g = F / s, g + math.log(s)
        if _ < k:
            F, g = F @ F, 2.0 * g
    return F, g


def _log_radii(A, E, logs):
    """``(log ρ, log R)``: of the products of equal dwells, and (two modes) of every pair."""
    M = E[0]
    for e in E[1:]:
        M = e @ M
    log_rho = np.log(_spectral_radius(M)) + sum(logs)
    if len(A) != 2:
        return log_rho, None
    R = _spectral_radius(np.einsum("bij,ajk->abik", E[1], E[0]))      # R[a, b]: τ_1 = τ_a, τ_2 = τ_b
    return log_rho, np.log(R) + logs[0][:, None] + logs[1][None, :]


def _finite(log_rho, log_R):
    return bool(np.all(np.isfinite(log_rho)) and (log_R is None or np.all(np.isfinite(log_R))))


def _suffix_max(R):
    """S[a, b] = max of R[a:, b:]."""
    S = np.maximum.accumulate(np.maximum.accumulate(R[::-1, ::-1], axis=0), axis=1)
    return S[::-1, ::-1]


def periodic_dwell_margin(modes, taus) -> PeriodicDwellMargin:
    """Spectral radius of the periodic switching 1 → 2 → … → I → 1 with dwell τ, over a grid of τ.

    Parameters
    ----------
    modes : list of (n, n) array_like or LTISystem
        The modes' state matrices A_i (I ≥ 2, Hurwitz).
    taus : (k,) array_like
        Dwell times in s, positive and strictly increasing. For two modes the unequal pairs
        (τ_1, τ_2) are taken from this grid (k² products).

    Returns
    -------
    PeriodicDwellMargin

    Raises
    ------
    TypeError
        If ``modes`` is not a list or tuple.
    ValueError
        If fewer than two modes are given, they differ in size, or ``taus`` is not positive and
        strictly increasing, or a τ is so long that e^{A_i τ}, even divided by its norm, cannot be
        represented in floats (its entries' ratio spans more than the float range, or ‖A_i‖ τ
        itself overflows). A τ whose e^{A_i τ} merely underflows is kept: its ρ may round to 0,
        its growth rate stays exact.
    DimensionError
        If a mode is not square or ``taus`` is not 1-D.
    UnstableError
        If a mode is not Hurwitz.

    Notes
    -----
    With d = 0 the state after one period is Φ x with Φ = e^{A_I τ_I} ⋯ e^{A_1 τ_1}; if
    ρ(Φ) > 1 the periodic switching diverges, so any dwell-time bound valid for all switching
    signals must exceed min_i τ_i. This measures how conservative τ* of
    :func:`dwell_time_bound` is.

    Examples
    --------
    Two modes whose average [[-1, 2], [2, -1]] is unstable: fast periodic switching diverges.

    >>> A1 = [[-1.0, 4.0], [0.0, -1.0]]
    >>> A2 = [[-1.0, 0.0], [4.0, -1.0]]
    >>> m = periodic_dwell_margin([A1, A2], [0.01, 0.1, 1.0, 5.0])
    >>> bool(m.rho[0] > 1), bool(m.rho[-1] < 1), m.lower_bound >= 0.1
    (True, True, True)
    """
    A = _mode_matrices(modes)
    taus = as_vector("taus", taus)
    if taus.size == 0 or taus[0] <= 0 or np.any(np.diff(taus) <= 0):
        raise ValueError(f"taus must be positive and strictly increasing, but found {taus}")
    _check_taus(A, taus)
    with np.errstate(all="ignore"):
        try:
            # one call per matrix: scipy's batched expm is slow for the large ‖Aτ‖ of stiff modes
            E = [np.array([expm(a * tau) for tau in taus]) for a in A]
            logs = [np.zeros(taus.size) for _ in A]
            clean = all(np.all(np.isfinite(e)) for e in E) and _finite(*_log_radii(A, E, logs))
        except (ValueError, np.linalg.LinAlgError, OverflowError):
            clean = False
        if not clean:
            # a τ so long that e^{Aτ} leaves the float range: each factor as a normalized matrix
            # times e^{log}, by squaring (so ρ and its growth rate come out in log space)
            pairs = [[_log_expm(a, tau) for tau in taus] for a in A]
            E = [np.array([f for f, _ in p]) for p in pairs]
            logs = [np.array([g for _, g in p]) for p in pairs]
        log_rho, log_R = _log_radii(A, E, logs)
        if not _finite(log_rho, log_R):
            # e^{A_i τ} is invertible, so a product of them has ρ > 0: a product of the
            # normalized factors that is singular has lost entries below the float range
            bad = ~np.isfinite(log_rho)
            if log_R is not None:
                bad |= ~np.all(np.isfinite(log_R), axis=0) | ~np.all(np.isfinite(log_R), axis=1)
            raise _unrepresentable(float(taus[bad].max()), _SPAN)
        rho = np.exp(log_rho)
    growth = log_rho / (len(A) * taus)
    if len(A) == 2:
        with np.errstate(all="ignore"):
            R = np.exp(log_R)
        G = log_R / (taus[:, None] + taus[None, :])
        rho_worst = np.diagonal(_suffix_max(R)).copy()
        growth_worst = np.diagonal(_suffix_max(G)).copy()
    else:
        rho_worst = growth_worst = np.full(taus.shape, np.nan)
    return PeriodicDwellMargin(taus, rho, growth, rho_worst, growth_worst, len(A))


def _signal(switch_times, sequence, n_modes):
    st = as_vector("switch_times", switch_times) if np.size(switch_times) else np.zeros(0)
    if st.size and (st[0] <= 0 or np.any(np.diff(st) <= 0)):
        raise ValueError(f"switch_times must be positive and strictly increasing, but found {st}")
    seq = np.asarray(sequence)
    if seq.ndim != 1 or seq.size != st.size + 1 or seq.dtype.kind not in "iu":
        raise ValueError(f"sequence must be a 1-D integer array with one mode per interval "
                         f"({st.size + 1}), but found {seq!r}")
    if seq.min() < 0 or seq.max() >= n_modes:
        raise ValueError(f"sequence must hold mode indices in [0, {n_modes}), but found {seq}")
    if np.any(seq[1:] == seq[:-1]):
        raise ValueError("sequence must change mode at every switch (consecutive entries differ)")
    return st, seq


def switched_states(modes, x0, switch_times, sequence, t) -> np.ndarray:
    """Exact states of ẋ = A_σ(t) x (d = 0) along a given switching signal.

    Parameters
    ----------
    modes : list of (n, n) array_like or LTISystem
        The modes' state matrices A_i (I ≥ 2, Hurwitz).
    x0 : (n,) array_like
        Initial state.
    switch_times : (m,) array_like
        Switching instants t_1 < … < t_m in s (> 0); may be empty.
    sequence : (m + 1,) int array_like
        Active mode on [0, t_1), [t_1, t_2), …, [t_m, ∞); consecutive entries differ.
    t : (k,) array_like
        Sample times in s (≥ 0).

    Returns
    -------
    (k, n) ndarray
        x(t) at the samples (e^{A_i (t − t_l)} x(t_l) on each interval: exact up to rounding).

    Raises
    ------
    ValueError
        If the signal is malformed, or a sample time is negative.
    DimensionError
        If ``x0`` does not have n entries.

    Examples
    --------
    >>> x = switched_states([[[-1.0]], [[-2.0]]], [1.0], [1.0], [0, 1], [0.0, 1.0, 2.0])
    >>> np.allclose(x[:, 0], [1.0, np.exp(-1), np.exp(-3)])
    True
    """
    A = _mode_matrices(modes)
    x0 = as_vector("x0", x0, A[0].shape[0])
    st, seq = _signal(switch_times, sequence, len(A))
    t = as_vector("t", t)
    if t.size and t.min() < 0:
        raise ValueError(f"t must be >= 0, but found {t.min()}")
    cache = {}

    def transition(i, h):
        # one matrix exponential per (mode, step); a uniform sample grid has few distinct steps
        if (i, h) not in cache:
            cache[i, h] = expm(A[i] * h)
        return cache[i, h]

    starts = np.concatenate([[0.0], st])
    xb = [x0]
    for m in range(st.size):
        xb.append(transition(seq[m], starts[m + 1] - starts[m]) @ xb[-1])
    idx = np.searchsorted(st, t, side="right")
    x = np.empty((t.size, x0.size))
    m, tc, xc = -1, 0.0, x0
    for q in np.argsort(t, kind="stable"):
        if idx[q] != m:
            m, tc, xc = idx[q], starts[idx[q]], xb[idx[q]]
        xc = transition(seq[m], t[q] - tc) @ xc
        tc = t[q]
        x[q] = xc
    return x


def random_dwell_signal(rng: np.random.Generator, n_modes: int, min_dwell: float, horizon: float,
                        *, max_dwell: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """A random switching signal on [0, horizon] whose dwells all lie in [min_dwell, max_dwell].

    Draws the initial mode, then alternately a dwell (uniform) and the next mode (uniform among
    the others). The first switch is at least ``min_dwell`` after 0.

    Parameters
    ----------
    rng : numpy.random.Generator
        Source of randomness.
    n_modes : int
        Number of modes (≥ 2).
    min_dwell : float
        Shortest dwell in s (> 0).
    horizon : float
        Length of the signal in s (> 0).
    max_dwell : float, optional
        Longest dwell in s (≥ ``min_dwell``); default 2 ``min_dwell``.

    Returns
    -------
    switch_times : (m,) ndarray
        Switching instants in (0, horizon).
    sequence : (m + 1,) int ndarray
        Active mode on each interval.

    Raises
    ------
    TypeError
        If ``rng`` is not a ``numpy.random.Generator``.
    ValueError
        If an argument is out of range, or ``horizon / min_dwell`` exceeds
        :data:`MAX_SWITCHES` (the signal could switch that often; the message names
        ``min_dwell``).

    Examples
    --------
    >>> st, seq = random_dwell_signal(np.random.default_rng(0), 2, 1.0, 10.0)
    >>> bool(np.all(np.diff(np.concatenate([[0.0], st])) >= 1.0)), seq.size == st.size + 1
    (True, True)
    """
    check_type("rng", rng, np.random.Generator, "a numpy.random.Generator")
    n_modes = as_count("n_modes", n_modes, 2)
    min_dwell = as_positive("min_dwell", min_dwell)
    horizon = as_positive("horizon", horizon)
    max_dwell = 2 * min_dwell if max_dwell is None else as_positive("max_dwell", max_dwell)
    if max_dwell < min_dwell:
        raise ValueError(f"max_dwell must be >= min_dwell = {min_dwell:g}, but found {max_dwell:g}")
    if horizon / min_dwell > MAX_SWITCHES:
        raise ValueError(f"min_dwell ({min_dwell:g} s) allows up to horizon / min_dwell = "
                         f"{horizon / min_dwell:.3g} switches in the horizon ({horizon:g} s), more "
                         f"than MAX_SWITCHES = {MAX_SWITCHES:.0e}; enlarge min_dwell or shorten the "
                         "horizon")
    seq = [int(rng.integers(n_modes))]
    times = []
    t = float(rng.uniform(min_dwell, max_dwell))
    # every step advances t by at least min_dwell ≥ horizon / MAX_SWITCHES (far above the
    # rounding of t < horizon): at most MAX_SWITCHES iterations
    while t < horizon:
        times.append(t)
        seq.append(int((seq[-1] + rng.integers(1, n_modes)) % n_modes))
        t += float(rng.uniform(min_dwell, max_dwell))
    return np.array(times), np.array(seq, dtype=int)


@dataclass(frozen=True)
class DwellCheck:
    """The bound V(t) ≤ μ^{N(t)} e^{−2λt} V(0) checked along one switching signal (d = 0).

    Parameters
    ----------
    max_ratio : float
        max over the samples t > 0 of V(t) / (μ^{N(t)} e^{−2λt} V(0)); ≤ 1 by the certificate
        (1.0 if there is no sample after 0).
    final_v_ratio : float
        V(T)/V(0) at the last sample.
    final_norm_ratio : float
        ‖x(T)‖/‖x(0)‖.
    rate_bound : float
        The guaranteed rate 2λ − ln μ/τ_d with τ_d the signal's shortest dwell (the first from
        t = 0 included); V(T)/V(0) ≤ e^{−rate_bound·T}.
    n_switches : int
        Number of switches.
    min_dwell : float
        Shortest dwell of the signal in s (the horizon if it never switches).
    horizon : float
        Last sample time T in s.
    """

    max_ratio: float
    final_v_ratio: float
    final_norm_ratio: float
    rate_bound: float
    n_switches: int
    min_dwell: float
    horizon: float

    def holds(self, rtol: float = 1e-9) -> bool:
        """Whether the envelope and the decay bound hold up to the relative tolerance ``rtol``.

        Parameters
        ----------
        rtol : float, optional
            Relative slack for rounding (≥ 0).

        Returns
        -------
        bool
        """
        rtol = as_nonnegative("rtol", rtol)
        decay_ok = self.final_v_ratio <= np.exp(-self.rate_bound * self.horizon) * (1 + rtol)
        return bool(self.max_ratio <= 1 + rtol and decay_ok)


def _check_modes(bound, A):
    """Raise ValueError naming ``modes`` unless ``A`` are the certificate's modes (or, for a
    certificate that does not hold them, unless its P_i satisfy the decay inequality for ``A``)."""
    if bound.A is not None:
        for k, (a, ref) in enumerate(zip(A, bound.A, strict=True)):
            scale = float(np.abs(ref).max())
            if not np.allclose(a, ref, rtol=MODES_RTOL, atol=MODES_RTOL * scale):
                raise ValueError(f"modes must be the modes of the certificate, but modes[{k}] "
                                 f"differs from its A_{k} by up to {float(np.abs(a - ref).max()):.3g} "
                                 f"(its entries are up to {scale:.3g})")
        return
    eigs = _decay_eigs(A, bound.P, bound.decay)
    scale = np.array([np.linalg.norm(a, 2) * np.linalg.norm(p, 2) for a, p in zip(A, bound.P, strict=True)])
    bad = np.flatnonzero(eigs > MODES_RTOL * scale)
    if bad.size:
        k = int(bad[0])
        raise ValueError(f"modes must be modes the certificate holds for, but modes[{k}] violates "
                         f"A'P + PA <= -2*decay*P with its P_{k} (largest eigenvalue "
                         f"{eigs[k]:.3g} > 0)")


def check_dwell_bound(bound: DwellTimeBound, modes, x0, switch_times, sequence, t) -> DwellCheck:
    """Check the Lyapunov envelope of a dwell-time certificate along a switching signal (d = 0).

    Parameters
    ----------
    bound : DwellTimeBound
        The certificate (its P_i, λ and μ).
    modes : list of (n, n) array_like or LTISystem
        The modes the certificate was computed for: their A_i must equal the certificate's
        (to a relative :data:`MODES_RTOL`); for a certificate without them (``bound.A`` None)
        its P_i must satisfy the decay inequality A_iᵀP_i + P_iA_i ⪯ −2λP_i for these modes.
    x0 : (n,) array_like
        Initial state (nonzero).
    switch_times, sequence : array_like
        The switching signal (see :func:`switched_states`).
    t : (k,) array_like
        Sample times in s, starting at 0; the switching instants are added to them.

    Returns
    -------
    DwellCheck

    Raises
    ------
    TypeError
        If ``bound`` is not a :class:`DwellTimeBound`.
    ValueError
        If the modes do not match the certificate (their number, size or matrices; the message
        names ``modes``), ``x0`` is zero, ``t`` does not start at 0, or the signal is malformed.

    Notes
    -----
    The envelope V(t) ≤ μ^{N(t)} e^{−2λt} V(0) holds for *every* switching signal; the dwell
    time is what makes it decay (see :func:`dwell_time_bound`).

    Examples
    --------
    >>> A = [[[-1.0, 2.0], [-2.0, -1.0]], [[-2.0, 0.0], [0.0, -3.0]]]
    >>> b = dwell_time_bound(A, decay=0.5)
    >>> c = check_dwell_bound(b, A, [1.0, 0.0], [1.0, 2.0], [0, 1, 0], np.linspace(0, 3, 31))
    >>> c.holds(), c.n_switches
    (True, 2)
    """
    check_type("bound", bound, DwellTimeBound, "an fdsc.dwell.DwellTimeBound")
    A = _mode_matrices(modes)
    if len(A) != len(bound.P) or A[0].shape != bound.P[0].shape:
        raise ValueError(f"modes must be the {len(bound.P)} modes of the certificate, but found "
                         f"{len(A)} of size {A[0].shape}")
    _check_modes(bound, A)
    x0 = as_vector("x0", x0, A[0].shape[0])
    if not np.any(x0):
        raise ValueError("x0 must be nonzero")
    st, seq = _signal(switch_times, sequence, len(A))
    t = as_vector("t", t)
    if t.size == 0 or t.min() != 0:
        raise ValueError(f"t must start at 0, but found {t.min() if t.size else 'no samples'}")
    t = np.union1d(t, st)
    x = switched_states(A, x0, st, seq, t)
    idx = np.searchsorted(st, t, side="right")
    P = np.array(bound.P)[seq[idx]]
    V = np.einsum("ki,kij,kj->k", x, P, x)
    with np.errstate(divide="ignore"):
        log_ratio = np.log(V) - np.log(V[0]) - idx * np.log(bound.mu) + 2 * bound.decay * t
    min_dwell = float(np.diff(np.concatenate([[0.0], st])).min()) if st.size else float(t[-1])
    rate = 2 * bound.decay - np.log(bound.mu) / min_dwell if min_dwell > 0 else -np.inf
    later = log_ratio[t > 0]
    return DwellCheck(float(np.exp(later.max())) if later.size else 1.0, float(V[-1] / V[0]),
                      float(np.linalg.norm(x[-1]) / np.linalg.norm(x[0])), float(rate),
                      int(st.size), min_dwell, float(t[-1]))


for _obj in (PeriodicDwellMargin, periodic_dwell_margin, switched_states, random_dwell_signal,
             DwellCheck, check_dwell_bound):
    _obj.__module__ = "fdsc.dwell"
