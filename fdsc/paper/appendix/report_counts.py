"""The reproduction report's counts: what kind of thing each entry compares, and the counts the
book quotes, each over one kind.

A record entry beside a printed value is one of three kinds (:func:`entry_kind`): a **printed
number** (a number or a matrix the paper prints as a result), a **proof step** (a step of a proof,
a statement of a lemma, proposition, theorem, table or remark, or an expression the paper prints,
given as words and checked numerically)
or **sentences** on a paper figure (decided one by one in the claims checklist). The counts of
printed numbers have two axes (:func:`printed_counts`): the verdict of the value (match, close,
differs, not reproducible) and, for a printed inequality, whether it holds; proof steps, sentences
and claims are counted apart.
"""

import re
from collections import Counter
from numbers import Real

import numpy as np

from fdsc.paper.appendix.report_values import words
from fdsc.paper.record import figure_status
from fdsc.paper.shared.prose import count, excess
from fdsc.paper.shared.verdict import CLAIM_VERDICTS, VERDICTS

__all__ = [
    "NUMBER",
    "PROOF_STEP",
    "SENTENCES",
    "INPUT",
    "FINDING",
    "KINDS",
    "COMPARED",
    "figures_named",
    "entry_kind",
    "summary",
    "printed_counts",
    "counts_prose",
    "counts_sentence",
    "claims_sentence",
]

#: The kinds of entries (:func:`entry_kind`).
NUMBER, PROOF_STEP, SENTENCES, INPUT, FINDING = ("printed number", "proof step", "sentences",
                                                 "input", "finding")
KINDS = (NUMBER, PROOF_STEP, SENTENCES, INPUT, FINDING)

#: The verdicts of an entry compared with a printed value (not ``input``, not ``new``).
COMPARED = VERDICTS[:4]


_FIGURES = re.compile(r"\bpaper Figs?\.\s*(\d+(?:\s*(?:,|and|–|-)\s*\d+)*)\b")


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


def entries_of(record):
    """The record's entries, their verdicts checked.

    Raises
    ------
    ValueError
        If the record is not a dict with a list of entries, or a verdict is unknown.
    """
    entries = record.get("entries") if isinstance(record, dict) else None
    if not isinstance(entries, list):
        raise ValueError("record must be a dict with a list 'entries' (the reproduction record), but found "
                         f"{type(record).__name__}")
    return _check_verdicts(entries, VERDICTS, "entry", "id")


def claims_of(record):
    """The record's claims (verdicts checked), or None when it has no checklist."""
    claims = record.get("claims")
    return None if claims is None else _check_verdicts(claims, CLAIM_VERDICTS, "claim", "claim")


def _numeric(value):
    if isinstance(value, np.ndarray):
        return value.dtype.kind in "iuf" and value.size > 0
    if isinstance(value, list | tuple):
        return bool(value) and all(_numeric(v) for v in value)
    return isinstance(value, Real | np.generic) and not isinstance(value, bool | str)


def entry_kind(entry):
    """What an entry compares: a printed number, a proof step, sentences, an input or a finding.

    Parameters
    ----------
    entry : dict
        A record entry.

    Returns
    -------
    str
        :data:`INPUT` (verdict ``input``), :data:`FINDING` (verdict ``new``), :data:`NUMBER` (the
        printed value is a number or an array of numbers), :data:`SENTENCES` (words whose source
        names a paper figure: the paper's sentences on its simulations) or :data:`PROOF_STEP`
        (any other words: a step of a proof, a statement of a lemma, proposition, theorem, table or
        remark, or an expression the paper prints).

    Examples
    --------
    >>> entry_kind({"verdict": "close", "paper": [[0.1048, 15.0897]], "source": "Sec. IV, K_f1"})
    'printed number'
    >>> entry_kind({"verdict": "differs", "paper": "w >= 0 on Omega_i", "source": "proof of Prop. 1"})
    'proof step'
    >>> entry_kind({"verdict": "differs", "paper": ["the range is smallest"],
    ...             "source": "Sec. IV, text on paper Fig. 4"})
    'sentences'
    """
    if entry["verdict"] == "input":
        return INPUT
    if entry["verdict"] == "new":
        return FINDING
    if _numeric(entry["paper"]):
        return NUMBER
    return SENTENCES if figures_named(entry.get("source", "")) else PROOF_STEP


