import numpy as np
import pytest
from numpy.testing import assert_allclose

from fdsc import Band, InfeasibleError, LTISystem, UnstableError, band_peak, random_system
from fdsc.lmi import gkyp_certify, gkyp_gamma, gkyp_matrix, real_embedding

N_RANDOM = 50


def random_bands(rng):
    w1 = float(rng.uniform(0.3, 3.0))
    return [Band.lf(w1), Band.mf(w1, w1 * float(rng.uniform(1.5, 10.0))), Band.hf(w1),
            Band.entire()]


@pytest.mark.parametrize("kind", ["LF", "MF", "HF", "EF"])
def test_lemma1_equals_sweep_peak_on_random_systems(kind):
    # the gKYP lemma is lossless: the smallest certified γ is the band peak
    rng = np.random.default_rng(2026)
    worst = 0.0
    for i in range(N_RANDOM):
        sys = random_system(rng, int(rng.integers(1, 5)), int(rng.integers(1, 3)), int(rng.integers(1, 4)),
                            abscissa=(-3.0, -0.1), direct=bool(i % 2))
        band = {b.kind: b for b in random_bands(rng)}[kind]
        cert = gkyp_gamma(sys, band)
        peak = band_peak(sys, band).gamma
        worst = max(worst, abs(cert.gamma - peak) / peak)
        assert cert.max_eig < 0
    assert worst < 1e-4


def test_certificate_reproduces_negative_lmi_matrix():
    sys = LTISystem([[-1.0, 2.0], [-2.0, -1.0]], [[1.0], [0.0]], [[1.0, 0.0]], [[0.0]])
    for band in (Band.lf(1.0), Band.mf(1.0, 3.0), Band.hf(3.0), Band.entire()):
        cert = gkyp_gamma(sys, band)
        M = gkyp_matrix(sys, band, cert.P, cert.Q, cert.gamma)
        assert np.linalg.eigvalsh(M).max() < 0
        assert_allclose(cert.P, cert.P.conj().T, atol=1e-12 * np.abs(cert.P).max())
        if band.kind != "EF":
            assert np.linalg.eigvalsh(cert.Q).min() > 0
        if band.kind == "MF":
            assert np.abs(cert.P.imag).max() > 0  # the complex certificate is really complex


def test_first_order_lf_value():
    # |1/(jω+1)| is largest at ω = 0 where it is 1
    cert = gkyp_gamma(LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]]), Band.lf(1.0))
    assert_allclose(cert.gamma, 1.0, rtol=1e-6)


def test_certify_above_and_below_the_peak():
    sys = LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]])
    band = Band.hf(2.0)
    peak = band_peak(sys, band).gamma  # 1/sqrt(5)
    assert gkyp_certify(sys, band, 1.01 * peak).gamma == pytest.approx(1.01 * peak)
    # decided by the sweep before any solve: the answer cannot depend on the solver's rounding
    with pytest.raises(InfeasibleError,
                       match=r"no certificate exists, sigma_max\(G\(jw\)\) reaches 0\.447") as info:
        gkyp_certify(sys, band, 0.99 * peak)
    assert info.value.status == "not solved (sweep)" and info.value.solver_status is None


def test_pole_on_the_imaginary_axis_is_refused_before_solving():
    # undamped oscillator at 0.5 rad/s: G is unbounded on the LF band [0, 1], and no γ bounds
    # the energy of a loop that is not asymptotically stable
    sys = LTISystem([[0.0, 1.0], [-0.25, 0.0]], [[0.0], [1.0]], [[1.0, 0.0]], [[0.0]])
    with pytest.raises(UnstableError, match=r"eigenvalue 0\+0\.5j") as info:
        gkyp_certify(sys, Band.lf(1.0), 10.0)
    assert info.value.eigenvalue == pytest.approx(0.5j)


def test_real_embedding_doubles_the_spectrum():
    rng = np.random.default_rng(3)
    X = rng.standard_normal((3, 3)) + 1j * rng.standard_normal((3, 3))
    M = X + X.conj().T
    ev = np.linalg.eigvalsh(M)
    assert_allclose(np.linalg.eigvalsh(real_embedding(M)), np.sort(np.repeat(ev, 2)), atol=1e-12)


@pytest.mark.parametrize(
    ("call", "exc", "match"),
    [
        (lambda s: gkyp_gamma(s, Band.lf(1.0), margin=0.0), ValueError, "margin must be a positive"),
        (lambda s: gkyp_gamma(s, Band.lf(1.0), margin=float("nan")), ValueError, "margin"),
        (lambda s: gkyp_certify(s, Band.lf(1.0), -1.0), ValueError, "gamma must be a positive"),
        (lambda s: gkyp_gamma(s, "LF"), TypeError, "band must be an fdsc.Band"),
        (lambda s: gkyp_gamma(s.A, Band.lf(1.0)), TypeError, "sys must be an fdsc.LTISystem"),
    ],
)
def test_bad_lmi_inputs(call, exc, match):
    sys = LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]])
    with pytest.raises(exc, match=match):
        call(sys)
