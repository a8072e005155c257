"""State-feedback controllers with states: a static gain is the controller without states.

A controller reads the plant's state x and, optionally, the disturbance estimate ŵ, and sets
the control input u::

    dx_k/dt = A_k x_k + B_k x + E_k ŵ,        u = C_k x_k + D_k x + F_k ŵ.

A gain K is ``Controller.static(K)`` (no states, D_k = K). With the plant of paper eq. (10) the
closed loop has the state ``[x; x_k]`` and, under the exact estimate ŵ = d (a nominal plant
with x and ẋ measured: :mod:`fdsc.supervisor`),

    A_cl = [[A + B2 D_k, B2 C_k], [B_k, A_k]],      B_cl = [[B1 + B2 F_k], [E_k]],
    C_cl = [C + D2 D_k, D2 C_k],                    D_cl = D1 + D2 F_k,

a map from d to z like any other (:meth:`Controller.closed_loop`), so band peaks, Lemma 1 and
the simulators take it as they take the closed loop of a gain. Several controllers switched on
one plant share the state ``[x; x_k,1; …; x_k,I]``: every controller runs on x (and ŵ), the
active one sets u (:func:`switched_loops`); for gains the state is x alone.

:func:`as_controller` is the one boundary: a Controller, a gain (array_like) or a
continuous-time python-control ``StateSpace`` from x to u.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ._validation import as_matrix
from .exceptions import DimensionError

__all__ = ["Controller", "as_controller", "switched_loops"]


@dataclass(frozen=True, eq=False)
class Controller:
    """A linear controller from the plant's state x (and the estimate ŵ) to u (module docstring).

    Parameters
    ----------
    A : (k, k) array_like
        The controller's state matrix (k ≥ 0 states; ``np.zeros((0, 0))`` for none).
    B : (k, n) array_like
        How x drives the controller's states.
    C : (m_u, k) array_like
        How the controller's states set u.
    D : (m_u, n) array_like
        The direct gain from x to u.
    E : (k, n_d) array_like, optional
        How ŵ drives the controller's states (default none: the controller does not read ŵ).
    F : (m_u, n_d) array_like, optional
        The direct gain from ŵ to u (default none).
    name : str, optional
        A label for tables and error messages.

    Raises
    ------
    DimensionError
        If the shapes do not fit together.
    ValueError
        If an entry is NaN, infinite or complex.

    Examples
    --------
    A first-order filter on x: u = K₁ x + ΔK (x − x_f), ẋ_f = ω_c (x − x_f), so that u ≈ K₁ x
    well below ω_c and u ≈ (K₁ + ΔK) x well above it:

    >>> K1, dK, wc = np.array([[-1.0]]), np.array([[-3.0]]), 2.0
    >>> c = Controller(-wc * np.eye(1), wc * np.eye(1), -dK, K1 + dK, name="filtered")   # .filtered
    >>> c.n_states, c.is_static, np.round(c.response([0.0, 1e4])[:, 0, 0].real, 3).tolist()
    (1, False, [-1.0, -4.0])
    """

    A: np.ndarray
    B: np.ndarray
    C: np.ndarray
    D: np.ndarray
    E: np.ndarray | None = None
    F: np.ndarray | None = None
    name: str = ""

    def __post_init__(self):
        A = np.asarray(self.A, dtype=float) if np.size(self.A) == 0 else self.A
        D = as_matrix("D", self.D)
        m, n = D.shape
        if np.size(A) == 0:
            A = np.zeros((0, 0))
            B = np.zeros((0, n)) if np.size(self.B) == 0 else as_matrix("B", self.B, (0, n))
            C = np.zeros((m, 0)) if np.size(self.C) == 0 else as_matrix("C", self.C, (m, 0))
        else:
            A = as_matrix("A", A, square=True)
            k = A.shape[0]
            B = as_matrix("B", self.B, (k, n))
            C = as_matrix("C", self.C, (m, k))
        k = A.shape[0]
        if (self.E is None) != (self.F is None):
            raise ValueError("E and F go together: give both (the controller reads ŵ) or neither")
        E = F = None
        if self.E is not None:
            F = as_matrix("F", self.F, (m, None))
            nd = F.shape[1]
            E = np.zeros((0, nd)) if k == 0 and np.size(self.E) == 0 else as_matrix("E", self.E, (k, nd))
        for key, val in (("A", A), ("B", B), ("C", C), ("D", D), ("E", E), ("F", F)):
            if val is not None:
                val = np.array(val, dtype=float)
                val.setflags(write=False)
            object.__setattr__(self, key, val)
        if not isinstance(self.name, str):
            raise TypeError(f"name must be a str, but found {type(self.name).__name__}")

    @classmethod
    def static(cls, K: ArrayLike, name: str = "") -> Controller:
        """The static gain ``u = K x`` as a controller without states.

        Parameters
        ----------
        K : (m_u, n) array_like
        name : str, optional

        Returns
        -------
        Controller

        Examples
        --------
        >>> Controller.static([[1.0, 2.0]]).gain.tolist()
        [[1.0, 2.0]]
        """
        K = as_matrix("K", K)
        return cls(np.zeros((0, 0)), np.zeros((0, K.shape[1])), np.zeros((K.shape[0], 0)), K, name=name)

    @classmethod
    def filtered(cls, K_low: ArrayLike, K_high: ArrayLike, corner: float, name: str = "") -> Controller:
        """``u = K_low x + (K_high − K_low)(x − x_f)``, ``ẋ_f = ω_c (x − x_f)``: one first-order
        filter state per plant state, the gain K_low well below the corner ω_c and K_high well
        above it.

        Parameters
        ----------
        K_low, K_high : (m_u, n) array_like
        corner : float
            ω_c > 0 (rad/s).
        name : str, optional

        Returns
        -------
        Controller

        Examples
        --------
        >>> c = Controller.filtered([[-1.0]], [[-4.0]], 2.0)
        >>> np.round(c.response([1e-4, 1e4])[:, 0, 0].real, 3).tolist()
        [-1.0, -4.0]
        """
        from ._validation import as_positive

        K_low, K_high = as_matrix("K_low", K_low), as_matrix("K_high", K_high, np.shape(K_low))
        wc = as_positive("corner", corner)
        n = K_low.shape[1]
        return cls(-wc * np.eye(n), wc * np.eye(n), K_low - K_high, K_high, name=name)

    @staticmethod
    def filtered_parameters(c: Controller) -> tuple:
        """``(K_low, K_high, ω_c)`` of a controller made by :meth:`filtered`.

        Parameters
        ----------
        c : Controller

        Returns
        -------
        tuple

        Raises
        ------
        ValueError
            If ``c`` does not have that structure.
        """
        n = c.n_inputs
        if c.n_states != n or c.reads_estimate or not n:
            raise ValueError(f"{c!r} is not a filtered controller (n filter states, no ŵ)")
        wc = -float(c.A[0, 0])
        if not (wc > 0 and np.allclose(c.A, -wc * np.eye(n)) and np.allclose(c.B, wc * np.eye(n))):
            raise ValueError(f"{c!r} is not a filtered controller (A = −ω_c I, B = ω_c I)")
        return c.D + c.C, c.D.copy(), wc

    @property
    def n_states(self) -> int:
        """The controller's own states k."""
        return self.A.shape[0]

    @property
    def n_inputs(self) -> int:
        """The plant states it reads, n."""
        return self.D.shape[1]

    @property
    def n_controls(self) -> int:
        """The control inputs it sets, m_u."""
        return self.D.shape[0]

    @property
    def reads_estimate(self) -> bool:
        """Whether it reads the disturbance estimate ŵ (E or F not zero)."""
        return self.F is not None and (bool(np.any(self.E)) or bool(np.any(self.F)))

    @property
    def is_static(self) -> bool:
        """A gain: no states and no ŵ."""
        return self.n_states == 0 and not self.reads_estimate

    @property
    def gain(self) -> np.ndarray:
        """The gain K of a static controller.

        Raises
        ------
        ValueError
            If the controller has states or reads ŵ.
        """
        if not self.is_static:
            what = f"{self.n_states} states" + (" and reads ŵ" if self.reads_estimate else "")
            label = f" {self.name!r}" if self.name else ""
            raise ValueError(f"controller{label} has {what}: it is not a gain")
        return self.D

    def poles(self) -> np.ndarray:
        """Eigenvalues of A_k (the controller's own poles), sorted by real part."""
        ev = np.linalg.eigvals(self.A) if self.n_states else np.zeros(0)
        return ev[np.argsort(ev.real)]

    def response(self, omega: ArrayLike) -> np.ndarray:
        """The controller's frequency response from x to u, ``D_k + C_k (jω − A_k)⁻¹ B_k``.

        Parameters
        ----------
        omega : (N,) array_like
            Frequencies (rad/s).

        Returns
        -------
        (N, m_u, n) complex ndarray
        """
        w = np.atleast_1d(np.asarray(omega, dtype=float))
        out = np.broadcast_to(self.D.astype(complex), (w.size, *self.D.shape)).copy()
        if self.n_states:
            M = 1j * w[:, None, None] * np.eye(self.n_states)[None] - self.A[None]
            out += self.C[None] @ np.linalg.solve(M, np.broadcast_to(self.B, (w.size, *self.B.shape)))
        return out

    def size(self) -> float:
        """The largest gain of the controller from x to u over frequency, a measure of how hard
        it drives u.

        Returns
        -------
        float
            ``sup_ω σ_max(D_k + C_k (jω − A_k)⁻¹ B_k)`` over ω ≥ 0 and ∞, found as
            :func:`fdsc.band_peak` finds a peak (a grid through the resonances of A_k, refined
            around its maxima; A_k need not be stable); ``inf`` if A_k has an eigenvalue on the
            imaginary axis (the gain is unbounded there).

        Examples
        --------
        A resonance of damping 10⁻⁴ between any grid's points: 1 / (2ζ) = 5000 at ω ≈ 3.3.

        >>> zeta, w0 = 1e-4, 3.3
        >>> c = Controller([[0.0, 1.0], [-w0**2, -2 * zeta * w0]], [[0.0], [1.0]], [[w0**2, 0.0]],
        ...                [[0.0]])
        >>> round(c.size())
        5000
        """
        if self.n_states == 0:
            return float(np.linalg.norm(self.D, 2)) if self.D.size else 0.0
        from .bands import Band
        from .frequency import DEFAULT_GRID_POINTS, POLE_RTOL, _peak
        from .plant import LTISystem

        ev = np.linalg.eigvals(self.A)
        if np.any(np.abs(ev.real) <= POLE_RTOL * np.maximum(1.0, np.abs(ev))):
            return float("inf")
        sys = LTISystem(self.A, self.B, self.C, self.D)
        return float(_peak(sys, Band.entire(), ev, DEFAULT_GRID_POINTS, 1e-10).gamma)

    def _check(self, plant, name):
        if self.D.shape != (plant.n_controls, plant.n_states):
            raise DimensionError(f"{name} must map the plant's {plant.n_states} states to its "
                                 f"{plant.n_controls} controls (D of shape "
                                 f"{(plant.n_controls, plant.n_states)}), but D has shape {self.D.shape}")
        if self.F is not None and self.F.shape[1] != plant.B1.shape[1]:
            raise DimensionError(f"{name} reads ŵ of {self.F.shape[1]} entries, but the plant has "
                                 f"{plant.B1.shape[1]} disturbance inputs")

    def control_map(self, plant) -> tuple:
        """``(Cu, Du)`` with ``u = Cu [x; x_k] + Du d`` on the closed loop's state, under the
        exact estimate.

        Parameters
        ----------
        plant : Plant

        Returns
        -------
        Cu : (m_u, n + k) ndarray
        Du : (m_u, n_d) ndarray
        """
        self._check(plant, "controller")
        F = np.zeros((plant.n_controls, plant.B1.shape[1])) if self.F is None else self.F
        return np.hstack([self.D, self.C]), F

    def closed_loop(self, plant, *, estimate_input: bool = False):
        """The closed loop from d to z, state ``[x; x_k]``, under the exact estimate ŵ = d
        (module docstring).

        Parameters
        ----------
        plant : Plant
        estimate_input : bool, optional
            False (default): one input, d (ŵ = d). True: two inputs ``[d; ŵ]``, the estimate
            the controller reads apart from the disturbance the plant feels (for an estimate
            with errors; a controller that does not read ŵ has a zero second column).

        Returns
        -------
        LTISystem

        Raises
        ------
        DimensionError
            If the controller does not fit the plant.

        Examples
        --------
        >>> from fdsc import Plant
        >>> p = Plant([[1.0]], [[1.0]], [[1.0]], [[1.0], [0.0]], [[0.0], [0.0]], [[0.0], [1.0]])
        >>> Controller.static([[-3.0]]).closed_loop(p).A.tolist()
        [[-2.0]]
        >>> Controller([[-1.0]], [[1.0]], [[-2.0]], [[-3.0]]).closed_loop(p).A.tolist()
        [[-2.0, -2.0], [1.0, -1.0]]
        """
        from .plant import LTISystem

        self._check(plant, "controller")
        A, B1, B2, C, D1, D2 = plant.A, plant.B1, plant.B2, plant.C, plant.D1, plant.D2
        if self.is_static and not estimate_input:
            return LTISystem(A + B2 @ self.D, B1, C + D2 @ self.D, D1)
        k = self.n_states
        F = np.zeros((B2.shape[1], B1.shape[1])) if self.F is None else self.F
        E = np.zeros((k, B1.shape[1])) if self.E is None else self.E
        Acl = np.block([[A + B2 @ self.D, B2 @ self.C], [self.B, self.A]])
        Ccl = np.hstack([C + D2 @ self.D, D2 @ self.C])
        if estimate_input:
            Bcl = np.block([[B1, B2 @ F], [np.zeros_like(E), E]])
            return LTISystem(Acl, Bcl, Ccl, np.hstack([D1, D2 @ F]))
        return LTISystem(Acl, np.vstack([B1 + B2 @ F, E]), Ccl, D1 + D2 @ F)

    def __repr__(self) -> str:
        label = f"{self.name!r}, " if self.name else ""
        return (f"Controller({label}{self.n_states} states, {self.n_inputs} → {self.n_controls}"
                + (", reads ŵ" if self.reads_estimate else "") + ")")


