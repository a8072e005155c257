"""Chapter 'ladder' and the landing page: the sentences both print from one function, so that
they cannot drift apart: where predicting pays under white measurement noise (the noise study of
:mod:`fdsc.paper.pays.information`, stored), how the adaptive feedforward compares with the
predictive law on the same draws (:mod:`fdsc.paper.pays.adaptive_rung`, stored), and how the
predictive law with a confidence check fares on the class's variants
(:mod:`fdsc.paper.pays.variant_laws`, stored)."""

import numpy as np

from fdsc.paper.pays.information import FALLBACK, summary
from fdsc.paper.shared.prose import num, pct, times_ci
from fdsc.paper.shared.stats import bootstrap_median

__all__ = ["noise_pays_words", "adaptive_vs_predictive", "adaptive_words", "adaptive_noise_words",
           "variant_verdicts", "variant_words", "variant_short", "VARIANT_CLAUSE"]

#: The examples in the words of the pages.
WHERE = {"aircraft": "aircraft", "generic": "generic example"}
#: The class's variants as a clause ("where ...").
VARIANT_CLAUSE = {"shorter": "segments are 4× shorter", "longer": "segments are 4× longer",
                  "alpha": "the dominating band's share α is anywhere in [0.5, 1]",
                  "noise": "every segment is band-limited noise"}


def noise_pays_words(info, rows=None, rung="predictive (confident)"):
    """Per example, the noise levels at which ``rung``'s whole 95 % interval over the best fixed
    controller at the same noise lies below 1, in words.

    Parameters
    ----------
    info : dict
        The stored noise study (:func:`fdsc.paper.pays.information.load_information`).
    rows : dict, optional
        ``{example: rows}`` as :func:`fdsc.paper.pays.information.summary` gives them (default:
        computed from ``info``).
    rung : str, optional
        A rung of :func:`fdsc.paper.pays.information.summary`.

    Returns
    -------
    str
        E.g. ``"at every level down to 0 dB on the aircraft and down to 10 dB on the generic
        example (not at 0 dB)"``; a level at which the law's training draws chose not to predict
        (``info[example][level]["window"]`` is :data:`fdsc.paper.pays.information.FALLBACK`) is
        said as such.

    Examples
    --------
    >>> row = lambda level, hi: {"level": level, "predictive (confident)": (0.9, 0.8, hi)}
    >>> rows = {e: [row("exact", 0.9), row("20 dB", 0.95), row("0 dB", 0.99 if e == "aircraft" else 1.04)]
    ...         for e in ("aircraft", "generic")}
    >>> noise_pays_words({"levels": ["exact", "20 dB", "0 dB"]}, rows)
    'at every level down to 0 dB on the aircraft and down to 20 dB on the generic example (not at 0 dB)'
    >>> same = {e: [row("exact", 0.9), row("20 dB", 0.95), row("0 dB", 0.99)] for e in rows}
    >>> noise_pays_words({"levels": ["exact", "20 dB", "0 dB"]}, same)
    'at every level down to 0 dB on both examples'
    >>> info = {"levels": ["exact", "20 dB", "0 dB"], "generic": {"0 dB": {"window": "fixed"}}}
    >>> noise_pays_words(info, rows).split(" and ")[1]  # doctest: +NORMALIZE_WHITESPACE
    'down to 20 dB on the generic example (not at 0 dB, where it does not predict: its training
    draws chose the best fixed controller)'
    """
    noisy = [k for k in info["levels"] if k != "exact"]
    rows = {e: summary(info, e) for e in WHERE} if rows is None else rows
    parts = []
    for e, name in WHERE.items():
        pays = [r["level"] for r in rows[e] if r["level"] != "exact" and r[rung][2] < 1.0]
        if pays == noisy:
            parts.append(f"at every level down to {noisy[-1]} on the {name}")
        elif pays and pays == noisy[:len(pays)]:
            rest = noisy[len(pays):]
            fixed = [lv for lv in rest if info.get(e, {}).get(lv, {}).get("window") == FALLBACK]
            why = (", where it does not predict: its training draws chose the best fixed controller"
                   if fixed == rest else "")
            parts.append(f"down to {pays[-1]} on the {name} (not at {', '.join(rest)}{why})")
        elif pays:
            parts.append(f"at {', '.join(pays)} on the {name}")
        else:
            parts.append(f"at no noise level on the {name}")
    names = [f"on the {n}" for n in WHERE.values()]
    alike = {p.replace(n, "") for p, n in zip(parts, names, strict=True)}
    if len(alike) == 1 and all(n in p for p, n in zip(parts, names, strict=True)):
        return parts[0].replace(names[0], "on both examples")
    return " and ".join(parts)


