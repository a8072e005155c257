"""The book cites the paper by the numbers of its compiled LaTeX: every "paper eq. (N)",
"paper Fig. N" and "paper Remark N" in the chapters' prose exists in that numbering, and where
the prose says what a disturbance equation or a figure is, it names the right one.

The numbering is computed here from the tex (amsmath: every ``equation`` and every
``subequations`` group takes one number, ``\\[ \\]`` and starred environments none; figures in
order, subfigures sharing their parent's number; remarks in order), not typed.
"""

import json
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
TEX = ROOT.parent / "shared" / "paper" / "fdsc-paper.tex"
BOOK = ROOT / "book"

pytestmark = pytest.mark.skipif(not TEX.exists(), reason="the paper's LaTeX is not beside the repository")


def _body():
    text = TEX.read_text()
    text = re.sub(r"(?<!\\)%.*", "", text)           # comments
    return text[text.index(r"\begin{document}"):]


def equation_numbers():
    """``{label: number}`` of the paper's numbered equations, and their count."""
    labels, n, inside = {}, 0, False
    for m in re.finditer(r"\\begin\{(equation|subequations)\}|\\end\{subequations\}|\\label\{([^}]*)\}",
                         _body()):
        token = m.group(0)
        if token == r"\begin{equation}" and not inside:
            n += 1
        elif token == r"\begin{subequations}":
            inside, n = True, n + 1
        elif token == r"\end{subequations}":
            inside = False
        elif m.group(2) is not None and n:
            labels.setdefault(m.group(2), n)
    return labels, n


def figure_numbers():
    """``{label: number}`` of the paper's figures (subfigures take their parent's number)."""
    labels, n, depth = {}, 0, 0
    for m in re.finditer(r"\\begin\{figure\}|\\end\{figure\}|\\label\{([^}]*)\}", _body()):
        token = m.group(0)
        if token.startswith(r"\begin{figure}"):
            n, depth = n + 1, depth + 1
        elif token == r"\end{figure}":
            depth -= 1
        elif depth:
            labels.setdefault(m.group(1), n)
    return labels, n


def remark_count():
    return len(re.findall(r"\\begin\{remark\}", _body()))


def _prose():
    """``[(page, text)]``: the markdown of every chapter and page of the book."""
    out = []
    for path in sorted(BOOK.glob("*.ipynb")):
        cells = json.loads(path.read_text())["cells"]
        out.append((path.name, "\n".join("".join(c["source"]) for c in cells
                                          if c["cell_type"] == "markdown")))
    for path in sorted(BOOK.glob("*.md")):
        out.append((path.name, path.read_text()))
    return out


# what the prose may call each numbered disturbance and figure (its own words), and the words that
# name another one
# (the piecewise signal is made of LF and HF tones, so those words may stand before its number)
DISTURBANCE_EQS = {"d-l": ("LF",), "d-h": ("HF",), "d-piece": ("piecewise", "LF", "HF")}
_DISTURBANCE_WORDS = {"LF": r"\bLF (?:disturbance|tones|signal)", "HF": r"\bHF (?:disturbance|tones|signal)",
                      "piecewise": r"\bpiecewise\b", "mixed": r"\bmixed\b"}
FIGURE_TOPICS = {"maximum singular value": r"σ_max|sigma_max|\\sigma_\{?\\max|singular value",
                 "q-LF": r"\bLF\b", "HF": r"\bHF\b", "gamma-HF": r"L_?2|L₂",
                 "power-para": r"ρ_p|rho_p|\\rho_p|mixed", "D-LF": r"ρ_t|rho_t|\\rho_t|piecewise"}


def test_the_numbering_is_the_compiled_one():
    eqs, n_eq = equation_numbers()
    figs, n_fig = figure_numbers()
    # the numbers the book's conventions rely on (DESIGN.md): checked against the tex, so that a
    # miscount here cannot pass silently
    assert (eqs["switchinglaw"], eqs["theorem1-1"], eqs["theorem1-2"]) == (31, 33, 34)
    assert (eqs["d-l"], eqs["d-h"], eqs["d-piece"]) == (56, 57, 58) and n_eq == 58
    assert figs["fig:linkcodedata"] == 2 and figs["maximum singular value"] == 3
    assert (figs["q-LF"], figs["HF"], figs["gamma-HF"], figs["power-para"], figs["D-LF"]) == (4, 5, 6, 7, 8)
    assert n_fig == 8 and remark_count() == 7


