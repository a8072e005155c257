"""Fixed controllers tuned on a disturbance class: exact energies and a local search on them.

A band design attenuates the worst case over a band; the disturbances a controller will meet
are a class (a distribution of signals), and on a class the best fixed controller is the one
with the least expected cost over it, found by tuning on training draws of the class and judged
on others. :func:`tune_controller` minimizes the mean log output energy

    J(θ) = (1/N) Σ_k log ∫₀^{T_k} ‖z_k‖² dt

over N training disturbances (each run exactly from rest: :func:`loop_energy`), the log so that
no single loud draw dominates and a ratio of energies is what counts. The search is Nelder–Mead
(adaptive) from each given start; a loop that is not Hurwitz costs ``UNSTABLE``; an optional cap
on the loop's H∞ norm (a worst-case guard: the tuned controller must not give up the
disturbances the class does not contain) enters as a penalty on a fixed frequency grid and is
checked by a sweep afterwards. Two structures:

* ``"static"``: a gain K;
* ``"filtered"``: ``u = K_low x + (K_high − K_low)(x − x_f)``, ``ẋ_f = ω_c (x − x_f)``
  (:meth:`fdsc.Controller.filtered`): n filter states, the gain K_low well below ω_c and
  K_high well above it, a fixed controller that does what switching between two gains by
  frequency sets out to do.

It is a local search: the result depends on its starts, and a better controller may exist.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize

from ._validation import as_choice, as_count, as_positive, as_vector, check_type
from .controller import Controller, as_controller
from .decisions import _largest, _scaled
from .exceptions import EnergyOverflowError, InfeasibleError, UnstableError
from .plant import LTISystem, as_plant
from .signals import Piecewise, Sinusoids

__all__ = ["loop_energy", "TuneResult", "tune_controller", "STRUCTURES", "UNSTABLE"]

#: The search's structures.
STRUCTURES = ("static", "filtered", "held")
#: The objective's value for a loop that is not Hurwitz (above any mean log energy met in
#: practice: e^1000 overflows).
UNSTABLE = 1e3
#: The H∞ penalty's weight per unit of log excess over the cap, and the grid it is checked on.
HINF_PENALTY = 100.0
HINF_GRID = np.logspace(-3, 4, 300)


class _ClassEnergies:
    """The exact energies of one loop over many disturbances at once, from rest, in the loop's
    eigenbasis (``A = V Λ V⁻¹``): on a piece of length L with tones ``a_j sin(ω_j t + φ_j)`` the
    state is a particular sinusoidal solution plus ``e^{Aτ} e_0``, and every term of
    ``∫ ‖z‖²`` (the sinusoids' products, their products with the transient, the transient's
    own Gramian) is a closed form in ``λ``, ``ω`` and L. Vectorized over the disturbances, in
    sequence over the pieces. A loop whose eigenbasis is ill-conditioned (``cond(V)`` above
    :data:`EIG_COND`) goes to the block-exponential engine instead."""

    def __init__(self, disturbances, horizons):
        from ._blocks import pieces

        per = [pieces(d, h) for d, h in zip(disturbances, horizons, strict=True)]
        self.grids = None
        self.disturbances, self.horizons = list(disturbances), list(horizons)
        K, P = len(per), max(len(p) for p in per)
        T = max(max((q[2].size for q in p), default=0) for p in per)
        self.L = np.zeros((K, P))
        self.w = np.zeros((K, P, T))
        self.a = np.zeros((K, P, T))
        self.th = np.zeros((K, P, T))
        for k, pc in enumerate(per):
            for j, (t0, t1, w, a, ph) in enumerate(pc):
                self.L[k, j] = t1 - t0
                self.w[k, j, :w.size], self.a[k, j, :w.size] = w, a
                self.th[k, j, :w.size] = w * t0 + ph
        self.w[self.a == 0] = 1.0                  # padding: a harmless frequency, no amplitude

    def exact(self, loop):
        if self.grids is None:
            self.grids = [_grid(d, h) for d, h in zip(self.disturbances, self.horizons, strict=True)]
        return np.array([_run(loop, g) for g in self.grids])

    def __call__(self, loop):
        A, B, C, D = loop.A, loop.B[:, 0], loop.C, loop.D[:, 0]
        lam, V = np.linalg.eig(A)
        if np.any(lam.real >= 0) or np.linalg.cond(V) > EIG_COND:
            return self.exact(loop)
        Vi = np.linalg.inv(V)
        Ch, Bh = C @ V, Vi @ B
        CC = Ch.conj().T @ Ch
        s_pq = lam.conj()[:, None] + lam[None, :]
        K, P = self.L.shape
        x = np.zeros((K, A.shape[0]))                       # the state at a piece's start
        total = np.zeros(K)
        with np.errstate(over="ignore", invalid="ignore"):
            for j in range(P):
                L = self.L[:, j][:, None]                   # (K, 1)
                w, ph = self.w[:, j], self.a[:, j] * np.exp(1j * self.th[:, j])
                jw = 1j * w                                 # (K, T)
                vh = Bh * ph[..., None] / (jw[..., None] - lam)           # (K, T, n), eigen-coords
                wz = vh @ Ch.T + D * ph[..., None]                          # (K, T, p)
                e0 = x - (vh @ V.T).sum(axis=1).imag                        # x − x_p(t0)
                eh = e0 @ Vi.T
                # the tones' own part: ½ Re Σ w_tᴴ w_s I(ω_s − ω_t) − ½ Re Σ w_tᵀ w_s I(ω_t + ω_s)
                dnu = w[:, :, None] - w[:, None, :]
                snu = w[:, :, None] + w[:, None, :]
                Lk = L[:, :, None]
                I1 = np.where(np.abs(dnu) * Lk < 1e-12, Lk + 0j,
                              (np.exp(1j * dnu * Lk) - 1) / (1j * np.where(dnu == 0, 1.0, dnu)))
                I2 = (np.exp(1j * snu * Lk) - 1) / (1j * snu)
                M1 = np.einsum("ktp,ksp->kts", wz.conj(), wz)
                M2 = np.einsum("ktp,ksp->kts", wz, wz)
                part = 0.5 * np.real(np.sum(M1 * np.conj(I1), axis=(1, 2))) \
                    - 0.5 * np.real(np.sum(M2 * I2, axis=(1, 2)))
                # the transient's Gramian over the piece
                Gm = CC[None] * (np.exp(s_pq[None] * Lk) - 1) / s_pq[None]
                trans = np.real(np.einsum("kp,kpq,kq->k", eh.conj(), Gm, eh))
                # twice the tones' product with the transient
                mu = lam[None, None, :] + jw[..., None]
                g = (np.exp(mu * Lk) - 1) / mu                               # (K, T, n)
                cross = 2 * np.imag(np.einsum("ktp,pn,ktn,kn->k", wz, Ch, g, eh))
                total += part + trans + cross
                x = ((eh * np.exp(lam * L)) @ V.T).real \
                    + ((vh * np.exp(jw * L)[..., None]) @ V.T).sum(axis=1).imag
        if not np.all(np.isfinite(total)):
            return self.exact(loop)
        return total


#: Above this condition number of the eigenvectors, :class:`_ClassEnergies` uses the exact
#: block-exponential engine.
EIG_COND = 1e6


def _grid(d, horizon):
    from ._blocks import Grid

    check_type("d", d, Sinusoids | Piecewise, "an fdsc.Sinusoids or fdsc.Piecewise")
    return Grid(d, np.array([0.0, as_positive("horizon", horizon)]))


def _run(loop, g, x0=None):
    x0 = np.zeros(loop.A.shape[0]) if x0 is None else x0
    return float(g.run(g.tables([(loop.A, loop.B, loop.C, loop.D)]), 0, False, x0)[0].sum())


def loop_energy(loop, d, horizon: float, *, x0=None) -> float:
    """∫₀ᴴ zᵀz of a fixed loop under d from x0, exactly (Van Loan's block exponential on each
    piece of d: no quadrature, no step).

    Parameters
    ----------
    loop : LTISystem
        One input (d).
    d : Sinusoids or Piecewise
    horizon : float
        H > 0 (s).
    x0 : (n,) array_like, optional
        Default 0.

    Returns
    -------
    float

    Raises
    ------
    TypeError, ValueError
        If the input is not of these types, the loop has more than one input, or x0 has the
        wrong size or a non-finite entry.
    EnergyOverflowError
        If the energy exceeds the float range.

    Examples
    --------
    >>> from fdsc import LTISystem
    >>> e = loop_energy(LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]]), Sinusoids([1.0], [1.0]), 2000.0)
    >>> round(e / 2000.0, 3)                    # the steady state: |1/(j + 1)|² / 2 = 1/4
    0.25
    """
    check_type("loop", loop, LTISystem, "an fdsc.LTISystem")
    if loop.B.shape[1] != 1:
        raise ValueError(f"loop must have one input, but has {loop.B.shape[1]}")
    g = _grid(d, horizon)
    x = None if x0 is None else as_vector("x0", x0, loop.A.shape[0])
    e = _run(loop, g, x)
    if not math.isfinite(e):
        raise EnergyOverflowError("loop_energy: the energy exceeds the float range (about 1.8e308)")
    return e


@dataclass(frozen=True)
class TuneResult:
    """A controller tuned on a class (see :func:`tune_controller`).

    Parameters
    ----------
    controller : Controller
    objective : float
        Its mean log energy on the training disturbances.
    start_objectives : tuple of float
        The objective at each start.
    evaluations : int
        Objective evaluations in all.
    hinf : float
        The H∞ norm of its loop (a refined sweep).
    hinf_cap : float or None
    structure : str
    """

    controller: Controller
    objective: float
    start_objectives: tuple
    evaluations: int
    hinf: float
    hinf_cap: float | None
    structure: str


#: The largest relative excess of the tuned loop's H∞ norm over ``hinf_cap`` that is accepted (the
#: penalty is evaluated on a grid; the refined sweep may find a peak slightly above it).
CAP_RTOL = 1e-3


def _training(disturbances, horizons):
    """The training draws validated, each scaled by a power of two to a largest amplitude in
    [½, 1), and the shift ``mean_k 2 e_k log 2`` that restores the mean log energy of the draws as
    given: the objective then does not depend on the disturbances' units (an energy near 1e-320
    would otherwise be subnormal or zero)."""
    if isinstance(disturbances, Sinusoids | Piecewise) or not hasattr(disturbances, "__len__"):
        raise TypeError("disturbances must be a sequence of Sinusoids or Piecewise")
    if not hasattr(horizons, "__len__") or len(disturbances) == 0 or len(disturbances) != len(horizons):
        found = len(horizons) if hasattr(horizons, "__len__") else repr(horizons)
        raise ValueError(f"disturbances and horizons must be non-empty and of one length, but found "
                         f"{len(disturbances)} and {found}")
    out, exps = [], []
    for k, (d, h) in enumerate(zip(disturbances, horizons, strict=True)):
        check_type(f"disturbances[{k}]", d, Sinusoids | Piecewise, "an fdsc.Sinusoids or fdsc.Piecewise")
        as_positive(f"horizons[{k}]", h)
        big = _largest(d)
        if big == 0.0:
            raise ValueError(f"disturbances[{k}] is zero: its log energy is undefined (leave it out)")
        e = math.frexp(big)[1]
        exps.append(e)
        out.append(_scaled(d, e))
    return out, [float(h) for h in horizons], 2.0 * math.log(2.0) * float(np.mean(exps))


def _feedforward_poles(feedforward, plant):
    """None (no feedforward), or the filter poles (an empty array for a static feedforward)."""
    if feedforward is None:
        return None
    if plant.B1.shape[1] != 1:
        raise ValueError(f"feedforward: the plant must have one disturbance input, but has "
                         f"{plant.B1.shape[1]}")
    if isinstance(feedforward, str):
        as_choice("feedforward", feedforward, ("static",))
        return np.zeros(0)
    p = as_vector("feedforward", feedforward)
    if np.any(p <= 0):
        raise ValueError(f"feedforward: the filter poles must be positive (rad/s), but found {p.tolist()}")
    from .frequency import POLE_RTOL

    if np.any(p <= POLE_RTOL):
        raise ValueError(f"feedforward: the filter poles must lie above {POLE_RTOL:g} rad/s (a slower filter "
                         f"is an integrator to the H∞ sweep's tolerance), but found {p.tolist()}")
    p = np.sort(p)
    if np.any(np.diff(p) <= 1e-9 * p[1:]):
        raise ValueError(f"feedforward: the filter poles must be distinct (a repeated pole adds a state "
                         f"with the same response), but found {p.tolist()}")
    return p


def _unpack(theta, structure, shape, scale):
    m, n = shape
    if structure == "static":
        return Controller.static((scale * theta).reshape(shape))
    k = m * n
    return Controller.filtered((scale * theta[:k]).reshape(shape), (scale * theta[k:2 * k]).reshape(shape),
                               math.exp(float(np.clip(theta[-1], -30.0, 30.0))))


def _pack(c, structure, corner, scale):
    if structure == "static":
        if not c.is_static:
            raise ValueError(f"starts: the static search starts from gains, but found {c!r}")
        return c.gain.ravel() / scale
    if c.is_static:
        return np.r_[c.gain.ravel(), c.gain.ravel(), 0.0] / np.r_[np.full(2 * c.gain.size, scale), 1.0] \
            + np.r_[np.zeros(2 * c.gain.size), math.log(corner)]
    low, high, wc = Controller.filtered_parameters(c)
    return np.r_[low.ravel() / scale, high.ravel() / scale, math.log(wc)]


def tune_controller(plant, disturbances, horizons, starts, *, structure: str = "static",
                    feedforward=None, hinf_cap: float | None = None, corner: float = 1.0,
                    maxiter: int = 2000, rounds: int = 6, name: str = "") -> TuneResult:
    """A fixed controller of least mean log energy on training disturbances (module docstring).

    Parameters
    ----------
    plant : Plant
    disturbances : sequence of Sinusoids or Piecewise
        The training draws of the class (each run from rest).
    horizons : sequence of float
        Their run lengths (s).
    starts : sequence of gain or Controller
        Where the search starts (gains for ``"static"``; gains or filtered controllers for
        ``"filtered"``, a gain K starting as K_low = K_high = K with the corner ``corner``).
    structure : {"static", "filtered", "held"}, optional
        The feedback part (from x); ``"held"`` keeps the one start's feedback part as it is and
        tunes the feedforward only.
    feedforward : None, "static" or sequence of float, optional
        What the controller reads of the disturbance estimate ŵ (one disturbance input): None
        (default) nothing; ``"static"`` a gain ``F ŵ``; a sequence of distinct poles p > 0 (rad/s,
        above 1e-10) the
        feedforward ``F ŵ + C_w ξ`` through first-order filters ``ξ̇_i = −p_i ξ_i + ŵ`` with the
        poles fixed and every gain tuned (its gains are exact for each feedback part: see
        Notes).
    hinf_cap : float, optional
        An upper bound on the loop's H∞ norm, kept as a penalty during the search.
    corner : float, optional
        ω_c (rad/s) of a filtered search started from a gain.
    maxiter : int, optional
        Nelder–Mead iterations per start (with a feedforward: per start and round).
    rounds : int, optional
        With a feedforward, the most rounds of (exact feedforward gains, Nelder–Mead on the
        feedback part) per start.
    name : str, optional
        The tuned controller's label.

    Returns
    -------
    TuneResult
        The best over the starts.

    Raises
    ------
    ValueError
        If the lists are empty or of different lengths, a disturbance is zero, ``structure`` is
        unknown, a start does not fit the structure, or a number is out of range.
    UnstableError
        If no start leads to a stabilizing controller (named ``starts``).
    InfeasibleError
        If ``hinf_cap`` is given and the best controller found exceeds it.

    Notes
    -----
    Each training disturbance is scaled by a power of two before its energy is integrated and
    the log energy shifted back, so the tuned controller does not depend on the disturbances'
    units and the objective moves by exactly ``2 log a`` when every draw is scaled by a.

    With a feedforward the energies are quadratic in its gains for a fixed feedback part; each
    round sets them to the least mean log energy exactly (majorization–minimization on the
    exact quadratics, :mod:`fdsc._feedforward_tuning`) and then searches the feedback part
    with them held (Nelder–Mead), until a round gains less than 1e-9 or ``rounds`` run out.
    The H∞ cap does not apply to it (the loop from d then includes the feedforward).

    Examples
    --------
    A static feedforward on ŵ nearly cancels a matched disturbance (ẋ = −x + d + u, z = [x; 0.1 u]):
    the energy of z over 200 s from rest falls from 80 (the start, u = 0) to about 0.1² ∫d² = 1,
    the price of u ≈ −d:

    >>> from fdsc import Plant
    >>> p = Plant([[-1.0]], [[1.0]], [[1.0]], [[1.0], [0.0]], [[0.0], [0.0]], [[0.0], [0.1]])
    >>> res = tune_controller(p, [Sinusoids([1.0], [0.5])], [200.0], [[[0.0]]], feedforward="static")
    >>> energies = np.exp([*res.start_objectives, res.objective])      # one draw: J = log energy
    >>> res.controller.reads_estimate, np.round(energies, 2).tolist()
    (True, [80.13, 0.99])
    """
    plant = as_plant(plant)
    structure = as_choice("structure", structure, STRUCTURES)
    disturbances, horizons, shift = _training(disturbances, horizons)
    if not hasattr(starts, "__len__") or len(starts) == 0:
        raise ValueError("starts must hold at least one gain or controller")
    cap = None if hinf_cap is None else as_positive("hinf_cap", hinf_cap)
    corner = as_positive("corner", corner)
    maxiter = as_count("maxiter", maxiter, 1)
    rounds = as_count("rounds", rounds, 1)
    poles = _feedforward_poles(feedforward, plant)
    if structure == "held" and (poles is None or len(starts) != 1):
        raise ValueError("structure 'held' needs a feedforward and exactly one start (the feedback part "
                         "it holds)")
    if poles is not None and cap is not None:
        raise ValueError("hinf_cap applies to controllers that read x only (feedforward=None)")
    energies = _ClassEnergies(disturbances, horizons)
    starts = [as_controller(s, plant, f"starts[{k}]") for k, s in enumerate(starts)]
    for k, s in enumerate(starts):
        if s.reads_estimate:
            raise ValueError(f"starts[{k}] reads ŵ: start from its feedback part (the feedforward gains "
                             "are set exactly)")
    shape = (plant.n_controls, plant.n_states)
    scale = max(1.0, max(float(np.abs(s.D).max()) for s in starts))
    if poles is not None:
        from ._feedforward_tuning import tune_feedforward

        ctrl, J, first, evals, hinf = tune_feedforward(plant, energies, shift, starts, structure, poles,
                                                       corner, scale, maxiter, rounds, name, _pack, _unpack,
                                                       UNSTABLE)
        return TuneResult(ctrl, J, first, evals, hinf, None, structure)
    evals = 0

    def f(theta, refined=False):
        nonlocal evals
        evals += 1
        loop = _unpack(theta, structure, shape, scale).closed_loop(plant)
        if not np.all(np.isfinite(loop.A)) or np.max(np.linalg.eigvals(loop.A).real) >= 0:
            return UNSTABLE
        with np.errstate(all="ignore"):
            J = float(np.mean(np.log(energies(loop)))) + shift
        if not math.isfinite(J):
            return UNSTABLE
        if cap is not None:
            from .bands import Band
            from .frequency import band_peak, sigma_max

            # on a fixed grid while searching; refined (between grid points too) to polish
            peak = (band_peak(loop, Band.entire()).gamma if refined
                    else float(sigma_max(loop, HINF_GRID).max()))
            J += HINF_PENALTY * max(0.0, math.log(peak / cap))
        return J

    best, first = None, []
    for s in starts:
        x0 = _pack(s, structure, corner, scale)
        first.append(f(x0))
        res = minimize(f, x0, method="Nelder-Mead",
                       options={"maxiter": maxiter, "xatol": 1e-8, "fatol": 1e-10, "adaptive": True})
        if best is None or res.fun < best.fun:
            best = res
    from .bands import Band
    from .frequency import band_peak

    ctrl = _unpack(best.x, structure, shape, scale)
    if cap is not None and best.fun < UNSTABLE and ctrl.closed_loop(plant).is_hurwitz() \
            and band_peak(ctrl.closed_loop(plant), Band.entire()).gamma > cap * (1.0 + CAP_RTOL):
        # the grid missed a peak between its points: polish with the refined peak
        best = minimize(lambda th: f(th, refined=True), best.x, method="Nelder-Mead",
                        options={"maxiter": max(200, maxiter // 4), "xatol": 1e-8, "fatol": 1e-10,
                                 "adaptive": True})
        ctrl = _unpack(best.x, structure, shape, scale)
    ctrl = Controller(ctrl.A, ctrl.B, ctrl.C, ctrl.D, name=name)
    loop = ctrl.closed_loop(plant)
    if best.fun >= UNSTABLE or not loop.is_hurwitz():
        lam = loop.poles()
        raise UnstableError(f"starts: no stabilizing controller found from the {len(starts)} start(s) (every "
                            f"loop the search met is unstable; the best has an eigenvalue at "
                            f"{complex(lam[-1]):.4g}): start from a stabilizing gain", complex(lam[-1]))
    hinf = band_peak(loop, Band.entire()).gamma
    if cap is not None and hinf > cap * (1.0 + CAP_RTOL):
        raise InfeasibleError(f"hinf_cap: the search found no controller with ‖loop‖∞ ≤ {cap:.6g} (the best "
                              f"it found has {hinf:.6g}); raise the cap or start from a controller that "
                              "meets it", "cap not met")
    return TuneResult(ctrl, float(best.fun), tuple(first), evals, float(hinf), cap, structure)
