r"""Check a built book: images exist and are non-empty, internal links resolve, nothing is fetched
from the web when a page loads (no external scripts, stylesheets or images), MathJax is the
book's own copy, no page shows TeX that was not typeset, and no page's text holds an emoji or
pictograph (U+2600–U+27BF, U+2B00–U+2BFF, U+1F000–U+1FAFF): a machine without an emoji font,
such as the browser test's, draws one as an empty box (arrows and mathematical symbols are fine).

Usage: ``python tests/check_book_html.py book/_build/html``. Exits non-zero on any problem.
Run by ``.ci/run`` after the book build (a figure that silently fails to render, e.g. when a
non-inline matplotlib backend is forced, leaves a chapter without images).

Raw TeX
-------
A page's *visible text* is its text minus what the reader does not see as prose: ``<head>``
(so ``<title>``), ``<script>``, ``<style>``, ``<noscript>``, ``<template>``, code (``<code>``,
``<pre>``, ``<kbd>``, ``<samp>``, ``<tt>``, class ``highlight``, notebook input areas
``cell_input``/``input_area``/``jp-InputArea``) and maths that MathJax typesets (``<math>``,
class ``math``, ``MathJax`` or ``mjx-*``, ``mjx-*`` elements). Sphinx writes inline maths as
``<span class="math">\(...\)</span>`` and display maths as ``<div class="math">\[...\]</div>``;
MathJax is told to typeset only those (the chapters carry ``mathjax_ignore``), so TeX anywhere
else reaches the reader as source. In the visible text, raw TeX is:

1. two dollar signs with nothing but whitespace between them: ``$$``, and also what is left of
   ``$<span class="math">...</span>$``, the trace of display maths written inside a sentence
   or list item;
2. a ``$...$`` pair on one line whose content is at most 80 characters, starts with a
   non-space character and looks like TeX: it holds a backslash followed by a letter, or a
   ``_``/``^`` after a non-space character and before ``{``, ``\`` or a letter or digit
   (``$H_\infty $``, ``$x_1$``). A lone ``$`` and prices (``$5 or $3``) are not TeX; a pair
   enclosing only letters (``$x$``) cannot be told from prose and is not reported;
3. a TeX control word, a backslash followed by two or more ASCII letters (``\begin``, ``\left``,
   ``\frac``, ``\sigma``, ...), or a MathJax delimiter ``\(``, ``\)``, ``\[``, ``\]`` outside a
   maths element. Prose has no other use for a backslash before a word; code, where
   ``C:\Users`` or ``"\n"`` belongs, is not visible text. Single-letter escapes (``\n``) are
   not reported.

:func:`raw_tex_snippets` applies these rules to any text; ``tests/test_browser.py`` uses it on
the text a browser shows once MathJax has run.

Readers' pages
--------------
The landing page (:data:`ROOT_PAGE`) must open with the section "Does FDSC work, and when?" and
hold at most :data:`MAX_ROOT_WORDS` words of visible text; its short list of errata must have as
many items as the report's (:data:`REPORT_PAGE`), each linked to its item there. No page's prose
shows the machinery (:func:`leaks`: e-notation, integers of five or more digits without
separators, dictionary keys, notebook file names) or an empty heading (:func:`empty_headings`),
and no page types a result that another page prints (:func:`typed_copies`: a number of three or
more significant digits in a page's Markdown or in the prose its code cells glue, found in
another page's text): a result printed on two pages comes from one computed value. Every page that uses a term of
:data:`LINKED_TERMS` links it to the glossary at least once. No sentence calls Theorem 1's LMIs a
certificate (:func:`theorem1_certified`): their feasibility certifies nothing (they hold for every
Hurwitz pair). No page's visible text may speak to the project
instead of the reader (:data:`PROJECT_SPEAK`: issue numbers, paths of test files, "record entry",
the ids of the reproduction record's entries outside the report's tables, raw NumPy arrays
printed with runs of spaces). And code a reader sees (notebook input areas not folded away by a
``hide-input`` toggle, MyST-NB's ``<details class="hide ...">``) may be at most
:data:`MAX_CODE_SHARE` of a page's words.
"""

import re
import sys
from html.parser import HTMLParser
from itertools import pairwise
from pathlib import Path
from urllib.parse import unquote, urlparse

__all__ = ["check", "visible_text", "raw_tex_snippets", "code_share", "project_speak", "unlinked_terms",
           "theorem1_certified", "leaks", "empty_headings", "typed_numbers", "typed_copies"]