def _ci(c):
    """:func:`times_ci`, with four significant digits where three print the median and both ends
    alike (a ratio within a few per mil of 1).

    Examples
    --------
    >>> _ci({"median": 1.0036, "low": 1.0021, "high": 1.0046})
    '×1.004 [1.002, 1.005]'
    """
    w = times_ci(c)
    printed = {times_ci({"median": c[k], "low": c[k], "high": c[k]}) for k in ("median", "low", "high")}
    if len(printed) > 1 or c["high"] - c["low"] <= 1e-9 * abs(c["high"]):
        return w
    return f"×{num(c['median'], 4)} [{num(c['low'], 4)}, {num(c['high'], 4)}]"


def adaptive_vs_predictive(adapt, example, against=None):
    """The adaptive feedforward over a predictive law, draw by draw, on the adaptive study's test
    draws: the median of the per-draw ratio with its bootstrap 95 % interval, and the share of
    draws on which the adaptive law has less energy.

    Parameters
    ----------
    adapt : dict
        The stored adaptive study (:func:`fdsc.paper.pays.adaptive_rung.load_adaptive`).
    example : {"aircraft", "generic"}
    against : sequence of float, optional
        The other law's energies on the same draws (default the stored study's predictive law,
        ``adapt[example]["predictive_energies"]``).

    Returns
    -------
    dict
        ``{"median", "low", "high", "win_rate", "draws"}``.
    """
    r = adapt[example]
    other = np.asarray(r["predictive_energies"] if against is None else against, float).reshape(-1)
    if other.size != len(r["energies"]):
        raise ValueError(f"against must hold one energy per test draw ({len(r['energies'])}), "
                         f"but has {other.size}")
    x = np.asarray(r["energies"], float) / other
    med, lo, hi = bootstrap_median(x)
    return {"median": med, "low": lo, "high": hi, "win_rate": float(np.mean(x < 1.0)), "draws": int(x.size)}


