"""simulate_batch on an executor: a process pool and a Dask LocalCluster (two worker processes,
loopback only) give the thread path's results bit for bit; the README's scale-out example runs
as written; a bad executor or chunk size is refused by name."""

import re
import warnings
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import control
import numpy as np
import pytest

import fdsc
from fdsc import Case, Sinusoids, UnstableRunWarning, simulate_batch

README = Path(__file__).resolve().parent.parent / "README.md"
distributed = pytest.importorskip("distributed")


@pytest.fixture(scope="module")
def client():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as c:
        yield c


@pytest.fixture(scope="module")
def own_plant_cases():
    # the README's own-plant design, under 36 seeded sums of tones: switched and fixed runs,
    # with coarse running integrals, traces and a dwell histogram
    plant = control.ss([[0.0, 1.0], [-4.0, -0.4]], [[0.0, 0.0], [1.0, 1.0]],
                       [[1.0, 0.0], [0.0, 0.0]], [[0.0, 0.0], [0.0, 0.1]])
    ctrl = fdsc.FDSC.synthesize(plant, [fdsc.Band.lf(0.5), fdsc.Band.hf(5.0)], in_band=1,
                                n_disturbances=1)
    rng = np.random.default_rng(7)
    draws = [Sinusoids(rng.uniform(0.1, 1.0, 3), rng.uniform(0.05, 20.0, 3)) for _ in range(12)]
    return ([ctrl.case(d, 10.0, 1e-3) for d in draws]
            + [Case(ctrl.mode(i), d, 10.0, 1e-3) for i in range(2) for d in draws])


def _assert_identical(a, b):
    assert len(a) == len(b)
    for r, s in zip(a, b, strict=True):
        assert r.energy == s.energy and r.input_energy == s.input_energy
        assert r.switches == s.switches and r.sigma_final == s.sigma_final
        np.testing.assert_array_equal(r.x_final, s.x_final)
        np.testing.assert_array_equal(r.time_share, s.time_share)
        np.testing.assert_array_equal(r.dwell_counts, s.dwell_counts)
        np.testing.assert_array_equal(r.energy_cum, s.energy_cum)
        np.testing.assert_array_equal(r.trace.z_hi, s.trace.z_hi)


KW = dict(cumulative_every=1.0, trace_every=0.5)


def test_a_local_dask_cluster_gives_the_thread_path_bit_for_bit(client, own_plant_cases):
    ref = simulate_batch(own_plant_cases, **KW)
    assert ref.switches[:12].max() > 0        # the switched runs switch
    for chunksize in (None, 5):
        _assert_identical(simulate_batch(own_plant_cases, executor=client, chunksize=chunksize, **KW), ref)
    # the client's own executor is accepted as well
    _assert_identical(simulate_batch(own_plant_cases, executor=client.get_executor(), **KW), ref)


def test_a_process_pool_gives_the_thread_path_bit_for_bit(own_plant_cases):
    ref = simulate_batch(own_plant_cases, **KW)
    with ProcessPoolExecutor(2) as pool:
        _assert_identical(simulate_batch(own_plant_cases, executor=pool, chunksize=7, **KW), ref)


def test_a_seeded_monte_carlo_set_on_the_cluster(client):
    from fdsc.paper.pays.monte_carlo import monte_carlo

    local = monte_carlo("generic", n=6, seed=3, noise_repeats=0)
    remote = monte_carlo("generic", n=6, seed=3, noise_repeats=0, executor=client)
    assert set(local.energy) == set(remote.energy)
    for name in local.energy:
        np.testing.assert_array_equal(remote.energy[name], local.energy[name])


def test_warnings_on_the_workers_are_raised_again_with_the_batch_index(client):
    # the classic pair of Hurwitz modes under a law that picks the growing mode (tests/test_divergence.py)
    A1 = np.array([[-0.1, 1.0], [-10.0, -0.1]])
    A2 = np.array([[-0.1, 10.0], [-1.0, -0.1]])
    B = np.array([[0.0], [1.0]])
    pair = [fdsc.LTISystem(A, B, np.eye(2), np.zeros((2, 1))) for A in (A1, A2)]
    S, Z = np.array([[0.0, -0.5], [-0.5, 0.0]]), np.zeros((2, 2))
    grow = [np.block([[Z, Z], [Z, S]]), np.block([[Z, Z], [Z, -S]])]
    ok = Case(pair[0], Sinusoids([0.1], [1.0]), 20.0, 1e-3, x0=[1.0, 0.0])
    bad = Case(pair, Sinusoids([0.1], [1.0]), 20.0, 1e-3, x0=[1.0, 0.0], law_weights=grow)
    with pytest.warns(UnstableRunWarning, match=r"1 of 3 cases diverge .*cases \[2\]"):
        runs = simulate_batch([ok, ok, bad], executor=client, chunksize=1)
    assert runs.diverged.tolist() == [False, False, True]
    # a warning raised while preparing a case on a worker names the case by its index in the batch
    single = Case(pair[0], Sinusoids([0.1], [1.0]), 5.0, 1e-3, rule=fdsc.SwitchRule.dwell_time(0.1))
    with pytest.warns(UserWarning, match=r"cases\[1\]: .*no effect"):
        simulate_batch([ok, single], executor=client, chunksize=1)


@pytest.mark.parametrize(("kwargs", "error", "match"), [
    (dict(executor="tcp://127.0.0.1:8786"), TypeError, "executor must be a concurrent.futures.Executor"),
    (dict(executor=object()), TypeError, "executor must be .* found object"),
    (dict(executor=None, chunksize=4), ValueError, "chunksize applies only with an executor"),
])
def test_bad_executor_arguments_are_refused_by_name(own_plant_cases, kwargs, error, match):
    with pytest.raises(error, match=match):
        simulate_batch(own_plant_cases[:2], **kwargs)


@pytest.mark.parametrize("chunksize", [0, -3, 2.5])
def test_a_bad_chunksize_is_refused_by_name(own_plant_cases, chunksize):
    with ProcessPoolExecutor(1) as pool, pytest.raises((TypeError, ValueError), match="chunksize"):
        simulate_batch(own_plant_cases[:2], executor=pool, chunksize=chunksize)


def test_the_readme_scale_out_example_runs_as_written(tmp_path, monkeypatch, capsys):
    section = README.read_text(encoding="utf-8").split("## Scaling out", 1)[1].split("\n## ", 1)[0]
    (code,) = re.findall(r"```python\n(.*?)```", section, re.S)
    monkeypatch.chdir(tmp_path)
    script = tmp_path / "scale_out.py"
    script.write_text(code, encoding="utf-8")
    import runpy

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        runpy.run_path(str(script), run_name="__main__")
    out = capsys.readouterr().out
    assert re.search(r"FDSC beats both fixed gains in \d+% of the draws", out)
    assert "the same as on this machine's threads, bit for bit: True" in out