#: Chapters and the least number of figures each must show.
MIN_IMAGES = {"frequency_ranges.html": 3, "gkyp_lemma.html": 1, "passive_controllers.html": 3,
              "frequency_selective.html": 3, "theorem1.html": 1, "switching_law.html": 2,
              "simulations.html": 4}
#: Raw-TeX findings reported per page (the rest are counted).
MAX_TEX_REPORTS = 3
#: The landing page, its first heading (the answer comes first) and its length in words of visible text.
ROOT_PAGE = "intro.html"
FINDINGS_HEADING = "Does FDSC work, and when?"
MAX_ROOT_WORDS = 1200
#: Largest share of a page's words that may be visible code, and the pages exempt: the own-plant
#: chapter is the library's worked example, whose code is what the reader came for.
MAX_CODE_SHARE = 0.15
CODE_PAGES = {"own_plant.html"}
#: Ids of the reproduction record's entries that read as code (the report's tables show them,
#: prose must not); paper symbols such as K_f1 or Q_1 are not listed, nor ids that are also the
#: name of a chapter (generic_example, theorem1_counterexamples: the environment
#: page's table lists chapters by file name).
RECORD_IDS = (
    "alpha_localized", "alpha_mixed", "bound_e", "bound_f1", "bound_f2", "bound_f3",
    "bound_time_domain", "claims_step_halving", "closed_loop_output_matrix", "eef_switching",
    "epf_aircraft_signs",
    "epsilon_scan_lf", "epsilon_scan_mf", "fdsc_configuration", "gamma_slip_in_band",
    "hf_best", "hf_good_in_band", "hf_l2_claims", "hf_outputs_claims",
    "hysteresis_dwell", "law_chattering", "lemma1_gamma", "lemma1_gamma_squared",
    "lf_outputs_claims", "lmi_vs_direct", "mixed_crossover", "p1_global",
    "p2_localized", "paley_wiener_share", "piecewise_crossover", "plot_scalings", "prop1_checks",
    "prop1_factorizations", "prop1_short_windows", "psi_weight_sign", "remark1_crossings",
    "remark3_gap", "sigma_peak", "step_halving_hf", "step_halving_lf", "sweep_parameters",
    "sweep_step_halving", "table1_checks", "thm1_gammas",
    "thm1_lyapunov_jumps", "thm1_mode_reference", "thm1_statement1", "thm1_statement1_false",
    "thm1_statement2", "thm1_statement3", "three_mode")
#: Prose that speaks to the project: (what, pattern).
PROJECT_SPEAK = (
    ("an issue number", re.compile(r"\bissues? #?\d+\b", re.IGNORECASE)),
    ("a test path", re.compile(r"\btests?/[\w/]+\.py\b")),
    ("'record entry'", re.compile(r"\brecord entr(?:y|ies)\b", re.IGNORECASE)),
    ("a raw NumPy array", re.compile(r"\[\s*-?\d+\.?\d*(?:e[-+]?\d+)? {2,}-?\d|\barray\(")),
    ("a record-entry id", re.compile(r"(?<![\w.])(?:" + "|".join(RECORD_IDS) + r")(?![\w(])")),
    ("a Python list of names", re.compile(r"\[\s*'[a-z][a-z0-9_]*'\s*,\s*'[a-z][a-z0-9_]*'")),
    ("a Python tuple", re.compile(r"\((?:True|False|None), |\(-?\d+\.\d{9,}, (?:True|False)")),
    ("the per-case comparator called 'best fixed controller' (the glossary's 'best comparator of "
     "the case')", re.compile(r"\bbest fixed (?:controller )?of (?:the|each) (?:case|draw|point)s?\b",
                             re.IGNORECASE)),
    ("a glue key or code name", re.compile(r"(?<![\w.$\\/-])(?!(?:" + "|".join(RECORD_IDS) + r")(?![\w(]))"
                                           r"[a-z][a-z0-9]*_[a-z0-9]+_[a-z0-9_]+(?![\w(/.])")),
)
#: The terms every page that uses them links to the glossary at least once (lower case).
LINKED_TERMS = ("fixed controller chosen in advance", "best fixed controller with equal information",
                "non-causal limit", "disturbance estimate", "clairvoyant switching reference",
                "comparator set", "static front", "dynamic front")
