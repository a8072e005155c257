"""The FDSC design object and the one system boundary (LTISystem / Plant / tuples / StateSpace)."""

import control
import numpy as np
import pytest
from numpy.testing import assert_allclose, assert_array_equal

from fdsc import (
    FDSC,
    Band,
    DimensionError,
    LTISystem,
    Piecewise,
    Plant,
    Sinusoids,
    UnstableError,
    as_plant,
    as_system,
    band_peak,
    certify_q,
    random_plant,
    simulate,
    time_grid,
)

# a lightly damped oscillator, z = [position, 0.1 u] (the README's own-plant example)
A = [[0.0, 1.0], [-4.0, -0.4]]
OSC = Plant(A, [[0.0], [1.0]], [[0.0], [1.0]], [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.1]])
BANDS = [Band.lf(0.5), Band.hf(5.0)]


@pytest.fixture(scope="module")
def design():
    return FDSC.synthesize(OSC, BANDS, in_band=1)


def test_synthesized_design_holds_certified_gains_and_q(design):
    assert design.n_modes == 2 and len(design.synthesis) == 2
    for res, K, band in zip(design.synthesis, design.gains, BANDS, strict=True):
        assert_array_equal(res.K, K)
        assert design.plant.closed_loop(K).is_hurwitz()
        # each gain's in-band gain, swept independently, is within its LMI bound
        assert band_peak(design.plant.closed_loop(K), band).gamma <= res.gamma_lmi * (1 + 1e-5)
    # Remark 4: γ of the out-of-band mode fixed at γ_tol = 10, the in-band one minimized
    assert design.gammas[0] == pytest.approx(10.0, rel=1e-6)
    assert design.gammas[1] < 1.0
    assert all(v < 0 for v in design.certificate.max_eigs.values())


def test_from_gains_with_given_q_certifies_them(design):
    again = FDSC.from_gains(OSC, list(design.gains), BANDS, 1, Q=list(design.Q))
    for q_given, q_held in zip(design.Q, again.Q, strict=True):
        assert_array_equal(q_held, q_given)  # the law uses the given Q's bit for bit
    ref = certify_q(list(design.modes), BANDS, list(design.Q))
    assert_allclose(again.gammas, ref.gammas, rtol=1e-6)


def test_simulate_is_the_switched_simulation_with_the_designs_law(design):
    d = Piecewise([0.0, 5.0, 50.0], [Sinusoids([1.0], [0.2]), Sinusoids([1.0], [12.0])])
    t = time_grid(10.0, 1e-3)
    run = design.simulate(d, t)
    ref = simulate(list(design.modes), d, t, law_bands=BANDS, law_Q=list(design.Q))
    assert_array_equal(run.z, ref.z)
    assert_array_equal(run.sigma, ref.sigma)
    # the law follows the disturbance: LF mode while it is slow, HF mode once it is fast
    assert np.mean(run.sigma[t < 5.0] == 0) > 0.5 and np.mean(run.sigma[t >= 5.0] == 1) > 0.5
    assert_array_equal(simulate(design.mode(1), d, t).z, simulate(design.modes[1], d, t).z)


def test_statespace_plant_gives_the_same_design(design):
    ss = control.ss(A, [[0.0, 0.0], [1.0, 1.0]], [[1.0, 0.0], [0.0, 0.0]], [[0.0, 0.0], [0.0, 0.1]])
    again = FDSC.from_gains(ss, list(design.gains), BANDS, 1, Q=list(design.Q), n_disturbances=1)
    assert_array_equal(again.plant.B1, OSC.B1)
    assert_array_equal(again.plant.D2, OSC.D2)


