"""fdsc.multiband: one gain for two bands. The Pareto front (direct search certified by Lemma 1)
against the single-band designs at its ends; the LMI design's bounds; bad input by name."""

import numpy as np
import pytest

from fdsc import Band, InfeasibleError, band_peak, random_plant, synthesize
from fdsc.multiband import pareto_front, synthesize_multiband

HF, LF = Band.hf(10.0), Band.lf(1.0)


@pytest.fixture(scope="module")
def plant():
    return random_plant(np.random.default_rng(3))


@pytest.fixture(scope="module")
def designs(plant):
    hf, lf = synthesize(plant, HF), synthesize(plant, LF)
    cl_hf, cl_lf = plant.closed_loop(hf.K), plant.closed_loop(lf.K)
    # band peaks [HF, LF] of each single-band design
    return {"HF": np.array([band_peak(cl_hf, HF).gamma, band_peak(cl_hf, LF).gamma]),
            "LF": np.array([band_peak(cl_lf, HF).gamma, band_peak(cl_lf, LF).gamma])}


@pytest.fixture(scope="module")
def front(plant, designs):
    # from the LF design's own LF peak to the HF design's: the whole trade-off between the two
    lo, hi = designs["LF"][1], designs["HF"][1]
    return pareto_front(plant, HF, LF, [lo, np.sqrt(lo * hi), hi], maxiter=150)


def test_the_front_meets_its_bounds_and_never_rises(front):
    assert front.feasible.all()
    peaks = front.peaks()
    assert np.all(peaks[:, 1] <= front.betas * (1 + 1e-12))
    assert np.all(np.diff(peaks[:, 0]) <= 0)


def test_the_front_ends_at_least_as_well_as_the_single_band_designs(front, designs):
    peaks = front.peaks()
    # at the LF design's bound the LF design itself is a candidate; at the HF design's, the HF one
    assert peaks[0, 0] <= designs["LF"][0] * (1 + 1e-12)
    assert peaks[-1, 0] <= designs["HF"][0] * (1 + 1e-12)
    # and the trade-off is real on this plant: the middle bound buys most of the HF design's quiet
    assert peaks[1, 0] < 0.2 * designs["LF"][0]


def test_each_point_is_certified_by_lemma1_on_its_closed_loop(plant, front):
    for p in front.points:
        cl = plant.closed_loop(p.K)
        assert np.all(cl.poles().real < 0)
        # a certificate bounds the swept peak; Lemma 1 is lossless, so an accurate solve gives it
        done = np.isfinite(p.gamma_lmi)
        assert np.all(p.gamma_lmi[done] >= p.peak[done] * (1 - 1e-6))
        assert p.certified == bool(done.all())
    tight = [p for p in front.points if p.certified and np.allclose(p.gamma_lmi, p.peak, rtol=1e-4)]
    assert len(tight) >= 2


def test_a_bound_below_every_gain_found_is_none_not_an_error(plant, designs):
    f = pareto_front(plant, HF, LF, [1e-6, designs["HF"][1]], maxiter=100)
    assert f.feasible.tolist() == [False, True] and f.points[0] is None


def test_the_lmi_design_meets_its_bound_and_is_certified(plant, designs):
    beta = 2.0 * designs["LF"][1]
    res = synthesize_multiband(plant, HF, (LF, beta))
    assert res.gamma_lmi[1] <= beta * (1 + 1e-6)
    assert np.all(res.gamma_sweep <= res.gamma_lmi * (1 + 1e-5)) and np.all(res.poles.real < 0)
    # sharing one slack between the bands is conservative: the front does better at that bound
    f = pareto_front(plant, HF, LF, [beta], maxiter=150)
    assert f.peaks()[0, 0] <= res.gamma_sweep[0]


def test_the_lmi_design_refuses_an_unreachable_bound(plant):
    with pytest.raises(InfeasibleError):
        synthesize_multiband(plant, HF, (LF, 1e-6))


@pytest.mark.parametrize(("call", "error", "match"), [
    (lambda p: pareto_front(p, HF, LF, []), ValueError, "betas must be positive"),
    (lambda p: pareto_front(p, HF, LF, [1.0, -2.0]), ValueError, "betas must be positive"),
    (lambda p: pareto_front(p, HF, LF, [np.inf]), ValueError, "betas"),
    (lambda p: pareto_front(p, Band.entire(), LF, [1.0]), ValueError, "objective is the entire range"),
    (lambda p: pareto_front(p, HF, Band.entire(), [1.0]), ValueError, "constrained is the entire range"),
    (lambda p: pareto_front(p, HF, "LF", [1.0]), TypeError, "constrained"),
    (lambda p: pareto_front(p, HF, LF, [1.0], maxiter=0), ValueError, "maxiter"),
    (lambda p: pareto_front(p, HF, LF, [1.0], penalty=-1.0), ValueError, "penalty"),
    (lambda p: synthesize_multiband(p, HF, []), ValueError, "constraints must hold at least one"),
    (lambda p: synthesize_multiband(p, HF, [(LF, 0.0)]), ValueError, r"constraints\[0\]\[1\]"),
    (lambda p: synthesize_multiband(p, HF, [("LF", 1.0)]), TypeError, r"constraints\[0\]\[0\]"),
    (lambda p: synthesize_multiband(p, HF, [LF]), TypeError, r"constraints\[0\] must be a pair"),
    (lambda p: synthesize_multiband(p, HF, (Band.entire(), 1.0)), ValueError,
     r"constraints\[0\]\[0\] is the entire"),
])
def test_bad_input_is_refused_by_name(plant, call, error, match):
    with pytest.raises(error, match=match):
        call(plant)