GLOSSARY_PAGE = "glossary.html"
#: The page whose list of errata the landing page repeats.
REPORT_PAGE = "report.html"
#: Pages Sphinx generates (indices, search) and the changelog (history, in the words of its day):
#: not held to the glossary-link rule.
UNLINKED_OK_PAGES = {"genindex.html", "py-modindex.html", "search.html", "changelog.html"}
#: Pages Sphinx generates, where code names are the content.
GENERATED_PAGES = {"genindex.html", "py-modindex.html", "search.html"}
#: The report: at most this many words of prose outside folded blocks, tables of at most
#: MAX_TABLE_COLUMNS columns whose cells show at most MAX_CELL_CHARS characters unfolded.
MAX_REPORT_WORDS = 5000
MAX_TABLE_COLUMNS = 8
MAX_CELL_CHARS = 300
#: Pages whose tables list the record's ids by design.
_ID_PAGES = {"report.html"}

#: Elements whose text is not prose: metadata, code and maths that MathJax typesets.
_HIDDEN_TAGS = {"head", "title", "script", "style", "noscript", "template", "code", "pre", "kbd",
                "samp", "tt", "math"}
_HIDDEN_CLASSES = {"highlight", "cell_input", "input_area", "jp-InputArea", "math", "MathJax"}
_VOID_TAGS = {"area", "base", "br", "col", "embed", "hr", "img", "input", "link", "meta", "param",
              "source", "track", "wbr"}
#: Elements that start a new line of text (so that text of two blocks never runs together).
_BLOCK_TAGS = {"address", "article", "aside", "blockquote", "br", "caption", "dd", "div", "dl",
               "dt", "figcaption", "figure", "footer", "h1", "h2", "h3", "h4", "h5", "h6", "header",
               "hr", "li", "main", "nav", "ol", "p", "section", "table", "td", "th", "tr", "ul"}

_DOUBLE_DOLLAR = re.compile(r"\$\s*\$")
_CONTROL_WORD = re.compile(r"\\(?:[A-Za-z]{2,}|[()\[\]])")
_TEX_IN_PAIR = re.compile(r"\\[A-Za-z]|\S[_^][{\\A-Za-z0-9]")
_PAIR_MAX = 80
_CONTEXT = 40
_PICTOGRAPH = re.compile("[\u2600-\u27bf\u2b00-\u2bff\U0001f000-\U0001faff]")


def _hidden(tag, attrs):
    if tag in _HIDDEN_TAGS or tag.startswith("mjx-"):
        return True
    classes = (dict(attrs).get("class") or "").split()
    return any(c in _HIDDEN_CLASSES or c.startswith("mjx-") for c in classes)


class _Collector(HTMLParser):
    def __init__(self):
        super().__init__()
        self.images, self.links, self.loads = [], [], []
        self._text = []
        self._open = []  # (tag, hidden, code input, folded) of each open element
        self._n_hidden = 0
        self._n_input = 0   # inside a notebook input area
        self._n_folded = 0  # inside a hide-input toggle
        self._code = []

    @property
    def text(self):
        return "".join(self._text)

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "img" and a.get("src"):
            self.images.append(a["src"])
        if tag == "a" and a.get("href"):
            self.links.append(a["href"])
        if tag == "script" and a.get("src"):
            self.loads.append(a["src"])
        if tag == "link" and a.get("rel") in ("stylesheet", "preload") and a.get("href"):
            self.loads.append(a["href"])
        if tag in _BLOCK_TAGS and not self._n_hidden:
            self._text.append("\n")
        if tag not in _VOID_TAGS:
            hidden = _hidden(tag, attrs)
            classes = (a.get("class") or "").split()
            code_input = "cell_input" in classes
            folded = tag == "details" and "hide" in classes
            self._open.append((tag, hidden, code_input, folded))
            self._n_hidden += hidden
            self._n_input += code_input
            self._n_folded += folded

    def handle_endtag(self, tag):
        # close up to the matching element (HTML lets some end tags be omitted); stray ones are ignored
        for i in range(len(self._open) - 1, -1, -1):
            if self._open[i][0] == tag:
                self._n_hidden -= sum(o[1] for o in self._open[i:])
                self._n_input -= sum(o[2] for o in self._open[i:])
                self._n_folded -= sum(o[3] for o in self._open[i:])
                del self._open[i:]
                break
        if tag in _BLOCK_TAGS and not self._n_hidden:
            self._text.append("\n")

    def handle_data(self, data):
        if not self._n_hidden:
            self._text.append(data)
        if self._n_input and not self._n_folded:
            self._code.append(data)

    @property
    def code(self):
        return " ".join(self._code)


