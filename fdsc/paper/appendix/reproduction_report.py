"""The reproduction report: the whole record as table rows (the book's chapter ``report``).

Pure functions of a record dict, as :func:`fdsc.paper.record.reproduction_record` returns it or as
``python -m fdsc reproduce`` writes it: the printed numbers beside ours, every paper figure with
its page, status and the verdict of the claims made on it, the claims checklist, the findings the
paper does not print, and the counts per verdict. A record without claims or without a figure's
data is rendered as such (no row is dropped, the absence is stated). The record's format is the
JSON Schema ``fdsc/paper/data/record.schema.json`` (:func:`record_schema`).
"""

import html
import json
import re
from collections import Counter
from importlib import resources

from fdsc.paper.record import PAPER_FIGURES, figure_status
from fdsc.paper.shared.report import compact
from fdsc.paper.shared.verdict import CLAIM_VERDICTS, VERDICTS, worst_verdict

__all__ = [
    "NO_CLAIM",
    "NO_CHECKLIST",
    "record_schema",
    "figures_named",
    "printed_rows",
    "full_value",
    "entry_link",
    "figure_rows",
    "claim_rows",
    "finding_rows",
    "errata",
    "summary",
    "claims_sentence",
]


#: Verdict of a figure on which the record's claims say nothing.
NO_CLAIM = "no claim"

#: Verdict of a figure when the record has no claims checklist at all.
NO_CHECKLIST = "no checklist"

_FIGURES = re.compile(r"\bpaper Figs?\.\s*(\d+(?:\s*(?:,|and|–|-)\s*\d+)*)\b")


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


def figures_named(source):
    """The paper figures a source names ("paper Fig. 7", "paper Figs. 4–6", "paper Figs. 7 and 8").

    Parameters
    ----------
    source : str
        A claim's or an entry's ``source``.

    Returns
    -------
    set of int

    Examples
    --------
    >>> figures_named("Sec. IV, text on paper Fig. 7"), figures_named("paper Fig. 10")
    ({7}, {10})
    >>> sorted(figures_named("paper Figs. 4–6 and the Abstract")), figures_named("Abstract")
    ([4, 5, 6], set())
    """
    found = set()
    for group in _FIGURES.findall(source):
        for part in re.split(r"\s*(?:,|and)\s*", group):
            ends = [int(x) for x in re.split(r"\s*[–-]\s*", part)]
            found.update(range(ends[0], ends[-1] + 1))
    return found


def _check_verdicts(items, allowed, kind, key):
    for item in items:
        if item.get("verdict") not in allowed:
            raise ValueError(f"record: {kind} {item.get(key)!r} has verdict {item.get('verdict')!r}, "
                             f"expected one of {allowed}")
    return items


def _entries(record):
    entries = record.get("entries") if isinstance(record, dict) else None
    if not isinstance(entries, list):
        raise ValueError("record must be a dict with a list 'entries' (the reproduction record), but found "
                         f"{type(record).__name__}")
    return _check_verdicts(entries, VERDICTS, "entry", "id")


def _claims(record):
    """The record's claims, or None when it has no checklist."""
    claims = record.get("claims")
    return None if claims is None else _check_verdicts(claims, CLAIM_VERDICTS, "claim", "claim")


def printed_rows(record):
    """One row per entry whose paper value is printed and compared (verdict not ``new``): the
    printed value beside ours.

    Parameters
    ----------
    record : dict
        The reproduction record.

    Returns
    -------
    list of dict
        ``id, source, paper, ours, verdict, reason`` (values as compact text, see
        :func:`fdsc.paper.shared.report.compact`), in the record's order.

    Raises
    ------
    ValueError
        If the record has no list of entries or an entry's verdict is unknown.

    Examples
    --------
    >>> rec = {"entries": [
    ...     {"id": "K", "source": "Sec. IV", "paper": [[0.1048, 15.0897]],
    ...      "recomputed": [[0.104946831, 15.09821467]], "verdict": "close", "note": "1e-3 off"},
    ...     {"id": "x", "source": "ours", "paper": None, "recomputed": 1, "verdict": "new", "note": "n"}]}
    >>> [(r["id"], r["paper"], r["ours"]) for r in printed_rows(rec)]
    [('K', '[[0.1048, 15.09]]', '[[0.1049, 15.1]]')]
    """
    return [{"id": e["id"], "entry": entry_link(e), "source": e["source"],
             "paper": compact(e["paper"]), "paper_full": full_value(e["paper"]),
             "ours": compact(e["recomputed"]), "ours_full": full_value(e["recomputed"]),
             "verdict": e["verdict"], "reason": e["note"]}
            for e in _entries(record) if e["paper"] is not None and e["verdict"] != "new"]


