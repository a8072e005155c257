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

import numpy as np

from ._grid_run import _run_on_grid
from ._validation import as_positive
from .controller import Controller, as_controller, switched_loops
from .decisions import SupervisedRun, _check_mu, _unscale
from .prepared import Prepared
from .realization import band_filter, copies_loop

__all__ = ["Supervisor", "LAWS", "supervise"]

#: The laws a :class:`Supervisor` runs: "cost" (the predictive-cost supervisor, the default) and
#: "band_power" (the gain of the band whose filtered estimate ŵ has the largest fading energy).
LAWS = ("cost", "band_power")


class Supervisor:
    """A switching law that decides on the disturbance estimate ŵ (module docstring).

    Parameters
    ----------
    plant : Plant, control.StateSpace or tuple
        The open-loop plant (one disturbance input, ``B1`` nonzero, so that the estimate
        ŵ = B1⁺(ẋ − A x − B2 u) of the nominal plant is d); a python-control StateSpace has
        the disturbance as its first input and the controls after it.
    gains : sequence of (m_u, n) array_like or Controller
        The candidates (two or more), each stabilizing: state-feedback gains, or controllers
        with states (:class:`fdsc.Controller`; a copy of its loop carries its controller's
        states, and in the direct realization every controller runs on x, the active one sets
        u).
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

        plant = as_plant(plant)          # a python-control StateSpace: its first input is d
        n, mu_ = plant.n_states, plant.n_controls
        if plant.B1.shape[1] != 1:
            raise ValueError("plant must have one disturbance input (B1 of shape (n, 1)), found "
                             f"{plant.B1.shape}")
        if not np.any(plant.B1):
            raise ValueError("plant: B1 is zero, so the disturbance cannot be estimated from "
                             "ẋ − A x − B2 u")
        if isinstance(gains, np.ndarray) and gains.ndim == 2 or not hasattr(gains, "__len__") \
                or isinstance(gains, Controller):
            raise TypeError("gains must be a sequence of gains (each (m_u, n)) or controllers, not one")
        if len(gains) < 2:
            raise ValueError(f"gains must hold at least two candidate gains, but found {len(gains)}")
        candidates = tuple(as_controller(K, plant, f"gains[{k}]") for k, K in enumerate(gains))
        gains = [np.array(c.gain) if c.is_static else c for c in candidates]
        loops = []
        for k, c in enumerate(candidates):
            loop = c.closed_loop(plant)
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
        if K0 is None:                  # every controller runs while another is active: stable alone
            for k, c in enumerate(candidates):
                if c.n_states and np.max(np.linalg.eigvals(c.A).real) >= 0:
                    raise ValueError(f"gains[{k}] is unstable on its own (A_k has an eigenvalue with "
                                     f"real part {np.max(np.linalg.eigvals(c.A).real):.4g}): in the "
                                     "direct realization it runs while inactive; give K0 (copies)")
        self.plant, self.gains, self.loops, self.K0 = plant, gains, loops, K0
        self.candidates = candidates

    @property
    def realization(self) -> str:
        """``"direct"`` (u = K_σ x) or ``"copies"`` (u = K0 x + (K_σ − K0) x̂_σ)."""
        return "direct" if self.K0 is None else "copies"

    def switched_loops(self, *, estimate_input: bool = False) -> list:
        """The loop with each candidate active: the closed loops (direct; with controllers that
        have states, on the shared state of :func:`fdsc.switched_loops`), or the plant with
        every copy, ``[x; c_0; …]`` (copies).

        Parameters
        ----------
        estimate_input : bool, optional
            Two inputs ``[d; ŵ]``: the plant on d, the copies and whatever reads ŵ on ŵ.

        Returns
        -------
        list of LTISystem
        """
        if self.K0 is None:
            if not estimate_input and all(c.is_static for c in self.candidates):
                return list(self.loops)
            return switched_loops(self.plant, self.candidates, estimate_input=estimate_input)
        return [copies_loop(self.plant, self.candidates, self.K0, m, estimate_input=estimate_input)
                for m in range(len(self.candidates))]

    def start(self, x0) -> np.ndarray:
        """The switched loops' initial state for a plant state ``x0``: controllers at rest, the
        copies of the realization from ``x0`` (their controllers at rest).

        Parameters
        ----------
        x0 : (n,) array_like

        Returns
        -------
        ndarray
        """
        x0 = np.asarray(x0, dtype=float)
        ks = [c.n_states for c in self.candidates]
        if self.K0 is None:
            return np.r_[x0, np.zeros(sum(ks))] if any(ks) else x0
        if not any(ks):
            return np.tile(x0, len(self.candidates) + 1)
        return np.concatenate([x0, *[np.r_[x0, np.zeros(k)] for k in ks]])

    def certificate(self):
        """What this law is guaranteed, computed for its candidates (:mod:`fdsc.law_certificate`).

        Returns
        -------
        LawCertificate
            For the realization through copies: whether A + B2 K0 and every candidate's loop
            are Hurwitz (what the argument needs), the assumptions (exact estimate, decisions on
            the grid), and an L2 gain bound for any switching on the grid. For the direct
            realization: not certified here (it needs a dwell time:
            :func:`fdsc.geromel_colaneri_dwell`).

        Examples
        --------
        >>> from fdsc import Plant
        >>> p = Plant([[-1.0]], [[1.0]], [[1.0]], [[1.0], [0.0]], [[0.0], [0.0]], [[0.0], [0.1]])
        >>> cert = Supervisor(p, [[[-1.0]], [[-3.0]]], K0=[[-2.0]]).certificate()
        >>> cert.stable, cert.l2_bound is not None
        (True, True)
        """
        from .law_certificate import LawCertificate, copies_l2_bound

        assumptions = ("the estimate is exact (ŵ = d: a nominal plant, x and ẋ measured)",
                       f"switches only at the decision points (every {self.decide_every:g} s)")
        loops_ok = all(lp.is_hurwitz() for lp in self.loops)
        if self.K0 is None:
            return LawCertificate("direct", {"every candidate's loop is Hurwitz": loops_ok},
                                  assumptions, False, None)
        A0 = self.plant.A + self.plant.B2 @ self.K0
        checks = {"A + B2 K0 is Hurwitz": bool(np.max(np.linalg.eigvals(A0).real) < 0),
                  "every candidate's loop is Hurwitz": loops_ok}
        stable = all(checks.values())
        bound = copies_l2_bound(self.plant, self.candidates, self.K0, self.decide_every) if stable else None
        return LawCertificate("copies", checks, assumptions, stable, bound)

    @property
    def reads_estimate(self) -> bool:
        """Whether the plant's input depends on ŵ (through copies, or a candidate reading ŵ)."""
        return self.K0 is not None or any(c.reads_estimate for c in self.candidates)

    def prepare(self, d, horizon: float, *, x0=None, estimate=None,
                copies_on_estimate: bool = True) -> Prepared:
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
            The estimate ŵ the controller has, if not ``d`` itself: ``d`` plus an error (e.g.
            measurement noise). The monitors are driven by it, and so are the copies of the
            realization and every candidate that reads ŵ (the controller as it can be built);
            the plant feels ``d``.
        copies_on_estimate : bool, optional
            False: only the decisions see ``estimate``; the copies and the candidates run on
            ``d`` (an idealization: no controller has ``d``). Default True.

        Returns
        -------
        Prepared
        """
        return Prepared(self, d, horizon, x0, estimate, copies_on_estimate=copies_on_estimate)

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

        >>> from fdsc import Piecewise, Plant, Sinusoids
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

        return _measured.run_measured(self, d, horizon, dt, derivative=derivative, true_A=true_A, x0=x0,
                                      forgetting=forgetting, hysteresis=hysteresis, warmup=warmup,
                                      min_dwell=min_dwell, sigma0=sigma0)


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
        (each step's energy exact, as in every run of the simulator: the two agree to
        rounding); ``decide_every`` must be a multiple of ``dt``. The decisions are the same
        either way.
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

    >>> from fdsc import Piecewise, Plant, Sinusoids
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
    mu = prep._mu(forgetting)                           # decided scaled (Prepared's Notes)
    _check_mu(mu, "supervise")
    sigma = prep._decide(mu, hysteresis, warmup, min_dwell, sigma0)
    return _run_on_grid(prep, sigma, _unscale(mu, prep._em, where="supervise: ",
                                              what="a monitoring signal"), dt)
