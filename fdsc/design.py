"""An FDSC design: a plant, one state-feedback gain (or controller with states) per frequency
range, the switching law's Q's and a solution of Theorem 1's LMIs for them, in one object that
simulates itself.

The paper's controller (Sec. III, paper eq. (30)) switches between I state-feedback gains
``u = K_σ x``; mode i is meant for disturbances that dominate the range Ω_i, and the law (paper
eq. (31)) picks the mode whose weighted FD-EPF ``[ẋ; x]ᵀ (Ψ_i ⊗ Q_i) [ẋ; x]`` is largest. The
Q's are either given (with the least γ's for which Theorem 1's LMIs, paper eqs. (33)-(34), are
feasible) or designed by paper Remark 4 (paper eq. (53)) around the in-band mode. The LMIs'
solution is called the design's ``certificate`` for short (the paper has no such word); it
certifies only that the LMIs are feasible and bounds nothing on its own (Theorem 1's
statement (1) fails for modes that satisfy them, see the book's chapter on Theorem 1).
"""

from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import ArrayLike

from ._validation import as_count, as_matrix, as_vector, check_hurwitz, check_type
from .bands import Band
from .controller import Controller, as_controller, switched_loops
from .exceptions import DimensionError
from .plant import LTISystem, Plant, as_plant
from .rules import PRINTED, SwitchRule
from .signals import Piecewise, Sinusoids
from .simulate import SimResult, simulate
from .stream import Case
from .switching import DEFAULT_GAMMA_TOL, Theorem1Result, certify_q, design_q
from .synthesis import synthesize, synthesize_hinf

__all__ = ["FDSC"]


def _bands(bands, count=None):
    if not isinstance(bands, list | tuple):
        raise TypeError(f"bands must be a list or tuple of fdsc.Band, one per mode, but found "
                        f"{type(bands).__name__}")
    if len(bands) < 2:
        raise ValueError("bands must list at least two frequency ranges (one per mode), but found "
                         f"{bands!r}")
    for k, b in enumerate(bands):
        check_type(f"bands[{k}]", b, Band)
    if count is not None and len(bands) != count:
        raise ValueError(f"bands must list one range per gain: {count} gains, {len(bands)} bands")
    return tuple(bands)


def _mode_index(name, index, n_modes):
    """``index`` as a mode index in [0, n_modes), or a ValueError naming ``name``."""
    index = as_count(name, index, 0)
    if index >= n_modes:
        raise ValueError(f"{name} must be a mode index in [0, {n_modes}), but found {index}")
    return index


def _gains(gains, plant):
    """Each mode's controller: a read-only (m_u, n) gain when it has no states, else a
    :class:`~fdsc.controller.Controller` (stable on its own); each error names ``gains[k]``."""
    if not isinstance(gains, list | tuple):
        raise TypeError("gains must be a list of (m_u, n) gains or fdsc.Controller objects, but found "
                        f"{type(gains).__name__}")
    out = []
    for k, g in enumerate(gains):
        c = as_controller(g, plant, f"gains[{k}]")
        if c.is_static:
            out.append(c.D)
            continue
        growth = float(np.max(np.linalg.eigvals(c.A).real)) if c.n_states else -np.inf
        if growth >= 0:
            raise ValueError(f"gains[{k}] must be a controller that is stable on its own (its states run "
                             "while another mode is active), but A_k has an eigenvalue with real part "
                             f"{growth:.4g}")
        out.append(c)
    # Theorem 1 (as implemented) needs one input matrix for every mode: a direct path from ŵ to u
    # (F) enters the mode's B and D, so it must be the same in every mode
    Fs = [np.zeros((plant.n_controls, plant.B1.shape[1])) if not isinstance(g, Controller) or g.F is None
          else g.F for g in out]
    for k, F in enumerate(Fs):
        if not np.array_equal(F, Fs[0]):
            raise ValueError(f"gains[{k}] reads ŵ directly with F = {F.tolist()} while gains[0] has "
                             f"F = {Fs[0].tolist()}: Theorem 1's modes must share their input matrices "
                             "(B1 + B2 F, D1 + D2 F), so give every mode the same F, or let ŵ act "
                             "through the controller's states (E) only")
    return tuple(out)


