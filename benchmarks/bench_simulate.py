"""Benchmark of the simulators (not a test: timings depend on the machine and its load).

Measures in one run, on the paper's FDSC loop (modes PassC-LF / PassC-HF, the paper's Q's, the
mixed disturbance d_h + 0.1 d_l: six tones, dt = 1 ms), every rate as a ratio against baselines
measured in the same run:

* **streaming path** (``fdsc.simulate_stream``, reductions only): end-to-end switched steps per
  second (preparation included, one core), and the loop's own rate (the same run minus the
  time of a one-step run, i.e. minus the preparation), by the loop specialized to the run's
  sizes (``specialize=True``), and by the general loop (``specialize=False``);
* **previous exact method** (``fdsc.simulate``, full trajectories, particular solutions computed
  in NumPy before its compiled loop): steps per second, and the agreement of the two (energy,
  switch count, every state of a 2 s run, the same mode at every sample);
* **scipy.integrate.solve_ivp** (DOP853, rtol = 1e-12) on the same switched system with the same
  sampled law, one integration per sample interval: steps per second and the error of both
  exact methods against it (equal accuracy: all at the 1e-12 level or better);
* **batch**: a ρ_p sweep as in paper Fig. 7 (21 values of ρ_p in [0, 0.5]; the four printed
  gains K_e, K_f1, K_f2, K_f3 and FDSC; 500 s at 1 ms: 105 runs, 5.25e7 steps) in one call of
  ``fdsc.simulate_batch`` on every core, against the same cases run one by one; the fixed-gain
  runs are summed in closed form by default, so the sweep is also timed with every run through
  the loop (``closed_form=False``), with the largest energy difference between the two;
* **LTI runs**: one 500 s fixed-gain run in closed form against the loop (time ratio), and an
  LTI output energy against its exact value, by the loop and by the closed form;
* **memory**: peak resident memory (``VmHWM``) of a 1e8-step reduction-only run, measured in a
  fresh process that imports what a simulation needs (``fdsc`` loads its modules on first use: NumPy,
  SciPy's linalg and numba with its LLVM, not CVXPY); its baseline after imports and
  compilation (the same for a run of one step) is reported beside it, and ``run_mb_1e8`` is the
  run's own growth. A first fresh process before them fills numba's disk cache if it was stale
  (compiling costs about 150 MB of LLVM memory once); its peak is reported too.

The last line printed is JSON with ``switched_steps_per_s``, ``speedup_vs_solve_ivp``,
``lti_energy_rel_err``, ``end_to_end_steps_per_s``, ``sweep_seconds`` and ``peak_mb_1e8``.
Usage: ``python benchmarks/bench_simulate.py [--quick]`` (``--quick`` skips the 1e8-step run).
"""

import json
import os
import subprocess
import sys
import time

import numba
import numpy as np
from scipy.integrate import solve_ivp

from fdsc import Case, LTISystem, Sinusoids, simulate, simulate_batch, simulate_stream, time_grid
from fdsc.paper.shared.data import aircraft, mixed_disturbance, paper_gains, paper_modes
from fdsc.simulate import particular

DT = 1e-3


def best_of(fn, repeat=3):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def solve_ivp_switched(t, sigma, modes, d):
    """Integrate each sample interval with the mode the exact run chose (same law, same grid)."""
    B = modes[0].B[:, 0]
    x = np.zeros(2)
    out = [x]
    for k in range(t.size - 1):
        A = modes[sigma[k]].A
        sol = solve_ivp(lambda s, y, A=A: A @ y + B * d(np.array([s]))[0], (t[k], t[k + 1]), x,
                        method="DOP853", rtol=1e-12, atol=1e-14)
        x = sol.y[:, -1]
        out.append(x)
    return np.array(out)


def sweep_cases(horizon=500.0):
    plant, gains, pm = aircraft(), paper_gains(), paper_modes()
    cases = []
    for rho in np.linspace(0.0, 0.5, 21):
        d = mixed_disturbance(float(rho))
        for name in ("K_e", "K_f1", "K_f2", "K_f3"):
            cases.append(Case(plant.closed_loop(gains[name]), d, horizon, DT))
        cases.append(Case(pm["modes"], d, horizon, DT, law_bands=pm["bands"], law_Q=pm["Q"]))
    return cases


