"""Chapter 'generic example': a second plant, not in the paper, on which band-limited
design matters, run through the whole FDSC pipeline with the public API only.

The paper's introduction promises simulation results on "a generic and a common benchmark
model"; only the benchmark (the aircraft) is there, and on it the trade-off that FDSC is meant to
resolve barely exists. This module builds one where it does: a two-mass chain (a soft-mounted
base, mass m_1 = 1, carrying a light appendage, mass m_2 = 0.3, on a stiff spring), the force u
acting on the base and the disturbance d on the appendage, the performance output the
appendage's position and velocity and the control effort. Holding the appendage still against a
slow force needs a stiff base, and a stiff base pushes the lightly damped appendage mode into the
HF band; damping that mode needs a base that moves. The LF design therefore beats H∞ by a wide
margin in its band and loses by a wider one in the HF band.

Everything goes through ``import fdsc`` as a user with their own plant would (README, "Use it on
your own plant"); from the paper layer only the cache, the record and :class:`Example` are used.
"""

import math
import time
from dataclasses import dataclass

import numpy as np

import fdsc
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.examples import OPEN_LOOP, Comparison, Example, beats
from fdsc.paper.shared.results import RecordPart, entry

__all__ = [
    "PLANT_PARAMETERS", "W_L", "W_H", "LF_EPSILON", "HF_SIGMA", "IN_BAND", "DWELL",
    "LF_TONES", "HF_TONES", "HORIZON", "DT", "RHO_P", "RHO_T", "T_SEGMENT", "RHO_P_STAR",
    "generic_plant", "generic_bands", "lf_disturbance", "hf_disturbance", "mixed_disturbance",
    "piecewise_disturbance", "generic_example", "BandDesign", "SweepWin", "Headline",
    "GenericStudy", "generic_study", "chosen_runs", "record_part",
]

#: The chain: base mass m1 on the ground spring k0 (damper c0), appendage m2 on the spring k
#: (damper c); weights of the appendage's velocity and of the control effort in z.
PLANT_PARAMETERS = {"m1": 1.0, "m2": 0.3, "k0": 1.0, "k": 50.0, "c0": 0.05, "c": 0.15,
                    "w_v": 0.3, "rho": 0.05}
#: Band limits (rad/s): LF is ``|ω| ≤ W_L``, HF is ``|ω| ≥ W_H``.
W_L, W_H = 1.0, 10.0
#: ε of the LF synthesis (the default 1e-2 of fdsc.synthesize costs 33 % in band; see the study).
LF_EPSILON = 1.0
#: σ of the HF synthesis, 10 ϖ_h (σ = 0 leaves the HF design 56 % above H∞ in band; see the study).
HF_SIGMA = 10.0 * W_H
#: The in-band mode of the FDSC design (paper Remark 4 minimizes its γ): the LF mode, whose
#: advantage over H∞ is the one FDSC is there to keep.
IN_BAND = 0
#: Minimum dwell time of the well-posed law: three periods at the HF band's edge, 3·2π/ϖ_h (s).
DWELL = round(3 * 2 * math.pi / W_H, 3)
#: Where random tones are drawn (rad/s), inside the bands.
LF_TONES, HF_TONES = (0.3, W_L), (W_H, 4 * W_H)
#: Run length and step (s).
HORIZON, DT = 100.0, 1e-3
#: ρ_p of d = d_h + ρ_p d_l (21 points, log grid).
RHO_P = tuple(float(x) for x in np.geomspace(0.01, 100.0, 21))
#: ρ_t of the piecewise disturbance: HF on [0, T), ρ*_p LF on [T, T + ρ_t T), HF for T more.
RHO_T = tuple(round(0.1 * k, 1) for k in range(21))
T_SEGMENT, RHO_P_STAR = 50.0, 1.0

_CONTROLLERS = ("PassC-EF", "PassC-LF", "PassC-HF")
_REGIONS = ("LF", "gap", "HF")