#: A MyST role left as source in the visible text (glued Markdown is not parsed as MyST, so a role
#: in it reaches the reader as ``{term}name``).
RAW_ROLE = re.compile(r"\{(?:term|doc|cite|ref|numref|eq|glue:text|glue:md|py:[a-z]+)\}")


def visible_text(html):
    """Text of an HTML page that a reader sees as prose (see the module docstring).

    Parameters
    ----------
    html : str
        A whole page or a fragment.

    Returns
    -------
    str
        The text, blocks separated by newlines. Typeset maths is dropped without a trace, so
        ``$<span class="math">\\(x\\)</span>$`` leaves ``$$``.
    """
    c = _Collector()
    c.feed(html)
    c.close()
    return c.text


def _tex_spans(text):
    spans = [m.span() for m in _DOUBLE_DOLLAR.finditer(text)]
    spans += [m.span() for m in _CONTROL_WORD.finditer(text)]
    dollars = [m.start() for m in re.finditer(r"\$", text)]
    for i, j in pairwise(dollars):
        inner = text[i + 1:j]
        if (0 < len(inner) <= _PAIR_MAX and "\n" not in inner and not inner[0].isspace()
                and _TEX_IN_PAIR.search(inner)):
            spans.append((i, j + 1))
    return sorted(spans)


def raw_tex_snippets(text):
    r"""Places where `text` shows TeX source, by the rules of the module docstring.

    Parameters
    ----------
    text : str
        Visible text of a page (:func:`visible_text`, or a browser's ``innerText``).

    Returns
    -------
    list of str
        One snippet per group of findings, the first finding with up to 40 characters on each
        side, whitespace collapsed; findings closer than 40 characters to the previous one
        join its group. Empty when there is no raw TeX.

    Examples
    --------
    >>> raw_tex_snippets(r"Reliable $H_\infty $ control, for $5 or $3.")
    ['Reliable $H_\\infty $ control, for $5 or $3.']
    >>> raw_tex_snippets("A price of $5 or $3; typeset maths was removed.")
    []
    """
    snippets, group_end = [], None
    for start, end in _tex_spans(text):
        if group_end is not None and start <= group_end + _CONTEXT:
            group_end = max(group_end, end)
            continue
        group_end = end
        window = text[max(0, start - _CONTEXT):end + _CONTEXT]
        snippets.append(" ".join(window.split()))
    return snippets


def code_share(html):
    """Share of a page's words that are visible code (input areas not folded by hide-input).

    Parameters
    ----------
    html : str

    Returns
    -------
    float
        0 for a page without words.
    """
    c = _Collector()
    c.feed(html)
    c.close()
    prose, code = len(c.text.split()), len(c.code.split())
    return code / (prose + code) if prose + code else 0.0


def project_speak(text, page=""):
    """``[(what, snippet)]``: prose that speaks to the project (:data:`PROJECT_SPEAK`).

    Parameters
    ----------
    text : str
        Visible text of a page.
    page : str, optional
        The page's file name (record-entry ids are allowed on :data:`_ID_PAGES`).

    Returns
    -------
    list of tuple
    """
    found = []
    for what, pattern in PROJECT_SPEAK:
        if what == "a record-entry id" and page in _ID_PAGES:
            continue
        for m in pattern.finditer(text):
            window = text[max(0, m.start() - _CONTEXT):m.end() + _CONTEXT]
            found.append((what, " ".join(window.split())))
    return found


#: Leaks of the machinery into the reader's text (item: what, pattern); the API reference, the
#: generated pages and the references (page and volume numbers) are not held to them.
LEAKS = (
    ("e-notation", re.compile(r"(?<![\w.])(?<!commit )\d+(?:\.\d+)?[eE][-+\u2212]?\d+(?!\w|\.\d)")),
    ("an integer of five or more digits without separators",
     re.compile(r"(?<![\w.,/:#\u2212-])(?<!commit )\d{5,}(?![\w,/])(?!\.\d)")),
    ("dictionary keys", re.compile(r"(?<![\w)])[A-Za-z_][\w ]{0,11}: [A-Za-z_]\w{0,11}: [-\u2212\d]")),
    ("a Python object's repr",
     re.compile(r"<(?:function|bound method|built-in function|module|[\w.]+ object at) ")),
)
#: The repr of a function or object as HTML shows it (escaped), in a page's outputs.
_OUTPUT_REPR = re.compile(r"&lt;(?:function|bound method|built-in function|module) [^&]{1,80}|"
                          r"&lt;[\w.]{1,80} object at 0x[0-9a-f]+&gt;")
