"""Chapter 'frequency_ranges': Sec. II-A, Definitions 1-3 (Ψ of the three ranges, the weight's
sign, Paley–Wiener, dominance degrees) and the factorizations printed in Proposition 1's proof.
"""

import math

import numpy as np

from .._validation import as_positive, as_vector, check_type
from ..bands import Band
from ..signals import Sinusoids, dominance_degree, localized_dominance
from .data import (
    hf_disturbance,
    lf_disturbance,
    mixed_disturbance,
    paper_bands,
    paper_data,
    piecewise_disturbance,
)

__all__ = [
    "psi_table",
    "psi_weights",
    "dominance_vs_rho",
    "localized_dominance_piecewise",
    "PALEY_WIENER_HORIZONS",
    "prop1_weight_check",
    "truncated_spectrum",
    "truncated_energy",
    "out_of_band_fraction",
    "paley_wiener_table",
]


def psi_table():
    """Ψ of each of the paper's bands (Ω_1, Ω_2, Ω_3 of eq. configuration) as nested lists."""
    out = {}
    for kind, band in paper_bands().items():
        if kind == "EF":
            continue
        psi = band.psi
        out[kind] = {"label": band.label, "psi": psi.tolist(), "complex": band.is_complex}
    return out


def psi_weights(omega=None):
    """The weight ``[jω;1]* Ψ [jω;1]`` and its real-signal part for the paper's three bands.

    Returns
    -------
    dict
        ``{"omega": (k,), "LF": {"weight": (k,), "real_weight": (k,), "lower", "upper"}, ...}``
        over positive and negative ω.
    """
    if omega is None:
        pos = np.geomspace(1e-2, 1e3, 600)
        omega = np.concatenate([-pos[::-1], pos])
    omega = np.asarray(omega, dtype=float)
    out = {"omega": omega}
    for kind, band in paper_bands().items():
        if kind == "EF":
            continue
        out[kind] = {"weight": band.weight(omega), "real_weight": band.real_weight(omega),
                     "lower": band.lower, "upper": band.upper, "label": band.label}
    return out


def dominance_vs_rho(rhos, *, horizon=500.0, dt=2e-3):
    """α(Ω_3) of the mixed disturbance ``d_h + ρ_p d_l`` (paper Fig. 7): exact and by FFT.

    Parameters
    ----------
    rhos : (k,) array_like
        Values of ρ_p.
    horizon, dt : float
        Record used by the FFT estimate (the paper's t ∈ [0, 500]).
    """
    hf = paper_bands()["HF"]
    t = np.arange(0.0, horizon, dt)
    exact, fft = [], []
    for rho in np.asarray(rhos, dtype=float):
        d = mixed_disturbance(rho)
        exact.append(d.dominance(hf))
        fft.append(dominance_degree(d(t), dt, hf))
    return {"rho_p": np.asarray(rhos, dtype=float), "exact": np.array(exact),
            "fft": np.array(fft), "horizon": horizon, "dt": dt}


def localized_dominance_piecewise(rho_t=0.2, *, T=None, window_length=60.0, hop=5.0, dt=2e-3):
    """α(Ω_1, T_l) and α(Ω_3, T_l) along the piecewise disturbance of paper Fig. 8 (eq. (58)).

    Parameters
    ----------
    rho_t : float
        Relative length of the LF segment.
    T : float, optional
        Length of the first HF segment in s (default the paper's T = 500); pass the T of the run
        the result is drawn beside.
    window_length, hop, dt : float
        STFT window, hop and sampling step in s.

    Returns
    -------
    dict
        ``breaks``, ``rho_t``, ``T``, ``window_length`` and per band ``{"t", "alpha"}``.
    """
    sim = paper_data("simulation")
    T = sim["piecewise_T"]["value"] if T is None else T
    d = piecewise_disturbance(T, rho_t, sim["piecewise_rho_p_star"]["value"])
    t = np.arange(0.0, d.breaks[-1], dt)
    x = d(t)
    bands = paper_bands()
    out = {"breaks": d.breaks, "rho_t": rho_t, "T": T}
    for kind in ("LF", "HF"):
        loc = localized_dominance(x, dt, bands[kind], window_length=window_length, hop=hop)
        out[kind] = {"t": loc.t, "alpha": loc.alpha}
    out["window_length"] = window_length
    return out


#: Truncation lengths T (s) of the paper's test signals in :func:`paley_wiener_table`.
PALEY_WIENER_HORIZONS = (50.0, 500.0, 5000.0)


