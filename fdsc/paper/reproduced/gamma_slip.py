"""Chapter 'gkyp_lemma', continued: γ or γ²?

The energy ratio of a slowly windowed in-band tone tends to ``|G(jω0)|²``, which Lemma 1 bounds
by γ² (statement (2), paper eq. (8)), while (P.1) (paper eq. (14)), (P.2) (paper eq. (15)) and
paper Remark 5 (paper eq. (54)) compare an energy ratio with γ: such ratios against γ and γ², and
the same in the paper's own in-band setting (a tone inside Ω_3 under K_f3).
"""

from dataclasses import dataclass

import numpy as np
from scipy.signal import lsim

from fdsc._validation import as_choice, as_positive, check_type
from fdsc.frequency import band_peak, sigma_max
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.data import aircraft, paper_bands, paper_gains
from fdsc.paper.shared.names import BAND_ORDER, GAIN_ORDER
from fdsc.paper.shared.prose import num
from fdsc.paper.shared.results import RecordPart, entry, pick
from fdsc.plant import LTISystem

__all__ = [
    "GammaSlip", "GammaSquaredCheck", "ToneCheck", "WindowedTone", "gamma_vs_gamma_squared",
    "in_band_gamma_slip", "windowed_tone_ratio",
]


def _exact(x):
    """A chosen parameter printed with just the digits it has (0.5, not 0.500)."""
    digits = f"{x:g}".replace(".", "").replace("-", "").lstrip("0")
    return num(float(x), max(1, len(digits)))


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
        """One row per gain with every field (for :func:`fdsc.paper.shared.report.html_table`).

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
        """The numbers the chapter quotes (:mod:`fdsc.paper.shared.prose`).

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
            "∫ zᵀz dt < γ ∫ dᵀd dt for inputs limited to Ω",
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
        """The numbers the chapter quotes (:mod:`fdsc.paper.shared.prose`).

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
        Name of the printed gain (one of :data:`fdsc.paper.shared.names.GAIN_ORDER`).
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
