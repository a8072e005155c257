"""Systems: the open-loop plant, closed loops, and the one boundary that converts user input to them.

A system ``dx/dt = A x + B d, z = C x + D d`` is paper eq. (6); the plant is paper eq. (10)::

    dx/dt = A x + B1 d + B2 u,     z = C x + D1 d + D2 u,

and state feedback ``u = K x`` gives the closed loop
``(A + B2 K, B1, C + D2 K, D1)`` (paper eqs. (9) and (32)). (The paper's switched closed loop
prints ``C + B2 K``; the dimensions force ``C + D2 K``.)
"""

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from ._validation import as_count, as_matrix

if TYPE_CHECKING:  # python-control is optional: annotations only
    import control

__all__ = ["LTISystem", "Plant", "as_system", "as_plant"]


@dataclass(frozen=True)
class LTISystem:
    """A continuous-time LTI system ``dx/dt = A x + B d, z = C x + D d`` (paper eq. (6)).

    The matrices are stored as read-only float arrays.

    Parameters
    ----------
    A : (n, n) array_like
        State matrix.
    B : (n, m) array_like
        Input (disturbance) matrix.
    C : (p, n) array_like
        Output matrix.
    D : (p, m) array_like
        Feedthrough matrix.

    Raises
    ------
    DimensionError
        If a matrix is not 2-D or the shapes do not fit together.
    ValueError
        If an entry is NaN, infinite, complex or not numeric.

    Examples
    --------
    >>> sys = LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]])
    >>> sys.n_states, sys.is_hurwitz()
    (1, True)
    """

    A: np.ndarray
    B: np.ndarray
    C: np.ndarray
    D: np.ndarray

    def __post_init__(self):
        A = as_matrix("A", self.A, square=True)
        n = A.shape[0]
        B = as_matrix("B", self.B, (n, None))
        C = as_matrix("C", self.C, (None, n))
        D = as_matrix("D", self.D, (C.shape[0], B.shape[1]))
        for name, val in zip("ABCD", (A, B, C, D), strict=True):
            object.__setattr__(self, name, val)

    @property
    def n_states(self) -> int:
        """Number of states n."""
        return self.A.shape[0]

    @property
    def n_inputs(self) -> int:
        """Number of disturbance inputs m."""
        return self.B.shape[1]

    @property
    def n_outputs(self) -> int:
        """Number of regulated outputs p."""
        return self.C.shape[0]

    def poles(self) -> np.ndarray:
        """Eigenvalues of A, sorted by real part (most negative first).

        Returns
        -------
        (n,) ndarray
            Complex, or real when every eigenvalue is real.

        Examples
        --------
        >>> LTISystem([[-1.0, 0.0], [0.0, -2.0]], [[1.0], [0.0]], [[1.0, 0.0]], [[0.0]]).poles()
        array([-2., -1.])
        """
        ev = np.linalg.eigvals(self.A)
        return ev[np.argsort(ev.real)]

    def is_hurwitz(self, margin: float = 0.0) -> bool:
        """True if every eigenvalue of A has real part < ``-margin``.

        Parameters
        ----------
        margin : float, optional
            Required distance of the eigenvalues from the imaginary axis (default 0: plain
            Hurwitz stability).

        Returns
        -------
        bool

        Examples
        --------
        >>> sys = LTISystem([[-0.5]], [[1.0]], [[1.0]], [[0.0]])
        >>> sys.is_hurwitz(), sys.is_hurwitz(margin=1.0)
        (True, False)
        """
        return bool(np.all(np.linalg.eigvals(self.A).real < -margin))


