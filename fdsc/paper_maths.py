"""The paper's mathematics, checked: numbers that decide statements of the text.

Each function returns plain data that a chapter glues into its prose:

- :func:`prop1_weight_check`: the factorizations of the frequency weight
  ``[(jω)* 1] Ψ [(jω)* 1]*`` printed in the proof of Proposition 1, against the weight itself;
- :func:`truncated_spectrum` and :func:`out_of_band_fraction`: the energy that a causal,
  finitely long sum of sinusoids has outside a band (Paley–Wiener: never zero);
- :func:`paley_wiener_table`: that fraction for the paper's LF and HF test signals;
- :func:`windowed_tone_ratio` and :func:`in_band_gamma_slip`: the energy ratio of an in-band
  tone against γ and γ² (the γ-for-γ² slip of Lemma 1, (P.1), (P.2) and Remark 5);
- :func:`autonomous_lyapunov_jumps`: the jumps of V = xᵀ P^s_σ x at the switches of the
  autonomous (d = 0) switched loop, the setting of Theorem 1 statement (1).

Equation numbers are those of the compiled paper.
"""

import math

import numpy as np
from scipy.signal import lsim

from ._validation import as_count, as_positive, as_vector, check_type
from .bands import Band
from .frequency import band_peak, sigma_max
from .plant import LTISystem, aircraft, paper_bands, paper_gains
from .selectiveness import paper_modes
from .signals import Sinusoids, hf_disturbance, lf_disturbance
from .simulate import simulate, time_grid
from .switching import Theorem1Result

__all__ = [
    "prop1_weight_check",
    "truncated_spectrum",
    "truncated_energy",
    "out_of_band_fraction",
    "paley_wiener_table",
    "windowed_tone_ratio",
    "in_band_gamma_slip",
    "autonomous_lyapunov_jumps",
    "PALEY_WIENER_HORIZONS",
]

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


def windowed_tone_ratio(system, omega0, *, tau, dt):
    """Energy ratio ``∫zᵀz / ∫d²`` of the windowed tone ``d = exp(−((t−4τ)/τ)²) sin(ω0 t)``.

    The tone's spectrum is concentrated within about ``2/τ`` of ω0, so for slow windows the
    ratio tends to ``σ_max(G(jω0))²`` (one input). Simulated from rest over ``[0, 8τ]`` with
    ``scipy.signal.lsim`` (first-order hold, exact for piecewise-linear input).

    Parameters
    ----------
    system : LTISystem
        Stable closed loop with one input.
    omega0, tau, dt : float
        Tone frequency (rad/s), window width (s), sample step (s).

    Returns
    -------
    dict
        ``ratio`` (simulated), ``gain_sq`` (σ_max(G(jω0))²).

    Examples
    --------
    >>> sys = LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]])  # 1/(s+1)
    >>> r = windowed_tone_ratio(sys, 1.0, tau=60.0, dt=0.05)
    >>> round(r["gain_sq"], 6), abs(r["ratio"] - 0.5) < 1e-3
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
    return {"ratio": ratio, "gain_sq": float(sigma_max(system, [omega0])[0] ** 2)}


def in_band_gamma_slip(gain="K_f3", kind="HF", omega0=10.5, *, tau=30.0, dt=5e-3):
    """γ against γ² in the paper's own in-band setting: a tone inside Ω_3 under K_f3.

    (P.1) eq. (14), (P.2) eq. (15) and Remark 5 eq. (54) compare an energy ratio with an
    (unsquared) gain. This evaluates the energy ratio of a slowly windowed tone inside the
    band against the band peak γ of σ_max and against γ².

    Returns
    -------
    dict
        ``gain, kind, omega0, tau, gamma`` (band peak of the printed gain), ``gamma_sq``,
        ``gain_sq`` (σ_max(G(jω0))²), ``ratio`` (simulated), ``exceeds_gamma``,
        ``below_gamma_sq``.

    Examples
    --------
    >>> r = in_band_gamma_slip()
    >>> r["exceeds_gamma"], r["below_gamma_sq"]
    (True, True)
    """
    band = paper_bands()[kind]
    if not band.contains(omega0):
        raise ValueError(f"omega0 must lie in the {band.label} band, but found {omega0} rad/s")
    cl = aircraft().closed_loop(paper_gains()[gain])
    gamma = band_peak(cl, band).gamma
    r = windowed_tone_ratio(cl, omega0, tau=tau, dt=dt)
    return {"gain": gain, "kind": kind, "omega0": float(omega0), "tau": float(tau), "gamma": gamma,
            "gamma_sq": gamma**2, "gain_sq": r["gain_sq"], "ratio": r["ratio"],
            "exceeds_gamma": r["ratio"] > gamma, "below_gamma_sq": r["ratio"] < gamma**2}


def autonomous_lyapunov_jumps(result, n_initial=40, *, horizon=60.0, dt=1e-3, seed=3, Q=None):
    """Jumps of ``V = xᵀ P^s_σ x`` at the switches of the autonomous switched loop (d = 0).

    Theorem 1 statement (1) is about d = 0; its proof differentiates V between switches and
    never compares V across a switch. The runs start from the same random initial states as
    :func:`fdsc.scenarios.autonomous_stability` (same ``seed``).

    Parameters
    ----------
    result : Theorem1Result
        Supplies P^s_1, P^s_2 and (unless ``Q`` is given) the law's Q's.
    n_initial : int
        Number of initial states (standard normal).
    horizon, dt : float
        Length and step of each run in s.
    seed : int
    Q : list of (n, n) array_like, optional
        Q's of the switching law.

    Returns
    -------
    dict
        ``ratios`` V(t⁺)/V(t⁻) at all switches of all runs, ``max_ratio``, ``frac_up`` (share
        of switches at which V increases), ``n_switches``, ``n_runs``, ``horizon``,
        ``final_ratio`` (‖x(T)‖/‖x(0)‖ per run).

    Examples
    --------
    >>> from fdsc.scenarios import our_q
    >>> j = autonomous_lyapunov_jumps(our_q(), 3, horizon=5.0)
    >>> j["n_runs"], bool(j["max_ratio"] > 1)
    (3, True)
    """
    check_type("result", result, Theorem1Result)
    n_initial = as_count("n_initial", n_initial)
    pm = paper_modes()
    Q = result.Q if Q is None else Q
    Ps = np.array(result.Ps)
    rng = np.random.default_rng(seed)
    t = time_grid(horizon, dt)
    zero = Sinusoids([0.0], [1.0])
    ratios, final = [], []
    for _ in range(n_initial):
        x0 = rng.standard_normal(Ps.shape[1])
        sim = simulate(pm["modes"], zero, t, x0=x0, law_bands=pm["bands"], law_Q=Q)
        k = np.flatnonzero(np.diff(sim.sigma)) + 1
        x = sim.x[k]
        before = np.einsum("ki,kij,kj->k", x, Ps[sim.sigma[k - 1]], x)
        after = np.einsum("ki,kij,kj->k", x, Ps[sim.sigma[k]], x)
        ratios.append(after / before)
        final.append(float(np.linalg.norm(sim.x[-1]) / np.linalg.norm(x0)))
    ratios = np.concatenate(ratios)
    return {"ratios": ratios, "max_ratio": float(ratios.max()) if ratios.size else 1.0,
            "frac_up": float(np.mean(ratios > 1)) if ratios.size else 0.0,
            "n_switches": int(ratios.size), "n_runs": n_initial, "horizon": float(horizon),
            "final_ratio": np.array(final)}
