"""Chapter 'frequency_ranges', continued: the factorizations printed in the proof of Proposition 1.

Each range's weight ``[jω; 1]* Ψ [jω; 1]`` against the product the proof prints for it, on a
grid of frequencies, with the sign the proof needs.
"""

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from fdsc._validation import as_vector
from fdsc.bands import Band
from fdsc.paper.shared.prose import count, num
from fdsc.paper.shared.results import RecordPart, entry

__all__ = ["Factorization", "Prop1WeightCheck", "prop1_weight_check"]


#: The factorizations as the proof of Proposition 1 prints them (between paper eqs. (23), (24)).
_PRINTED = {"LF": "(ϖ_l − jω)(ϖ_l + jω) > 0", "MF": "(ω − ϖ_1)(ϖ_2 − ω) > 0",
            "HF": "(jω − ϖ_h)(jω + ϖ_h) > 0"}


def _default_grid():
    # 400 points per sign: the log step 5/399 puts no grid point on a band edge (1 or 10 rad/s),
    # where the weight is zero and its sign undefined.
    pos = np.geomspace(1e-2, 1e3, 400)
    return np.concatenate([-pos[::-1], pos])


@dataclass(frozen=True)
class Factorization:
    """One printed factorization of the weight against the weight (see :func:`prop1_weight_check`).

    Parameters
    ----------
    kind : {"LF", "MF", "HF"}
        The range.
    weight : (N,) ndarray
        The weight ``[jω; 1]* Ψ [jω; 1]`` (:meth:`fdsc.Band.weight`).
    printed : (N,) ndarray
        The product printed in the proof of Proposition 1.
    corrected : (N,) ndarray
        The real factorization of the weight.
    tau_diagonal : (N,) ndarray
        τ(Ψ_i, ω, ω) of the proof of Theorem 1.
    in_band : (N,) ndarray of bool
        Mask of the two-sided band.
    n_wrong_sign : int
        Points where printed product and weight have opposite signs.
    n_claim_fails : int
        In-band points where the printed product is not > 0 (the proof's claim).
    n_in_band_negative : int
        In-band points with ω < 0.
    max_abs_diff, max_abs_diff_corrected, max_abs_diff_tau : float
        Largest ``|printed − weight|``, ``|corrected − weight|``, ``|tau_diagonal − weight|``.
    """

    kind: str
    weight: np.ndarray
    printed: np.ndarray
    corrected: np.ndarray
    tau_diagonal: np.ndarray
    in_band: np.ndarray
    n_wrong_sign: int
    n_claim_fails: int
    n_in_band_negative: int
    max_abs_diff: float
    max_abs_diff_corrected: float
    max_abs_diff_tau: float

    @property
    def n_in_band(self) -> int:
        """Grid points in the (two-sided) band."""
        return int(self.in_band.sum())

    @property
    def n_out_of_band(self) -> int:
        """Grid points outside the band."""
        return int((~self.in_band).sum())

    @property
    def rel_diff_corrected(self) -> float:
        """``max_abs_diff_corrected`` relative to the largest ``|weight|`` on the grid."""
        return self.max_abs_diff_corrected / float(np.max(np.abs(self.weight)))

    @property
    def rel_diff_tau(self) -> float:
        """``max_abs_diff_tau`` relative to the largest ``|weight|`` on the grid."""
        return self.max_abs_diff_tau / float(np.max(np.abs(self.weight)))


