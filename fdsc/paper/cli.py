"""Command line of the paper layer (also reachable as: python -m fdsc reproduce).

python -m fdsc reproduce --out DIR [--jobs N]
                                     recompute every artefact of the paper and write
                                     DIR/reproduction.json (the reproduction record), the
                                     chapters on N processes (default: the CPUs, at most 4)
python -m fdsc cold-times [--book DIR] [--out FILE]
                                     execute every chapter of the book alone, cold (an empty
                                     results folder each), and write the times to FILE
                                     (default: book/data/cold_times.json, which the book's
                                     environment page shows); takes many minutes
python -m fdsc disturbance-law [--n N] [--workers W] [--scheduler ADDRESS] [--out FILE | --replace]
                               [--robustness-only | --measured-only]
                                     the full non-stationary study (fixed controllers and laws;
                                     N draws per example, default 500), on W processes or a Dask
                                     scheduler, written to FILE (default:
                                     out/disturbance_law_full.json; --replace writes the stored
                                     study book/data/disturbance_law_full.json that the book reads)
python -m fdsc information [--workers W] [--replace]
                                     the ladder under measurement noise, delay and model error on
                                     the stored study's draws (fdsc.paper.pays.information)
python -m fdsc adaptive-rung [--workers W] [--replace]
                                     the ladder's adaptive-regulation rung on the stored study's
                                     draws (fdsc.paper.pays.adaptive_rung)
python -m fdsc observer-rung [--workers W] [--replace]
                                     the ladder with ŵ from a disturbance observer on noisy
                                     measurements of x (fdsc.paper.pays.observer_rung)
python -m fdsc variant-laws [--workers W] [--replace]
                                     the predictive law with a confidence check on the class's
                                     variants (fdsc.paper.pays.variant_laws)
python -m fdsc part-two [--n N] [--workers W] [--out DIR | --replace]
                                     every study above at one commit, the full study first
                                     (fdsc.paper.pays.part_two)
"""

import argparse
import json
import os
import sys
import time
from pathlib import Path

from fdsc.paper.record import JOBS_ENV, reproduction_record
from fdsc.paper.shared.results import RECORD_DIGITS, to_jsonable

__all__ = ["main", "reproduce", "cold_times_command", "disturbance_law_command", "to_jsonable",
           "RECORD_DIGITS", "SCHEDULER_TIMEOUT"]


#: How long ``disturbance-law --scheduler`` waits for the Dask scheduler before giving up.
SCHEDULER_TIMEOUT = "10s"


def _cannot_write(folder):
    """Why no file can be written in ``folder`` (created if missing), or None if one can."""
    for above in (folder, *folder.parents):
        if above.exists():
            if not above.is_dir():
                return f"{above} is a file, not a folder"
            break
    try:
        folder.mkdir(parents=True, exist_ok=True)
        probe = folder / ".fdsc-write-test"
        probe.write_text("", encoding="utf-8")
        probe.unlink()
    except OSError as exc:
        return exc.strerror or str(exc)
    return None


def _writable_dir(path, prog, flag="--out"):
    """Create the folder ``path`` if needed and check that a file can be written there, before
    computing; else exit with a message signed by the command ``prog`` and naming ``flag``."""
    why = _cannot_write(path)
    if why:
        raise SystemExit(f"{prog}: {flag} {path}: cannot write there ({why})")


def _writable_file(path, prog, flag="--out"):
    """Check, before computing, that the file ``path`` can be written: not a folder, in a folder
    that is or can be made one and is writable."""
    if path.is_dir():
        raise SystemExit(f"{prog}: {flag} {path}: is a folder, but a file to write is expected")
    why = _cannot_write(path.parent)
    if why:
        raise SystemExit(f"{prog}: {flag} {path}: cannot write its folder {path.parent} ({why})")


def _path(text):
    """An argparse type: a non-empty path (an empty one would mean the current folder)."""
    if not text:
        raise argparse.ArgumentTypeError("must name a path, but found an empty string (which would mean "
                                         "the current folder)")
    return Path(text)


