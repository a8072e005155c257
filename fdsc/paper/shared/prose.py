"""Numbers for the book's prose: one formatter, and one call that glues a result's numbers.

Every number a chapter quotes is formatted here, so that the book prints numbers one way:
significant digits are kept (``num(7.0)`` is ``7.00``, not ``7``), counts get thousands
separators, very large or small magnitudes a power of ten, a factor reads ``×1.00`` and a range
whose ends print alike prints once. A chapter's result says which of its numbers the prose
quotes (a ``prose()`` method returning ``{name: text}``) and :func:`glue_numbers` glues them in
one call, so that the cells that only glue stay short and hidden.
"""

import math
from numbers import Integral, Real

import numpy as np

__all__ = ["num", "count", "times", "span", "pct", "excess", "matrix_text", "glue_numbers",
           "reading_minutes", "WORDS_PER_MINUTE", "times_ci", "share_pct", "share_ci", "headroom_pct"]

_SUPERSCRIPT = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")


def _real(x, name):
    if isinstance(x, bool | np.bool_) or not isinstance(x, Real):
        raise TypeError(f"{name} must be a real number, but found {type(x).__name__} {x!r}")
    return float(x)


def num(x, digits=3):
    """A number with ``digits`` significant digits, trailing zeros kept.

    Parameters
    ----------
    x : float or int
        Integers (Python or NumPy) print in full with thousands separators (:func:`count`).
    digits : int, optional
        Significant digits of a float (≥ 1).

    Returns
    -------
    str
        ``∞``/``−∞`` and ``n/a`` (NaN) for non-finite values; magnitudes ≥ 10⁵ or below 10⁻³ as
        ``m × 10ᵉ``; magnitudes with more integer digits than ``digits`` as a whole number with
        thousands separators; minus signs as U+2212.

    Raises
    ------
    TypeError
        If ``x`` is not a real number.
    ValueError
        If ``digits`` < 1.

    Examples
    --------
    >>> num(7.0), num(0.43593), num(22.534), num(118.82), num(1.149e7), num(37493)
    ('7.00', '0.436', '22.5', '119', '1.15 × 10⁷', '37,493')
    >>> num(-0.0128), num(2.7e-26, 2), num(float("inf")), num(1092.79), num(999.7)
    ('−0.0128', '2.7 × 10⁻²⁶', '∞', '1,093', '1,000')
    >>> num(1072.4, 4), num(1234.5678, 6)
    ('1,072', '1,234.57')
    """
    if isinstance(x, Integral) and not isinstance(x, bool | np.bool_):
        return count(x)
    v = _real(x, "x")
    if digits < 1:
        raise ValueError(f"digits must be at least 1, but found {digits!r}")
    if math.isnan(v):
        return "n/a"
    if math.isinf(v):
        return "∞" if v > 0 else "−∞"
    if v != 0 and (abs(v) >= 1e5 or abs(v) < 1e-3):
        mantissa, exponent = f"{v:.{digits - 1}e}".split("e")
        return f"{mantissa} × 10{str(int(exponent)).translate(_SUPERSCRIPT)}".replace("-", "−")
    if abs(v) >= 10 ** digits - 0.5:   # more integer digits than asked: the whole number
        return count(round(v)) if abs(round(v)) < 100_000 else num(float(round(v)), digits)
    text = f"{v:#.{digits}g}"
    if abs(v) >= 1000:       # thousands separators, as count() prints whole numbers
        text = f"{v:,.{len(text.partition('.')[2])}f}"
    return text.rstrip(".").replace("-", "−")


def count(n):
    """A whole number with thousands separators.

    Parameters
    ----------
    n : int

    Returns
    -------
    str

    Raises
    ------
    TypeError
        If ``n`` is not an integer (bools are refused).

    Examples
    --------
    >>> count(37493), count(0), count(-1200)
    ('37,493', '0', '−1,200')
    """
    if isinstance(n, bool | np.bool_) or not isinstance(n, Integral):
        raise TypeError(f"n must be an integer, but found {type(n).__name__} {n!r}")
    return f"{int(n):,}".replace("-", "−")