def generic_plant(m2: float = PLANT_PARAMETERS["m2"], k: float = PLANT_PARAMETERS["k"],
                  rho: float = PLANT_PARAMETERS["rho"]) -> fdsc.Plant:
    """The two-mass chain, x = [q1, q2, v1, v2], u on the base, d on the appendage.

    Parameters
    ----------
    m2 : float, optional
        Appendage mass (> 0).
    k : float, optional
        Stiffness of the appendage's spring (> 0).
    rho : float, optional
        Weight of the control effort in z (> 0: D2 of full column rank).

    Returns
    -------
    fdsc.Plant
        ``z = [q2; w_v v2; ρ u]``, D1 = 0.

    Raises
    ------
    ValueError
        If a parameter is not a positive finite number.

    Examples
    --------
    >>> p = generic_plant()
    >>> p.n_states, p.n_controls, p.C.shape
    (4, 1, (3, 4))
    >>> bool(p.closed_loop([[0.0, 0.0, 0.0, 0.0]]).is_hurwitz())
    True
    """
    for name, value in (("m2", m2), ("k", k), ("rho", rho)):
        if not isinstance(value, int | float) or not math.isfinite(value) or value <= 0:
            raise ValueError(f"{name} must be a positive finite number, but found {value!r}")
    p = PLANT_PARAMETERS
    m1, k0, c0, c = p["m1"], p["k0"], p["c0"], p["c"]
    A = [[0.0, 0.0, 1.0, 0.0],
         [0.0, 0.0, 0.0, 1.0],
         [-(k0 + k) / m1, k / m1, -(c0 + c) / m1, c / m1],
         [k / m2, -k / m2, c / m2, -c / m2]]
    B1 = [[0.0], [0.0], [0.0], [1.0 / m2]]
    B2 = [[0.0], [0.0], [1.0 / m1], [0.0]]
    C = [[0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 0.0, p["w_v"]], [0.0, 0.0, 0.0, 0.0]]
    return fdsc.Plant(A, B1, B2, C, [[0.0], [0.0], [0.0]], [[0.0], [0.0], [rho]])


def generic_bands() -> dict:
    """``{"LF": Band.lf(W_L), "HF": Band.hf(W_H)}``.

    Returns
    -------
    dict

    Examples
    --------
    >>> [b.label for b in generic_bands().values()]
    ['LF [0, 1] rad/s', 'HF [10, ∞] rad/s']
    """
    return {"LF": fdsc.Band.lf(W_L), "HF": fdsc.Band.hf(W_H)}


def lf_disturbance() -> fdsc.Sinusoids:
    """The stationary LF disturbance: unit tones at 0.3, 0.6 and 0.9 rad/s.

    Returns
    -------
    fdsc.Sinusoids

    Examples
    --------
    >>> lf_disturbance().dominance(generic_bands()["LF"])
    1.0
    """
    return fdsc.Sinusoids([1.0, 1.0, 1.0], [0.3, 0.6, 0.9])


def hf_disturbance() -> fdsc.Sinusoids:
    """The stationary HF disturbance: unit tones at 14, 20 and 30 rad/s.

    The 14 rad/s tone sits near the open loop's appendage mode (14.7 rad/s), so that the open
    loop is not the best controller under HF tones, as it is on the paper's aircraft.

    Returns
    -------
    fdsc.Sinusoids

    Examples
    --------
    >>> hf_disturbance().dominance(generic_bands()["HF"])
    1.0
    """
    return fdsc.Sinusoids([1.0, 1.0, 1.0], [14.0, 20.0, 30.0])


def _nonnegative(name, value):
    if not isinstance(value, int | float) or not math.isfinite(value) or value < 0:
        raise ValueError(f"{name} must be a finite number >= 0, but found {value!r}")
    return float(value)


