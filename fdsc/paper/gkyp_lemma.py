"""Chapter 'gkyp_lemma': Lemma 1 (paper eq. (7)) on the printed gains, the printed bounds, and the
γ versus γ² slip of statement (2) (paper eq. (8)) and of (P.1), (P.2) and paper Remark 5.
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
from .results import RecordPart, entry, pick
from .verdict import verdict

__all__ = [
    "record_part",
    "GainBandPeak",
    "GainBandTable",
    "gain_band_table",
    "PrintedBound",
    "PrintedBounds",
    "printed_bounds",
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

    def to_record(self) -> RecordPart:
        """Record entries ``sigma_peak`` (band peaks of σ_max of the printed gains) and
        ``lemma1_gamma`` (Lemma 1's certified γ for the same pairs); both new: the printed bounds
        are judged once, in the entries ``bound_f1`` … ``bound_e``.

        Returns
        -------
        RecordPart
        """
        bounds = printed_bounds(self).bounds
        ratios = ", ".join(f"{b.gain} {b.paper}/{b.peak:.4f}" for b in bounds)
        return RecordPart((
            entry("sigma_peak", "Sec. IV, the printed gains K_f1, K_f2, K_f3, K_e; paper Fig. 3",
                  None, self.by_gain_band("peak"), "new",
                  "sup of sigma_max(G(jw)) over each band (grid + local refinement, tail bound "
                  "for HF/EF) for the printed gains; in-band, beside the printed bounds: " + ratios +
                  ". Each printed bound has one verdict, in its own entry (the printed bounds "
                  "appendix), with every reading tried.", omega_peak=self.by_gain_band("omega_peak"),
                  printed_bounds=_paper_bounds()),
            entry("lemma1_gamma", "Lemma 1 (eq. gKYP_LMI) applied to the printed gains",
                  None, self.by_gain_band("lmi_gamma"), "new",
                  f"smallest gamma certified by the gKYP LMI (cvxpy + Clarabel, real embedding "
                  f"for MF); equals the swept band peak within {self.worst_rel_diff:.1e} relative "
                  f"on all {len(self.pairs)} gain/band pairs, so Lemma 1 is lossless here. Lemma 1's "
                  "value is one of the readings of each printed bound (the printed bounds appendix).",
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


@dataclass(frozen=True)
class PrintedBound:
    """A bound printed in Sec. IV beside the in-band peak of its gain.

    Parameters
    ----------
    gain : str
        Name of the printed gain.
    band : str
        The band it was designed for.
    paper : float
        The printed bound.
    peak : float
        The in-band peak of σ_max for the printed gain.
    lmi_gamma : float
        Lemma 1's γ for the same pair.
    ratio : float
        ``paper / peak``.
    verdict : str
        Of ``peak`` against ``paper`` (:func:`fdsc.paper.verdict.verdict`).
    """

    gain: str
    band: str
    paper: float
    peak: float
    lmi_gamma: float
    ratio: float
    verdict: str


@dataclass(frozen=True)
class PrintedBounds:
    """The four printed bounds (see :func:`printed_bounds`).

    Parameters
    ----------
    bounds : tuple of PrintedBound
        In the order of the gains.
    """

    bounds: tuple

    def rows(self) -> list:
        """One row per bound with every field (for :func:`fdsc.paper.report.html_table`).

        Returns
        -------
        list of dict
        """
        return [vars(b).copy() for b in self.bounds]

    def __getitem__(self, gain: str) -> PrintedBound:
        """The bound of one gain.

        Parameters
        ----------
        gain : str
            Name of the gain.

        Returns
        -------
        PrintedBound
        """
        return pick(self.bounds, "gain", gain)


def printed_bounds(table: GainBandTable | None = None) -> PrintedBounds:
    """The four printed bounds beside the in-band peak of σ_max for the printed gains.

    Parameters
    ----------
    table : GainBandTable, optional
        Output of :func:`gain_band_table` (default: computed).

    Returns
    -------
    PrintedBounds
    """
    table = gain_band_table() if table is None else table
    ctrl = paper_data("controllers")
    out = []
    for p in table.pairs:
        bound = ctrl[p.gain]["bound"]
        if ctrl[p.gain]["band"] == p.band:
            out.append(PrintedBound(p.gain, p.band, bound, p.peak, p.lmi_gamma, bound / p.peak,
                                    verdict(bound, p.peak)))
    return PrintedBounds(tuple(out))


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
            f"energy ratio of the windowed tone exp(-((t - 4 tau)/tau)^2) sin({omega0:g} t), "
            f"tau = {self.tau:g} s, inside Omega_1, simulated exactly (first-order hold): it "
            f"tends to sigma_max(G(j{omega0:g}))^2 and exceeds gamma for "
            f"{', '.join(fails) or 'no gain'}, while gamma^2 bounds it for every gain. The LMI of "
            f"paper eq. (7) carries -gamma^2: the energy bound is gamma^2.",
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
            f"windowed tone at {self.omega0:g} rad/s inside the {self.kind} band (tau = "
            f"{self.tau:g} s) under {self.gain}: the energy ratio {self.ratio:.4g} "
            + ("exceeds" if self.exceeds_gamma else "stays below")
            + f" gamma = {self.gamma:.4g} and "
            + ("stays below" if self.below_gamma_sq else "exceeds")
            + f" gamma^2 = {self.gamma_sq:.4g}; read with squares the three statements agree "
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
