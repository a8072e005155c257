"""The reproduction report: the whole record as table rows in words (the book's chapter ``report``).

Pure functions of a record dict, as :func:`fdsc.paper.record.reproduction_record` returns it or as
``python -m fdsc reproduce`` writes it: one row per printed number, with the verdict of its value
and, for a printed inequality, whether it holds; the proof steps and sentences checked; the printed
inputs; every paper figure with its page, status and the verdict of the claims made on it; the
claims checklist; the findings the paper does not print; the errata; and the numbers of the law
on the disturbance estimate, stored study and build-time check side by side. Cells are trusted
HTML in words (:mod:`fdsc.paper.appendix.report_values`): no raw dictionary, long detail folded.
A record without claims or without a figure's data is rendered as such (the absence is stated).
The record's format is the JSON Schema ``fdsc/paper/data/record.schema.json`` (:func:`record_schema`).
"""

import html
import json
from importlib import resources

from fdsc.paper.appendix.report_counts import (
    FINDING,
    INPUT,
    NUMBER,
    PROOF_STEP,
    SENTENCES,
    claims_of,
    claims_sentence,
    counts_prose,
    counts_sentence,
    entries_of,
    entry_kind,
    figures_named,
    printed_counts,
    summary,
)
from fdsc.paper.appendix.report_further import FURTHER_WORDS, further_findings, further_summary
from fdsc.paper.appendix.report_law import LAW_ENTRY, ladder_rows, law_rows
from fdsc.paper.appendix.report_values import details, note_html, number_text, page_titles, value_html, words
from fdsc.paper.record import PAPER_FIGURES, figure_status
from fdsc.paper.shared.verdict import CLAIM_VERDICTS, worst_verdict

__all__ = [
    "NO_CLAIM",
    "NO_CHECKLIST",
    "LAW_ENTRY",
    "OURS_DIGITS",
    "record_schema",
    "figures_named",
    "entry_kind",
    "entry_link",
    "inequality_cell",
    "printed_rows",
    "step_rows",
    "input_rows",
    "figure_rows",
    "claim_rows",
    "finding_rows",
    "errata",
    "errata_summary",
    "FURTHER_WORDS",
    "further_findings",
    "further_summary",
    "law_rows",
    "ladder_rows",
    "page_titles",
    "summary",
    "printed_counts",
    "counts_prose",
    "counts_sentence",
    "claims_sentence",
]


#: Verdict of a figure on which the record's claims say nothing.
NO_CLAIM = "no claim"

#: Verdict of a figure when the record has no claims checklist at all.
NO_CHECKLIST = "no checklist"

#: Significant digits of our values beside a printed number (the record keeps ten).
OURS_DIGITS = 5


def record_schema():
    """The JSON Schema (draft 2020-12) of the record, shipped as package data.

    Returns
    -------
    dict

    Examples
    --------
    >>> schema = record_schema()
    >>> schema["required"], schema["$schema"]
    (['entries', 'figures', 'environment', 'claims'], 'https://json-schema.org/draft/2020-12/schema')
    """
    path = resources.files("fdsc.paper") / "data" / "record.schema.json"
    return json.loads(path.read_text(encoding="utf-8"))


def entry_link(entry, titles=None):
    """A link to the book page that computes an entry, named by the page's title (trusted HTML).

    Parameters
    ----------
    entry : dict
        A record entry; its ``chapter`` (a page's file stem), if any, is the link's target.
    titles : dict, optional
        ``{page: title}``; a page without one is named by its file stem in words.

    Returns
    -------
    str
        An HTML anchor, or ``""`` if the entry names no page.

    Examples
    --------
    >>> entry_link({"id": "K_f1", "chapter": "passive_controllers"})
    '<a href="passive_controllers.html">passive controllers</a>'
    >>> entry_link({"chapter": "gkyp_lemma"}, {"gkyp_lemma": "Lemma 1"}), entry_link({"id": "x"})
    ('<a href="gkyp_lemma.html">Lemma 1</a>', '')
    """
    page = entry.get("chapter")
    if not page:
        return ""
    title = (titles or {}).get(page, page.replace("_", " "))
    return f'<a href="{html.escape(page)}.html">{html.escape(title)}</a>'


def _distinct(a, b):
    for digits in range(4, 11):
        x, y = number_text(a, digits), number_text(b, digits)
        if x != y:
            return x, y
    return x, y


