"""The per-build cache of chapter results."""

import numpy as np
import pytest

from fdsc.paper.shared import cache
from fdsc.paper.shared.cache import CACHE_ENV, cached

CALLS = []


@cached
def _square(x, *, shift=0.0):
    CALLS.append((x, shift))
    return np.array([x * x + shift])


def test_without_the_variable_nothing_is_cached(monkeypatch):
    monkeypatch.delenv(CACHE_ENV, raising=False)
    CALLS.clear()
    _square(2.0)
    _square(2.0)
    assert len(CALLS) == 2


def test_with_the_variable_each_argument_set_is_computed_once(monkeypatch, tmp_path):
    monkeypatch.setenv(CACHE_ENV, str(tmp_path))
    CALLS.clear()
    a = _square(3.0)
    b = _square(3.0)
    c = _square(3.0, shift=1.0)
    assert CALLS == [(3.0, 0.0), (3.0, 1.0)]
    assert a.tolist() == b.tolist() == [9.0] and c.tolist() == [10.0]
    assert len(list(tmp_path.glob("*.pickle"))) == 2


def test_the_same_arguments_spelled_differently_share_one_value(monkeypatch, tmp_path):
    # chapter 'baselines' calls mixed_sweep() where chapter 'nonstationary' calls
    # mixed_sweep(dt=1e-3): both must find one value (the key once held the arguments as given)
    monkeypatch.setenv(CACHE_ENV, str(tmp_path))
    CALLS.clear()
    a = _square(3.0)
    b = _square(3.0, shift=0.0)
    c = _square(x=3.0, shift=0.0)
    d = _square(3.0, shift=0.5)
    assert CALLS == [(3.0, 0.0), (3.0, 0.5)]
    assert a.tolist() == b.tolist() == c.tolist() == [9.0] and d.tolist() == [9.5]
    assert len(list(tmp_path.glob("*.pickle"))) == 2


@cached
def _labelled(x, **labels):
    CALLS.append((x, labels))
    return [x, sorted(labels)]


def test_keyword_arguments_are_keyed_and_a_wrong_call_names_the_function(monkeypatch, tmp_path):
    monkeypatch.setenv(CACHE_ENV, str(tmp_path))
    CALLS.clear()
    assert _labelled(1, a=2, b=3) == _labelled(1, b=3, a=2) == [1, ["a", "b"]]
    _labelled(1, a=2)
    assert len(CALLS) == 2 and len(list(tmp_path.glob("*.pickle"))) == 2
    with pytest.raises(TypeError, match="_square"):
        _square(1.0, 2.0)       # shift is keyword-only: Python's own message


def test_arguments_that_are_not_plain_bypass_the_cache(monkeypatch, tmp_path):
    monkeypatch.setenv(CACHE_ENV, str(tmp_path))
    CALLS.clear()
    _square(np.float64(2.0) * np.ones(1))
    _square(np.float64(2.0) * np.ones(1))
    assert len(CALLS) == 2 and list(tmp_path.glob("*.pickle")) == []


def test_a_change_of_the_sources_changes_the_key(monkeypatch, tmp_path):
    monkeypatch.setenv(CACHE_ENV, str(tmp_path))
    CALLS.clear()
    _square(5.0)
    monkeypatch.setattr(cache, "fingerprint", lambda: "another version of the code")
    _square(5.0)
    assert len(CALLS) == 2


def test_fingerprint_is_stable():
    assert cache.fingerprint() == cache.fingerprint() and len(cache.fingerprint()) == 64


@pytest.mark.parametrize("value", [1, 1.5, "a", None, True, (1, ("b", 2.0))])
def test_plain_values(value):
    assert cache._plain((value,))


def test_a_value_being_computed_is_waited_for_not_computed_again(monkeypatch, tmp_path):
    # the second caller arrives while the first computes: it waits for the key's lock and reads
    # the stored value (without the lock both would compute: calls == 2)
    import threading
    import time

    monkeypatch.setenv(CACHE_ENV, str(tmp_path))
    calls, started = [], threading.Event()

    @cached
    def slow(x):
        calls.append(x)
        started.set()
        time.sleep(0.3)
        return [x, x]

    out = {}
    first = threading.Thread(target=lambda: out.setdefault("a", slow(7)))
    first.start()
    started.wait()
    out["b"] = slow(7)
    first.join()
    assert calls == [7]
    assert out["a"] == out["b"] == [7, 7]


def test_worker_threads_share_the_cpus_keep_a_callers_setting_and_restore(monkeypatch):
    import multiprocessing
    import os
    from concurrent.futures import ProcessPoolExecutor

    for v in cache.THREAD_VARS:
        monkeypatch.delenv(v, raising=False)
    monkeypatch.setenv("MKL_NUM_THREADS", "7")
    monkeypatch.setattr(os, "cpu_count", lambda: 8)
    with cache.worker_threads(3) as caps:
        # a process started in the block sees the caps (8 CPUs // 3 workers = 2 threads each)
        with ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("spawn")) as pool:
            seen = pool.submit(os.getenv, "OPENBLAS_NUM_THREADS").result()
    assert seen == "2" and caps["NUMBA_NUM_THREADS"] == "2" and caps["MKL_NUM_THREADS"] == "7"
    assert "OPENBLAS_NUM_THREADS" not in os.environ and os.environ["MKL_NUM_THREADS"] == "7"
    with cache.worker_threads(16) as caps:
        assert caps["OMP_NUM_THREADS"] == "1"          # never fewer than one thread
    for bad in (0, 1.5, True, "2"):
        with pytest.raises(ValueError, match="processes must be a whole number"):
            with cache.worker_threads(bad):
                pass
