"""Chapter 'gkyp_lemma': Lemma 1 (paper eq. (7)) on the printed gains against a frequency sweep,
and the γ versus γ² slip of statement (2) (paper eq. (8)) and of (P.1), (P.2) and paper Remark 5.
The bounds printed beside the gains are judged once, in :mod:`fdsc.paper.printed_bounds`.
"""

from dataclasses import dataclass

import numpy as np
from scipy.signal import lsim

from .._validation import as_choice, as_positive, check_type
from ..frequency import band_peak, sigma_max
from ..lmi import gkyp_gamma
from ..plant import LTISystem
from .cache import cached
from .data import (
    aircraft,
    paper_bands,
    paper_data,
    paper_gains,
)
from .names import BAND_ORDER, GAIN_ORDER
from .prose import count, num
from .results import RecordPart, entry, pick

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


def _exact(x):
    """A chosen parameter printed with just the digits it has (0.5, not 0.500)."""
    digits = f"{x:g}".replace(".", "").replace("-", "").lstrip("0")
    return num(float(x), max(1, len(digits)))


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
        """One row per pair with every field (for :func:`fdsc.paper.report.html_table`).

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
        """The numbers the chapter quotes (:mod:`fdsc.paper.prose`).

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
        … ``bound_e`` (:mod:`fdsc.paper.printed_bounds`).

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


# -- γ or γ²? ------------------------------------------------------------------------------------

@dataclass(frozen=True)
class WindowedTone:
    """Energy ratio of a windowed tone through a system (see :func:`windowed_tone_ratio`).

    Parameters
    ----------
    omega0 : float
        Tone frequency in rad/s.
    tau : float
        Window width in s.
    dt : float
        Sample step in s.
    ratio : float
        Simulated ``∫zᵀz / ∫d²``.
    gain_sq : float
        ``σ_max(G(jω0))²``, the limit of ``ratio`` for slow windows.
    """

    omega0: float
    tau: float
    dt: float
    ratio: float
    gain_sq: float


def windowed_tone_ratio(system: LTISystem, omega0: float, *, tau: float,
                        dt: float) -> WindowedTone:
    """Energy ratio ``∫zᵀz / ∫d²`` of the windowed tone ``d = exp(−((t−4τ)/τ)²) sin(ω0 t)``.

    The tone's spectrum is concentrated within about ``2/τ`` of ω0, so for slow windows the
    ratio tends to ``σ_max(G(jω0))²`` (one input). Simulated from rest over ``[0, 8τ]`` with
    ``scipy.signal.lsim`` (first-order hold, exact for piecewise-linear input).

    Parameters
    ----------
    system : LTISystem
        Stable closed loop with one input.
    omega0 : float
        Tone frequency in rad/s.
    tau : float
        Window width in s.
    dt : float
        Sample step in s.

    Returns
    -------
    WindowedTone

    Raises
    ------
    TypeError
        If ``system`` is not an :class:`fdsc.LTISystem`.
    ValueError
        If the system has more than one input or a number is not positive.

    Examples
    --------
    >>> sys = LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]])  # 1/(s+1)
    >>> r = windowed_tone_ratio(sys, 1.0, tau=60.0, dt=0.05)
    >>> round(r.gain_sq, 6), abs(r.ratio - 0.5) < 1e-3
    (0.5, True)
    """
    check_type("system", system, LTISystem)
    omega0, tau, dt = as_positive("omega0", omega0), as_positive("tau", tau), as_positive("dt", dt)
    if system.B.shape[1] != 1:
        raise ValueError(f"system must have one input, but found {system.B.shape[1]}")
    t = np.arange(0.0, 8.0 * tau, dt)
    d = np.exp(-(((t - 4.0 * tau) / tau) ** 2)) * np.sin(omega0 * t)
    _, z, _ = lsim((system.A, system.B, system.C, system.D), d, t, interp=True)
    z = z.reshape(t.size, -1)
    ratio = float(np.trapezoid(np.sum(z**2, axis=1), t) / np.trapezoid(d**2, t))
    return WindowedTone(omega0, tau, dt, ratio, float(sigma_max(system, [omega0])[0] ** 2))


