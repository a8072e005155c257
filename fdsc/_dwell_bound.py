"""The certificate class of :mod:`fdsc.dwell`, shared by ``fdsc.dwell`` (which builds it) and
``fdsc._dwell_signals`` (which checks switching signals against it). Internal: the public name is
``fdsc.dwell.DwellTimeBound``, which is where its ``__module__`` points.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._validation import as_positive, frozen_array

__all__ = []


@dataclass(frozen=True)
class DwellTimeBound:
    """A certified dwell-time bound τ* = ln μ / (2λ) with its Lyapunov matrices.

    Parameters
    ----------
    tau : float
        τ* = ln μ / (2λ) in s: every switching signal whose switches are at least τ_d > τ* apart
        makes the switched system (d = 0) globally exponentially stable.
    decay : float
        λ in 1/s: A_iᵀP_i + P_iA_i ⪯ −2λP_i for every mode (V decays like e^{−2λt}).
    mu : float
        μ = max_{i≠j} λ_max(P_i^{−1/2} P_j P_i^{−1/2}) ≥ 1 of the returned P_i (V_j ≤ μ V_i).
    mu_crude : float
        The crude form max_i λ_max(P_i) / min_j λ_min(P_j), minimized over the P_i at this λ.
    tau_crude : float
        ln(mu_crude) / (2λ) in s.
    P : tuple of (n, n) ndarray
        The Lyapunov matrices P_i (symmetric positive definite), one per mode.
    decay_limits : (I,) ndarray
        λ_i^max = −max Re eig(A_i) of each mode; λ < min_i λ_i^max.
    decays : (k,) ndarray
        The decay rates tried (sorted); one entry if ``decay`` was given.
    mus, mus_crude, taus, taus_crude : (k,) ndarray
        μ, crude μ, τ* and crude τ* at each decay rate tried (inf where no certificate was found,
        which happens only for λ very close to min_i λ_i^max).
    max_eigs : (I,) ndarray
        Largest eigenvalue of A_iᵀP_i + P_iA_i + 2λP_i at the certificate (all < 0).
    min_eig_P : (I,) ndarray
        Smallest eigenvalue of each P_i (all > 0).
    n_solves : int
        Number of LMI solves.
    n_failed : int
        Solves that ended without a verified certificate other than by infeasibility (a solver
        stop or a failed eigenvalue check near the boundary of the feasible set); each counts as
        "not certified" there, which can only make μ larger, never invalid.
    A : tuple of (n, n) ndarray, optional
        The modes' state matrices A_i the certificate was computed for (set by
        :func:`~fdsc.dwell.dwell_time_bound`; :func:`~fdsc.dwell.check_dwell_bound` compares
        the modes it is given with them). None for a certificate assembled by hand.

    Notes
    -----
    The dwell-time theorem (Liberzon 2003, Ch. 3, stability under slow switching; Hespanha & Morse 1999).
    """

    tau: float
    decay: float
    mu: float
    mu_crude: float
    tau_crude: float
    P: tuple
    decay_limits: np.ndarray
    decays: np.ndarray
    mus: np.ndarray
    mus_crude: np.ndarray
    taus: np.ndarray
    taus_crude: np.ndarray
    max_eigs: np.ndarray
    min_eig_P: np.ndarray
    n_solves: int
    n_failed: int
    A: tuple | None = None

    def __post_init__(self):
        object.__setattr__(self, "P", tuple(frozen_array(p) for p in self.P))
        if self.A is not None:
            object.__setattr__(self, "A", tuple(frozen_array(np.asarray(a, dtype=float))
                                                for a in self.A))
        for name in ("decay_limits", "decays", "mus", "mus_crude", "taus", "taus_crude",
                     "max_eigs", "min_eig_P"):
            object.__setattr__(self, name, frozen_array(np.asarray(getattr(self, name), dtype=float)))

    def rate(self, dwell: float) -> float:
        """Guaranteed exponential decay rate of V under switches at least ``dwell`` apart.

        Parameters
        ----------
        dwell : float
            The minimum dwell time τ_d in s (> 0).

        Returns
        -------
        float
            2λ − ln μ / τ_d in 1/s (positive exactly when ``dwell`` > τ*): with the first switch
            at least τ_d after 0, V(t) ≤ e^{−(2λ − ln μ/τ_d) t} V(0).

        Raises
        ------
        ValueError
            If ``dwell`` is not positive.
        """
        dwell = as_positive("dwell", dwell)
        return 2 * self.decay - np.log(self.mu) / dwell

    def envelope(self, t: np.ndarray, n_switches: np.ndarray) -> np.ndarray:
        """The bound μ^{N(t)} e^{−2λt} on V(t)/V(0).

        Parameters
        ----------
        t : (k,) array_like
            Times in s (≥ 0).
        n_switches : (k,) array_like
            N(t), the number of switches in (0, t].

        Returns
        -------
        (k,) ndarray
        """
        t = np.asarray(t, dtype=float)
        return np.exp(np.asarray(n_switches, dtype=float) * np.log(self.mu) - 2 * self.decay * t)


DwellTimeBound.__module__ = "fdsc.dwell"
