"""Streaming, batch simulation of LTI and switched loops: one compiled loop per run, O(1) memory.

:func:`fdsc.simulate.simulate` keeps every sample of a run and computes the particular
solutions of all steps in NumPy before its loop. This module does the same exact step without
any per-step array: the disturbance is generated inside the loop and everything a study needs is
reduced while the run goes.

**The step.** On a segment where the disturbance is ``d(t) = Σ a_j sin(ω_j t + φ_j)`` (a
:class:`~fdsc.signals.Sinusoids`, or one part of a :class:`~fdsc.signals.Piecewise`), write
``d = Σ a_j Im p_j`` with the phasors ``p_j(t) = e^{j(ω_j t + φ_j)}``: the plant and the tones'
oscillators form one autonomous linear system, and its exact discretization gives the step of
mode i from ``t_k`` to ``t_{k+1}``

    x_{k+1} = Φ_i x_k + Σ_j Im(H_ij p_j(t_k)),   Φ_i = e^{A_i Δt},
    H_ij = a_j ∫₀^Δt e^{A_i(Δt−s)} B e^{jω_j s} ds,

``H_i`` being the top-right block of ``expm([[A_i, B aᵀ], [0, diag(jω)]] Δt)`` (Van Loan). A
step costs ``n² + 2nT`` multiplications for T tones and needs no particular solution (a tone at a
pole of a mode is still refused, as by :func:`~fdsc.simulate.simulate`).
The phasors are rotated, not recomputed: within blocks of
:data:`PHASOR_BLOCK` steps, ``e^{j(ω t_k + φ)} = e^{j(ω t_b + φ)} · e^{jω (k − b) Δt}`` with the
block's first phasor computed by cos and sin and the rotations taken from a table, so each phasor
is a product of two correctly rounded numbers and no rounding error accumulates over the run.
Against a closed form and ``solve_ivp`` at rtol 1e-12 the states agree to a few 1e-14 (scalar
loop) and 4e-13 (the paper's switched loop, bounded by ``solve_ivp``'s own error); against
:func:`~fdsc.simulate.simulate` (particular solutions per step) to about 1e-13 relative (see the
tests and ``benchmarks/bench_simulate.py``). The switching law's score
``vᵀ W_i v`` with ``v = [ẋ; x]`` (or ``[ẍ; ẋ; x]``) is linear in ``ξ = [x; d]`` (or
``[x; d; ḋ]``), so it is evaluated as ``ξᵀ M ξ`` with M precomputed per (mode whose derivative
is measured, candidate): ``(n + 1)(n + 2)/2`` products instead of ``(2n)(2n + 1)/2``.
A :class:`~fdsc.signals.Sampled` input is integrated
exactly for its hold: ``x_{k+1} = Φ x_k + Γ₀ u_k`` (zero-order) or ``+ Γ₁ (u_{k+1} − u_k)``
(first-order), with ``Φ, Γ₀, Γ₁`` from one matrix exponential (Van Loan's block form).

**Reductions** (all in the loop): ``∫ zᵀz`` and ``∫ d²`` over the run by the composite
Simpson rule that :func:`scipy.integrate.simpson` applies to the same samples (Neumaier-
compensated sums, so 1e9 steps lose no digits); the same two integrals at every point of a
coarse grid (for the running L2-induced ratio and window energies); the switch count; the
histogram of dwell times; the number of steps spent in each mode; and, only if asked for,
traces decimated to min/max per bin (plus the share of each mode per bin), which represent a
fast oscillation faithfully at any plot resolution. A run that keeps no traces needs memory
independent of its length.

**LTI runs in closed form.** A run of one mode under a Sinusoids or Piecewise disturbance, with
no traces, has samples in closed form (a transient plus a steady state per piece), and so have
its Simpson sums: :mod:`fdsc._closed_form` computes them, the coarse grid included, in a time
independent of the horizon, wherever that keeps the loop's accuracy (else the loop runs; see
:func:`simulate_stream`, Notes).

**Batch.** :func:`simulate_batch` runs many :class:`Case` s (mode sets, disturbances, laws,
horizons and steps may all differ) in one call, parallel over cases on
``numba.get_num_threads()`` threads: each case is one call of the compiled loop, which releases
the GIL, from a pool of Python threads, the longest cases first; the results come back as arrays
(:class:`BatchResult`). The compiled loop is specialized to the batch's sizes when the batch is
long enough to repay a compilation (:data:`UNROLL_MIN_STEPS`), with the same results bit for bit.
"""

import functools
import math
import warnings
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field

import numba
import numpy as np
from numba import njit
from numpy.typing import ArrayLike
from scipy.linalg import expm

from . import _closed_form
from ._validation import as_choice, as_count, as_positive, as_vector, check_type
from .exceptions import UnstableError, UnstableRunWarning
from .frequency import check_no_pole_at
from .rules import PRINTED, SwitchRule, decide, rule_state, window_scores
from .signals import Piecewise, Sampled, Sinusoids
from .simulate import LAWS, _as_modes, _law_weights, _shared_input

__all__ = ["Case", "Trace", "StreamResult", "BatchResult", "simulate_stream", "simulate_batch",
           "PHASOR_BLOCK", "STREAM_KERNELS", "UNROLL_MAX", "UNROLL_MIN_STEPS"]

#: Steps per block of phasor rotations (the first phasor of a block is computed by cos and sin).
PHASOR_BLOCK = 512
#: The compiled kernel, or the same loop run by the Python interpreter (for tests; slow).
STREAM_KERNELS = ("numba", "python")

_KIND_SINES, _KIND_ZOH, _KIND_FOH = 0, 1, 2
#: Points per block of plain summation; blocks are added with Neumaier's compensation.
_SUM_BLOCK = 1024
_LAW_CODE = {"previous": 0, "candidate": 1}


# ---------------------------------------------------------------------------------------------
# the compiled loop
# ---------------------------------------------------------------------------------------------