def reproduce(argv=None):
    """``reproduce --out DIR``: recompute every artefact and write ``DIR/reproduction.json``.

    Registered as the command ``reproduce`` of ``python -m fdsc`` (entry-point group
    ``fdsc.commands``).

    Parameters
    ----------
    argv : list of str, optional
        The arguments after ``reproduce`` (default ``sys.argv[2:]``).

    Returns
    -------
    int
        Exit status (0 on success; a bad ``--out`` exits with a message before any computing).
    """
    parser = argparse.ArgumentParser(prog="python -m fdsc reproduce",
                                     description="recompute every artefact and write reproduction.json")
    parser.add_argument("--out", required=True, type=_path, help="output folder (created if missing)")
    parser.add_argument("--jobs", type=int, default=None,
                        help=f"processes computing the chapters (default: ${JOBS_ENV}, else the "
                             "number of CPUs, at most 4)")
    args = parser.parse_args(sys.argv[2:] if argv is None else argv)
    if args.jobs is not None and args.jobs < 1:
        parser.error(f"--jobs must be at least 1, found {args.jobs}")
    _writable_dir(args.out, parser.prog)
    t0 = time.perf_counter()
    saved = os.environ.get(JOBS_ENV)
    if args.jobs is not None:
        os.environ[JOBS_ENV] = str(args.jobs)
    try:
        record = reproduction_record()
    finally:
        if saved is None:
            os.environ.pop(JOBS_ENV, None)
        else:
            os.environ[JOBS_ENV] = saved
    record["environment"]["elapsed_s"] = time.perf_counter() - t0
    path = args.out / "reproduction.json"
    path.write_text(json.dumps(to_jsonable(record), indent=1) + "\n", encoding="utf-8")
    for e in record["entries"]:
        print(f"{e['id']:<16} {e['verdict']}")
    print(f"wrote {path} in {record['environment']['elapsed_s']:.1f} s")
    return 0


def cold_times_command(argv=None):
    """``cold-times [--book DIR] [--out FILE]``: measure every chapter's cold execution time.

    Registered as the command ``cold-times`` of ``python -m fdsc``
    (:func:`fdsc.paper.shared.environment.measure_cold_times`).

    Parameters
    ----------
    argv : list of str, optional
        The arguments after ``cold-times`` (default ``sys.argv[2:]``).

    Returns
    -------
    int
        Exit status (0 on success).
    """
    from fdsc.paper.shared.environment import COLD_TIMES_FILE, measure_cold_times

    root = Path(__file__).resolve().parents[2]
    parser = argparse.ArgumentParser(prog="python -m fdsc cold-times",
                                     description="execute every chapter alone, cold, and time it")
    parser.add_argument("--book", type=_path, default=root / "book", help="the book's folder")
    parser.add_argument("--out", type=_path, default=root / COLD_TIMES_FILE,
                        help="the JSON file to write")
    args = parser.parse_args(sys.argv[2:] if argv is None else argv)
    if not (args.book / "_toc.yml").is_file():
        parser.error(f"--book must be the book's folder (with _toc.yml), found {args.book}")
    _writable_file(args.out, parser.prog)
    result = measure_cold_times(args.book, args.out)
    print(f"wrote {args.out}: {len(result['chapters'])} chapters, "
          f"{sum(result['chapters'].values()):.0f} s in all on {result['host']['cpus']} CPUs")
    return 0


