"""Exceptions raised by fdsc.

Every exception derives from a Python built-in so that callers may catch either
the specific fdsc class or the familiar base (``ValueError``, ``RuntimeError``).
"""

__all__ = [
    "FdscError",
    "DimensionError",
    "BandError",
    "SolverError",
    "InfeasibleError",
    "VerificationError",
    "IterationLimitError",
    "UnstableError",
    "SingularFrequencyError",
    "MemoryLimitError",
    "EnergyOverflowError",
    "EnergyUnderflowWarning",
    "UnstableRunWarning",
    "ResolutionWarning",
]


class FdscError(Exception):
    """Base class of every exception raised on purpose by fdsc."""


class DimensionError(FdscError, ValueError):
    """An array argument has the wrong number of dimensions or the wrong shape."""


class BandError(FdscError, ValueError):
    """A frequency band is specified with invalid limits."""


class SolverError(FdscError, RuntimeError):
    """An LMI solve failed; ``status`` holds the cvxpy status, ``solver_status`` Clarabel's own.

    The message ends with ``(status: ...)``; the base class ``RuntimeError`` lets callers that
    know nothing of fdsc catch it.

    Parameters
    ----------
    message : str
        What was being solved and why it failed.
    status : str
        The cvxpy status (e.g. ``"infeasible"``, ``"solver_error"``), or a description of the
        check that decided without a solve.
    solver_status : str, optional
        Clarabel's status (e.g. ``"InsufficientProgress"``, ``"AlmostSolved"``), when a solve ran.

    Examples
    --------
    >>> err = SolverError("band LMI", "solver_error", "InsufficientProgress")
    >>> str(err), err.solver_status
    ('band LMI (status: solver_error)', 'InsufficientProgress')
    """

    def __init__(self, message: str, status: str, solver_status: str | None = None):
        super().__init__(f"{message} (status: {status})")
        self.status = status
        self.solver_status = solver_status


class InfeasibleError(SolverError):
    """The solver reported the LMI (or the specification) infeasible.

    Parameters
    ----------
    message : str
        What was being solved and why it failed.
    status : str
        The cvxpy status (e.g. ``"infeasible"``), or a description of the check that decided
        without a solve.
    solver_status : str, optional
        Clarabel's status, when a solve ran.

    Examples
    --------
    >>> isinstance(InfeasibleError("Theorem 1", "infeasible"), RuntimeError)
    True
    """


class VerificationError(SolverError):
    """The solver reported success but the a-posteriori check of the certificate failed.

    Parameters
    ----------
    message : str
        What was solved and which check failed.
    status : str
        The cvxpy status of the solve (``"optimal"`` or ``"optimal_inaccurate"``).
    solver_status : str, optional
        Clarabel's status, when known.
    """


class IterationLimitError(FdscError, RuntimeError):
    """An iterative procedure reached its iteration cap without converging."""


class UnstableError(FdscError, ValueError):
    """A system that must be stable (A Hurwitz) is not, or a simulated state diverged.

    The message names the offending eigenvalue (or the instant at which the state overflowed).

    Parameters
    ----------
    message : str
        What needs a stable system and which eigenvalue violates it.
    eigenvalue : complex, optional
        The eigenvalue with the largest real part, kept as ``eigenvalue`` (``None`` for a
        diverged simulation).

    Examples
    --------
    >>> UnstableError("sys is not stable", 0.5 + 1j).eigenvalue
    (0.5+1j)
    """

    def __init__(self, message: str, eigenvalue: complex | None = None):
        super().__init__(message)
        self.eigenvalue = eigenvalue


class SingularFrequencyError(FdscError, ValueError):
    """A frequency response is requested where it is undefined: a pole of A lies on jω at a
    frequency of the sweep or band, or a disturbance tone sits at an eigenvalue of a closed loop."""


class MemoryLimitError(FdscError, MemoryError):
    """A requested computation would allocate more memory than the stated limit."""


class EnergyOverflowError(FdscError, OverflowError):
    """A simulated run's state stays finite but its energy exceeds the float range (≈ 1.8e308).

    The simulators scale such runs by a power of two so that their sums do not overflow on the
    way (the loop is linear); only a total that cannot be represented in the caller's units is
    refused, with this error."""


class EnergyUnderflowWarning(UserWarning):
    """A run's energy is not zero but lies below the smallest normal float (≈ 2.2e-308) in the
    caller's units, where a float keeps few digits or none (a disturbance of amplitude about
    1e-155 or less).

    The run itself is made at a scale where its energies are of order one (a power of two,
    exact), so its decisions and states are those of the unscaled run; only the energies brought
    back into the caller's units lose their digits, and this warning says so.
    """


class UnstableRunWarning(UserWarning):
    """A simulated loop has a mode that is not Hurwitz (its finite results may still grow)."""


class ResolutionWarning(UserWarning):
    """Tones identified from a window of samples lie closer than the window resolves: two tones
    closer than its Rayleigh resolution 2π/T (T the window's length), or a tone within half of it
    (π/T) of the Nyquist frequency π/step, where its samples barely tell it from its alias.

    Their frequencies may still be right (on exact samples the identification separates them
    below that resolution), but their amplitudes and phases are ill-conditioned: a small error in
    the samples moves them much (at π/step exactly, only ``a sin φ`` of ``a sin(ωt + φ)`` is seen).
    """
