"""Chapter 'switching_law': the switching law (paper eq. (31)) in action, σ(t) against the
time-localized dominance, and the region where the law cannot settle.
"""

from dataclasses import dataclass

import numpy as np

from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.data import (
    STATIONARY_DT,
    aircraft,
    our_q,
    paper_modes,
    piecewise_disturbance,
)
from fdsc.paper.shared.prose import count, num, pct
from fdsc.paper.shared.results import RecordPart, entry
from fdsc.simulate import SimResult, simulate, time_grid

__all__ = [
    "record_part",
    "PRINTED_OUTPUT_MATRIX",
    "output_matrix_entry",
    "LawConflict",
    "law_conflict",
    "LawVariant",
    "SwitchingStatistics",
    "switching_statistics",
]


@dataclass(frozen=True)
class LawConflict:
    """Where the law with the measured ẋ cannot settle, along one run (see :func:`law_conflict`).

    Parameters
    ----------
    in_region : float
        Fraction of the samples in the region where every mode prefers another.
    switches_in_region : float
        Fraction of the switches taken at a sample in that region.
    n_switches : int
        Number of switches of the run.
    """

    in_region: float
    switches_in_region: float
    n_switches: int


def law_conflict(sim: SimResult, modes: list, law_bands: list, law_Q: list) -> LawConflict:
    """Where the printed law with the measured ẋ cannot settle, along a simulated run.

    With ẋ = A_σ(t⁻) x + B d the score of every candidate depends on the mode active just before
    t. At a sample, mode i "prefers" the mode with the best score computed with ẋ = A_i x + B d. The
    law cannot settle where every mode prefers another (for two modes: mode 1 prefers mode 2 and
    mode 2 prefers mode 1): whichever is active, the next sample switches. That set is a region of
    the (x, d) space, not the surface where two scores are equal.

    Parameters
    ----------
    sim : SimResult
        A run of the switched loop.
    modes : list of LTISystem
        The closed loops of the modes.
    law_bands : list of Band
        Ω_i of the law.
    law_Q : list of (n, n) array_like
        Q_i of the law.

    Returns
    -------
    LawConflict

    Notes
    -----
    The score is the instantaneous FD-EPF ``[ẋ; x]ᵀ(Ψ_i ⊗ Q_i)[ẋ; x]`` of the law, paper eq. (31).
    """
    n_modes = len(modes)
    scores = np.empty((n_modes, n_modes, sim.t.size))  # [active i, candidate j, k]
    for i, m in enumerate(modes):
        xdot = sim.x @ m.A.T + np.outer(sim.d, m.B[:, 0])
        v = np.hstack([xdot, sim.x])
        for j, (b, Q) in enumerate(zip(law_bands, law_Q, strict=True)):
            W = np.kron(b.psi.real, np.asarray(Q, dtype=float))
            scores[i, j] = np.einsum("kr,rc,kc->k", v, W, v)
    prefers = scores.argmax(axis=1)  # [active i, k]
    region = np.all(prefers != np.arange(n_modes)[:, None], axis=0)
    sw = np.flatnonzero(np.diff(sim.sigma)) + 1
    return LawConflict(float(region.mean()), float(region[sw].mean()) if sw.size else 0.0,
                       int(sw.size))


@dataclass(frozen=True)
class LawVariant:
    """σ(t) and its statistics for one variant of the law along one run.

    Parameters
    ----------
    label : str
        The variant (Q's and reading of ẋ).
    law : {"previous", "candidate"}
        How ẋ enters the law: ``"previous"`` is the measured ẋ (the mode active just before),
        ``"candidate"`` the candidate ẋ (each mode's own).
    sigma : (k,) ndarray
        Share of each bin spent in the HF mode (so chattering is not aliased).
    switches : int
        Number of switches.
    share_hf : tuple of float
        Fraction of each disturbance segment spent in the HF mode.
    single_sample_dwell : float
        Fraction of dwell intervals lasting one sample (the signature of chattering).
    energy : float
        ∫zᵀz over the run.
    conflict : LawConflict or None
        Where the law cannot settle (measured ẋ only; None for the candidate reading).
    """

    label: str
    law: str
    sigma: np.ndarray
    switches: int
    share_hf: tuple
    single_sample_dwell: float
    energy: float
    conflict: LawConflict | None


