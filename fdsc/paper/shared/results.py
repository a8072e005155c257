"""What a chapter contributes to the reproduction record: entries and figure data.

Each chapter module returns small typed results (frozen dataclasses); a result that carries
record entries has ``to_record()`` returning a :class:`RecordPart`, and
:func:`fdsc.paper.record.reproduction_record` adds the parts up.
"""

from dataclasses import dataclass, field

import numpy as np

from fdsc.paper.shared.verdict import VERDICTS

__all__ = ["RecordPart", "entry", "pick", "to_jsonable", "RECORD_DIGITS"]

_REQUIRED = ("id", "source", "paper", "recomputed", "verdict", "note")


def entry(id: str, source: str, paper: object, recomputed: object, verdict: str,  # noqa: A002  (the record's key)
          note: str, **extra) -> dict:
    """One record entry ``{"id", "source", "paper", "recomputed", "verdict", "note", ...}``.

    Parameters
    ----------
    id : str
        Identifier of the entry (fixed once published: the issues and the book refer to it).
    source : str
        Where the paper prints the quantity ("Sec. IV, K_{f_1}"), or what it is derived from.
    paper : object
        The printed value (None when the paper prints nothing: verdict "new").
    recomputed : object
        Our value.
    verdict : str
        One of :data:`fdsc.paper.shared.verdict.VERDICTS`.
    note : str
        Why the verdict, in a sentence or two.
    **extra
        Further keys (per-item verdicts, statuses, eigenvalues).

    Returns
    -------
    dict

    Raises
    ------
    ValueError
        If the verdict is unknown or the id is not a non-empty string.

    Examples
    --------
    >>> entry("x", "Sec. IV", 1.0, 1.0, "match", "equal")["verdict"]
    'match'
    """
    if verdict not in VERDICTS:
        raise ValueError(f"verdict must be one of {VERDICTS}, but found {verdict!r}")
    if not isinstance(id, str) or not id:
        raise ValueError(f"id must be a non-empty string, but found {id!r}")
    return {"id": id, "source": source, "paper": paper, "recomputed": recomputed,
            "verdict": verdict, "note": note, **extra}


@dataclass(frozen=True)
class RecordPart:
    """Entries and figure data that one result contributes to the record.

    Parameters
    ----------
    entries : tuple of dict
        Record entries (see :func:`entry`), in the order the record lists them.
    figures : dict
        Figure data keyed by figure id (see :data:`fdsc.paper.record.FIGURE_IDS`).

    Raises
    ------
    ValueError
        If an entry lacks one of the keys ``id``, ``source``, ``paper``, ``recomputed``,
        ``verdict``, ``note``; or, for ``+``, if an entry id or a figure key repeats.

    Examples
    --------
    >>> a = RecordPart((entry("a", "s", None, 1, "new", "n"),))
    >>> b = RecordPart(figures={"f": {"x": [1]}})
    >>> [e["id"] for e in (a + b).entries], list((a + b).figures)
    (['a'], ['f'])
    """

    entries: tuple = ()
    figures: dict = field(default_factory=dict)

    def __post_init__(self):
        entries = tuple(self.entries)
        for e in entries:
            missing = [k for k in _REQUIRED if k not in e]
            if missing:
                raise ValueError(f"entries: entry {e.get('id')!r} lacks {missing}")
        object.__setattr__(self, "entries", entries)

    def __add__(self, other: "RecordPart") -> "RecordPart":
        """Concatenate the entries and merge the figures (ids and figure keys must be unique)."""
        ids = {e["id"] for e in self.entries}
        dup = ids & {e["id"] for e in other.entries}
        dup_fig = set(self.figures) & set(other.figures)
        if dup or dup_fig:
            raise ValueError(f"other: duplicate entry ids {sorted(dup)} or figures {sorted(dup_fig)}")
        return RecordPart(self.entries + other.entries, {**self.figures, **other.figures})


def pick(items, attr, value):
    """The item of ``items`` whose attribute ``attr`` equals ``value`` (row lookup by name).

    Parameters
    ----------
    items : iterable
        Rows of a result (dataclasses).
    attr : str
        Name of the key attribute (e.g. ``"gain"``).
    value : object
        The key looked for.

    Returns
    -------
    object
        The first matching row.

    Raises
    ------
    KeyError
        Naming the key and the keys available.

    Examples
    --------
    >>> from types import SimpleNamespace as R
    >>> pick([R(gain="K_f1", v=1), R(gain="K_f3", v=3)], "gain", "K_f3").v
    3
    """
    items = list(items)
    for item in items:
        if getattr(item, attr) == value:
            return item
    raise KeyError(f"{attr} {value!r} not found; available: {[getattr(i, attr) for i in items]}")


#: Significant digits of the floats written to the record (far beyond any printed number; the
#: last digits of a solver's answer are rounding noise and would make two builds differ).
RECORD_DIGITS = 10


def to_jsonable(obj):
    """Convert arrays, complex numbers and NumPy scalars to JSON-friendly values.

    Floats are rounded to :data:`RECORD_DIGITS` significant digits; non-finite floats become
    the strings ``"inf"``, ``"-inf"``, ``"nan"``.

    Parameters
    ----------
    obj : object
        Nested dicts, lists, tuples, arrays and scalars.

    Returns
    -------
    object
        The same structure with JSON-serializable leaves.
    """
    if isinstance(obj, dict):
        return {str(k): to_jsonable(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [to_jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return to_jsonable(obj.tolist())
    if isinstance(obj, complex | np.complexfloating):
        return {"re": float(obj.real), "im": float(obj.imag)}
    if isinstance(obj, np.bool_):
        return bool(obj)
    if isinstance(obj, np.integer):
        return int(obj)
    if isinstance(obj, float | np.floating):
        x = float(obj)
        return float(f"{x:.{RECORD_DIGITS}g}") if np.isfinite(x) else str(x)
    return obj