def adaptive_words(adapt, numbers=True, confident=None, only_confident=False):
    """Which of the adaptive feedforward and the predictive law does better on each example, by
    the paired comparison of :func:`adaptive_vs_predictive` (better only where the whole 95 %
    interval of the per-draw ratio lies on one side of 1), in words; with ``confident``, also
    against the predictive law with a confidence check on the same draws.

    Parameters
    ----------
    adapt : dict
        The stored adaptive study.
    numbers : bool, optional
        False: the verdicts alone (the landing page's short form).
    confident : dict, optional
        ``{example: energies}`` of the law with a confidence check on the adaptive study's test
        draws (the noise study's exact estimate).
    only_confident : bool, optional
        With ``confident`` and ``numbers=False``: only the comparison with the law with a
        confidence check (the landing page's shortest form).

    Returns
    -------
    str
        E.g. ``"draw by draw, the adaptive law over the predictive law has ×0.987 [0.979, 1.00]
        on the aircraft (less energy on 62 % of the draws: neither does better) and ..."``.

    Examples
    --------
    >>> a = {e: {"energies": [1.0, 2.0, 3.0, 4.0], "predictive_energies": [1.1, 2.2, 3.3, 4.4]}
    ...      for e in WHERE}
    >>> adaptive_words(a).split(" and ")[0]  # doctest: +NORMALIZE_WHITESPACE
    'draw by draw, the adaptive law over the predictive law has ×0.909 [0.909, 0.909] on the
    aircraft (less energy on 100 % of the draws: the adaptive law does better)'
    >>> adaptive_words(a, numbers=False)
    'draw by draw, the adaptive law does better on the aircraft and on the generic example'
    >>> conf = {e: [0.9, 1.9, 2.9, 3.9] for e in WHERE}
    >>> adaptive_words(a, numbers=False, confident=conf)  # doctest: +NORMALIZE_WHITESPACE
    'draw by draw, the adaptive law does better on the aircraft and on the generic example; against
    the law with a confidence check, that law does better on both examples'
    >>> adaptive_words(a, numbers=False, confident=conf, only_confident=True)
    'draw by draw, the law with a confidence check does better on both examples'
    """
    def compare(against, other):
        parts, verdicts = [], {}
        for e, name in WHERE.items():
            c = adaptive_vs_predictive(adapt, e, None if against is None else against[e])
            verdict = ("the adaptive law does better" if c["high"] < 1.0 else
                       f"{other} does better" if c["low"] > 1.0 else "neither does better")
            parts.append(f"{_ci(c)} on the {name} (less energy on {pct(c['win_rate'])} of the draws: "
                         f"{verdict})")
            verdicts.setdefault(verdict, []).append(f"on the {name}")
        return parts, verdicts

    if only_confident and confident is not None and not numbers:
        _p, cverdicts = compare(confident, "the law with a confidence check")
        mine = "it does better than the law with a confidence check"
        return "draw by draw, " + "; ".join(
            v.replace("the adaptive law does better", mine) + " "
            + ("on both examples" if len(w) == len(WHERE) else " and ".join(w)) for v, w in cverdicts.items())
    parts, verdicts = compare(None, "the predictive law")
    if not numbers:
        out = "draw by draw, " + "; ".join(f"{v} {' and '.join(w)}" for v, w in verdicts.items())
    else:
        out = "draw by draw, the adaptive law over the predictive law has " + " and ".join(parts)
    if confident is not None:
        cparts, cverdicts = compare(confident, "that law")
        def where(w):
            return "on both examples" if len(w) == len(WHERE) else " and ".join(w)

        out += ("; against the law with a confidence check, "
                + "; ".join(f"{v} {where(w)}" for v, w in cverdicts.items()) if not numbers else
            "; over the law with a confidence check it has " + " and ".join(cparts))
    return out


def adaptive_noise_words(adapt, info):
    """The adaptive law with noise on its samples against the best fixed controller at the same
    level and beside the law with a confidence check there, on the same draws, in words.

    Parameters
    ----------
    adapt : dict
        The stored adaptive study, with its run under noise (``adapt[example]["noise"]``).
    info : dict
        The stored noise study: its row at the adaptive study's level holds the law with a
        confidence check and the best fixed controller on the same draws.

    Returns
    -------
    str
        E.g. ``"with white noise on its samples at 20 dB, the adaptive law has ×0.93 [0.90, 0.95]
        of the best fixed controller at that level on the aircraft (less energy on 100 % of the
        draws) and …; the law with a confidence check has ×… and ×… there"``.

    Raises
    ------
    ValueError
        If the two studies' draws or their best fixed controller's energies differ (one reference
        behind both).
    """
    level = f"{adapt['noise_level']:g} dB"
    mine, theirs = [], []
    for e, name in WHERE.items():
        nz, n = adapt[e]["noise"], len(adapt[e]["test_indices"])
        row = info[e][level]
        if info[e]["test_indices"][:n] != adapt[e]["test_indices"]:
            raise ValueError(f"{name}: the adaptive study and the noise study do not share their test draws")
        ref = np.asarray(row["energies"]["best fixed (x, ŵ)"][:n], float)
        if not np.allclose(ref, nz["reference_energies"], rtol=1e-6, atol=0):
            raise ValueError(f"{name}: the best fixed controller at {level} has other energies in the "
                             "adaptive study than in the noise study")
        x = np.asarray(nz["energies"], float) / ref
        med, lo, hi = bootstrap_median(x)
        mine.append(f"{times_ci({'median': med, 'low': lo, 'high': hi})} on the {name} (less energy on "
                    f"{pct(float(np.mean(x < 1.0)))} of the draws)")
        y = np.asarray(row["energies"]["predictive (confident)"][:n], float) / ref
        theirs.append(times_ci(dict(zip(("median", "low", "high"), bootstrap_median(y), strict=True))))
    return (f"with white noise on its samples at {level}, the adaptive law has {' and '.join(mine)} of the "
            "best fixed controller at that level; the law with a confidence check has "
            f"{' and '.join(theirs)} there, on the same draws")


