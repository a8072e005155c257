"""The paper's data (package data, read through importlib.resources) and its setup:
the aircraft, the printed gains, bands and Q's, the disturbances, the FDSC modes, our choices.
"""

import functools
import json
from importlib import resources

import numpy as np

from fdsc._defaults import DEFAULT_GAMMA_TOL
from fdsc._validation import as_choice, as_finite_real, as_positive
from fdsc.bands import band_from_spec
from fdsc.paper.shared.names import CONTROLLER_GAINS, CONTROLLERS, FDSC_IN_BAND
from fdsc.plant import Plant
from fdsc.signals import Piecewise, Sinusoids
from fdsc.simulate import simulate

__all__ = [
    "DATA_FILES",
    "paper_data",
    "aircraft",
    "paper_gains",
    "paper_bands",
    "lf_disturbance",
    "hf_disturbance",
    "PAPER_DISTURBANCES",
    "paper_disturbance",
    "mixed_disturbance",
    "piecewise_disturbance",
    "paper_modes",
    "STATIONARY_HORIZON",
    "STATIONARY_DT",
    "our_q",
    "paper_fdsc",
    "run_controller",
]


#: The data files shipped with the paper layer (``fdsc/paper/data/*.json``).
DATA_FILES = ("aircraft", "controllers", "simulation", "switching")


def paper_data(name):
    """Load the paper's data file ``<name>.json`` (package data of :mod:`fdsc.paper`).

    Each file is a dict of ``{"value": ..., "source": ...}`` entries, the source naming where
    the paper prints the value.

    Parameters
    ----------
    name : {"aircraft", "controllers", "simulation", "switching"}
        The data file.

    Returns
    -------
    dict

    Examples
    --------
    >>> paper_data("controllers")["K_f1"]["bound"]
    0.3443
    """
    as_choice("name", name, DATA_FILES)
    path = resources.files("fdsc.paper") / "data" / f"{name}.json"
    return json.loads(path.read_text(encoding="utf-8"))


def aircraft():
    """The longitudinal aircraft model of Sec. IV (two states, two controls, one disturbance).

    Returns
    -------
    Plant
        ``A_long, B^w_long, B^u_long, C_long, D_long`` as printed, with the names of states,
        inputs and outputs.
    """
    d = paper_data("aircraft")
    names = {k: d[k]["value"] for k in ("state_names", "input_names", "output_names")}
    return Plant(*(np.array(d[k]["value"]) for k in ("A", "B1", "B2", "C", "D1", "D2")),
                 names=names)


def paper_gains():
    """The printed gains of Sec. IV.

    Returns
    -------
    dict of str to (2, 2) ndarray
        ``{"K_f1": K, "K_f2": K, "K_f3": K, "K_e": K}``.
    """
    d = paper_data("controllers")
    return {k: np.array(v["value"]) for k, v in d.items() if k.startswith("K_")}


def paper_bands():
    """The paper's frequency ranges (paper eq. (55)) and the entire range.

    Returns
    -------
    dict of str to Band
        ``{"LF": Ω_1, "MF": Ω_2, "HF": Ω_3, "EF": Ω_e}``.
    """
    specs = paper_data("aircraft")["bands"]["value"]
    bands = {}
    for spec in specs.values():
        b = band_from_spec(spec)
        bands[b.kind] = b
    bands["EF"] = band_from_spec({"kind": "EF"})
    return bands


def _paper_sinusoids(key):
    v = paper_data("simulation")[key]["value"]
    return Sinusoids(v["amplitudes"], v["frequencies"])


def lf_disturbance():
    """The LF disturbance ``d_l(t) = sin 0.1t + sin 0.2t + sin 0.3t`` (paper eq. (56)).

    Returns
    -------
    Sinusoids
    """
    return _paper_sinusoids("lf_disturbance")


def hf_disturbance():
    """The HF disturbance ``d_h(t) = sin 100t + sin 200t + sin 300t`` (paper eq. (57)).

    Returns
    -------
    Sinusoids
    """
    return _paper_sinusoids("hf_disturbance")


#: The paper's stationary disturbances: eq. (56) (LF) and eq. (57) (HF).
PAPER_DISTURBANCES = ("LF", "HF")