@dataclass(frozen=True)
class SwitchingStatistics:
    """σ(t) of several law variants along the piecewise disturbance (see
    :func:`switching_statistics`).

    Parameters
    ----------
    T, rho_t, rho_p_star : float
        The piecewise disturbance (paper eq. (58)).
    t : (k,) ndarray
        Bin starts in s.
    bin : float
        Bin length in s.
    breaks : (4,) ndarray
        Segment limits of the disturbance in s.
    variants : dict
        ``{label: LawVariant}``.
    """

    T: float
    rho_t: float
    rho_p_star: float
    t: np.ndarray
    bin: float
    breaks: np.ndarray
    variants: dict

    def rows(self) -> list:
        """One row per variant (for :func:`fdsc.paper.shared.report.html_table`).

        Returns
        -------
        list of dict
            ``law, switches``, the HF share of each segment, ``one-sample dwells`` and the
            energy.
        """
        return [{"law": label, "switches": v.switches,
                 "HF share, 1st HF segment": v.share_hf[0], "HF share, LF segment": v.share_hf[1],
                 "HF share, 2nd HF segment": v.share_hf[2],
                 "one-sample dwells": v.single_sample_dwell, "energy ∫zᵀz": v.energy}
                for label, v in self.variants.items()]

    #: Short keys of the default variants in :meth:`prose`.
    KEYS = {"paper Q, measured ẋ": "pm", "paper Q, candidate ẋ": "pc", "our Q, measured ẋ": "om"}

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``sw_T``, ``sw_rho_t``, ``sw_horizon``, ``bin_ms`` and, per
            variant (key ``pm``, ``pc``, ``om`` for the default ones, else its label),
            ``sw_<key>`` (switches), ``lfshare_<key>`` (HF share in the LF segment),
            ``dwell1_<key>`` (share of one-sample dwells) and, with the measured ẋ,
            ``region_<key>`` and ``region_sw_<key>`` (the chattering region's shares of the
            samples and of the switches).
        """
        def whole(x):
            return count(int(x)) if float(x).is_integer() else num(float(x))

        out = {"sw_T": whole(self.T), "sw_rho_t": num(self.rho_t, 1), "sw_horizon": whole(self.breaks[-1]),
               "bin_ms": whole(round(self.bin * 1e3, 9))}
        for label, v in self.variants.items():
            key = self.KEYS.get(label, label)
            out.update({f"sw_{key}": count(v.switches), f"lfshare_{key}": pct(v.share_hf[1], 1),
                        f"dwell1_{key}": pct(v.single_sample_dwell)})
            if v.conflict is not None:
                out[f"region_{key}"] = pct(v.conflict.in_region, 2)
                out[f"region_sw_{key}"] = pct(v.conflict.switches_in_region)
        return out

    def to_record(self) -> RecordPart:
        """Record entry ``law_chattering`` (new): switches, shares, dwells and the conflict
        region of every variant.

        Returns
        -------
        RecordPart
        """
        rec = {}
        for label, v in self.variants.items():
            rec[label] = {"switches": v.switches, "share_hf": list(v.share_hf),
                          "single_sample_dwell": v.single_sample_dwell, "energy": v.energy}
            if v.conflict is not None:
                rec[label]["in_conflict_region"] = v.conflict.in_region
                rec[label]["switches_in_conflict_region"] = v.conflict.switches_in_region
        return RecordPart((entry(
            "law_chattering", "switching law, paper eq. (31), paper Remark 7 (nothing printed)",
            None, rec, "new",
            f"piecewise disturbance of paper eq. (58) with T = {self.T:g} s, rho_t = {self.rho_t:g}, "
            f"rho_p* = {self.rho_p_star:g}; the share of time on the HF mode per segment (HF, LF, "
            "HF); a large share of "
            "one-sample dwells is chattering at the sampling rate. The conflict (chattering) region "
            "is the set of states where each mode's score prefers the other once it is active; on "
            "its border a continuous-time law would slide, which the sampled law realizes as "
            "chattering. Theorem 1 assumes no sliding motion, so runs that chatter are outside its "
            "assumptions.",
            T=self.T, rho_t=self.rho_t, rho_p_star=self.rho_p_star),))


@cached
def switching_statistics(*, T: float = 100.0, rho_t: float = 0.2, rho_p_star: float = 0.1,
                         dt: float = STATIONARY_DT, laws: dict | None = None) -> SwitchingStatistics:
    """σ(t) along the piecewise disturbance of paper Fig. 8 (shortened to T), for several law variants.

    Parameters
    ----------
    T, rho_t, rho_p_star : float, optional
        The piecewise disturbance (paper eq. (58)): HF on [0, T), ρ*_p·LF on [T, T + ρ_t T),
        HF on [T + ρ_t T, 2T + ρ_t T).
    dt : float, optional
        Step in s.
    laws : dict, optional
        ``{label: (Q's, law)}`` with law in {"previous", "candidate"}; default the paper's Q's
        with both readings and our Q's with the measured ẋ.

    Returns
    -------
    SwitchingStatistics

    Notes
    -----
    The law is paper eq. (31); a variant with the measured ẋ (``"previous"``) also gets the
    conflict region of :func:`law_conflict`.
    """
    d = piecewise_disturbance(T, rho_t, rho_p_star)
    t = time_grid(d.breaks[-1], dt)
    pm = paper_modes()
    laws = laws or {"paper Q, measured ẋ": (pm["Q"], "previous"),
                    "paper Q, candidate ẋ": (pm["Q"], "candidate"),
                    "our Q, measured ẋ": (our_q().Q, "previous")}
    every = 20
    starts = np.arange(0, t.size, every)
    seg = d.segment_of(t)
    variants = {}
    for label, (Q, law) in laws.items():
        sim = simulate(pm["modes"], d, t, law_bands=pm["bands"], law_Q=Q, law=law)
        share = tuple(float(np.mean(sim.sigma[seg == k] == 1)) for k in range(len(d.parts)))
        sw = np.flatnonzero(np.diff(sim.sigma)) + 1
        dwell = np.diff(np.concatenate([[0], sw, [t.size - 1]]))
        variants[label] = LawVariant(
            label, law,
            # the share of each bin spent in mode 1: σ chatters at the sampling rate, so every
            # n-th sample of σ would alias; the per-bin share holds every sample
            np.add.reduceat(sim.sigma, starts) / np.diff(np.append(starts, t.size)),
            int(sw.size), share, float(np.mean(dwell <= 1)) if dwell.size else 0.0, sim.energy(),
            law_conflict(sim, pm["modes"], pm["bands"], Q) if law == "previous" else None)
    return SwitchingStatistics(float(T), float(rho_t), float(rho_p_star), t[starts], every * dt,
                               np.asarray(d.breaks), variants)


#: The switched closed loop's output matrix as paper eq. (32) prints it.
PRINTED_OUTPUT_MATRIX = "C_σ(t) = C + B₂K_σ(t)"


def output_matrix_entry() -> RecordPart:
    """Record entry ``closed_loop_output_matrix``: the printed expression C + B₂K_σ of paper
    eq. (32), which the dimensions rule out (a printed expression that differs).

    Returns
    -------
    RecordPart

    Examples
    --------
    >>> (e,) = output_matrix_entry().entries
    >>> e["verdict"], e["recomputed"]["C"], e["recomputed"]["B₂K_σ"]
    ('differs', [3, 2], [2, 2])
    """
    plant = aircraft()
    n, m = plant.B2.shape
    p = plant.C.shape[0]
    return RecordPart((entry(
        "closed_loop_output_matrix", "Sec. III-B, the switched closed loop, paper eq. (32)",
        PRINTED_OUTPUT_MATRIX, {"C": [p, n], "B₂K_σ": [n, n], "D₂K_σ": [p, n],
                                "used": "C_σ(t) = C + D₂K_σ(t)"},
        "differs",
        f"The dimensions rule it out: on the aircraft C is {p} × {n} and B₂K_σ is {n} × {n} "
        f"(B₂ is {n} × {m}), so the sum is undefined. With u = K_σ x the output z = Cx + D₁d + D₂u "
        "is (C + D₂K_σ)x + D₁d, so C_σ = C + D₂K_σ is meant, and the book uses it throughout "
        "(the closed loops of the chapter “The switching law” and of every chapter that "
        "simulates FDSC)."),))


def record_part() -> RecordPart:
    """Record entries of the chapter: ``closed_loop_output_matrix`` (a printed expression that
    differs) and ``law_chattering`` (new).

    Returns
    -------
    RecordPart
    """
    return output_matrix_entry() + switching_statistics().to_record()