def full_value(value):
    """A record value as HTML for a table cell, never cut: numbers to ten significant digits
    (as the record keeps them), so a printed number shows every digit printed; a long value
    (a matrix, a list, a dict) shows its short form (:func:`fdsc.paper.shared.report.compact`) with the
    whole value in a ``<details>`` element below it.

    Parameters
    ----------
    value : object
        A record value.

    Returns
    -------
    str
        Trusted HTML (every part escaped).

    Examples
    --------
    >>> full_value(15.0897)
    '15.0897'
    >>> full_value(list(range(30))).startswith("<details><summary>[0, 1, 2, 3, 4, 5, …] (30 values)")
    True
    """
    whole = compact(value, digits=10, max_items=10**6, max_chars=10**9)
    short = compact(value)
    if len(whole) <= 60 or whole == short:
        return html.escape(whole)
    return (f"<details><summary>{html.escape(short)}</summary>"
            f"<span style='overflow-wrap:anywhere'>{html.escape(whole)}</span></details>")


def entry_link(entry):
    """The entry's id as a link to the book page that computes it (trusted HTML).

    Parameters
    ----------
    entry : dict
        A record entry; its ``chapter`` (a page's file stem), if any, is the link's target.

    Returns
    -------
    str
        An HTML anchor, or the escaped id if the entry names no page.

    Examples
    --------
    >>> entry_link({"id": "K_f1", "chapter": "passive_controllers"})
    '<a href="passive_controllers.html">K_f1</a>'
    >>> entry_link({"id": "x"})
    'x'
    """
    page = entry.get("chapter")
    name = html.escape(entry["id"])
    return f'<a href="{html.escape(page)}.html">{name}</a>' if page else name


def figure_rows(record):
    """Every paper figure: what it shows, a link to its page, its data, status and claims' verdict.

    Parameters
    ----------
    record : dict
        The reproduction record.

    Returns
    -------
    list of dict
        One row per figure of :data:`fdsc.paper.record.PAPER_FIGURES` (paper Figs. 1–8):
        ``figure`` ("paper Fig. N"), ``number``, ``shows``, ``chapter``, ``link`` (an HTML anchor
        to ``<chapter>.html``, empty if no chapter redraws it), ``record_entry``, ``status`` (of
        :func:`fdsc.paper.record.figure_status`, e.g. ``not reproduced yet``) and ``verdict``: the
        worst verdict of the claims whose source names the figure, :data:`NO_CLAIM` if none does,
        :data:`NO_CHECKLIST` if the record has no claims.

    Examples
    --------
    >>> rec = {"entries": [], "figures": {"sigma_max": {"paper_figure": 3}},
    ...        "claims": [{"claim": "c", "source": "Sec. IV, text on paper Fig. 3", "verdict": "PARTLY"}]}
    >>> row = figure_rows(rec)[2]
    >>> row["link"], row["status"], row["verdict"]
    ('<a href="gkyp_lemma.html">gkyp_lemma</a>', 'redrawn from recorded data', 'PARTLY')
    >>> figure_rows(rec)[0]["verdict"], figure_rows({"entries": [], "figures": {}})[6]["verdict"]
    ('no claim', 'no checklist')
    """
    claims = _claims(record)
    rows = []
    for number, row in zip(PAPER_FIGURES, figure_status(record), strict=True):
        chapter = row["chapter"]
        link = f'<a href="{html.escape(chapter)}.html">{html.escape(chapter)}</a>' if chapter else ""
        if claims is None:
            verdict = NO_CHECKLIST
        else:
            named = [c["verdict"] for c in claims if number in figures_named(c["source"])]
            verdict = worst_verdict(named, CLAIM_VERDICTS) if named else NO_CLAIM
        rows.append({**row, "number": number, "link": link, "verdict": verdict})
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
        ``claim, source, measure, value`` (compact text), ``verdict, reason``.

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
    return [{"claim": c["claim"], "source": c["source"], "measure": c["measure"],
             "value": compact(c["value"]), "verdict": c["verdict"], "reason": c["reason"]}
            for c in _claims(record) or []]


def finding_rows(record):
    """The findings the paper does not print: entries with verdict ``new``.

    Parameters
    ----------
    record : dict
        The reproduction record.

    Returns
    -------
    list of dict
        ``id, source, note``, in the record's order.

    Examples
    --------
    >>> rec = {"entries": [{"id": "x", "source": "s", "paper": None, "recomputed": 1, "verdict": "new",
    ...                     "note": "n"}]}
    >>> finding_rows(rec)
    [{'id': 'x', 'entry': 'x', 'source': 's', 'note': 'n'}]
    """
    return [{"id": e["id"], "entry": entry_link(e), "source": e["source"], "note": e["note"]}
            for e in _entries(record) if e["verdict"] == "new"]


