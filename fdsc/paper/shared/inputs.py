"""The printed numbers that are inputs of the reproduction, in the record beside what is used.

The paper prints results (gains, bounds, Q's, energies) and inputs: the aircraft model, the
frequency ranges, the disturbances, the sweep parameters, the drawing scalings of paper Figs. 7
and 8 and the FDSC configuration. The inputs are not recomputed, they are used as printed; their
entries (verdict ``input``) set the printed value (as transcribed into ``fdsc/paper/data``) beside
the value the computations use, read back from the objects they build (the plant's matrices,
the bands' limits, the disturbances' tones, the piecewise signal's breaks, the FDSC design's
gains). ``tests/paper/test_inputs.py`` checks the transcription against the paper's LaTeX source.
"""

import numpy as np

from fdsc.paper.shared.data import (
    aircraft,
    hf_disturbance,
    lf_disturbance,
    paper_bands,
    paper_data,
    paper_fdsc,
    paper_gains,
    piecewise_disturbance,
)
from fdsc.paper.shared.results import RecordPart, entry

__all__ = [
    "INPUT_IDS",
    "PIECEWISE_HORIZON_PRINTED",
    "passc_hf_scale",
    "record_part",
]


#: The record entries of this module, in order.
INPUT_IDS = ("model", "bands", "disturbances", "sweep_parameters", "plot_scalings", "fdsc_configuration")


#: The horizon printed in the caption of paper Fig. 8, t ∈ [0, 1000 + 500 ρ_t]: its constant and
#: its coefficient of ρ_t (s). Eq. (58) gives it as 2T + ρ_t T; the data files hold T, not the caption.
PIECEWISE_HORIZON_PRINTED = {"constant": 1000.0, "per_rho_t": 500.0}


#: Keys of the drawing scalings in simulation.json, the current name first, then the former one.
_SCALE_KEYS = {"mixed": ("mixed_passc_hf_scale", "fig6_passc_hf_scale"),
               "piecewise": ("piecewise_passc_hf_scale", "fig7_passc_hf_scale")}


def passc_hf_scale(sweep):
    """The factor applied to PassC-HF's energy in the paper's drawing of a sweep.

    Parameters
    ----------
    sweep : {"mixed", "piecewise"}
        Paper Fig. 7 (ρ_p sweep, printed 1/5000) or paper Fig. 8 (ρ_t sweep, printed 1/100).

    Returns
    -------
    float

    Raises
    ------
    ValueError
        If ``sweep`` is unknown.
    KeyError
        If simulation.json holds the scaling under none of its names.

    Examples
    --------
    >>> passc_hf_scale("mixed"), passc_hf_scale("piecewise")
    (0.0002, 0.01)
    """
    if sweep not in _SCALE_KEYS:
        raise ValueError(f"sweep must be one of {tuple(_SCALE_KEYS)}, but found {sweep!r}")
    sim = paper_data("simulation")
    for key in _SCALE_KEYS[sweep]:
        if key in sim:
            return sim[key]["value"]
    raise KeyError(f"simulation.json holds none of {_SCALE_KEYS[sweep]}")


def _leaves(value, path=""):
    """``(path, leaf)`` of a nested value, in order (the structure compared by :func:`_same`)."""
    if isinstance(value, dict):
        return [leaf for k, v in value.items() for leaf in _leaves(v, f"{path}/{k}")]
    if isinstance(value, list | tuple | np.ndarray):
        return [leaf for i, v in enumerate(value) for leaf in _leaves(v, f"{path}/{i}")]
    return [(path, value)]


def _same(a, b):
    """Equal structure and equal leaves (numbers exactly, as floats; other leaves by ==)."""
    la, lb = _leaves(a), _leaves(b)
    if [k for k, _ in la] != [k for k, _ in lb]:
        return False
    for (_, x), (_, y) in zip(la, lb, strict=True):
        numbers = all(isinstance(v, int | float | np.number) and not isinstance(v, bool) for v in (x, y))
        if not (float(x) == float(y) if numbers else x == y):
            return False
    return True


def _input(id, source, paper, used, note):  # noqa: A002  (the record's key)
    """An entry with verdict ``input`` when ``used`` equals ``paper``, else ``differs``."""
    if _same(paper, used):
        return entry(id, source, paper, used, "input", note)
    return entry(id, source, paper, used, "differs",
                 "NOT used as printed: the value the code uses differs from the transcription. " + note)


def _model():
    d, plant = paper_data("aircraft"), aircraft()
    names = {"A_long": "A", "B^u_long": "B2", "B^w_long": "B1", "C_long": "C", "D_long": "D2"}
    paper = {printed: d[key]["value"] for printed, key in names.items()}
    used = {printed: getattr(plant, key).tolist() for printed, key in names.items()}
    return _input("model", "Sec. IV, the aircraft model: A_long, B^u_long, B^w_long, C_long, D_long",
                  paper, used,
                  "the plant dx/dt = A x + B1 d + B2 u, z = C x + D1 d + D2 u with A = A_long, "
                  "B1 = B^w_long, B2 = B^u_long, C = C_long, D2 = D_long as printed; D1 = 0 (not printed: "
                  "the output equation has no direct term in d)")


def _band_parameters(kind, lower, upper):
    return {"LF": {"w_l": upper}, "MF": {"w_1": lower, "w_2": upper}, "HF": {"w_h": lower}}[kind]