def summary(record):
    """Counts per verdict of the entries and of the claims, per kind, and per figure status.

    Parameters
    ----------
    record : dict
        The reproduction record.

    Returns
    -------
    dict
        ``entries``: ``{verdict: count}`` over :data:`~fdsc.paper.shared.verdict.VERDICTS` (zeros
        included, in that order); ``kinds``: ``{kind: count}`` over :data:`KINDS`; ``claims``:
        ``{verdict: count}`` over :data:`~fdsc.paper.shared.verdict.CLAIM_VERDICTS`, or None
        without a checklist; ``figures``: ``{status: count}``; ``n_entries``, ``n_claims`` (0
        without a checklist) and ``n_figures``.

    Raises
    ------
    ValueError
        If the record has no list of entries, or a verdict is unknown.

    Examples
    --------
    >>> s = summary({"entries": [{"id": "a", "verdict": "match", "paper": 1.0, "source": "s"},
    ...                          {"id": "b", "verdict": "new", "paper": None, "source": "s"}],
    ...              "figures": {}})
    >>> s["entries"]["match"], s["kinds"]["finding"], s["claims"], s["n_figures"]
    (1, 1, None, 8)
    """
    entries, claims = entries_of(record), claims_of(record)
    by_entry = Counter(e["verdict"] for e in entries)
    by_kind = Counter(entry_kind(e) for e in entries)
    by_claim = None if claims is None else Counter(c["verdict"] for c in claims)
    figures = figure_status(record)
    return {"entries": {v: by_entry[v] for v in VERDICTS}, "n_entries": len(entries),
            "kinds": {k: by_kind[k] for k in KINDS},
            "claims": None if by_claim is None else {v: by_claim[v] for v in CLAIM_VERDICTS},
            "n_claims": 0 if claims is None else len(claims),
            "figures": dict(Counter(r["status"] for r in figures)), "n_figures": len(figures)}


def printed_counts(record):
    """The counts of what the paper prints, each over one kind.

    Parameters
    ----------
    record : dict
        The reproduction record.

    Returns
    -------
    dict
        ``numbers``: ``{verdict: count}`` of the printed numbers over :data:`COMPARED`;
        ``inequalities``: ``{"hold": n, "fail": n}`` of the printed numbers that are the bound of
        a printed inequality (an entry's ``inequality``), and ``fail_printed``: their printed
        values where the inequality fails; ``fail_by``: for each of those, what it bounds (the
        inequality's ``subject``, else the entry's source) and how far the quantity lies above
        it (:func:`fdsc.paper.shared.prose.excess`); ``proof_steps``: ``{verdict: count}``; ``sentences``:
        the entries of sentences on figures; ``claims``: ``{verdict: count}`` of the checklist
        (None without one); ``inputs``, ``findings``.

    Examples
    --------
    >>> rec = {"entries": [
    ...     {"id": "b", "verdict": "close", "paper": 0.4025, "source": "Sec. IV",
    ...      "inequality": {"statement": "s", "quantity": 0.4028, "bound": 0.4025, "holds": False}},
    ...     {"id": "e", "verdict": "differs", "paper": 0.7125, "source": "Sec. IV",
    ...      "inequality": {"statement": "s", "quantity": 0.4028, "bound": 0.7125, "holds": True}},
    ...     {"id": "p", "verdict": "match", "paper": "w >= 0", "source": "proof"}]}
    >>> c = printed_counts(rec)
    >>> c["numbers"]["close"], c["numbers"]["differs"], c["inequalities"], c["fail_printed"]
    (1, 1, {'hold': 1, 'fail': 1}, [0.4025])
    >>> c["fail_by"]
    [('Sec. IV', '0.07 % above')]
    >>> c["proof_steps"]["match"], c["claims"]
    (1, None)
    """
    entries, claims = entries_of(record), claims_of(record)
    kind = [(entry_kind(e), e) for e in entries]
    numbers = [e for k, e in kind if k == NUMBER]
    steps = [e for k, e in kind if k == PROOF_STEP]
    ineq = [e for e in numbers if e.get("inequality")]
    return {"numbers": {v: sum(e["verdict"] == v for e in numbers) for v in COMPARED},
            "inequalities": {"hold": sum(bool(e["inequality"]["holds"]) for e in ineq),
                             "fail": sum(not e["inequality"]["holds"] for e in ineq)},
            "fail_printed": [e["paper"] for e in ineq if not e["inequality"]["holds"]],
            "fail_by": [(e["inequality"].get("subject") or words(e["source"]),
                         excess(e["inequality"]["quantity"], e["inequality"]["bound"]))
                        for e in ineq if not e["inequality"]["holds"]],
            "proof_steps": {v: sum(e["verdict"] == v for e in steps) for v in COMPARED},
            "sentences": sum(k == SENTENCES for k, _ in kind),
            "claims": None if claims is None else {v: sum(c["verdict"] == v for c in claims)
                                                   for v in CLAIM_VERDICTS},
            "inputs": sum(k == INPUT for k, _ in kind), "findings": sum(k == FINDING for k, _ in kind)}


def _and(items):
    items = [str(x) for x in items]
    if len(items) < 2:
        return items[0] if items else "none"
    return ", ".join(items[:-1]) + " and " + items[-1]


