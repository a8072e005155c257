"""The printed inputs: their record entries, and their transcription checked against the paper's LaTeX."""

import re
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_array_equal

from fdsc.paper.shared import inputs
from fdsc.paper.shared.data import (
    aircraft,
    mixed_disturbance,
    paper_bands,
    paper_data,
    paper_fdsc,
    paper_gains,
    piecewise_disturbance,
)
from fdsc.paper.shared.inputs import INPUT_IDS, PIECEWISE_HORIZON_PRINTED, passc_hf_scale, record_part
from fdsc.paper.shared.verdict import VERDICTS

TEX = Path(__file__).resolve().parents[3] / "shared" / "paper" / "fdsc-paper.tex"


@pytest.fixture(scope="module")
def entries():
    return {e["id"]: e for e in record_part().entries}


def test_the_input_entries_use_what_is_printed(entries):
    assert tuple(entries) == INPUT_IDS
    for e in entries.values():
        assert e["verdict"] == "input" and e["verdict"] in VERDICTS, e["id"]
        assert e["paper"] == e["recomputed"], e["id"]


def test_the_model_entry_is_the_plant_the_code_simulates(entries):
    p, model = aircraft(), entries["model"]["paper"]
    for printed, used in (("A_long", p.A), ("B^u_long", p.B2), ("B^w_long", p.B1), ("C_long", p.C),
                          ("D_long", p.D2)):
        assert_array_equal(model[printed], used, err_msg=printed)
    assert_array_equal(p.D1, np.zeros((3, 1)))


def test_the_bands_disturbances_and_configuration_entries(entries):
    b = paper_bands()
    assert entries["bands"]["paper"] == {"LF": {"w_l": b["LF"].upper},
                                         "MF": {"w_1": b["MF"].lower, "w_2": b["MF"].upper},
                                         "HF": {"w_h": b["HF"].lower}}
    assert entries["bands"]["crossovers_rad_s"] == [1.0, 10.0]
    d = entries["disturbances"]["paper"]
    # the mixed disturbance of paper Fig. 7 is built from exactly these tones
    assert_array_equal(np.sort(mixed_disturbance(0.2).frequencies),
                       sorted(d["d_l"]["frequencies"] + d["d_h"]["frequencies"]))
    ctrl, gains = paper_fdsc("paper"), paper_gains()
    cfg = entries["fdsc_configuration"]["paper"]
    assert_array_equal(ctrl.gains[0], gains[cfg["K_1"]])
    assert_array_equal(ctrl.gains[1], gains[cfg["K_2"]])
    assert cfg["in_band"] == "HF" and cfg["bands"] == ["LF", "HF"]


def test_the_sweep_parameters_are_those_the_sweeps_read(entries):
    sim, sp = paper_data("simulation"), entries["sweep_parameters"]["paper"]
    assert sp["rho_p_range"] == sim["rho_p_range"]["value"] == [0.0, 0.5]
    assert (sp["mixed_horizon"], sp["T"], sp["rho_p_star"]) == (500.0, 500.0, 0.1)
    # paper Fig. 8's caption: t ∈ [0, 1000 + 500 ρ_t], the end of eq. (58)'s last segment
    for rho_t in (0.0, 0.3, 0.5):
        end = piecewise_disturbance(sp["T"], rho_t, sp["rho_p_star"]).breaks[-1]
        assert end == PIECEWISE_HORIZON_PRINTED["constant"] + PIECEWISE_HORIZON_PRINTED["per_rho_t"] * rho_t
    assert entries["plot_scalings"]["paper"] == {"mixed": 0.0002, "piecewise": 0.01}


def test_an_input_not_used_as_printed_is_not_an_input(monkeypatch):
    plant = aircraft()
    changed = type(plant)(plant.A + 1e-3, plant.B1, plant.B2, plant.C, plant.D1, plant.D2)
    monkeypatch.setattr(inputs, "aircraft", lambda: changed)
    e = record_part().entries[0]
    assert e["id"] == "model" and e["verdict"] == "differs" and e["note"].startswith("NOT used as printed")


def test_the_scalings_are_found_under_their_former_names(monkeypatch):
    sim = paper_data("simulation")
    old = {k: v for k, v in sim.items() if not k.endswith("_passc_hf_scale")}
    old["fig6_passc_hf_scale"], old["fig7_passc_hf_scale"] = {"value": 0.0002}, {"value": 0.01}
    monkeypatch.setattr(inputs, "paper_data", lambda name: old)
    assert (passc_hf_scale("mixed"), passc_hf_scale("piecewise")) == (0.0002, 0.01)
    del old["fig7_passc_hf_scale"]
    with pytest.raises(KeyError, match="piecewise_passc_hf_scale"):
        passc_hf_scale("piecewise")


def test_passc_hf_scale_rejects_an_unknown_sweep():
    with pytest.raises(ValueError, match="sweep must be one of .*'mixed'.*found 'fig7'"):
        passc_hf_scale("fig7")


# -- the transcription against the paper's LaTeX source ---------------------------------------------