def mixed_disturbance(rho_p: float) -> fdsc.Sinusoids:
    """``d = d_h + ρ_p d_l`` (the family of paper Fig. 7 on this plant).

    Parameters
    ----------
    rho_p : float
        Weight ρ_p ≥ 0 of the LF part.

    Returns
    -------
    fdsc.Sinusoids

    Raises
    ------
    ValueError
        If ``rho_p`` is negative or not finite.

    Examples
    --------
    >>> mixed_disturbance(1.0).dominance(generic_bands()["HF"])
    0.5
    """
    rho_p = _nonnegative("rho_p", rho_p)
    return hf_disturbance() + lf_disturbance().scaled(rho_p)


def piecewise_disturbance(rho_t: float, T: float = T_SEGMENT,  # noqa: N803  (the paper's symbol)
                          rho_p_star: float = RHO_P_STAR) -> tuple:
    """HF on ``[0, T)``, ``ρ*_p`` LF on ``[T, T + ρ_t T)``, HF on ``[T + ρ_t T, 2T + ρ_t T)``
    (paper eq. (58) with this plant's tones), and its horizon.

    Parameters
    ----------
    rho_t : float
        Length of the LF segment relative to T (≥ 0).
    T : float, optional
        Length of each HF segment (s, > 0).
    rho_p_star : float, optional
        Weight of the LF segment (≥ 0).

    Returns
    -------
    d : fdsc.Piecewise
    horizon : float
        ``2T + ρ_t T`` (s).

    Raises
    ------
    ValueError
        If an argument is negative or not finite, or T is zero.

    Examples
    --------
    >>> d, h = piecewise_disturbance(0.5)
    >>> d.breaks.tolist(), h
    ([0.0, 50.0, 75.0, 125.0], 125.0)
    """
    rho_t, rho_p_star = _nonnegative("rho_t", rho_t), _nonnegative("rho_p_star", rho_p_star)
    if _nonnegative("T", T) == 0:
        raise ValueError("T must be > 0, but found 0")
    hf, lf = hf_disturbance(), lf_disturbance().scaled(rho_p_star)
    horizon = 2 * T + rho_t * T
    return fdsc.Piecewise([0.0, T, T + rho_t * T, horizon], (hf, lf, hf)), float(horizon)


@cached
def _synthesis() -> tuple:
    """H∞, LF and HF syntheses (SynthesisResult each)."""
    plant, bands = generic_plant(), generic_bands()
    return (fdsc.synthesize_hinf(plant), fdsc.synthesize(plant, bands["LF"], epsilon=LF_EPSILON),
            fdsc.synthesize(plant, bands["HF"], sigma=HF_SIGMA))


@cached
def generic_example(dwell: float = DWELL) -> Example:
    """The generic example: open loop, PassC-EF (H∞), PassC-LF, PassC-HF, FDSC and FDSC (dwell).

    Parameters
    ----------
    dwell : float, optional
        Minimum dwell time τ_d (s, > 0) of the "FDSC (dwell)" law.

    Returns
    -------
    Example
        FDSC switches between PassC-LF (mode 0, in band) and PassC-HF (mode 1) with Q's designed
        by Theorem 1 / paper Remark 4.

    Raises
    ------
    ValueError
        If ``dwell`` is not a positive finite number.
    """
    if not isinstance(dwell, int | float) or not math.isfinite(dwell) or dwell <= 0:
        raise ValueError(f"dwell must be a positive finite number of seconds, but found {dwell!r}")
    plant, bands = generic_plant(), generic_bands()
    hinf, lf, hf = _synthesis()
    ctrl = fdsc.FDSC.from_gains(plant, [lf.K, hf.K], [bands["LF"], bands["HF"]], IN_BAND)
    gains = {OPEN_LOOP: np.zeros_like(hinf.K), "PassC-EF": hinf.K, "PassC-LF": lf.K, "PassC-HF": hf.K}
    designs = {"FDSC": (ctrl, fdsc.PRINTED), "FDSC (dwell)": (ctrl, fdsc.SwitchRule.dwell_time(dwell))}
    return Example("generic", plant, bands, gains, designs, LF_TONES, HF_TONES, HORIZON, DT)


