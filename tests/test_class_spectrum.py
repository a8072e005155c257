import math

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.integrate import quad

from fdsc.class_spectrum import SegmentClass

AIRCRAFT = SegmentClass([(0.1, 1.0), (10.0, 300.0)], [0.5, 0.5])


def test_survival_is_the_stationary_renewal_probability():
    # lengths 20 + Exp(80): P(no break in (t, t + τ]) = (1/100) ∫_τ^∞ P(L > s) ds
    c = AIRCRAFT
    for tau in (0.0, 7.0, 20.0, 55.0, 300.0):
        tail = quad(lambda s: 1.0 if s < 20 else math.exp(-(s - 20) / 80), tau, np.inf)[0] / 100.0
        assert_allclose(c.survival(tau), tail, rtol=1e-8)
    # simulated: share of random instants t whose segment still holds at t + τ
    rng = np.random.default_rng(0)
    ends = np.cumsum(20.0 + rng.exponential(80.0, 200_000))
    t = rng.uniform(0.0, ends[-1] - 1000.0, 200_000)
    k = np.searchsorted(ends, t)
    for tau in (10.0, 60.0):
        assert abs(np.mean(t + tau < ends[k]) - c.survival(tau)) < 4e-3


def test_kernel_is_the_transform_of_the_survival():
    # K(ω) = 2 ∫₀^∞ S(τ) cos ωτ dτ by quadrature (S below e^-40 beyond 20 + 40·80 s)
    c = AIRCRAFT
    for w in (0.0, 1e-6, 0.01, 0.3, 5.0):
        direct = sum(2 * quad(lambda t, w=w: float(c.survival(t)) * math.cos(w * t), a, b, limit=2000,
                              epsabs=1e-13)[0] for a, b in ((0, 20), (20, 3220)))
        assert_allclose(c.kernel(w), direct, rtol=1e-8, atol=1e-9)


def test_tone_covariance_is_the_mean_of_log_uniform_tones():
    # one band: c(τ) = ∫ cos(ντ) / (ν ln(h/l)) dν
    c = SegmentClass([(2.0, 50.0)], [1.0], power=3.0)
    for tau in (0.0, 0.01, 0.3, 4.0):
        direct = 3.0 * quad(lambda v, tau=tau: math.cos(v * tau) / (v * math.log(25.0)), 2.0, 50.0,
                            limit=400)[0]
        assert_allclose(c.tone_covariance(tau), direct, rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize("w", [0.05, 0.3, 0.999, 3.0, 10.01, 50.0, 299.0, 320.0, 1000.0])
def test_spectrum_is_the_convolution_of_the_tones_with_the_kernel(w):
    # Φ(ω) = ∫ p(ν) ½ (K(ω − ν) + K(ω + ν)) dν, by adaptive quadrature (an independent route)
    c = AIRCRAFT
    direct = 0.0
    for (lo, hi), s in zip(c.bands, c.shares, strict=True):
        def f(v, lo=lo, hi=hi, s=s):
            return s / (v * math.log(hi / lo)) * 0.5 * (c.kernel(w - v) + c.kernel(w + v))
        direct += quad(f, lo, hi, points=[w] if lo < w < hi else None, limit=500, epsabs=0,
                       epsrel=1e-10)[0]
    # the lag grid's trapezoid and the frequency grid's interpolation: 1e-3 near a band edge,
    # and far out (Φ below 1e-6 of its peak) a small absolute error of the lag grid's aliasing
    assert_allclose(c.spectrum(w), direct, rtol=2e-3, atol=1e-5 * float(c.spectrum(0.1)))


def test_spectrum_integrates_to_the_power_and_transforms_back():
    c = SegmentClass([(0.3, 1.0), (10.0, 40.0)], [0.3, 0.7], power=2.0)
    w = np.linspace(0.0, 50.0, 100_001)          # to 1.25 times the top tone: the lag grid's range
    phi = c.spectrum(w)
    # beyond 50 rad/s the tails fall like 1/ω² (a few 1e-4 of the power)
    assert_allclose(np.trapezoid(phi, w) / math.pi, 2.0, rtol=2e-3)
    for tau in (0.5, 3.0):
        assert_allclose(np.trapezoid(phi * np.cos(w * tau), w) / math.pi, c.autocovariance(tau),
                        rtol=0, atol=5e-3)


def test_monte_carlo_of_draws_matches_the_autocovariance():
    # independent segments of 3 tones per band, log-uniform, the power split by the shares
    c = SegmentClass([(0.5, 2.0), (10.0, 30.0)], [0.4, 0.6], min_length=5.0, mean_extra=15.0)
    rng = np.random.default_rng(3)
    dt, total = 0.01, 4000.0
    t = np.arange(0.0, total, dt)
    d = np.zeros_like(t)
    start = 0.0
    while start < total:
        end = start + 5.0 + rng.exponential(15.0)
        sel = (t >= start) & (t < end)
        for (lo, hi), share in zip(c.bands, c.shares, strict=True):
            w = np.exp(rng.uniform(math.log(lo), math.log(hi), 3))
            a = np.full(3, math.sqrt(2 * share / 3))
            ph = rng.uniform(0, 2 * np.pi, 3)
            d[sel] += np.sin(np.outer(t[sel], w) + ph) @ a
        start = end
    for tau in (0.0, 0.05, 0.4, 3.0):
        k = round(tau / dt)
        emp = np.mean(d[:d.size - k] * d[k:])
        assert abs(emp - c.autocovariance(tau)) < 0.05


@pytest.mark.parametrize("kwargs, match", [
    (dict(bands=[(1.0, 0.5)], shares=[1.0]), "bands must be pairs 0 < low < high"),
    (dict(bands=[(0.0, 1.0)], shares=[1.0]), "bands must be pairs 0 < low < high"),
    (dict(bands="ab", shares=[1.0]), "bands must be a sequence"),
    (dict(bands=[(1.0, 2.0)], shares=[0.5, 0.5]), "one entry per band"),
    (dict(bands=[(1.0, 2.0), (3.0, 4.0)], shares=[0.6, 0.6]), "sum to 1"),
    (dict(bands=[(1.0, 2.0)], shares=[1.0], mean_extra=0.0), "mean_extra"),
    (dict(bands=[(1.0, 2.0)], shares=[1.0], min_length=-1.0), "min_length"),
    (dict(bands=[(1.0, 2.0)], shares=[1.0], power=np.nan), "power"),
])
def test_bad_classes_are_refused_by_name(kwargs, match):
    with pytest.raises(ValueError, match=match):
        SegmentClass(**kwargs)
