"""Command line: ``python -m fdsc reproduce --out DIR`` writes ``DIR/reproduction.json``."""

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

from .record import reproduction_record

__all__ = ["main", "to_jsonable"]


def to_jsonable(obj):
    """Convert arrays, complex numbers and NumPy scalars to JSON-friendly values."""
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
        return x if np.isfinite(x) else str(x)
    return obj


def main(argv=None):
    """Entry point of ``python -m fdsc``."""
    parser = argparse.ArgumentParser(prog="python -m fdsc", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)
    rep = sub.add_parser("reproduce", help="recompute every artefact and write reproduction.json")
    rep.add_argument("--out", required=True, type=Path, help="output folder (created if missing)")
    args = parser.parse_args(argv)
    if args.command == "reproduce":
        t0 = time.perf_counter()
        record = reproduction_record()
        record["environment"]["elapsed_s"] = time.perf_counter() - t0
        args.out.mkdir(parents=True, exist_ok=True)
        path = args.out / "reproduction.json"
        path.write_text(json.dumps(to_jsonable(record), indent=1) + "\n", encoding="utf-8")
        for e in record["entries"]:
            print(f"{e['id']:<16} {e['verdict']}")
        print(f"wrote {path} in {record['environment']['elapsed_s']:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