def inequality_cell(entry):
    """Whether an entry's printed inequality holds, with the two numbers (trusted HTML).

    Parameters
    ----------
    entry : dict
        A record entry; its ``inequality`` (``quantity``, ``bound``, ``holds``), if any.

    Returns
    -------
    str
        ``"holds: q < b"`` or ``"fails: q ≥ b"`` (enough digits to tell them apart), ``"—"`` if
        the printed value is not the bound of an inequality.

    Examples
    --------
    >>> inequality_cell({"inequality": {"quantity": 0.40279, "bound": 0.4025, "holds": False}})
    'fails: 0.4028 ≥ 0.4025'
    >>> inequality_cell({"inequality": {"quantity": 0.40279, "bound": 0.7125, "holds": True}})
    'holds: 0.4028 &lt; 0.7125'
    >>> inequality_cell({})
    '—'
    """
    ineq = entry.get("inequality")
    if not ineq:
        return "—"
    q, b = _distinct(ineq["quantity"], ineq["bound"])
    return html.escape(f"holds: {q} < {b}" if ineq["holds"] else f"fails: {q} ≥ {b}")


def _item(entry):
    """The entry's source in words, its note folded below it."""
    return f"<b>{html.escape(words(entry['source']))}</b><br>{note_html(entry['note'])}"


def printed_rows(record, titles=None):
    """One row per printed number (a number or a matrix the paper prints as a result), in words.

    Parameters
    ----------
    record : dict
        The reproduction record.
    titles : dict, optional
        ``{page: title}`` for the links (:func:`entry_link`).

    Returns
    -------
    list of dict
        ``id`` (not for display) and the trusted-HTML cells ``item`` (where the paper prints it,
        the reason for the verdict folded below), ``printed`` (every printed digit), ``ours``
        (:data:`OURS_DIGITS` significant digits), ``verdict`` (of the value), ``holds``
        (:func:`inequality_cell`) and ``link``, in the record's order.

    Raises
    ------
    ValueError
        If the record has no list of entries or an entry's verdict is unknown.

    Examples
    --------
    >>> rec = {"entries": [
    ...     {"id": "K", "source": "Sec. IV, K", "paper": [[0.1048, 15.0897]],
    ...      "recomputed": [[0.104946831, 15.09821467]], "verdict": "close", "note": "1e-3 off"},
    ...     {"id": "s", "source": "proof", "paper": "w >= 0", "recomputed": {}, "verdict": "match",
    ...      "note": "n"}]}
    >>> [(r["id"], r["verdict"], r["holds"]) for r in printed_rows(rec)]
    [('K', 'close', '—')]
    """
    return [{"id": e["id"], "item": _item(e), "printed": value_html(e["paper"]),
             "ours": value_html(e["recomputed"], OURS_DIGITS), "verdict": e["verdict"],
             "holds": inequality_cell(e), "link": entry_link(e, titles)}
            for e in entries_of(record) if entry_kind(e) == NUMBER]


def step_rows(record, titles=None):
    """One row per proof step or group of sentences checked against the paper's words.

    Parameters
    ----------
    record : dict
        The reproduction record.
    titles : dict, optional
        ``{page: title}`` for the links.

    Returns
    -------
    list of dict
        ``id`` (not for display), ``kind`` (:data:`~fdsc.paper.appendix.report_counts.PROOF_STEP`
        or :data:`~fdsc.paper.appendix.report_counts.SENTENCES`) and the trusted-HTML cells
        ``item`` (the source, the reason folded below), ``printed`` (the paper's words),
        ``verdict`` and ``link``; proof steps first, then the sentences.

    Examples
    --------
    >>> rec = {"entries": [{"id": "p", "source": "proof of Prop. 1", "paper": "w >= 0",
    ...                     "recomputed": {"grid": 8}, "verdict": "match", "note": "n"}]}
    >>> [(r["kind"], r["printed"]) for r in step_rows(rec)]
    [('proof step', 'w ≥ 0')]
    """
    entries = entries_of(record)
    return [{"id": e["id"], "kind": kind, "item": _item(e), "printed": value_html(e["paper"]),
             "verdict": e["verdict"], "link": entry_link(e, titles)}
            for kind in (PROOF_STEP, SENTENCES) for e in entries if entry_kind(e) == kind]