@dataclass(frozen=True)
class ToneCheck:
    """Statement (2) of Lemma 1 for one gain: a windowed LF tone against γ and γ².

    Parameters
    ----------
    gain : str
        Name of the printed gain.
    omega0 : float
        Tone frequency in rad/s (inside Ω_1).
    gamma_lf : float
        Band peak γ of σ_max on Ω_1.
    gamma_sq : float
        γ².
    gain_at_omega0_sq : float
        ``σ_max(G(jω0))²``.
    simulated_ratio : float
        Simulated energy ratio ``∫zᵀz / ∫d²``.
    bound_gamma_holds : bool
        ``simulated_ratio < γ`` (statement (2) as printed).
    bound_gamma_sq_holds : bool
        ``simulated_ratio < γ²``.
    """

    gain: str
    omega0: float
    gamma_lf: float
    gamma_sq: float
    gain_at_omega0_sq: float
    simulated_ratio: float
    bound_gamma_holds: bool
    bound_gamma_sq_holds: bool

    @property
    def rel_to_tone_gain(self) -> float:
        """``|simulated_ratio − gain_at_omega0_sq| / gain_at_omega0_sq``."""
        return abs(self.simulated_ratio - self.gain_at_omega0_sq) / self.gain_at_omega0_sq


@dataclass(frozen=True)
class GammaSquaredCheck:
    """Statement (2) of Lemma 1 (paper eq. (8)) on windowed LF tones (see
    :func:`gamma_vs_gamma_squared`).

    Parameters
    ----------
    tones : tuple of ToneCheck
        One per gain.
    tau : float
        Window width in s.
    dt : float
        Sample step in s.
    """

    tones: tuple
    tau: float
    dt: float

    def rows(self) -> list:
        """One row per gain with every field (for :func:`fdsc.paper.report.html_table`).

        Returns
        -------
        list of dict
        """
        return [vars(t).copy() for t in self.tones]

    def __getitem__(self, gain: str) -> ToneCheck:
        """The check of one gain.

        Parameters
        ----------
        gain : str
            Name of the gain.

        Returns
        -------
        ToneCheck
        """
        return pick(self.tones, "gain", gain)

    def prose(self) -> dict:
        """The numbers the chapter quotes (:mod:`fdsc.paper.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``omega0``, ``tau``, ``dt``; per gain ``ratio_<gain>`` (simulated
            energy ratio), ``gamma_<gain>``, ``gamma_sq_<gain>``, ``tone_rel_<gain>`` (relative
            distance of the ratio to ``σ_max(G(jω0))²``).
        """
        out = {"omega0": _exact(self.tones[0].omega0), "tau": _exact(self.tau), "dt": _exact(self.dt)}
        for t in self.tones:
            out |= {f"ratio_{t.gain}": num(t.simulated_ratio, 4),
                    f"gamma_{t.gain}": num(t.gamma_lf, 4), f"gamma_sq_{t.gain}": num(t.gamma_sq, 4),
                    f"tone_rel_{t.gain}": num(t.rel_to_tone_gain, 2)}
        return out

    def display_rows(self) -> list:
        """One row per gain, formatted for the book: ``gain, gamma, gamma_sq, tone_sq, ratio,
        below_gamma, below_gamma_sq``.

        Returns
        -------
        list of dict
        """
        return [{"gain": t.gain, "gamma": num(t.gamma_lf, 4), "gamma_sq": num(t.gamma_sq, 4),
                 "tone_sq": num(t.gain_at_omega0_sq, 4), "ratio": num(t.simulated_ratio, 4),
                 "below_gamma": "yes" if t.bound_gamma_holds else "no",
                 "below_gamma_sq": "yes" if t.bound_gamma_sq_holds else "no"} for t in self.tones]

    def to_record(self) -> RecordPart:
        """Record entry ``lemma1_gamma_squared``: the energy ratio against γ and γ².

        Returns
        -------
        RecordPart
        """
        fails = [t.gain for t in self.tones if not t.bound_gamma_holds]
        omega0 = self.tones[0].omega0
        return RecordPart((entry(
            "lemma1_gamma_squared", "Lemma 1, statement (2), paper eq. (8)",
            "int z'z dt < gamma int d'd dt for inputs limited to Omega",
            {t.gain: {"gamma": t.gamma_lf, "gamma_sq": t.gamma_sq,
                      "energy_ratio": t.simulated_ratio} for t in self.tones},
            "differs" if fails else "match",
            f"Energy ratio ∫zᵀz / ∫d² of the windowed tone d(t) = exp(−((t − 4τ)/τ)²) "
            f"sin({_exact(omega0)} t), τ = {_exact(self.tau)} s, inside the LF range Ω_1, simulated "
            f"exactly (first-order hold): it tends to σ_max(G(j{_exact(omega0)}))², exceeds γ for "
            f"{', '.join(fails) or 'no gain'} and stays below γ² for every gain. The LMI of paper "
            f"eq. (7) carries −γ²: the energy bound is γ², not γ.",
            omega0=omega0, tau=self.tau, dt=self.dt),))


