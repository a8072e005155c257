"""simulate_batch and supervise_batch on executors, reliably: chunks interleaved on threads keep
their own warnings and leave the warnings module as they found it, a thread pool is refused by
simulate_batch, a shut-down or broken pool and a closed Dask client are named, labels stay with
the caller (they need not be picklable) while any other unpicklable part of a case is named, and
supervise_batch refuses a chunk size without an executor."""

import importlib
import os
import sys
import threading
import warnings
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor

import numpy as np
import pytest

from fdsc import (
    Case,
    LTISystem,
    Piecewise,
    Plant,
    Sinusoids,
    SupervisedCase,
    Supervisor,
    SwitchRule,
    UnstableRunWarning,
    simulate_batch,
    supervise_batch,
)

stream = importlib.import_module("fdsc.stream")
superbatch = importlib.import_module("fdsc.supervise_batch")    # fdsc.supervise_batch is the function

LOOP = LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]])
TONE = Sinusoids([0.1], [1.0])
PLAIN = Case(LOOP, TONE, 0.1, 1e-3)
RULED = Case(LOOP, TONE, 0.1, 1e-3, rule=SwitchRule.dwell_time(0.01))    # warns: no effect
OPTS = (None, None, None, 2.0**32, "numba", True, None)

PLANT = Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
              [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.1]])
GAINS = [np.array([[-21.85, -22.27]]), np.array([[0.495, -1.473]])]
D = Piecewise([0.0, 20.0, 60.0], [Sinusoids([1.0], [0.2]), Sinusoids([1.0], [12.0])])
SUP = Supervisor(PLANT, GAINS)
CALM = SupervisedCase(SUP, D, 0.5, 1e-3)
# a plant that is run far from the model: the loop diverges and run_measured warns
WILD = SupervisedCase(SUP, D, 0.5, 1e-3, {"true_A": PLANT.A + 30.0 * np.eye(2)})

THREADS, PER_CHUNK = 4, 6


@pytest.fixture(scope="module")
def pool():
    with ProcessPoolExecutor(1) as p:
        yield p


def _stream_chunk(offset):
    cases = [RULED if i % 2 == 0 else PLAIN for i in range(PER_CHUNK)]
    return [str(text) for _, text in stream._run_chunk(cases, offset, OPTS)[2]]


def _supervise_chunk(offset):
    cases = [WILD if i % 2 == 0 else CALM for i in range(PER_CHUNK)]
    runs, caught, failed = superbatch._run_chunk(cases, offset)
    assert failed is None and len(runs) == PER_CHUNK
    return [text for _, text in caught]


@pytest.mark.parametrize("chunk, says", [(_stream_chunk, "no effect on a single mode"),
                                         (_supervise_chunk, "run_measured: ")])
def test_chunks_interleaved_on_threads_keep_their_warnings(chunk, says):
    before = (warnings.showwarning, warnings._showwarnmsg_impl, list(warnings.filters))
    switch = sys.getswitchinterval()
    sys.setswitchinterval(1e-6)                 # switch threads as often as possible
    got, errors = {}, []
    try:
        for repeat in range(4):
            barrier = threading.Barrier(THREADS)

            def work(k, repeat=repeat, barrier=barrier):
                try:
                    barrier.wait()
                    got[repeat, k] = chunk(100 * k)
                except BaseException as exc:   # noqa: BLE001 - reported below
                    errors.append(exc)

            threads = [threading.Thread(target=work, args=(k,)) for k in range(THREADS)]
            for t in threads:
                t.start()
            for t in threads:
                t.join()
    finally:
        sys.setswitchinterval(switch)
        after = (warnings.showwarning, warnings._showwarnmsg_impl, list(warnings.filters))
        warnings.showwarning, warnings._showwarnmsg_impl = before[:2]
        warnings.filters[:] = before[2]
    assert not errors, errors
    for (repeat, k), texts in sorted(got.items()):
        want = [f"cases[{100 * k + i}]: " for i in range(0, PER_CHUNK, 2)]
        assert [t[:len(w)] for t, w in zip(texts, want, strict=False)] == want and len(texts) == len(want), \
            (repeat, k, texts)
        assert all(says in t for t in texts)
    assert len(got) == 4 * THREADS
    # the warnings module is as it was: the same hooks and filters, and it still records
    assert after[0] is before[0] and after[1] is before[1] and after[2] == before[2]
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        warnings.warn("x", stacklevel=1)
    assert [str(m.message) for m in w] == ["x"]


def test_simulate_batch_refuses_a_thread_pool():
    with ThreadPoolExecutor(1) as threads, \
            pytest.raises(TypeError, match=r"executor .*ThreadPoolExecutor.*threads="):
        simulate_batch([PLAIN], executor=threads)