def input_rows(record, titles=None):
    """One row per printed input (model, bands, signals, parameters), used as printed.

    Parameters
    ----------
    record : dict
        The reproduction record.
    titles : dict, optional
        ``{page: title}`` for the links.

    Returns
    -------
    list of dict
        Trusted-HTML cells ``item`` (what, with how it is used folded below), ``printed`` (the
        values, folded) and ``link``.

    Examples
    --------
    >>> rec = {"entries": [{"id": "m", "source": "Sec. IV, model", "paper": {"A": [[1.0]]},
    ...                     "recomputed": {"A": [[1.0]]}, "verdict": "input", "note": "as printed"}]}
    >>> input_rows(rec)[0]["printed"].startswith("<details><summary>the printed values")
    True
    """
    return [{"item": _item(e), "printed": details("the printed values", value_html(e["paper"])),
             "link": entry_link(e, titles)}
            for e in entries_of(record) if entry_kind(e) == INPUT]


def figure_rows(record, titles=None):
    """Every paper figure: what it shows, a link to its page, its data, status and claims' verdict.

    Parameters
    ----------
    record : dict
        The reproduction record.
    titles : dict, optional
        ``{page: title}`` for the links.

    Returns
    -------
    list of dict
        One row per figure of :data:`fdsc.paper.record.PAPER_FIGURES` (paper Figs. 1–8):
        ``figure`` ("paper Fig. N"), ``number``, ``shows`` (in words), ``chapter``, ``link`` (an
        HTML anchor to ``<chapter>.html``, empty if no chapter redraws it), ``record_entry``,
        ``status`` (of :func:`fdsc.paper.record.figure_status`, e.g. ``not reproduced yet``) and
        ``verdict``: the worst verdict of the claims whose source names the figure,
        :data:`NO_CLAIM` if none does, :data:`NO_CHECKLIST` if the record has no claims.

    Examples
    --------
    >>> rec = {"entries": [], "figures": {"sigma_max": {"paper_figure": 3}},
    ...        "claims": [{"claim": "c", "source": "Sec. IV, text on paper Fig. 3", "verdict": "PARTLY"}]}
    >>> row = figure_rows(rec)[2]
    >>> row["link"], row["status"], row["verdict"]
    ('<a href="gkyp_lemma.html">gkyp lemma</a>', 'redrawn from recorded data', 'PARTLY')
    >>> figure_rows(rec)[0]["verdict"], figure_rows({"entries": [], "figures": {}})[6]["verdict"]
    ('no claim', 'no checklist')
    """
    claims = claims_of(record)
    rows = []
    for number, row in zip(PAPER_FIGURES, figure_status(record), strict=True):
        if claims is None:
            verdict = NO_CHECKLIST
        else:
            named = [c["verdict"] for c in claims if number in figures_named(c["source"])]
            verdict = worst_verdict(named, CLAIM_VERDICTS) if named else NO_CLAIM
        rows.append({**row, "shows": words(row["shows"]), "number": number,
                     "link": entry_link(row, titles), "verdict": verdict})
    return rows


def claim_rows(record):
    """The claims checklist, one row per claim (empty if the record has none).

    Parameters
    ----------
    record : dict
        The reproduction record.

    Returns
    -------
    list of dict
        Trusted-HTML cells ``claim`` (the paper's words, where, and how they are read, folded),
        ``value`` (in words, four significant digits), ``verdict`` and ``reason`` (folded when
        long).

    Raises
    ------
    ValueError
        If a claim's verdict is not one of :data:`fdsc.paper.shared.verdict.CLAIM_VERDICTS`.

    Examples
    --------
    >>> rec = {"claims": [{"claim": "FDSC is best for rho_p <= 0.2", "source": "paper Fig. 7",
    ...                    "measure": "crossover", "value": 0.04811, "verdict": "FAIL", "reason": "r"}]}
    >>> [(r["value"], r["verdict"]) for r in claim_rows(rec)]
    [('0.04811', 'FAIL')]
    """
    return [{"claim": f"“{html.escape(words(c['claim']))}”<br><small>{html.escape(c['source'])}</small>"
                      + details("how it is read", f"<p>{html.escape(words(c['measure']))}</p>"),
             "value": value_html(c["value"], 4), "verdict": c["verdict"], "reason": note_html(c["reason"])}
            for c in claims_of(record) or []]


def finding_rows(record, titles=None):
    """The findings the paper does not print: entries with verdict ``new``, but :data:`LAW_ENTRY`
    (shown beside the stored study by :func:`law_rows`).

    Parameters
    ----------
    record : dict
        The reproduction record.
    titles : dict, optional
        ``{page: title}`` for the links.

    Returns
    -------
    list of dict
        ``id`` (not for display) and the trusted-HTML cells ``item`` (what it is derived from),
        ``finding`` (the note, folded when long) and ``link``, in the record's order.

    Examples
    --------
    >>> rec = {"entries": [{"id": "x", "source": "s", "paper": None, "recomputed": 1, "verdict": "new",
    ...                     "note": "n"}]}
    >>> finding_rows(rec)
    [{'id': 'x', 'item': 's', 'finding': 'n', 'link': ''}]
    """
    return [{"id": e["id"], "item": html.escape(words(e["source"])), "finding": note_html(e["note"]),
             "link": entry_link(e, titles)}
            for e in entries_of(record) if entry_kind(e) == FINDING and e["id"] != LAW_ENTRY]