def counts_prose(record):
    """The counts as the book's prose quotes them (for :func:`fdsc.paper.shared.prose.glue_numbers`).

    Parameters
    ----------
    record : dict
        The reproduction record.

    Returns
    -------
    dict
        ``{name: text}``: ``n_numbers`` and ``numbers_match``, ``numbers_close``,
        ``numbers_differ``, ``numbers_not_reproducible``; ``n_inequalities``,
        ``inequalities_hold``, ``inequalities_fail``, ``inequalities_fail_printed``,
        ``inequalities_fail_by`` (what each failing inequality bounds and by how much its
        quantity exceeds the printed bound, e.g. "K_f1 ×1.09, K_f2 0.07 % above"); ``n_steps``
        and ``steps_match``, ``steps_close``, ``steps_differ``, ``steps_not_reproducible``;
        ``n_sentences``; ``n_claims``, ``claims_pass``, ``claims_partly``, ``claims_fail`` (``0``
        without a checklist); ``n_inputs``, ``n_findings``.

    Examples
    --------
    >>> rec = {"entries": [{"id": "k", "verdict": "close", "paper": 1.0, "source": "Sec. IV"}]}
    >>> p = counts_prose(rec)
    >>> p["n_numbers"], p["numbers_close"], p["n_inequalities"], p["inequalities_fail_printed"]
    ('1', '1', '0', 'none')
    """
    c = printed_counts(record)
    n, s, ineq = c["numbers"], c["proof_steps"], c["inequalities"]
    claims = c["claims"] or dict.fromkeys(CLAIM_VERDICTS, 0)
    out = {"n_numbers": count(sum(n.values())), "n_inequalities": count(sum(ineq.values())),
           "inequalities_hold": count(ineq["hold"]), "inequalities_fail": count(ineq["fail"]),
           "inequalities_fail_printed": _and(c["fail_printed"]),
           "inequalities_fail_by": _and([f"{what} {by}" for what, by in c["fail_by"]]),
           "n_steps": count(sum(s.values())), "n_sentences": count(c["sentences"]),
           "n_claims": count(sum(claims.values())), "claims_pass": count(claims["PASS"]),
           "claims_partly": count(claims["PARTLY"]), "claims_fail": count(claims["FAIL"]),
           "n_inputs": count(c["inputs"]), "n_findings": count(c["findings"])}
    for verdict, word in zip(COMPARED, ("match", "close", "differ", "not_reproducible"), strict=True):
        out[f"numbers_{word}"] = count(n[verdict])
        out[f"steps_{word}"] = count(s[verdict])
    return out


def _n(k, one, many):
    return f"{count(k)} {one if k == 1 else many}"


def counts_sentence(record):
    """The counts in two sentences, each over one kind (the report's and the landing page's answer).

    Parameters
    ----------
    record : dict
        The reproduction record.

    Returns
    -------
    str
        Markdown.

    Examples
    --------
    >>> rec = {"entries": [
    ...     {"id": "b", "verdict": "close", "paper": 0.4025, "source": "Sec. IV",
    ...      "inequality": {"statement": "s", "quantity": 0.4028, "bound": 0.4025, "holds": False}},
    ...     {"id": "p", "verdict": "match", "paper": "w >= 0", "source": "proof"}]}
    >>> print(counts_sentence(rec))  # doctest: +NORMALIZE_WHITESPACE
    Of the 1 number the paper prints as a result, 0 match ours, 1 is close (within 1 %), 0 differ
    and 0 cannot be reproduced; it is the bound of a printed inequality, which fails (the quantity
    against the printed bound: Sec. IV 0.07 % above). Checked apart: 1 proof step, of which 1
    holds as printed.
    """
    c = printed_counts(record)
    n, ineq, steps = c["numbers"], c["inequalities"], c["proof_steps"]
    total, n_ineq, n_steps = sum(n.values()), sum(ineq.values()), sum(steps.values())
    what = _n(total, "number the paper prints as a result", "numbers the paper prints as results")
    text = (f"Of the {what}, "
            f"{count(n['match'])} match ours, {_n(n['close'], 'is', 'are')} close (within 1 %), "
            f"{count(n['differs'])} differ and {count(n['not reproducible'])} cannot be reproduced")
    by = _and([f"{what} {amount}" for what, amount in c["fail_by"]])
    by = f" (the quantity against the printed bound: {by})" if c["fail_by"] else ""
    if n_ineq == 1:
        text += f"; it is the bound of a printed inequality, which {'holds' if ineq['hold'] else 'fails'}"
    elif n_ineq:
        text += (f"; {count(n_ineq)} are the bounds of printed inequalities, of which "
                 f"{_n(ineq['hold'], 'holds', 'hold')} and {_n(ineq['fail'], 'fails', 'fail')}")
    text += by
    text += f". Checked apart: {_n(n_steps, 'proof step', 'proof steps')}, of which "
    text += f"{_n(steps['match'], 'holds', 'hold')} as printed"
    if c["claims"] is not None:
        k = c["claims"]
        text += (f"; {_n(sum(k.values()), 'claim', 'claims')} about the simulations, of which "
                 f"{count(k['PASS'])} hold, {count(k['PARTLY'])} hold in part and {count(k['FAIL'])} fail")
    return text + "."


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