#: Pages exempt from :data:`LEAKS`.
LEAK_FREE_PAGES = GENERATED_PAGES | {"references.html"}
_HEADING = re.compile(r"<h([1-6])\b[^>]*>(.*?)</h\1>", flags=re.S)
_EMPTY_SECTION = re.compile(r"<section\b[^>]*>\s*<h([1-6])\b[^>]*>(.*?)</h\1>\s*</section>", flags=re.S)


def leaks(text, page="", stems=()):
    """``[(what, snippet)]``: machinery in a page's visible text (:data:`LEAKS`), and the file
    names of notebooks (``stems`` with an underscore) used as names of chapters.

    Parameters
    ----------
    text : str
        Visible text of a page.
    page : str, optional
        The page's file name (:data:`LEAK_FREE_PAGES` are exempt).
    stems : iterable of str, optional
        The book's notebook file names without suffix.

    Returns
    -------
    list of tuple

    Examples
    --------
    >>> [w for w, _ in leaks("gamma^2 = 9.932e+05. After 196254 steps, see wellposed_laws",
    ...                      stems=["wellposed_laws"])]
    ['e-notation', 'an integer of five or more digits without separators', 'a notebook file name']
    >>> [w for w, _ in leaks("<function fdsc.f.<locals>.g()> and <fdsc.Plant object at 0x7f>")]
    ["a Python object's repr", "a Python object's repr"]
    >>> leaks("196,254 steps in 2023 at commit 0394711 (or commit 6e88619), doi 10.5281/zenodo.7990805, 1.5 s")
    []
    """
    if page in LEAK_FREE_PAGES:
        return []
    found = []
    for what, pattern in LEAKS:
        for m in pattern.finditer(text):
            window = text[max(0, m.start() - _CONTEXT):m.end() + _CONTEXT]
            found.append((what, " ".join(window.split())))
    for stem in stems:
        if "_" in stem:
            for m in re.finditer(rf"(?<![\w/.-]){re.escape(stem)}(?![\w])", text):
                window = text[max(0, m.start() - _CONTEXT):m.end() + _CONTEXT]
                found.append(("a notebook file name", " ".join(window.split())))
    return found


def empty_headings(html):
    """Headings of ``html`` without text (their permalink apart) and sections holding nothing but
    their heading.

    Returns
    -------
    list of str
        The headings' text ('' for one without text).

    Examples
    --------
    >>> empty_headings('<section><h2>A<a class="headerlink">#</a></h2></section><h3> </h3>')
    ['A', '']
    """
    out = []
    for m in _HEADING.finditer(html):
        if not " ".join(visible_text(re.sub(r'<a class="headerlink".*?</a>', "", m.group(2))).split()):
            out.append("")
    for m in _EMPTY_SECTION.finditer(html):
        out.insert(0, " ".join(visible_text(re.sub(r'<a class="headerlink".*?</a>', "", m.group(2))).split()))
    return out


def article(html):
    """The page's article (``<article>…</article>``: without the navigation, whose chapter titles
    are not the page's prose); the whole page if it has none."""
    m = re.search(r"<article\b.*?</article>", html, flags=re.S)
    return m.group(0) if m else html


def unlinked_terms(html, text):
    """The terms of :data:`LINKED_TERMS` that a page's visible text uses but none of its links to
    the glossary carries.

    Parameters
    ----------
    html : str
        The page.
    text : str
        Its visible text.

    Returns
    -------
    list of str
    """
    low = " ".join(text.lower().split())
    anchors = re.findall(r'<a [^>]*href="[^"]*glossary\.html#term[^"]*"[^>]*>(.*?)</a>', html, flags=re.S)
    linked = " ".join(" ".join(re.sub(r"<[^>]+>", " ", m).lower().split()) for m in anchors)
    return [t for t in LINKED_TERMS if t in low and t not in linked]


def theorem1_certified(text):
    """Sentences that call Theorem 1's LMIs (or their feasibility) a certificate, unless negated.

    Parameters
    ----------
    text : str

    Returns
    -------
    list of str

    Examples
    --------
    >>> theorem1_certified("The printed Q's are certified by Theorem 1's LMIs. They are not.")
    ["The printed Q's are certified by Theorem 1's LMIs."]
    >>> theorem1_certified("Theorem 1's LMIs are feasible, which this book does not call certified.")
    []
    """
    out = []
    for sentence in re.split(r"(?<=[.;:])\s+", " ".join(text.split())):
        low = sentence.lower()
        if "theorem 1" in low and "lmi" in low and "certif" in low \
                and not re.search(r"\b(?:not|never|no|nothing|neither|nor)\b", low):
            out.append(sentence)
    return out


