"""The reproduction report's numbers of the law on the disturbance estimate: one source for them.

The landing page, the chapters and the report give the law's numbers from the stored study
(:func:`fdsc.paper.pays.disturbance_law.load_full`, computed at a recorded commit); the record
recomputes the same procedure on the first few of its draws when the book is built, as a check.
:func:`law_rows` sets the two side by side, each labelled.
"""

import html

from fdsc.paper.appendix.report_counts import entries_of
from fdsc.paper.shared.prose import count, headroom_pct, pct, share_ci, times, times_ci

__all__ = ["LAW_ENTRY", "law_rows", "ladder_rows"]

#: The entry of the law on the disturbance estimate: the build-time check of the stored study,
#: shown beside it (:func:`law_rows`), not among the findings.
LAW_ENTRY = "supervisor"

_LAW_EXAMPLES = {"aircraft": "aircraft", "generic": "generic example"}


def _with_interval(median, per_draw):
    """``×m`` or, where the per-draw ratios are at hand, ``×m [low, high]`` (bootstrap 95 %)."""
    if per_draw is None or len(per_draw) < 2:
        return times(median)
    from fdsc.paper.shared.stats import bootstrap_median

    _m, low, high = bootstrap_median(per_draw)
    return times_ci({"median": median, "low": low, "high": high})


def _law_row(study, example, r):
    return {"study": study, "example": _LAW_EXAMPLES.get(example, example),
            "scored": count(int(r["draws_test"])), "chosen": html.escape(r["fixed_in_advance"]),
            "median": _with_interval(r["median_ratio_vs_fixed_in_advance"],
                                     r.get("ratio_vs_fixed_in_advance")),
            "wins": pct(r["win_rate_vs_fixed_in_advance"]),
            "clairvoyant": _with_interval(r["reference_median_ratio"],
                                          r.get("reference_ratio", {}).get(r.get("reference_family")))}


def law_rows(record, full=None, *, fresh=True):
    """The law on the disturbance estimate per example: the stored study's numbers, labelled with
    its commit; where this checkout has no stored study, the record's build-time check instead.

    Parameters
    ----------
    record : dict
        The reproduction record (its entry :data:`LAW_ENTRY`: the check).
    full : dict, optional
        The stored study (:func:`fdsc.paper.pays.disturbance_law.load_full`); None if absent
        (then the rows are the record's build-time check).
    fresh : bool, optional
        The sources of this build are those the stored study was computed with.

    Returns
    -------
    list of dict
        Trusted-HTML cells ``study`` (which numbers: the stored study with its draws and commit,
        or the build-time check with its draws), ``example``, ``scored`` (draws scored),
        ``chosen`` (the fixed controller chosen in advance), ``median`` (the law's median energy
        over that controller's, with its bootstrap 95 % interval where the per-draw ratios are
        stored), ``wins`` (share of scored draws with less energy) and
        ``clairvoyant`` (the median of clairvoyant switching at the breaks, with its interval
        likewise).

    Examples
    --------
    >>> one = {"draws_test": 6, "draws_train": 6, "fixed_in_advance": "tuned",
    ...        "median_ratio_vs_fixed_in_advance": 0.96, "win_rate_vs_fixed_in_advance": 1.0,
    ...        "reference_median_ratio": 0.959}
    >>> rec = {"entries": [{"id": "supervisor", "verdict": "new", "recomputed": {"aircraft": one}}]}
    >>> full = {"n": 500, "commit": "048c47d821e7", "aircraft": dict(one, draws_test=250)}
    >>> [(r["scored"], r["median"]) for r in law_rows(rec, full)]
    [('250', '×0.960')]
    >>> law_rows(rec, full)[0]["study"]
    'stored study: 500 draws per example, computed at commit 048c47d'
    >>> [(r["scored"], r["median"]) for r in law_rows(rec)]
    [('6', '×0.960')]
    """
    rows = []
    if full is not None:
        label = (f"stored study: {count(int(full['n']))} draws per example, computed at commit "
                 f"{html.escape(str(full['commit']).split()[0][:7])}"
                 + ("" if fresh else " (the sources have changed since)"))
        rows += [_law_row(label, e, full[e]) for e in _LAW_EXAMPLES if e in full]
    # the record entry carries the stored study's summary (rechecked at build time on its first
    # test draws): a row of its own only where the stored study is not in this checkout
    check = next((e for e in entries_of(record) if e["id"] == LAW_ENTRY), None) if full is None else None
    for example, r in (check or {}).get("recomputed", {}).items():
        n = int(r["draws_test"]) + int(r.get("draws_train", 0))
        label = (f"build-time check: the procedure rerun on the first {count(n)} draws of the seeded "
                 "sequence (training draws of the stored study), half to train, half to score, a "
                 "shorter search for the tuned designs")
        rows.append(_law_row(label, example, r))
    return rows


def _share_words(share):
    """The median share of the headroom with its interval (where it takes any), or nothing."""
    if not share:
        return ""
    return share_ci(share) if share[0] > 0 else headroom_pct(share[0])


def ladder_rows(full):
    """The ladder of the stored study (every rung over the best fixed controller with equal
    information), per example and rung, labelled with its commit.

    Parameters
    ----------
    full : dict or None
        The stored study (:func:`fdsc.paper.pays.disturbance_law.load_full`).

    Returns
    -------
    list of dict
        Trusted-HTML cells ``example``, ``rung``, ``median`` (median [bootstrap 95 % interval]),
        ``wins`` and ``share`` (of the headroom to the non-causal limit, causal rungs only);
        empty without a stored ladder.

    Examples
    --------
    >>> row = {"median": 0.8, "low": 0.79, "high": 0.81, "win_rate": 1.0, "draws": 250}
    >>> full = {"commit": "048c47d821e7", "aircraft": {"ladder": {"summary": {"limit": row}}}}
    >>> [(r["rung"], r["median"]) for r in ladder_rows(full)]
    [('non-causal limit (knows the whole draw)', '×0.800 [0.790, 0.810]')]
    """
    from fdsc.paper.pays.ladder import REFERENCE, RUNG_WORDS, RUNGS

    rows = []
    for example in _LAW_EXAMPLES:
        lad = (full or {}).get(example, {}).get("ladder")
        if not lad:
            continue
        for rung in RUNGS:
            s = lad["summary"].get(rung)
            if s is None:
                continue
            share = s.get("headroom_share")
            rows.append({"example": _LAW_EXAMPLES[example], "rung": html.escape(RUNG_WORDS[rung]),
                         "median": times_ci(s),
                         "wins": "the reference" if rung == REFERENCE else pct(s["win_rate"]),
                         "share": _share_words(share)})
    return rows