def paper_disturbance(kind):
    """The paper's LF (paper eq. (56)) or HF (paper eq. (57)) disturbance by name.

    Parameters
    ----------
    kind : {"LF", "HF"}
        Which disturbance.

    Returns
    -------
    Sinusoids

    Examples
    --------
    >>> paper_disturbance("HF").frequencies
    array([100., 200., 300.])
    """
    as_choice("kind", kind, PAPER_DISTURBANCES)
    return lf_disturbance() if kind == "LF" else hf_disturbance()


def mixed_disturbance(rho_p):
    """The mixed disturbance ``d = d_h + ρ_p d_l`` of paper Fig. 7.

    Parameters
    ----------
    rho_p : float
        Weight ρ_p ≥ 0 of the LF part.

    Returns
    -------
    Sinusoids

    Examples
    --------
    >>> round(mixed_disturbance(0.5).dominance(paper_bands()["HF"]), 6)   # 3 / (3 + 3 * 0.25)
    0.8
    """
    rho_p = as_finite_real("rho_p", rho_p)
    if rho_p < 0:
        raise ValueError(f"rho_p must be >= 0, but found {rho_p}")
    return hf_disturbance() + lf_disturbance().scaled(rho_p)


def piecewise_disturbance(T, rho_t, rho_p_star):
    """The piecewise disturbance (paper eq. (58)) of paper Fig. 8.

    HF on ``[0, T)``, ``ρ*_p`` times LF on ``[T, T + ρ_t T)``, HF on
    ``[T + ρ_t T, 2T + ρ_t T)``.

    Parameters
    ----------
    T : float
        Length of the first HF segment (s, > 0).
    rho_t : float
        Length of the LF segment relative to T (≥ 0).
    rho_p_star : float
        Weight ρ*_p of the LF segment.

    Returns
    -------
    Piecewise
    """
    T = as_positive("T", T)
    rho_t = as_finite_real("rho_t", rho_t)
    if rho_t < 0:
        raise ValueError(f"rho_t must be >= 0, but found {rho_t}")
    rho_p_star = as_finite_real("rho_p_star", rho_p_star)
    hf, lf = hf_disturbance(), lf_disturbance().scaled(rho_p_star)
    return Piecewise([0.0, T, T + rho_t * T, 2 * T + rho_t * T], (hf, lf, hf))


def paper_modes():
    """The two FDSC modes of Sec. IV: closed loops, bands and the printed Q's.

    Returns
    -------
    dict
        ``{"modes": [cl_1, cl_2], "bands": [LF, HF], "Q": [Q_1, Q_2], "names": [...]}``.
    """
    sw = paper_data("switching")
    plant, gains, bands = aircraft(), paper_gains(), paper_bands()
    names = sw["modes"]["value"]
    return {"modes": [plant.closed_loop(gains[k]) for k in names],
            "bands": [bands[b] for b in sw["mode_bands"]["value"]],
            "Q": [np.array(sw["Q_1"]["value"]), np.array(sw["Q_2"]["value"])], "names": names}


#: Our choice for the horizon of paper Figs. 4-6 (not printed): 500 s, the horizon of paper Fig. 7.
STATIONARY_HORIZON = 500.0


#: Our time step: 1 ms (0.3 rad per step at the fastest tone; the step is exact, the law is
#: sampled and the energy integral is Simpson's rule with a relative error of order (ω dt)⁴/180).
STATIONARY_DT = 1e-3


def our_q(gamma_tol=DEFAULT_GAMMA_TOL):
    """Our Q_1, Q_2: the paper Remark 4 design on the paper's modes (in-band mode PassC-HF).

    Parameters
    ----------
    gamma_tol : float, optional
        γ_tol of paper Remark 4 (not printed; :data:`fdsc.switching.DEFAULT_GAMMA_TOL` by default).

    Returns
    -------
    Theorem1Result
        The solution of Theorem 1's LMIs (feasible, which proves nothing on its own: see the
        chapter 'theorem1_counterexamples'); its ``Q`` are the law's weights.
    """
    return paper_fdsc(gamma_tol=gamma_tol).certificate