def disturbance_law_command(argv=None):
    """``disturbance-law [--n N] [--workers W] [--scheduler ADDRESS] [--out FILE]
    [--robustness-only | --measured-only]``: the full
    study of :mod:`fdsc.paper.pays.disturbance_law` (:func:`~fdsc.paper.pays.disturbance_law.full_study`).

    Parameters
    ----------
    argv : list of str, optional
        The arguments after ``disturbance-law`` (default ``sys.argv[2:]``).

    Returns
    -------
    int
        0. A bad argument (``--n`` below :data:`~fdsc.paper.pays.disturbance_law_full.N_MIN`, an
        ``--out`` that cannot be written, a scheduler that does not answer) exits with a one-line
        message before any computing.
    """
    import argparse
    from concurrent.futures import ProcessPoolExecutor

    from fdsc.paper.pays.disturbance_law import FULL_FILE, N_FULL, full_study, measured_robustness, robustness
    from fdsc.paper.pays.disturbance_law_full import N_MIN
    from fdsc.paper.shared.fixed_choice import FILE as CHOICE_FILE

    parser = argparse.ArgumentParser(prog="python -m fdsc disturbance-law",
                                     description="the full study of the law on the disturbance estimate")
    parser.add_argument("--n", type=int, default=N_FULL, help="draws per example (half train, half test)")
    parser.add_argument("--workers", type=int, default=os.cpu_count() or 1, help="processes")
    parser.add_argument("--scheduler", default=None,
                        help="address of a Dask scheduler (instead of processes)")
    root = Path(__file__).resolve().parents[2]
    parser.add_argument("--out", type=_path, default=Path("out") / FULL_FILE.name,
                        help="the JSON file to write (default out/disturbance_law_full.json; the book "
                             "reads the stored study, which only --replace overwrites)")
    parser.add_argument("--replace", action="store_true",
                        help=f"write the book's stored study ({FULL_FILE}) instead of --out")
    parser.add_argument("--robustness-only", action="store_true",
                        help="add the robustness study to an existing --out file instead of rerunning")
    parser.add_argument("--measured-only", action="store_true",
                        help="add only the runs on sampled measurements to an existing --out file")
    args = parser.parse_args(sys.argv[2:] if argv is None else argv)
    if args.n < N_MIN:
        parser.error(f"--n must be at least {N_MIN} (half of the draws train, half are scored), but "
                     f"found {args.n}")
    if args.workers < 1:
        parser.error(f"--workers must be at least 1, but found {args.workers}")
    if args.replace:
        args.out = root / FULL_FILE
    extend = args.robustness_only or args.measured_only
    if extend and not args.out.is_file():
        parser.error(f"--robustness-only and --measured-only need the full study in {args.out}, "
                     "which does not exist")
    stored = _stored_study(args.out, parser) if extend else None
    _writable_file(args.out, parser.prog, "--replace" if args.replace else "--out")
    if args.replace:
        _writable_file(Path(__file__).resolve().parent / "data" / CHOICE_FILE, parser.prog, "--replace")
    start, load_before = time.perf_counter(), os.getloadavg()[0]

    def run(executor):
        if not (args.robustness_only or args.measured_only):
            return full_study(args.n, executor=executor, out=args.out)
        result = stored
        if args.robustness_only:
            result["robustness"] = robustness(result, executor=executor)
        result["measured"] = measured_robustness(result, executor=executor)
        args.out.write_text(json.dumps(result, indent=1))
        return result

    if args.scheduler:
        from dask.distributed import Client

        try:
            client = Client(args.scheduler, timeout=SCHEDULER_TIMEOUT)
        except (OSError, ValueError) as exc:       # unreachable (a timeout), or not an address
            raise SystemExit(f"{parser.prog}: --scheduler {args.scheduler}: cannot connect to a Dask "
                             f"scheduler there ({exc})") from None
        with client:
            result = run(client)
    else:
        # one BLAS thread per worker: the step tables are small matrix exponentials, and several
        # workers each spinning several BLAS threads on the same cores run many times slower
        import multiprocessing

        for var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
            os.environ.setdefault(var, "1")
        with ProcessPoolExecutor(args.workers, mp_context=multiprocessing.get_context("spawn")) as pool:
            result = run(pool)
    if not (args.robustness_only or args.measured_only):
        # how long the stored study took, and where (the book states it beside the numbers)
        result["seconds"] = round(time.perf_counter() - start, 1)
        # the CPU time of this process and of its (joined) workers, and the host's load average
        # over the last minute before and after: with the wall time, what the host gave the run
        import resource

        usage = [resource.getrusage(who) for who in (resource.RUSAGE_SELF, resource.RUSAGE_CHILDREN)]
        cpu = sum(u.ru_utime + u.ru_stime for u in usage)
        result["host"] = {"cpus": os.cpu_count(), "workers": args.workers if not args.scheduler else None,
                          "scheduler": bool(args.scheduler), "cpu_seconds": round(cpu, 1),
                          "load_before": round(load_before, 2), "load_after": round(os.getloadavg()[0], 2)}
        args.out.write_text(json.dumps(result, indent=1))
    if args.replace:
        from fdsc.paper.shared.fixed_choice import FILE, write_choice

        write_choice(result, Path(__file__).resolve().parent / "data" / FILE)
    for example in ("aircraft", "generic"):
        r = result[example]
        print(f"{example}: median {r['median_ratio_vs_fixed_in_advance']:.3f}x {r['fixed_in_advance']}, "
              f"p95 {r['p95_ratio_vs_fixed_in_advance']:.3f}, wins {r['win_rate_vs_fixed_in_advance']:.0%} "
              f"of {r['draws_test']} test draws")
    print(f"wrote {args.out} in {time.perf_counter() - start:.0f} s")
    return 0


def _stored_study(path, parser):
    """The full study in ``path`` that ``--robustness-only`` or ``--measured-only`` extends, read and
    checked (both examples' stored controllers rebuilt) before computing; a file that is not one
    (truncated, binary, JSON of something else, a damaged controller) exits with a one-line message
    naming it."""
    from fdsc.paper.pays.stored_study import load_full, stored_fixed_set

    try:
        full = load_full(path)
        for example in ("aircraft", "generic"):
            stored_fixed_set(full, example)
    except (ValueError, KeyError, TypeError) as exc:
        why = exc.args[0] if isinstance(exc, KeyError) and exc.args else str(exc)
        parser.error(f"--out {path}: not a full study that --robustness-only or --measured-only can extend "
                     f"({why})")
    return full


def main(argv=None):
    """Entry point of ``python -m fdsc.paper`` (the same commands as ``python -m fdsc``).

    Parameters
    ----------
    argv : list of str, optional
        Command-line arguments (default ``sys.argv[1:]``).

    Returns
    -------
    int
        Exit status of the command.
    """
    parser = argparse.ArgumentParser(prog="python -m fdsc.paper", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("command", choices=["reproduce", "cold-times", "disturbance-law"])
    parser.add_argument("args", nargs=argparse.REMAINDER)
    args = parser.parse_args(argv)
    commands = {"reproduce": reproduce, "cold-times": cold_times_command,
                "disturbance-law": disturbance_law_command}
    return commands[args.command](args.args)
