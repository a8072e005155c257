"""Small HTML tables for the notebooks (the book renders ``text/html`` outputs as is), and a
compact text form of the record's nested values for their cells."""

import html
import math

import numpy as np

__all__ = ["html_table", "fmt", "compact"]


def fmt(value, spec=".4g"):
    """Format a number (or pass text through) for a table cell.

    Parameters
    ----------
    value : float, int, bool, str or None
        The cell's value; infinities print as ∞, NaN and None as a dash, booleans as yes/no, a
        number that the spec puts in e-notation as m × 10ᵉ, text as is.
    spec : str, optional
        Format specification of a finite number.

    Returns
    -------
    str

    Examples
    --------
    >>> fmt(0.123456), fmt(float("inf")), fmt(float("nan")), fmt("LF"), fmt(None), fmt(True)
    ('0.1235', '∞', '—', 'LF', '—', 'yes')
    >>> fmt(15280.4), fmt(-2.5e-7, ".2g")
    ('1.528 × 10⁴', '−2.5 × 10⁻⁷')
    """
    if value is None:
        return "—"
    if isinstance(value, bool | np.bool_):
        return "yes" if value else "no"
    if isinstance(value, int | float):
        if math.isnan(value):
            return "—"  # nothing to show (e.g. no closed form)
        if math.isinf(value):
            return "∞" if value > 0 else "−∞"
        text = format(value, spec)
        mant, e, exp = text.partition("e")
        if e and exp.lstrip("+-").isdigit():   # 1.528e+04 -> 1.528 × 10⁴, as the prose prints it
            from fdsc.paper.shared.prose import _SUPERSCRIPT

            return f"{mant} × 10{str(int(exp)).translate(_SUPERSCRIPT)}".replace("-", "−")
        return text
    return str(value)


def html_table(rows, columns, *, formats=None, caption=None, raw=()):
    """Render ``rows`` (list of dict) as an HTML table.

    Every cell is escaped, except those of the columns named in ``raw``.

    Parameters
    ----------
    rows : list of dict
        The table's rows; a missing key gives the cell ``None``.
    columns : dict
        ``{key: header}`` in display order.
    formats : dict, optional
        ``{key: format spec}``; default ``.4g`` for numbers.
    caption : str, optional
        The table's caption.
    raw : collection of str, optional
        Keys of columns whose cells are trusted HTML built by the caller (e.g. links), inserted
        without escaping.

    Returns
    -------
    str

    Raises
    ------
    ValueError
        If ``raw`` names a key that is not a column.

    Examples
    --------
    >>> print(html_table([{"a": 1.0}], {"a": "A"}))
    <table class="table"><thead><tr><th>A</th></tr></thead><tbody><tr><td>1</td></tr></tbody></table>
    >>> html_table([{"a": "<b>x</b>", "b": "<a href='p.html'>p</a>"}], {"a": "A", "b": "B"},
    ...            raw={"b"}).split("<tbody>")[1]
    "<tr><td>&lt;b&gt;x&lt;/b&gt;</td><td><a href='p.html'>p</a></td></tr></tbody></table>"
    """
    formats = formats or {}
    raw = set(raw)
    if not raw <= set(columns):
        raise ValueError(f"raw must name columns {list(columns)}, but found {sorted(raw - set(columns))}")

    def cell(r, k):
        text = fmt(r.get(k), formats.get(k, ".4g"))
        return text if k in raw else html.escape(text)

    head = "".join(f"<th>{html.escape(h)}</th>" for h in columns.values())
    body = "".join("<tr>" + "".join(f"<td>{cell(r, k)}</td>" for k in columns) + "</tr>" for r in rows)
    cap = f"<caption>{html.escape(caption)}</caption>" if caption else ""
    return f'<table class="table">{cap}<thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>'


def compact(value, *, digits=4, max_items=6, max_chars=160):
    """A short text form of a record value (numbers, lists, matrices, dicts) for a table cell.

    Numbers get ``digits`` significant digits (through :func:`fmt`); lists print as
    ``[a, b, …] (n values)`` beyond ``max_items`` items, matrices as ``[[a, b], [c, d]]`` (rows
    shortened the same way); dicts as ``k: v; k: v`` (nested dicts in braces, beyond
    ``max_items`` keys ``…; (n keys)``); the whole text is cut at ``max_chars`` with ``…``.

    Parameters
    ----------
    value : object
        Nested dicts, lists, tuples, arrays, numbers, strings or None.
    digits : int, optional
        Significant digits of a number.
    max_items : int, optional
        Items of a list (or keys of a dict) shown before the rest is replaced by ``…``.
    max_chars : int, optional
        Length at which the text is cut.

    Returns
    -------
    str

    Examples
    --------
    >>> compact([[-1.175, 0.9871], [-8.458, -0.87765]])
    '[[-1.175, 0.9871], [-8.458, -0.8777]]'
    >>> compact({"LF": {"w_l": 1.0}, "T": 500.0, "label": "HF"})
    'LF: {w_l: 1}; T: 500; label: HF'
    >>> compact(list(range(21)))
    '[0, 1, 2, 3, 4, 5, …] (21 values)'
    >>> compact(None), compact(float("inf"))
    ('—', '∞')
    """
    text = _compact(value, f".{digits}g", max_items, top=True)
    return text if len(text) <= max_chars else text[:max_chars - 1].rstrip() + "…"


def _compact(value, spec, max_items, *, top=False):
    if isinstance(value, np.ndarray):
        value = value.tolist()
    elif isinstance(value, np.generic):
        value = value.item()
    if value is None:
        return "—"
    if isinstance(value, complex):
        return format(value, spec)
    if isinstance(value, dict):
        items = [f"{k}: {_compact(v, spec, max_items)}" for k, v in list(value.items())[:max_items]]
        if len(value) > max_items:
            items.append(f"… ({len(value)} keys)")
        text = "; ".join(items)
        return text if top else "{" + text + "}"
    if isinstance(value, list | tuple):
        items = [_compact(v, spec, max_items) for v in value[:max_items]]
        if len(value) <= max_items:
            return "[" + ", ".join(items) + "]"
        return "[" + ", ".join(items) + f", …] ({len(value)} values)"
    return fmt(value, spec)