def _bands():
    specs = paper_data("aircraft")["bands"]["value"]
    paper = {s["kind"]: {k: v for k, v in s.items() if k != "kind"} for s in specs.values()}
    bands = paper_bands()
    used = {kind: _band_parameters(kind, bands[kind].lower, bands[kind].upper) for kind in paper}
    crossovers = sorted({v for p in paper.values() for v in p.values()})
    e = _input("bands", "Sec. IV, paper eq. (55): Ω_1 = (-1, 1), Ω_2 = (-10, -1] ∪ [1, 10), "
               "Ω_3 = (-∞, -10] ∪ [10, ∞), crossovers 10⁰ and 10¹ rad/s", paper, used,
               "the LF, MF and HF bands built from the printed crossovers (rad/s); the limits read back "
               "from the bands the code uses")
    return {**e, "crossovers_rad_s": crossovers}


def _disturbances():
    sim = paper_data("simulation")
    paper = {"d_l": sim["lf_disturbance"]["value"], "d_h": sim["hf_disturbance"]["value"]}
    used = {name: {"amplitudes": d.amplitudes.tolist(), "frequencies": d.frequencies.tolist()}
            for name, d in (("d_l", lf_disturbance()), ("d_h", hf_disturbance()))}
    return _input("disturbances", "Sec. IV, paper eqs. (56) and (57): d_l = sin 0.1t + sin 0.2t + sin 0.3t, "
                  "d_h = sin 100t + sin 200t + sin 300t", paper, used,
                  "unit amplitudes, frequencies in rad/s; the mixed (paper Fig. 7) and piecewise "
                  "(paper eq. (58), paper Fig. 8) disturbances are built from these two")


def _sweep_parameters():
    sim = paper_data("simulation")
    keys = {"rho_p_range": "rho_p_range", "mixed_horizon": "mixed_horizon", "T": "piecewise_T",
            "rho_p_star": "piecewise_rho_p_star", "rho_t_range": "rho_t_range"}
    printed = {name: sim[key]["value"] for name, key in keys.items()}
    T, rho_p_star = printed["T"], printed["rho_p_star"]
    # the horizon as the code builds it: the last break of eq. (58)'s signal, at rho_t = 0 and 1
    end = [float(piecewise_disturbance(T, r, rho_p_star).breaks[-1]) for r in (0.0, 1.0)]
    paper = {**printed, "piecewise_horizon": PIECEWISE_HORIZON_PRINTED}
    used = {**printed, "piecewise_horizon": {"constant": end[0], "per_rho_t": end[1] - end[0]}}
    return _input("sweep_parameters", "Sec. IV, paper Fig. 7 (t ∈ [0, 500], ρ_p over [0, 0.5]), paper eq. "
                  "(58) and paper Fig. 8 (T = 500, ρ*_p = 0.1, ρ_t ∈ [0, 0.5], t ∈ [0, 1000 + 500ρ_t])",
                  paper, used,
                  "the sweeps read these values from the data; the piecewise horizon is the end of "
                  "eq. (58)'s last segment, 2T + ρ_t T, whose constant and ρ_t coefficient are read back "
                  "from the signal the code builds (s)")


def _plot_scalings():
    scale = {sweep: passc_hf_scale(sweep) for sweep in _SCALE_KEYS}
    return _input("plot_scalings", "Sec. IV, text on paper Figs. 7 and 8: 1/5000 and 1/100 of the PassC-HF "
                  "energy are drawn", scale, dict(scale),
                  "a factor of the drawing only (mixed: paper Fig. 7, piecewise: paper Fig. 8), applied "
                  "as printed when the book redraws them; the record's energies are unscaled")


def _fdsc_configuration():
    sw = paper_data("switching")
    modes = sw["modes"]["value"]
    paper = {"K_1": modes[0], "K_2": modes[1], "bands": sw["mode_bands"]["value"],
             "in_band": sw["in_band"]["value"]}
    ctrl, gains = paper_fdsc("paper"), paper_gains()
    named = [[name for name, K in gains.items() if np.array_equal(K, Ki)] for Ki in ctrl.gains]
    used = {"K_1": "/".join(named[0]) or "unprinted", "K_2": "/".join(named[1]) or "unprinted",
            "bands": [b.kind for b in ctrl.bands], "in_band": ctrl.bands[ctrl.in_band].kind}
    return _input("fdsc_configuration", "Sec. IV: 'setting K_1 = K_{f_1} and K_2 = K_{f_3}', the in-band "
                  "range HF (Ω_3)", paper, used,
                  "the FDSC the simulations use: its gains identified among the printed ones, its "
                  "bands and its in-band mode")


def record_part():
    """Record entries ``model``, ``bands``, ``disturbances``, ``sweep_parameters``,
    ``plot_scalings``, ``fdsc_configuration``: the printed inputs beside what the code uses.

    Each entry's ``paper`` is the printed value as transcribed into ``fdsc/paper/data``, its
    ``recomputed`` the value read back from what the computations use; the verdict is ``input``
    when the two are equal (exactly), ``differs`` otherwise.

    Returns
    -------
    RecordPart

    Notes
    -----
    The model and the FDSC configuration are printed in Sec. IV; the bands in paper eq. (55); the
    disturbances in paper eqs. (56), (57); the sweep parameters with paper Fig. 7, in paper
    eq. (58) and in the caption of paper Fig. 8; the scalings in the text on paper Figs. 7 and 8.

    Examples
    --------
    >>> part = record_part()
    >>> [(e["id"], e["verdict"]) for e in part.entries][:2]
    [('model', 'input'), ('bands', 'input')]
    """
    return RecordPart((_model(), _bands(), _disturbances(), _sweep_parameters(), _plot_scalings(),
                       _fdsc_configuration()))