def as_controller(obj, plant=None, name: str = "controller") -> Controller:
    """A controller from what a user may give: the one boundary.

    Parameters
    ----------
    obj : Controller, (m_u, n) array_like or control.StateSpace
        A controller (returned as is), a gain K (u = K x), or a continuous-time python-control
        ``StateSpace`` whose inputs are the plant's states and outputs its controls.
    plant : Plant, optional
        When given, the controller is checked against it.
    name : str, optional
        The argument's name, for error messages.

    Returns
    -------
    Controller

    Raises
    ------
    TypeError
        If ``obj`` is none of these.
    DimensionError
        If it does not fit the plant.

    Examples
    --------
    >>> as_controller([[1.0, 0.0]]).is_static
    True
    """
    from .plant import LTISystem, Plant, _statespace_matrices

    if isinstance(obj, Controller):
        c = obj
    elif isinstance(obj, LTISystem | Plant):
        raise TypeError(f"{name} must be a gain, an fdsc.Controller or a StateSpace from x to u, but "
                        f"found an {type(obj).__name__}")
    else:
        abcd = _statespace_matrices(obj, name, static_ok=True)
        if abcd is not None:
            A, B, C, D = (np.asarray(a, dtype=float) for a in abcd)
            try:
                c = Controller(A, B, C, D)
            except ValueError as exc:                   # DimensionError included: name the argument
                raise type(exc)(f"{name} (a StateSpace from x to u): its {exc}") from None
        else:
            if isinstance(obj, str | bytes | dict) or obj is None:
                raise TypeError(f"{name} must be a gain (m_u, n), an fdsc.Controller or a StateSpace "
                                f"from x to u, but found {type(obj).__name__}")
            shape = None if plant is None else (plant.n_controls, plant.n_states)
            c = Controller.static(as_matrix(name, obj, shape))
    if plant is not None:
        c._check(plant, name)
    return c


