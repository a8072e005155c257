"""Chapter 'passive_controllers', continued: the free parameters ε and σ, and the best HF design.

The LF and MF designs over ε of the stability LMI (:data:`EPSILON_GRID`), the HF designs over
the fictitious-pole parameter σ (:data:`HF_SIGMA_GRID`): certified γ, in-band sweep and
out-of-band peak, and the HF design with the smallest certified γ, beside K_f3.
"""

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from fdsc._validation import as_choice, as_vector
from fdsc.bands import Band
from fdsc.frequency import band_peak
from fdsc.paper.reproduced.passive_gains import _exact, _fmt_K
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.data import aircraft, paper_bands, paper_data, paper_gains
from fdsc.paper.shared.prose import count, num
from fdsc.paper.shared.results import RecordPart, entry
from fdsc.synthesis import DEFAULT_EPSILON, synthesize

__all__ = [
    "EPSILON_GRID", "EpsilonScan", "HFBest", "HF_SIGMA_GRID", "SigmaScan", "epsilon_sensitivity",
    "hf_best", "sigma_sensitivity",
]


#: ε of the stability LMI scanned by :func:`epsilon_sensitivity`.
EPSILON_GRID = (1e-3, 1e-2, 1e-1, 1.0, 10.0)


#: σ of the HF slack scanned by :func:`hf_best`: 0 and 17 log-spaced values in [10⁻², 10²].
HF_SIGMA_GRID = (0.0, *(float(s) for s in np.geomspace(1e-2, 1e2, 17)))


# -- the free parameters ε and σ ------------------------------------------------------------------

@dataclass(frozen=True)
class EpsilonScan:
    """Designs of one band over ε of the stability LMI (see :func:`epsilon_sensitivity`).

    Parameters
    ----------
    kind : {"LF", "MF"}
        The band.
    epsilon : (k,) ndarray
        The values of ε.
    gamma_lmi, gamma_sweep : (k,) ndarray
        Certified γ and in-band peak of the designed closed loop.
    fast_pole : (k,) ndarray
        Smallest real part of the closed-loop poles.
    K : (k, m, n) ndarray
        The gains.
    status : tuple of str
        cvxpy statuses.
    """

    kind: str
    epsilon: np.ndarray
    gamma_lmi: np.ndarray
    gamma_sweep: np.ndarray
    fast_pole: np.ndarray
    K: np.ndarray
    status: tuple

    @property
    def spread(self) -> float:
        """``max / min − 1`` of the in-band peak over ε."""
        return float(self.gamma_sweep.max() / self.gamma_sweep.min() - 1)

    def spread_over(self, lo: float, hi: float) -> float:
        """``max / min − 1`` of the in-band peak over the values of ε in ``[lo, hi]``.

        Parameters
        ----------
        lo, hi : float
            The ends of the range of ε.

        Returns
        -------
        float

        Raises
        ------
        ValueError
            If no ε of the scan lies in ``[lo, hi]``.
        """
        inside = (self.epsilon >= lo) & (self.epsilon <= hi)
        if not inside.any():
            raise ValueError(f"lo, hi must enclose an epsilon of the scan {self.epsilon.tolist()}, "
                             f"but found [{lo}, {hi}]")
        g = self.gamma_sweep[inside]
        return float(g.max() / g.min() - 1)

    def prose(self, lo: float = 1e-2, hi: float = 1.0) -> dict:
        """The numbers the chapter quotes (:mod:`fdsc.paper.shared.prose`).

        Parameters
        ----------
        lo, hi : float, optional
            A sub-range of ε whose spread is quoted beside that of the whole grid.

        Returns
        -------
        dict
            ``{name: text}``: ``spread`` and ``grid_lo``, ``grid_hi`` (the in-band peak's
            relative spread over the whole grid of ε and its ends); ``spread_mid`` over
            ``[mid_lo, mid_hi]``.
        """
        return {"spread": num(self.spread, 2), "grid_lo": _exact(self.epsilon.min()),
                "grid_hi": _exact(self.epsilon.max()), "spread_mid": num(self.spread_over(lo, hi), 2),
                "mid_lo": _exact(lo), "mid_hi": _exact(hi)}

    def display_rows(self) -> list:
        """One row per ε, formatted for the book: ``kind, epsilon, gamma_lmi, gamma_sweep,
        fast_pole, K``.

        Returns
        -------
        list of dict
        """
        return [{"kind": self.kind, "epsilon": _exact(e), "gamma_lmi": num(float(g), 5),
                 "gamma_sweep": num(float(w), 5), "fast_pole": num(float(p)), "K": _fmt_K(K)}
                for e, g, w, p, K in zip(self.epsilon, self.gamma_lmi, self.gamma_sweep,
                                         self.fast_pole, self.K, strict=True)]

    def rows(self) -> list:
        """One row per ε: ``kind, epsilon, gamma_lmi, gamma_sweep, fast_pole, K`` (K printed).

        Returns
        -------
        list of dict
        """
        return [{"kind": self.kind, "epsilon": float(e), "gamma_lmi": float(g),
                 "gamma_sweep": float(s), "fast_pole": float(p), "K": _fmt_K(K), "status": st}
                for e, g, s, p, K, st in zip(self.epsilon, self.gamma_lmi, self.gamma_sweep,
                                              self.fast_pole, self.K, self.status, strict=True)]

    def to_record(self) -> RecordPart:
        """Record entry ``epsilon_scan_<kind>`` (new): the designs over ε.

        Returns
        -------
        RecordPart
        """
        return RecordPart((entry(
            f"epsilon_scan_{self.kind.lower()}",
            f"Sec. IV, {self.kind} design (epsilon of the stability LMI, not printed)", None,
            {"epsilon": self.epsilon, "gamma_lmi": self.gamma_lmi, "gamma_sweep": self.gamma_sweep,
             "fast_pole": self.fast_pole}, "new",
            f"the paper prints no synthesis method; our {self.kind} design shares X and Y with a "
            f"stability LMI whose epsilon is free: its in-band peak varies by "
            f"{self.spread:.1%} over epsilon in [{self.epsilon.min():g}, {self.epsilon.max():g}] "
            f"(we use {DEFAULT_EPSILON:g})."),))


