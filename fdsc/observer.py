"""A disturbance observer: the estimate ŵ built from sampled, noisy measurements of the state.

The paper's laws read ŵ = B1⁺(ẋ − A x − B2 u), which needs ẋ measured and no noise. A controller
in practice samples ``y_k = x(t_k) + v_k`` every ``h`` seconds (``v_k`` white, covariance ``R``),
holds its control ``u`` over each step, and estimates d itself. This module gives it the standard
means: model d as the output of a shaping filter driven by white noise,

    dη/dt = A_d η + B_d ω,     d = C_d η,     ω white with intensity Q_ω,

(default one random walk per disturbance input: ``A_d = 0``, ``B_d = C_d = I``), augment the
plant with it (``ξ = (x, η)``), sample the augmented plant exactly (a zero-order hold on u; the
process noise's covariance over a step by Van Loan's integral), and run the steady-state Kalman
filter of ξ from the samples. Its estimate of d, ``ŵ_k = C_d η̂_{k|k}``, is what a controller
reading ŵ then reads; the observer is part of that controller.

Everything about the filter's accuracy is in closed form: the error of the filtered estimate
evolves as ``e_k = (I − L H) Φ e_{k−1} + (noise terms)`` (:attr:`DisturbanceObserver.error_dynamics`),
its steady-state covariance is :attr:`DisturbanceObserver.covariance` (from the discrete
algebraic Riccati equation), and the variance of the estimate of d is
:attr:`DisturbanceObserver.estimate_covariance` — under the model. On a disturbance that is not
the model's (tones, say), the error is what the filter's transfer function from d to ŵ makes of
it (:meth:`DisturbanceObserver.estimate` runs it on samples).
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import expm, solve_discrete_are

from ._validation import as_matrix, as_positive, as_vector, check_type
from .exceptions import DimensionError, SolverError
from .plant import LTISystem, as_plant

__all__ = ["DisturbanceObserver", "random_walk_model"]


def random_walk_model(m: int = 1) -> LTISystem:
    """The default model of d: one random walk per disturbance input (``A_d = 0``, ``B_d = C_d = I``).

    Parameters
    ----------
    m : int, optional
        The number of disturbance inputs.

    Returns
    -------
    LTISystem
        ``m`` states, ``m`` inputs ω, ``m`` outputs d.

    Examples
    --------
    >>> random_walk_model(2).A.tolist()
    [[0.0, 0.0], [0.0, 0.0]]
    """
    if not isinstance(m, int | np.integer) or isinstance(m, bool) or m < 1:
        raise ValueError(f"m must be a whole number ≥ 1, but found {m!r}")
    z, i = np.zeros((m, m)), np.eye(m)
    return LTISystem(z, i, i, z)


def _covariance(name, value, n):
    """A symmetric positive definite (n, n) matrix from a number (times I) or a matrix."""
    arr = np.asarray(value, dtype=float) if not isinstance(value, str) else None
    if arr is not None and arr.ndim == 0:
        return as_positive(name, float(arr)) * np.eye(n)
    M = as_matrix(name, value, (n, n))
    if not np.allclose(M, M.T, rtol=1e-12, atol=0.0):
        raise ValueError(f"{name} must be symmetric")
    if np.min(np.linalg.eigvalsh(M)) <= 0.0:
        raise ValueError(f"{name} must be positive definite, but its least eigenvalue is "
                         f"{np.min(np.linalg.eigvalsh(M)):.3g}")
    return np.array(M)


class DisturbanceObserver:
    """The steady-state Kalman filter of the plant augmented with a model of d, sampled exactly.

    Parameters
    ----------
    plant : Plant, control.StateSpace or tuple
        ``dx/dt = A x + B1 d + B2 u`` (C, D1, D2 are not used).
    step : float
        The sampling interval h (s); u is held over each step.
    noise : float or (n, n) array_like
        The covariance R of the measurement noise ``v_k`` on each sample of x (a number: ``R = r I``).
    model : LTISystem, optional
        The shaping filter of d (``A_d, B_d, C_d``; its D must be 0): as many outputs as the plant
        has disturbance inputs. Default :func:`random_walk_model`.
    intensity : float or array_like, optional
        The intensity ``Q_ω`` of the white noise ω that drives the model (a number: times I).
        With the noise R it sets the filter's bandwidth: a larger ``Q_ω / R`` follows d faster
        and passes more noise. Default 1.

    Attributes
    ----------
    Phi, Gamma : ndarray
        The augmented plant over one step: ``ξ_{k+1} = Phi ξ_k + Gamma u_k + (process noise)``.
    process_noise : ndarray
        The covariance of the process noise over one step (Van Loan).
    H : ndarray
        ``[I, 0]``: the samples read x.
    gain : ndarray
        The Kalman gain L of the update ``ξ̂_{k|k} = ξ̂_{k|k−1} + L (y_k − H ξ̂_{k|k−1})``.
    prior_covariance, covariance : ndarray
        The steady-state covariance of the error before and after the update (``P⁻`` solves the
        discrete algebraic Riccati equation; ``P⁺ = (I − L H) P⁻``).
    error_dynamics : ndarray
        ``(I − L H) Phi``: without noise, the filtered error obeys ``e_k = error_dynamics e_{k−1}``.
    estimate_covariance : ndarray
        ``C_d P⁺_ηη C_dᵀ``: the steady-state covariance of ŵ − d under the model.

    Raises
    ------
    ValueError
        If step, noise or intensity is out of range, the model's D is not 0, or d cannot be
        estimated from x (the augmented pair is not detectable: B1 loses a direction of d, or the
        model has a mode that d never shows).
    DimensionError
        If the model's outputs do not match the plant's disturbance inputs, or a covariance's shape
        does not fit.
    SolverError
        If the Riccati equation has no stabilizing solution.

    Examples
    --------
    A constant disturbance of a lightly damped plant, sampled every 10 ms with noise of standard
    deviation 10⁻³: after 2 s the estimate is within 10⁻⁵ of it.

    >>> import numpy as np
    >>> from fdsc import Plant
    >>> p = Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
    ...           [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.3]])
    >>> obs = DisturbanceObserver(p, 0.01, 1e-6, intensity=10.0)
    >>> bool(np.max(np.abs(np.linalg.eigvals(obs.error_dynamics))) < 1)
    True
    >>> xi = obs.estimate(*obs.noiseless_run(np.zeros(2), np.zeros((200, 1)), d=0.5))[0]
    >>> bool(abs(xi[-1, 0] - 0.5) < 1e-5)
    True
    """

    def __init__(self, plant, step: float, noise, *, model: LTISystem | None = None, intensity=1.0):
        self.plant = p = as_plant(plant)
        self.step = h = as_positive("step", step)
        n, m, mu = p.n_states, p.B1.shape[1], p.n_controls
        if model is None:
            model = random_walk_model(m)
        check_type("model", model, LTISystem, "an fdsc.LTISystem (the shaping filter of d)")
        if model.C.shape[0] != m:
            raise DimensionError(f"model must have as many outputs as the plant has disturbance inputs "
                                 f"({m}), but found {model.C.shape[0]}")
        if np.any(model.D):
            raise ValueError("model: its D must be 0 (d is the filter's state seen through C_d)")
        self.model = model
        k, w = model.n_states, model.B.shape[1]
        R = _covariance("noise", noise, n)
        Qw = _covariance("intensity", intensity, w)
        F = np.block([[p.A, p.B1 @ model.C], [np.zeros((k, n)), model.A]])
        G = np.vstack([np.zeros((n, w)), model.B])
        Bu = np.vstack([p.B2, np.zeros((k, mu))])
        N = n + k
        # Van Loan: the process noise's covariance over one step, and the exact sampled plant
        M = expm(np.block([[-F, G @ Qw @ G.T], [np.zeros((N, N)), F.T]]) * h)
        self.Phi = M[N:, N:].T.copy()
        Qd = self.Phi @ M[:N, N:]
        self.process_noise = Qd = (Qd + Qd.T) / 2
        Z = expm(np.block([[F, Bu], [np.zeros((mu, N + mu))]]) * h)
        self.Gamma = Z[:N, N:].copy()
        self.H = H = np.hstack([np.eye(n), np.zeros((n, k))])
        self._check_detectable()
        try:
            P = solve_discrete_are(self.Phi.T, H.T, Qd, R)
        except (np.linalg.LinAlgError, ValueError) as err:
            raise SolverError("DisturbanceObserver: the Riccati equation of the filter has no "
                              "stabilizing solution", str(err)) from err
        P = (P + P.T) / 2
        S = H @ P @ H.T + R
        self.gain = L = np.linalg.solve(S, H @ P).T
        self.prior_covariance = P
        Pf = (np.eye(N) - L @ H) @ P
        self.covariance = (Pf + Pf.T) / 2
        self.error_dynamics = (np.eye(N) - L @ H) @ self.Phi
        if np.max(np.abs(np.linalg.eigvals(self.error_dynamics))) >= 1.0:
            raise SolverError("DisturbanceObserver: the filter is not stable",
                              "the Riccati solution does not stabilize the error dynamics")
        self.estimate_covariance = model.C @ self.covariance[n:, n:] @ model.C.T
        self.measurement_noise = R
        self.noise_intensity = Qw

    def _check_detectable(self):
        """Every mode of the sampled augmented plant on or outside the unit circle shows in x."""
        lam, V = np.linalg.eig(self.Phi)
        for j in np.flatnonzero(np.abs(lam) >= 1.0 - 1e-12):
            v = V[:, j]
            if np.linalg.norm(self.H @ v) <= 1e-9 * np.linalg.norm(v):
                raise ValueError("DisturbanceObserver: d cannot be estimated from x: the mode at "
                                 f"eigenvalue {lam[j]:.6g} of the sampled plant augmented with the "
                                 "model never shows in x (check the plant's B1 and the model)")

    @property
    def n_states(self) -> int:
        """The augmented state's dimension (the plant's plus the model's)."""
        return self.Phi.shape[0]

    def update(self, prior, y):
        """The filtered estimate ``ξ̂_{k|k}`` from its prediction and the sample y_k.

        Parameters
        ----------
        prior : (N,) ndarray
            ``ξ̂_{k|k−1}``.
        y : (n,) ndarray
            The sample ``y_k``.

        Returns
        -------
        (N,) ndarray
        """
        return prior + self.gain @ (y - self.H @ prior)

    def predict(self, filtered, u):
        """The prediction ``ξ̂_{k+1|k} = Phi ξ̂_{k|k} + Gamma u_k``.

        Parameters
        ----------
        filtered : (N,) ndarray
            ``ξ̂_{k|k}``.
        u : (m_u,) ndarray
            The control held over the step.

        Returns
        -------
        (N,) ndarray
        """
        return self.Phi @ filtered + self.Gamma @ u

    def estimate(self, y, u, prior=None):
        """Run the filter over samples.

        Parameters
        ----------
        y : (K, n) array_like
            The samples ``y_k = x(t_k) + v_k``, k = 0 … K−1.
        u : (K, m_u) array_like
            The control held over ``[t_k, t_{k+1})`` (its last row is not used).
        prior : (N,) array_like, optional
            ``ξ̂_{0|−1}``, the estimate before the first sample (default 0).

        Returns
        -------
        w_hat : (K, m) ndarray
            ``ŵ_k = C_d η̂_{k|k}``.
        xi : (K, N) ndarray
            The filtered estimates of the augmented state.
        """
        n, mu, N = self.plant.n_states, self.plant.n_controls, self.n_states
        y = as_matrix("y", y, (None, n))
        u = as_matrix("u", u, (y.shape[0], mu))
        xi_k = np.zeros(N) if prior is None else np.array(as_vector("prior", prior, N, allow_scalar=False))
        out = np.empty((y.shape[0], N))
        for k in range(y.shape[0]):
            xi_k = self.update(xi_k, y[k])
            out[k] = xi_k
            xi_k = self.predict(xi_k, u[k])
        return out[:, n:] @ self.model.C.T, out

    def noiseless_run(self, x0, u, d):
        """Samples of the plant, without noise, under a disturbance the model holds constant over
        the run (``η`` fixed at a value with ``C_d η = d``; for the default model, d constant).

        A helper for checks: the filter's error on these samples follows
        :attr:`error_dynamics` exactly.

        Parameters
        ----------
        x0 : (n,) array_like
        u : (K, m_u) array_like
            The held control per step.
        d : float or (m,) array_like

        Returns
        -------
        y : (K, n) ndarray
        u : (K, m_u) ndarray
        """
        n = self.plant.n_states
        eta = np.linalg.lstsq(self.model.C, np.broadcast_to(np.asarray(d, float), (self.model.C.shape[0],)),
                              rcond=None)[0]
        if np.any(np.abs(self.model.A @ eta) > 1e-12 * max(1.0, np.linalg.norm(eta))):
            raise ValueError("d: the model does not hold this disturbance constant (A_d η ≠ 0)")
        u = as_matrix("u", u, (None, self.plant.n_controls))
        xi = np.concatenate([as_vector("x0", x0, n), eta])
        y = np.empty((u.shape[0], n))
        for k in range(u.shape[0]):
            y[k] = xi[:n]
            xi = self.Phi @ xi + self.Gamma @ u[k]
        return y, np.array(u)