def _case_loop(N, dt, nm, Phi, C, D, Mt, law, sigma0, x0,
               kind, seg_start, seg_nt, omega, amp, phase, Gr, Gi, Rre, Rim,
               u, G0, G1, cum_every, trace_every, dwell_edges, rparams, ring, ring_sum, istate,
               sums, share_steps, dwell_counts, cum, tr_lo, tr_hi, tr_share, x_out, info, shape):
    """One run; see the module docstring. Writes every result into the output arguments.

    ``sums`` = [∫zᵀz, ∫d², switches]; ``info`` = [diverged point or −1, final mode]. Points
    are k = 0 … N−1; step k goes from point k to point k+1 and uses
    the mode chosen at point k and the disturbance segment that contains point k.

    ``shape`` specializes the compiled loop (see :func:`_shape_tag`): seven tuples whose
    lengths, constants of the compiled code, are n, p, the number of modes, the length of a
    row of ``Mt``, the number of tones T (every segment padded to T: padded tones have zero
    amplitude, gains and rotations and add exact zeros), 1 if the disturbance is a sum of
    sinusoids and 1 if no traces are kept; an empty tuple leaves that quantity to the arrays
    and arguments. The loops then have fixed trip counts, about twice as fast for the paper's
    loop, and give the same numbers."""
    # sizes: constants of the compiled code where ``shape`` gives them, else from the arrays
    n = len(shape[0]) if len(shape[0]) > 0 else x0.shape[0]
    p = len(shape[1]) if len(shape[1]) > 0 else C.shape[1]
    if len(shape[2]) > 0:
        nm = len(shape[2])
    nt2 = len(shape[3]) if len(shape[3]) > 0 else Mt.shape[2]
    TT = len(shape[4])      # > 0: every segment's tone loops run over all T tones
    T = TT if TT > 0 else omega.shape[1]
    if len(shape[5]) > 0:
        kind = 0
    if len(shape[6]) > 0:
        trace_every = 0
    K = Rre.shape[1]
    # ξ = [x; d] (first-order law) or [x; d; ḋ] (second-order law): nt2 = r (r + 1) / 2
    r_xi = n + 1 if nt2 == (n + 1) * (n + 2) // 2 else n + 2
    prod = np.empty(nt2)
    xi = np.zeros(r_xi)
    sc = np.empty(Mt.shape[1])
    eff = np.empty(Mt.shape[1])
    margin = rparams[0]
    relative = rparams[1] > 0
    dwell_steps = int(rparams[2])
    win = int(rparams[3])
    plain = margin == 0.0 and dwell_steps == 0
    last_switch = 0
    x = x0.copy()
    xn = np.empty(n)
    bre = np.empty(T)       # phasor at the first point kb of the current block
    bim = np.empty(T)
    pre = np.empty(T)       # phasor at the current point
    pim = np.empty(T)
    s = 0
    kb = 0
    if kind == 0:
        for j in range(TT if TT > 0 else seg_nt[0]):
            th = omega[0, j] * (0.0 * dt) + phase[0, j]
            bre[j] = math.cos(th)
            bim[j] = math.sin(th)
            pre[j] = bre[j]
            pim[j] = bim[j]
    prev = sigma0
    switches = 0
    dwell_start = 0
    share_start = 0     # first point of the current mode (steps per mode: counted at switches)
    k_done = 0
    cum_next = 0 if cum_every > 0 else -1
    n_edges = dwell_edges.shape[0]
    # Simpson sums (weights 1, 4, 2, 4, …) with Neumaier compensation, and the last two samples
    sz = 0.0
    cz = 0.0
    sd = 0.0
    cd = 0.0
    fz1 = 0.0       # f at the last three points (1 = latest)
    fz2 = 0.0
    fz3 = 0.0
    fd1 = 0.0
    fd2 = 0.0
    fd3 = 0.0
    sz_half = 0.0   # the Simpson sum over points < N − 2 (for an even number of points)
    sd_half = 0.0
    bz = 0.0        # the current block's plain sums
    bd = 0.0
    kblock = 0
    wgt = 1.0
    diverged = -1
    for k in range(N):
        k_done = k
        if kind == 0 and k == seg_start[s + 1]:
            s += 1
            kb = k
            for j in range(TT if TT > 0 else seg_nt[s]):
                th = omega[s, j] * (k * dt) + phase[s, j]
                bre[j] = math.cos(th)
                bim[j] = math.sin(th)
                pre[j] = bre[j]
                pim[j] = bim[j]
        if kind == 0:
            nt = TT if TT > 0 else seg_nt[s]
            dk = 0.0
            for j in range(nt):
                dk += amp[s, j] * pim[j]
        else:
            nt = 0
            dk = u[k]
        # the switching law at point k: score_i = ξᵀ M ξ with ξ = [x; d] or [x; d; ḋ]
        if nm > 1:
            for c in range(n):
                xi[c] = x[c]
            xi[n] = dk
            if r_xi > n + 1:
                # ḋ at point k, for the measured ẍ = A_σ ẋ + B ḋ of a second-order law
                ddk = 0.0
                if kind == 0:
                    for j in range(nt):
                        ddk += amp[s, j] * omega[s, j] * pre[j]
                elif kind == 2:
                    ddk = (u[k + 1] - u[k]) / dt if k + 1 < N else (u[k] - u[k - 1]) / dt
                xi[n + 1] = ddk
            idx = 0
            for a in range(r_xi):
                xa = xi[a]
                for b_ in range(a, r_xi):
                    prod[idx] = xa * xi[b_]
                    idx += 1
            if law == 0:
                # the measured derivatives are those of the active mode, for every candidate
                for i in range(nm):
                    acc = 0.0
                    for q_ in range(nt2):
                        acc += Mt[prev, i, q_] * prod[q_]
                    sc[i] = acc
            else:
                for i in range(nm):
                    acc = 0.0
                    for q_ in range(nt2):
                        acc += Mt[i, i, q_] * prod[q_]
                    sc[i] = acc
            # the rule (fdsc.rules): window means, argmax of the case's own nm modes (padded
            # modes of a batch are never chosen), dwell time and hysteresis
            if win > 1:
                window_scores(sc, nm, win, ring, ring_sum, istate, eff)
                for i in range(nm):
                    sc[i] = eff[i]
            best = -np.inf
            choice = prev
            for i in range(nm):
                if sc[i] > best:
                    best = sc[i]
                    choice = i
            if not plain:
                choice = decide(choice, prev, sc[choice], sc[prev], k, last_switch, margin,
                                relative, dwell_steps)
                if choice != prev:
                    last_switch = k
            if choice != prev:
                if k > 0:
                    switches += 1
                    length = k - dwell_start
                    for e in range(n_edges - 1):
                        if dwell_edges[e] <= length < dwell_edges[e + 1]:
                            dwell_counts[e] += 1
                            break
                dwell_start = k
                share_steps[prev] += k - share_start
                share_start = k
            prev = choice
        m = prev
        # output and integrands at point k
        fz = 0.0
        if trace_every > 0:
            b = k // trace_every
            first = k % trace_every == 0
            tr_share[b, m] += 1.0
        for r in range(p):
            zr = D[r] * dk
            for c in range(n):
                zr += C[m, r, c] * x[c]
            fz += zr * zr
            if trace_every > 0:
                if first or zr < tr_lo[b, n + r]:
                    tr_lo[b, n + r] = zr
                if first or zr > tr_hi[b, n + r]:
                    tr_hi[b, n + r] = zr
        if not fz < np.inf:
            diverged = k
            break
        fd = dk * dk
        if trace_every > 0:
            for r in range(n):
                if first or x[r] < tr_lo[b, r]:
                    tr_lo[b, r] = x[r]
                if first or x[r] > tr_hi[b, r]:
                    tr_hi[b, r] = x[r]
            if first or dk < tr_lo[b, n + p]:
                tr_lo[b, n + p] = dk
            if first or dk > tr_hi[b, n + p]:
                tr_hi[b, n + p] = dk
        if k == cum_next:
            cum_next += cum_every
            row_ = k // cum_every
            if k == 0:
                cum[row_, 0] = 0.0
                cum[row_, 1] = 0.0
            else:
                cum[row_, 0] = dt / 3.0 * (((sz + bz) + cz) + fz)
                cum[row_, 1] = dt / 3.0 * (((sd + bd) + cd) + fd)
        if k == N - 2:
            sz_half = (sz + bz) + cz
            sd_half = (sd + bd) + cd
        # weights 1, 4, 2, 4, …: plain sums within blocks, Neumaier-compensated between them
        bz += wgt * fz
        bd += wgt * fd
        wgt = 2.0 if wgt == 4.0 else 4.0
        if k - kblock == _SUM_BLOCK - 1:
            kblock = k + 1
            t_ = sz + bz
            if abs(sz) >= abs(bz):
                cz += (sz - t_) + bz
            else:
                cz += (bz - t_) + sz
            sz = t_
            t_ = sd + bd
            if abs(sd) >= abs(bd):
                cd += (sd - t_) + bd
            else:
                cd += (bd - t_) + sd
            sd = t_
            bz = 0.0
            bd = 0.0
        fz3 = fz2
        fz2 = fz1
        fz1 = fz
        fd3 = fd2
        fd2 = fd1
        fd1 = fd
        if k == N - 1:
            break
        # the exact step k → k + 1 in mode m: x_{k+1} = Φ x_k + Γ p_k (augmented system)
        if kind == 0:
            for r in range(n):
                acc = 0.0
                for c in range(n):
                    acc += Phi[m, r, c] * x[c]
                for j in range(nt):
                    acc += Gr[s, m, r, j] * pre[j] + Gi[s, m, r, j] * pim[j]
                xn[r] = acc
            if nt > 0:
                # phasors at t_{k+1}: the block's first phasor times a rotation from the table
                jj = k + 1 - kb
                if jj >= K:
                    kb = k + 1
                    jj = 0
                    for j in range(nt):
                        th = omega[s, j] * ((k + 1) * dt) + phase[s, j]
                        bre[j] = math.cos(th)
                        bim[j] = math.sin(th)
                for j in range(nt):
                    rr = Rre[s, jj, j]
                    ri = Rim[s, jj, j]
                    pre[j] = bre[j] * rr - bim[j] * ri
                    pim[j] = bre[j] * ri + bim[j] * rr
        else:
            for r in range(n):
                acc = G0[m, r] * u[k]
                if kind == 2:
                    acc += G1[m, r] * (u[k + 1] - u[k])
                for c in range(n):
                    acc += Phi[m, r, c] * x[c]
                xn[r] = acc
        for r in range(n):
            x[r] = xn[r]
    # steps 0 … min(last point, N − 2) in the last mode
    share_steps[prev] += min(k_done, N - 2) + 1 - share_start
    # totals by scipy.integrate.simpson's rule for N equally spaced points
    if diverged >= 0:
        sums[0] = np.inf
        sums[1] = np.nan
    elif N == 2:
        sums[0] = dt * (fz2 + fz1) / 2.0
        sums[1] = dt * (fd2 + fd1) / 2.0
    elif N % 2 == 1:
        # (s + c) holds Σ w_k f_k with the last point weighted 2 (even k): correct it to 1
        sums[0] = dt / 3.0 * (((sz + bz) + cz) - fz1)
        sums[1] = dt / 3.0 * (((sd + bd) + cd) - fd1)
    else:
        # Simpson over the first N − 1 points, then the last interval from the last three
        sums[0] = dt / 3.0 * (sz_half + fz2) + dt * (5.0 * fz1 + 8.0 * fz2 - fz3) / 12.0
        sums[1] = dt / 3.0 * (sd_half + fd2) + dt * (5.0 * fd1 + 8.0 * fd2 - fd3) / 12.0
    sums[2] = switches
    for r in range(n):
        x_out[r] = x[r]
    info[0] = diverged
    info[1] = prev