@cached
def epsilon_sensitivity(kind: str, epsilons: ArrayLike = EPSILON_GRID) -> EpsilonScan:
    """LMI and sweep γ of the ``kind`` design (LF or MF) over ε of the stability LMI.

    Parameters
    ----------
    kind : {"LF", "MF"}
        The band.
    epsilons : (k,) array_like, optional
        Values of ε (> 0).

    Returns
    -------
    EpsilonScan

    Raises
    ------
    ValueError
        If ``kind`` is neither LF nor MF.
    """
    as_choice("kind", kind, ("LF", "MF"))
    plant, band = aircraft(), paper_bands()[kind]
    designs = [synthesize(plant, band, epsilon=eps) for eps in as_vector("epsilons", epsilons)]
    return EpsilonScan(kind, np.array([r.epsilon for r in designs]),
                       np.array([r.gamma_lmi for r in designs]),
                       np.array([r.gamma_sweep for r in designs]),
                       np.array([float(r.poles.real.min()) for r in designs]),
                       np.array([r.K for r in designs]), tuple(r.status for r in designs))


def _out_of_band_peak(cl, band):
    """Peak of σ_max outside an HF band, i.e. over ``|ω| ≤ ϖ_h``."""
    return band_peak(cl, Band.lf(band.lower)).gamma


@dataclass(frozen=True)
class SigmaScan:
    """HF designs over the fictitious-pole parameter σ (see :func:`sigma_sensitivity`).

    Parameters
    ----------
    sigma : (k,) ndarray
        The values of σ.
    gamma_lmi, gamma_sweep : (k,) ndarray
        Certified γ and in-band peak of the designed closed loop.
    out_of_band : (k,) ndarray
        Peak of σ_max outside the band, over ``|ω| ≤ ϖ_h``.
    K : (k, m, n) ndarray
        The gains.
    status : tuple of str
        cvxpy statuses.
    band_edge : float
        ϖ_h in rad/s.
    """

    sigma: np.ndarray
    gamma_lmi: np.ndarray
    gamma_sweep: np.ndarray
    out_of_band: np.ndarray
    K: np.ndarray
    status: tuple
    band_edge: float

    def rows(self) -> list:
        """One row per σ: ``sigma, gamma_lmi, gamma_sweep, out_of_band, K`` (K printed).

        Returns
        -------
        list of dict
        """
        return [{"sigma": float(s), "gamma_lmi": float(g), "gamma_sweep": float(w),
                 "out_of_band": float(o), "K": _fmt_K(K)}
                for s, g, w, o, K in zip(self.sigma, self.gamma_lmi, self.gamma_sweep,
                                         self.out_of_band, self.K, strict=True)]


def sigma_sensitivity(sigmas: ArrayLike, *, epsilon: float = DEFAULT_EPSILON) -> SigmaScan:
    """HF designs over the fictitious-pole parameter σ: LMI γ, in-band sweep, out-of-band peak.

    Parameters
    ----------
    sigmas : (k,) array_like
        Values of σ (≥ 0).
    epsilon : float, optional
        ε of the stability LMI.

    Returns
    -------
    SigmaScan
    """
    plant, band = aircraft(), paper_bands()["HF"]
    sigmas = as_vector("sigmas", sigmas)
    designs, oob = [], []
    for s in sigmas:
        r = synthesize(plant, band, epsilon=epsilon, sigma=s)
        designs.append(r)
        oob.append(_out_of_band_peak(plant.closed_loop(r.K), band))
    return SigmaScan(np.array(sigmas),
                     np.array([r.gamma_lmi for r in designs]),
                     np.array([r.gamma_sweep for r in designs]), np.array(oob),
                     np.array([r.K for r in designs]), tuple(r.status for r in designs), band.lower)