_NUMBER = r"[-+]?\d+(?:\.\d+)?"


def _between(tex, start, end):
    """The text from ``start`` to the next ``end`` (both regexes), or ''."""
    m = re.search(start + r"(.*?)" + end, tex, re.S)
    return m.group(1) if m else ""


def _pmat(tex, name):
    """The first ``pmat`` block after ``<name>=`` as a list of rows of floats (None if absent)."""
    body = _between(tex, re.escape(name) + r"\s*=", r"\\end\{pmat\}")
    if r"\begin{pmat}" not in body:
        return None
    body = re.sub(r"\{\\kern\s*[\d.]+pt\}", "", body.split(r"\begin{pmat}[{.}]", 1)[1])
    return [[float(c) for c in row.split("&")] for row in body.split(r"\cr") if row.strip()]


def _tones(tex, label):
    """``{"amplitudes", "frequencies"}`` of the sum of sines in the equation ``label``."""
    eq = _between(tex, r"\\label\{" + label + r"\}", r"\\end\{equation\}")
    found = re.findall(r"(\d+(?:\.\d+)?)?\s*\\sin\((\d+(?:\.\d+)?)t\)", eq)
    return {"amplitudes": [float(a or 1) for a, _ in found], "frequencies": [float(w) for _, w in found]}


def _numbers(pattern, text):
    m = re.search(pattern, text)
    return [float(x) for x in m.groups()] if m else None


def _figure_number(tex, label):
    """The compiled number of the figure holding ``label`` (figure environments before it, + 0)."""
    i = tex.find(r"\label{" + label + "}")
    return len(re.findall(r"\\begin\{figure\*?\}", tex[:i])) if i >= 0 else None


def transcription(tex):
    """What the paper's LaTeX prints for each input, in the form of the data files."""
    bands = _between(tex, r"\\label\{configuration\}", r"\\end\{equation\}")
    fig7 = _between(tex, r"\\label\{power-para\}", r"\\label\{d-piece\}")
    mixed = _between(tex, r"d_h\(t\)\+\\rho_\{p\} d_l\(t\)", r"\\label\{power-para\}")
    piecewise = _between(tex, r"\\label\{d-piece\}", r"\\section\{Conclusion\}")
    fig8 = piecewise.split(r"\label{D-LF}", 1)[-1] if r"\label{D-LF}" in piecewise else ""
    lf = _numbers(r"\\Omega_\{1\}:\s*\((" + _NUMBER + r"),\s*(" + _NUMBER + r")\)", bands)
    mf = _numbers(r"\\Omega_\{2\}:\s*\(-(\d+),\s*-(\d+)\]\s*\\cup\s*\[(\d+),\s*(\d+)\)", bands)
    hf = _numbers(r"\\Omega_\{3\}:\s*\(-\\infty,\s*-(\d+)\]\s*\\cup\s*\[(\d+),\s*\+\\infty\)", bands)
    scale7 = _numbers(r"\$1/(\d+)\$ energy value of PassC-HF", fig7)
    scale8 = _numbers(r"\$1/(\d+)\$ of the energy value of PassC-HF", fig8)
    horizon8 = _numbers(r"t\\in \[0,(\d+)\+(\d+)\\rho_t\]", piecewise)
    config = re.search(r"setting \$K_1=K_\{f_(\d)\}\$ and \$K_2=K_\{f_(\d)\}\$", tex)
    return {
        "A": _pmat(tex, "A_{long}"), "B2": _pmat(tex, "B^u_{long}"), "B1": _pmat(tex, "B^w_{long}"),
        "C": _pmat(tex, "C_{long}"), "D2": _pmat(tex, "D_{long}"),
        # LF (-w_l, w_l), MF (-w_2, -w_1] ∪ [w_1, w_2), HF (-inf, -w_h] ∪ [w_h, inf): each symmetric
        "LF": {"w_l": lf[1]} if lf and lf[0] == -lf[1] else None,
        "MF": {"w_1": mf[2], "w_2": mf[3]} if mf and mf[:2] == mf[:1:-1] else None,
        "HF": {"w_h": hf[1]} if hf and hf[0] == hf[1] else None,
        "crossovers": [10.0 ** x for x in
                       _numbers(r"\$10\^(\d), 10\^(\d)\$ as the crossover frequencies", tex) or []],
        "lf_disturbance": _tones(tex, "d-l"), "hf_disturbance": _tones(tex, "d-h"),
        "mixed_horizon": _numbers(r"t\\in \[0,(\d+)\]", mixed),
        "rho_p_range": _numbers(r"\\rho_\{p\}\$ over \[(" + _NUMBER + r"), (" + _NUMBER + r")\]", mixed),
        "piecewise_T": _numbers(r"\$T=(\d+)\$", piecewise),
        "piecewise_rho_p_star": _numbers(r"\$\\rho_p\^\*=(" + _NUMBER + r")\$", piecewise),
        "rho_t_range": _numbers(r"\$\\rho_t\\in\[(" + _NUMBER + r"),(" + _NUMBER + r")\]", piecewise),
        # eq. (58)'s segments end at 2T + rho_t T, the horizon the caption prints
        "piecewise_segments": bool(re.search(r"\[T\+\\rho_tT,2T\+\\rho_tT\)", piecewise)),
        "piecewise_horizon": {"constant": horizon8[0], "per_rho_t": horizon8[1]} if horizon8 else None,
        "scales": [1 / scale7[0] if scale7 else None, 1 / scale8[0] if scale8 else None],
        "figures": [_figure_number(tex, "power-para"), _figure_number(tex, "D-LF")],
        "modes": [f"K_f{config.group(1)}", f"K_f{config.group(2)}"] if config else None,
    }


