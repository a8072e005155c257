"""How the reproduction report prints the record's values and notes: words and small HTML.

A record value is a number, a matrix, a list or a nested dict; the report never prints it as a raw
dictionary. :func:`value_html` prints a number with its digits, a matrix as a bracketed grid, a
list of sentences as a list and a dict as a list of labelled items (keys in words), and folds a
long value in an HTML ``<details>`` element; :func:`note_html` shows a note's first sentence and
folds the rest; :func:`words` writes the ASCII names of Greek letters, ``<=`` and a few other
ASCII spellings (``H-infinity``, ``xdot``) as symbols.
Every function returns trusted HTML: each part is escaped.
"""

import html
import json
import math
import re
from numbers import Real
from pathlib import Path

import numpy as np

__all__ = ["words", "key_words", "details", "note_html", "value_html", "number_text", "page_titles",
           "readable_numbers"]

_GREEK = {"rho": "ρ", "omega": "ω", "Omega": "Ω", "gamma": "γ", "delta": "δ", "alpha": "α",
          "beta": "β", "sigma": "σ", "epsilon": "ε", "tau": "τ", "Psi": "Ψ", "lambda": "λ"}
_GREEK_NAME = re.compile(r"(?<![A-Za-z])(" + "|".join(_GREEK) + r")(?![A-Za-z])")
_SENTENCE_END = re.compile(r"(?<=[a-z0-9)\]%])[.;:] (?=[A-Z(])")

#: Characters of a note shown before the rest is folded.
NOTE_SHOWN = 160


def words(text):
    """Text with the ASCII names of Greek letters as letters, ``<=``, ``>=`` as ``≤``, ``≥``,
    ``H-infinity`` as ``H∞``, ``xdot`` as ``ẋ`` and its numbers as the prose writes them
    (:func:`readable_numbers`).

    Parameters
    ----------
    text : str

    Returns
    -------
    str
        Plain text (not escaped).

    Examples
    --------
    >>> words("rho_p <= 0.2 and the 2 delta_E output; Lemma 1's gamma")
    "ρ_p ≤ 0.2 and the 2δ_E output; Lemma 1's γ"
    >>> words("the H-infinity gain, the measured xdot")
    'the H∞ gain, the measured ẋ'
    """
    text = _GREEK_NAME.sub(lambda m: _GREEK[m.group(1)], str(text))
    text = re.sub(r"(\d) ([δ])", r"\1\2", text)
    text = re.sub(r"(?<![A-Za-z])xdot(?![A-Za-z])", "ẋ", text.replace("H-infinity", "H∞"))
    return readable_numbers(text.replace("<=", "≤").replace(">=", "≥"))


def key_words(key):
    """A dict key as a label: Greek letters as letters, and underscores between words as spaces
    (a subscript such as ``K_f1`` or ``ρ_p`` is kept).

    Parameters
    ----------
    key : str

    Returns
    -------
    str

    Examples
    --------
    >>> key_words("extended_crossover_lf"), key_words("K_f1"), key_words("2 delta_E")
    ('extended crossover lf', 'K_f1', '2δ_E')
    """
    text = words(key)
    parts = text.split("_")
    if any(len(p) >= 3 and p.isalpha() for p in parts[1:]) or (len(parts) > 1 and len(parts[0]) >= 3
                                                                 and parts[0].isalpha()):
        return " ".join(parts)
    return text


def details(summary, body):
    """``<details>``: ``summary`` shown, ``body`` one click away (both trusted HTML).

    Parameters
    ----------
    summary, body : str

    Returns
    -------
    str
    """
    return f"<details><summary>{summary}</summary>{body}</details>"


_E_NUMBER = re.compile(r"(?<![\w.])(-?\d+(?:\.\d+)?)[eE]([-+]?\d+)(?!\w|\.\d)")
_LONG_INTEGER = re.compile(r"(?<![\w.,/#-])\d{5,}(?![\w,/])(?!\.\d)")


def readable_numbers(text):
    """Text with its numbers as the prose writes them: e-notation as ``m × 10ⁿ``, integers of
    five or more digits with thousands separators.

    Parameters
    ----------
    text : str

    Returns
    -------
    str

    Examples
    --------
    >>> readable_numbers("passes 1e6 at 2.88e+06, after 196254 steps in 2023, doi 10.5281/zenodo.7990805")
    'passes 1 × 10⁶ at 2.88 × 10⁶, after 196,254 steps in 2023, doi 10.5281/zenodo.7990805'
    >>> readable_numbers("PassC-HF 6.27e+03.")
    'PassC-HF 6.27 × 10³.'
    """
    text = _E_NUMBER.sub(lambda m: f"{m.group(1)} × 10{str(int(m.group(2))).translate(_SUPERSCRIPT)}", text)
    return _LONG_INTEGER.sub(lambda m: f"{int(m.group(0)):,}", text)


