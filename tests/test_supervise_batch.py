"""fdsc.supervise_batch and FDSC.supervisor: a batch of exact and measured runs equals the runs
made one by one (here and on a process pool), warnings and errors name their case, and the
design's supervisor is the Supervisor of its gains and bands."""

import warnings
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor

import numpy as np
import pytest

from fdsc import (
    FDSC,
    Band,
    Piecewise,
    Plant,
    Sinusoids,
    SupervisedCase,
    Supervisor,
    UnstableRunWarning,
    lqr_gain,
    supervise_batch,
)

PLANT = Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
              [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.1]])
GAINS = [np.array([[-21.85, -22.27]]), np.array([[0.495, -1.473]])]
D = Piecewise([0.0, 20.0, 60.0], [Sinusoids([1.0], [0.2]), Sinusoids([1.0], [12.0])])


def _cases():
    sup = Supervisor(PLANT, GAINS, restart=10.0)
    cop = Supervisor(PLANT, GAINS, restart=10.0, K0=lqr_gain(PLANT))
    return [SupervisedCase(sup, D, 40.0, options={"warmup": 2.0}),
            SupervisedCase(cop, D, 40.0, 1e-3, {"warmup": 2.0, "derivative": "backward"}),
            SupervisedCase(cop, D, 40.0, 2e-3, {"true_A": 1.1 * PLANT.A, "hysteresis": 0.5})]


def _same(a, b):
    assert a.energy == b.energy and np.array_equal(a.switch_times, b.switch_times)
    assert np.array_equal(a.mu, b.mu) and np.array_equal(a.x_final, b.x_final)


def test_a_batch_equals_its_runs_one_by_one():
    cases = _cases()
    runs = supervise_batch(cases)
    for c, r in zip(cases, runs, strict=True):
        _same(r, c.run())
    one = cases[1]
    _same(runs[1], one.supervisor.run_measured(one.d, one.horizon, one.dt, **one.options))
    assert runs[0].dt is None and runs[1].dt == 1e-3


def test_a_batch_on_a_process_pool_equals_the_serial_batch():
    cases = _cases()
    with ProcessPoolExecutor(1) as pool:          # one worker: the chunks cross a process boundary
        far = supervise_batch(cases, executor=pool, chunksize=2)
    for a, b in zip(far, supervise_batch(cases), strict=True):
        _same(a, b)


def test_warnings_and_errors_name_their_case():
    sup = Supervisor(PLANT, GAINS)
    bad = SupervisedCase(sup, D, 4.0, 1e-3, {"true_A": PLANT.A + 30.0 * np.eye(2)})
    with pytest.warns(UnstableRunWarning, match=r"cases\[1\]: run_measured"):
        supervise_batch([SupervisedCase(sup, D, 4.0), bad])
    with pytest.raises(ValueError, match=r"cases\[1\]: .*horizon"):
        supervise_batch([SupervisedCase(sup, D, 4.0), SupervisedCase(sup, D, 4.05)])
    with pytest.raises(ValueError, match=r"\['derivative'\] do not apply to an exact run"):
        supervise_batch([SupervisedCase(sup, D, 4.0, options={"derivative": "backward"})])


@pytest.mark.parametrize("cases, kwargs, error, match", [
    ([], {}, TypeError, "non-empty"),
    ([object()], {}, TypeError, r"cases\[0\]"),
    (None, {"chunksize": 0}, ValueError, "chunksize"),
    (None, {"executor": object()}, TypeError, "executor"),
    (None, {"executor": ThreadPoolExecutor(1)}, TypeError, "not a ThreadPoolExecutor"),
])
def test_bad_batches_are_refused_by_name(cases, kwargs, error, match):
    cases = _cases()[:1] if cases is None else cases
    with pytest.raises(error, match=match):
        supervise_batch(cases, **kwargs)


def test_the_designs_supervisor_switches_its_gains_by_its_bands():
    bands = [Band.lf(2.0), Band.hf(8.0)]
    ctrl = FDSC.from_gains(PLANT, GAINS, bands, in_band=1)
    sup = ctrl.supervisor()
    ref = Supervisor(PLANT, GAINS, law="band_power", bands=bands, K0=lqr_gain(PLANT))
    _same(sup.run(D, 40.0, warmup=2.0), ref.run(D, 40.0, warmup=2.0))
    assert sup.realization == "copies" and ctrl.supervisor(K0=None).realization == "direct"
    assert ctrl.supervisor("cost").law == "cost"
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert ctrl.supervisor().run(D, 40.0, warmup=2.0).sequence.tolist() == [0, 1]
    with pytest.raises(ValueError, match="K0 must be 'lqr'"):
        ctrl.supervisor(K0="lq")
    with pytest.raises(ValueError, match="law"):
        ctrl.supervisor("argmax")