def _top_items(fragment):
    """The ``<li>`` items of a list's inner HTML at its top level (nested lists apart).

    Examples
    --------
    >>> _top_items("<li>a <ul><li>b</li></ul></li><li>c</li>")
    2
    """
    depth, n = 0, 0
    for m in re.finditer(r"<(/?)(ol|ul)\b|<li\b", fragment):
        if m.group(2):
            depth += -1 if m.group(1) else 1
        elif depth == 0:
            n += 1
    return n


def _errata_problems(root, page):
    """The landing page's errata against the report's: as many items."""
    report = root / REPORT_PAGE
    if not report.is_file():
        return []
    rep = report.read_text(encoding="utf-8")
    m = re.search(r"<ol class=.errata.>(.*?)</ol>", rep, flags=re.S)
    if m is None:
        return [f"{REPORT_PAGE}: no list of errata"]
    n_report = _top_items(m.group(1))
    html = page.read_text(encoding="utf-8")
    m2 = re.search(r"<ol class=.errata-short.>(.*?)</ol>", html, flags=re.S)
    n_here = _top_items(m2.group(1)) if m2 else 0
    if n_here != n_report:
        return [f"{page.name}: {n_here} errata, the report lists {n_report}"]
    # each item links to its explanation in the report
    ids = set(re.findall(r"<li id=.(erratum-\d+).", rep))
    targets = re.findall(rf"{re.escape(REPORT_PAGE)}#(erratum-\d+)", m2.group(1)) if m2 else []
    out = [f"{page.name}: the errata link to {REPORT_PAGE}#{t}, which has no such item" for t in targets
           if t not in ids]
    if len(targets) != n_here:
        out.append(f"{page.name}: {n_here - len(targets)} errata do not link to their item in {REPORT_PAGE}")
    return out


_DETAILS = re.compile(r"<details\b.*?</details>", flags=re.S)
_TABLE = re.compile(r"<table\b.*?</table>", flags=re.S)
_ROW = re.compile(r"<tr\b.*?</tr>", flags=re.S)
_CELL = re.compile(r"<t([hd])\b[^>]*>(.*?)</t\1>", flags=re.S)


def unfolded(html):
    """``html`` without its folded blocks (``<details>`` elements: dropdowns and toggles)."""
    return _DETAILS.sub("", html)


def table_problems(html):
    """Tables of ``html`` (folded ones apart) wider than MAX_TABLE_COLUMNS columns or with a
    cell whose unfolded visible text is longer than MAX_CELL_CHARS characters.

    Returns
    -------
    list of str
    """
    out = []
    for k, table in enumerate(_TABLE.findall(unfolded(html)), 1):
        rows = _ROW.findall(table)
        width = max((len(_CELL.findall(r)) for r in rows), default=0)
        if width > MAX_TABLE_COLUMNS:
            out.append(f"table {k} has {width} columns, at most {MAX_TABLE_COLUMNS}")
        for r in rows:
            for _, cell in _CELL.findall(r):
                text = " ".join(visible_text(cell).split())
                if len(text) > MAX_CELL_CHARS:
                    out.append(f"table {k} has a cell of {len(text)} characters, at most "
                               f"{MAX_CELL_CHARS}: '{text[:_CONTEXT]}…'")
    return out


#: Pages whose typed numbers are history or bibliography (versions, years, DOIs), not results.
TYPED_OK_PAGES = {"changelog", "how_to_cite", "references", "api"}
#: A number as prose prints a result: a decimal, an integer with thousands separators, or one of
#: four or more digits (years excepted below); not a piece of a DOI, a version or a dotted name.
_TYPED_NUMBER = re.compile(r"(?<![\w.,/#−-])(\d{1,3}(?:,\d{3})+(?:\.\d+)?|\d+\.\d+|\d{4,})"
                           r"(?![\w/]|\.\d|,\d{3})")
_MD_NOT_PROSE = (re.compile(r"```.*?```", re.S), re.compile(r"\$\$.*?\$\$", re.S),
                 re.compile(r"\{[\w:-]+\}`[^`]*`"), re.compile(r"\$[^$\n]*\$"), re.compile(r"`[^`]*`"),
                 re.compile(r"\]\([^)]*\)"), re.compile(r"^:[\w-]+:.*$", re.M),
                 re.compile(r"<[^>]+>"))