def note_html(note, shown=NOTE_SHOWN):
    """A note in words: whole if short, else its first sentence with the rest folded.

    Parameters
    ----------
    note : str
    shown : int, optional
        Length up to which a note is shown whole.

    Returns
    -------
    str

    Examples
    --------
    >>> note_html("short; rho_p")
    'short; ρ_p'
    >>> note_html("width <= 1e-3 after 196254 steps")
    'width ≤ 1 × 10⁻³ after 196,254 steps'
    >>> note_html("First part here. " + "x" * 200).startswith("<details><summary>First part here. …")
    True
    """
    text = words(note).strip()
    if len(text) <= shown:
        return html.escape(text)
    cut = _SENTENCE_END.search(text, 20)
    head, rest = (text[:cut.start() + 1], text[cut.end():]) if cut and cut.start() < 2 * shown else (
        text[:shown].rsplit(" ", 1)[0], text[len(text[:shown].rsplit(" ", 1)[0]):].lstrip())
    return details(f"{html.escape(head)} …", f"<p>{html.escape(rest)}</p>")


_SUPERSCRIPT = str.maketrans("0123456789-", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻")


def number_text(x, digits=None):
    """A number: every digit the record keeps (``digits=None``, ten significant at most) or
    ``digits`` significant ones; ``yes``/``no`` for a bool, ``—`` for None.

    Parameters
    ----------
    x : float, int, bool or None
    digits : int, optional

    Returns
    -------
    str

    Examples
    --------
    >>> number_text(15.0897), number_text(0.104946831, 4), number_text(1.0), number_text(None)
    ('15.0897', '0.1049', '1', '—')
    >>> number_text(1.0735e-08), number_text(-2876000.0, 4), number_text(855900), number_text(1010.0)
    ('1.0735 × 10⁻⁸', '−2.876 × 10⁶', '855,900', '1,010')
    """
    if x is None:
        return "—"
    if isinstance(x, bool | np.bool_):
        return "yes" if x else "no"
    v = float(x)
    if not math.isfinite(v):
        return "∞" if v > 0 else ("−∞" if v < 0 else "n/a")
    text = format(v, f".{digits or 10}g")
    if "e" in text:   # as the prose writes it, never e-notation
        mantissa, exponent = text.split("e")
        text = f"{mantissa} × 10{str(int(exponent)).translate(_SUPERSCRIPT)}"
    else:             # thousands separators on four or more digits, as the prose writes them
        whole, dot, frac = text.partition(".")
        if len(whole.lstrip("-")) >= 4:
            whole = f"{int(whole):,}"
        text = whole + dot + frac
    return text.replace("-", "−")


def _is_number(v):
    return isinstance(v, Real | np.generic) and not isinstance(v, str)


def _is_matrix(v):
    return (isinstance(v, list) and len(v) > 0 and all(isinstance(r, list) and r for r in v)
            and len({len(r) for r in v}) == 1 and all(_is_number(x) for r in v for x in r))


def _plain(value):
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, tuple):
        return list(value)
    return value


def value_html(value, digits=None, *, max_items=8):
    """A record value as HTML for a table cell: never a raw dictionary.

    Parameters
    ----------
    value : object
        A number, a string, a list (of numbers, of sentences), a matrix or a nested dict.
    digits : int, optional
        Significant digits of the numbers (default: every digit the record keeps).
    max_items : int, optional
        Items of a list or a dict shown before the whole is folded.

    Returns
    -------
    str

    Examples
    --------
    >>> value_html(0.2), value_html("w <= 0 outside")
    ('0.2', 'w ≤ 0 outside')
    >>> value_html([[0.1048, 15.0897], [0.0205, 2.976]]).startswith("<table class='matrix'>")
    True
    >>> value_html({"PassC-LF": 0.119140625, "in_range": None}, 4)
    '<ul class="kv"><li>PassC-LF: 0.1191</li><li>in range: —</li></ul>'
    """
    value = _plain(value)
    if value is None or isinstance(value, bool) or _is_number(value):
        return html.escape(number_text(value, digits))
    if isinstance(value, str):
        return html.escape(words(value))
    if _is_matrix(value):
        rows = "".join("<tr>" + "".join(f"<td>{html.escape(number_text(x, digits))}</td>" for x in r)
                       + "</tr>" for r in value)
        return f"<table class='matrix'>{rows}</table>"
    if isinstance(value, list):
        if all(_is_number(x) for x in value):
            items = [html.escape(number_text(x, digits)) for x in value]
            if len(items) <= max_items:
                return ", ".join(items)
            return details(", ".join(items[:max_items // 2]) + f", … ({len(items)} values)",
                           f"<p>{', '.join(items)}</p>")
        body = "<ul>" + "".join(f"<li>{value_html(x, digits)}</li>" for x in value) + "</ul>"
        return body if len(value) <= max_items else details(f"{len(value)} items", body)
    if isinstance(value, dict):
        items = (f"<li>{html.escape(key_words(str(k)))}: {value_html(v, digits)}</li>"
                 for k, v in value.items())
        body = '<ul class="kv">' + "".join(items) + "</ul>"
        return body if len(value) <= max_items else details(f"{len(value)} items", body)
    return html.escape(str(value))


def page_titles(book):
    """``{page: title}`` of a book's pages: the first Markdown heading of each notebook.

    Parameters
    ----------
    book : path
        The book's folder.

    Returns
    -------
    dict
    """
    out = {}
    for path in sorted(Path(book).glob("*.ipynb")):
        for cell in json.loads(path.read_text(encoding="utf-8"))["cells"]:
            heading = next((line[2:].strip() for line in "".join(cell["source"]).splitlines()
                            if cell["cell_type"] == "markdown" and line.startswith("# ")), None)
            if heading:
                out[path.stem] = heading
                break
    return out