def _check_certificate(cert, modes, bands):
    """Refuse a certificate whose LMIs do not hold for these modes and bands (e.g. another design's)."""
    from .exceptions import VerificationError
    from .switching import _verify

    try:
        _verify(modes, bands, cert.Ps, cert.P, cert.Q, cert.gammas, cert.status, "certificate")
    except (VerificationError, ValueError) as err:
        raise ValueError("certificate must solve Theorem 1's LMIs for these modes and bands (is it "
                         f"another design's?): {err}") from None


def _size(plant, gains):
    """N: the plant's states and those of every controller with states."""
    return plant.n_states + sum(g.n_states for g in gains if isinstance(g, Controller))


def _modes(plant, gains):
    """The modes of ``gains`` (normalized by :func:`_gains`): closed loops, or on the shared state."""
    if all(not isinstance(g, Controller) for g in gains):
        return [plant.closed_loop(K) for K in gains]
    return switched_loops(plant, gains)


def _shared_x0(x0, n, N):
    """An initial plant state (controllers at rest) or shared state, as the shared state."""
    if x0 is None or N == n:
        return x0
    x0 = as_vector("x0", x0)
    if x0.shape == (n,):
        return np.r_[x0, np.zeros(N - n)]
    if x0.shape != (N,):
        raise DimensionError(f"x0 must be the plant's state ({n},) or the shared state ({N},) of plant "
                             f"and controllers, but found shape {x0.shape}")
    return x0