def _significant(number):
    """Significant digits of a number as printed, without separators, the point, and leading or
    trailing zeros (1.00, 3,000 and 0.50 are round settings or definitions, not measurements)."""
    return len(number.replace(",", "").replace(".", "").strip("0"))


def typed_numbers(markdown):
    """Numbers that a page's Markdown source types as results: at least three significant
    digits, outside glue and other roles, maths, code, link targets and directive options;
    years (1900–2099 without separators) are not results.

    Parameters
    ----------
    markdown : str

    Returns
    -------
    list of str

    Examples
    --------
    >>> typed_numbers("K_f3's peak is 1.605 ({glue:text}`peak`); T = 500 s, h = 0.2, "
    ...               "9,666.0 exactly, ×1.00 by definition, $\\gamma = 2.345$, in 2013 (`x = 4.567`), "
    ...               "doi 10.5281/zenodo.1")
    ['1.605', '9,666.0']
    """
    for pattern in _MD_NOT_PROSE:
        markdown = pattern.sub(" ", markdown)
    return [x for x in _TYPED_NUMBER.findall(markdown)
            if _significant(x) >= 3 and not (x.isdigit() and len(x) == 4 and 1900 <= int(x) < 2100)]


def _strings(code):
    """The string literals of a code cell (the prose it glues), or nothing if it does not parse."""
    import io
    import tokenize

    try:
        return [t.string for t in tokenize.generate_tokens(io.StringIO(code).readline)
                if t.type == tokenize.STRING]
    except (tokenize.TokenError, SyntaxError, IndentationError):
        return []


def _sources(book):
    """``{page stem: text}``: the Markdown of the book's pages, and for a notebook its Markdown
    cells and the string literals of its code cells (the prose a cell glues)."""
    import json

    out = {}
    for path in sorted(book.glob("*.ipynb")):
        cells = json.loads(path.read_text(encoding="utf-8")).get("cells", [])
        out[path.stem] = "\n\n".join("".join(c["source"]) if c["cell_type"] == "markdown"
                                      else "\n".join(_strings("".join(c["source"]))) for c in cells)
    for path in sorted(book.glob("*.md")):
        out[path.stem] = path.read_text(encoding="utf-8")
    return out


def typed_copies(book, root):
    """A number typed in one page's source and printed on another page: ``[(page, number,
    [other pages])]``. A result the book prints on two pages comes from one computed (glued)
    value; a typed copy of it is how copies drift apart.

    Parameters
    ----------
    book : path
        The book's sources (notebooks and Markdown pages).
    root : path
        The built HTML.

    Returns
    -------
    list of tuple
    """
    book, root = Path(book), Path(root)
    shown = {p.stem: visible_text(article(p.read_text(encoding="utf-8"))) for p in root.glob("*.html")
             if p.name not in GENERATED_PAGES}
    found = []
    for stem, markdown in _sources(book).items():
        if stem in TYPED_OK_PAGES:
            continue
        for number in dict.fromkeys(typed_numbers(markdown)):
            pattern = re.compile(r"(?<![\d.,])" + re.escape(number) + r"(?![\d]|[.,]\d)")
            others = sorted(k for k, text in shown.items() if k != stem and pattern.search(text))
            if others:
                found.append((stem, number, others))
    return found


