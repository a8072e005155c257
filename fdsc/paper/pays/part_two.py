"""Every stored study of Part II at one commit: ``python -m fdsc part-two``.

The full study (:func:`fdsc.paper.pays.disturbance_law_full.full_study`: the fixed controllers,
the laws, the ladder) first, then on its result, in memory, the four studies on its draws: the
noise study (:mod:`~fdsc.paper.pays.information`), the adaptive rung
(:mod:`~fdsc.paper.pays.adaptive_rung`), the variants with the confident law
(:mod:`~fdsc.paper.pays.variant_laws`) and the disturbance observer
(:mod:`~fdsc.paper.pays.observer_rung`). Each is written where its own command writes it, with
its wall time, CPU time and host; :data:`RUN_FILE` holds the whole run's (the book states it).

The files are kept in a pending folder (untracked) until the last study ends and then moved into
place, so that the tree stays clean while the studies run: each study records the commit it was
computed at and whether the tree had uncommitted changes, and a study's own output written into a
tracked file would count as one.

A run stopped part-way (a machine shut down after hours) is taken up with ``--resume``: every
study whose file in the pending folder was computed at this commit, with the sources it depends
on unchanged (and, for the full study, the same number of draws), is read back instead of
recomputed, up to the first that is missing or stale; that one and all after it are computed.
"""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path

__all__ = ["STUDIES", "RUN_FILE", "PENDING", "part_two", "main"]

#: The studies on the full study's draws, in the order they run: (name, module, function, file).
STUDIES = (("information", "fdsc.paper.pays.information", "information_study", "INFO_FILE"),
           ("adaptive rung", "fdsc.paper.pays.adaptive_rung", "adaptive_study", "ADAPTIVE_FILE"),
           ("variant laws", "fdsc.paper.pays.variant_laws", "variant_law_study", "VARIANT_FILE"),
           ("observer rung", "fdsc.paper.pays.observer_rung", "observer_study", "OBSERVER_FILE"))
#: The record of the whole run (relative to the repository's root).
RUN_FILE = Path("book") / "data" / "part_two_run.json"
#: Where the files wait (inside the folder written) until the last study ends.
PENDING = ".part_two_pending"


def _full(_unused, *, executor, n):
    """The full study of ``n`` draws per example (the signature :func:`run_on_pool` calls)."""
    from fdsc.paper.pays.disturbance_law_full import full_study

    return full_study(n, executor=executor)


