"""Frequency-weighted H∞ state feedback: one dynamic controller that attenuates two bands at once.

A static gain gives one loop, and with it one trade-off between the bands (the multi-band front
of :func:`fdsc.pareto_front`). A controller with states can do better: it may act like one gain
in one band and like another gain in the other. The classical way to design one (Zames 1981;
the multi-band idea of Iwasaki and Hara 2005 in its weighted form) weights the regulated output
by a filter ``W(s)`` that is large where attenuation matters and synthesizes H∞ state feedback
for the weighted plant::

    ‖W G‖∞ < γ   ⇒   σ_max(G(jω)) < γ / |W(jω)|  at every ω.

Here ``W(s) = w_lf L(s) + w_hf H(s) + floor``, with L a second-order Butterworth low-pass at
the LF band's edge and H a high-pass at the HF band's edge, applied to every output. The weight
filter's states are driven by ``z = C x + D1 d + D2 u``, which the controller can form from x
and u when ``D1 = 0`` (and from ŵ as well otherwise), so state feedback on the weighted plant's
state ``[x; x_w]`` (:func:`fdsc.synthesize_hinf`, the existing LMI) is a controller with the
weight's states as its own (:class:`fdsc.Controller`). A penalty ``ρ u`` added to the output
bounds the controller's gain (its bandwidth); the controller's poles and size are reported.

Sweeping the ratio ``w_lf / w_hf`` traces a *dynamic front* (LF peak against HF peak) to set
beside the static one: :func:`dynamic_front`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ._plant_scaling import normalize_plant
from ._validation import as_nonnegative, as_positive, as_vector, check_type
from .bands import Band
from .controller import Controller
from .frequency import band_peak
from .plant import LTISystem, Plant, as_plant

__all__ = ["band_weight", "WeightedDesign", "weighted_hinf", "DynamicFront", "dynamic_front"]

#: The weight's floor relative to the larger band weight (the gap between the bands is weighted
#: by at least this, so the design does not give it up entirely).
DEFAULT_FLOOR = 1e-2
#: The weight's corners lie this factor inside the gap between the bands (an octave, so that the
#: weight is not 3 dB down at a band's edge).
DEFAULT_CORNER = 2.0


def _butterworth(w, high):
    """(A, B, C, D) of a second-order Butterworth low-pass (or high-pass) at ``w`` rad/s."""
    A = np.array([[0.0, 1.0], [-w * w, -math.sqrt(2.0) * w]])
    B = np.array([[0.0], [1.0]])
    if high:                 # s² / (s² + √2 w s + w²) = 1 − (√2 w s + w²) / (…)
        return A, B, np.array([[-w * w, -math.sqrt(2.0) * w]]), np.array([[1.0]])
    return A, B, np.array([[w * w, 0.0]]), np.array([[0.0]])


def band_weight(lf: Band, hf: Band, w_lf: float, w_hf: float, *, floor: float = DEFAULT_FLOOR,
                corner: float = DEFAULT_CORNER) -> LTISystem:
    """The scalar weight ``W(s) = w_lf L(s) + w_hf H(s) + floor · max(w_lf, w_hf)``.

    Parameters
    ----------
    lf : Band
        An LF band (L is a Butterworth low-pass at ``corner · ϖ_l``).
    hf : Band
        An HF band (H is a Butterworth high-pass at ``ϖ_h / corner``).
    w_lf, w_hf : float
        The weights of the two bands (≥ 0, not both 0).
    floor : float, optional
        The weight everywhere, relative to the larger band weight.
    corner : float, optional
        How far (a factor ≥ 1) the corners lie inside the gap; at most ``sqrt(ϖ_h / ϖ_l)``.

    Returns
    -------
    LTISystem
        Four states, one input, one output.

    Raises
    ------
    ValueError
        If the bands are not an LF and an HF band with ϖ_l < ϖ_h, or a weight is negative.

    Examples
    --------
    >>> from fdsc import freqresp
    >>> W = band_weight(Band.lf(1.0), Band.hf(10.0), 4.0, 1.0)
    >>> np.round(np.abs(freqresp(W, [0.01, 1.0, 10.0, 1e3])[:, 0, 0]), 2).tolist()
    [4.04, 3.87, 0.86, 1.04]
    """
    check_type("lf", lf, Band)
    check_type("hf", hf, Band)
    if lf.kind != "LF" or hf.kind != "HF" or not lf.upper < hf.lower:
        raise ValueError(f"lf and hf must be an LF band and an HF band above it, but found {lf.label} "
                         f"and {hf.label}")
    w_lf, w_hf = as_nonnegative("w_lf", w_lf), as_nonnegative("w_hf", w_hf)
    corner = as_positive("corner", corner)
    if not 1.0 <= corner <= math.sqrt(hf.lower / lf.upper):
        raise ValueError(f"corner must lie in [1, {math.sqrt(hf.lower / lf.upper):.4g}] (the corners "
                         f"inside the gap, not crossing), but found {corner!r}")
    if w_lf == 0 and w_hf == 0:
        raise ValueError("w_lf and w_hf are both 0: the weight would be the floor alone")
    floor = as_nonnegative("floor", floor) * max(w_lf, w_hf)
    A1, B1, C1, D1 = _butterworth(corner * lf.upper, False)
    A2, B2, C2, D2 = _butterworth(hf.lower / corner, True)
    A = np.block([[A1, np.zeros((2, 2))], [np.zeros((2, 2)), A2]])
    return LTISystem(A, np.vstack([B1, B2]), np.hstack([w_lf * C1, w_hf * C2]),
                     w_lf * D1 + w_hf * D2 + floor)


@dataclass(frozen=True)
class WeightedDesign:
    """A weighted H∞ design (see :func:`weighted_hinf`).

    Parameters
    ----------
    controller : Controller
        From x (and ŵ when ``D1 ≠ 0``) to u; its states are the weight's.
    gamma : float
        ‖W G‖∞ (with the u penalty) certified by the synthesis LMI.
    peaks : dict
        ``{"LF": γ, "HF": γ}``: the band peaks of the true loop (plant and controller).
    poles : ndarray
        The controller's own poles.
    size : float
        The controller's largest gain from x to u over frequency (:meth:`Controller.size`).
    loop_poles : ndarray
        The closed loop's poles.
    """

    controller: Controller
    gamma: float
    peaks: dict
    poles: np.ndarray
    size: float
    loop_poles: np.ndarray


def weighted_hinf(plant, lf: Band, hf: Band, w_lf: float, w_hf: float, *, u_penalty: float = 0.0,
                  floor: float = DEFAULT_FLOOR, corner: float = DEFAULT_CORNER,
                  name: str = "") -> WeightedDesign:
    """Frequency-weighted H∞ state feedback for two bands (module docstring).

    Parameters
    ----------
    plant : Plant, control.StateSpace or tuple
        The open-loop plant (:func:`fdsc.as_plant`: a StateSpace's first input is the
        disturbance; convert one with more with ``fdsc.as_plant(sys, n_disturbances=k)``).
    lf, hf : Band
        The LF and HF bands (see :func:`band_weight`).
    w_lf, w_hf : float
        Their weights: the ratio sets the trade-off.
    u_penalty : float, optional
        ρ ≥ 0: the output ``ρ u`` is added to the weighted output, which bounds the controller's
        gain (its bandwidth) at the price of attenuation.
    floor, corner : float, optional
        See :func:`band_weight`.
    name : str, optional
        The controller's label.

    Returns
    -------
    WeightedDesign

    Raises
    ------
    ValueError
        If the bands or weights are out of range (:func:`band_weight`) or ``u_penalty < 0``.
    InfeasibleError, SolverError, VerificationError
        As :func:`fdsc.synthesize_hinf` raises them.

    Notes
    -----
    The weighted plant is built from the plant in normalized units (d, u and z divided by the
    norms of B1, B2 and ``[C, D1, D2]``; ρ carried along so that the problem is the one posed)
    and the controller mapped back, so that a change of the units of d or u, or of z together
    with ``u_penalty``, gives the same closed loop, its γ and band peaks scaled by the change, up
    to the solver's tolerance. Where the optimum is not unique (the weighted norm leaves the
    peak of the band with the smaller weight free below its bound) that band's peak may move by
    up to a few parts in 10³ between such rescalings.

    Examples
    --------
    >>> from fdsc import random_plant
    >>> plant = random_plant(np.random.default_rng(7))
    >>> des = weighted_hinf(plant, Band.lf(1.0), Band.hf(10.0), 1.0, 1.0, u_penalty=0.1)
    >>> des.controller.n_states, bool(np.all(des.loop_poles.real < 0))   # 4 per output
    (8, True)
    """
    from .synthesis import synthesize_hinf

    plant = as_plant(plant)
    rho = as_nonnegative("u_penalty", u_penalty)
    W = band_weight(lf, hf, w_lf, w_hf, floor=floor, corner=corner)
    # designed in normalized units (fdsc._plant_scaling; the weight's states see z̃ = c_z z), so
    # that the units of z, d and u do not change the design; ‖[W z; ρ u]‖ = ‖[W z̃; ρ̃ ũ]‖ / c_z
    # with ρ̃ = ρ a_u c_z keeps the problem the caller posed
    sc = normalize_plant(plant)
    rho = rho * sc.a_u * sc.c_z
    A, B1, B2, C, D1, D2 = (sc.plant.A, sc.plant.B1, sc.plant.B2, sc.plant.C, sc.plant.D1,
                            sc.plant.D2)
    nz, n, m = C.shape[0], plant.n_states, plant.n_controls
    Aw = np.kron(np.eye(nz), W.A)
    Bw = np.kron(np.eye(nz), W.B)
    Cw = np.kron(np.eye(nz), W.C)
    Dw = float(W.D[0, 0]) * np.eye(nz)
    nw = Aw.shape[0]
    Aa = np.block([[A, np.zeros((n, nw))], [Bw @ C, Aw]])
    B1a = np.vstack([B1, Bw @ D1])
    B2a = np.vstack([B2, Bw @ D2])
    Ca = np.block([[Dw @ C, Cw], [np.zeros((m, n + nw))]])
    D1a = np.vstack([Dw @ D1, np.zeros((m, B1.shape[1]))])
    D2a = np.vstack([Dw @ D2, rho * np.eye(m)])
    if rho == 0:
        Ca, D1a, D2a = Ca[:nz], D1a[:nz], D2a[:nz]
    res = synthesize_hinf(Plant(Aa, B1a, B2a, Ca, D1a, D2a))
    Kx, Kw = res.K[:, :n], res.K[:, n:]
    reads = bool(np.any(D1))
    # back to the plant's units: ŵ̃ = ŵ / a_d, u = a_u ũ (the weight's states keep z̃'s units)
    ctrl = Controller(Aw + Bw @ D2 @ Kw, Bw @ (C + D2 @ Kx), sc.a_u * Kw, sc.gain(Kx),
                      E=Bw @ D1 / sc.a_d if reads else None,
                      F=np.zeros((m, B1.shape[1])) if reads else None, name=name)
    loop = ctrl.closed_loop(plant)
    peaks = {"LF": band_peak(loop, lf).gamma, "HF": band_peak(loop, hf).gamma}
    return WeightedDesign(ctrl, sc.gamma(float(res.gamma_lmi)), peaks, ctrl.poles(), ctrl.size(),
                          loop.poles())


@dataclass(frozen=True)
class DynamicFront:
    """Weighted H∞ designs along a sweep of ``w_lf / w_hf`` (see :func:`dynamic_front`).

    Parameters
    ----------
    ratios : (k,) ndarray
    designs : tuple of WeightedDesign or None
        None where the solver failed (see ``failures``).
    failures : dict
        ``{ratio: the solver's message}`` of the failed points.
    """

    ratios: np.ndarray
    designs: tuple
    failures: dict

    def peaks(self) -> np.ndarray:
        """(k, 2): the LF and HF peak of each design (NaN where it failed)."""
        return np.array([[np.nan, np.nan] if d is None else [d.peaks["LF"], d.peaks["HF"]]
                         for d in self.designs])

    def nondominated(self) -> np.ndarray:
        """(k,) bool: designs that no other design beats in both bands (False where it failed)."""
        p = self.peaks()
        ok = np.all(np.isfinite(p), axis=1)
        q = p[ok]
        return np.array([bool(ok[i]) and not np.any(np.all(q <= p[i], axis=1) & np.any(q < p[i], axis=1))
                         for i in range(len(p))])


def dynamic_front(plant, lf: Band, hf: Band, ratios, *, u_penalty: float = 0.0,
                  floor: float = DEFAULT_FLOOR, corner: float = DEFAULT_CORNER) -> DynamicFront:
    """The dynamic front: :func:`weighted_hinf` at each ratio ``w_lf / w_hf`` (w_hf = 1).

    Parameters
    ----------
    plant : Plant, control.StateSpace or tuple
        As :func:`weighted_hinf` takes it.
    lf, hf : Band
    ratios : (k,) array_like
        Positive ratios.
    u_penalty, floor, corner : float, optional
        See :func:`weighted_hinf`.

    Returns
    -------
    DynamicFront
        A point whose synthesis fails (the solver's status, or a gain that fails its checks) is
        None, with the message in ``failures``: a weighting the LMI cannot resolve is a gap in
        the front, not an error of the sweep.

    Raises
    ------
    ValueError
        If a ratio is not positive and finite, or the bands or ``u_penalty`` are out of range.
    """
    from .exceptions import SolverError, VerificationError

    ratios = np.sort(as_vector("ratios", ratios))
    if ratios.size == 0 or not np.all(np.isfinite(ratios)) or np.any(ratios <= 0):
        raise ValueError(f"ratios must be positive and finite, at least one, but found {ratios.tolist()}")
    as_nonnegative("u_penalty", u_penalty)
    band_weight(lf, hf, 1.0, 1.0, floor=floor, corner=corner)      # refuse bad bands before solving
    designs, failures = [], {}
    for r in ratios:
        try:
            designs.append(weighted_hinf(plant, lf, hf, float(r), 1.0, u_penalty=u_penalty, floor=floor,
                                         corner=corner, name=f"weighted H∞ {r:.3g}:1"))
        except (SolverError, VerificationError) as exc:
            designs.append(None)
            failures[float(r)] = str(exc)
    return DynamicFront(ratios, tuple(designs), failures)