@dataclass(frozen=True)
class BandDesign:
    """One synthesized gain.

    Parameters
    ----------
    name : str
        Controller name ("PassC-EF", "PassC-LF", "PassC-HF").
    band : str
        Label of the band designed for.
    K : (1, 4) ndarray
        The gain.
    gamma_lmi : float
        Certified γ.
    gamma_sweep : float
        In-band peak of σ_max (band_peak), ≤ gamma_lmi.
    """

    name: str
    band: str
    K: np.ndarray
    gamma_lmi: float
    gamma_sweep: float


@dataclass(frozen=True)
class SweepWin:
    """Where along a sweep one FDSC law beats the best fixed controller, and by how much.

    Parameters
    ----------
    law : str
        The switched controller ("FDSC", "FDSC (dwell)").
    share : float
        Share of the grid points where its energy is below every fixed controller's.
    first, last : float
        Smallest and largest parameter where it wins (NaN if nowhere).
    best_gain : float
        Largest ratio (best fixed energy) / (its energy) over the grid (> 1: a win).
    at : float
        Parameter of ``best_gain``.
    worst_gain : float
        Smallest such ratio over the grid (< 1: where it loses most).
    """

    law: str
    share: float
    first: float
    last: float
    best_gain: float
    at: float
    worst_gain: float


@dataclass(frozen=True)
class Headline:
    """The chapter's headline numbers.

    Parameters
    ----------
    factor_lf, factor_hf : float
        PassC-EF's band peak over PassC-LF's in LF, and over PassC-HF's in HF.
    loss_lf, loss_hf : float
        PassC-LF's HF peak over PassC-EF's, and PassC-HF's LF peak over PassC-EF's.
    rho_p, rho_t : tuple of SweepWin
        One per FDSC law.
    """

    factor_lf: float
    factor_hf: float
    loss_lf: float
    loss_hf: float
    rho_p: tuple
    rho_t: tuple


@dataclass(frozen=True)
class GenericStudy:
    """Everything of the chapter (see :func:`generic_study`).

    Parameters
    ----------
    designs : tuple of BandDesign
        PassC-EF (H∞), PassC-LF, PassC-HF.
    epsilon_scan : (E, 2) ndarray
        ε and PassC-LF's in-band peak for that ε (why :data:`LF_EPSILON`).
    sigma_scan : (S, 2) ndarray
        σ and PassC-HF's in-band peak for that σ (why :data:`HF_SIGMA`).
    omega : (W,) ndarray
        Frequency grid (rad/s) of ``sigma``.
    sigma : dict
        ``{fixed controller: (W,) ndarray}``, σ_max of each closed loop.
    peaks : dict
        ``{fixed controller: (3,) ndarray}``, band peaks over LF, the gap ϖ_l ≤ ω ≤ ϖ_h and HF.
    theorem1_gammas : (2,) ndarray
        γ_i for which Theorem 1's LMIs are feasible with the designed Q's.
    Q : tuple of (4, 4) ndarray
        The law's Q's.
    stationary : Comparison
        Every controller under :func:`lf_disturbance` (point 0) and :func:`hf_disturbance` (1).
    rho_p : (P,) ndarray
    rho_p_sweep : Comparison
    rho_t : (R,) ndarray
    rho_t_sweep : Comparison
    ideal_rho_t : (R,) ndarray
        ∫zᵀz of the ideal segment law along ρ_t (PassC-HF on the HF pieces, PassC-LF on the LF
        piece, :meth:`~fdsc.paper.shared.examples.Example.segment_ideal`): what a law that knows the
        signal would reach with FDSC's two modes.
    headline : Headline
    compute_time : float
        Wall-clock seconds of the study (machine-dependent; not in the record).
    """

    designs: tuple
    epsilon_scan: np.ndarray
    sigma_scan: np.ndarray
    omega: np.ndarray
    sigma: dict
    peaks: dict
    theorem1_gammas: np.ndarray
    Q: tuple
    stationary: Comparison
    rho_p: np.ndarray
    rho_p_sweep: Comparison
    rho_t: np.ndarray
    rho_t_sweep: Comparison
    ideal_rho_t: np.ndarray
    headline: Headline
    compute_time: float

    @property
    def regions(self) -> tuple:
        """Labels of the columns of :attr:`peaks`."""
        return _REGIONS


