"""Chapter 'frequency_ranges', continued: Definition 1 on [0, ∞), Paley–Wiener.

By Paley–Wiener no record of finite length lies in one range: the spectrum of the paper's test
signals cut to [0, T] in closed form, its energy, and the share of it outside the signal's range
for several record lengths T.
"""

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from fdsc._validation import as_positive, as_vector, check_type
from fdsc.bands import Band
from fdsc.paper.reproduced.dominance import _length
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.data import hf_disturbance, lf_disturbance, paper_bands
from fdsc.paper.shared.prose import count, num
from fdsc.paper.shared.results import RecordPart, entry
from fdsc.signals import Sinusoids

__all__ = [
    "PALEY_WIENER_HORIZONS", "PaleyWienerCase", "PaleyWienerTable", "out_of_band_fraction",
    "paley_wiener_table", "truncated_energy", "truncated_spectrum",
]


#: Truncation lengths T (s) of the paper's test signals in :func:`paley_wiener_table`.
PALEY_WIENER_HORIZONS = (50.0, 500.0, 5000.0)


#: Gauss–Legendre nodes per panel in :func:`out_of_band_fraction`.
_GL_NODES = 16


#: Panels per half period 2π/T of the spectrum's oscillation in ω.
_PANELS_PER_HALF_PERIOD = 2


def _check_sinusoids(d):
    check_type("d", d, Sinusoids)
    if np.any(d.phases != 0):
        raise ValueError("d must have zero phases (sums of sines, as in the paper), "
                         f"but found phases {d.phases.tolist()}")


def _window_integral(nu, T):
    # ∫_0^T exp(jνt) dt, written with sinc so that ν = 0 needs no special case.
    return T * np.exp(0.5j * nu * T) * np.sinc(nu * T / (2.0 * np.pi))


def truncated_spectrum(d: Sinusoids, T: float, omega: ArrayLike) -> np.ndarray:
    """Fourier transform of the causal truncation ``d(t)·1[0, T](t)`` of a sum of sines.

    ``D(ω) = ∫_0^T d(t) e^{−jωt} dt`` in closed form, for ``d = Σ a_k sin(ω_k t)``.

    Parameters
    ----------
    d : Sinusoids
        With zero phases.
    T : float
        Length of the record in s (> 0).
    omega : (N,) array_like
        Frequencies in rad/s.

    Returns
    -------
    (N,) complex ndarray

    Raises
    ------
    TypeError
        If ``d`` is not a :class:`fdsc.Sinusoids`.
    ValueError
        If ``d`` has a nonzero phase or ``T`` is not positive.

    Notes
    -----
    The transform of paper eq. (3) (Definition 1) applied to a finite record.

    Examples
    --------
    >>> D = truncated_spectrum(Sinusoids([1.0], [1.0]), 2 * np.pi, [1.0])
    >>> complex(np.round(D[0], 10))  # ∫_0^{2π} sin t e^{−jt} dt = −jπ
    -3.1415926536j
    """
    _check_sinusoids(d)
    T = as_positive("T", T)
    w = as_vector("omega", omega)
    D = np.zeros(w.shape, dtype=complex)
    for a, wk in zip(d.amplitudes, d.frequencies, strict=True):
        D += a / 2j * (_window_integral(wk - w, T) - _window_integral(-wk - w, T))
    return D


def truncated_energy(d: Sinusoids, T: float) -> float:
    """``∫_0^T d(t)² dt`` in closed form for a sum of sines ``d = Σ a_k sin(ω_k t)``.

    Parameters
    ----------
    d : Sinusoids
        With zero phases.
    T : float
        Length of the record in s (> 0).

    Returns
    -------
    float

    Raises
    ------
    TypeError
        If ``d`` is not a :class:`fdsc.Sinusoids`.
    ValueError
        If ``d`` has a nonzero phase or ``T`` is not positive.

    Examples
    --------
    >>> round(truncated_energy(Sinusoids([1.0], [1.0]), 2 * np.pi), 12)  # = π
    3.14159265359
    """
    _check_sinusoids(d)
    T = as_positive("T", T)
    a, w = d.amplitudes, d.frequencies

    def cos_integral(nu):  # ∫_0^T cos(νt) dt
        return T * np.sinc(nu * T / np.pi)

    diff = np.subtract.outer(w, w)
    summ = np.add.outer(w, w)
    return float(0.5 * a @ (cos_integral(diff) - cos_integral(summ)) @ a)


def _low_band_energy(d, T, upper):
    """``(1/π) ∫_0^upper |D(ω)|² dω`` (energy in |ω| ≤ upper) by panelled Gauss–Legendre."""
    n_panels = max(8, math.ceil(_PANELS_PER_HALF_PERIOD * upper * T / np.pi))
    x, wq = np.polynomial.legendre.leggauss(_GL_NODES)
    edges = np.linspace(0.0, upper, n_panels + 1)
    half = 0.5 * np.diff(edges)
    nodes = (edges[:-1, None] + half[:, None] * (x[None, :] + 1.0)).ravel()
    weights = (half[:, None] * wq[None, :]).ravel()
    return float(weights @ np.abs(truncated_spectrum(d, T, nodes)) ** 2 / np.pi)


