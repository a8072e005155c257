"""Chapter 'frequency_ranges': Sec. II-A, Definitions 1-3 (Ψ of the three ranges, the weight's
sign, Paley–Wiener, dominance degrees) and the factorizations printed in Proposition 1's proof.
"""

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from fdsc._validation import as_vector
from fdsc.paper.reproduced.dominance import (
    DominanceVsRho,
    PiecewiseDominance,
    dominance_vs_rho,
    localized_dominance_piecewise,
)
from fdsc.paper.reproduced.paley_wiener import (
    PALEY_WIENER_HORIZONS,
    PaleyWienerCase,
    PaleyWienerTable,
    out_of_band_fraction,
    paley_wiener_table,
    truncated_energy,
    truncated_spectrum,
)
from fdsc.paper.reproduced.proposition1 import Factorization, Prop1WeightCheck, prop1_weight_check
from fdsc.paper.shared.data import paper_bands
from fdsc.paper.shared.names import BAND_ORDER
from fdsc.paper.shared.prose import count, num
from fdsc.paper.shared.results import RecordPart, entry

__all__ = [
    "record_part",
    "RANGES",
    "PsiEntry",
    "PsiTable",
    "psi_table",
    "BandWeight",
    "PsiWeights",
    "psi_weights",
    "DominanceVsRho",
    "dominance_vs_rho",
    "PiecewiseDominance",
    "localized_dominance_piecewise",
    "Factorization",
    "Prop1WeightCheck",
    "prop1_weight_check",
    "truncated_spectrum",
    "truncated_energy",
    "out_of_band_fraction",
    "PALEY_WIENER_HORIZONS",
    "PaleyWienerCase",
    "PaleyWienerTable",
    "paley_wiener_table",
]


#: The ranges of Lemma 1 that carry a Ψ (the entire range Ω_e has Ψ = 0).
RANGES = tuple(k for k in BAND_ORDER if k != "EF")


# -- Ψ and its weight ---------------------------------------------------------------------------

@dataclass(frozen=True)
class PsiEntry:
    """Ψ of one of the paper's ranges (Lemma 1, paper eq. (7)).

    Parameters
    ----------
    kind : {"LF", "MF", "HF"}
        The range.
    label : str
        The range with its limits, e.g. ``"LF [0, 1] rad/s"``.
    psi : (2, 2) ndarray
        Ψ (complex for MF).
    is_complex : bool
        Ψ has a nonzero imaginary part.
    """

    kind: str
    label: str
    psi: np.ndarray
    is_complex: bool


@dataclass(frozen=True)
class PsiTable:
    """Ψ of the paper's three ranges Ω_1, Ω_2, Ω_3 (paper eq. (55)).

    Parameters
    ----------
    ranges : tuple of PsiEntry
        One per range, in the order LF, MF, HF.
    """

    ranges: tuple

    def rows(self) -> list:
        """One row per range: ``band, range, Psi`` (printed to 3 decimals), ``complex``.

        Returns
        -------
        list of dict
            For :func:`fdsc.paper.shared.report.html_table`.
        """
        return [{"band": r.kind, "range": r.label, "Psi": _matrix_text(r.psi),
                 "complex": "yes" if r.is_complex else "no"} for r in self.ranges]


def _entry_text(z):
    z = complex(z)
    re_, im = z.real, z.imag
    if im == 0:
        return num(re_) if not float(re_).is_integer() else count(int(re_))
    mag = num(abs(im)) if not float(im).is_integer() else count(int(abs(im)))
    return ("−" if im < 0 else "") + f"{mag}j" if re_ == 0 else f"{num(re_)} {'−' if im < 0 else '+'} {mag}j"


def _matrix_text(m):
    """A small matrix as the prose prints it, rows separated by a semicolon: ``[−1, 0; 0, 1]``."""
    return "[" + "; ".join(", ".join(_entry_text(z) for z in row) for row in np.asarray(m)) + "]"


def psi_table() -> PsiTable:
    """Ψ of each of the paper's bands (Ω_1, Ω_2, Ω_3 of paper eq. (55)).

    Returns
    -------
    PsiTable

    Examples
    --------
    >>> [(r.kind, r.is_complex) for r in psi_table().ranges]
    [('LF', False), ('MF', True), ('HF', False)]
    """
    bands = paper_bands()
    return PsiTable(tuple(PsiEntry(k, bands[k].label, bands[k].psi, bands[k].is_complex)
                          for k in RANGES))


def _sign_violations(band, omega, weight):
    """Grid points where the weight has the wrong sign: < 0 in the band or > 0 outside.

    For MF only ω ≥ 0 counts as in band: on the mirror interval [−ϖ_2, −ϖ_1] the weight is
    negative by construction (the rule the proof needs holds for ω > 0 only, see
    :func:`prop1_weight_check`).
    """
    inside = band.contains(omega)
    rule_inside = inside & ((omega >= 0) | (band.kind != "MF"))
    return int(np.sum(weight[rule_inside] < 0) + np.sum(weight[~inside] > 0))


@dataclass(frozen=True)
class BandWeight:
    """The weight of Ψ of one range over ω (see :func:`psi_weights`).

    Parameters
    ----------
    kind : {"LF", "MF", "HF"}
        The range.
    label : str
        The range with its limits.
    lower, upper : float
        Band limits in rad/s (``upper`` is inf for HF).
    weight : (k,) ndarray
        ``[jω; 1]* Ψ [jω; 1]``.
    real_weight : (k,) ndarray
        The same with Re Ψ (what a quadratic form in a real signal sees).
    n_sign_violations : int
        Grid points where ``weight`` is < 0 in the band (MF: for ω ≥ 0) or > 0 outside.
    """

    kind: str
    label: str
    lower: float
    upper: float
    weight: np.ndarray
    real_weight: np.ndarray
    n_sign_violations: int