def check(root):
    root = Path(root)
    problems = []
    # the notebooks' file names, from the book's sources beside the build (none when built elsewhere)
    book = root.parent.parent
    stems = sorted(p.stem for p in book.glob("*.ipynb")) if root.parent.name == "_build" else []
    for page in sorted(root.glob("*.html")):
        c = _Collector()
        c.feed(page.read_text(encoding="utf-8"))
        c.close()
        for src in c.images:
            if urlparse(src).scheme:
                problems.append(f"{page.name}: external image {src}")
                continue
            f = (page.parent / unquote(src)).resolve()
            if not f.is_file() or f.stat().st_size == 0:
                problems.append(f"{page.name}: missing or empty image {src}")
        for src in c.loads:
            if urlparse(src).scheme in ("http", "https") or src.startswith("//"):
                problems.append(f"{page.name}: loads {src} from the web")
        if page.name in MIN_IMAGES and not any("_static/mathjax/" in s for s in c.loads):
            problems.append(f"{page.name}: does not load the book's own MathJax")
        if len(c.images) < MIN_IMAGES.get(page.name, 0):
            problems.append(f"{page.name}: {len(c.images)} images, expected >= {MIN_IMAGES[page.name]}")
        for href in c.links:
            u = urlparse(href)
            if u.scheme or href.startswith(("#", "mailto:")):
                continue
            target = (page.parent / unquote(u.path)).resolve()
            if not target.exists():
                problems.append(f"{page.name}: broken link {href}")
        glyphs = sorted(set(_PICTOGRAPH.findall(c.text)))
        if glyphs:
            problems.append(f"{page.name}: emoji or pictographs in visible text (no font may "
                            f"draw them): {' '.join(glyphs)}")
        share = len(c.code.split()) / max(1, len(c.code.split()) + len(c.text.split()))
        if share > MAX_CODE_SHARE and page.name not in CODE_PAGES:
            problems.append(f"{page.name}: visible code is {share:.0%} of the page's words "
                            f"(at most {MAX_CODE_SHARE:.0%})")
        if page.name not in GENERATED_PAGES:
            problems += [f"{page.name}: {what} in the prose: '{snippet}'"
                         for what, snippet in project_speak(c.text, page.name)[:MAX_TEX_REPORTS]]
            body = article(page.read_text(encoding="utf-8"))
            problems += [f"{page.name}: {what} in the prose: '{snippet}'"
                         for what, snippet in leaks(visible_text(body), page.name, stems)[:MAX_TEX_REPORTS]]
            problems += [f"{page.name}: an empty heading or section: '{h}'" for h in empty_headings(body)]
            # a cell whose last line returns an object shows its repr as the cell's output
            problems += [f"{page.name}: a Python object's repr in a cell's output: '{m.group(0)}'"
                         for m in list(_OUTPUT_REPR.finditer(body))[:MAX_TEX_REPORTS]]
        if page.name == ROOT_PAGE:
            body = article(page.read_text(encoding="utf-8"))
            headings = [" ".join(visible_text(re.sub(r'<a class="headerlink".*?</a>', "", m.group(2))).split())
                        for m in _HEADING.finditer(body) if m.group(1) == "2"]
            if not headings or headings[0] != FINDINGS_HEADING:
                problems.append(f"{page.name}: its first section is not '{FINDINGS_HEADING}'")
            n = len(visible_text(body).split())
            if n > MAX_ROOT_WORDS:
                problems.append(f"{page.name}: {n} words of visible text, at most {MAX_ROOT_WORDS}")
            problems += _errata_problems(root, page)
        if page.name == REPORT_PAGE:
            html = page.read_text(encoding="utf-8")
            n = len(visible_text(unfolded(article(html))).split())
            if n > MAX_REPORT_WORDS:
                problems.append(f"{page.name}: {n} words of unfolded visible text, "
                                f"at most {MAX_REPORT_WORDS}")
            problems += [f"{page.name}: {p}" for p in table_problems(html)]
        if page.name != GLOSSARY_PAGE and page.name not in UNLINKED_OK_PAGES:
            body = article(page.read_text(encoding="utf-8"))
            problems += [f"{page.name}: uses '{t}' without linking it to the glossary"
                         for t in unlinked_terms(body, visible_text(body))]
        if page.name not in GENERATED_PAGES:
            problems += [f"{page.name}: Theorem 1's LMIs called a certificate: '{s}'"
                         for s in theorem1_certified(c.text)[:MAX_TEX_REPORTS]]
        problems += [f"{page.name}: a MyST role reached the reader as source: '{m.group(0)}'"
                     for m in list(RAW_ROLE.finditer(c.text))[:MAX_TEX_REPORTS]]
        tex = raw_tex_snippets(c.text)
        problems += [f"{page.name}: raw TeX in visible text: '{s}'" for s in tex[:MAX_TEX_REPORTS]]
        if len(tex) > MAX_TEX_REPORTS:
            problems.append(f"{page.name}: raw TeX in visible text: {len(tex) - MAX_TEX_REPORTS} more")
    if stems:
        problems += [f"{stem}: {number} is typed here and printed on {', '.join(others)}: print it "
                     "from one computed value" for stem, number, others in typed_copies(book, root)]
    return problems


if __name__ == "__main__":
    found = check(sys.argv[1] if len(sys.argv) > 1 else "book/_build/html")
    print("\n".join(found) or "book HTML: images present, internal links resolve, no web loads, "
                              "no raw TeX, no emoji, findings first, no project speak, little code")
    sys.exit(1 if found else 0)