#: Gauss–Legendre nodes per panel in :func:`out_of_band_fraction`.
_GL_NODES = 16


#: Panels per half period 2π/T of the spectrum's oscillation in ω.
_PANELS_PER_HALF_PERIOD = 2


def _default_grid():
    # 400 points per sign: the log step 5/399 puts no grid point on a band edge (1 or 10 rad/s),
    # where the weight is zero and its sign undefined.
    pos = np.geomspace(1e-2, 1e3, 400)
    return np.concatenate([-pos[::-1], pos])


def prop1_weight_check(varpi_l=1.0, varpi_1=1.0, varpi_2=10.0, varpi_h=10.0, omega=None):
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
    dict
        ``omega`` and, per kind ``"LF"``, ``"MF"``, ``"HF"``, a dict with ``weight`` (from
        :meth:`fdsc.Band.weight`), ``printed``, ``corrected``, ``tau_diagonal`` (τ(ω, ω) of
        the proof of Theorem 1), ``in_band`` (mask of the two-sided band), ``n_wrong_sign``
        (points where printed product and weight have opposite signs), ``n_claim_fails``
        (in-band points where the printed product is not > 0), ``max_abs_diff`` (printed −
        weight), ``max_abs_diff_corrected`` and ``max_abs_diff_tau``.

    Examples
    --------
    >>> r = prop1_weight_check()
    >>> r["LF"]["n_wrong_sign"], r["HF"]["n_wrong_sign"], r["MF"]["n_wrong_sign"]
    (480, 320, 0)
    >>> r["MF"]["n_claim_fails"], r["HF"]["n_claim_fails"] == int(r["HF"]["in_band"].sum())
    (80, True)
    >>> float(r["HF"]["max_abs_diff_corrected"]) < 1e-9 * float(r["HF"]["max_abs_diff"])
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
    out = {"omega": w}
    for kind, band in bands.items():
        weight = band.weight(w)
        inside = band.contains(w)
        p = printed[kind]
        out[kind] = {
            "weight": weight, "printed": p, "corrected": corrected[kind], "tau_diagonal": tau[kind],
            "in_band": inside,
            "n_wrong_sign": int(np.sum(np.sign(p) * np.sign(weight) < 0)),
            "n_claim_fails": int(np.sum(inside & ~(p > 0))),
            "max_abs_diff": float(np.max(np.abs(p - weight))),
            "max_abs_diff_corrected": float(np.max(np.abs(corrected[kind] - weight))),
            "max_abs_diff_tau": float(np.max(np.abs(tau[kind] - weight))),
        }
    return out


def _check_sinusoids(d):
    check_type("d", d, Sinusoids)
    if np.any(d.phases != 0):
        raise ValueError("d must have zero phases (sums of sines, as in the paper), "
                         f"but found phases {d.phases.tolist()}")


def _window_integral(nu, T):
    # ∫_0^T exp(jνt) dt, written with sinc so that ν = 0 needs no special case.
    return T * np.exp(0.5j * nu * T) * np.sinc(nu * T / (2.0 * np.pi))


def truncated_spectrum(d, T, omega):
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


def truncated_energy(d, T):
    """``∫_0^T d(t)² dt`` in closed form for a sum of sines ``d = Σ a_k sin(ω_k t)``.

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


def out_of_band_fraction(d, T, band):
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
    ValueError
        If ``band`` is not LF or HF.

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


def paley_wiener_table(horizons=PALEY_WIENER_HORIZONS):
    """Out-of-band energy share of the paper's test signals truncated to ``[0, T]``.

    The LF signal of eq. (56) against Ω_1 and the HF signal of eq. (57) against Ω_3.

    Returns
    -------
    list of dict
        ``signal, band, T, fraction_out``, one row per signal and T.

    Examples
    --------
    >>> rows = paley_wiener_table((100.0,))
    >>> [r["signal"] for r in rows], all(r["fraction_out"] > 0 for r in rows)
    (['LF, eq. (56)', 'HF, eq. (57)'], True)
    """
    bands = paper_bands()
    rows = []
    for label, d, band in (("LF, eq. (56)", lf_disturbance(), bands["LF"]),
                           ("HF, eq. (57)", hf_disturbance(), bands["HF"])):
        for T in horizons:
            rows.append({"signal": label, "band": band.label, "T": float(T),
                         "fraction_out": out_of_band_fraction(d, T, band)})
    return rows