MEMORY_SCRIPT = """
import sys, time
def peak_mb():
    # VmHWM: the peak resident memory of this process's own address space (ru_maxrss is not:
    # Linux carries it over exec from the forked copy of the parent that started this process)
    with open("/proc/self/status") as f:
        return next(int(line.split()[1]) for line in f if line.startswith("VmHWM:")) / 1024
from fdsc import simulate_stream
from fdsc.paper.shared.data import mixed_disturbance, paper_modes
pm, d = paper_modes(), mixed_disturbance(0.1)
kw = dict(law_bands=pm["bands"], law_Q=pm["Q"], specialize=True)   # one loop for every length
simulate_stream(pm["modes"], d, 1.0, 1e-3, **kw)
base = peak_mb()
t0 = time.perf_counter()
run = simulate_stream(pm["modes"], d, float(sys.argv[1]), 1e-3, **kw)
seconds = time.perf_counter() - t0
peak = peak_mb()
print(base, peak, seconds, run.switches)
"""


def memory_run(steps):
    out = subprocess.run([sys.executable, "-c", MEMORY_SCRIPT, str(steps * DT)], check=True,
                         capture_output=True, text=True).stdout.split()
    base, peak, seconds, switches = (float(v) for v in out)
    return base, peak, seconds, int(switches)


