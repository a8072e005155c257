"""Small HTML tables for the notebooks (the book renders ``text/html`` outputs as is)."""

import html
import math

__all__ = ["html_table", "fmt"]


def fmt(value, spec=".4g"):
    """Format a number (or pass text through) for a table cell.

    Parameters
    ----------
    value : float, int, str or None
        The cell's value; infinities print as ∞, NaN and None as a dash, text as is.
    spec : str, optional
        Format specification of a finite number.

    Returns
    -------
    str

    Examples
    --------
    >>> fmt(0.123456), fmt(float("inf")), fmt(float("nan")), fmt("LF")
    ('0.1235', '∞', '—', 'LF')
    """
    if isinstance(value, bool) or value is None:
        return str(value)
    if isinstance(value, int | float):
        if math.isnan(value):
            return "—"  # nothing to show (e.g. no closed form)
        if math.isinf(value):
            return "∞" if value > 0 else "−∞"
        return format(value, spec)
    return str(value)


def html_table(rows, columns, *, formats=None, caption=None):
    """Render ``rows`` (list of dict) as an HTML table.

    Parameters
    ----------
    rows : list of dict
    columns : dict
        ``{key: header}`` in display order.
    formats : dict, optional
        ``{key: format spec}``; default ``.4g`` for numbers.
    caption : str, optional

    Examples
    --------
    >>> print(html_table([{"a": 1.0}], {"a": "A"}))
    <table class="table"><thead><tr><th>A</th></tr></thead><tbody><tr><td>1</td></tr></tbody></table>
    """
    formats = formats or {}
    head = "".join(f"<th>{html.escape(h)}</th>" for h in columns.values())
    body = "".join(
        "<tr>" + "".join(f"<td>{html.escape(fmt(r.get(k), formats.get(k, '.4g')))}</td>"
                         for k in columns) + "</tr>" for r in rows)
    cap = f"<caption>{html.escape(caption)}</caption>" if caption else ""
    return f'<table class="table">{cap}<thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>'
