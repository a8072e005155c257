"""The paper's data (package data, read through importlib.resources) and its setup:
the aircraft, the printed gains, bands and Q's, the disturbances, the FDSC modes, our choices.
"""

import json
from importlib import resources

import numpy as np

from .._validation import as_choice, as_finite_real, as_positive
from ..bands import band_from_spec
from ..plant import Plant
from ..signals import Piecewise, Sinusoids
from ..simulate import simulate
from ..switching import DEFAULT_GAMMA_TOL, design_q
from .names import CONTROLLER_GAINS, CONTROLLERS

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
    """
    d = paper_data("aircraft")
    names = {k: d[k]["value"] for k in ("state_names", "input_names", "output_names")}
    return Plant(*(np.array(d[k]["value"]) for k in ("A", "B1", "B2", "C", "D1", "D2")),
                 names=names)


def paper_gains():
    """The printed gains ``{"K_f1": K, "K_f2": K, "K_f3": K, "K_e": K}`` (arrays (2, 2))."""
    d = paper_data("controllers")
    return {k: np.array(v["value"]) for k, v in d.items() if k.startswith("K_")}


def paper_bands():
    """The paper's bands ``{"LF": Ω_1, "MF": Ω_2, "HF": Ω_3, "EF": Ω_e}`` as :class:`Band`."""
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
    """``d_l(t) = sin 0.1t + sin 0.2t + sin 0.3t`` (eq. d-l)."""
    return _paper_sinusoids("lf_disturbance")


def hf_disturbance():
    """``d_h(t) = sin 100t + sin 200t + sin 300t`` (eq. d-h)."""
    return _paper_sinusoids("hf_disturbance")


#: The paper's stationary disturbances: eq. (56) (LF) and eq. (57) (HF).
PAPER_DISTURBANCES = ("LF", "HF")


def paper_disturbance(kind):
    """The paper's LF (eq. (56)) or HF (eq. (57)) disturbance by name.

    Examples
    --------
    >>> paper_disturbance("HF").frequencies
    array([100., 200., 300.])
    """
    as_choice("kind", kind, PAPER_DISTURBANCES)
    return lf_disturbance() if kind == "LF" else hf_disturbance()


def mixed_disturbance(rho_p):
    """``d = d_h + ρ_p d_l`` (paper Fig. 7).

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
    """
    T = as_positive("T", T)
    rho_t = as_finite_real("rho_t", rho_t)
    if rho_t < 0:
        raise ValueError(f"rho_t must be >= 0, but found {rho_t}")
    rho_p_star = as_finite_real("rho_p_star", rho_p_star)
    hf, lf = hf_disturbance(), lf_disturbance().scaled(rho_p_star)
    return Piecewise([0.0, T, T + rho_t * T, 2 * T + rho_t * T], (hf, lf, hf))


def paper_modes():
    """The two FDSC modes of Sec. IV: closed loops, bands and Q's.

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
    """Q_1, Q_2 from the paper Remark 4 design on the paper's modes (in-band mode: HF, index 1)."""
    pm = paper_modes()
    return design_q(pm["modes"], pm["bands"], 1, gamma_tol=gamma_tol)


def run_controller(name, d, t, *, Q=None, law="previous", x0=None):
    """Simulate one of :data:`CONTROLLERS` (FDSC with the given Q's, default the paper's).

    Parameters
    ----------
    name : {"PassC-EF", "PassC-LF", "PassC-HF", "FDSC"}
    d : Sinusoids or Piecewise
    t : (N,) array_like
        Uniform grid.
    Q : list of (2, 2) array_like, optional
        Q's of the FDSC law (default the paper's).
    law : {"previous", "candidate"}
    x0 : (2,) array_like, optional

    Returns
    -------
    SimResult
    """
    as_choice("name", name, CONTROLLERS)
    plant, gains = aircraft(), paper_gains()
    if name == "FDSC":
        pm = paper_modes()
        return simulate(pm["modes"], d, t, law_bands=pm["bands"], law_Q=pm["Q"] if Q is None else Q,
                        law=law, x0=x0)
    return simulate(plant.closed_loop(gains[CONTROLLER_GAINS[name]]), d, t, x0=x0)
