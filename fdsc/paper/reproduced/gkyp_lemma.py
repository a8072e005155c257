"""Chapter 'gkyp_lemma': Lemma 1 (paper eq. (7)) on the printed gains against a frequency sweep,
and the γ versus γ² slip of statement (2) (paper eq. (8)) and of (P.1), (P.2) and paper Remark 5.
The bounds printed beside the gains are judged once, in :mod:`fdsc.paper.reproduced.printed_bounds`.
"""

from dataclasses import dataclass

import numpy as np

from fdsc.frequency import band_peak
from fdsc.lmi import gkyp_gamma
from fdsc.paper.reproduced.gamma_slip import (
    GammaSlip,
    GammaSquaredCheck,
    ToneCheck,
    WindowedTone,
    gamma_vs_gamma_squared,
    in_band_gamma_slip,
    windowed_tone_ratio,
)
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.data import aircraft, paper_bands, paper_data, paper_gains
from fdsc.paper.shared.names import GAIN_ORDER
from fdsc.paper.shared.prose import count, num
from fdsc.paper.shared.results import RecordPart, entry

__all__ = [
    "record_part",
    "GainBandPeak",
    "GainBandTable",
    "gain_band_table",
    "WindowedTone",
    "windowed_tone_ratio",
    "ToneCheck",
    "GammaSquaredCheck",
    "gamma_vs_gamma_squared",
    "GammaSlip",
    "in_band_gamma_slip",
]


# -- Lemma 1 against the sweep -------------------------------------------------------------------

@dataclass(frozen=True)
class GainBandPeak:
    """Lemma 1's γ and the swept band peak of σ_max for one gain and one band.

    Parameters
    ----------
    gain : str
        Name of the gain (e.g. ``"K_f1"``).
    band : {"LF", "MF", "HF", "EF"}
        The band.
    peak : float
        sup of σ_max(G(jω)) over the band (:func:`fdsc.band_peak`).
    omega_peak : float
        Where the peak is attained in rad/s (inf: the limit ω → ∞).
    lmi_gamma : float
        Smallest γ certified by the gKYP LMI (:func:`fdsc.lmi.gkyp_gamma`).
    rel_diff : float
        ``(lmi_gamma − peak) / peak``.
    max_eig : float
        Largest eigenvalue of the LMI matrix at the certificate (< 0).
    status : str
        cvxpy status of the solve.
    solve_time : float
        Seconds of the solve.
    poles : (n,) ndarray
        Closed-loop poles.
    """

    gain: str
    band: str
    peak: float
    omega_peak: float
    lmi_gamma: float
    rel_diff: float
    max_eig: float
    status: str
    solve_time: float
    poles: np.ndarray

    @property
    def slowest_pole(self) -> float:
        """Largest real part of the closed-loop poles."""
        return float(np.max(np.real(self.poles)))

    @property
    def fastest_pole(self) -> float:
        """Smallest real part of the closed-loop poles."""
        return float(np.min(np.real(self.poles)))


#: The paper's names of the ranges.
_OMEGA = {"LF": "Ω_1", "MF": "Ω_2", "HF": "Ω_3", "EF": "Ω_e"}


def _paper_bounds():
    ctrl = paper_data("controllers")
    return {g: {ctrl[g]["band"]: ctrl[g]["bound"]} for g in GAIN_ORDER}