# nogil: the cases of a batch run on Python threads (see _run), each in compiled code
_case_numba = njit(cache=True, nogil=True)(_case_loop)


# ---------------------------------------------------------------------------------------------
# cases and results
# ---------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class Case:
    """One run of a batch: a loop, a disturbance, a law and a grid.

    Parameters
    ----------
    modes : LTISystem or list of LTISystem
        Closed loop(s) ``(A_i, B, C_i, D)`` sharing B and D (python-control ``StateSpace`` or
        ``(A, B, C, D)`` tuples are accepted too).
    d : Sinusoids, Piecewise or Sampled
        Scalar disturbance. Breaks of a Piecewise must lie on the grid; a Sampled signal must
        have the step ``dt`` and cover the horizon (samples after it are not used).
    horizon : float
        End time in s; a multiple of ``dt``.
    dt : float
        Step in s (> 0).
    x0 : (n,) array_like, optional
        Initial state (default 0).
    law_bands : list of Band, optional
        Ω_i of the switching law (required for several modes).
    law_Q : list of (n, n) array_like, optional
        Q_i of the switching law (symmetric positive definite).
    law : {"previous", "candidate"}, optional
        How ẋ enters the law (:data:`fdsc.simulate.LAWS`).
    sigma0 : int, optional
        Mode assumed active before t = 0.
    rule : SwitchRule, optional
        Hysteresis, minimum dwell time and/or moving window (default the printed argmax).
    law_weights : list of array_like, optional
        Instead of ``law_bands`` and ``law_Q``: one symmetric W_i per mode on ``[ẋ; x]`` (2n) or
        ``[ẍ; ẋ; x]`` (3n); see :func:`fdsc.simulate.simulate`.
    label : object, optional
        Anything that identifies the case for the caller (kept, not used).
    """

    modes: object
    d: object
    horizon: float
    dt: float
    x0: ArrayLike | None = None
    law_bands: list | None = None
    law_Q: list | None = None
    law: str = "previous"
    sigma0: int = 0
    rule: SwitchRule = PRINTED
    law_weights: list | None = None
    label: object = field(default=None, compare=False)


@dataclass(frozen=True)
class Trace:
    """Traces decimated to bins of equal length: min and max of every sample in a bin.

    Parameters
    ----------
    t : (M,) ndarray
        Start time of each bin in s.
    x_lo, x_hi : (M, n) ndarray
        Smallest and largest state components in each bin.
    z_lo, z_hi : (M, p) ndarray
        Smallest and largest regulated outputs in each bin.
    d_lo, d_hi : (M,) ndarray
        Smallest and largest disturbance sample in each bin.
    share : (M, I) ndarray
        Fraction of the bin's samples in each mode.
    """

    t: np.ndarray
    x_lo: np.ndarray
    x_hi: np.ndarray
    z_lo: np.ndarray
    z_hi: np.ndarray
    d_lo: np.ndarray
    d_hi: np.ndarray
    share: np.ndarray