@dataclass(frozen=True)
class FDSC:
    """A frequency-dependent switching controller for one plant, with a solution of Theorem 1's LMIs.

    Build it with :meth:`from_gains` (gains given) or :meth:`synthesize` (gains synthesized on
    the bands); the constructor itself takes a finished certificate.

    Parameters
    ----------
    plant : Plant
        The open-loop plant (any form :func:`~fdsc.plant.as_plant` accepts).
    gains : sequence of (m_u, n) array_like or Controller
        Mode i's controller: a gain K_i (the paper's case) or a :class:`~fdsc.controller.Controller`
        with states, stable on its own; stored as the gain when it has no states.
    bands : sequence of Band
        Ω_i, the range of mode i (real Ψ: LF, HF or entire; Theorem 1 and the law need it).
    in_band : int
        Index of the in-band mode (0-based): the mode for the range the design cares most about;
        paper Remark 4 minimizes its γ.
    certificate : Theorem1Result
        Theorem 1 for the modes (:attr:`modes`) on ``bands``; its Q's, of the size of the modes'
        state, are the law's.
    synthesis : tuple of SynthesisResult, optional
        The synthesis results, when the gains were synthesized.

    Raises
    ------
    TypeError
        If ``gains`` is not a list or tuple, a band is not a :class:`~fdsc.bands.Band`, or
        ``certificate`` is not a :class:`~fdsc.switching.Theorem1Result`.
    ValueError
        If fewer than two bands are given, the counts of gains, bands and the certificate's Q's
        differ, ``in_band`` is not a mode index, a controller with states is unstable on its
        own, the modes' direct gains from ŵ differ, or ``certificate`` does not solve Theorem 1's
        LMIs for these modes and bands.
    DimensionError
        If a gain is not of shape ``(m_u, n)``, a controller does not fit the plant, or a Q is
        not of the modes' state size.

    Attributes
    ----------
    Q : tuple of (N, N) ndarray
        The Q_i of the law (from the certificate), on the modes' state (N = n for gains).
    gammas : (I,) ndarray
        γ_i for which Theorem 1's LMIs are feasible (not a bound on the switched loop).
    modes : tuple of LTISystem
        The closed loops ``(A + B2 K_i, B1, C + D2 K_i, D1)`` for gains; with controllers that
        have states, mode i on the shared state of :func:`~fdsc.controller.switched_loops`.
    controllers : tuple of Controller
        Every mode's controller, gains as controllers without states.

    Notes
    -----
    The controller ``u = K_σ(t) x`` of paper eq. (30) with the law of paper eq. (31); the
    certificate holds the LMIs of Theorem 1, paper eqs. (33)-(34). The design knows nothing of
    the paper's example: any plant and any real-Ψ bands.

    Controllers with states (an extension; the paper switches gains): every controller runs all
    the time on x, the active one sets u, so each mode is an LTI system on the shared state
    ``ξ = [x; x_k,1; …; x_k,I]`` of size N = n + Σ k_i, and Theorem 1's LMIs and the law read
    ``[ξ̇; ξ]`` with N×N Q's (the controllers' states are the controller's own, so the law can
    read them). A controller that reads ŵ gets the exact estimate ŵ = d; its direct gain F from
    ŵ to u must be the same in every mode (Theorem 1's modes share their input matrices). The states of an
    inactive controller are driven by x but do not act, so each must be stable on its own.

    Examples
    --------
    >>> from fdsc import Band, Plant, Sinusoids, time_grid
    >>> plant = Plant([[0.0, 1.0], [-1.0, -0.2]], [[0.0], [1.0]], [[0.0], [1.0]],
    ...               [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.1]])
    >>> ctrl = FDSC.synthesize(plant, [Band.lf(1.0), Band.hf(10.0)], in_band=1)
    >>> ctrl.n_modes, bool(np.all(ctrl.gammas > 0))
    (2, True)
    >>> run = ctrl.simulate(Sinusoids([1.0], [30.0]), time_grid(2.0, 1e-3))
    >>> run.z.shape
    (2001, 2)
    """

    plant: Plant
    gains: tuple
    bands: tuple
    in_band: int
    certificate: Theorem1Result
    synthesis: tuple | None = None

    def __post_init__(self):
        plant = as_plant(self.plant)
        gains = _gains(self.gains, plant)
        bands = _bands(self.bands, len(gains))
        in_band = _mode_index("in_band", self.in_band, len(gains))
        check_type("certificate", self.certificate, Theorem1Result)
        if len(self.certificate.Q) != len(gains):
            raise ValueError(f"certificate must hold one Q per mode ({len(gains)}), but holds "
                             f"{len(self.certificate.Q)}")
        N = _size(plant, gains)
        for k, q in enumerate(self.certificate.Q):
            if np.shape(q) != (N, N):
                raise DimensionError(f"certificate.Q[{k}] must be ({N}, {N}), the modes' state size, "
                                     f"but has shape {np.shape(q)}")
        _check_certificate(self.certificate, _modes(plant, gains), bands)
        if self.synthesis is not None:
            from .synthesis import SynthesisResult

            if not isinstance(self.synthesis, tuple) or len(self.synthesis) != len(gains) or not all(
                    isinstance(r, SynthesisResult) for r in self.synthesis):
                raise TypeError("synthesis must be None or a tuple of one fdsc.SynthesisResult per mode, "
                                f"but found {self.synthesis!r:.80}")
        for name, val in (("plant", plant), ("gains", gains), ("bands", bands), ("in_band", in_band)):
            object.__setattr__(self, name, val)

    @classmethod
    def from_gains(cls, plant: Plant | tuple, gains: list | tuple, bands: list | tuple, in_band: int, *,
                   Q: list | tuple | None = None, gamma_tol: float = DEFAULT_GAMMA_TOL,
                   n_disturbances: int | None = None) -> "FDSC":
        """Build the design from given gains: certify given Q's, or design them.

        Parameters
        ----------
        plant : Plant, control.StateSpace or tuple
            The open-loop plant (see :func:`~fdsc.plant.as_plant`).
        gains : sequence of (m_u, n) array_like or Controller
            Mode i's controller, one per mode (each must stabilize the plant): a gain K_i, or a
            :class:`~fdsc.controller.Controller` with states (stable on its own; the modes then
            live on the shared state, see the class's Notes).
        bands : sequence of Band
            Ω_i of each mode (real Ψ).
        in_band : int
            Index of the in-band mode (0-based).
        Q : sequence of (N, N) array_like, optional
            The law's Q_i on the modes' state (N = n for gains). Given: the least γ's for which
            Theorem 1's LMIs are feasible with them, by :func:`~fdsc.switching.certify_q`. Omitted:
            designed by paper Remark 4 (:func:`~fdsc.switching.design_q`).
        gamma_tol : float, optional
            γ_tol of paper Remark 4 (used only when Q is omitted).
        n_disturbances : int, optional
            Number of disturbance inputs of a python-control ``StateSpace`` plant, its first
            inputs (default 1, as everywhere: :func:`~fdsc.plant.as_plant`).

        Returns
        -------
        FDSC

        Raises
        ------
        UnstableError
            If a controller does not stabilize the plant.
        InfeasibleError
            If Theorem 1's LMIs are infeasible for the given Q's, or no Q's exist for this γ_tol.
        SolverError
            If a solve fails.
        DimensionError
            If a gain is not of shape ``(m_u, n)`` (the message names ``gains[k]``).
        TypeError, ValueError
            On invalid arguments (see the class).

        Notes
        -----
        Given Q's get the least γ's for which Theorem 1's LMIs (paper eqs. (33)-(34)) are
        feasible; omitted ones are designed by paper Remark 4, paper eq. (53).
        """
        plant = as_plant(plant, n_disturbances=n_disturbances)
        gains = _gains(gains, plant)
        bands = _bands(bands, len(gains))
        in_band = _mode_index("in_band", in_band, len(gains))
        for k, g in enumerate(gains):
            alone = g.closed_loop(plant) if isinstance(g, Controller) else plant.closed_loop(g)
            check_hurwitz(f"the closed loop of gains[{k}]", alone.A, "an FDSC mode")
        modes = _modes(plant, gains)
        N = _size(plant, gains)
        if Q is not None:
            if not isinstance(Q, list | tuple) or len(Q) != len(gains):
                raise ValueError(f"Q must list one (N, N) matrix per mode ({len(gains)}), but found "
                                 f"{Q!r:.60}")
            Q = [as_matrix(f"Q[{k}]", q, (N, N)) for k, q in enumerate(Q)]
        if Q is None:
            cert = design_q(modes, bands, in_band, gamma_tol=gamma_tol)
        else:
            cert = certify_q(modes, bands, Q)
            # certify_q solves with Q/s and scales back, which changes the last bits; the law
            # must use the Q's the user gave (the certificate holds for them: its LMIs are
            # verified with a margin far above that rounding)
            cert = replace(cert, Q=[np.array(q, dtype=float) for q in Q])
        return cls(plant, tuple(gains), bands, in_band, cert)

    @classmethod
    def synthesize(cls, plant: Plant | tuple, bands: list | tuple, in_band: int, *,
                   Q: list | tuple | None = None, gamma_tol: float = DEFAULT_GAMMA_TOL,
                   n_disturbances: int | None = None, **synthesis_options) -> "FDSC":
        """Synthesize one gain per band, then build the design as :meth:`from_gains` does.

        Each gain minimizes the certified gain γ on its band (:func:`~fdsc.synthesis.synthesize`;
        :func:`~fdsc.synthesis.synthesize_hinf` for the entire range) and stabilizes the plant.

        Parameters
        ----------
        plant : Plant, control.StateSpace or tuple
            The open-loop plant.
        bands : sequence of Band
            Ω_i of each mode (real Ψ: LF, HF or entire).
        in_band : int
            Index of the in-band mode (0-based).
        Q : sequence of (n, n) array_like, optional
            Given Q's to certify (default: designed by paper Remark 4).
        gamma_tol : float, optional
            γ_tol of paper Remark 4.
        n_disturbances : int, optional
            Number of disturbance inputs of a python-control ``StateSpace`` plant, its first
            inputs (default 1, as everywhere: :func:`~fdsc.plant.as_plant`).
        **synthesis_options
            Passed to :func:`~fdsc.synthesis.synthesize` for the band-limited gains
            (``epsilon``, ``sigma``, ``margin``, ``stability``).

        Returns
        -------
        FDSC

        Raises
        ------
        InfeasibleError
            If a synthesis or Theorem 1 is infeasible.
        SolverError
            If a solve fails.
        VerificationError
            If a synthesized gain fails its a-posteriori check.
        TypeError, ValueError
            On invalid arguments (see the class).
        """
        plant = as_plant(plant, n_disturbances=n_disturbances)
        bands = _bands(bands)
        results = tuple(synthesize_hinf(plant) if b.kind == "EF" else
                        synthesize(plant, b, **synthesis_options) for b in bands)
        made = cls.from_gains(plant, [r.K for r in results], bands, in_band, Q=Q, gamma_tol=gamma_tol)
        return cls(made.plant, made.gains, made.bands, made.in_band, made.certificate, results)

    @property
    def n_modes(self) -> int:
        """Number of modes I."""
        return len(self.gains)

    @property
    def controllers(self) -> tuple:
        """Every mode's controller (gains as controllers without states), a tuple of Controller."""
        return tuple(g if isinstance(g, Controller) else Controller.static(g) for g in self.gains)

    @property
    def n_states(self) -> int:
        """Size N of the modes' state: n for gains, n + Σ k_i with controllers that have states."""
        return _size(self.plant, self.gains)

    @property
    def Q(self) -> tuple:
        """The law's Q_i (from the certificate), a tuple of (n, n) ndarray."""
        return tuple(np.asarray(q) for q in self.certificate.Q)

    @property
    def gammas(self) -> np.ndarray:
        """γ_i for which Theorem 1's LMIs are feasible, an (I,) ndarray."""
        return np.asarray(self.certificate.gammas)

    @property
    def modes(self) -> tuple:
        """The modes (tuple of :class:`~fdsc.plant.LTISystem`): the closed loops of the gains,
        or, with controllers that have states, on the shared state (class Notes)."""
        return tuple(_modes(self.plant, self.gains))

    def mode(self, i: int) -> LTISystem:
        """Closed loop of mode ``i``'s controller alone, the fixed controller (state x, or
        ``[x; x_k,i]`` for a controller with states).

        Parameters
        ----------
        i : int
            Mode index (0-based).

        Returns
        -------
        LTISystem

        Raises
        ------
        ValueError
            If ``i`` is not a mode index in [0, ``n_modes``) (the message names ``i``).
        """
        i = _mode_index("i", i, self.n_modes)
        return self.controllers[i].closed_loop(self.plant)

    def simulate(self, d: Sinusoids | Piecewise, t: ArrayLike, *, x0: ArrayLike | None = None,
                 law: str = "previous", sigma0: int = 0, rule: SwitchRule = PRINTED,
                 kernel: str = "numba", **options) -> SimResult:
        """Simulate the switched closed loop under the law (paper eq. (31)) with this design's Q's.

        Parameters
        ----------
        d : Sinusoids or Piecewise
            The scalar disturbance.
        t : (N,) array_like
            Uniform time grid (see :func:`~fdsc.simulate.time_grid`).
        x0 : (n,) or (N,) array_like, optional
            Initial plant state, the controllers at rest, or the modes' state (default 0).
        law : {"previous", "candidate"}, optional
            How ẋ enters the law (see :data:`fdsc.simulate.LAWS`).
        sigma0 : int, optional
            Mode active before t = 0.
        rule : SwitchRule, optional
            Hysteresis, minimum dwell time and/or moving window applied to the law
            (:class:`~fdsc.rules.SwitchRule`; default the printed argmax).
        kernel : {"numba", "numpy"}, optional
            Compiled kernel or its NumPy reference.
        **options
            Further keyword arguments of :func:`~fdsc.simulate.simulate` (``max_memory``).

        Returns
        -------
        SimResult
            Its states are the modes' state (x, then the controllers' states when they have any).

        Raises
        ------
        DimensionError
            If ``x0`` is neither of the plant's nor of the modes' state size.
        ValueError, TypeError, SingularFrequencyError, MemoryLimitError, UnstableError
            As :func:`~fdsc.simulate.simulate` raises them.

        Warns
        -----
        UnstableRunWarning
            As :func:`~fdsc.simulate.simulate` warns: in particular if the divergence monitor
            (:mod:`fdsc._divergence`) finds the switched run diverging.
        """
        x0 = _shared_x0(x0, self.plant.n_states, self.n_states)
        return simulate(list(self.modes), d, t, x0=x0, law_bands=list(self.bands),
                        law_Q=list(self.Q), law=law, sigma0=sigma0, rule=rule, kernel=kernel,
                        **options)

    def supervisor(self, law: str = "band_power", *, K0="lqr", decide_every: float = 0.1,
                   restart: float = 20.0):
        """This design's gains switched by a law on the disturbance estimate instead of the
        printed law (:class:`~fdsc.supervisor.Supervisor`).

        Parameters
        ----------
        law : {"band_power", "cost"}, optional
            ``"band_power"`` (default): the gain of the band of :attr:`bands` that holds most
            of the estimate's recent power, the paper's frequency selectiveness applied to the
            disturbance; ``"cost"``: the predictive-cost supervisor over the design's gains.
        K0 : "lqr", None or (m_u, n) array_like, optional
            The realization: ``"lqr"`` (default) through copies around the plant's LQR gain
            (:func:`~fdsc.realization.lqr_gain`), None direct (``u = K_σ x``), or a gain.
        decide_every, restart : float, optional
            See :class:`~fdsc.supervisor.Supervisor`.

        Returns
        -------
        Supervisor
            Run it with ``.run`` (exact, on the exact estimate), ``.run_measured`` (on sampled
            measurements) or :func:`fdsc.supervise_batch`.

        Raises
        ------
        ValueError
            As :class:`~fdsc.supervisor.Supervisor` raises them (e.g. a plant with more than one
            disturbance input, or an unknown law).

        Examples
        --------
        >>> from fdsc import Band, Piecewise, Plant, Sinusoids
        >>> plant = Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
        ...               [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.1]])
        >>> ctrl = FDSC.from_gains(plant, [[[-21.85, -22.27]], [[0.495, -1.473]]],
        ...                        [Band.lf(2.0), Band.hf(8.0)], in_band=1)
        >>> d = Piecewise([0.0, 60.0, 200.0], [Sinusoids([1.0], [0.2]), Sinusoids([1.0], [12.0])])
        >>> ctrl.supervisor().run(d, 120.0, warmup=5.0).sequence.tolist()
        [0, 1]
        """
        from .realization import lqr_gain
        from .supervisor import Supervisor

        if isinstance(K0, str):
            if K0 != "lqr":
                raise ValueError(f"K0 must be 'lqr', None or a gain, but found {K0!r}")
            K0 = lqr_gain(self.plant)
        bands = list(self.bands) if law == "band_power" else None
        return Supervisor(self.plant, list(self.controllers) if self.n_states > self.plant.n_states
                          else list(self.gains), law=law, bands=bands, decide_every=decide_every,
                          restart=restart, K0=K0)

    def case(self, d, horizon: float, dt: float, *, x0: ArrayLike | None = None,
             law: str = "previous", sigma0: int = 0, rule: SwitchRule = PRINTED,
             label: object = None) -> Case:
        """The switched closed loop under this design's law as one :class:`~fdsc.stream.Case`
        of a batch (:func:`~fdsc.stream.simulate_batch`) or a streamed run.

        Parameters
        ----------
        d : Sinusoids, Piecewise or Sampled
            The scalar disturbance.
        horizon, dt : float
            End time and step in s (the horizon a multiple of dt).
        x0 : (n,) or (N,) array_like, optional
            Initial plant state, the controllers at rest, or the modes' state (default 0).
        law : {"previous", "candidate"}, optional
            How ẋ enters the law (see :data:`fdsc.simulate.LAWS`).
        sigma0 : int, optional
            Mode active before t = 0.
        rule : SwitchRule, optional
            Hysteresis, minimum dwell time and/or moving window (default the printed argmax).
        label : object, optional
            Kept with the case for the caller.

        Returns
        -------
        Case
            Checked when the batch runs (errors name the case there).

        Examples
        --------
        >>> from fdsc import Band, Plant, Sinusoids, simulate_batch
        >>> plant = Plant([[-1.0]], [[1.0]], [[1.0]], [[1.0], [0.0]], [[0.0], [0.0]], [[0.0], [0.1]])
        >>> ctrl = FDSC.from_gains(plant, [[[-0.5]], [[-2.0]]], [Band.lf(1.0), Band.hf(5.0)], in_band=1)
        >>> runs = simulate_batch([ctrl.case(Sinusoids([1.0], [w]), 20.0, 1e-3) for w in (0.3, 30.0)])
        >>> np.round(runs.time_share[:, 1], 2)          # share of the HF mode: slow tone, fast tone
        array([0.04, 0.89])
        """
        x0 = _shared_x0(x0, self.plant.n_states, self.n_states)
        return Case(list(self.modes), d, horizon, dt, x0=x0, law_bands=list(self.bands),
                    law_Q=list(self.Q), law=law, sigma0=sigma0, rule=rule, label=label)