def _sizes(study, n):
    """A study's test and training draws for a full study of n draws per example: its defaults,
    or fewer where the full study has fewer test draws (a smaller run, to try the command)."""
    import inspect

    half = n // 2
    out = {}
    for key, par in inspect.signature(study).parameters.items():
        if key in ("n_test", "n_train") and par.default is not inspect.Parameter.empty:
            out[key] = max(2 if key == "n_test" else 1, min(par.default, half // 2))
    return out


def _reusable(path, module, n=None):
    """The study stored at ``path`` if it was computed at this commit from unchanged sources (and
    with ``n`` draws per example, when given), else None."""
    from fdsc.paper.shared.cache import study_fingerprint
    from fdsc.paper.shared.environment import build_commit

    if not path.is_file():
        return None
    res = json.loads(path.read_text(encoding="utf-8"))
    if (res.get("commit") != build_commit() or res.get("fingerprint") != study_fingerprint(module)
            or (n is not None and res.get("n") != n)):
        return None
    return res


def part_two(n: int, workers: int, folder, resume: bool = False) -> dict:
    """Run every study (module docstring) on ``workers`` processes and write each to ``folder``
    under its stored file's name.

    Parameters
    ----------
    n : int
        Draws per example of the full study (below its default, the other studies take fewer
        draws too: at most a quarter of n each for testing and training).
    workers : int
    folder : path
        Where the files go (the repository's ``book/data`` to replace the stored studies).
    resume : bool, optional
        Read back the studies a stopped run left in the pending folder (module docstring).

    Returns
    -------
    dict
        The run's record: ``commit``, ``fingerprint`` (the full study's), ``studies`` ({name:
        {"file", "seconds", "cpu_seconds"}}), ``seconds`` (the sum of the studies' wall times),
        ``resumed`` (the names of the studies read back, empty unless ``resume``), ``host``.
    """
    import importlib

    from fdsc.paper.pays.stored_study import FULL_FILE
    from fdsc.paper.pays.study_command import run_on_pool

    folder = Path(folder)
    pending = folder / PENDING
    pending.mkdir(parents=True, exist_ok=True)
    load0 = os.getloadavg()[0]
    reused = []

    def run(name, module, path, compute, n=None):
        # read back while the studies before it were read back too; else compute
        res = _reusable(path, module, n) if resume and len(reused) == len(done) else None
        if res is None:
            res = compute()
            path.write_text(json.dumps(res, indent=1) + "\n", encoding="utf-8")
            print(f"part two: {name} took {res['seconds']:.0f} s", file=sys.stderr, flush=True)
        else:
            reused.append(name)
            print(f"part two: {name} read back from {path}", file=sys.stderr, flush=True)
        done[name] = {"file": path.name, "seconds": res["seconds"], "cpu_seconds": res["host"]["cpu_seconds"]}
        return res

    def full_study():
        res = run_on_pool(_full, None, workers, n=n)
        res["host"]["scheduler"] = False
        return res

    done = {}
    run("full study", "fdsc.paper.pays.disturbance_law_full", pending / FULL_FILE.name, full_study, n)
    # the studies on it read what the book reads: the file, not the object in memory
    full = json.loads((pending / FULL_FILE.name).read_text(encoding="utf-8"))
    for name, module, function, file in STUDIES:
        mod = importlib.import_module(module)
        study = getattr(mod, function)
        run(name, module, pending / getattr(mod, file).name,
            lambda study=study: run_on_pool(study, full, workers, **_sizes(study, n)))
    for f in (v["file"] for v in done.values()):
        (pending / f).replace(folder / f)
    pending.rmdir()
    return {"commit": full["commit"], "fingerprint": full["fingerprint"], "n": n, "studies": done,
            "seconds": round(sum(v["seconds"] for v in done.values()), 1), "resumed": reused,
            "host": {"cpus": os.cpu_count(), "workers": workers, "load_before": round(load0, 2),
                     "load_after": round(os.getloadavg()[0], 2)}}


def main(argv=None) -> int:
    """``python -m fdsc part-two [--n N] [--workers W] [--out DIR | --replace] [--resume]``: every
    study of Part II at this commit (module docstring), written to DIR (default ``out``) or, with
    ``--replace``, over the stored studies the book reads (and the fixed choice the record reads);
    ``--resume`` takes up a stopped run.

    Parameters
    ----------
    argv : list of str, optional

    Returns
    -------
    int
        0 on success (a bad argument exits with a one-line message before any computing).
    """
    import argparse

    from fdsc.paper.pays.disturbance_law_full import N_FULL, N_MIN
    from fdsc.paper.pays.study_command import REPO

    ap = argparse.ArgumentParser(prog="python -m fdsc part-two",
                                 description="every stored study of Part II at one commit")
    ap.add_argument("--n", type=int, default=N_FULL, help="draws per example of the full study")
    ap.add_argument("--workers", type=int, default=min(os.cpu_count() or 1, 4))
    ap.add_argument("--out", default="out", help="the folder to write (default out)")
    ap.add_argument("--replace", action="store_true",
                    help=f"write the stored studies in {RUN_FILE.parent}, which the book reads")
    ap.add_argument("--resume", action="store_true",
                    help="read back the studies a stopped run left at this commit, compute the rest")
    args = ap.parse_args(argv)
    if args.n < N_MIN:
        ap.error(f"--n must be at least {N_MIN}, but found {args.n}")
    if args.workers < 1:
        ap.error(f"--workers must be at least 1, but found {args.workers}")
    folder = REPO / RUN_FILE.parent if args.replace else Path(args.out)
    record = part_two(args.n, args.workers, folder, resume=args.resume)
    (folder / RUN_FILE.name).write_text(json.dumps(record, indent=1) + "\n", encoding="utf-8")
    if args.replace:
        from fdsc.paper.pays.stored_study import load_full
        from fdsc.paper.shared.fixed_choice import FILE, write_choice

        write_choice(load_full(folder / "disturbance_law_full.json"), REPO / "fdsc" / "paper" / "data" / FILE)
    print(f"part two: {record['seconds']:.0f} s on {args.workers} workers; written to {folder}",
          file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