@cached
def gamma_vs_gamma_squared(omega0: float = 0.5, *, tau: float = 300.0,
                           dt: float = 0.02) -> GammaSquaredCheck:
    """Energy ratio ∫z²/∫d² of a slowly windowed in-band tone, against γ and γ².

    The input ``d(t) = exp(−((t − 4τ)/τ)²) sin(ω0 t)`` is essentially band-limited
    around ω0 (spectral width ~ 1/τ), so its energy ratio tends to ``|G(jω0)|²``,
    which Lemma 1 bounds by γ² (not γ). Simulated exactly for first-order-hold input
    by ``scipy.signal.lsim`` (:func:`windowed_tone_ratio`).

    Parameters
    ----------
    omega0 : float, optional
        Tone frequency in rad/s (inside Ω_1).
    tau : float, optional
        Window width in s.
    dt : float, optional
        Sample step in s.

    Returns
    -------
    GammaSquaredCheck
        For K_f1 and K_f3 on the LF band.

    Raises
    ------
    ValueError
        If ``omega0`` lies outside Ω_1.

    Notes
    -----
    Statement (2) of Lemma 1 (paper eq. (8)) bounds the energy ratio by γ.
    """
    lf = paper_bands()["LF"]
    if not lf.contains(omega0):
        raise ValueError(f"omega0 must lie in the {lf.label} band, but found {omega0} rad/s")
    plant, gains = aircraft(), paper_gains()
    tones = []
    for name in ("K_f1", "K_f3"):
        cl = plant.closed_loop(gains[name])
        gam = band_peak(cl, lf).gamma
        r = windowed_tone_ratio(cl, omega0, tau=tau, dt=dt)
        tones.append(ToneCheck(name, float(omega0), gam, gam**2, r.gain_sq, r.ratio,
                               r.ratio < gam, r.ratio < gam**2))
    return GammaSquaredCheck(tuple(tones), float(tau), float(dt))


