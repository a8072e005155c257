"""Benchmark of simulate_batch scaled out (not a test: timings depend on the machine and its load).

On the README's own-plant design (two modes, three tones per draw, dt = 1 ms), measures in one
run, for N seeded draws under the switching law (default N = 1000, 20 s each):

* **threads**: ``fdsc.simulate_batch(cases)`` on every core of this process: cases per second;
* **LocalCluster**: the same call with ``executor=client`` on a ``dask.distributed.LocalCluster``
  of W worker processes (one thread each; default W = the number of CPUs): cases per second (the
  cluster already started and its workers warm: each has run one small batch), and the equality
  of the results with the thread path, bit for bit;
* **overhead per case**: the same N cases with a horizon of two steps, on the cluster, minus the
  same on threads, per case: the cost of sending a case to a worker and its result back;
* **projection**: the time of a 10⁶-draw study of such cases per worker, and on W workers, from
  the cluster's measured time per case.

Its last line is JSON (``threads_cases_per_s``, ``cluster_cases_per_s``, ``ratio``,
``overhead_ms_per_case``, ``projected_hours_1e6_per_worker``, ``bit_for_bit``, the host's CPUs
and load).

Usage: ``python benchmarks/bench_scale_out.py [--n N] [--workers W] [--horizon T]``.
"""

import argparse
import json
import os
import time

import control
import numpy as np
from dask.distributed import Client, LocalCluster

import fdsc


def _cases(n, horizon, seed=1):
    plant = control.ss([[0.0, 1.0], [-4.0, -0.4]], [[0.0, 0.0], [1.0, 1.0]],
                       [[1.0, 0.0], [0.0, 0.0]], [[0.0, 0.0], [0.0, 0.1]])
    ctrl = fdsc.FDSC.synthesize(plant, [fdsc.Band.lf(0.5), fdsc.Band.hf(5.0)], in_band=1,
                                n_disturbances=1)
    rng = np.random.default_rng(seed)
    draws = [fdsc.Sinusoids(rng.uniform(0.1, 1.0, 3), rng.uniform(0.05, 20.0, 3)) for _ in range(n)]
    return [ctrl.case(d, horizon, 1e-3) for d in draws]


def _timed(fn):
    t0 = time.perf_counter()
    out = fn()
    return out, time.perf_counter() - t0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--n", type=int, default=1000, help="cases (draws)")
    parser.add_argument("--workers", type=int, default=os.cpu_count() or 1, help="cluster workers")
    parser.add_argument("--horizon", type=float, default=20.0, help="seconds per case")
    args = parser.parse_args()
    cases = _cases(args.n, args.horizon)
    tiny = _cases(args.n, 2e-3)
    fdsc.simulate_batch(cases[:4])                      # compile (or load) the loops here
    ref, t_threads = _timed(lambda: fdsc.simulate_batch(cases))
    _, t_threads_tiny = _timed(lambda: fdsc.simulate_batch(tiny))
    with LocalCluster(n_workers=args.workers, threads_per_worker=1, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        fdsc.simulate_batch(cases[:4 * args.workers], executor=client, chunksize=4)   # warm workers
        out, t_cluster = _timed(lambda: fdsc.simulate_batch(cases, executor=client))
        _, t_cluster_tiny = _timed(lambda: fdsc.simulate_batch(tiny, executor=client))
    same = bool(np.array_equal(out.energy, ref.energy) and np.array_equal(out.switches, ref.switches))
    steps = args.n * round(args.horizon / 1e-3)
    per_case = t_cluster * args.workers / args.n          # worker-seconds per case
    result = {
        "host_cpus": os.cpu_count(), "load_1min": round(os.getloadavg()[0], 2), "n": args.n,
        "workers": args.workers, "horizon_s": args.horizon, "steps": steps,
        "threads_s": round(t_threads, 3), "cluster_s": round(t_cluster, 3),
        "threads_cases_per_s": round(args.n / t_threads, 1),
        "cluster_cases_per_s": round(args.n / t_cluster, 1),
        "ratio": round(t_threads / t_cluster, 3),
        "threads_steps_per_s": round(steps / t_threads),
        "overhead_ms_per_case": round(1e3 * (t_cluster_tiny - t_threads_tiny) / args.n, 3),
        "projected_hours_1e6_per_worker": round(per_case * 1e6 / 3600, 2),
        "projected_hours_1e6_on_workers": round(per_case * 1e6 / 3600 / args.workers, 2),
        "bit_for_bit": same,
    }
    print(f"{args.n} cases of {args.horizon:g} s ({steps:.3g} steps) on {os.cpu_count()} CPUs, "
          f"load {result['load_1min']}:")
    print(f"  threads      {t_threads:7.2f} s  {result['threads_cases_per_s']:8.1f} cases/s")
    print(f"  LocalCluster {t_cluster:7.2f} s  {result['cluster_cases_per_s']:8.1f} cases/s "
          f"({args.workers} workers; threads / cluster time = {result['ratio']})")
    print(f"  overhead per case sent to a worker: {result['overhead_ms_per_case']} ms")
    print(f"  a 1e6-draw study: {result['projected_hours_1e6_per_worker']} h per worker, "
          f"{result['projected_hours_1e6_on_workers']} h on {args.workers}")
    print(f"  the same numbers bit for bit: {same}")
    print(json.dumps(result))


if __name__ == "__main__":
    main()