def out_of_band_fraction(d: Sinusoids, T: float, band: Band) -> float:
    """Share of the energy of ``d·1[0, T]`` that lies outside ``band`` (two-sided spectrum).

    By Paley–Wiener the Fourier transform of a nonzero causal L2 signal cannot vanish on an
    interval, so this share is positive for every T; it is not zero for a finite record of
    in-band sinusoids either.

    Parameters
    ----------
    d : Sinusoids
        With zero phases.
    T : float
        Record length in s.
    band : Band
        An LF or HF band.

    Returns
    -------
    float
        ``E_out / E`` with ``E = ∫_0^T d² dt`` (closed form) and the in-band part by
        Parseval, ``(1/2π) ∫_{Ω} |D(ω)|² dω``, integrated by Gauss–Legendre on panels much
        shorter than the spectrum's oscillation period 2π/T.

    Raises
    ------
    TypeError
        If ``d`` or ``band`` has the wrong type.
    ValueError
        If ``band`` is not LF or HF, ``d`` has a nonzero phase or ``T`` is not positive.

    Notes
    -----
    Definition 1 (paper eq. (3)) asks this share to be zero.

    Examples
    --------
    >>> lf = Sinusoids([1.0, 1.0, 1.0], [0.1, 0.2, 0.3])
    >>> f = out_of_band_fraction(lf, 500.0, Band.lf(1.0))
    >>> 0 < f < 1e-2
    True
    """
    check_type("band", band, Band)
    if band.kind not in ("LF", "HF"):
        raise ValueError(f"band must be an LF or HF band, but found kind {band.kind!r}")
    total = truncated_energy(d, T)
    if band.kind == "LF":
        return (total - _low_band_energy(d, T, band.upper)) / total
    return _low_band_energy(d, T, band.lower) / total


@dataclass(frozen=True)
class PaleyWienerCase:
    """One of the paper's test signals cut to ``[0, T]``, and its energy outside its band.

    Parameters
    ----------
    kind : {"LF", "HF"}
        The signal (paper eq. (56) or (57)) and its band (Ω_1 or Ω_3).
    signal : str
        The signal as the table names it.
    band : str
        The band's label.
    T : float
        Record length in s.
    fraction_out : float
        Share of the record's energy outside the band (:func:`out_of_band_fraction`).
    """

    kind: str
    signal: str
    band: str
    T: float
    fraction_out: float


@dataclass(frozen=True)
class PaleyWienerTable:
    """Out-of-band energy shares of the paper's test signals over record lengths.

    Parameters
    ----------
    cases : tuple of PaleyWienerCase
        One per signal and record length.
    """

    cases: tuple

    def rows(self) -> list:
        """One row per case: ``signal, band, T, fraction_out``.

        Returns
        -------
        list of dict
            For :func:`fdsc.paper.shared.report.html_table`.
        """
        return [{"signal": c.signal, "band": c.band, "T": c.T, "fraction_out": c.fraction_out}
                for c in self.cases]

    @property
    def horizons(self) -> tuple:
        """The record lengths, in order of first appearance."""
        return tuple(dict.fromkeys(c.T for c in self.cases))

    @property
    def n_positive(self) -> int:
        """Cases with a positive out-of-band share."""
        return sum(c.fraction_out > 0 for c in self.cases)

    def min_fraction(self, kind: str) -> float:
        """Smallest out-of-band share of one signal over the record lengths.

        Parameters
        ----------
        kind : {"LF", "HF"}
            The signal.

        Returns
        -------
        float
        """
        return min(c.fraction_out for c in self.cases if c.kind == kind)

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``T_list`` (the record lengths), ``lf_min``, ``hf_min`` (the
            smallest out-of-band shares), ``n_positive``, ``n_rows``.
        """
        return {"T_list": ", ".join(_length(T) for T in self.horizons),
                "lf_min": num(self.min_fraction("LF")), "hf_min": num(self.min_fraction("HF")),
                "n_positive": count(int(self.n_positive)), "n_rows": count(len(self.cases))}

    def to_record(self) -> RecordPart:
        """Record entry ``paley_wiener_share`` (new): Definition 1 on finite records.

        Returns
        -------
        RecordPart
        """
        shares = {c.kind: {} for c in self.cases}
        for c in self.cases:
            shares[c.kind][f"T={c.T:g}"] = c.fraction_out
        return RecordPart((entry(
            "paley_wiener_share", "Definition 1 (paper eq. (3)) on the signals of paper eqs. (56), (57)",
            None, shares, "new",
            f"share of the energy of the LF (eq. (56)) and HF (eq. (57)) signals cut to [0, T] "
            f"that lies outside Omega_1 and Omega_3, from the closed-form transform: positive in "
            f"{self.n_positive} of {len(self.cases)} cases, shrinking with T. By Paley-Wiener no "
            f"nonzero causal L2 signal is frequency-limited, so the class of Definition 1 is "
            f"empty and the statements that assume it are vacuous as printed."),))


@cached
def paley_wiener_table(horizons: tuple = PALEY_WIENER_HORIZONS) -> PaleyWienerTable:
    """Out-of-band energy share of the paper's test signals truncated to ``[0, T]``.

    The LF signal of paper eq. (56) against Ω_1 and the HF signal of paper eq. (57) against Ω_3.

    Parameters
    ----------
    horizons : tuple of float, optional
        Record lengths T in s.

    Returns
    -------
    PaleyWienerTable

    Examples
    --------
    >>> table = paley_wiener_table((100.0,))
    >>> [c.signal for c in table.cases], table.n_positive
    (['LF, eq. (56)', 'HF, eq. (57)'], 2)
    """
    bands = paper_bands()
    cases = []
    for kind, d in (("LF", lf_disturbance()), ("HF", hf_disturbance())):
        label = "LF, eq. (56)" if kind == "LF" else "HF, eq. (57)"
        for T in horizons:
            cases.append(PaleyWienerCase(kind, label, bands[kind].label, float(T),
                                         out_of_band_fraction(d, T, bands[kind])))
    return PaleyWienerTable(tuple(cases))