def errata(record):
    """The errata for the paper's authors: what it prints that is false or cannot be reproduced.

    A printed number that differs or cannot be reproduced, unless it is the bound of a printed
    inequality that holds (a true but loose bound is no error); a printed inequality that fails,
    whatever its value's verdict; a proof step that differs; then every claim that fails. The
    sentences on figures appear through their claims.

    Parameters
    ----------
    record : dict
        The reproduction record.

    Returns
    -------
    list of dict
        ``n`` and the trusted-HTML fields ``where``, ``printed``, ``ours`` (empty for words),
        ``verdict`` and ``why``, ``what`` (:func:`erratum_words`, plain text) and ``id`` (the record
        entry's; None for a claim), printed numbers and proof steps first in the record's order, then
        the failing claims.

    Raises
    ------
    ValueError
        If an entry's or a claim's verdict is unknown.

    Examples
    --------
    >>> rec = {"entries": [
    ...     {"id": "K_f3", "source": "Sec. IV, K", "paper": 0.2, "recomputed": 0.119, "verdict": "differs",
    ...      "note": "bisected"},
    ...     {"id": "e", "source": "Sec. IV, bound", "paper": 0.7125, "recomputed": 0.4028,
    ...      "verdict": "differs", "note": "n",
    ...      "inequality": {"statement": "s", "quantity": 0.4028, "bound": 0.7125, "holds": True}},
    ...     {"id": "b", "source": "Sec. IV", "paper": 1.0, "recomputed": 1.0, "verdict": "match",
    ...      "note": "equal"}],
    ...     "claims": [{"claim": "c", "source": "Abstract", "measure": "m", "value": 3.0,
    ...                 "verdict": "FAIL", "reason": "r"}]}
    >>> [(r["n"], r["where"], r["verdict"]) for r in errata(rec)]
    [(1, 'Sec. IV, K', 'differs'), (2, 'Abstract', 'FAIL')]
    """
    rows = []
    for e in entries_of(record):
        kind, ineq = entry_kind(e), e.get("inequality")
        bad = e["verdict"] in ("differs", "not reproducible")
        if kind == NUMBER and ((bad and not (ineq and ineq["holds"])) or (ineq and not ineq["holds"])):
            verdict = e["verdict"] + ("; the printed inequality fails" if ineq and not ineq["holds"] else "")
            rows.append({"where": html.escape(words(e["source"])), "printed": value_html(e["paper"]),
                         "ours": value_html(e["recomputed"], OURS_DIGITS), "verdict": verdict,
                         "why": note_html(e["note"]), "what": erratum_words(e), "id": e["id"]})
        elif kind == PROOF_STEP and bad:
            rows.append({"where": html.escape(words(e["source"])), "printed": value_html(e["paper"]),
                         "ours": "", "verdict": e["verdict"], "why": note_html(e["note"]),
                         "what": erratum_words(e), "id": e["id"]})
    rows += [{"where": html.escape(c["source"]), "printed": html.escape(words(c["claim"])),
              "ours": value_html(c["value"], 4), "verdict": c["verdict"], "why": note_html(c["reason"]),
              "what": erratum_words(c), "id": None}
             for c in claims_of(record) or [] if c["verdict"] == "FAIL"]
    return [{"n": k, **r} for k, r in enumerate(rows, start=1)]


def _fmt(x, digits=4):
    from fdsc.paper.shared.prose import num

    return num(float(x), digits)


def _bound_words(e):
    q = e.get("inequality")
    if not q:
        return _note_words(e)
    return (f"the band peak of its gain is {_fmt(q['quantity'])}, above the printed {_fmt(q['bound'])} "
            f"(×{_fmt(q['quantity'] / q['bound'], 4)})")


def _table1_words(e):
    off = [k for k, v in e["recomputed"].items() if isinstance(v, dict) and v.get("verdict") == "differs"]
    return (f"the time shares ({', '.join(off)}) do not follow in the simulations the monotone trends "
            "the table prints; its steady-state rows hold")