def test_every_cited_number_exists():
    _, n_eq = equation_numbers()
    _, n_fig = figure_numbers()
    n_rem = remark_count()
    bad = []
    for page, text in _prose():
        for kind, limit in (("eq", n_eq), ("Fig", n_fig), ("Remark", n_rem)):
            pattern = {"eq": r"paper eqs?\. \((\d+)\)", "Fig": r"paper Figs?\. (\d+)",
                       "Remark": r"paper Remarks? (\d+)"}[kind]
            bad += [(page, m.group(0)) for m in re.finditer(pattern, text)
                    if not 1 <= int(m.group(1)) <= limit]
    assert not bad, f"cited numbers the compiled paper does not have: {bad}"


def _sentence_around(text, start, end):
    lo = max(text.rfind(".", 0, max(start - 1, 0)), text.rfind("\n\n", 0, start)) + 1
    hi = min(k for k in (text.find(". ", end), text.find("\n\n", end), len(text)) if k != -1)
    return text[lo:hi]


def disturbance_miscitations(pages):
    """``[(page, text, wrong names)]``: disturbance equations cited under another signal's name."""
    eqs, _ = equation_numbers()
    number = {eqs[label]: names for label, names in DISTURBANCE_EQS.items()}
    bad = []
    for page, text in pages:
        for m in re.finditer(r"paper eq\. \((\d+)\)", text):
            n = int(m.group(1))
            if n not in number:
                continue
            # the words right before the citation ("the mixed one of paper eq. (57)") name the signal
            before = text[max(0, m.start() - 40):m.start()]
            wrong = [w for w, pat in _DISTURBANCE_WORDS.items()
                     if w not in number[n] and re.search(pat, before)]
            if wrong:
                bad.append((page, before + m.group(0), wrong))
    return bad


def figure_miscitations(pages):
    """``[(page, sentence, number, other figures)]``: figures cited for another one's content."""
    figs, _ = figure_numbers()
    topic = {figs[label]: pat for label, pat in FIGURE_TOPICS.items()}
    bad = []
    for page, text in pages:
        for m in re.finditer(r"paper Fig\. (\d)\b(?![–-]\d)", text):
            n = int(m.group(1))
            if n not in topic:
                continue
            # "paper Fig. 3 (σ_max ...)" / "the ρ_p sweep of paper Fig. 7": a sentence that names
            # exactly one figure and another figure's topic but not its own is a miscitation
            sentence = _sentence_around(text, m.start(), m.end())
            if len(set(re.findall(r"paper Figs?\. (\d)", sentence))) > 1:
                continue
            own = re.search(topic[n], sentence)
            others = [k for k, pat in topic.items()
                      if k != n and k not in (4, 5) and re.search(pat, sentence)]
            if not own and others:
                bad.append((page, sentence.strip()[:160], n, others))
    return bad


def test_disturbance_equations_are_named_right():
    bad = disturbance_miscitations(_prose())
    assert not bad, f"a disturbance equation cited under another signal's name: {bad}"


def test_figures_are_named_right():
    bad = figure_miscitations(_prose())
    assert not bad, f"a paper figure cited for another figure's content: {bad}"


def test_the_checks_fire_on_miscitations():
    # the slip the book once had ("the mixed one of paper eq. (57)": (57) is the HF disturbance),
    # an LF disturbance cited as the HF one's equation, and the ρ_p sweep cited as paper Fig. 3
    pages = [("a", "the LF tones of paper eqs. (56)–(57) and the mixed one of paper eq. (57)"),
             ("b", "under the HF disturbance (paper eq. (56)) the loop"),
             ("c", "The energy against ρ_p, drawn in paper Fig. 3, rises.")]
    assert [b[0] for b in disturbance_miscitations(pages)] == ["a", "b"]
    assert [(b[0], b[2], b[3]) for b in figure_miscitations(pages)] == [("c", 3, [7])]
    good = [("d", "the piecewise signal of paper eq. (58) (HF tones, then LF ones)"),
            ("e", "paper Fig. 7 draws the energy against ρ_p; paper Fig. 3 the σ_max curves")]
    assert disturbance_miscitations(good) == [] and figure_miscitations(good) == []