@dataclass(frozen=True)
class GammaSlip:
    """An in-band windowed tone against γ and γ² (see :func:`in_band_gamma_slip`).

    Parameters
    ----------
    gain : str
        Name of the printed gain.
    kind : str
        The band.
    omega0 : float
        Tone frequency in rad/s (in the band).
    tau : float
        Window width in s.
    gamma : float
        Band peak of σ_max for the gain.
    gamma_sq : float
        γ².
    gain_sq : float
        ``σ_max(G(jω0))²``.
    ratio : float
        Simulated energy ratio.
    exceeds_gamma : bool
        ``ratio > γ``.
    below_gamma_sq : bool
        ``ratio < γ²``.
    """

    gain: str
    kind: str
    omega0: float
    tau: float
    gamma: float
    gamma_sq: float
    gain_sq: float
    ratio: float
    exceeds_gamma: bool
    below_gamma_sq: bool

    @property
    def sigma_at_omega0(self) -> float:
        """``σ_max(G(jω0))``."""
        return float(np.sqrt(self.gain_sq))

    @property
    def excess(self) -> float:
        """``ratio − γ`` (positive: the unsquared bound fails)."""
        return self.ratio - self.gamma

    def prose(self) -> dict:
        """The numbers the chapter quotes (:mod:`fdsc.paper.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``omega0``, ``tau``, ``gamma``, ``gamma_sq``, ``ratio``,
            ``sigma0`` (σ_max at ω0) and ``excess`` (ratio − γ).
        """
        return {"omega0": _exact(self.omega0), "tau": _exact(self.tau), "gamma": num(self.gamma, 4),
                "gamma_sq": num(self.gamma_sq, 4), "ratio": num(self.ratio, 4),
                "sigma0": num(self.sigma_at_omega0, 4), "excess": num(self.excess, 3)}

    def to_record(self) -> RecordPart:
        """Record entry ``gamma_slip_in_band``: (P.1), (P.2) and paper Remark 5 in band.

        Returns
        -------
        RecordPart
        """
        return RecordPart((entry(
            "gamma_slip_in_band",
            "(P.1) paper eq. (14), (P.2) paper eq. (15), paper Remark 5 eq. (54)",
            "energy ratio compared with the unsquared gain gamma",
            {"energy_ratio": self.ratio, "gamma": self.gamma, "gamma_sq": self.gamma_sq,
             "sigma_max_at_omega0": self.sigma_at_omega0},
            "differs" if self.exceeds_gamma else "match",
            f"Windowed tone at {_exact(self.omega0)} rad/s inside the {self.kind} range (τ = "
            f"{_exact(self.tau)} s) under {self.gain}: the energy ratio {num(self.ratio, 4)} "
            + ("exceeds" if self.exceeds_gamma else "stays below")
            + f" γ = {num(self.gamma, 4)} and "
            + ("stays below" if self.below_gamma_sq else "exceeds")
            + f" γ² = {num(self.gamma_sq, 4)}; read with squares, the three statements agree "
            "with the simulation.", gain=self.gain, omega0=self.omega0, tau=self.tau),))


@cached
def in_band_gamma_slip(gain: str = "K_f3", kind: str = "HF", omega0: float = 10.5, *,
                       tau: float = 30.0, dt: float = 5e-3) -> GammaSlip:
    """γ against γ² in the paper's own in-band setting: a tone inside Ω_3 under K_f3.

    (P.1) paper eq. (14), (P.2) paper eq. (15) and paper Remark 5 eq. (54) compare an energy
    ratio with an (unsquared) gain. This evaluates the energy ratio of a slowly windowed tone
    inside the band against the band peak γ of σ_max and against γ².

    Parameters
    ----------
    gain : str, optional
        Name of the printed gain (one of :data:`fdsc.paper.names.GAIN_ORDER`).
    kind : {"LF", "MF", "HF", "EF"}, optional
        The band.
    omega0 : float, optional
        Tone frequency in rad/s (in the band).
    tau : float, optional
        Window width in s.
    dt : float, optional
        Sample step in s.

    Returns
    -------
    GammaSlip

    Raises
    ------
    ValueError
        If ``gain`` or ``kind`` is unknown or ``omega0`` lies outside the band.

    Examples
    --------
    >>> r = in_band_gamma_slip()
    >>> r.exceeds_gamma, r.below_gamma_sq
    (True, True)
    """
    as_choice("gain", gain, GAIN_ORDER)
    as_choice("kind", kind, BAND_ORDER)
    band = paper_bands()[kind]
    if not band.contains(omega0):
        raise ValueError(f"omega0 must lie in the {band.label} band, but found {omega0} rad/s")
    cl = aircraft().closed_loop(paper_gains()[gain])
    gamma = band_peak(cl, band).gamma
    r = windowed_tone_ratio(cl, omega0, tau=tau, dt=dt)
    return GammaSlip(gain, kind, float(omega0), float(tau), gamma, gamma**2, r.gain_sq, r.ratio,
                     r.ratio > gamma, r.ratio < gamma**2)


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