def variant_verdicts(rows):
    """Per example and variant, how the law with a confidence check stands against the variant's
    best fixed controller (x, ŵ), by the bootstrap 95 % interval of its per-draw ratio: ``"gain"``
    (the whole interval below 1), ``"fixed"`` (its training draws chose not to predict: it is
    that controller), ``"no loss"`` (median at most 1, the interval reaching 1), ``"loss"`` (the
    whole interval above 1) or ``"unclear"`` (median above 1, the interval reaching below 1).

    Parameters
    ----------
    rows : dict
        ``{example: summary}``, each :func:`fdsc.paper.pays.variant_laws.summary`.

    Returns
    -------
    dict
        ``{(example, variant): verdict}``.

    Examples
    --------
    >>> def law(m, lo, hi):
    ...     return {"predictive (confident)": {"median": m, "low": lo, "high": hi}, "window": 4.0}
    >>> v = variant_verdicts({"aircraft": {"a": law(0.9, 0.8, 0.95), "b": law(1.0, 0.99, 1.01)},
    ...                       "generic": {"a": law(1.1, 1.05, 1.2), "b": law(1.01, 0.98, 1.04)}})
    >>> [v[k] for k in sorted(v)]
    ['gain', 'no loss', 'loss', 'unclear']
    """
    out = {}
    for e, rs in rows.items():
        for v, r in rs.items():
            q = r["predictive (confident)"]
            out[e, v] = ("fixed" if r["window"] == FALLBACK else "gain" if q["high"] < 1.0 else
                         "loss" if q["low"] > 1.0 else "no loss" if q["median"] <= 1.0 else "unclear")
    return out


def _listed(items, conj="and"):
    return items[0] if len(items) == 1 else ", ".join(items[:-1]) + f" {conj} " + items[-1]