@dataclass(frozen=True)
class StreamResult:
    """Reductions of one streamed run (see :func:`simulate_stream`).

    Parameters
    ----------
    horizon, dt : float
        The grid ``0, dt, …, horizon`` (s).
    energy, input_energy : float
        ``∫ zᵀz`` and ``∫ d²`` over the horizon by Simpson's rule on the samples, as
        :meth:`SimResult.energy <fdsc.simulate.SimResult.energy>`; ``inf`` and ``nan`` if the run
        diverged. Under a :class:`~fdsc.signals.Sampled` input this is a quadrature of the
        samples, not the exact integral of the held signal (which jumps, for ZOH, at every
        sample): for a sampled smooth signal the two differ by O(dt).
    switches : int
        Number of changes of the active mode.
    time_share : (I,) ndarray
        Fraction of the horizon spent in each mode (of the nominal horizon: if the run diverged,
        the shares sum to less than 1).
    dwell_edges : (B + 1,) ndarray
        Edges (s) of the dwell-time histogram; a dwell of L steps counts in bin b if
        ``edges[b] ≤ L dt < edges[b + 1]``.
    dwell_counts : (B,) int ndarray
        Completed dwell intervals (ended by a switch) per bin.
    x_final : (n,) ndarray
        State at the horizon (at the divergence if the run diverged).
    sigma_final : int
        Mode chosen at the last point.
    t_cum : (M,) ndarray
        Coarse grid (s) of the running integrals (empty if none was asked for).
    energy_cum, input_energy_cum : (M,) ndarray
        ``∫₀ᵗ zᵀz`` and ``∫₀ᵗ d²`` at ``t_cum``.
    trace : Trace or None
        Decimated traces, if asked for.
    diverged_at : float or None
        Time (s) at which the state overflowed, None if it stayed finite.
    """

    horizon: float
    dt: float
    energy: float
    input_energy: float
    switches: int
    time_share: np.ndarray
    dwell_edges: np.ndarray
    dwell_counts: np.ndarray
    x_final: np.ndarray
    sigma_final: int
    t_cum: np.ndarray
    energy_cum: np.ndarray
    input_energy_cum: np.ndarray
    trace: Trace | None = None
    diverged_at: float | None = None

    @property
    def n_steps(self) -> int:
        """Number of steps (grid points − 1)."""
        return round(self.horizon / self.dt)

    def l2_ratio(self) -> float:
        """The L2-induced ratio ``√(∫zᵀz / ∫d²)`` over the horizon.

        Returns
        -------
        float

        Raises
        ------
        UnstableError
            If the run diverged.
        ValueError
            If the disturbance has zero energy.
        """
        if self.diverged_at is not None:
            raise UnstableError(f"the run diverged at t = {self.diverged_at:g} s; it has no L2 ratio")
        if not self.input_energy > 0:
            raise ValueError("the disturbance has zero energy: the L2-induced ratio is undefined")
        return math.sqrt(self.energy / self.input_energy)

    def running_l2(self) -> tuple[np.ndarray, np.ndarray]:
        """``√(∫₀ᵗ zᵀz / ∫₀ᵗ d²)`` on the coarse grid (nan where ``∫₀ᵗ d² = 0``).

        Returns
        -------
        t, ratio : (M,) ndarray

        Raises
        ------
        ValueError
            If the run kept no coarse grid (``cumulative_every`` was not given).
        """
        self._need_cum("running_l2")
        with np.errstate(invalid="ignore", divide="ignore"):
            ratio = np.sqrt(self.energy_cum / np.where(self.input_energy_cum > 0,
                                                       self.input_energy_cum, np.nan))
        return self.t_cum, ratio

    def window_energies(self, length: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``∫ zᵀz`` and ``∫ d²`` over every window ``[t, t + length]`` starting on the coarse grid.

        Parameters
        ----------
        length : float
            Window length in s, a multiple of the coarse grid's step, at most the horizon.

        Returns
        -------
        t_start, energy, input_energy : (M − L,) ndarray
            The sliding windows (hop = the coarse step).

        Raises
        ------
        ValueError
            If the run kept no coarse grid, or ``length`` is not a positive multiple of its step
            no longer than the horizon.
        """
        self._need_cum("window_energies")
        length = as_positive("length", length)
        step = self.t_cum[1] - self.t_cum[0]
        L = round(length / step)
        if L < 1 or abs(L * step - length) > 1e-9 * length or L >= self.t_cum.size:
            raise ValueError(f"length must be a multiple of the coarse step {step:g} s and at most "
                             f"{(self.t_cum.size - 1) * step:g} s, found {length:g}")
        return (self.t_cum[:-L], self.energy_cum[L:] - self.energy_cum[:-L],
                self.input_energy_cum[L:] - self.input_energy_cum[:-L])

    def _need_cum(self, what):
        if self.t_cum.size < 2:
            raise ValueError(f"{what} needs the coarse grid: run with cumulative_every=…")


class BatchResult:
    """The results of :func:`simulate_batch`: arrays over cases, and one
    :class:`StreamResult` per case by indexing (``batch[c]``).

    Parameters
    ----------
    cases : sequence of Case
        The cases, in order.
    results : sequence of StreamResult
        One result per case.

    Attributes
    ----------
    cases : list of Case
    energy, input_energy : (C,) ndarray
        ``∫ zᵀz`` and ``∫ d²`` of every case (``inf``/``nan`` where it diverged).
    switches : (C,) int ndarray
    time_share : (C, I_max) ndarray
        Zero for modes a case does not have.
    diverged : (C,) bool ndarray
    """

    def __init__(self, cases, results):
        self.cases = list(cases)
        self._results = list(results)
        self.energy = np.array([r.energy for r in results])
        self.input_energy = np.array([r.input_energy for r in results])
        self.switches = np.array([r.switches for r in results], dtype=np.int64)
        width = max(r.time_share.size for r in results)
        self.time_share = np.array([np.pad(r.time_share, (0, width - r.time_share.size))
                                    for r in results])
        self.diverged = np.array([r.diverged_at is not None for r in results])

    def __len__(self):
        return len(self._results)

    def __getitem__(self, c) -> StreamResult:
        return self._results[c]

    def __iter__(self):
        return iter(self._results)

    def __repr__(self):
        return (f"BatchResult({len(self)} cases, {int(self.diverged.sum())} diverged, "
                f"energies {np.array2string(self.energy, precision=4, threshold=6)})")


# ---------------------------------------------------------------------------------------------
# preparation of one case
# ---------------------------------------------------------------------------------------------

def _steps_of(name, seconds, dt, where, *, even=False):
    """A duration in s as a whole number of steps of ``dt`` (≥ 1, even if asked)."""
    seconds = as_positive(name, seconds)
    k = round(seconds / dt)
    if k < 1 or abs(k * dt - seconds) > 1e-9 * seconds:
        raise ValueError(f"{where}{name} ({seconds:g} s) must be a multiple of dt ({dt:g} s)")
    if even and k % 2:
        raise ValueError(f"{where}{name} ({seconds:g} s) must be an even number of steps of dt = "
                         f"{dt:g} s (the running integrals use Simpson's rule); found {k} steps")
    return k


def _segments(d, N, dt, where):
    """Point segments [start_s, start_{s+1}) and their Sinusoids (None: d = 0 there)."""
    if isinstance(d, Sinusoids):
        return [0, N], [d]
    starts, parts = [0], []
    idx = []
    for b in d.breaks:
        k = round(b / dt)
        if abs(k * dt - b) > 1e-9 * max(1.0, abs(b)):
            raise ValueError(f"{where}the disturbance switches at t = {b:g}, which is not on the grid "
                             f"(dt = {dt:g}); choose dt dividing every break")
        idx.append(min(max(k, 0), N))
    pieces = [(0, idx[0], None)] + [(idx[j], idx[j + 1], p) for j, p in enumerate(d.parts)] \
        + [(idx[-1], N, None)]
    starts, parts = [], []
    for k0, k1, part in pieces:
        if k1 > k0:
            starts.append(k0)
            parts.append(part)
    return starts + [N], parts


def _prepare(case, where, cumulative_every, trace_every, dwell_edges):
    check_type(f"{where}case", case, Case)
    modes = _as_modes(case.modes)
    n, B, D = _shared_input(modes, where)
    B, D = B[:, 0].copy(), D[:, 0].copy()
    nm, p = len(modes), modes[0].n_outputs
    law = as_choice(f"{where}law", case.law, LAWS)
    W = _law_weights(n, nm, case.law_bands, case.law_Q, case.law_weights, where)
    check_type(f"{where}rule", case.rule, SwitchRule)
    sigma0 = as_count(f"{where}sigma0", case.sigma0, 0)
    if sigma0 >= nm:
        raise ValueError(f"{where}sigma0 must be a mode index in [0, {nm}), found {sigma0}")
    dt = as_positive(f"{where}dt", case.dt)
    horizon = as_positive(f"{where}horizon", case.horizon)
    steps = round(horizon / dt)
    if steps < 1 or abs(steps * dt - horizon) > 1e-9 * horizon:
        raise ValueError(f"{where}horizon ({horizon:g}) must be a multiple of dt ({dt:g})")
    N = steps + 1
    x0 = np.zeros(n) if case.x0 is None else np.array(as_vector(f"{where}x0", case.x0, n))
    A = np.array([m.A for m in modes])
    C = np.array([m.C for m in modes])
    Phi = np.array([expm(a * dt) for a in A])
    check_type(f"{where}d", case.d, Sinusoids | Piecewise | Sampled,
               "an fdsc.signals.Sinusoids, Piecewise or Sampled")
    rparams, ring, _, _ = rule_state(case.rule, dt, nm)
    out = dict(N=N, dt=dt, nm=nm, n=n, p=p, Phi=Phi, A=A, B=B, C=C, D=D, W=W, law=_LAW_CODE[law],
               sigma0=sigma0, x0=x0, horizon=steps * dt, modes=modes, rparams=rparams,
               ring_len=ring.shape[0])
    if isinstance(case.d, Sampled):
        if abs(case.d.dt - dt) > 1e-12 * dt:
            raise ValueError(f"{where}d is sampled every {case.d.dt:g} s but the run steps by "
                             f"dt = {dt:g} s; they must be equal")
        if case.d.values.size < N:
            raise ValueError(f"{where}d has {case.d.values.size} samples but the horizon needs {N}")
        G0, G1 = _hold_matrices(A, B, dt)
        out.update(kind=_KIND_ZOH if case.d.hold == "zoh" else _KIND_FOH, u=case.d.values[:N],
                   G0=G0, G1=G1, seg_start=np.array([0, N]), segments=[None])
    else:
        seg_start, parts = _segments(case.d, N, dt, where)
        out.update(kind=_KIND_SINES, u=np.zeros(0), G0=np.zeros((nm, n)), G1=np.zeros((nm, n)),
                   seg_start=np.array(seg_start, dtype=np.int64), segments=parts)
        for part in parts:
            if part is not None:
                for i, a in enumerate(A):
                    check_no_pole_at(a, part.frequencies,
                                     what=f"{where}the forced response of mode {i} to the disturbance")
    out["cum_every"] = 0 if cumulative_every is None else _steps_of(
        "cumulative_every", cumulative_every, dt, where, even=True)
    if out["cum_every"] > steps:
        raise ValueError(f"{where}cumulative_every ({cumulative_every:g} s) exceeds the horizon "
                         f"({horizon:g} s): the coarse grid would hold one point")
    out["trace_every"] = 0 if trace_every is None else _steps_of("trace_every", trace_every, dt, where)
    if dwell_edges is None:
        edges = 2 ** np.arange(0, max(2, math.ceil(math.log2(N)) + 2), dtype=np.int64)
    else:
        e = np.asarray(dwell_edges, dtype=float)
        if e.ndim != 1 or e.size < 2 or np.any(np.isnan(e)) or np.any(np.diff(e) <= 0) or e[0] < 0:
            raise ValueError(f"{where}dwell_edges must be at least 2 increasing times ≥ 0 (s; the "
                             f"last may be inf), found {dwell_edges!r}")
        # edges beyond the horizon (inf included) all mean "longer than any dwell of this run"
        edges = np.round(np.minimum(e, horizon + (np.arange(e.size) + 1) * dt) / dt).astype(np.int64)
        if np.any(np.diff(edges) <= 0):
            raise ValueError(f"{where}dwell_edges must be at least one step (dt = {dt:g} s) apart, "
                             f"found {e.tolist()}")
    out["dwell_edges"] = edges
    return out


def _hold_matrices(A, B, dt):
    """Φ, Γ₀, Γ₁ of the exact step under a held input (Van Loan): expm of
    [[A, B, 0], [0, 0, 1/dt], [0, 0, 0]] dt = [[Φ, Γ₀, Γ₁], …]."""
    nm, n = A.shape[0], A.shape[1]
    G0, G1 = np.zeros((nm, n)), np.zeros((nm, n))
    for i, a in enumerate(A):
        M = np.zeros((n + 2, n + 2))
        M[:n, :n] = a
        M[:n, n] = B
        M[n, n + 1] = 1.0 / dt
        E = expm(M * dt)
        G0[i], G1[i] = E[:n, n], E[:n, n + 1]
    return G0, G1


def _tone_arrays(prep, T):
    """Per segment: frequencies, amplitudes, phases, the input matrices H of the augmented
    system and the rotation table, padded to T tones.

    Step k → k + 1 of mode i under ``d = Σ a_j Im(p_j)``, ``p_j = e^{j(ω_j t + φ_j)}``, is
    ``x_{k+1} = Φ_i x_k + Σ_j Im(H_ij p_j(t_k))`` with ``H_ij = a_j ∫₀^Δt e^{A_i(Δt−s)} B
    e^{jω_j s} ds``: the top-right block of ``expm([[A_i, B a], [0, diag(jω)]] Δt)`` (the exact
    discretization of the plant driven by the tones' oscillators)."""
    S, nm, n, dt = len(prep["segments"]), prep["nm"], prep["n"], prep["dt"]
    K = PHASOR_BLOCK
    nt = np.zeros(S, dtype=np.int64)
    omega, amp, phase = np.zeros((S, T)), np.zeros((S, T)), np.zeros((S, T))
    H = np.zeros((S, nm, n, T), dtype=complex)
    R = np.zeros((S, T, K), dtype=complex)
    jdt = np.arange(K) * dt
    for s, part in enumerate(prep["segments"]):
        if part is None:
            continue
        k = part.frequencies.size
        nt[s] = k
        omega[s, :k], amp[s, :k], phase[s, :k] = part.frequencies, part.amplitudes, part.phases
        for j, w in enumerate(part.frequencies):
            theta = w * jdt
            R[s, j] = np.cos(theta) + 1j * np.sin(theta)
        for i, Ai in enumerate(prep["A"]):
            H[s, i, :, :k] = _tone_input(Ai, prep["B"], part, dt)
    return nt, omega, amp, phase, H, R


def _tone_input(A, B, part, dt):
    """H of one mode and one piece: the top-right block of ``expm([[A, B aᵀ], [0, diag(jω)]] Δt)``
    (see :func:`_tone_arrays`); (n, T) complex."""
    n, k = A.shape[0], part.frequencies.size
    M = np.zeros((n + k, n + k), dtype=complex)
    M[:n, :n] = A
    M[:n, n:] = np.outer(B, part.amplitudes)
    M[n:, n:] = np.diag(1j * part.frequencies)
    return expm(M * dt)[:n, n:]


def _law_forms(A, B, W, f):
    """The law's forms on ξ = [x; d] (f = 2) or [x; d; ḋ] (f = 3), packed for the kernel.

    Score i with the derivatives of mode m is ``vᵀ W_i v``, ``v = L_m ξ`` (``v = [ẋ; x]`` or
    ``[ẍ; ẋ; x]``), so it is ``ξᵀ (L_mᵀ W_i L_m) ξ``; returns ``Mt[m, q, i]``, the upper
    triangle of that form (row-major, off-diagonal entries doubled) at position q (the caller
    stores it as ``[m, i, q]``, each score one contiguous dot product)."""
    nm, n = A.shape[0], A.shape[1]
    r = n + f - 1
    iu = np.triu_indices(r)
    Mt = np.zeros((nm, r * (r + 1) // 2, W.shape[0]))
    for m in range(nm):
        L = np.zeros((f * n, r))
        Am = A[m]
        if f == 2:
            L[:n, :n], L[:n, n] = Am, B                      # ẋ = A x + B d
        else:
            L[:n, :n], L[:n, n], L[:n, n + 1] = Am @ Am, Am @ B, B   # ẍ = A² x + A B d + B ḋ
            L[n:2 * n, :n], L[n:2 * n, n] = Am, B
        L[(f - 1) * n:, :n] = np.eye(n)                      # x
        for i in range(W.shape[0]):
            F = L.T @ W[i] @ L
            F = F + F.T - np.diag(np.diag(F))
            Mt[m, :, i] = F[iu]
    return Mt


def _packed_positions(n_own, f_own, n, f):
    """Where the packed upper triangle of a form on ``ξ = [x; d(; ḋ)]`` with ``n_own`` states and
    law order ``f_own`` goes in that of ``n ≥ n_own`` states and order ``f ≥ f_own``: the states
    keep their indices, d and ḋ move from ``n_own`` on to ``n`` on."""
    r_own, r = n_own + f_own - 1, n + f - 1
    idx = np.arange(r_own)
    idx = np.where(idx < n_own, idx, idx - n_own + n)
    a, b = np.triu_indices(r_own)
    ia, ib = idx[a], idx[b]
    # row-major upper triangle of an r × r matrix: row a starts at a·r − a(a − 1)/2
    return ia * r - ia * (ia - 1) // 2 + (ib - ia)


def _stack(preps):
    """Pad every case to common sizes and concatenate the ragged outputs."""
    C = len(preps)
    n = max(q["n"] for q in preps)
    p = max(q["p"] for q in preps)
    nm = max(q["nm"] for q in preps)
    S = max(len(q["segments"]) for q in preps)
    T = max([1] + [s.frequencies.size for q in preps for s in q["segments"] if s is not None])
    nb = max(q["dwell_edges"].size for q in preps)
    # the law's vector: [ẋ; x] (f = 2), or [ẍ; ẋ; x] (f = 3) if any case has a second-order law
    f = max(q["W"].shape[1] // q["n"] for q in preps)
    K = PHASOR_BLOCK
    st = dict(N=np.array([q["N"] for q in preps], dtype=np.int64),
              dt=np.array([q["dt"] for q in preps]),
              nm=np.array([q["nm"] for q in preps], dtype=np.int64),
              Phi=np.zeros((C, nm, n, n)), C=np.zeros((C, nm, p, n)), D=np.zeros((C, p)),
              Mt=np.zeros((C, nm, nm, (n + f - 1) * (n + f) // 2)),
              law=np.array([q["law"] for q in preps], dtype=np.int64),
              sigma0=np.array([q["sigma0"] for q in preps], dtype=np.int64),
              x0=np.zeros((C, n)), kind=np.array([q["kind"] for q in preps], dtype=np.int64),
              seg_start=np.zeros((C, S + 1), dtype=np.int64), seg_nt=np.zeros((C, S), dtype=np.int64),
              omega=np.zeros((C, S, T)), amp=np.zeros((C, S, T)), phase=np.zeros((C, S, T)),
              Gr=np.zeros((C, S, nm, n, T)), Gi=np.zeros((C, S, nm, n, T)),
              Rre=np.zeros((C, S, K, T)), Rim=np.zeros((C, S, K, T)),
              G0=np.zeros((C, nm, n)), G1=np.zeros((C, nm, n)),
              cum_every=np.array([q["cum_every"] for q in preps], dtype=np.int64),
              trace_every=np.array([q["trace_every"] for q in preps], dtype=np.int64),
              dwell_edges=np.full((C, nb), np.iinfo(np.int64).max, dtype=np.int64),
              rparams=np.zeros((C, 4)))
    u_off, cum_off, tr_off = [0], [0], [0]
    for c, q in enumerate(preps):
        qn, qm, qp = q["n"], q["nm"], q["p"]
        st["Phi"][c, :qm, :qn, :qn] = q["Phi"]
        # padded states: Φ = I keeps them at zero; padded modes are never chosen (nm per case)
        for i in range(qm):
            st["Phi"][c, i, qn:, qn:] = np.eye(n - qn)
        st["C"][c, :qm, :qp, :qn] = q["C"]
        st["D"][c, :qp] = q["D"]
        # the forms on ξ from the case's own matrices, then placed in the padded ξ = [x; d; ḋ]
        # (a first-order law in a second-order batch leaves the ḋ entries zero; computed on
        # padded matrices, the products would round differently with the padding, and a
        # near-tie of the scores could switch otherwise than in the case's own run)
        g = q["W"].shape[1] // qn
        own = _law_forms(q["A"], q["B"], q["W"], g).transpose(0, 2, 1)
        st["Mt"][c, :qm, :qm][..., _packed_positions(qn, g, n, f)] = own
        st["rparams"][c] = q["rparams"]
        st["x0"][c, :qn] = q["x0"]
        st["G0"][c, :qm, :qn] = q["G0"]
        st["G1"][c, :qm, :qn] = q["G1"]
        ss = q["seg_start"]
        st["seg_start"][c, :ss.size] = ss
        st["seg_start"][c, ss.size:] = q["N"]
        if q["kind"] == _KIND_SINES:
            nt, om, am, ph, H, R = _tone_arrays(q, T)
            s_ = nt.size
            st["seg_nt"][c, :s_] = nt
            st["omega"][c, :s_], st["amp"][c, :s_], st["phase"][c, :s_] = om, am, ph
            # Im(H p) = Im(H) Re(p) + Re(H) Im(p); the tone index innermost: contiguous loops
            st["Gr"][c, :s_, :qm, :qn], st["Gi"][c, :s_, :qm, :qn] = H.imag, H.real
            R = R.transpose(0, 2, 1)
            st["Rre"][c, :s_], st["Rim"][c, :s_] = R.real, R.imag
        st["dwell_edges"][c, :q["dwell_edges"].size] = q["dwell_edges"]
        u_off.append(u_off[-1] + q["u"].size)
        ce, te = q["cum_every"], q["trace_every"]
        cum_off.append(cum_off[-1] + ((q["N"] - 1) // ce + 1 if ce else 0))
        tr_off.append(tr_off[-1] + (-(-q["N"] // te) if te else 0))
    st["u_all"] = np.concatenate([q["u"] for q in preps]) if u_off[-1] else np.zeros(1)
    st["u_off"], st["cum_off"], st["tr_off"] = (np.array(o, dtype=np.int64) for o in (u_off, cum_off, tr_off))
    st["ring_off"] = np.concatenate([[0], np.cumsum([q["ring_len"] for q in preps])]).astype(np.int64)
    return st, dict(n=n, p=p, nm=nm, nb=nb)


_INPUTS = ("N", "dt", "nm", "Phi", "C", "D", "Mt", "law", "sigma0", "x0", "kind",
           "seg_start", "seg_nt", "omega", "amp", "phase", "Gr", "Gi", "Rre", "Rim")


def _run(preps, kernel, threads, closed_form=True, specialize=None):
    """Results of every prepared case: by the closed form where it applies (if allowed), by the
    loop otherwise."""
    closed = [_closed_result(q) if closed_form and _closed_form_applies(q) else None for q in preps]
    looped = [i for i, c in enumerate(closed) if c is None]
    # the loop runs in groups of cases with the same number of modes, kind of input and traces
    # or none, so that each group's compiled loop can be specialized to it (_shape_tag)
    groups = {}
    for i in looped:
        q = preps[i]
        groups.setdefault((q["nm"], q["kind"] == _KIND_SINES, q["trace_every"] == 0), []).append(i)
    planned = [(members, _loop_plan([preps[i] for i in members], kernel, specialize))
               for members in groups.values()]
    # every group's cases on one pool of threads, the longest first, so that the threads finish
    # together; each case writes only its own rows of its group's outputs
    runs = sorted(((steps, run) for _, plan in planned for steps, run in plan[0]),
                  key=lambda job: -job[0])
    if kernel == "numba" and len(runs) > 1 and threads > 1:
        with ThreadPoolExecutor(min(threads, len(runs))) as pool:
            for _ in pool.map(lambda job: job[1](), runs):
                pass
    else:
        for _, run in runs:
            run()
    for members, (_, results) in planned:
        for i, res in zip(members, results(), strict=True):
            closed[i] = res
    return closed


def _closed_form_applies(pr):
    return (pr["nm"] == 1 and pr["kind"] == _KIND_SINES and pr["trace_every"] == 0
            and _closed_form.applies(pr["Phi"][0]))


def _closed_result(pr):
    """The result of an LTI run under pieces of tones from the closed form of its Simpson sums
    (:mod:`fdsc._closed_form`): the same numbers as the loop's, rounded differently; None if
    the closed form's terms cancel too much to keep its accuracy."""
    N, dt, ce = pr["N"], pr["dt"], pr["cum_every"]
    A, B = pr["A"][0], pr["B"]
    parts = pr["segments"]
    H = [None if part is None else _tone_input(A, B, part, dt) for part in parts]
    grid = np.arange(0, N, ce, dtype=np.int64) if ce else np.zeros(0, dtype=np.int64)
    if N == 2:
        ends, points = [], [0, 1]
    elif N % 2 == 1:
        ends, points = [N], [0, N - 1]
    else:
        ends, points = [N - 2], [0, N - 3, N - 2, N - 1]
    ends_all = np.concatenate([np.array(ends, dtype=np.int64), grid])
    points_all = np.concatenate([np.array(points, dtype=np.int64), grid])
    G, f, x_last, mag = _closed_form.simpson_sums(pr["Phi"][0], pr["C"][0], pr["D"], pr["x0"],
                                                  pr["seg_start"], parts, H, dt, ends_all, points_all)
    if not np.all(mag <= _closed_form.MAX_CANCELLATION * np.abs(G[0, 0])):
        return None     # its terms cancel: digits would be lost, run the loop
    # Simpson's weighted sum Σ_{k<K} w_k f_k (w = 1, 4, 2, 4, …) = 3 G₊ − G₋ − f₀
    W = 3.0 * G[:, 0, :] - G[:, 1, :] - f[:, :1]
    if N == 2:
        total = dt * (f[:, 0] + f[:, 1]) / 2.0
    elif N % 2 == 1:
        total = dt / 3.0 * (W[:, 0] - f[:, 1])
    else:
        total = dt / 3.0 * (W[:, 0] + f[:, 2]) + dt * (5.0 * f[:, 3] + 8.0 * f[:, 2] - f[:, 1]) / 12.0
    t_cum = grid * dt
    cum = np.zeros((2, grid.size))
    if grid.size:
        cum[:, 1:] = dt / 3.0 * (W[:, len(ends) + 1:] + f[:, len(points) + 1:])
    edges = pr["dwell_edges"].astype(float) * dt
    return StreamResult(
        horizon=pr["horizon"], dt=dt, energy=float(total[0]), input_energy=float(total[1]),
        switches=0, time_share=np.ones(1), dwell_edges=edges,
        dwell_counts=np.zeros(edges.size - 1, dtype=np.int64),
        x_final=x_last, sigma_final=0, t_cum=t_cum, energy_cum=cum[0], input_energy_cum=cum[1],
        trace=None, diverged_at=None)


#: Largest size for which the compiled loop is specialized (see :func:`_shape_tag`): states,
#: outputs, tones and modes up to this many have loops of a fixed trip count.
UNROLL_MAX = 8
#: Fewest steps in one call (one group of cases) for which the specialized loop is used by
#: default. Compiling it for new sizes costs about 3–4 s of one core once (then numba's disk cache
#: has it) and saves 30–40 ns per step on the paper's loop, so a call repays its first
#: compilation from about 1e8 steps on; 5e7 lets the record's four largest calls (of the
#: paper's two-mode loop under 6 and 3 tones) share two compiled loops, and leaves its other
#: calls (3e8 steps in all, about 10 s) to the general loop rather than compile eight more
#: (about 30 s on every fresh install, such as each CI run).
UNROLL_MIN_STEPS = 50_000_000


def _shape_tag(st, kernel, specialize=None):
    """The ``shape`` argument of the compiled loop for the stacked cases ``st``.

    The general loop (``((),) * 7``) reads every size from its arrays, so its small inner loops
    (over the n states, p outputs, T tones, modes) have trip counts unknown to the compiler.
    For a group of cases run by the compiled kernel (``specialize`` True, or None and at least
    :data:`UNROLL_MIN_STEPS` steps in the group), each size up to :data:`UNROLL_MAX` that all
    cases share (after padding: n, p, T and the law's vector are padded to the largest case,
    the number of modes only if every case has it) becomes the length of a tuple: a constant
    of the compiled code, one compiled loop per combination. The arithmetic is the same, in the
    same order, so the results are the general loop's bit for bit (the tests check this):
    padded tones add exact zeros.
    """
    general = ((),) * 7
    if specialize is None:
        specialize = int((st["N"] - 1).sum()) >= UNROLL_MIN_STEPS   # N points: N − 1 steps
    if kernel != "numba" or not specialize:
        return general

    def fixed(size):
        return (0,) * int(size) if 0 < size <= UNROLL_MAX else ()

    nm = st["nm"]
    sines = st["kind"] == _KIND_SINES
    n_law = st["Mt"].shape[3]
    return (fixed(st["x0"].shape[1]), fixed(st["D"].shape[1]),
            fixed(nm[0]) if np.all(nm == nm[0]) else (),
            (0,) * n_law if n_law <= (UNROLL_MAX + 1) * (UNROLL_MAX + 2) // 2 else (),
            fixed(st["omega"].shape[2]) if np.any(sines) else (),
            (0,) if np.all(sines) else (), (0,) if np.all(st["trace_every"] == 0) else ())


def _loop_plan(preps, kernel, specialize=None):
    """The loop's runs of a group of cases: ``([(points, run), ...], results)``, each ``run()``
    stepping one case into the group's output arrays and ``results()`` reading them once every
    run is done."""
    st, dims = _stack(preps)
    shape = _shape_tag(st, kernel, specialize)
    Cn, n, p, nm, nb = len(preps), dims["n"], dims["p"], dims["nm"], dims["nb"]
    q = n + p + 1
    sums = np.zeros((Cn, 3))
    share_steps = np.zeros((Cn, nm), dtype=np.int64)
    dwell_counts = np.zeros((Cn, nb - 1), dtype=np.int64)
    cum = np.zeros((int(st["cum_off"][-1]), 2))
    n_tr = int(st["tr_off"][-1])
    tr_lo, tr_hi, tr_share = np.zeros((n_tr, q)), np.zeros((n_tr, q)), np.zeros((n_tr, nm))
    x_out = np.zeros((Cn, n))
    info = np.zeros((Cn, 2), dtype=np.int64)
    args = [st[k] for k in _INPUTS]
    ring = np.zeros((int(st["ring_off"][-1]), nm))
    ring_sum = np.zeros((Cn, nm))
    istate = np.zeros((Cn, 3), dtype=np.int64)
    loop = _case_numba if kernel == "numba" else _case_loop

    def run_case(c):
        u = st["u_all"][st["u_off"][c]:st["u_off"][c + 1]]
        cs = slice(st["cum_off"][c], st["cum_off"][c + 1])
        ts = slice(st["tr_off"][c], st["tr_off"][c + 1])
        with np.errstate(over="ignore", invalid="ignore"):
            loop(*[a[c] for a in args], u, st["G0"][c], st["G1"][c], st["cum_every"][c],
                 st["trace_every"][c], st["dwell_edges"][c], st["rparams"][c],
                 ring[st["ring_off"][c]:st["ring_off"][c + 1]], ring_sum[c], istate[c],
                 sums[c], share_steps[c],
                 dwell_counts[c], cum[cs], tr_lo[ts], tr_hi[ts], tr_share[ts], x_out[c], info[c],
                 shape)

    def results():
        return [_result(pr, c, st, sums, share_steps, dwell_counts, cum, tr_lo, tr_hi, tr_share,
                        x_out, info) for c, pr in enumerate(preps)]

    return [(int(st["N"][c]), functools.partial(run_case, c)) for c in range(Cn)], results


def _result(pr, c, st, sums, share_steps, dwell_counts, cum, tr_lo, tr_hi, tr_share, x_out, info):
    N, dt, n, p, nm = pr["N"], pr["dt"], pr["n"], pr["p"], pr["nm"]
    diverged = int(info[c, 0])
    ce, te = pr["cum_every"], pr["trace_every"]
    cs = slice(st["cum_off"][c], st["cum_off"][c + 1])
    t_cum = np.arange(cs.stop - cs.start) * ce * dt
    e_cum, d_cum = cum[cs, 0].copy(), cum[cs, 1].copy()
    trace = None
    if te:
        ts = slice(st["tr_off"][c], st["tr_off"][c + 1])
        lo, hi, sh = tr_lo[ts].copy(), tr_hi[ts].copy(), tr_share[ts, :nm].copy()
        start = np.arange(lo.shape[0]) * te
        last = N - 1 if diverged < 0 else diverged      # the last point written
        counts = np.clip(last + 1 - start, 1, te).astype(float)
        # bins after the point where the state overflowed were never written: not a value
        lo[start > last], hi[start > last], sh[start > last] = np.nan, np.nan, np.nan
        nn = st["x0"].shape[1]
        cols_x, cols_z = slice(0, n), slice(nn, nn + p)
        dcol = nn + st["D"].shape[1]
        trace = Trace(start * dt, lo[:, cols_x], hi[:, cols_x], lo[:, cols_z], hi[:, cols_z],
                      lo[:, dcol], hi[:, dcol], sh / counts[:, None])
    if diverged >= 0:
        # rows at and after the point where the state overflowed were never written
        keep = np.arange(t_cum.size) * ce < diverged
        t_cum, e_cum, d_cum = t_cum[keep], e_cum[keep], d_cum[keep]
    edges = st["dwell_edges"][c, :pr["dwell_edges"].size].astype(float) * dt
    return StreamResult(
        horizon=pr["horizon"], dt=dt, energy=float(sums[c, 0]), input_energy=float(sums[c, 1]),
        switches=int(sums[c, 2]), time_share=share_steps[c, :nm] / (N - 1),
        dwell_edges=edges, dwell_counts=dwell_counts[c, :edges.size - 1].copy(),
        x_final=x_out[c, :n].copy(), sigma_final=int(info[c, 1]), t_cum=t_cum, energy_cum=e_cum,
        input_energy_cum=d_cum, trace=trace, diverged_at=None if diverged < 0 else diverged * dt)


def _warn_unstable_modes(pr, res, where, stacklevel):
    for i, m in enumerate(pr["modes"]):
        ev = np.linalg.eigvals(m.A)
        if ev.real.max() >= 0 and res.time_share[i] > 0:
            worst = ev[np.argmax(ev.real)]
            warnings.warn(f"{where}mode {i} is not Hurwitz (eigenvalue {worst:.6g}) and is active "
                          "in this run; its energies grow with the horizon", UnstableRunWarning,
                          stacklevel=stacklevel)


# ---------------------------------------------------------------------------------------------
# public functions
# ---------------------------------------------------------------------------------------------

def simulate_stream(modes, d: Sinusoids | Piecewise | Sampled, horizon: float, dt: float, *,
                    x0: ArrayLike | None = None, law_bands: list | None = None,
                    law_Q: list | None = None, law: str = "previous", sigma0: int = 0,
                    rule: SwitchRule = PRINTED, law_weights: list | None = None,
                    cumulative_every: float | None = None, trace_every: float | None = None,
                    dwell_edges: ArrayLike | None = None, kernel: str = "numba",
                    closed_form: bool = True, specialize: bool | None = None) -> StreamResult:
    """Simulate one LTI or switched loop on ``0, dt, …, horizon`` and return its reductions.

    The same exact step and the same sampled switching law (paper eq. (31)) as
    :func:`fdsc.simulate.simulate`, streamed: the memory does not grow with the horizon unless
    traces or a coarse grid are asked for.

    Parameters
    ----------
    modes : LTISystem or list of LTISystem
        Closed loop(s) sharing B and D (``StateSpace`` or ``(A, B, C, D)`` accepted).
    d : Sinusoids, Piecewise or Sampled
        Scalar disturbance (see :class:`Case`).
    horizon, dt : float
        End time and step in s; the horizon must be a multiple of dt.
    x0 : (n,) array_like, optional
        Initial state (default 0).
    law_bands, law_Q : list, optional
        Ω_i and Q_i of the switching law (required for several modes).
    law : {"previous", "candidate"}, optional
        How ẋ enters the law (:data:`fdsc.simulate.LAWS`).
    sigma0 : int, optional
        Mode assumed active before t = 0.
    rule : SwitchRule, optional
        Hysteresis, minimum dwell time and/or moving window (:class:`~fdsc.rules.SwitchRule`;
        default the printed argmax).
    law_weights : list of array_like, optional
        Instead of ``law_bands`` and ``law_Q``: one symmetric W_i per mode on ``[ẋ; x]`` (2n) or
        ``[ẍ; ẋ; x]`` (3n); see :func:`fdsc.simulate.simulate`.
    cumulative_every : float, optional
        Step (s) of the coarse grid on which ``∫₀ᵗ zᵀz`` and ``∫₀ᵗ d²`` are kept: an even
        number of steps of dt. Needed by :meth:`StreamResult.running_l2` and
        :meth:`StreamResult.window_energies`.
    trace_every : float, optional
        Bin width (s, a multiple of dt) of decimated min/max traces of x, z and d and of the
        mode share per bin.
    dwell_edges : (B + 1,) array_like, optional
        Edges (s) of the dwell-time histogram, at least one step apart (default 1, 2, 4, …
        steps, up to beyond the horizon); dwells longer than the last edge are not counted.
    kernel : {"numba", "python"}, optional
        The compiled loop or the same loop in the interpreter (slow; for tests).
    closed_form : bool, optional
        Sum an LTI run (one mode) under a Sinusoids or Piecewise disturbance, with no traces,
        in closed form instead of stepping through it (default True; see Notes).
    specialize : bool, optional
        Compile the loop for the run's sizes (states, outputs, modes, law vector, tones up to
        :data:`UNROLL_MAX`): about twice as fast per step, the same numbers bit for bit, but a
        first use for new sizes compiles for a few seconds (then numba's disk cache has it).
        Default None: only for runs of at least :data:`UNROLL_MIN_STEPS` steps. Ignored by the
        ``"python"`` kernel.

    Returns
    -------
    StreamResult

    Raises
    ------
    ValueError
        On a grid, coarse grid, trace bin or break that does not fit ``dt``, modes that do not
        share B and D, a non-scalar disturbance, non-PD ``law_Q``, law weights that are not
        symmetric or given together with ``law_bands``/``law_Q``, an unknown law or kernel.
    TypeError
        If ``modes``, ``d``, ``law_bands`` or ``rule`` are not of the accepted types.
    DimensionError
        If a law weight is neither (2n, 2n) nor (3n, 3n).
    SingularFrequencyError
        If a disturbance tone sits at an eigenvalue of a mode.
    UnstableError
        If the state overflows: the loop diverges and no finite energy summarizes it.

    Warns
    -----
    UnstableRunWarning
        If a mode that is not Hurwitz is active but the run stayed finite.

    Notes
    -----
    The samples of an LTI run under tones are a transient plus a steady state in closed form,
    so the same Simpson sums (total and coarse grid) and the state at the end are computed
    without the loop, in a time independent of the horizon (:mod:`fdsc._closed_form`). It is
    used only where it keeps the loop's accuracy: the step Φ = e^{AΔt} has spectral radius
    ≤ 1 − 1e-6, and the closed form's terms are at most 30 times its sums (not so for a large
    steady state against the transient of a slow pole over a short run, or for a stiff loop in
    badly scaled coordinates); otherwise, and for ``closed_form=False``, the run goes through
    the loop. Where it is kept it agrees with the loop to a few 1e-11 relative or better
    (random loops with poles from 1e-3 to 5e5 rad/s; the paper's loops: about 1e-13).

    Examples
    --------
    >>> from fdsc import LTISystem, Sinusoids
    >>> loop = LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]])
    >>> run = simulate_stream(loop, Sinusoids([1.0], [1.0]), 100.0, 1e-3)
    >>> round(run.energy / run.input_energy, 3)     # |1/(j + 1)|² = 1/2, plus the transient
    0.499
    >>> run.switches, run.time_share
    (0, array([1.]))
    """
    as_choice("kernel", kernel, STREAM_KERNELS)
    check_type("closed_form", closed_form, (bool, np.bool_), "True or False")
    check_type("specialize", specialize, (bool, np.bool_, type(None)), "True, False or None")
    case = Case(modes, d, horizon, dt, x0=x0, law_bands=law_bands, law_Q=law_Q, law=law,
                sigma0=sigma0, rule=rule, law_weights=law_weights)
    pr = _prepare(case, "", cumulative_every, trace_every, dwell_edges)
    (res,) = _run([pr], kernel, 1, closed_form, specialize)
    if res.diverged_at is not None:
        raise UnstableError(f"simulate_stream: the state overflowed at t = {res.diverged_at:g} s; "
                            "the loop diverges and no finite energy summarizes it")
    _warn_unstable_modes(pr, res, "simulate_stream: ", 3)
    return res


def simulate_batch(cases, *, cumulative_every: float | None = None, trace_every: float | None = None,
                   dwell_edges: ArrayLike | None = None, threads: int | None = None,
                   kernel: str = "numba", closed_form: bool = True,
                   specialize: bool | None = None) -> BatchResult:
    """Run many :class:`Case` s in one call, in parallel over cases.

    Parameters
    ----------
    cases : sequence of Case
        The runs (modes, disturbance, law, horizon and step may differ between cases).
    cumulative_every, trace_every, dwell_edges : optional
        As in :func:`simulate_stream`, the same for every case (each must fit every case's dt).
    threads : int, optional
        Threads to use (default ``numba.get_num_threads()``, i.e. every core; at most
        ``numba.config.NUMBA_NUM_THREADS``).
    kernel : {"numba", "python"}, optional
        The compiled loop (cases in parallel) or the same loop in the interpreter (one case
        after the other).
    closed_form : bool, optional
        LTI cases under tones without traces in closed form (default True; see
        :func:`simulate_stream`).
    specialize : bool, optional
        As in :func:`simulate_stream`, for each group of cases with the same number of modes,
        kind of input and traces or none (default None: groups of at least
        :data:`UNROLL_MIN_STEPS` steps).

    Returns
    -------
    BatchResult
        Cases that diverged have ``energy = inf`` and ``diverged`` set; they are reported by a
        warning, not by an exception, so that the other cases are kept.

    Raises
    ------
    ValueError, TypeError, SingularFrequencyError
        As :func:`simulate_stream`, with the message naming the case (``cases[c]``); also if
        ``cases`` is empty or ``threads`` is not a positive integer.

    Warns
    -----
    UnstableRunWarning
        For diverged cases (listed), and for a non-Hurwitz mode active in a finite run.

    Examples
    --------
    >>> from fdsc import LTISystem, Sinusoids
    >>> loop = LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]])
    >>> runs = simulate_batch([Case(loop, Sinusoids([1.0], [w]), 50.0, 1e-3) for w in (0.5, 2.0)])
    >>> np.round(runs.energy / runs.input_energy, 3)     # ≈ 1 / (1 + ω²) after the transient
    array([0.801, 0.201])
    """
    as_choice("kernel", kernel, STREAM_KERNELS)
    check_type("closed_form", closed_form, (bool, np.bool_), "True or False")
    check_type("specialize", specialize, (bool, np.bool_, type(None)), "True, False or None")
    if isinstance(cases, Case) or not hasattr(cases, "__iter__"):
        raise TypeError(f"cases must be a sequence of Case, found {type(cases).__name__}")
    cases = list(cases)
    if not cases:
        raise ValueError("cases must hold at least one Case")
    threads = numba.get_num_threads() if threads is None else as_count("threads", threads)
    threads = min(threads, numba.config.NUMBA_NUM_THREADS)
    preps = [_prepare(c, f"cases[{i}]: ", cumulative_every, trace_every, dwell_edges)
             for i, c in enumerate(cases)]
    results = _run(preps, kernel, threads, closed_form, specialize)
    batch = BatchResult(cases, results)
    if batch.diverged.any():
        bad = np.flatnonzero(batch.diverged)
        warnings.warn(f"simulate_batch: {bad.size} of {len(cases)} cases diverged (the state "
                      f"overflowed): cases {bad.tolist()[:20]}; their energy is inf",
                      UnstableRunWarning, stacklevel=2)
    for pr, res, i in zip(preps, results, range(len(preps)), strict=True):
        if res.diverged_at is None:
            _warn_unstable_modes(pr, res, f"simulate_batch: cases[{i}]: ", 3)
    return batch