@dataclass(frozen=True)
class Prop1WeightCheck:
    """The factorizations printed in the proof of Proposition 1, per range, on one grid.

    Parameters
    ----------
    omega : (N,) ndarray
        Frequencies in rad/s.
    bands : dict
        ``{kind: Factorization}`` for LF, MF, HF.
    """

    omega: np.ndarray
    bands: dict

    def __getitem__(self, kind: str) -> Factorization:
        """The check of one range.

        Parameters
        ----------
        kind : {"LF", "MF", "HF"}
            The range.

        Returns
        -------
        Factorization
        """
        return self.bands[kind]

    @property
    def max_printed_diff(self) -> float:
        """Largest ``|printed − weight|`` over LF and HF (MF prints the weight itself)."""
        return max(self.bands[k].max_abs_diff for k in ("LF", "HF"))

    @property
    def max_rel_diff_corrected(self) -> float:
        """Largest relative difference of the corrected factorizations over the three ranges."""
        return max(f.rel_diff_corrected for f in self.bands.values())

    @property
    def max_rel_diff_tau(self) -> float:
        """Largest relative difference of τ's diagonal over the three ranges."""
        return max(f.rel_diff_tau for f in self.bands.values())

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``n_grid``; per range ``{kind}_wrong``, ``{kind}_claim_fails``,
            ``{kind}_in_band``, ``{kind}_out_band``; ``max_diff``, ``corrected_rel``,
            ``tau_rel``, ``mf_negative``.
        """
        out = {"n_grid": count(self.omega.size)}
        for kind, f in self.bands.items():
            out.update({f"{kind}_wrong": count(f.n_wrong_sign), f"{kind}_claim_fails": count(f.n_claim_fails),
                        f"{kind}_in_band": count(f.n_in_band), f"{kind}_out_band": count(f.n_out_of_band)})
        return {**out, "max_diff": num(self.max_printed_diff),
                "corrected_rel": num(self.max_rel_diff_corrected, 2),
                "tau_rel": num(self.max_rel_diff_tau, 2),
                "mf_negative": count(self.bands["MF"].n_in_band_negative)}

    def to_record(self) -> RecordPart:
        """Record entry ``prop1_factorizations``: the printed products against the weight.

        Returns
        -------
        RecordPart
        """
        fails = any(f.n_wrong_sign or f.n_claim_fails for f in self.bands.values())
        mf = self.bands["MF"]
        return RecordPart((entry(
            "prop1_factorizations",
            "Sec. III, proof of Proposition 1, display between paper eqs. (23) and (24)",
            dict(_PRINTED),
            {"grid_points": int(self.omega.size),
             **{k: {"wrong_sign": f.n_wrong_sign, "claim_fails": f.n_claim_fails,
                    "in_band": f.n_in_band, "max_abs_diff": f.max_abs_diff}
                for k, f in self.bands.items()},
             "corrected_max_rel_diff": self.max_rel_diff_corrected},
            "differs" if fails else "match",
            f"multiplied out, the printed LF product is ϖ_l² + ω² > 0 and the HF product "
            f"−ω² − ϖ_h² < 0 at every ω, while the weights are ϖ_l² − ω² and ω² − ϖ_h² "
            f"(wrong sign at {self.bands['LF'].n_wrong_sign} and {self.bands['HF'].n_wrong_sign} "
            f"of {count(self.omega.size)} grid points); the real factorizations (ϖ_l − ω)(ϖ_l + ω) and "
            f"(ω − ϖ_h)(ω + ϖ_h), those of τ in the proof of Theorem 1, agree with the weight to "
            f"{self.max_rel_diff_corrected:.1e} relative. The MF product is the weight itself, "
            f"but its claim > 0 fails on the mirror interval [−ϖ_2, −ϖ_1] ({mf.n_claim_fails} of "
            f"{mf.n_in_band} in-band points)."),))


def prop1_weight_check(varpi_l: float = 1.0, varpi_1: float = 1.0, varpi_2: float = 10.0,
                       varpi_h: float = 10.0, omega: ArrayLike | None = None) -> Prop1WeightCheck:
    """The factorizations printed in the proof of Proposition 1, against the weight.

    The proof writes the weight ``w(ω) = [(jω)* 1] Ψ [(jω)* 1]*`` as
    ``(ϖ_l − jω)(ϖ_l + jω)`` (LF), ``(ω − ϖ_1)(ϖ_2 − ω)`` (MF) and ``(jω − ϖ_h)(jω + ϖ_h)``
    (HF), each claimed ``> 0`` when Ω_i lies in the band. The LF product equals
    ``ϖ_l² + ω² > 0`` and the HF product ``−ω² − ϖ_h² < 0`` for every ω, while the weights
    are ``ϖ_l² − ω²`` and ``ω² − ϖ_h²``. The correct real factorizations are
    ``(ϖ_l − ω)(ϖ_l + ω)`` and ``(ω − ϖ_h)(ω + ϖ_h)``; the MF product is the weight itself.
    The proof of Theorem 1 uses the correct forms in its function τ(Ψ_i, ω_k, ω_κ).

    Parameters
    ----------
    varpi_l, varpi_1, varpi_2, varpi_h : float
        Band limits in rad/s (the paper's: 1, 1, 10, 10).
    omega : (N,) array_like, optional
        Frequencies in rad/s (default: ±[10⁻², 10³], 400 log-spaced points per sign, none on
        a band edge).

    Returns
    -------
    Prop1WeightCheck

    Notes
    -----
    The printed display stands between paper eqs. (23) and (24).

    Examples
    --------
    >>> r = prop1_weight_check()
    >>> r["LF"].n_wrong_sign, r["HF"].n_wrong_sign, r["MF"].n_wrong_sign
    (480, 320, 0)
    >>> r["MF"].n_claim_fails, r["HF"].n_claim_fails == r["HF"].n_in_band
    (80, True)
    >>> r["HF"].max_abs_diff_corrected < 1e-9 * r["HF"].max_abs_diff
    True
    """
    w = _default_grid() if omega is None else as_vector("omega", omega)
    bands = {"LF": Band.lf(varpi_l), "MF": Band.mf(varpi_1, varpi_2), "HF": Band.hf(varpi_h)}
    jw = 1j * w
    lo, hi = bands["LF"].upper, bands["HF"].lower
    w1, w2 = bands["MF"].lower, bands["MF"].upper
    printed = {"LF": ((lo - jw) * (lo + jw)).real, "MF": (w - w1) * (w2 - w),
               "HF": ((jw - hi) * (jw + hi)).real}
    corrected = {"LF": (lo - w) * (lo + w), "MF": (w - w1) * (w2 - w), "HF": (w - hi) * (w + hi)}
    # τ(Ψ_i, ω_k, ω_κ) as printed in the proof of Theorem 1, at ω_k = ω_κ = ω.
    tau = {"LF": (lo - w) * (w + lo), "MF": (w2 - w) * (w - w1), "HF": (w - hi) * (w + hi)}
    out = {}
    for kind, band in bands.items():
        weight = band.weight(w)
        inside = band.contains(w)
        p = printed[kind]
        out[kind] = Factorization(
            kind, weight, p, corrected[kind], tau[kind], inside,
            n_wrong_sign=int(np.sum(np.sign(p) * np.sign(weight) < 0)),
            n_claim_fails=int(np.sum(inside & ~(p > 0))),
            n_in_band_negative=int(np.sum(inside & (w < 0))),
            max_abs_diff=float(np.max(np.abs(p - weight))),
            max_abs_diff_corrected=float(np.max(np.abs(corrected[kind] - weight))),
            max_abs_diff_tau=float(np.max(np.abs(tau[kind] - weight))))
    return Prop1WeightCheck(w, out)
