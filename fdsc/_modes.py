"""The closed loops both simulators accept (:func:`fdsc.simulate` and :mod:`fdsc.stream`): one
system or a list of modes that share their input, and the quadratic forms of the switching law.
Internal: the public names are those of :mod:`fdsc.simulate` and :mod:`fdsc.stream`.
"""

import numpy as np

from ._validation import as_matrix
from .bands import Band
from .energy import check_weight
from .exceptions import DimensionError
from .plant import LTISystem, as_system

__all__ = ["LAWS"]

#: How ẋ enters the switching law: "previous" (default: ẋ = A_σ(t⁻) x + B d, the measured
#: derivative) or "candidate" (each candidate i is scored with its own ẋ = A_i x + B d).
LAWS = ("previous", "candidate")


def _is_one_system(obj):
    """True for an LTISystem, a StateSpace or an (A, B, C, D) tuple of arrays (not of systems)."""
    if isinstance(obj, LTISystem) or type(obj).__name__ == "StateSpace":
        return True
    return isinstance(obj, tuple) and len(obj) == 4 and all(
        isinstance(a, np.ndarray | list | tuple | int | float) and not _is_one_system(a) for a in obj)


def _as_modes(modes):
    """One system, or a non-empty list or tuple of systems, as a list of :class:`LTISystem`."""
    if _is_one_system(modes):
        return [as_system(modes, "modes")]
    if not isinstance(modes, list | tuple) or not modes:
        raise TypeError("modes must be a system (LTISystem, StateSpace or (A, B, C, D)) or a "
                        f"non-empty list of systems, but found {type(modes).__name__}")
    return [as_system(m, f"modes[{k}]") for k, m in enumerate(modes)]


def _shared_input(modes, where=""):
    """n, B, D of modes that share B, D and their dimensions, with a scalar disturbance."""
    n = modes[0].n_states
    B, D = modes[0].B, modes[0].D
    for k, m in enumerate(modes[1:], start=1):
        if m.A.shape != (n, n) or not np.array_equal(m.B, B) or m.C.shape != modes[0].C.shape \
                or not np.array_equal(m.D, D):
            raise ValueError(f"{where}modes must share B, D and the state and output dimensions; "
                             f"mode {k} differs from mode 0")
    if B.shape[1] != 1:
        raise ValueError(f"{where}the disturbance must be scalar (B of shape (n, 1)), found {B.shape}")
    if modes[0].C.shape[0] == 0:
        # z would be empty: every energy 0 and every L2 ratio 0, whatever the loop does
        raise ValueError(f"{where}modes have no regulated output: C has shape {modes[0].C.shape} "
                         "(0 rows), so the energy of z would be 0; give C (and D) at least one row")
    return n, B, D


def _law_matrices(psis, Qs):
    """Stack the quadratic forms of the switching law: W_i = [[ψ11 Q, ψ12 Q], [ψ21 Q, ψ22 Q]]."""
    return np.array([np.kron(p, Q) for p, Q in zip(psis, Qs, strict=True)])


def _law_weights(n, n_modes, law_bands, law_Q, law_weights, where=""):
    """The law's quadratic forms, (I, 2n, 2n) on [ẋ; x] or (I, 3n, 3n) on [ẍ; ẋ; x].

    Either ``law_bands`` and ``law_Q`` (paper eq. (31): W_i = Re Ψ_i ⊗ Q_i) or ``law_weights``
    (any symmetric W_i; those of size 2n are placed on the [ẋ; x] block when another is 3n)."""
    if n_modes == 1:
        if law_weights is not None or law_bands is not None or law_Q is not None:
            raise ValueError(f"{where}a single mode has no switching law: leave law_bands, law_Q "
                             "and law_weights unset")
        return np.zeros((1, 2 * n, 2 * n))
    if law_weights is not None:
        if law_bands is not None or law_Q is not None:
            raise ValueError(f"{where}give either law_weights or law_bands with law_Q, not both")
        if not isinstance(law_weights, list | tuple) or len(law_weights) != n_modes:
            raise ValueError(f"{where}law_weights must be a list with one matrix per mode "
                             f"({n_modes} modes), found {type(law_weights).__name__}")
        Ws = []
        for i, W in enumerate(law_weights):
            W = np.asarray(as_matrix(f"{where}law_weights[{i}]", W, square=True))
            if W.shape[0] not in (2 * n, 3 * n):
                raise DimensionError(f"{where}law_weights[{i}] must be ({2 * n}, {2 * n}) on [ẋ; x] "
                                     f"or ({3 * n}, {3 * n}) on [ẍ; ẋ; x], but found {W.shape}")
            if not np.allclose(W, W.T, rtol=1e-12, atol=1e-12 * max(1.0, float(np.abs(W).max()))):
                raise ValueError(f"{where}law_weights[{i}] must be symmetric")
            Ws.append(W)
        q = max(W.shape[0] for W in Ws)
        out = np.zeros((n_modes, q, q))
        for i, W in enumerate(Ws):
            out[i, q - W.shape[0]:, q - W.shape[0]:] = W
        return out
    for name, value in (("law_bands", law_bands), ("law_Q", law_Q)):
        if not isinstance(value, list | tuple) or len(value) != n_modes:
            raise ValueError(f"{where}{name} must be a list with one entry per mode ({n_modes} "
                             f"modes), found {type(value).__name__}"
                             + (f" of length {len(value)}" if isinstance(value, list | tuple) else ""))
    if not all(isinstance(b, Band) for b in law_bands):
        raise TypeError(f"{where}law_bands must be a list of fdsc.Band")
    for i, b in enumerate(law_bands):
        if b.is_complex:
            # as certify_q and FDSC refuse it: Re Ψ of an MF range is negative definite, so its
            # mode's score is never positive and the mode is chosen only when every other loses
            raise ValueError(f"{where}law_bands[{i}] is an MF range ({b.label}): the switching law "
                             "is implemented for real Ψ (LF, HF, entire), as Theorem 1; it sees "
                             "only Re Ψ of an MF range, whose score is never positive")
    Qs = []
    for i, Q in enumerate(law_Q):
        try:
            Qs.append(check_weight(Q, n))
        except (ValueError, TypeError) as exc:
            raise type(exc)(f"{where}law_Q[{i}]: {exc}") from None
    return _law_matrices([b.psi.real for b in law_bands], Qs)