def variant_words(rows, numbers=True):
    """Where on the class's variants the law with a confidence check gains, does not predict, or
    loses, in words (:func:`variant_verdicts`).

    Parameters
    ----------
    rows : dict
        ``{example: summary}``, each :func:`fdsc.paper.pays.variant_laws.summary`.
    numbers : bool, optional
        False: the verdicts alone (the landing page's short form).

    Returns
    -------
    str

    Examples
    --------
    >>> def law(m, lo, hi, w=4.0):
    ...     return {"predictive (confident)": {"median": m, "low": lo, "high": hi}, "window": w}
    >>> rows = {"aircraft": {"shorter": law(0.9, 0.8, 0.95), "noise": law(0.9998, 0.9994, 1.0001)},
    ...         "generic": {"shorter": law(0.8, 0.7, 0.9), "noise": law(1.0, 1.0, 1.0, "fixed")}}
    >>> variant_words(rows, numbers=False)  # doctest: +NORMALIZE_WHITESPACE
    'it loses on no variant: it gains (its whole interval below 1) on both examples where segments
    are 4× shorter; where every segment is band-limited noise, its median is at most 1 on the
    aircraft and its training draws chose not to predict on the generic example (it is then the best
    fixed controller)'
    >>> variant_words(rows).split("; ")[0]  # doctest: +NORMALIZE_WHITESPACE
    'it loses on no variant: it gains (its whole interval below 1) on both examples where segments
    are 4× shorter (×0.900 [0.800, 0.950] on the aircraft, ×0.800 [0.700, 0.900] on the generic
    example)'
    """
    verdict = variant_verdicts(rows)
    examples = list(rows)
    variants = list(dict.fromkeys(v for e in examples for v in rows[e]))

    def on(es):
        return "on both examples" if len(es) == len(examples) == 2 else " and ".join(
            f"on the {WHERE[e]}" for e in es)

    def nums(v, es):
        if not numbers:
            return ""
        return " (" + ", ".join(times_ci(rows[e][v]["predictive (confident)"])
                                + (f" on the {WHERE[e]}" if len(es) > 1 else "") for e in es) + ")"

    bad = [(e, v) for (e, v), k in verdict.items() if k in ("loss", "unclear")]
    head = ("it loses on no variant" if not bad else
            "it does not keep its median at or below 1 " + _listed(
                [f"where {VARIANT_CLAUSE.get(v, v)} on the {WHERE[e]}" for e, v in bad]))
    gain = [v for v in variants if all(verdict.get((e, v)) == "gain" for e in examples)]
    parts = []
    if gain:
        parts.append(f"it gains (its whole interval below 1) {on(examples)} where "
                     + _listed([VARIANT_CLAUSE.get(v, v) + nums(v, examples) for v in gain], "or"))
    labels = (("gain", "it gains", ""), ("no loss", "its median is at most 1", ""),
              ("fixed", "its training draws chose not to predict", " (it is then the best fixed controller)"),
              ("unclear", "it is not shown to gain or lose", ""), ("loss", "it loses", ""))
    for v in variants:
        if v in gain:
            continue
        bits = []
        for kind, label, after in labels:
            es = [e for e in examples if verdict.get((e, v)) == kind]
            if es:
                bits.append(f"{label} {on(es)}{'' if kind == 'fixed' else nums(v, es)}{after}")
        parts.append(f"where {VARIANT_CLAUSE.get(v, v)}, " + " and ".join(bits))
    return head + ": " + "; ".join(parts)


def variant_short(rows):
    """:func:`variant_words` in one clause, for the landing page: whether the law with a confidence
    check loses on any variant, and on how many of the variant-and-example pairs it gains.

    Parameters
    ----------
    rows : dict
        ``{example: summary}``, each :func:`fdsc.paper.pays.variant_laws.summary`.

    Returns
    -------
    str

    Examples
    --------
    >>> def law(m, lo, hi, w=4.0):
    ...     return {"predictive (confident)": {"median": m, "low": lo, "high": hi}, "window": w}
    >>> rows = {"aircraft": {"shorter": law(0.9, 0.8, 0.95), "noise": law(0.9998, 0.9994, 1.0001)},
    ...         "generic": {"shorter": law(0.8, 0.7, 0.9), "noise": law(1.0, 1.0, 1.0, "fixed")}}
    >>> variant_short(rows)  # doctest: +NORMALIZE_WHITESPACE
    'it loses on none and gains on 2 of the 4 variant-and-example pairs (not where every segment
    is band-limited noise)'
    """
    verdict = variant_verdicts(rows)
    bad = [k for k, v in verdict.items() if v in ("loss", "unclear")]
    gains = [k for k, v in verdict.items() if v == "gain"]
    rest = list(dict.fromkeys(v for (e, v), k in verdict.items() if k != "gain"))
    out = ("it loses on none" if not bad else f"it does not keep its median at or below 1 on {len(bad)}")
    out += f" and gains on {len(gains)} of the {len(verdict)} variant-and-example pairs"
    if rest:
        out += " (not where " + _listed([VARIANT_CLAUSE.get(v, v) for v in rest], "or") + ")"
    return out