def expected_transcription():
    """The same items from the data files (and the module constants) the code uses."""
    a, sim = paper_data("aircraft"), paper_data("simulation")
    bands = {s["kind"]: {k: v for k, v in s.items() if k != "kind"} for s in a["bands"]["value"].values()}
    return {
        **{k: a[k]["value"] for k in ("A", "B2", "B1", "C", "D2")}, **bands,
        "crossovers": sorted({v for b in bands.values() for v in b.values()}),
        **{k: sim[k]["value"] for k in ("lf_disturbance", "hf_disturbance")},
        "mixed_horizon": [sim["mixed_horizon"]["value"]], "rho_p_range": sim["rho_p_range"]["value"],
        "piecewise_T": [sim["piecewise_T"]["value"]],
        "piecewise_rho_p_star": [sim["piecewise_rho_p_star"]["value"]],
        "rho_t_range": sim["rho_t_range"]["value"], "piecewise_segments": True,
        "piecewise_horizon": PIECEWISE_HORIZON_PRINTED,
        "scales": [passc_hf_scale("mixed"), passc_hf_scale("piecewise")],
        "figures": [7, 8],  # the sweeps are paper Figs. 7 and 8 of the compiled numbering
        "modes": paper_data("switching")["modes"]["value"],
    }


def mismatches(tex):
    """The items whose transcription differs from the paper's LaTeX (empty when all agree)."""
    found, expected = transcription(tex), expected_transcription()
    assert set(found) == set(expected)
    return sorted(k for k in expected if found[k] != expected[k])


@pytest.fixture(scope="module")
def tex():
    if not TEX.is_file():
        pytest.skip(f"the paper's LaTeX source is not at {TEX} (it lives outside the repository)")
    return TEX.read_text(encoding="utf-8")


def test_every_input_is_transcribed_as_printed(tex):
    found = transcription(tex)
    # guards against a pattern that finds nothing and a data file that holds nothing alike
    assert found["A"] == [[-1.175, 0.9871], [-8.458, -0.8776]] and found["scales"] == [1 / 5000, 1 / 100]
    assert mismatches(tex) == []


@pytest.mark.parametrize(("printed", "mistyped", "item"), [
    ("-1.175 &{\\kern 2pt}0.9871", "-1.157 &{\\kern 2pt}0.9871", "A"),
    ("-19.29 &{\\kern 2pt}-3.803", "-19.29 &{\\kern 2pt}-3.830", "B2"),
    ("1\\cr\n\t\t4\\cr", "1\\cr\n\t\t2\\cr", "B1"),
    ("0 &{\\kern 2pt}4\\cr", "0 &{\\kern 2pt}2\\cr", "C"),
    ("0 &{\\kern 2pt}2\\cr", "0 &{\\kern 2pt}3\\cr", "D2"),
    ("(-10, -1] \\cup [1, 10)", "(-10, -1] \\cup [1, 100)", "MF"),
    ("\\Omega_{1}: (-1, 1)", "\\Omega_{1}: (-1, 2)", "LF"),
    ("\\sin(200t)+\\sin(300t)\n", "\\sin(20t)+\\sin(300t)\n", "hf_disturbance"),
    ("\\sin(0.1t)+\\sin(0.2t)+\\sin(0.3t)\n", "\\sin(0.1t)+2\\sin(0.2t)+\\sin(0.3t)\n", "lf_disturbance"),
    ("$T=500$", "$T=50$", "piecewise_T"),
    ("$\\rho_p^*=0.1$", "$\\rho_p^*=0.01$", "piecewise_rho_p_star"),
    ("over [0, 0.5]", "over [0, 0.25]", "rho_p_range"),
    ("$\\rho_t\\in[0,0.5]$", "$\\rho_t\\in[0,0.4]$", "rho_t_range"),
    ("t\\in [0,1000+500\\rho_t]", "t\\in [0,1000+50\\rho_t]", "piecewise_horizon"),
    ("$1/5000$", "$1/500$", "scales"),
    ("$1/100$", "$1/10$", "scales"),
    ("$K_2=K_{f_3}$", "$K_2=K_{f_2}$", "modes"),
])
def test_a_mistyped_number_is_caught(tex, printed, mistyped, item):
    assert printed in tex, f"the test's pattern {printed!r} is not in the paper"
    assert mismatches(tex.replace(printed, mistyped, 1)) == [item]