def _win(comp: Comparison, param, law, fixed) -> SweepWin:
    _, best = comp.best(fixed)
    gain = best / comp.energy[law]
    won = param[beats(1.0 / gain)]
    k = int(np.argmax(gain))
    return SweepWin(law, float(np.mean(beats(1.0 / gain))), float(won.min()) if won.size else math.nan,
                    float(won.max()) if won.size else math.nan, float(gain[k]), float(param[k]),
                    float(gain.min()))


@cached
def generic_study(n_omega: int = 2000) -> GenericStudy:
    """Synthesis per band, σ_max curves, band peaks, Theorem 1, stationary runs and both sweeps.

    Parameters
    ----------
    n_omega : int, optional
        Points (≥ 100) of the logarithmic frequency grid of the σ_max curves, 1e-2 to 1e3 rad/s.

    Returns
    -------
    GenericStudy

    Raises
    ------
    ValueError
        If ``n_omega`` is not an integer ≥ 100.
    """
    if isinstance(n_omega, bool) or not isinstance(n_omega, int) or n_omega < 100:
        raise ValueError(f"n_omega must be an integer >= 100, but found {n_omega!r}")
    t0 = time.perf_counter()
    plant, bands = generic_plant(), generic_bands()
    ex = generic_example()
    hinf, lf, hf = _synthesis()
    designs = tuple(BandDesign(n, r.band.label, r.K, r.gamma_lmi, r.gamma_sweep)
                    for n, r in zip(_CONTROLLERS, (hinf, lf, hf), strict=True))
    eps = np.array([[e, fdsc.synthesize(plant, bands["LF"], epsilon=e).gamma_sweep]
                    for e in (1e-2, 1e-1, 1.0, 10.0)])
    sig = np.array([[s, fdsc.synthesize(plant, bands["HF"], sigma=s).gamma_sweep]
                    for s in (0.0, 1.0, 10.0, 30.0, 100.0, 300.0)])
    omega = np.geomspace(1e-2, 1e3, n_omega)
    regions = (bands["LF"], fdsc.Band.mf(W_L, W_H), bands["HF"])
    sigma, peaks = {}, {}
    for name in ex.fixed_names:
        cl = ex.closed_loop(name)
        sigma[name] = fdsc.sigma_max(cl, omega)
        peaks[name] = np.array([fdsc.band_peak(cl, b).gamma for b in regions])
    ctrl = ex.designs["FDSC"][0]
    stationary = ex.compare([lf_disturbance(), hf_disturbance()])
    rho_p = np.array(RHO_P)
    rho_p_sweep = ex.compare([mixed_disturbance(r) for r in rho_p])
    rho_t = np.array(RHO_T)
    pieces = [piecewise_disturbance(r) for r in rho_t]
    rho_t_sweep = ex.compare([d for d, _ in pieces], [h for _, h in pieces])
    ideal = np.array([ex.segment_ideal(d, h, ("PassC-LF", "PassC-HF")) for d, h in pieces])
    fixed, laws = ex.fixed_names, tuple(ex.designs)
    pk = peaks
    headline = Headline(
        float(pk["PassC-EF"][0] / pk["PassC-LF"][0]), float(pk["PassC-EF"][2] / pk["PassC-HF"][2]),
        float(pk["PassC-LF"][2] / pk["PassC-EF"][2]), float(pk["PassC-HF"][0] / pk["PassC-EF"][0]),
        tuple(_win(rho_p_sweep, rho_p, law, fixed) for law in laws),
        tuple(_win(rho_t_sweep, rho_t, law, fixed) for law in laws))
    return GenericStudy(designs, eps, sig, omega, sigma, peaks, ctrl.gammas.copy(), ctrl.Q,
                        stationary, rho_p, rho_p_sweep, rho_t, rho_t_sweep, ideal, headline,
                        time.perf_counter() - t0)


