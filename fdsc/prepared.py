"""The exact engine of a law on the disturbance estimate: a :class:`~fdsc.supervisor.Supervisor`
prepared for one disturbance (:class:`Prepared`: the monitors' energies per decision interval and
the switched loops' step tables, from which any setting of the law, fixed candidates, segment
laws and the clairvoyant per-segment oracle are evaluated exactly), and the switched run along a
decided sequence at a given step (by :func:`fdsc.simulate_stream`).
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from . import _divergence
from ._grid_run import shift_signal
from ._validation import as_nonnegative, as_positive, as_vector, check_type
from .decisions import (
    SupervisedRun,
    _abcd,
    _bank_starts,
    _check_memory,
    _check_mu,
    _decide,
    _fading,
    _input_energy,
    _n_blocks,
    _older_bank,
    _scale_exponent,
    _scaled,
    _schedule,
    _unscale,
)
from .exceptions import DimensionError, EnergyOverflowError, UnstableRunWarning
from .signals import Piecewise, Sinusoids

__all__ = ["Prepared", "shift_signal"]

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
        The estimate ŵ the controller has (default ``d``; see :meth:`Supervisor.prepare`).
    copies_on_estimate : bool, optional
        Whether the copies and the candidates that read ŵ run on ``estimate`` (default) or on
        ``d`` (see :meth:`Supervisor.prepare`).

    Notes
    -----
    Scale: the runs are linear in (x0, d, ŵ) and the law compares its monitoring signals
    relative to each other, so the engine runs scaled by a power of two whenever the largest
    entry of the disturbance, its estimate or x0 lies outside [2^−200, 2^200]
    (:data:`fdsc.decisions.SCALE_RANGE`): the monitors by the estimate's own power, the runs by
    that of (x0, d, ŵ). Decisions then do not depend on the disturbance's scale across the
    float range, and every result is given in the disturbance's units (states times 2^e,
    energies and monitoring signals times 2^2e, exactly); a result that those units cannot
    represent raises :class:`~fdsc.exceptions.EnergyOverflowError` by name.

    Raises
    ------
    TypeError
        If ``d`` is not Sinusoids or Piecewise.
    ValueError
        If ``horizon`` is not a whole number of decision intervals or ``x0`` has the wrong size.
    """

    def __init__(self, sup, d, horizon, x0, estimate=None, *, copies_on_estimate: bool = True):
        from ._blocks import Grid

        check_type("d", d, Sinusoids | Piecewise, "an fdsc.Sinusoids or fdsc.Piecewise")
        horizon = as_positive("horizon", horizon)
        nb = _n_blocks(horizon, sup.decide_every)
        n = sup.plant.n_states
        self.sup, self.d, self.horizon, self.n_blocks = sup, d, float(horizon), nb
        self.x0 = np.zeros(n) if x0 is None else np.array(as_vector("x0", x0, n))
        if estimate is not None:
            check_type("estimate", estimate, Sinusoids | Piecewise, "an fdsc.Sinusoids or fdsc.Piecewise")
        _check_memory(sup, d, estimate, nb)
        self.points = np.arange(nb + 1) * sup.decide_every
        self.points[-1] = horizon
        # power-of-two scaling (Notes): the monitors by ŵ's exponent, the runs by (x0, d, ŵ)'s
        self._em = _scale_exponent(np.zeros(0), d if estimate is None else estimate)
        self._e = _scale_exponent(self.x0, d, estimate)
        self._d, self._est = _scaled(d, self._e), _scaled(estimate, self._e)
        self._x0 = np.ldexp(self.x0, -self._e)
        g = self.grid = Grid(self._d, self.points)
        gm = (Grid(_scaled(d, self._em), self.points) if estimate is None and self._em != self._e
              else g if estimate is None else Grid(_scaled(estimate, self._em), self.points))
        # the monitors' energies per decision interval, for each bank of restarts
        self.starts = _bank_starts(nb, sup.restart_blocks)
        self.E = np.zeros((2, nb, len(sup.monitors)))
        sizes = {m.A.shape[0] for m in sup.monitors}
        shared = None
        if sup.law == "cost" and len(sizes) == 1:   # the monitors are the closed loops: one table
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
        self.input_energy = _unscale(_input_energy(g), self._e, where="prepare: ",
                                     what="the disturbance's energy ∫d²")
        # the controller as built: the copies (and whatever reads ŵ) run on the estimate
        self.two_signals = estimate is not None and copies_on_estimate and sup.reads_estimate
        if self.two_signals:
            g = self.grid = Grid(self._d, self.points, estimate=self._est)
        self.estimate, self.two_signals_asked = estimate, copies_on_estimate
        self.loops = sup.switched_loops(estimate_input=self.two_signals)
        static = all(c.is_static for c in sup.candidates)
        if shared is not None and static and sup.K0 is None and estimate is None and gm is g:
            self.tables = shared
        else:
            self.tables = g.tables([_abcd(lp) for lp in self.loops])
        self.xstart = sup.start(self.x0)
        self._xstart = sup.start(self._x0)

    def _energy(self, value, where, what="the energy"):
        """A run's energy in the disturbance's units (refused by name beyond the float range)."""
        return _unscale(float(value), self._e, where=f"{where}: ", what=what)

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
        from ._blocks import Grid

        cls = type(self.sup)
        sup = cls.__new__(cls)
        sup.__dict__.update(self.sup.__dict__)
        other = cls(self.sup.plant, self.sup.candidates, K0=K0)
        sup.K0 = other.K0
        new = Prepared.__new__(Prepared)
        new.__dict__.update(self.__dict__)
        new.sup = sup
        new.two_signals = self.estimate is not None and self.two_signals_asked and sup.reads_estimate
        if new.two_signals != self.two_signals:
            new.grid = Grid(self._d, self.points, estimate=self._est if new.two_signals else None)
        new.loops = sup.switched_loops(estimate_input=new.two_signals)
        new.tables = new.grid.tables([_abcd(lp) for lp in new.loops])
        new.xstart = sup.start(new.x0)
        new._xstart = sup.start(new._x0)
        new._u = None                                   # the control's tables are the realization's
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
            In the units of ŵ² s (see the class's Notes on scale; :meth:`run` decides on the
            scaled signals, so its decisions hold even where these underflow).

        Raises
        ------
        EnergyOverflowError
            If a monitoring signal exceeds the float range in the disturbance's units.
        """
        return _unscale(self._mu(forgetting), self._em, where="mu: ", what="a monitoring signal")

    def _mu(self, forgetting):
        """:meth:`mu` in the monitors' scaled units."""
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
        nm = len(self.sup.gains)
        mu = np.asarray(mu)
        if mu.shape != (self.n_blocks + 1, nm) or not np.issubdtype(mu.dtype, np.floating):
            raise ValueError(f"mu must be a float array of shape {(self.n_blocks + 1, nm)} (one row "
                             f"per decision point, one column per candidate), but found "
                             f"{mu.dtype} of shape {mu.shape}")
        if not np.all(np.isfinite(mu)) or np.any(mu < 0):
            raise ValueError("mu must hold finite, non-negative monitoring signals")
        return self._decide(np.ldexp(mu, -2 * self._em), hysteresis, warmup, min_dwell, sigma0)

    def _decide(self, mu, hysteresis, warmup, min_dwell, sigma0):
        """:meth:`decide` on the monitors' scaled signals."""
        h = as_nonnegative("hysteresis", hysteresis)
        nm = len(self.sup.gains)
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
        e, big, x = g.run(self.tables, sigma[g.block], False, self._xstart)
        change = np.flatnonzero(np.diff(sigma)) + 1
        # the divergence monitor's rule (fdsc._divergence) at the switches and at the end
        limit = _divergence.threshold([lp.A for lp in self.loops], self.loops[0].B, self._xstart, self._d)
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
            with np.errstate(over="ignore"):
                shown = float(np.ldexp(bound, self._e))
            warnings.warn(_divergence.message(f"{where}: ", diverged, float(big[s]) / bound, shown),
                          UnstableRunWarning, stacklevel=3)
        seq = np.r_[sigma[:1], sigma[change]]
        share = np.bincount(sigma, minlength=len(self.loops)) / sigma.size
        with np.errstate(over="ignore"):                  # a diverged run has warned
            x = np.ldexp(x[:self.sup.plant.n_states], self._e)
        return SupervisedRun(self.horizon, None, self._energy(e.sum(), where), self.input_energy,
                             change * self.sup.decide_every, seq, share, x, self.points,
                             np.zeros((0, len(self.loops))), diverged)

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
        mu = self._mu(forgetting)
        _check_mu(mu, "run")
        sigma = self._decide(mu, hysteresis, warmup, min_dwell, sigma0)
        r = self.run_sequence(sigma)
        mu = _unscale(mu, self._em, where="run: ", what="a monitoring signal")
        return SupervisedRun(r.horizon, r.dt, r.energy, r.input_energy, r.switch_times, r.sequence,
                             r.time_share, r.x_final, self.points, mu, r.diverged_at)

    def control(self, sigma) -> dict:
        """How the control input moves along a sequence: its steps at the switches and its RMS.

        Parameters
        ----------
        sigma : (n_blocks,) array_like of int
            One candidate per decision interval (e.g. decided by :meth:`decide`).

        Returns
        -------
        dict
            ``jumps`` ((m,) ndarray: ‖u(t⁺) − u(t⁻)‖ at each switch), ``rms`` (``√(∫‖u‖² / T)``
            over the run) and ``times`` (the switches, s).
        """
        from .realization import control_maps

        sigma = np.asarray(sigma).astype(np.int64)
        sup, g = self.sup, self.grid
        if getattr(self, "_u", None) is None:           # the loops with u as their output, once
            maps = control_maps(sup.plant, sup.candidates, sup.K0, estimate_input=self.two_signals)
            self._u = (maps, g.tables([(lp.A, lp.B, Ku, Du)
                                       for lp, (Ku, Du) in zip(self.loops, maps, strict=True)]))
        maps, u_tables = self._u
        e, _big, _x = g.run(u_tables, sigma[g.block], False, self._xstart)
        change = np.flatnonzero(np.diff(sigma)) + 1
        at = np.searchsorted(g.block, change)             # the first step of each new candidate
        x, jumps, start = self._xstart.copy(), [], 0
        for k, s in zip(change, at, strict=True):
            _e, _b, x = g.run(self.tables, sigma[g.block], False, x, start, s)
            t = float(g.edges[s])
            w = np.atleast_1d(np.asarray(self._d([t]), dtype=float)).ravel()
            if self.two_signals:
                w = np.r_[w, np.atleast_1d(np.asarray(self._est([t]), dtype=float)).ravel()]
            (Kq, Dq), (Kp, Dp) = maps[sigma[k - 1]], maps[sigma[k]]
            jumps.append(float(np.linalg.norm((Kp - Kq) @ x + (Dp - Dq) @ w)))
            start = s
        with np.errstate(over="ignore"):
            jumps = np.ldexp(np.array(jumps), self._e)
            rms = float(np.ldexp(np.sqrt(e.sum() / self.horizon), self._e))
        return {"jumps": jumps, "rms": rms, "times": change * sup.decide_every}

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
        """∫zᵀz of any other fixed controller or loop from x0, by the same exact engine.

        Parameters
        ----------
        loop : LTISystem or Controller
            A closed loop whose first n states are the plant's (its others start at rest), with
            d as its one input: e.g. the closed loop of a gain or controller that is not a
            candidate. A :class:`~fdsc.controller.Controller` is closed on the plant; if it
            reads ŵ and the run has an estimate (with ``copies_on_estimate``), it reads the
            estimate.

        Returns
        -------
        float

        Raises
        ------
        TypeError, DimensionError, ValueError
            If ``loop`` is neither, has fewer states than the plant or more than one input, or
            is not stable.
        """
        from ._blocks import Grid
        from .controller import Controller
        from .plant import LTISystem

        check_type("loop", loop, LTISystem | Controller, "an fdsc.LTISystem or fdsc.Controller")
        g = self.grid
        if isinstance(loop, Controller):
            two = self.estimate is not None and self.two_signals_asked and loop.reads_estimate
            loop = loop.closed_loop(self.sup.plant, estimate_input=two)
            if two and not self.two_signals:
                g = Grid(self._d, self.points, estimate=self._est)
        n = self.x0.size
        if loop.A.shape[0] < n or loop.B.shape[1] != (2 if g.channels is not None and
                                                          loop.B.shape[1] == 2 else 1):
            raise DimensionError(f"loop must have at least the plant's {n} states and one input, but "
                                 f"found A {loop.A.shape} and B {loop.B.shape}")
        worst = float(np.max(np.linalg.eigvals(loop.A).real))
        if worst >= 0:
            raise ValueError(f"loop must be stable, but A has an eigenvalue with real part {worst:.4g}")
        x0 = np.r_[self._x0, np.zeros(loop.A.shape[0] - n)]
        e = float(g.run(g.tables([_abcd(loop)]), 0, False, x0)[0].sum())
        if not math.isfinite(e):
            raise EnergyOverflowError("energy_of: the energy exceeds the float range (about 1.8e308)")
        return self._energy(e, "energy_of")

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
        g, x, total = self.grid, self._xstart.copy(), 0.0
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
        if not math.isfinite(total):
            raise EnergyOverflowError("segment_law: the energy is not finite (a loop too close to the "
                                      "imaginary axis, or a disturbance beyond the float range)")
        return self._energy(total, "segment_law")

    def clairvoyant(self) -> tuple:
        """The clairvoyant per-segment oracle: on each piece of d the candidate with the least
        energy on that piece from the carried-over state.

        Returns
        -------
        energy : float
        choice : list of int
            The candidate on each piece.
        """
        g, x, total, choice = self.grid, self._xstart.copy(), 0.0, []
        for a, b in self.piece_steps():
            best = None
            for i in range(len(self.loops)):
                e, _big, xi = g.run(self.tables, i, False, x, a, b)
                if best is None or e.sum() < best[0]:
                    best = (float(e.sum()), i, xi)
            total += best[0]
            choice.append(best[1])
            x = best[2]
        return self._energy(total, "clairvoyant"), choice