def main():
    quick = "--quick" in sys.argv
    pm = paper_modes()
    d = mixed_disturbance(0.1)
    law = dict(law_bands=pm["bands"], law_Q=pm["Q"])

    # streaming path: end to end, and the loop alone (minus the preparation of a one-step run)
    # compile (cached on disk) the general loop and the loop specialized to the paper's sizes
    # (the default from stream.UNROLL_MIN_STEPS steps on; asked for here, for a 5e6-step run)
    for specialize in (False, True):
        simulate_stream(pm["modes"], d, 1.0, DT, specialize=specialize, **law)
    horizon = 5000.0
    steps = round(horizon / DT)
    t_stream = best_of(lambda: simulate_stream(pm["modes"], d, horizon, DT, specialize=True, **law))
    t_general = best_of(lambda: simulate_stream(pm["modes"], d, horizon, DT, specialize=False, **law))
    t_setup = best_of(lambda: simulate_stream(pm["modes"], d, DT, DT, specialize=True, **law), repeat=20)
    end_to_end = steps / t_stream
    loop_rate = steps / (t_stream - t_setup)

    # previous exact method (full trajectories) on a shorter horizon, and the agreement
    old_h = 500.0
    grid = time_grid(old_h, DT)
    simulate(pm["modes"], d, time_grid(1.0, DT), **law)
    t_old = best_of(lambda: simulate(pm["modes"], d, grid, **law), repeat=2)
    old = simulate(pm["modes"], d, grid, **law)
    new = simulate_stream(pm["modes"], d, old_h, DT, **law)
    old_rate = (grid.size - 1) / t_old

    # solve_ivp on the same switched run (short horizon; its per-step cost is constant)
    g2 = time_grid(2.0, DT)
    ref = simulate(pm["modes"], d, g2, **law)
    t0 = time.perf_counter()
    x_ivp = solve_ivp_switched(g2, ref.sigma, pm["modes"], d)
    ivp_rate = (g2.size - 1) / (time.perf_counter() - t0)
    ivp_err = float(np.max(np.abs(x_ivp - ref.x)) / np.max(np.abs(ref.x)))
    short = simulate_stream(pm["modes"], d, 2.0, DT, **law, trace_every=DT)
    scale = np.max(np.abs(ref.x))
    stream_vs_exact = float(np.max(np.abs(short.trace.x_lo - ref.x)) / scale)
    stream_vs_ivp = float(np.max(np.abs(short.trace.x_lo - x_ivp)) / scale)
    same_sigma = bool(np.array_equal(np.argmax(short.trace.share, axis=1), ref.sigma))

    # batch: the ρ_p sweep of paper Fig. 7 (21 × 5 runs of 500 s)
    cases = sweep_cases()
    simulate_batch(sweep_cases(1.0))                              # compile the parallel loop
    t0 = time.perf_counter()
    batch = simulate_batch(cases)
    sweep_seconds = time.perf_counter() - t0
    t0 = time.perf_counter()
    one_by_one = [simulate_stream(c.modes, c.d, c.horizon, c.dt, law_bands=c.law_bands,
                                  law_Q=c.law_Q, specialize=True) for c in cases]
    serial_seconds = time.perf_counter() - t0
    assert all(a.energy == b.energy for a, b in zip(batch, one_by_one, strict=True))
    sweep_steps = sum(round(c.horizon / c.dt) for c in cases)
    t0 = time.perf_counter()
    looped = simulate_batch(cases, closed_form=False)
    sweep_loop_seconds = time.perf_counter() - t0
    closed_vs_loop = float(np.max(np.abs(batch.energy - looped.energy) / looped.energy))

    # one fixed-gain run of 500 s: closed form against the loop
    fixed = cases[0]
    t_closed = best_of(lambda: simulate_stream(fixed.modes, fixed.d, fixed.horizon, fixed.dt))
    t_loop = best_of(lambda: simulate_stream(fixed.modes, fixed.d, fixed.horizon, fixed.dt,
                                             closed_form=False))

    # memory of a reduction-only run of 1e8 steps (and 1e6 steps for the baseline), fresh processes;
    # the first one loads the kernels from numba's disk cache if it holds them, or compiles them
    # (LLVM's memory counts then): reported apart, and the runs measured after it load them
    mem = {}
    if not quick:
        first = memory_run(1)
        for n in (10**6, 10**8):
            mem[n] = memory_run(n)

    # LTI energy against its closed form: one tone in steady state over whole periods
    sys_ = LTISystem([[-2.0]], [[1.0]], [[1.0]], [[0.0]])
    w = 1.0
    T = 2 * np.pi * 200
    tone = Sinusoids([1.0], [w])
    xp, _ = particular(sys_.A, sys_.B, tone, [0.0])
    e = simulate_stream(sys_, tone, T, T / 400_000, x0=xp[0], closed_form=False).energy
    e_closed = simulate_stream(sys_, tone, T, T / 400_000, x0=xp[0]).energy
    exact = abs(1 / (1j * w + 2)) ** 2 * T / 2

    result = {
        "switched_steps_per_s": end_to_end,
        "end_to_end_steps_per_s": end_to_end,
        "loop_steps_per_s": loop_rate,
        "general_loop_end_to_end_steps_per_s": steps / t_general,
        "specialized_speedup_vs_general_loop": t_general / t_stream,
        "end_to_end_share_of_loop": end_to_end / loop_rate,
        "setup_seconds": t_setup,
        "previous_method_steps_per_s": old_rate,
        "speedup_vs_previous_method": end_to_end / old_rate,
        "energy_rel_diff_vs_previous_method": abs(new.energy - old.energy()) / old.energy(),
        "switches_previous_method": int(old.switch_times.size),
        "switches_stream": new.switches,
        "stream_state_rel_err_vs_exact": stream_vs_exact,
        "stream_state_rel_err_vs_solve_ivp": stream_vs_ivp,
        "stream_same_modes_as_previous_method": same_sigma,
        "solve_ivp_steps_per_s": ivp_rate,
        "speedup_vs_solve_ivp": end_to_end / ivp_rate,
        "solve_ivp_rel_err_vs_exact": ivp_err,
        "sweep_cases": len(cases),
        "sweep_steps": sweep_steps,
        "sweep_seconds": sweep_seconds,
        "sweep_serial_seconds": serial_seconds,
        "sweep_parallel_speedup": serial_seconds / sweep_seconds,
        "sweep_cases_per_s": len(cases) / sweep_seconds,
        "sweep_steps_per_s": sweep_steps / sweep_seconds,
        "sweep_loop_only_seconds": sweep_loop_seconds,
        "sweep_closed_form_speedup": sweep_loop_seconds / sweep_seconds,
        "sweep_energy_rel_diff_closed_form_vs_loop": closed_vs_loop,
        "lti_run_500s_closed_form_seconds": t_closed,
        "lti_run_500s_loop_seconds": t_loop,
        "threads": numba.get_num_threads(),
        "peak_mb_1e8": mem[10**8][1] if mem else None,
        "baseline_mb_after_imports": mem[10**8][0] if mem else None,
        "run_mb_1e8": mem[10**8][1] - mem[10**8][0] if mem else None,
        "peak_mb_1e6": mem[10**6][1] if mem else None,
        "peak_mb_first_process": first[1] if mem else None,
        "seconds_1e8": mem[10**8][2] if mem else None,
        "lti_energy_rel_err": abs(e - exact) / exact,
        "lti_energy_rel_err_closed_form": abs(e_closed - exact) / exact,
        "horizon_s": horizon, "dt_s": DT, "steps": steps, "cpu_count": os.cpu_count(),
    }
    for k, v in result.items():
        print(f"{k:36s} {v:.4g}" if isinstance(v, float) else f"{k:36s} {v}")
    print(json.dumps(result))


if __name__ == "__main__":
    main()