@dataclass(frozen=True)
class Plant:
    """The open-loop plant ``dx/dt = A x + B1 d + B2 u``, ``z = C x + D1 d + D2 u`` (paper eq. (10)).

    The matrices are stored as read-only float arrays.

    Parameters
    ----------
    A : (n, n) array_like
        State matrix.
    B1 : (n, m_d) array_like
        Disturbance input matrix.
    B2 : (n, m_u) array_like
        Control input matrix.
    C : (p, n) array_like
        Output matrix of the regulated output z.
    D1 : (p, m_d) array_like
        Feedthrough from the disturbance.
    D2 : (p, m_u) array_like
        Feedthrough from the control.
    names : dict, optional
        Names of states, inputs and outputs (for plots); not compared by ``==``.

    Raises
    ------
    DimensionError
        If a matrix is not 2-D or the shapes do not fit together.
    ValueError
        If an entry is NaN, infinite, complex or not numeric.

    Examples
    --------
    >>> p = Plant([[0.0, 1.0], [-2.0, -0.5]], [[0.0], [1.0]], [[0.0], [1.0]],
    ...           [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [1.0]])
    >>> cl = p.closed_loop([[-1.0, -1.0]])
    >>> cl.A.tolist(), cl.C.shape
    ([[0.0, 1.0], [-3.0, -1.5]], (2, 2))
    """

    A: np.ndarray
    B1: np.ndarray
    B2: np.ndarray
    C: np.ndarray
    D1: np.ndarray
    D2: np.ndarray
    names: dict = field(default_factory=dict, compare=False)

    def __post_init__(self):
        A = as_matrix("A", self.A, square=True)
        n = A.shape[0]
        B1 = as_matrix("B1", self.B1, (n, None))
        B2 = as_matrix("B2", self.B2, (n, None))
        C = as_matrix("C", self.C, (None, n))
        D1 = as_matrix("D1", self.D1, (C.shape[0], B1.shape[1]))
        D2 = as_matrix("D2", self.D2, (C.shape[0], B2.shape[1]))
        for name, val in (("A", A), ("B1", B1), ("B2", B2), ("C", C), ("D1", D1), ("D2", D2)):
            object.__setattr__(self, name, val)

    @property
    def n_states(self) -> int:
        """Number of states n."""
        return self.A.shape[0]

    @property
    def n_controls(self) -> int:
        """Number of control inputs m_u."""
        return self.B2.shape[1]

    def closed_loop(self, K: ArrayLike) -> LTISystem:
        """Closed loop under ``u = K x``: ``(A + B2 K, B1, C + D2 K, D1)``.

        Parameters
        ----------
        K : (m_u, n) array_like or Controller
            State-feedback gain, or a controller with states (its closed loop has the state
            ``[x; x_k]``: :meth:`fdsc.Controller.closed_loop`).

        Returns
        -------
        LTISystem
            The map from d to z.

        Raises
        ------
        DimensionError
            If K is not of shape ``(m_u, n)``.
        ValueError
            If an entry of K is NaN, infinite, complex or not numeric.

        Notes
        -----
        State feedback paper eq. (9) applied to the plant, paper eq. (10); the closed loop is one
        mode of paper eq. (32), with ``C + D2 K`` where the paper prints ``C + B2 K``.

        Examples
        --------
        >>> p = Plant([[1.0]], [[1.0]], [[1.0]], [[1.0], [0.0]], [[0.0], [0.0]], [[0.0], [1.0]])
        >>> cl = p.closed_loop([[-3.0]])
        >>> cl.A.tolist(), cl.C.tolist()
        ([[-2.0]], [[1.0], [-3.0]])
        """
        if callable(getattr(K, "closed_loop", None)):        # a Controller (fdsc.controller)
            return K.closed_loop(self)
        K = as_matrix("K", K, (self.n_controls, self.n_states))
        return LTISystem(self.A + self.B2 @ K, self.B1, self.C + self.D2 @ K, self.D1)


def _statespace_matrices(sys, name, *, static_ok=False):
    """(A, B, C, D) of a continuous-time python-control StateSpace, or None if ``sys`` is not one.
    With ``static_ok`` a system without states may have ``dt = None`` (python-control's default
    for a static gain: it is a gain in continuous time as well)."""
    try:
        import control
    except ImportError:  # python-control is optional for the library
        return None
    if not isinstance(sys, control.StateSpace):
        if isinstance(sys, control.InputOutputSystem):
            raise TypeError(f"{name} must be a python-control StateSpace (convert with control.ss), "
                            f"but found {type(sys).__name__}")
        return None
    if not sys.isctime(strict=True) and not (static_ok and sys.nstates == 0 and sys.dt is None):
        raise ValueError(f"{name} must be a continuous-time system (dt = 0), but found dt={sys.dt}")
    return sys.A, sys.B, sys.C, sys.D


