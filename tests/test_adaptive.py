"""fdsc.adaptive: the adaptive FIR feedforward against the non-causal limit (never below it, near
it on held tones), with its filter held at zero against the fixed loop it then is (an independent
closed form), its energy invariant to how a piece is cut and to the units of d, causal, and bad
input by name."""

import math

import numpy as np
import pytest

from fdsc import Controller, Piecewise, Plant, Sinusoids, loop_energy, lq_data, noncausal_limit
from fdsc.adaptive import AdaptiveFeedforward

P2 = Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
           [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.3]])
TONES = Sinusoids([1.0, 0.5], [3.0, 7.0], [0.3, 1.1])


def test_on_held_tones_it_comes_near_the_limit_and_never_passes_it():
    lim = noncausal_limit(P2, TONES, 100.0).energy
    lq_only = AdaptiveFeedforward(P2, 0.02, taps=1, regularization=1e12).run(TONES, 100.0).energy
    run = AdaptiveFeedforward(P2, 0.02, taps=16, memory=4.0).run(TONES, 100.0)
    assert lim <= run.energy < 1.08 * lim
    assert run.energy < 0.6 * lq_only                       # the adaptation does the work
    assert run.output_energy.sum() == pytest.approx(run.energy, rel=1e-12)
    assert run.steps == 5000


def test_with_its_filter_held_at_zero_it_is_the_fixed_loop_of_its_static_part():
    # δ huge: Θ = −(R + δI)⁻¹g ≈ 0, so u = K x + (K_d − R⁻¹B2ᵀψ(0)) ŵ, a fixed LTI loop whose
    # energy the closed form of loop_energy gives independently (breaks off the sampling grid)
    d = Piecewise([0.0, 13.337, 41.05, 70.0],
                  [TONES, Sinusoids([0.8], [1.7]), Sinusoids([0.4, 0.2], [5.0, 0.4])])
    lq = lq_data(P2)
    F = lq.K_d - lq.R_inv_B2T @ lq.psi_gain([0.0])[0]
    fixed = Controller(np.zeros((0, 0)), np.zeros((0, 2)), np.zeros((1, 0)), lq.K,
                       E=np.zeros((0, 1)), F=F.real)
    run = AdaptiveFeedforward(P2, 0.03, taps=4, regularization=1e30).run(d, 80.0)
    assert run.largest_update < 1e-20
    assert run.energy == pytest.approx(loop_energy(fixed.closed_loop(P2), d, 80.0), rel=1e-9)


def test_the_energy_does_not_depend_on_where_a_piece_is_cut():
    # the same tones split at an instant off the grid: the partial steps around the cut carry
    # the held v exactly, so the run and its energy are the same
    whole = Piecewise([0.0, 30.0], [TONES])
    cut = Piecewise([0.0, 11.1234, 30.0], [TONES, TONES])
    law = AdaptiveFeedforward(P2, 0.05, taps=8, memory=2.0)
    a, b = law.run(whole, 30.0), law.run(cut, 30.0)
    assert a.largest_update > 0.1
    assert b.energy == pytest.approx(a.energy, rel=1e-9)
    assert b.pieces.shape[0] == a.pieces.shape[0] + 1


def test_the_energy_scales_with_the_square_of_the_disturbance():
    law = AdaptiveFeedforward(P2, 0.05, taps=8, memory=2.0)
    big = Sinusoids(1e3 * TONES.amplitudes, TONES.frequencies, TONES.phases)
    assert law.run(big, 40.0).energy == pytest.approx(1e6 * law.run(TONES, 40.0).energy, rel=1e-9)


def test_it_is_causal_what_comes_after_a_break_does_not_change_the_run_before_it():
    law = AdaptiveFeedforward(P2, 0.05, taps=8, memory=2.0)
    one = law.run(Piecewise([0.0, 20.0, 40.0], [TONES, Sinusoids([1.0], [2.0])]), 40.0)
    two = law.run(Piecewise([0.0, 20.0, 40.0], [TONES, Sinusoids([3.0], [9.0])]), 40.0)
    assert one.pieces[0, 2] == two.pieces[0, 2]
    assert one.pieces[1, 2] != two.pieces[1, 2]


def test_a_noisy_estimate_costs_energy():
    law = AdaptiveFeedforward(P2, 0.02, taps=16, memory=4.0)
    noisy = Sinusoids(np.r_[TONES.amplitudes, 0.1, 0.1], np.r_[TONES.frequencies, 11.0, 17.0],
                      np.r_[TONES.phases, 0.0, 0.5])
    clean = law.run(TONES, 60.0).energy
    assert law.run(TONES, 60.0, estimate=noisy).energy > clean
    assert law.run(TONES, 60.0, estimate=TONES).energy == pytest.approx(clean, rel=1e-9)


@pytest.mark.parametrize("kwargs, err, match", [
    (dict(step=0.0), ValueError, "step"),
    (dict(step=0.02, taps=0), ValueError, "taps"),
    (dict(step=0.02, memory=-1.0), ValueError, "memory"),
    (dict(step=0.02, regularization=0.0), ValueError, "regularization"),
    (dict(step=0.02, base="LQR"), TypeError, "base"),
])
def test_bad_arguments_are_named(kwargs, err, match):
    with pytest.raises(err, match=match):
        AdaptiveFeedforward(P2, **kwargs)


def test_bad_run_arguments_are_named():
    law = AdaptiveFeedforward(P2, 0.05)
    with pytest.raises(TypeError, match="d must be"):
        law.run([1.0, 2.0], 10.0)
    with pytest.raises(ValueError, match="horizon"):
        law.run(TONES, -1.0)
    with pytest.raises(TypeError, match="estimate must be"):
        law.run(TONES, 10.0, estimate=3.0)
    two = Plant(P2.A, np.c_[P2.B1, P2.B1], P2.B2, P2.C, np.c_[P2.D1, P2.D1], P2.D2)
    with pytest.raises(ValueError, match="one disturbance input"):
        AdaptiveFeedforward(two, 0.05)


def _noisy_case():
    from fdsc import Plant, Sinusoids
    p = Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
              [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.3]])
    return AdaptiveFeedforward(p, 0.02, taps=8, memory=2.0), Sinusoids([1.0, 0.5], [3.0, 7.0])


def test_noise_on_the_samples_costs_energy_and_is_seeded():
    law, d = _noisy_case()
    exact = law.run(d, 30.0).energy
    assert law.run(d, 30.0, noise=0.0, seed=5).energy == exact          # no noise: the exact run
    noisy = [law.run(d, 30.0, noise=1e-2, seed=s).energy for s in (1, 1, 2)]
    assert noisy[0] == noisy[1] and noisy[0] != noisy[2]                 # seeded, and the seed matters
    assert min(noisy) > exact                                            # noise the law reads costs energy
    # more noise costs more (on average over seeds)
    louder = np.mean([law.run(d, 30.0, noise=1.0, seed=s).energy for s in range(3)])
    assert louder > np.mean(noisy)


@pytest.mark.parametrize("noise", [-1.0, math.inf, math.nan, "0.1", True])
def test_noise_must_be_a_variance(noise):
    law, d = _noisy_case()
    with pytest.raises(ValueError, match="noise must be a variance"):
        law.run(d, 5.0, noise=noise)


def test_seed_must_be_an_int():
    law, d = _noisy_case()
    with pytest.raises(TypeError, match="seed"):
        law.run(d, 5.0, noise=0.1, seed=1.5)
