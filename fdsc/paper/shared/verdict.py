"""The one verdict rule of the reproduction record.
"""

import numpy as np

__all__ = [
    "VERDICTS",
    "VERDICT_RULES",
    "VERDICT_CLOSE_RTOL",
    "CLAIM_VERDICTS",
    "CLAIM_VERDICT_RULES",
    "verdict",
    "worst_verdict",
]


#: Relative difference up to which a number that misses the printed precision is "close".
VERDICT_CLOSE_RTOL = 1e-2


#: The verdicts of the record's entries, from best to worst, then ``input`` (a printed input, used
#: as printed) and ``new`` (nothing printed to compare with).
VERDICTS = ("match", "close", "differs", "not reproducible", "input", "new")


#: The verdict rules, stated once (the book's reproduction report renders this text).
VERDICT_RULES = {
    "match": "equal to the printed number to its printed precision (half a unit in its last "
             "printed decimal), entry by entry for matrices",
    "close": "not a match, but within 1 % relative (Frobenius norm for matrices) of the quantity "
             "the paper says it printed; never given to a quantity picked, after the fact, as the "
             "nearest of several candidates",
    "differs": "the quantity the paper says it printed, recomputed, is further than 1 % away",
    "not reproducible": "the paper prints a number but not what is needed to recompute it (an "
                        "unprinted parameter), or no quantity tried gives it to its printed "
                        "precision",
    "input": "a printed number that is an input of the reproduction (model, bands, signals, "
             "parameters), used as printed; a test checks the transcription against the paper's "
             "LaTeX source",
    "new": "a quantity the paper does not print (our finding); there is nothing to compare with",
}


#: The verdicts of the record's claims (the paper's sentences read as statements), best to worst.
CLAIM_VERDICTS = ("PASS", "PARTLY", "FAIL")


#: The claim verdict rules, stated once.
CLAIM_VERDICT_RULES = {
    "PASS": "the number that decides the claim, measured, supports the paper's words as read",
    "PARTLY": "it supports them for part of the range, of the controllers or of the sentence only",
    "FAIL": "it contradicts them",
}


def verdict(paper, ours, decimals=4, *, after_the_fact=False, unprinted=()):
    """Compare a printed number (or matrix) with a recomputed one, by :data:`VERDICT_RULES`.

    Parameters
    ----------
    paper, ours : float or array_like
        The printed and the recomputed value (same shape).
    decimals : int, optional
        Decimals printed in the paper.
    after_the_fact : bool, optional
        ``ours`` was picked as the nearest of several candidates after seeing ``paper``: it can
        be a ``match`` (equal to the printed precision) but never ``close``.
    unprinted : sequence of str, optional
        The parameters that the recomputation needs and the paper does not print (e.g. ``("σ",
        "ε")`` of the HF synthesis): a value further than 1 % away is then ``not reproducible``,
        since our choice of them, not the paper, may be what differs.

    Returns
    -------
    {"match", "close", "differs", "not reproducible"}

    Examples
    --------
    >>> verdict(0.4025, 0.40252), verdict(0.4025, 0.4028), verdict(0.1714, 1.605)
    ('match', 'close', 'differs')
    >>> verdict(0.3443, 0.3426, after_the_fact=True)
    'differs'
    >>> verdict(0.1714, 1.605, unprinted=("σ",)), verdict(0.4025, 0.4028, unprinted=("ε",))
    ('not reproducible', 'close')
    """
    paper, ours = np.asarray(paper, dtype=float), np.asarray(ours, dtype=float)
    if paper.shape != ours.shape:
        raise ValueError(f"paper and ours must have one shape, found {paper.shape} and {ours.shape}")
    if np.all(np.abs(paper - ours) <= 0.5 * 10.0 ** (-decimals) * (1 + 1e-9)):
        return "match"
    if not after_the_fact and np.linalg.norm(paper - ours) <= VERDICT_CLOSE_RTOL * np.linalg.norm(paper):
        return "close"
    return "not reproducible" if unprinted else "differs"


def worst_verdict(verdicts, order=VERDICTS):
    """The worst of several verdicts, in the order of :data:`VERDICTS` (``new`` counts as worst).

    Parameters
    ----------
    verdicts : iterable of str
        Verdicts from ``order``.
    order : tuple of str, optional
        The verdicts from best to worst: :data:`VERDICTS` (entries) or :data:`CLAIM_VERDICTS`.

    Returns
    -------
    str

    Raises
    ------
    ValueError
        If a verdict is not in ``order``, or there is none.

    Examples
    --------
    >>> worst_verdict(["match", "differs", "close"])
    'differs'
    >>> worst_verdict(["PASS", "PARTLY"], CLAIM_VERDICTS)
    'PARTLY'
    """
    verdicts = list(verdicts)
    unknown = [v for v in verdicts if v not in order]
    if unknown or not verdicts:
        raise ValueError(f"verdicts must be a non-empty list from {order}, but found {verdicts!r}")
    return max(verdicts, key=order.index)