@dataclass(frozen=True)
class HFBest:
    """The HF design with the smallest certified γ over a grid of σ, beside K_f3.

    Parameters
    ----------
    sigma : float
        σ of the best design.
    K : (m, n) ndarray
        Its gain.
    gamma_lmi : float
        Its certified γ.
    in_band : float
        Its in-band peak (sweep).
    out_of_band : float
        Its peak over ``|ω| ≤ ϖ_h``.
    K_f3_in_band, K_f3_out_of_band : float
        The same two peaks for the printed K_f3.
    scan : SigmaScan
        The whole σ scan.
    """

    sigma: float
    K: np.ndarray
    gamma_lmi: float
    in_band: float
    out_of_band: float
    K_f3_in_band: float
    K_f3_out_of_band: float
    scan: SigmaScan

    @property
    def gamma_lmi_smallest_sigma(self) -> float:
        """Certified γ at the smallest σ of the scan (σ = 0 on the default grid)."""
        return float(self.scan.gamma_lmi[np.argmin(self.scan.sigma)])

    def prose(self) -> dict:
        """The numbers the chapter quotes (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``sigma``, ``gamma_lmi``, ``in_band``, ``out_of_band`` of the best
            design; ``K_f3_in_band``, ``K_f3_out_of_band``; ``lmi_sigma0`` (the certified γ at
            the smallest σ) and ``sigma_min`` (that σ); ``n_sigma``, ``sigma_lo``, ``sigma_hi``
            (the scan's positive grid).
        """
        pos = self.scan.sigma[self.scan.sigma > 0]
        return {"sigma": _exact(self.sigma), "gamma_lmi": num(self.gamma_lmi, 4),
                "in_band": num(self.in_band, 4), "out_of_band": num(self.out_of_band, 4),
                "K_f3_in_band": num(self.K_f3_in_band, 4), "K_f3_out_of_band": num(self.K_f3_out_of_band, 4),
                "lmi_sigma0": num(self.gamma_lmi_smallest_sigma, 4),
                "sigma_min": _exact(float(self.scan.sigma.min())), "n_sigma": count(self.scan.sigma.size),
                "sigma_lo": _exact(float(pos.min())), "sigma_hi": _exact(float(pos.max()))}

    def to_record(self) -> RecordPart:
        """Record entry ``hf_best`` (new).

        Returns
        -------
        RecordPart
        """
        return RecordPart((entry(
            "hf_best", "Sec. IV, K_f3 and paper Fig. 3 (HF design)",
            {"K": paper_data("controllers")["K_f3"]["value"], "in_band": self.K_f3_in_band,
             "out_of_band": self.K_f3_out_of_band},
            {"K": self.K, "sigma": self.sigma, "gamma_lmi": self.gamma_lmi,
             "in_band": self.in_band, "out_of_band": self.out_of_band},
            "new",
            f"not printed by the paper: best certified HF design over the sigma grid: "
            f"in-band gain {self.in_band:.4f} "
            f"(LMI {self.gamma_lmi:.4f}) and out-of-band peak {self.out_of_band:.4f}, "
            f"against {self.K_f3_in_band:.4f} and {self.K_f3_out_of_band:.1f} for the printed "
            f"K_f3 (its values recomputed from the printed gain)."),))


@cached
def hf_best(sigmas: ArrayLike | None = None, *, epsilon: float = DEFAULT_EPSILON) -> HFBest:
    """The HF design with the smallest certified γ over a grid of σ, beside K_f3.

    Parameters
    ----------
    sigmas : (k,) array_like, optional
        Values of σ (default :data:`HF_SIGMA_GRID`).
    epsilon : float, optional
        ε of the stability LMI.

    Returns
    -------
    HFBest
    """
    scan = sigma_sensitivity(HF_SIGMA_GRID if sigmas is None else sigmas, epsilon=epsilon)
    k = int(np.argmin(scan.gamma_lmi))
    plant, band = aircraft(), paper_bands()["HF"]
    cl3 = plant.closed_loop(paper_gains()["K_f3"])
    return HFBest(float(scan.sigma[k]), scan.K[k], float(scan.gamma_lmi[k]),
                  float(scan.gamma_sweep[k]), float(scan.out_of_band[k]), band_peak(cl3, band).gamma,
                  _out_of_band_peak(cl3, band), scan)