def _simulate(cases, **kw):
    return simulate_batch([c if isinstance(c, Case) else PLAIN for c in cases], **kw)


def _supervise(cases, **kw):
    return supervise_batch([c if isinstance(c, SupervisedCase) else CALM for c in cases], **kw)


@pytest.mark.parametrize("batch", [_simulate, _supervise])
def test_a_shut_down_or_broken_process_pool_is_named(batch):
    dead = ProcessPoolExecutor(1)
    dead.shutdown()
    with pytest.raises(RuntimeError, match=r"^executor is shut down") as info:
        batch([None, None], executor=dead)
    assert "after shutdown" in str(info.value.__cause__)
    broken = ProcessPoolExecutor(1)
    try:
        broken.submit(os._exit, 1).exception()         # the worker dies: the pool is broken
        with pytest.raises(RuntimeError, match=r"^executor's process pool is broken"):
            batch([None, None], executor=broken)
    finally:
        broken.shutdown()


@pytest.mark.parametrize("batch", [_simulate, _supervise])
def test_a_closed_dask_client_is_named(batch):
    distributed = pytest.importorskip("distributed")
    client = distributed.Client(processes=False, n_workers=1, threads_per_worker=1,
                                dashboard_address=None)
    own = client.get_executor()
    client.close()
    for executor in (client, own):                    # the client, and the executor it gave
        with pytest.raises(RuntimeError, match=r"^executor is a closed Dask client"):
            batch([None], executor=executor)


def test_an_in_process_dask_client_keeps_every_chunks_warnings_and_labels():
    distributed = pytest.importorskip("distributed")
    cases = [Case(LOOP, TONE, 0.1, 1e-3, rule=SwitchRule.dwell_time(0.01), label=("c", k))
             for k in range(4)]
    with distributed.Client(processes=False, n_workers=1, threads_per_worker=2,
                            dashboard_address=None) as client:
        with warnings.catch_warnings(record=True) as w:
            warnings.simplefilter("always")
            batch = simulate_batch(cases, executor=client, chunksize=1)
            runs = supervise_batch([WILD, CALM, WILD], executor=client, chunksize=1)
    texts = sorted(str(m.message) for m in w)
    assert sum("no effect" in t for t in texts) == 4
    assert [t[:9] for t in texts if "no effect" in t] == [f"cases[{k}]:" for k in range(4)]
    assert [t[:10] for t in texts if "run_measured" in t] == ["cases[0]: ", "cases[2]: "]
    assert [c.label for c in batch.cases] == [("c", k) for k in range(4)]
    assert len(runs) == 3


def test_unpicklable_labels_stay_with_the_caller(pool):
    label = lambda: "mine"                                # noqa: E731 - cannot be pickled
    cases = [Case(LOOP, TONE, 0.1, 1e-3, label=label), Case(LOOP, TONE, 0.2, 1e-3, label="b")]
    far = simulate_batch(cases, executor=pool, chunksize=1)
    near = simulate_batch(cases)
    assert far.cases[0].label is label and far.cases[1].label == "b"
    assert far.energy.tolist() == near.energy.tolist()
    np.testing.assert_array_equal(far[1].x_final, near[1].x_final)
    sup = [SupervisedCase(SUP, D, 0.5, 1e-3, label=label), CALM]
    runs = supervise_batch(sup, executor=pool)
    assert sup[0].label is label
    for a, b in zip(runs, supervise_batch(sup), strict=True):
        assert a.energy == b.energy and np.array_equal(a.x_final, b.x_final)


def test_any_other_unpicklable_part_of_a_case_is_named(pool):
    lock = threading.Lock()
    with pytest.raises(TypeError, match=r"cases\[1\] .*pickl"):
        simulate_batch([PLAIN, Case(LOOP, TONE, 0.1, 1e-3, x0=lock)], executor=pool)
    with pytest.raises(TypeError, match=r"cases\[1\] .*pickl"):
        supervise_batch([CALM, SupervisedCase(SUP, D, 0.5, 1e-3, {"x0": lock})], executor=pool)


def test_supervise_batch_refuses_a_chunksize_without_an_executor():
    with pytest.raises(ValueError, match=r"chunksize applies only with an executor.*found 2"):
        supervise_batch([CALM], chunksize=2)


def test_warnings_still_record_after_a_batch_on_an_executor(pool):
    before = warnings.showwarning
    with pytest.warns(UserWarning, match=r"cases\[0\]: .*no effect"):
        simulate_batch([RULED, PLAIN], executor=pool, chunksize=1)
    assert warnings.showwarning is before
    with pytest.warns(UnstableRunWarning, match=r"cases\[1\]: run_measured"):
        supervise_batch([CALM, WILD], executor=pool, chunksize=1)