@dataclass(frozen=True)
class PsiWeights:
    """The weight of Ψ for the paper's three ranges over positive and negative ω.

    Parameters
    ----------
    omega : (k,) ndarray
        Frequencies in rad/s.
    bands : dict
        ``{kind: BandWeight}`` for LF, MF, HF.
    """

    omega: np.ndarray
    bands: dict

    def __post_init__(self):
        for kind, b in self.bands.items():
            if b.weight.shape != self.omega.shape or b.real_weight.shape != self.omega.shape:
                raise ValueError(f"bands: the weights of {kind} must have the shape of omega "
                                 f"{self.omega.shape}, but found {b.weight.shape}")

    def __getitem__(self, kind: str) -> BandWeight:
        """The weight of one range.

        Parameters
        ----------
        kind : {"LF", "MF", "HF"}
            The range.

        Returns
        -------
        BandWeight
        """
        return self.bands[kind]

    @property
    def n_sign_violations(self) -> int:
        """Sign violations summed over the three ranges."""
        return sum(b.n_sign_violations for b in self.bands.values())

    @property
    def mf_real_max(self) -> float:
        """Largest weight of Re Ψ_MF on the grid (−(ω² + ϖ_1ϖ_2) < 0 in closed form)."""
        return float(self.bands["MF"].real_weight.max())

    @property
    def mf_product(self) -> float:
        """ϖ_1ϖ_2 of the MF range in (rad/s)²."""
        return self.bands["MF"].lower * self.bands["MF"].upper

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``n_grid``, ``sign_violations``, ``mf_real_max``, ``mf_w1w2``.
        """
        return {"n_grid": count(self.omega.size), "sign_violations": count(self.n_sign_violations),
                "mf_real_max": num(self.mf_real_max, 4), "mf_w1w2": num(float(self.mf_product), 3)}

    def to_record(self) -> RecordPart:
        """Record entry ``psi_weight_sign``: the sign rule of the weight that the proof of
        Proposition 1 rests on, and the MF weight seen by real signals.

        Returns
        -------
        RecordPart
        """
        counts = {k: b.n_sign_violations for k, b in self.bands.items()}
        rng = f"±[{np.abs(self.omega).min():g}, {np.abs(self.omega).max():g}] rad/s"
        return RecordPart((entry(
            "psi_weight_sign",
            "Sec. III, proof of Proposition 1: sign of [(jω)* 1] Ψ [(jω)* 1]*",
            "the weight [(jω)* 1] Ψ_i [(jω)* 1]* ≥ 0 for ω in Ω_i and ≤ 0 outside",
            {"sign_violations": counts, "grid_points": int(self.omega.size),
             "mf_real_weight_max": self.mf_real_max},
            "match" if self.n_sign_violations == 0 else "differs",
            f"weight of Ψ counted on {count(self.omega.size)} grid points over {rng}: "
            f"{self.n_sign_violations} sign violations for LF and HF over all ω and for MF over "
            f"ω ≥ 0 (on the mirror interval [−ϖ_2, −ϖ_1] the MF weight is negative: see "
            f"the factorized weights of Proposition 1). For real signals only Re Ψ counts, and the MF "
            f"weight of Re Ψ is −(ω² + ϖ_1ϖ_2), at most {num(self.mf_real_max, 4)} on the grid: the "
            f"MF FD-EEF of a real signal is never positive."),))


def psi_weights(omega: ArrayLike | None = None) -> PsiWeights:
    """The weight ``[jω;1]* Ψ [jω;1]`` and its real-signal part for the paper's three bands.

    Parameters
    ----------
    omega : (k,) array_like, optional
        Frequencies in rad/s (default: ±[10⁻², 10³], 600 log-spaced points per sign).

    Returns
    -------
    PsiWeights
        With the sign-rule count of each range.

    Notes
    -----
    The weight is written ``[(jω)* 1] Ψ [(jω)* 1]*`` in the proof of paper Proposition 1, which
    rests on its sign: ≥ 0 in the band, ≤ 0 outside.

    Examples
    --------
    >>> w = psi_weights()
    >>> w.n_sign_violations, w.mf_real_max < -w.mf_product
    (0, True)
    """
    if omega is None:
        pos = np.geomspace(1e-2, 1e3, 600)
        omega = np.concatenate([-pos[::-1], pos])
    omega = as_vector("omega", omega)
    bands = paper_bands()
    out = {}
    for kind in RANGES:
        band = bands[kind]
        weight = band.weight(omega)
        out[kind] = BandWeight(kind, band.label, band.lower, band.upper, weight,
                               band.real_weight(omega), _sign_violations(band, omega, weight))
    return PsiWeights(omega, out)


def record_part() -> RecordPart:
    """Record entries of the chapter: ``psi_weight_sign``, ``prop1_factorizations``,
    ``paley_wiener_share``, ``alpha_mixed`` and ``alpha_localized``.

    Returns
    -------
    RecordPart
    """
    return (psi_weights().to_record() + prop1_weight_check().to_record()
            + paley_wiener_table().to_record() + dominance_vs_rho().to_record()
            + localized_dominance_piecewise().to_record())