@dataclass(frozen=True)
class GainBandTable:
    """Lemma 1 against the sweep for every (gain, band) pair (see :func:`gain_band_table`).

    Parameters
    ----------
    pairs : tuple of GainBandPeak
        One per gain and band, gains outer.
    """

    pairs: tuple

    def __post_init__(self):
        object.__setattr__(self, "pairs", tuple(self.pairs))
        if not all(isinstance(p, GainBandPeak) for p in self.pairs):
            raise TypeError("pairs must hold GainBandPeak results")

    def rows(self) -> list:
        """One row per pair with every field (for :func:`fdsc.paper.shared.report.html_table`).

        Returns
        -------
        list of dict
        """
        return [vars(p).copy() for p in self.pairs]

    def by_gain_band(self, key: str) -> dict:
        """One field as ``{gain: {band: value}}``.

        Parameters
        ----------
        key : str
            A field of :class:`GainBandPeak`.

        Returns
        -------
        dict
        """
        out = {}
        for p in self.pairs:
            out.setdefault(p.gain, {})[p.band] = getattr(p, key)
        return out

    def pair(self, gain: str, band: str) -> GainBandPeak:
        """The result of one pair.

        Parameters
        ----------
        gain : str
            Name of the gain.
        band : str
            The band.

        Returns
        -------
        GainBandPeak

        Raises
        ------
        KeyError
            If the table has no such pair.
        """
        for p in self.pairs:
            if (p.gain, p.band) == (gain, band):
                return p
        raise KeyError(f"no pair ({gain!r}, {band!r}) in the table")

    @property
    def worst_rel_diff(self) -> float:
        """Largest ``|rel_diff|`` over the pairs."""
        return max(abs(p.rel_diff) for p in self.pairs)

    @property
    def max_max_eig(self) -> float:
        """Largest LMI eigenvalue at the certificates (< 0 if every certificate holds)."""
        return max(p.max_eig for p in self.pairs)

    @property
    def total_solve_time(self) -> float:
        """Seconds of all solves together."""
        return sum(p.solve_time for p in self.pairs)

    def solver_short(self) -> tuple:
        """The pairs whose solve stopped short of the solver's full accuracy (accepted only
        because their certificate passes the check after the solve)."""
        return tuple(p for p in self.pairs if p.status != "optimal")

    def display_rows(self) -> list:
        """One row per pair, formatted for the book: ``gain, band, peak, omega, lmi_gamma,
        rel_diff, max_eig``.

        Returns
        -------
        list of dict
        """
        return [{"gain": p.gain, "band": p.band, "peak": num(p.peak, 6), "omega": num(p.omega_peak),
                 "lmi_gamma": num(p.lmi_gamma, 6), "rel_diff": num(p.rel_diff, 2),
                 "max_eig": num(p.max_eig, 2)} for p in self.pairs]

    def prose(self) -> dict:
        """The numbers the chapter quotes (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``n_pairs``, ``worst_rel_diff``, ``max_max_eig``, ``n_short`` and
            ``short_bands`` (solves short of full accuracy and their bands), ``kf3_slow_pole``
            (K_f3's slowest pole), ``fast_pole_lo`` and ``fast_pole_hi`` (fastest poles of the
            other three loops), and ``peak_<gain>_<band>``, ``lmi_<gain>_<band>``.
        """
        fast = [p.fastest_pole for p in self.pairs if p.gain != "K_f3" and p.band == "EF"]
        short = self.solver_short()
        out = {"n_pairs": count(len(self.pairs)), "worst_rel_diff": num(self.worst_rel_diff, 2),
               "max_max_eig": num(self.max_max_eig, 2), "n_short": count(len(short)),
               "short_bands": " and ".join(dict.fromkeys(p.band for p in short)) or "none",
               "kf3_slow_pole": num(next(p for p in self.pairs if p.gain == "K_f3").slowest_pole, 4),
               "fast_pole_lo": num(min(fast)), "fast_pole_hi": num(max(fast))}
        for p in self.pairs:
            out |= {f"peak_{p.gain}_{p.band}": num(p.peak, 4), f"lmi_{p.gain}_{p.band}": num(p.lmi_gamma, 4)}
        return out

    def to_record(self) -> RecordPart:
        """Record entries ``sigma_peak`` (band peaks of σ_max of the printed gains) and
        ``lemma1_gamma`` (Lemma 1's certified γ for the same pairs); both ``new`` (the paper
        prints neither table): the printed bounds are judged once, in the entries ``bound_f1``
        … ``bound_e`` (:mod:`fdsc.paper.reproduced.printed_bounds`).

        Returns
        -------
        RecordPart
        """
        ctrl = paper_data("controllers")
        beside = "; ".join(f"{g} {num(self.pair(g, ctrl[g]['band']).peak, 4)} on "
                           f"{_OMEGA[ctrl[g]['band']]} (printed bound {ctrl[g]['bound']})"
                           for g in GAIN_ORDER)
        where = ("appendix 'The printed bounds', which gives each printed bound one verdict and "
                 "every reading tried")
        return RecordPart((
            entry("sigma_peak", "Sec. IV, the printed gains K_f1, K_f2, K_f3, K_e; paper Fig. 3",
                  None, self.by_gain_band("peak"), "new",
                  f"Band peak of σ_max(G(jω)) for the closed loop of each printed gain over each "
                  f"range (a dense sweep refined locally, with a bound on the tail for HF and the "
                  f"entire range), {count(len(self.pairs))} numbers the paper does not print. For "
                  f"each gain's own range: {beside}. These peaks are the quantity the printed "
                  f"bounds state; their verdicts are given once, in the {where}.",
                  omega_peak=self.by_gain_band("omega_peak"), printed_bounds=_paper_bounds()),
            entry("lemma1_gamma", "Lemma 1 (paper eq. (7)) applied to the printed gains",
                  None, self.by_gain_band("lmi_gamma"), "new",
                  f"Smallest γ certified by the LMI of Lemma 1 for each printed gain and range "
                  f"(complex MF data posed through the real embedding). It equals the swept band "
                  f"peak within {num(self.worst_rel_diff, 2)} relative on all "
                  f"{count(len(self.pairs))} pairs, and every certificate's LMI is negative "
                  f"definite when rebuilt after the solve (largest eigenvalue "
                  f"{num(self.max_max_eig, 2)}): Lemma 1 is lossless here. It is one reading of "
                  f"each printed bound, judged in the {where}.",
                  max_eig=self.by_gain_band("max_eig"), status=self.by_gain_band("status"),
                  printed_bounds=_paper_bounds()),
        ))