def times(x, digits=3):
    """A factor: ``×`` and :func:`num` (``times(1.0)`` is ``×1.00``).

    Parameters
    ----------
    x : float
    digits : int, optional
        Significant digits.

    Returns
    -------
    str

    Raises
    ------
    TypeError
        If ``x`` is not a real number.

    Examples
    --------
    >>> times(1.0), times(0.742), times(22.53)
    ('×1.00', '×0.742', '×22.5')
    """
    return "×" + num(float(_real(x, "x")), digits)


def span(lo, hi, digits=3, *, sep="–", fmt=num):
    """A range that prints once when its ends print alike.

    Parameters
    ----------
    lo, hi : float
    digits : int, optional
    sep : str, optional
        Between the two ends.
    fmt : callable, optional
        ``fmt(x, digits)`` formats each end (:func:`num` or :func:`times`).

    Returns
    -------
    str

    Examples
    --------
    >>> span(1.3601, 1.3649), span(0.436, 7.0), span(0.436, 7.0, fmt=times)
    ('1.36', '0.436–7.00', '×0.436–×7.00')
    """
    a, b = fmt(lo, digits), fmt(hi, digits)
    return a if a == b else f"{a}{sep}{b}"


def pct(share, digits=0):
    """A share in [0, 1] as a percentage (``pct(0.04)`` is ``4 %``); a share strictly between 0
    and 1 is never printed as ``0 %`` or ``100 %`` (decimals are added, up to three, until it is
    not).

    Parameters
    ----------
    share : float
    digits : int, optional
        Decimals of the percentage (at least).

    Returns
    -------
    str

    Raises
    ------
    ValueError
        If the share is outside [0, 1] or not finite.

    Examples
    --------
    >>> pct(0.0), pct(0.9), pct(0.123, 1), pct(0.996), pct(1.0), pct(0.00004)
    ('0 %', '90 %', '12.3 %', '99.6 %', '100 %', '0.004 %')
    """
    v = _real(share, "share")
    if not 0.0 <= v <= 1.0:
        raise ValueError(f"share must lie in [0, 1], but found {v!r}")
    out = f"{100 * v:.{digits}f} %"
    while 0.0 < v < 1.0 and digits < 3 and float(out[:-2]) in (0.0, 100.0):
        digits += 1
        out = f"{100 * v:.{digits}f} %"
    return out


#: Excess over a bound up to which :func:`excess` prints a percentage rather than a factor.
EXCESS_PCT_UNDER = 0.01


def excess(quantity, bound):
    """How far a quantity lies above a bound: a percentage when it is within 1 % above it
    (:data:`EXCESS_PCT_UNDER`), else the factor quantity / bound.

    Parameters
    ----------
    quantity, bound : float
        ``quantity > bound > 0``.

    Returns
    -------
    str

    Raises
    ------
    ValueError
        If the quantity is not above a positive bound.

    Examples
    --------
    >>> excess(0.40279, 0.4025), excess(1.6051, 0.1714), excess(0.37374, 0.3443)
    ('0.07 % above', '×9.36', '×1.09')
    """
    q, b = _real(quantity, "quantity"), _real(bound, "bound")
    if not 0 < b < q:
        raise ValueError(f"quantity must lie above a positive bound, but found {q!r} and {b!r}")
    over = q / b - 1
    return f"{pct(over, 2)} above" if over < EXCESS_PCT_UNDER else times(q / b)


def matrix_text(m, digits=4):
    """A small matrix as the book prints it: rows separated by semicolons, entries by
    :func:`fdsc.paper.shared.prose.num` (no raw NumPy array in the book).

    Parameters
    ----------
    m : (n, k) array_like
    digits : int, optional
        Significant digits of each entry.

    Returns
    -------
    str

    Examples
    --------
    >>> matrix_text([[1.0, -2.5e-11], [-2.5e-11, 0.5]])
    '[1.000, −2.500 × 10⁻¹¹; −2.500 × 10⁻¹¹, 0.5000]'
    """
    return "[" + "; ".join(", ".join(num(float(v), digits) for v in row)
                           for row in np.atleast_2d(np.asarray(m, dtype=float))) + "]"


