"""Compare two reproduction records number by number.

    python tests/compare_records.py OLD.json NEW.json [--rtol 1e-9] [--allow-new] [--ignore KEY ...]

Every entry (matched by id) and every figure is compared leaf by leaf: numbers to ``rtol``
relative (``|a − b| ≤ rtol · max(|a|, |b|)``; two zeros are equal), strings and booleans exactly,
and the structure (keys, list lengths) exactly. The environment (versions, timings) is ignored.
With ``--allow-new``, entries and figures present only in NEW (additions) are listed but do not
count as differences. With ``--ignore KEY`` (repeatable), values under a key of that name are not
compared (for prose such as ``source`` whose wording was corrected). Exit status 0 if the
records agree, 1 otherwise, with one line per difference.
"""

import argparse
import json
import math
import sys

__all__ = ["compare_records", "main"]


def _compare(a, b, path, rtol, out, ignore=()):
    if isinstance(a, dict) and isinstance(b, dict):
        if a.keys() != b.keys():
            out.append(f"{path}: keys differ: only old {sorted(a.keys() - b.keys())}, "
                       f"only new {sorted(b.keys() - a.keys())}")
        for k in sorted((a.keys() & b.keys()) - set(ignore)):
            _compare(a[k], b[k], f"{path}.{k}", rtol, out, ignore)
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            out.append(f"{path}: length {len(a)} != {len(b)}")
        for k, (x, y) in enumerate(zip(a, b, strict=False)):
            _compare(x, y, f"{path}[{k}]", rtol, out, ignore)
    elif isinstance(a, bool) or isinstance(b, bool) or isinstance(a, str) or isinstance(b, str):
        if a != b:
            out.append(f"{path}: {a!r} != {b!r}")
    elif isinstance(a, int | float) and isinstance(b, int | float):
        if not (a == b or abs(a - b) <= rtol * max(abs(a), abs(b))) and not (
                math.isnan(a) and math.isnan(b)):
            out.append(f"{path}: {a!r} != {b!r} (relative {abs(a - b) / max(abs(a), abs(b)):.2e})")
    elif a != b:
        out.append(f"{path}: {a!r} != {b!r}")


def compare_records(old, new, rtol=1e-9, *, allow_new=False, ignore=()):
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
    """
    out = []
    old_e = {e["id"]: e for e in old["entries"]}
    new_e = {e["id"]: e for e in new["entries"]}
    new_f = new["figures"]
    if allow_new:
        new_e = {k: v for k, v in new_e.items() if k in old_e}
        new_f = {k: v for k, v in new_f.items() if k in old["figures"]}
    _compare(old_e, new_e, "entries", rtol, out, ignore)
    _compare(old["figures"], new_f, "figures", rtol, out, ignore)
    return out


def main(argv=None):
    """Command line: compare two record files; print the differences.

    Parameters
    ----------
    argv : list of str, optional
        ``OLD NEW [--rtol R] [--allow-new] [--ignore KEY ...]`` (default ``sys.argv[1:]``).

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
    args = parser.parse_args(argv)
    with open(args.old, encoding="utf-8") as fh:
        old = json.load(fh)
    with open(args.new, encoding="utf-8") as fh:
        new = json.load(fh)
    diffs = compare_records(old, new, args.rtol, allow_new=args.allow_new, ignore=args.ignore)
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
