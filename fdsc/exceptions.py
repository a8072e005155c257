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
]


class FdscError(Exception):
    """Base class of every exception raised on purpose by fdsc."""


class DimensionError(FdscError, ValueError):
    """An array argument has the wrong number of dimensions or the wrong shape."""


class BandError(FdscError, ValueError):
    """A frequency band is specified with invalid limits."""


class SolverError(FdscError, RuntimeError):
    """An LMI solve failed; ``status`` holds the solver's status string.

    Parameters
    ----------
    message : str
        What was being solved and why it failed.
    status : str
        The cvxpy status (e.g. ``"infeasible"``, ``"solver_error"``).
    """

    def __init__(self, message, status):
        super().__init__(f"{message} (solver status: {status})")
        self.status = status


class InfeasibleError(SolverError):
    """The solver reported the LMI (or the specification) infeasible."""


class VerificationError(SolverError):
    """The solver reported success but the a-posteriori check of the certificate failed."""


class IterationLimitError(FdscError, RuntimeError):
    """An iterative procedure reached its iteration cap without converging."""
