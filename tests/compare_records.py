"""Compare two reproduction records number by number.

    python tests/compare_records.py OLD.json NEW.json [--rtol 1e-9] [--allow-new] [--ignore KEY ...]
                                    [--relative-key KEY ...]

Every entry (matched by id) and every figure is compared leaf by leaf: numbers to ``rtol``
relative (``|a − b| ≤ rtol · max(|a|, |b|)``; two zeros are equal), strings and booleans exactly,
and the structure (keys, list lengths) exactly. The environment (versions, timings) is ignored.
With ``--allow-new``, entries and figures present only in NEW (additions) are listed but do not
count as differences. With ``--ignore KEY`` (repeatable), values under a key of that name are not
compared (for prose such as ``source`` whose wording was corrected). With ``--relative-key KEY``
(repeatable), numbers under a key of that name are relative changes ``|E₂ − E₁| / E₁`` of two
results of the record: they are compared absolutely, ``|a − b| ≤ 2 rtol (1 + max(|a|, |b|))``,
the most they move when E₁ and E₂ each move by rtol relative (a relative change near rounding,
such as 5e-15, is all rounding, and comparing it relative to itself would ask for the last bits
of E₁ and E₂). Exit status 0 if the records agree, 1 otherwise, with one line per difference.
"""

import argparse
import json
import math
import sys

__all__ = ["compare_records", "main"]


def _compare(a, b, path, rtol, out, ignore=(), relative_keys=(), change=False):
    if isinstance(a, dict) and isinstance(b, dict):
        if a.keys() != b.keys():
            out.append(f"{path}: keys differ: only old {sorted(a.keys() - b.keys())}, "
                       f"only new {sorted(b.keys() - a.keys())}")
        for k in sorted((a.keys() & b.keys()) - set(ignore)):
            _compare(a[k], b[k], f"{path}.{k}", rtol, out, ignore, relative_keys,
                     change or k in relative_keys)
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            out.append(f"{path}: length {len(a)} != {len(b)}")
        for k, (x, y) in enumerate(zip(a, b, strict=False)):
            _compare(x, y, f"{path}[{k}]", rtol, out, ignore, relative_keys, change)
    elif isinstance(a, bool) or isinstance(b, bool) or isinstance(a, str) or isinstance(b, str):
        if a != b:
            out.append(f"{path}: {a!r} != {b!r}")
    elif isinstance(a, int | float) and isinstance(b, int | float):
        if math.isnan(a) and math.isnan(b):
            return
        big = max(abs(a), abs(b))
        if change:
            if not abs(a - b) <= 2 * rtol * (1 + big):
                out.append(f"{path}: {a!r} != {b!r} (a relative change; absolute {abs(a - b):.2e})")
        elif not (a == b or abs(a - b) <= rtol * big):
            out.append(f"{path}: {a!r} != {b!r} (relative {abs(a - b) / big:.2e})")
    elif a != b:
        out.append(f"{path}: {a!r} != {b!r}")


def compare_records(old, new, rtol=1e-9, *, allow_new=False, ignore=(), relative_keys=()):
    """Differences between two records (dicts as written by ``python -m fdsc reproduce``).

    Parameters
    ----------
    old, new : dict
        Records with ``entries`` (list of dict with ``id``) and ``figures`` (dict).
    rtol : float, optional
        Relative tolerance for numbers.
    allow_new : bool, optional
        Ignore entries and figures that only ``new`` has (additions); everything ``old`` has
        must still be there and equal.
    ignore : sequence of str, optional
        Keys whose values are not compared wherever they occur (prose such as ``source``).
    relative_keys : sequence of str, optional
        Keys whose numbers are relative changes of two results, compared absolutely (see the
        module docstring).

    Returns
    -------
    list of str
        One line per difference (empty if the records agree).

    Examples
    --------
    >>> r = {"entries": [{"id": "a", "recomputed": 1.0}], "figures": {}}
    >>> compare_records(r, {"entries": [{"id": "a", "recomputed": 1.0 + 1e-12}], "figures": {}})
    []
    >>> compare_records(r, {"entries": [{"id": "a", "recomputed": 1.001}], "figures": {}})
    ['entries.a.recomputed: 1.0 != 1.001 (relative 9.99e-04)']
    >>> compare_records(r, {"entries": [{"id": "a", "recomputed": 2.0}], "figures": {}},
    ...                 ignore=["recomputed"])
    []
    >>> c = {"entries": [{"id": "a", "rel_change": 5.25e-15}], "figures": {}}
    >>> compare_records(c, {"entries": [{"id": "a", "rel_change": 5.04e-15}], "figures": {}})
    ['entries.a.rel_change: 5.25e-15 != 5.04e-15 (relative 4.00e-02)']
    >>> compare_records(c, {"entries": [{"id": "a", "rel_change": 5.04e-15}], "figures": {}},
    ...                 relative_keys=["rel_change"])
    []
    >>> compare_records(c, {"entries": [{"id": "a", "rel_change": 3e-9}], "figures": {}},
    ...                 relative_keys=["rel_change"])
    ['entries.a.rel_change: 5.25e-15 != 3e-09 (a relative change; absolute 3.00e-09)']
    """
    out = []
    old_e = {e["id"]: e for e in old["entries"]}
    new_e = {e["id"]: e for e in new["entries"]}
    new_f = new["figures"]
    if allow_new:
        new_e = {k: v for k, v in new_e.items() if k in old_e}
        new_f = {k: v for k, v in new_f.items() if k in old["figures"]}
    _compare(old_e, new_e, "entries", rtol, out, ignore, relative_keys)
    _compare(old["figures"], new_f, "figures", rtol, out, ignore, relative_keys)
    return out


def main(argv=None):
    """Command line: compare two record files; print the differences.

    Parameters
    ----------
    argv : list of str, optional
        ``OLD NEW [--rtol R] [--allow-new] [--ignore KEY ...] [--relative-key KEY ...]``
        (default ``sys.argv[1:]``).

    Returns
    -------
    int
        0 if the records agree, 1 otherwise.
    """
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("old")
    parser.add_argument("new")
    parser.add_argument("--rtol", type=float, default=1e-9)
    parser.add_argument("--allow-new", action="store_true",
                        help="entries and figures only NEW has are additions, not differences")
    parser.add_argument("--ignore", action="append", default=[], metavar="KEY",
                        help="do not compare values under keys of this name (repeatable)")
    parser.add_argument("--relative-key", action="append", default=[], metavar="KEY",
                        help="numbers under keys of this name are relative changes of two results: "
                             "compared absolutely to 2 rtol (1 + |value|) (repeatable)")
    args = parser.parse_args(argv)
    with open(args.old, encoding="utf-8") as fh:
        old = json.load(fh)
    with open(args.new, encoding="utf-8") as fh:
        new = json.load(fh)
    diffs = compare_records(old, new, args.rtol, allow_new=args.allow_new, ignore=args.ignore,
                            relative_keys=args.relative_key)
    n_old = len(old["entries"])
    added = sorted({e["id"] for e in new["entries"]} - {e["id"] for e in old["entries"]})
    added += sorted(f"figure {k}" for k in set(new["figures"]) - set(old["figures"]))
    if added:
        print(f"only in {args.new}: {', '.join(added)}")
    for line in diffs:
        print(line)
    ignored = f"; keys not compared: {', '.join(args.ignore)}" if args.ignore else ""
    print(f"{len(diffs)} differences at rtol={args.rtol:g} ({n_old} entries, "
          f"{len(old['figures'])} figures compared{ignored})")
    return 1 if diffs else 0


if __name__ == "__main__":
    sys.exit(main())