def paper_fdsc(Q=None, *, gamma_tol=DEFAULT_GAMMA_TOL):
    """The paper's FDSC (Sec. IV) as a design object: K_1 = K_f1 on Ω_1, K_2 = K_f3 on Ω_3.

    Parameters
    ----------
    Q : sequence of (2, 2) array_like or "paper", optional
        The law's Q's: ``"paper"`` for the printed ones, given matrices, or None to design them
        by paper Remark 4 with ``gamma_tol``. Given or printed Q's get the least γ's for which
        Theorem 1's LMIs are feasible.
    gamma_tol : float, optional
        γ_tol of paper Remark 4 (used only when ``Q`` is None).

    Returns
    -------
    FDSC
        Computed once per process for each ``Q`` (and ``gamma_tol``) and shared by later calls:
        its arrays are read-only.

    Examples
    --------
    >>> ctrl = paper_fdsc("paper")
    >>> ctrl.in_band, [b.kind for b in ctrl.bands]
    (1, ['LF', 'HF'])
    """
    if isinstance(Q, str):
        as_choice("Q", Q, ("paper",))
    key = _q_key(Q)
    try:
        hash(gamma_tol)
    except TypeError:
        key = None
    if key is None:
        return _build_paper_fdsc(Q, gamma_tol)
    return _paper_fdsc_memo(key, gamma_tol if Q is None else None)


def _q_key(Q):
    """A hashable key of ``Q`` (None, "paper" or finite real matrices), or None if it has none
    (invalid input: built uncached, so that the design's own checks raise)."""
    if Q is None or isinstance(Q, str):
        return ("design",) if Q is None else (Q,)
    if not isinstance(Q, list | tuple):
        return None
    try:
        mats = [np.asarray(q, dtype=float) for q in Q]
    except (TypeError, ValueError):
        return None
    if not all(np.all(np.isfinite(m)) for m in mats):
        return None
    return ("given",) + tuple((m.shape, m.tobytes()) for m in mats)


@functools.lru_cache(maxsize=16)
def _paper_fdsc_memo(key, gamma_tol):
    """:func:`paper_fdsc` computed once per process and per key (the chapters ask for the same
    designs dozens of times, each a Theorem 1 solve); its arrays are made read-only, so that
    the shared design cannot be changed by a caller."""
    if key == ("design",):
        ctrl = _build_paper_fdsc(None, gamma_tol)
    elif key == ("paper",):
        ctrl = _build_paper_fdsc("paper", gamma_tol)
    else:
        ctrl = _build_paper_fdsc([np.frombuffer(b).reshape(shape) for shape, b in key[1:]],
                                 DEFAULT_GAMMA_TOL)
    cert = ctrl.certificate
    for a in (*ctrl.gains, *cert.Q, *cert.P, *cert.Ps, cert.gammas):
        if isinstance(a, np.ndarray):
            a.setflags(write=False)
    return ctrl


def _build_paper_fdsc(Q, gamma_tol):
    sw = paper_data("switching")
    gains = paper_gains()
    bands = paper_bands()
    if isinstance(Q, str):
        Q = paper_modes()["Q"]
    from fdsc.design import FDSC  # imported here: loading the paper's data needs no CVXPY

    return FDSC.from_gains(aircraft(), [gains[k] for k in sw["modes"]["value"]],
                           [bands[b] for b in sw["mode_bands"]["value"]], FDSC_IN_BAND, Q=Q,
                           gamma_tol=gamma_tol)


def run_controller(name, d, t, *, Q=None, law="previous", x0=None):
    """Simulate one of :data:`CONTROLLERS` (FDSC with the given Q's, default the paper's).

    Parameters
    ----------
    name : {"PassC-EF", "PassC-LF", "PassC-HF", "FDSC"}
        The controller (paper's names).
    d : Sinusoids or Piecewise
        The disturbance.
    t : (N,) array_like
        Uniform grid.
    Q : list of (2, 2) array_like, optional
        Q's of the FDSC law (default the paper's); with Theorem 1's LMIs solved first.
    law : {"previous", "candidate"}
        How ẋ enters the law (see :data:`fdsc.simulate.LAWS`).
    x0 : (2,) array_like, optional
        Initial state (default 0).

    Returns
    -------
    SimResult
    """
    as_choice("name", name, CONTROLLERS)
    if name == "FDSC":
        return paper_fdsc("paper" if Q is None else Q).simulate(d, t, law=law, x0=x0)
    return simulate(aircraft().closed_loop(paper_gains()[CONTROLLER_GAINS[name]]), d, t, x0=x0)
