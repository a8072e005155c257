"""The statements of the paper that a chapter finds false or vacuous although no graded item of the
report carries them (no printed number, inequality, checked proof step or claim): one line each,
its numbers read from the record's finding; shown on the landing page and in the report after its
errata."""

from fdsc.paper.appendix.report_counts import entries_of
from fdsc.paper.shared.prose import num

__all__ = ["FURTHER_WORDS", "further_findings", "further_summary"]


def _fmt(x, digits=4):
    return num(float(x), digits)


def _pw_words(e):
    shares = [v for band in e["recomputed"].values() for v in band.values()]
    return ("no nonzero causal signal of finite energy is frequency-limited (Paley–Wiener): the paper's "
            f"own LF and HF signals, cut to a window, keep {_fmt(100 * min(shares), 2)} % to "
            f"{_fmt(100 * max(shares), 2)} % of their energy outside their ranges, so the class of "
            "Definition 1 is empty and Lemma 1 (2) and Proposition 1 1), which assume it, are vacuous "
            "as printed")


def _gap_words(e):
    r = e["recomputed"]
    cross = r["first_sign_change_rad_s"].values()
    return (f"read literally it asks the reverse of what the curves show: the gap of K_f3 over the "
            f"other printed gains is {_fmt(min(r['gap_at_lowest_omega'].values()), 4)} or more at the "
            f"lowest frequency and first changes sign between {_fmt(min(cross), 3)} and "
            f"{_fmt(max(cross), 3)} rad/s, so the in-band controller is better only above the crossing")


def _chatter_words(e):
    run = e["recomputed"]["paper Q, measured ẋ"]
    # the run's horizon said with its count (the paper's T = 500 s gives another count)
    T, rho_t = e.get("T"), e.get("rho_t")
    horizon = (f" with T = {_fmt(T, 3)} s (a run of {_fmt(2 * T + rho_t * T, 3)} s)"
               if T is not None and rho_t is not None else "")
    return (f"“sliding motion very rarely occurs” does not hold for the printed law with the measured ẋ: "
            f"on the piecewise disturbance of paper eq. (58){horizon} it switches {run['switches']:,} "
            f"times, {_fmt(100 * run['single_sample_dwell'], 2)} % of its dwells one sample long "
            "(sliding, realized as chattering), outside Theorem 1's assumptions")


def _hysteresis_words(e):
    h = e["recomputed"]["hysteresis"]
    grid = ", ".join(_fmt(p, 2) for p in h["parameters"])
    return (f"a hysteresis, which the remark offers to avoid sliding, does not: with relative margins "
            f"{grid} the printed law still switches {h['switches']['LF'][-1]:,} times under the LF "
            f"disturbance, and {h['switches_half_dt']['LF'][-1]:,} times when the step halves (a "
            "minimum dwell time does avoid it)")


def _statement3_words(e):
    runs = e["recomputed"].values()
    held = sum(bool(r["below"]) for r in runs)
    return ("its proof bounds the energy ratio with weights that are each mode's share of the "
            "disturbance's energy, not the time shares β_i the theorem defines; with time shares the "
            f"bound holds on {held} of {len(runs)} of our runs, as a measured fact, not by the proof")


def _hf_best_words(e):
    hf = {k: v["HF"] for k, v in e["recomputed"].items()}
    others = [v for k, v in hf.items() if k != "K_f3"]
    worst = max(hf, key=hf.get)
    return ("“Obviously, K_f3 provides best HF disturbance attenuation performance” does not hold: its band "
            f"peak over the HF range is {_fmt(hf['K_f3'], 4)}, "
            + ("the worst" if worst == "K_f3" else "not the best") + " of the four printed gains (the others "
            f"{_fmt(min(others), 4)} to {_fmt(max(others), 4)})")


#: Statements of the paper that a chapter finds false or vacuous although no graded item of the
#: report (printed number, inequality, proof step, claim) carries them: per record finding, where in
#: the paper and what is wrong in one line, its numbers read from the finding.
FURTHER_WORDS = {
    "paley_wiener_share": ("Definition 1, Lemma 1 (2), Proposition 1 1)", _pw_words),
    "sigma_peak": ("Sec. IV, text on paper Fig. 3", _hf_best_words),
    "remark3_gap": ("paper Remark 3, the gap function", _gap_words),
    "law_chattering": ("paper Remark 7", _chatter_words),
    "hysteresis_dwell": ("paper Remark 7, its remedies", _hysteresis_words),
    "thm1_statement3": ("Theorem 1, statement (3)", _statement3_words),
    "generic_example": ("Sec. I", lambda e: (
        "the introduction promises simulations on “a generic and a common benchmark model”; only the "
        "benchmark (the aircraft) is simulated")),
}


def further_findings(record) -> list:
    """The statements of :data:`FURTHER_WORDS` that the record's findings show false or vacuous,
    in that order: the errata that no graded item of the report carries.

    Parameters
    ----------
    record : dict
        The reproduction record.

    Returns
    -------
    list of dict
        ``n``, ``where``, ``what`` (plain text) and ``id``, one per finding of :data:`FURTHER_WORDS`
        that the record holds.

    Examples
    --------
    >>> rec = {"entries": [{"id": "generic_example", "source": "ours", "paper": None,
    ...                     "recomputed": {}, "verdict": "new", "note": "n"}]}
    >>> [(r["n"], r["where"]) for r in further_findings(rec)]
    [(1, 'Sec. I')]
    """
    held = {e["id"]: e for e in entries_of(record)}
    rows = [{"where": where, "what": say(held[i]), "id": i}
            for i, (where, say) in FURTHER_WORDS.items() if i in held]
    return [{"n": k, **r} for k, r in enumerate(rows, start=1)]


def further_summary(record) -> str:
    """:func:`further_findings` as a short numbered Markdown list, for the summary and the report.

    Parameters
    ----------
    record : dict

    Returns
    -------
    str
    """
    return "\n".join(f"{r['n']}. {r['where']}: {r['what']}" for r in further_findings(record))