@cached
def chosen_runs() -> dict:
    """The fixed controller chosen in advance (:mod:`fdsc.paper.shared.fixed_choice`) in the
    generic example's own cases, by the simulator and step of :func:`generic_study`.

    Returns
    -------
    dict
        ``{"name", "stationary": [E_LF, E_HF], "rho_p": [...], "rho_t": [...]}``.
    """
    from fdsc.paper.shared.fixed_choice import fixed_in_advance

    name, c = fixed_in_advance("generic")
    ex = generic_example()
    pieces = [piecewise_disturbance(r) for r in RHO_T]
    return {"name": name,
            "stationary": ex.energies_of(c, [lf_disturbance(), hf_disturbance()]).tolist(),
            "rho_p": ex.energies_of(c, [mixed_disturbance(r) for r in RHO_P]).tolist(),
            "rho_t": ex.energies_of(c, [d for d, _ in pieces], [h for _, h in pieces]).tolist()}


def record_part() -> RecordPart:
    """The record entry ``generic_example`` (verdict "new": the paper has no such example).

    Returns
    -------
    RecordPart
        One entry; ``recomputed`` holds the headline numbers.
    """
    h = generic_study().headline
    p = {w.law: w for w in h.rho_p}
    t = {w.law: w for w in h.rho_t}
    recomputed = {"factor_lf": h.factor_lf, "factor_hf": h.factor_hf, "loss_lf": h.loss_lf,
                  "loss_hf": h.loss_hf,
                  "fdsc_rho_p_share": p["FDSC"].share, "fdsc_rho_p_best_gain": p["FDSC"].best_gain,
                  "fdsc_rho_p_worst_gain": p["FDSC"].worst_gain,
                  "dwell_rho_p_share": p["FDSC (dwell)"].share,
                  "dwell_rho_p_best_gain": p["FDSC (dwell)"].best_gain,
                  "fdsc_rho_t_share": t["FDSC"].share, "fdsc_rho_t_best_gain": t["FDSC"].best_gain,
                  "dwell_rho_t_share": t["FDSC (dwell)"].share,
                  "dwell_rho_t_best_gain": t["FDSC (dwell)"].best_gain}
    note = (f"on a two-mass chain (d on the appendage, u on the base) PassC-LF's LF peak is "
            f"{h.factor_lf:.3g} times below H-infinity's and its HF peak {h.loss_lf:.3g} times above; "
            f"PassC-HF's HF peak is {h.factor_hf:.4f} times H-infinity's (H-infinity is limited by "
            f"the HF band); FDSC (printed law, Theorem 1 Q's) beats the best comparator on "
            f"{p['FDSC'].share:.0%} of the rho_p sweep (its least energy ratio to the best comparator "
            f"{1 / p['FDSC'].best_gain:.4f}) and on {t['FDSC'].share:.0%} of the rho_t sweep "
            f"({1 / t['FDSC'].best_gain:.4f}); with the dwell law on {p['FDSC (dwell)'].share:.0%} and "
            f"{t['FDSC (dwell)'].share:.0%}")
    return RecordPart((entry("generic_example", "our addition: a generic example (not in the paper)", None,
                             recomputed, "new", note),))