def switched_loops(plant, controllers, *, estimate_input: bool = False) -> list:
    """The closed loops of several controllers switched on one plant: every controller runs on
    x (and ŵ = d), the active one sets u (module docstring).

    Parameters
    ----------
    plant : Plant
    controllers : sequence of Controller or gain
        One per mode.
    estimate_input : bool, optional
        Two inputs ``[d; ŵ]`` instead of d alone (see :meth:`Controller.closed_loop`).

    Returns
    -------
    list of LTISystem
        Mode i with controller i active, on the shared state ``[x; x_k,1; …; x_k,I]`` (x alone
        for gains: then mode i is ``plant.closed_loop(K_i)``).

    Raises
    ------
    TypeError, DimensionError
        As :func:`as_controller` raises them, naming ``controllers[i]``.
    ValueError
        If ``controllers`` is empty, or a controller with states is unstable on its own (its
        states would grow while it is not in the loop).

    Examples
    --------
    >>> from fdsc import Plant
    >>> p = Plant([[1.0]], [[1.0]], [[1.0]], [[1.0], [0.0]], [[0.0], [0.0]], [[0.0], [1.0]])
    >>> loops = switched_loops(p, [[[-3.0]], Controller([[-1.0]], [[1.0]], [[-2.0]], [[-3.0]])])
    >>> [lp.A.shape for lp in loops], loops[0].A.tolist()
    ([(2, 2), (2, 2)], [[-2.0, 0.0], [1.0, -1.0]])
    """
    from .plant import LTISystem

    cs = [as_controller(c, plant, f"controllers[{i}]") for i, c in enumerate(controllers)]
    if not cs:
        raise ValueError("controllers must hold at least one controller (one per mode), but found "
                         "none")
    for i, c in enumerate(cs):
        if c.n_states and len(cs) > 1 and np.max(np.linalg.eigvals(c.A).real) >= 0:
            raise ValueError(f"controllers[{i}] is unstable on its own (A_k has an eigenvalue with real "
                             f"part {np.max(np.linalg.eigvals(c.A).real):.4g}): it cannot run while "
                             "another controller is active; switch it through copies instead")
    if all(c.n_states == 0 for c in cs):
        return [c.closed_loop(plant, estimate_input=estimate_input) for c in cs]
    n, nd = plant.n_states, plant.B1.shape[1]
    sizes = [c.n_states for c in cs]
    N = n + sum(sizes)
    Aa = np.zeros((N, N))
    Aa[:n, :n] = plant.A
    Bd, Bw = np.zeros((N, nd)), np.zeros((N, nd))
    Bd[:n] = plant.B1
    offs = np.cumsum([n, *sizes])
    for c, o, k in zip(cs, offs[:-1], sizes, strict=True):
        if k:
            Aa[o:o + k, :n] = c.B
            Aa[o:o + k, o:o + k] = c.A
            if c.E is not None:
                Bw[o:o + k] = c.E
    out = []
    for c, o, k in zip(cs, offs[:-1], sizes, strict=True):
        Ku = np.zeros((plant.n_controls, N))
        Ku[:, :n] = c.D
        Ku[:, o:o + k] = c.C
        F = np.zeros((plant.n_controls, nd)) if c.F is None else c.F
        A = Aa.copy()
        A[:n] += plant.B2 @ Ku
        Bm = Bw.copy()
        Bm[:n] += plant.B2 @ F
        Ca = np.zeros((plant.C.shape[0], N))
        Ca[:, :n] = plant.C
        if estimate_input:
            out.append(LTISystem(A, np.hstack([Bd, Bm]), Ca + plant.D2 @ Ku,
                                 np.hstack([plant.D1, plant.D2 @ F])))
        else:
            out.append(LTISystem(A, Bd + Bm, Ca + plant.D2 @ Ku, plant.D1 + plant.D2 @ F))
    return out
