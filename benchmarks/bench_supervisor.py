"""Benchmark of the law on the disturbance estimate (not a test: timings depend on the machine).

On the README's oscillator with its LF and HF gains (two modes), a piecewise disturbance of
``--segments`` pieces of 100 s alternating a slow and a fast tone, measures in one run:

* **law**: ``fdsc.supervise`` with the realization through copies (monitors in two banks of
  restarts, exact integration between decision points every 0.1 s, the switched loop with its
  copies): wall time, and the *equivalent* rate in steps of dt = 1 ms per second (the horizon in
  steps of 1 ms over the wall time: what a stepping simulator would have to reach to match it);
* **baseline**: ``fdsc.simulate_stream`` of one fixed loop over the same horizon at dt = 1 ms
  without the closed form (the compiled stepping loop): steps per second;
* their **ratio** (law time over baseline time), which does not depend on the host's speed;
* **measured**: the same law run causally on sampled measurements at dt = 1 ms
  (``Supervisor.run_measured``, backward-difference derivative): steps per second, and its ratio
  to the baseline.

Its last line is JSON (``law_s``, ``law_equivalent_steps_per_s``, ``baseline_steps_per_s``,
``ratio``, ``switches``, ``measured_steps_per_s``, ``measured_ratio``, ``measured_switches``, the
host's CPUs and load).

Usage: ``python benchmarks/bench_supervisor.py [--segments K] [--repeat R]``.
"""

import argparse
import json
import os
import time

import numpy as np

import fdsc

PLANT = fdsc.Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
                   [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.1]])
GAINS = [np.array([[-21.85, -22.27]]), np.array([[0.495, -1.473]])]


def _best(fn, repeat):
    out, best = None, np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return out, best


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--segments", type=int, default=20)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args(argv)
    slow, fast = fdsc.Sinusoids([1.0, 0.5], [0.2, 0.3]), fdsc.Sinusoids([1.0], [12.0])
    horizon = 100.0 * args.segments
    d = fdsc.Piecewise(np.arange(args.segments + 1) * 100.0,
                       [slow if k % 2 == 0 else fast for k in range(args.segments)])
    K0 = fdsc.lqr_gain(PLANT)
    law = lambda: fdsc.supervise(PLANT, GAINS, d, horizon, K0=K0)            # noqa: E731
    law()                                                                   # compile
    run, t_law = _best(law, args.repeat)
    loop = PLANT.closed_loop(GAINS[0])
    steps = round(horizon / 1e-3)
    base = lambda: fdsc.simulate_stream(loop, d, horizon, 1e-3, closed_form=False)  # noqa: E731
    base()
    _r, t_base = _best(base, args.repeat)
    sup = fdsc.Supervisor(PLANT, GAINS, K0=K0)
    measured = lambda: sup.run_measured(d, horizon, 1e-3, derivative="backward")  # noqa: E731
    measured()
    mrun, t_meas = _best(measured, args.repeat)
    out = {"horizon_s": horizon, "law_s": t_law, "law_equivalent_steps_per_s": steps / t_law,
           "baseline_steps_per_s": steps / t_base, "ratio": t_law / t_base,
           "switches": run.switches, "measured_steps_per_s": steps / t_meas,
           "measured_ratio": t_meas / t_base, "measured_switches": mrun.switches,
           "cpus": os.cpu_count(), "load": os.getloadavg()[0]}
    print(f"law: {t_law:.3f} s for {horizon:g} s ({steps / t_law:.3g} equivalent steps/s of 1 ms), "
          f"{run.switches} switches; stepping baseline: {steps / t_base:.3g} steps/s; "
          f"ratio {t_law / t_base:.3g}; on sampled measurements: {steps / t_meas:.3g} steps/s "
          f"(ratio {t_meas / t_base:.3g}), {mrun.switches} switches")
    print(json.dumps(out))


if __name__ == "__main__":
    main()