#: One line per erratum of the paper: what is wrong, its numbers read from the record entry.
ERRATUM_WORDS = {
    "prop1_factorizations": lambda e: (
        "its LF and HF products have the wrong sign (multiplied out they are ϖ_l² + ω² and −ω² − ϖ_h², "
        f"not the weights ϖ_l² − ω² and ω² − ϖ_h²: wrong at {e['recomputed']['LF']['wrong_sign']} and "
        f"{e['recomputed']['HF']['wrong_sign']} of {e['recomputed']['grid_points']} frequencies); the "
        "real factorizations hold"),
    "lemma1_gamma_squared": lambda e: "the energy bound the LMI gives is γ², not γ",
    "gamma_slip_in_band": lambda e: (
        f"the objectives compare an energy ratio with γ where γ² is meant: a tone in the HF range "
        f"reaches {_fmt(e['recomputed']['energy_ratio'])} > γ = {_fmt(e['recomputed']['gamma'])}"),
    "K_f3": lambda e: "σ and ε of its design are not printed, so the gain cannot be recomputed",
    "bound_f1": _bound_words, "bound_f2": _bound_words, "bound_f3": _bound_words,
    "prop1_checks": lambda e: (
        f"fails in {e['recomputed']['failed']} of {e['recomputed']['failed'] + e['recomputed']['passed']} "
        "checks: with MF as the in-band range, and on windows that hold the transient"),
    "table1_checks": _table1_words,
    "Q_1": lambda e: "γ_tol and the scale of the Q's, which their design needs, are not printed",
    "Q_2": lambda e: "γ_tol and the scale of the Q's, which their design needs, are not printed",
    "thm1_lyapunov_jumps": lambda e: (
        f"the proof never compares V across a switch: V jumps up at "
        f"{_fmt(100 * e['recomputed']['frac_up'], 2)} % of the switches, by up to "
        f"×{_fmt(e['recomputed']['max_ratio'], 3)}"),
    "thm1_statement1_false": lambda e: (
        "false: two Hurwitz modes whose Q's satisfy the LMIs diverge by "
        f"×{_fmt(e['recomputed']['multiplier'], 4)} "
        "per turn of the printed law, without sliding"),
    "closed_loop_output_matrix": lambda e: "C + B₂K_σ is undefined (its dimensions); C + D₂K_σ is meant",
    "mixed_crossover": lambda e: (
        f"FDSC's energy reaches PassC-LF's at ρ_p = {_fmt(e['recomputed']['PassC-LF'], 3)}, not at 0.2"),
}


def erratum_words(item) -> str:
    """What is wrong, in one line: for a record entry from :data:`ERRATUM_WORDS` (by its id), for a
    failing claim its measure and our value.

    Parameters
    ----------
    item : dict
        A record entry (with ``id``) or a claim (with ``claim`` and ``measure``).

    Returns
    -------
    str
        Plain text.

    Notes
    -----
    An entry without a line in :data:`ERRATUM_WORDS` gets the first sentence of its note (a test
    checks that every erratum of the book's record has its own line).
    """
    if "claim" in item:
        v = item["value"]
        ours = (", ".join(f"{words(k)}: {_fmt(x, 3)}" for k, x in v.items()) if isinstance(v, dict)
                else _fmt(v, 4))
        measure = words(item["measure"]).split(";")[0]
        return f"“{words(item['claim'])}” does not hold (read as: {measure}; ours {ours})"
    if item.get("id") not in ERRATUM_WORDS:
        return _note_words(item)
    return ERRATUM_WORDS[item["id"]](item)


def _note_words(item):
    """The first sentence of an entry's note, as plain text."""
    note = words(str(item.get("note", ""))).strip()
    first = note.split(". ", 1)[0].rstrip(".")
    return first if len(first) <= 300 else first[:297].rsplit(" ", 1)[0] + " …"


def errata_summary(record) -> str:
    """The errata of :func:`errata` as a short numbered Markdown list (where, the verdict, and what
    is wrong in one line), the same items in the same order, for the book's summary page.

    Parameters
    ----------
    record : dict

    Returns
    -------
    str

    Examples
    --------
    >>> rec = {"entries": [{"id": "closed_loop_output_matrix", "source": "Sec. III-B, eq. (32)",
    ...                     "paper": "C + B2 K", "recomputed": {}, "verdict": "differs", "note": "n",
    ...                     "kind": "proof step"}]}
    >>> errata_summary(rec)
    '1. Sec. III-B, eq. (32): *differs*: C + B₂K_σ is undefined (its dimensions); C + D₂K_σ is meant'
    """
    return "\n".join(f"{r['n']}. {html.unescape(r['where'])}: *{r['verdict']}*: {r['what']}"
                     for r in errata(record))