def glue_numbers(numbers, prefix=""):
    """Glue every ``{name: value}`` for the prose (``{glue:text}`prefix+name```), not displayed.

    Parameters
    ----------
    numbers : mapping of str to object
        Usually a result's ``prose()``: formatted text, or any other object (e.g. ``Markdown``
        for ``{glue:md}``). Text is glued as a ``str``: MyST-NB's ``{glue:text}`` reads back the
        ``repr`` with ``ast.literal_eval``, which gives the text itself (an object whose ``repr``
        were the bare text would be evaluated: ``37,493`` would print as ``(37, 493)`` and
        ``1.00`` as ``1.0``).
    prefix : str, optional
        Put before every name (a chapter's results share one namespace per page).

    Returns
    -------
    None
        Nothing, so that a cell ending in this call shows no output.

    Raises
    ------
    TypeError
        If a name is not a string.
    """
    from myst_nb import glue  # only inside a notebook

    for key, value in numbers.items():
        if not isinstance(key, str):
            raise TypeError(f"numbers must be keyed by str, but found {type(key).__name__} {key!r}")
        glue(prefix + key, value, display=False)


#: Words a reader reads per minute (the reading time the landing page states).
WORDS_PER_MINUTE = 230


def reading_minutes(book_dir) -> int:
    """The minutes a reader needs for the book's prose: the words of every page's Markdown (the
    notebooks' text cells and the Markdown pages; code, tables and figures not counted) at
    :data:`WORDS_PER_MINUTE`.

    Parameters
    ----------
    book_dir : path
        The book's folder (with ``_toc.yml``).

    Returns
    -------
    int
    """
    import json
    import re
    from pathlib import Path

    book = Path(book_dir)
    words = 0
    for p in sorted(book.glob("*.ipynb")) + sorted(book.glob("*.md")):
        if p.suffix == ".ipynb":
            cells = json.loads(p.read_text(encoding="utf-8"))["cells"]
            text = "\n".join("".join(c["source"]) for c in cells if c["cell_type"] == "markdown")
        else:
            text = p.read_text(encoding="utf-8")
        text = re.sub(r"```.*?```", " ", text, flags=re.S)          # directives and code blocks
        words += len(re.findall(r"[A-Za-zÀ-ÿ]{2,}", text))
    return max(1, round(words / WORDS_PER_MINUTE))


def times_ci(row) -> str:
    """A median ratio with its interval, ``×m [lo, hi]``, from ``{"median", "low", "high"}``.

    Parameters
    ----------
    row : dict

    Returns
    -------
    str

    Examples
    --------
    >>> times_ci({"median": 0.8, "low": 0.79, "high": 0.812})
    '×0.800 [0.790, 0.812]'
    """
    return f"{times(row['median'])} [{times(row['low'])[1:]}, {times(row['high'])[1:]}]"


def headroom_pct(x) -> str:
    """A rung's share of the headroom for a table: :func:`share_pct` where it takes some (x ≥ 0),
    ``none`` where it has more energy than the fixed controller it is scored against (a negative
    share, which can run to thousands of per cent, says no more than its median ratio does).

    Parameters
    ----------
    x : float

    Returns
    -------
    str

    Examples
    --------
    >>> headroom_pct(0.69), headroom_pct(0.0), headroom_pct(-46.57)
    ('69 %', '0 %', 'none')
    """
    v = _real(x, "x")
    return share_pct(v) if v >= 0 else "none"


def share_pct(x) -> str:
    """A share of the headroom as a percentage that may be negative (a loss): ``-0.04`` is
    ``−4 %``, ``0.5`` is ``50 %``.

    Parameters
    ----------
    x : float

    Returns
    -------
    str

    Examples
    --------
    >>> share_pct(0.503), share_pct(-0.04)
    ('50 %', '−4 %')
    """
    v = round(100 * _real(x, "x"))
    return f"{'−' if v < 0 else ''}{abs(v)} %"


def share_ci(share) -> str:
    """A median share of the headroom with its bootstrap interval, ``69 % [65 %, 73 %]``.

    Parameters
    ----------
    share : sequence of 3 floats
        Median, low and high (as stored in a ladder summary's ``headroom_share``).

    Returns
    -------
    str

    Examples
    --------
    >>> share_ci([0.69, 0.65, 0.73])
    '69 % [65 %, 73 %]'
    """
    m, lo, hi = share
    return f"{share_pct(m)} [{share_pct(lo)}, {share_pct(hi)}]"