@pytest.mark.parametrize(("make", "exc", "match"), [
    (lambda d: FDSC.from_gains(OSC, d.gains, BANDS, 2), ValueError, r"in_band must be a mode index"),
    (lambda d: FDSC.from_gains(OSC, d.gains, BANDS[:1], 0), ValueError, "at least two frequency ranges"),
    (lambda d: FDSC.from_gains(OSC, list(d.gains) * 2, BANDS, 0), ValueError, "one range per gain: 4 gains"),
    (lambda d: FDSC.from_gains(OSC, d.gains[0], BANDS, 0), TypeError, "gains must be a list"),
    (lambda d: FDSC.from_gains(OSC, [np.zeros((1, 3))] * 2, BANDS, 0), DimensionError,
         r"gains\[0\]: expected shape \(1, 2\)"),
    (lambda d: FDSC.from_gains(OSC, [np.array([[10.0, 0.0]])] * 2, BANDS, 0), UnstableError, "not stable"),
    (lambda d: FDSC.from_gains(OSC, d.gains, [Band.lf(0.5), Band.mf(1.0, 3.0)], 0), ValueError, "real Ψ"),
    (lambda d: FDSC.from_gains(OSC, d.gains, [Band.lf(0.5), "HF"], 0), TypeError, r"bands\[1\]"),
    (lambda d: FDSC(OSC, d.gains, BANDS, 1, "certificate"), TypeError, "certificate"),
])
def test_bad_design_inputs(design, make, exc, match):
    with pytest.raises(exc, match=match):
        make(design)


def test_as_system_accepts_every_form_and_they_agree():
    rng = np.random.default_rng(4)
    A_, B_, C_, D_ = (rng.standard_normal(s) for s in ((3, 3), (3, 1), (2, 3), (2, 1)))
    A_ = A_ - 4 * np.eye(3)
    ref = LTISystem(A_, B_, C_, D_)
    for form in ((A_, B_, C_, D_), [A_, B_, C_, D_], control.ss(A_, B_, C_, D_), ref):
        sys = as_system(form)
        for name in "ABCD":
            assert_array_equal(getattr(sys, name), getattr(ref, name))
    assert band_peak(control.ss(A_, B_, C_, D_), Band.hf(1.0)).gamma == band_peak(ref, Band.hf(1.0)).gamma


@pytest.mark.parametrize(("call", "exc", "match"), [
    (lambda: as_system(OSC), TypeError, "found a Plant; close it with plant.closed_loop"),
    (lambda: as_system("sys"), TypeError, r"sys must be an fdsc.LTISystem, a python-control StateSpace or"),
    (lambda: as_system(([[-1.0]], [[1.0]], [[1.0]])), TypeError, "found tuple"),
    (lambda: as_system(control.ss([[0.5]], [[1.0]], [[1.0]], [[0.0]], 0.1)), ValueError, "continuous-time"),
    (lambda: as_system(control.tf([1.0], [1.0, 1.0])), TypeError, "convert with control.ss"),
    # a StateSpace's first input is the disturbance unless n_disturbances says otherwise
    (lambda: as_plant(control.ss(A, [[1.0], [0.0]], np.eye(2), np.zeros((2, 1)))), ValueError,
     r"below the number of inputs 1 .* \(the default: the first input is the disturbance\)"),
    (lambda: as_plant(control.ss(A, np.eye(2), np.eye(2), np.zeros((2, 2))), n_disturbances=2), ValueError,
     "at least one control input"),
    (lambda: as_plant(LTISystem(A, [[0.0], [1.0]], [[1.0, 0.0]], [[0.0]])), TypeError, "found an LTISystem"),
    (lambda: as_plant((A, A)), TypeError, r"tuple \(A, B1, B2, C, D1, D2\)"),
])
def test_bad_system_inputs(call, exc, match):
    with pytest.raises(exc, match=match):
        call()


def test_plant_tuple_and_random_plant():
    p = random_plant(np.random.default_rng(0), 3, stable=True)
    q = as_plant((p.A, p.B1, p.B2, p.C, p.D1, p.D2))
    for name in ("A", "B1", "B2", "C", "D1", "D2"):
        assert_array_equal(getattr(q, name), getattr(p, name))
    # spectral abscissa drawn in the default range [-1, -0.1]
    assert -1.0 - 1e-12 <= np.linalg.eigvals(p.A).real.max() <= -0.1 + 1e-12
