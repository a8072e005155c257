"""Chapter 'ladder' and the landing page: one sentence, in words, of where predicting pays under
white measurement noise (the noise study of :mod:`fdsc.paper.pays.information`, stored), so that
both pages print it from one function."""

from fdsc.paper.pays.information import summary

__all__ = ["noise_pays_words"]

#: The examples in the words of the pages.
WHERE = {"aircraft": "aircraft", "generic": "generic example"}


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
        example (not at 0 dB)"``.

    Examples
    --------
    >>> row = lambda level, hi: {"level": level, "predictive (confident)": (0.9, 0.8, hi)}
    >>> rows = {e: [row("exact", 0.9), row("20 dB", 0.95), row("0 dB", 0.99 if e == "aircraft" else 1.04)]
    ...         for e in ("aircraft", "generic")}
    >>> noise_pays_words({"levels": ["exact", "20 dB", "0 dB"]}, rows)
    'at every level down to 0 dB on the aircraft and down to 20 dB on the generic example (not at 0 dB)'
    """
    noisy = [k for k in info["levels"] if k != "exact"]
    rows = {e: summary(info, e) for e in WHERE} if rows is None else rows
    parts = []
    for e, name in WHERE.items():
        pays = [r["level"] for r in rows[e] if r["level"] != "exact" and r[rung][2] < 1.0]
        if pays == noisy:
            parts.append(f"at every level down to {noisy[-1]} on the {name}")
        elif pays and pays == noisy[:len(pays)]:
            parts.append(f"down to {pays[-1]} on the {name} (not at {', '.join(noisy[len(pays):])})")
        elif pays:
            parts.append(f"at {', '.join(pays)} on the {name}")
        else:
            parts.append(f"at no noise level on the {name}")
    return " and ".join(parts)