def as_system(sys: "LTISystem | control.StateSpace | tuple", name: str = "sys") -> LTISystem:
    """Convert a system to :class:`LTISystem`: the one boundary for every function that takes one.

    Parameters
    ----------
    sys : LTISystem, control.StateSpace or tuple
        An :class:`LTISystem` (returned as is), a continuous-time python-control ``StateSpace``,
        or a tuple ``(A, B, C, D)`` of array_like.
    name : str, optional
        Name of the argument, for error messages.

    Returns
    -------
    LTISystem

    Raises
    ------
    TypeError
        If ``sys`` is none of the accepted types (a ``Plant`` must be closed first).
    ValueError
        If a python-control system is discrete-time, or an entry is not finite and real.
    DimensionError
        If the matrices do not fit together.

    Examples
    --------
    >>> import control
    >>> as_system(control.ss([[-1.0]], [[1.0]], [[2.0]], [[0.0]])).C
    array([[2.]])
    >>> as_system(([[-1.0]], [[1.0]], [[2.0]], [[0.0]])).n_states
    1
    """
    if isinstance(sys, LTISystem):
        return sys
    if isinstance(sys, Plant):
        raise TypeError(f"{name} must be a closed loop (LTISystem), but found a Plant; close it "
                        "with plant.closed_loop(K)")
    abcd = _statespace_matrices(sys, name)
    if abcd is None and isinstance(sys, tuple | list) and len(sys) == 4:
        abcd = sys
    if abcd is None:
        raise TypeError(f"{name} must be an fdsc.LTISystem, a python-control StateSpace or a tuple "
                        f"(A, B, C, D), but found {type(sys).__name__}")
    return LTISystem(*abcd)


def as_plant(plant: "Plant | control.StateSpace | tuple", name: str = "plant", *,
             n_disturbances: int | None = None) -> Plant:
    """Convert an open-loop plant to :class:`Plant`: the boundary for synthesis and FDSC designs.

    Parameters
    ----------
    plant : Plant, control.StateSpace or tuple
        A :class:`Plant` (returned as is), a tuple ``(A, B1, B2, C, D1, D2)`` of array_like, or a
        continuous-time python-control ``StateSpace`` whose inputs are ``[d; u]``: the first
        ``n_disturbances`` inputs are disturbances, the others controls.
    name : str, optional
        Name of the argument, for error messages.
    n_disturbances : int, optional
        Number of disturbance inputs of a ``StateSpace`` plant (a StateSpace does not say which
        inputs are controls): default 1, its first input, the rule of every function of fdsc
        that takes a plant (convert a plant with more disturbances with this function first, or
        give ``n_disturbances=`` where a function takes it). For a Plant or a tuple it may be
        given and must then equal B1's columns.

    Returns
    -------
    Plant

    Raises
    ------
    TypeError
        If ``plant`` is none of the accepted types.
    ValueError
        If ``n_disturbances`` leaves no disturbance or no control input or contradicts a
        Plant's B1, if a python-control system is discrete-time, or if an entry is not finite
        and real.
    DimensionError
        If the matrices do not fit together.

    Examples
    --------
    >>> import control
    >>> ss = control.ss([[0.0, 1.0], [-2.0, -0.5]], [[0.0, 0.0], [1.0, 1.0]],
    ...                 [[1.0, 0.0], [0.0, 0.0]], [[0.0, 0.0], [0.0, 1.0]])
    >>> p = as_plant(ss)                     # the first input is the disturbance
    >>> p.B1.shape, p.B2.shape, p.D2.ravel().tolist()
    ((2, 1), (2, 1), [0.0, 1.0])
    """
    if isinstance(plant, Plant | tuple | list) and n_disturbances is not None:
        k = as_count("n_disturbances", n_disturbances)
        have = plant.B1.shape[1] if isinstance(plant, Plant) else np.shape(plant[1])[-1] if \
            len(plant) == 6 and np.ndim(plant[1]) == 2 else k
        if k != have:
            raise ValueError(f"n_disturbances must match the plant's {have} disturbance input(s) "
                             f"(B1's columns) or be left out, but found {k}")
    if isinstance(plant, Plant):
        return plant
    if isinstance(plant, LTISystem):
        raise TypeError(f"{name} must be an open-loop plant with separate disturbance and control "
                        "inputs (Plant, a StateSpace with inputs [d; u], or (A, B1, B2, C, D1, D2)), "
                        "but found an LTISystem")
    abcd = _statespace_matrices(plant, name)
    if abcd is not None:
        k = 1 if n_disturbances is None else as_count("n_disturbances", n_disturbances)
        m = abcd[1].shape[1]
        if k >= m:
            raise ValueError(f"n_disturbances must be below the number of inputs {m} (at least one "
                             f"control input), but found {k}"
                             + (" (the default: the first input is the disturbance)"
                                if n_disturbances is None else ""))
        A, B, C, D = (np.asarray(x) for x in abcd)
        return Plant(A, B[:, :k], B[:, k:], C, D[:, :k], D[:, k:])
    if isinstance(plant, tuple | list) and len(plant) == 6:
        return Plant(*plant)
    raise TypeError(f"{name} must be an fdsc.Plant, a python-control StateSpace (inputs [d; u]) "
                    f"or a tuple (A, B1, B2, C, D1, D2), but found {type(plant).__name__}")
