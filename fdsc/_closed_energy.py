"""Energies of a fixed loop under pieces of tones by closed forms, independent of the block engine.

Internal: the second method that rechecks energies computed by :mod:`fdsc._blocks` (Taylor
series and doublings of the augmented system, in coordinates from a Schur form). Neither method
below shares any of that; both run from rest, piece by piece, the state carried over.

* ``"modal closed form"``: the loop is brought to its real modal form by its own eigenvectors
  (real and imaginary parts of each complex pair; the inverse refined and the similarity formed
  by compensated products, :mod:`fdsc._compensated`, so that it is exact to rounding however
  stiff the loop), then :class:`fdsc.tuning._ClassEnergies` integrates it in closed form (the
  tones' steady state, the transient's Gramian and their cross terms in the eigenbasis). Taking
  the eigenvalues from the near-diagonal modal form rather than from A itself keeps a slow
  eigenvalue's digits when A also holds a pole at −2·10⁵ /s (LAPACK's error is relative to ‖A‖).
* ``"Schur closed form"``, where the eigenvectors are ill-conditioned (condition number above
  :data:`fdsc.tuning.EIG_COND`) or the modal form is not finite: in the complex Schur basis
  ``A = U T Uᴴ`` of the loop, on a piece of length L with tone phasors ``p_j``, the steady state
  ``X_j = U (jω_j − T)⁻¹ Uᴴ B p_j`` (triangular solves), the transient's Gramian
  ``Tᴴ Y + Y T = e^{TᴴL} N e^{TL} − N`` (``N = (CU)ᴴ CU``, a Sylvester equation), the cross
  terms ``CU (T + jω)⁻¹ (e^{(T + jω)L} − I) ε₀`` and the tones' own products
  ``∫ e^{jντ} dτ = L e^{jνL/2} sinc(νL / 2π)``. It is the less accurate of the two on a stiff
  loop (LAPACK's Schur form is exact to ε‖A‖, and ‖A‖ = 10⁷ where the slow poles are near 2 /s:
  about 1e-7 relative on the stored generic study's stiff designs, where the modal form keeps
  1e-15), and exact to rounding on a Jordan block, where there is no eigenbasis.

Neither falls back to the block engine: a loop that neither can integrate raises.
"""

import math

import numpy as np
from scipy.linalg import expm, schur, solve_sylvester, solve_triangular

from ._blocks import pieces
from ._compensated import dot, refined_inverse, similar
from .exceptions import EnergyOverflowError
from .plant import LTISystem
from .tuning import EIG_COND, _ClassEnergies

__all__ = []

#: The methods' names, as :func:`closed_form_energies` reports them.
MODAL, SCHUR = "modal closed form", "Schur closed form"


class _NoClosedForm(ArithmeticError):
    """The modal closed form does not apply (it would fall back to the block engine)."""


class _Modal(_ClassEnergies):
    """The modal closed form that refuses, rather than falls back to the block engine."""

    def exact(self, loop):
        raise _NoClosedForm


def _modal_basis(A):
    """The real modal basis of A (a column per real eigenvector, two per complex pair: its real
    and imaginary parts), or None if it is not finite or its condition number is above
    :data:`~fdsc.tuning.EIG_COND`."""
    lam, V = np.linalg.eig(A)
    cols, k = [], 0
    while k < lam.size:
        if lam[k].imag == 0:
            cols.append(V[:, k].real)
            k += 1
        elif k + 1 < lam.size and lam[k + 1] == lam[k].conjugate():
            cols += [V[:, k].real, V[:, k].imag]
            k += 2
        else:
            return None
    S = np.array(cols).T
    if not np.all(np.isfinite(S)) or np.linalg.cond(S) > EIG_COND:
        return None
    return S


def _modal(loop, disturbances, horizons):
    """The energies by the modal closed form (module docstring), or None where it does not
    apply."""
    A = loop.A
    S = _modal_basis(A) if A.shape[0] and np.all(np.isfinite(A)) else None
    if S is None:
        return None
    Si = refined_inverse(S)
    real = LTISystem(similar(Si, A, S), dot(Si, loop.B), dot(loop.C, S), loop.D)
    try:
        return _Modal(disturbances, horizons)(real)
    except _NoClosedForm:
        return None


def _window(nu, L):
    """``∫₀^L e^{jντ} dτ`` for every ν, without cancellation at small νL."""
    return L * np.exp(0.5j * nu * L) * np.sinc(nu * L / (2 * math.pi))


def _schur(loop, disturbances, horizons):
    """The energies by the Schur closed form (module docstring)."""
    A, B, C, D = loop.A, loop.B[:, 0], loop.C, loop.D[:, 0]
    n = A.shape[0]
    T, U = schur(A.astype(complex), output="complex")
    Uh = U.conj().T
    Bu, Cu = Uh @ B, C @ U
    N = Cu.conj().T @ Cu
    eye = np.eye(n)
    per_length = {}
    out = []
    for d, horizon in zip(disturbances, horizons, strict=True):
        x, total = np.zeros(n), 0.0
        for t0, t1, w, a, ph in pieces(d, horizon):
            L = t1 - t0
            if L not in per_length:
                E = expm(T * L)
                per_length[L] = (E, solve_sylvester(T.conj().T, T, E.conj().T @ N @ E - N))
            E, Y = per_length[L]
            p = a * np.exp(1j * (w * t0 + ph))                          # phasors at t0
            Xp = np.zeros((n, w.size), dtype=complex)                  # steady-state phasors
            for j, (wj, pj) in enumerate(zip(w, p, strict=True)):
                Xp[:, j] = U @ solve_triangular(1j * wj * eye - T, Bu * pj)
            Z = C @ Xp + np.outer(D, p)                                 # output phasors
            eps = Uh @ (x - Xp.sum(axis=1).imag)                        # the transient at t0
            tones = 0.5 * np.real(np.sum((Z.conj().T @ Z) * _window(w[None, :] - w[:, None], L))) \
                - 0.5 * np.real(np.sum((Z.T @ Z) * _window(w[:, None] + w[None, :], L)))
            cross = 0.0
            for j, wj in enumerate(w):
                g = solve_triangular(T + 1j * wj * eye, np.exp(1j * wj * L) * (E @ eps) - eps)
                cross += 2.0 * np.imag(Z[:, j] @ (Cu @ g))
            total += tones + float(np.real(eps.conj() @ Y @ eps)) + cross
            x = np.real(U @ (E @ eps)) + (Xp * np.exp(1j * w * L)).sum(axis=1).imag
        out.append(total)
    return np.array(out)


def closed_form_energies(loop, disturbances, horizons) -> tuple:
    """``(energies, method)``: ∫₀ᴴ zᵀz of a fixed loop from rest under each disturbance, by the
    modal closed form where it applies and by the Schur closed form elsewhere (module
    docstring); ``method`` names the one used.

    Parameters
    ----------
    loop : LTISystem
        One input (d).
    disturbances : sequence of Sinusoids or Piecewise
    horizons : sequence of float

    Returns
    -------
    energies : (K,) ndarray
    method : str
        :data:`MODAL` or :data:`SCHUR`.

    Raises
    ------
    EnergyOverflowError
        If the Schur closed form, where it is used, gives an energy that is not finite (an
        unstable loop, or one beyond the float range).
    """
    e = _modal(loop, disturbances, horizons)
    if e is not None:
        return e, MODAL
    e = _schur(loop, disturbances, horizons)
    if not np.all(np.isfinite(e)):
        raise EnergyOverflowError("closed_form_energies: the energy is not finite (an unstable loop, "
                                  "or one beyond the float range)")
    return e, SCHUR