def errata(record):
    """The errata for the paper's authors: every printed number that differs or cannot be
    reproduced, then every claim that fails, each with what decides it.

    Parameters
    ----------
    record : dict
        The reproduction record.

    Returns
    -------
    list of dict
        ``n, where, printed, ours, verdict, why`` (values as compact text), printed numbers first
        in the record's order, then the failing claims.

    Raises
    ------
    ValueError
        If an entry's or a claim's verdict is unknown.

    Examples
    --------
    >>> rec = {"entries": [
    ...     {"id": "a", "source": "Sec. IV, K", "paper": 0.2, "recomputed": 0.119, "verdict": "differs",
    ...      "note": "bisected"},
    ...     {"id": "b", "source": "Sec. IV", "paper": 1.0, "recomputed": 1.0, "verdict": "match",
    ...      "note": "equal"}],
    ...     "claims": [{"claim": "c", "source": "Abstract", "measure": "m", "value": 3.0,
    ...                 "verdict": "FAIL", "reason": "r"}]}
    >>> [(r["n"], r["where"], r["verdict"]) for r in errata(rec)]
    [(1, 'Sec. IV, K', 'differs'), (2, 'Abstract', 'FAIL')]
    """
    rows = [{"where": e["source"], "printed": compact(e["paper"]), "ours": compact(e["recomputed"]),
             "verdict": e["verdict"], "why": e["note"]}
            for e in _entries(record) if e["verdict"] in ("differs", "not reproducible")]
    rows += [{"where": c["source"], "printed": c["claim"], "ours": compact(c["value"]),
              "verdict": c["verdict"], "why": c["reason"]}
             for c in _claims(record) or [] if c["verdict"] == "FAIL"]
    return [{"n": k, **r} for k, r in enumerate(rows, start=1)]


def summary(record):
    """Counts per verdict of the entries and of the claims, and per status of the figures.

    Parameters
    ----------
    record : dict
        The reproduction record.

    Returns
    -------
    dict
        ``entries``: ``{verdict: count}`` over :data:`fdsc.paper.shared.verdict.VERDICTS` (zeros
        included, in that order); ``claims``: ``{verdict: count}`` over
        :data:`fdsc.paper.shared.verdict.CLAIM_VERDICTS`, or None if the record has no checklist;
        ``figures``: ``{status: count}`` over the paper's figures; ``n_entries``, ``n_claims``
        (0 without a checklist) and ``n_figures``.

    Raises
    ------
    ValueError
        If the record has no list of entries, or a verdict is unknown.

    Examples
    --------
    >>> s = summary({"entries": [{"id": "a", "verdict": "match"}, {"id": "b", "verdict": "new"}],
    ...              "figures": {}})
    >>> s["entries"]["match"], s["entries"]["new"], s["claims"], s["n_figures"]
    (1, 1, None, 8)
    """
    entries, claims = _entries(record), _claims(record)
    by_entry = Counter(e["verdict"] for e in entries)
    by_claim = None if claims is None else Counter(c["verdict"] for c in claims)
    figures = figure_status(record)
    return {"entries": {v: by_entry[v] for v in VERDICTS}, "n_entries": len(entries),
            "claims": None if by_claim is None else {v: by_claim[v] for v in CLAIM_VERDICTS},
            "n_claims": 0 if claims is None else len(claims),
            "figures": dict(Counter(r["status"] for r in figures)), "n_figures": len(figures)}


def claims_sentence(record):
    """One Markdown sentence on the claims checklist: its counts per verdict, or that it is missing.

    Parameters
    ----------
    record : dict
        The reproduction record.

    Returns
    -------
    str

    Examples
    --------
    >>> claims_sentence({"entries": [], "figures": {}, "claims": [
    ...     {"claim": "c", "source": "Abstract", "verdict": "PARTLY"}]})
    'The checklist holds 1 claims: 0 PASS, 1 PARTLY and 0 FAIL.'
    >>> claims_sentence({"entries": [], "figures": {}})[:45]
    'The record holds **no claims checklist**: the'
    """
    counts = summary(record)
    if counts["claims"] is None:
        return ("The record holds **no claims checklist**: the paper's claims are not checked in this "
                "build.")
    c = counts["claims"]
    return (f"The checklist holds {counts['n_claims']} claims: {c['PASS']} PASS, {c['PARTLY']} PARTLY "
            f"and {c['FAIL']} FAIL.")