@cached
def gain_band_table(gains: dict | None = None, bands: dict | None = None) -> GainBandTable:
    """Lemma 1's γ and the swept band peak for every gain and band.

    Parameters
    ----------
    gains : dict, optional
        ``{name: K}``; default the four printed gains.
    bands : dict, optional
        ``{kind: Band}``; default LF, MF, HF of the paper and the entire range.

    Returns
    -------
    GainBandTable

    Notes
    -----
    Lemma 1 is the LMI of paper eq. (7); the lemma is lossless, so the certified γ must equal the
    swept peak.
    """
    plant = aircraft()
    gains = paper_gains() if gains is None else gains
    bands = paper_bands() if bands is None else bands
    pairs = []
    for gname, K in gains.items():
        cl = plant.closed_loop(K)
        for bname, band in bands.items():
            pk = band_peak(cl, band)
            cert = gkyp_gamma(cl, band)
            pairs.append(GainBandPeak(gname, bname, pk.gamma, pk.omega, cert.gamma,
                                      (cert.gamma - pk.gamma) / pk.gamma, cert.max_eig,
                                      cert.status, cert.solve_time, cl.poles()))
    return GainBandTable(tuple(pairs))


def record_part() -> RecordPart:
    """Record entries ``sigma_peak`` and ``lemma1_gamma`` (Lemma 1 on the printed gains),
    ``lemma1_gamma_squared`` (statement (2)) and ``gamma_slip_in_band`` ((P.1), (P.2), paper
    Remark 5).

    Returns
    -------
    RecordPart
    """
    return (gain_band_table().to_record() + gamma_vs_gamma_squared().to_record()
            + in_band_gamma_slip().to_record())
