"""The feedforward part of a tuned controller that reads ŵ (internal, for :func:`fdsc.tune_controller`).

A controller that reads x and the estimate ŵ adds to its feedback part ``u_fb`` (a gain or the
filtered structure) a feedforward through fixed first-order filters on ŵ::

    u = u_fb + F ŵ + C_w ξ,      ξ̇ = −diag(p) ξ + 1 ŵ,

with the poles p fixed (none: a static feedforward F ŵ) and the gains ``g = [F, C_w]`` free.
For a fixed feedback part every output energy is a quadratic in g (the loop is linear in the
signal u_ff that g weights), ``E_k(g) = c_k + 2 b_kᵀ g + gᵀ M_k g``, whose coefficients follow
exactly from the energies at a few gains (polarization). The mean log energy is then minimized
over g by majorization–minimization: ``log E ≤ log E⁰ + (E − E⁰)/E⁰`` makes each step the
weighted least-squares problem ``min Σ_k E_k(g)/E_k(g⁰)``, which never increases the
objective. The tuning alternates this exact step with a Nelder–Mead search over the feedback
part (variable projection by blocks).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import minimize

from .controller import Controller
from .exceptions import UnstableError

__all__ = []

#: Iterations of the majorization–minimization over the feedforward gains, and its tolerance.
MM_ITER, MM_TOL = 200, 1e-12


def with_feedforward(fb: Controller, poles, gains, name: str = "") -> Controller:
    """The controller ``u = fb(x) + F ŵ + C_w ξ`` (module docstring) for one disturbance input;
    ``gains`` is (m_u, 1 + len(poles)): F first, then C_w."""
    p = np.asarray(poles, dtype=float)
    nf, k = p.size, fb.n_states
    m, n = fb.D.shape
    g = np.asarray(gains, dtype=float).reshape(m, 1 + nf)
    A = np.zeros((k + nf, k + nf))
    A[:k, :k] = fb.A
    A[k:, k:] = -np.diag(p)
    B = np.vstack([fb.B, np.zeros((nf, n))])
    C = np.hstack([fb.C, g[:, 1:]])
    E = np.vstack([np.zeros((k, 1)), np.ones((nf, 1))])
    return Controller(A, B, C, fb.D, E=E, F=g[:, :1], name=name)


class Quadratic:
    """``E_k(g) = c_k + 2 b_kᵀ g + gᵀ M_k g`` for every training draw k, from the exact energies
    of the loops at chosen gains (see the module docstring)."""

    def __init__(self, energies, loop_of, q, step=None):
        # each gain probed at a step that changes the energies by about their size, so that no
        # coefficient is lost to rounding against the others
        c = energies(loop_of(np.zeros(q)))
        s = np.ones(q) if step is None else np.asarray(step, dtype=float)
        up = np.empty((q, c.size))
        dn = np.empty((q, c.size))
        for i in range(q):
            e = np.zeros(q)
            e[i] = s[i]
            up[i], dn[i] = energies(loop_of(e)), energies(loop_of(-e))
        diag = 0.5 * (up + dn) - c                      # s_i² M_ii per draw
        lin = 0.25 * (up - dn)                          # s_i b_i per draw
        M = np.zeros((c.size, q, q))
        for i in range(q):
            M[:, i, i] = diag[i]
            for j in range(i + 1, q):
                e = np.zeros(q)
                e[i], e[j] = s[i], s[j]
                both = energies(loop_of(e))
                # E(e_i + e_j) = c + 2(b_i + b_j) + M_ii + M_jj + 2 M_ij  (scaled)
                M[:, i, j] = M[:, j, i] = 0.5 * (both - c - 2 * (lin[i] + lin[j]) - diag[i] - diag[j])
        self.c, self.b, self.M, self.s = c, lin.T, M, s      # in the scaled gains g / s

    def energies(self, g) -> np.ndarray:
        h = np.asarray(g, dtype=float) / self.s
        return self.c + 2 * self.b @ h + np.einsum("i,kij,j->k", h, self.M, h)

    def minimize(self, g0=None) -> np.ndarray:
        """The gains of least mean log energy (majorization–minimization from g0, default 0)."""
        q = self.s.size
        h = np.zeros(q) if g0 is None else np.asarray(g0, dtype=float) / self.s
        f_old = math.inf
        for _ in range(MM_ITER):
            E = self.c + 2 * self.b @ h + np.einsum("i,kij,j->k", h, self.M, h)
            if np.any(E <= 0):
                break
            f = float(np.mean(np.log(E)))
            if f_old - f < MM_TOL * max(1.0, abs(f)):
                break
            f_old = f
            w = 1.0 / E
            Mw = np.einsum("k,kij->ij", w, self.M)
            bw = w @ self.b
            try:
                h = np.linalg.solve(Mw + 1e-14 * np.trace(Mw) * np.eye(q), -bw)
            except np.linalg.LinAlgError:
                h = np.linalg.lstsq(Mw, -bw, rcond=None)[0]
        return h * self.s


def tune_feedforward(plant, energies, shift, starts, structure, poles, corner, scale, maxiter, rounds,
                     name, pack, unpack, UNSTABLE):
    """Rounds of exact feedforward gains and Nelder–Mead on the feedback part (for
    :func:`fdsc.tune_controller`)."""
    from .bands import Band
    from .frequency import band_peak

    shape = (plant.n_controls, plant.n_states)
    q = plant.n_controls * (1 + poles.size)
    evals = 0

    def loop_of(fb, g):
        return with_feedforward(fb, poles, g).closed_loop(plant)

    def objective(E):
        with np.errstate(all="ignore"):
            J = float(np.mean(np.log(E))) + shift
        return J if math.isfinite(J) else UNSTABLE

    def stable(fb):
        A = fb.closed_loop(plant).A
        return np.all(np.isfinite(A)) and np.max(np.linalg.eigvals(A).real) < 0

    def gains_for(fb, g0):
        nonlocal evals
        quad = Quadratic(energies, lambda g: loop_of(fb, g), q, _probe_steps(energies, loop_of, fb, q))
        evals += 1 + q + q * (q + 1) // 2
        return quad.minimize(g0)

    best = None
    first = []
    for s in starts:
        if structure == "held":
            theta, fb = None, s
        else:
            theta = pack(s, structure, corner, scale)
            fb = unpack(theta, structure, shape, scale)
        if not stable(fb):
            first.append(UNSTABLE)
            continue
        g = gains_for(fb, None)
        J = objective(energies(loop_of(fb, g)))
        first.append(objective(energies(fb.closed_loop(plant))))
        for _r in range(0 if structure == "held" else rounds):
            held = g

            def f(th, held=held):
                nonlocal evals
                evals += 1
                c = unpack(th, structure, shape, scale)
                if not stable(c):
                    return UNSTABLE
                return objective(energies(loop_of(c, held)))

            res = minimize(f, theta, method="Nelder-Mead",
                           options={"maxiter": maxiter, "xatol": 1e-8, "fatol": 1e-10, "adaptive": True})
            theta = res.x
            fb = unpack(theta, structure, shape, scale)
            g = gains_for(fb, g)
            J_new = objective(energies(loop_of(fb, g)))
            done = J - J_new < 1e-9
            J = min(J, J_new)
            if done:
                break
        if best is None or J < best[0]:
            best = (J, fb, g)
    if best is None or best[0] >= UNSTABLE:
        raise UnstableError(f"starts: no stabilizing controller found from the {len(starts)} start(s): start "
                            "from a stabilizing gain")
    J, fb, g = best
    ctrl = with_feedforward(fb, poles, g, name=name)
    hinf = band_peak(ctrl.closed_loop(plant), Band.entire()).gamma
    return ctrl, float(J), tuple(first), evals, float(hinf)


def _probe_steps(energies, loop_of, fb, q):
    """Per feedforward gain, the step at which it changes the mean energy by about its size."""
    c = energies(loop_of(fb, np.zeros(q)))
    out = np.ones(q)
    for i in range(q):
        e = np.zeros(q)
        e[i] = 1.0
        up, dn = energies(loop_of(fb, e)), energies(loop_of(fb, -e))
        curv = float(np.mean(0.5 * (up + dn) - c))            # mean M_ii at unit step
        if curv > 0:
            out[i] = math.sqrt(float(np.mean(c)) / curv)
    return out
