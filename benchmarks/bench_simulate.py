"""Benchmark of the switched-system simulator (not a test: timings depend on the machine).

Measures in one run, on the paper's FDSC loop (modes PassC-LF / PassC-HF, paper's Q's, mixed
disturbance d_h + 0.1 d_l, dt = 1 ms):

* the throughput of ``simulate`` with the compiled kernel (switched steps per second, one core,
  setup included);
* the same exact-discretization method with the plain Python/NumPy reference kernel
  (``simulate(..., kernel="numpy")``);
* scipy.integrate.solve_ivp (DOP853, rtol = 1e-12) integrating the same switched system with the
  same sampled law, one event interval per sample, and its error against our exact steps;
* the relative error of an LTI output energy against its closed form.

Only public functions are used (``fdsc.simulate``, ``fdsc.time_grid``,
``fdsc.simulate.particular`` and the paper's setup from ``fdsc.paper.data``). The last line
printed is JSON with at least ``switched_steps_per_s``, ``speedup_vs_solve_ivp`` and
``lti_energy_rel_err``. Usage: ``python benchmarks/bench_simulate.py``.
"""

import json
import os
import time

import numpy as np
from scipy.integrate import solve_ivp

from fdsc import LTISystem, Sinusoids, simulate, time_grid
from fdsc.paper.data import mixed_disturbance, paper_modes
from fdsc.simulate import particular


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


def main():
    pm = paper_modes()
    d = mixed_disturbance(0.1)
    dt = 1e-3

    def run(horizon, kernel):
        return simulate(pm["modes"], d, time_grid(horizon, dt), law_bands=pm["bands"], law_Q=pm["Q"],
                        kernel=kernel)

    run(1.0, "numba")  # warm-up: compilation is cached on disk after the first run
    steps = time_grid(1250.0, dt).size
    t_numba = best_of(lambda: run(1250.0, "numba"))
    py_steps = time_grid(20.0, dt).size
    t_python = best_of(lambda: run(20.0, "numpy"), repeat=1)
    # solve_ivp on the same switched run (short horizon; the per-step cost is constant)
    t_ivp_grid = time_grid(2.0, dt)
    ref = simulate(pm["modes"], d, t_ivp_grid, law_bands=pm["bands"], law_Q=pm["Q"])
    t0 = time.perf_counter()
    x_ivp = solve_ivp_switched(t_ivp_grid, ref.sigma, pm["modes"], d)
    t_ivp = time.perf_counter() - t0
    ivp_err = float(np.max(np.abs(x_ivp - ref.x)) / np.max(np.abs(ref.x)))
    kernel_rate = steps / t_numba
    ivp_rate = t_ivp_grid.size / t_ivp
    # LTI energy against its closed form: one tone in steady state over whole periods
    sys = LTISystem([[-2.0]], [[1.0]], [[1.0]], [[0.0]])
    w = 1.0
    T = 2 * np.pi * 200
    tone = Sinusoids([1.0], [w])
    xp, _ = particular(sys.A, sys.B, tone, [0.0])
    e = simulate(sys, tone, time_grid(T, T / 400_000), x0=xp[0]).energy()
    exact = abs(1 / (1j * w + 2)) ** 2 * T / 2
    result = {
        "switched_steps_per_s": kernel_rate,
        "python_steps_per_s": py_steps / t_python,
        "speedup_vs_python": kernel_rate / (py_steps / t_python),
        "solve_ivp_steps_per_s": ivp_rate,
        "speedup_vs_solve_ivp": kernel_rate / ivp_rate,
        "solve_ivp_rel_err_vs_exact": ivp_err,
        "lti_energy_rel_err": abs(e - exact) / exact,
        "horizon_s": 1250.0, "dt_s": dt, "steps": steps, "cpu_count": os.cpu_count(),
    }
    for k, v in result.items():
        print(f"{k:36s} {v:.4g}" if isinstance(v, float) else f"{k:36s} {v}")
    print(json.dumps(result))


if __name__ == "__main__":
    main()
