import cvxpy as cp
import numpy as np
import pytest
from numpy.testing import assert_allclose, assert_array_equal

from fdsc import PHI, Band, DimensionError, LTISystem, Plant, random_system
from fdsc.kyp import kyp_matrix, kyp_outer, kyp_weight, supply_parts
from fdsc.lmi import gkyp_matrix
from fdsc.switching import theorem1_matrices
from fdsc.synthesis import _band_lmi, _hinf_lmi

RTOL, ATOL = 1e-12, 1e-12
KINDS = ["LF", "MF", "HF", "EF"]


def band_of(kind):
    return {"LF": Band.lf(1.5), "MF": Band.mf(0.7, 4.0), "HF": Band.hf(2.5),
            "EF": Band.entire()}[kind]


def hermitian(rng, n, cplx):
    X = rng.standard_normal((n, n)) + (1j * rng.standard_normal((n, n)) if cplx else 0)
    return 0.5 * (X + X.conj().T)


def pair(M):
    return (M.real, M.imag) if np.iscomplexobj(M) else (M, None)


def assemble(re, im):
    return re if im is None else re + 1j * im


def hand_weight(P, psi_q):
    """Φ⊗P + Σ s Ψ⊗Q block by block in complex arithmetic (no Kronecker product)."""
    W = np.block([[0 * P, P], [P, 0 * P]]).astype(complex)
    for psi, Q, s in psi_q:
        W = W + s * np.block([[psi[0, 0] * Q, psi[0, 1] * Q], [psi[1, 0] * Q, psi[1, 1] * Q]])
    return W


@pytest.mark.parametrize("kind", KINDS)
def test_weight_equals_hand_written_blocks(kind):
    rng = np.random.default_rng(1)
    band = band_of(kind)
    for _ in range(5):
        n = int(rng.integers(1, 5))
        P, Q = hermitian(rng, n, band.is_complex), hermitian(rng, n, band.is_complex)
        terms = [] if kind == "EF" else [(band.psi, pair(Q), 1)]
        re, im = kyp_weight(pair(P), terms)
        ref = hand_weight(P, [] if kind == "EF" else [(band.psi, Q, 1)])
        assert_allclose(assemble(re, im), ref, rtol=RTOL, atol=ATOL)
        assert (im is None) == (kind != "MF")


def test_weight_with_two_terms_of_opposite_sign():
    # Theorem 1's Φ⊗P + Ψ_i⊗Q_i − Ψ_j⊗Q_j, including a complex Ψ to cover the cross terms
    rng = np.random.default_rng(2)
    n = 3
    P, Qi, Qj = (hermitian(rng, n, True) for _ in range(3))
    bi, bj = Band.lf(1.0), Band.mf(1.0, 3.0)
    re, im = kyp_weight(pair(P), [(bi.psi, pair(Qi), 1), (bj.psi, pair(Qj), -1)])
    assert_allclose(assemble(re, im), hand_weight(P, [(bi.psi, Qi, 1), (bj.psi, Qj, -1)]),
                    rtol=RTOL, atol=ATOL)


@pytest.mark.parametrize("kind", KINDS)
def test_parts_reassemble_to_a_hermitian_matrix(kind):
    rng = np.random.default_rng(3)
    band = band_of(kind)
    sys = random_system(rng, 3, 2, 2, direct=True)
    P, Q = hermitian(rng, 3, band.is_complex), hermitian(rng, 3, band.is_complex)
    terms = [] if kind == "EF" else [(band.psi, pair(Q), 1)]
    re, im = kyp_matrix(sys.A, sys.B, sys.C, sys.D, pair(P), terms, 1.7)
    M = assemble(re, im)
    assert_allclose(M, M.conj().T, rtol=RTOL, atol=ATOL)
    assert_allclose(re, re.T, rtol=RTOL, atol=ATOL)
    if im is not None:
        assert_allclose(im, -im.T, rtol=RTOL, atol=ATOL)


@pytest.mark.parametrize("kind", KINDS)
def test_kyp_matrix_equals_lemma1_written_out(kind):
    # F* W F + G* diag(I, −g I) G with F = [A B; I 0], G = [C D; 0 I] in complex arithmetic
    rng = np.random.default_rng(4)
    band = band_of(kind)
    for _ in range(5):
        n, m, p = (int(k) for k in rng.integers(1, 4, size=3))
        sys = random_system(rng, n, m, p, direct=True)
        P, Q = hermitian(rng, n, band.is_complex), hermitian(rng, n, band.is_complex)
        g = float(rng.uniform(0.5, 3.0))
        F = np.block([[sys.A, sys.B], [np.eye(n), np.zeros((n, m))]])
        G = np.block([[sys.C, sys.D], [np.zeros((m, n)), np.eye(m)]])
        Pi = np.block([[np.eye(p), np.zeros((p, m))], [np.zeros((m, p)), -g * np.eye(m)]])
        W = hand_weight(P, [] if kind == "EF" else [(band.psi, Q, 1)])
        ref = F.T @ W @ F + G.T @ Pi @ G
        terms = [] if kind == "EF" else [(band.psi, pair(Q), 1)]
        re, im = kyp_matrix(sys.A, sys.B, sys.C, sys.D, pair(P), terms, g)
        assert_allclose(assemble(re, im), ref, rtol=1e-10, atol=1e-10)


def test_outer_without_input_is_the_lyapunov_form():
    # [A; I]ᵀ W [A; I] = Aᵀ W11 A + Aᵀ W12 + W21 A + W22
    rng = np.random.default_rng(5)
    A = rng.standard_normal((3, 3))
    W = rng.standard_normal((6, 6))
    ref = A.T @ W[:3, :3] @ A + A.T @ W[:3, 3:] + W[3:, :3] @ A + W[3:, 3:]
    assert_allclose(kyp_outer(W, A), ref, rtol=1e-12, atol=1e-12)


def test_supply_parts_are_cd_gram_and_input_selector():
    rng = np.random.default_rng(6)
    C, D = rng.standard_normal((2, 3)), rng.standard_normal((2, 4))
    out, inn = supply_parts(C, D)
    CD = np.hstack([C, D])
    assert_allclose(out, CD.T @ CD, rtol=1e-12, atol=1e-12)
    assert_array_equal(inn, np.diag([0.0] * 3 + [1.0] * 4))


def cvx_pair(value, name):
    """A cvxpy variable pair holding ``value`` (the imaginary part as a general matrix)."""
    re = cp.Variable(value.shape, name=f"{name}_re")
    re.value = value.real
    if not np.iscomplexobj(value):
        return re, None
    im = cp.Variable(value.shape, name=f"{name}_im")
    im.value = value.imag
    return re, im


def value(expr):
    return None if expr is None else expr.value


@pytest.mark.parametrize("kind", KINDS)
def test_numpy_and_cvxpy_backends_agree(kind):
    rng = np.random.default_rng(7)
    band = band_of(kind)
    sys = random_system(rng, 3, 2, 2, direct=True)
    P, Q = hermitian(rng, 3, band.is_complex), hermitian(rng, 3, band.is_complex)
    g = 2.3
    gv = cp.Variable(name="g")
    gv.value = g
    terms_np = [] if kind == "EF" else [(band.psi, pair(Q), 1)]
    terms_cp = [] if kind == "EF" else [(band.psi, cvx_pair(Q, "Q"), 1)]
    re, im = kyp_matrix(sys.A, sys.B, sys.C, sys.D, pair(P), terms_np, g)
    cre, cim = kyp_matrix(sys.A, sys.B, sys.C, sys.D, cvx_pair(P, "P"), terms_cp, gv,
                          backend="cvxpy")
    assert isinstance(cre, cp.Expression)
    assert_allclose(cre.value, re, rtol=1e-12, atol=1e-12)
    if im is None:
        assert cim is None
    else:
        assert_allclose(value(cim), im, rtol=1e-12, atol=1e-12)


def test_cvxpy_backend_accepts_constants():
    # Theorem 1 with given Q's mixes variables and fixed matrices
    rng = np.random.default_rng(8)
    P, Q = hermitian(rng, 2, False), hermitian(rng, 2, False)
    re, _ = kyp_weight(cvx_pair(P, "P"), [(Band.hf(2.0).psi, Q, 1)], backend="cvxpy")
    assert_allclose(re.value, kyp_weight(P, [(Band.hf(2.0).psi, Q, 1)])[0], rtol=1e-12, atol=1e-12)


def previous_lmi_parts(sys, band, P, Q, g):
    """Reference: fdsc.lmi._lmi_parts as it read before the builder (NumPy branch, verbatim)."""
    n, m, p = sys.n_states, sys.n_inputs, sys.n_outputs
    F = np.block([[sys.A, sys.B], [np.eye(n), np.zeros((n, m))]])
    Gm = np.block([[sys.C, sys.D], [np.zeros((m, n)), np.eye(m)]])
    kron = np.kron
    psi_re, psi_im = band.psi.real, band.psi.imag
    W_re = kron(band.phi, P[0])
    W_im = kron(band.phi, P[1]) if P[1] is not None else None
    if band.kind != "EF":
        W_re = W_re + kron(psi_re, Q[0])
        if band.is_complex:
            W_re = W_re - kron(psi_im, Q[1])
            W_im = W_im + kron(psi_re, Q[1]) + kron(psi_im, Q[0])
    Z = np.zeros((m, p))
    Pi_out = np.block([[np.eye(p), Z.T], [Z, np.zeros((m, m))]])
    Pi_in = np.block([[np.zeros((p, p)), Z.T], [Z, np.eye(m)]])
    re = F.T @ W_re @ F + Gm.T @ Pi_out @ Gm - g * (Gm.T @ Pi_in @ Gm)
    im = F.T @ W_im @ F if W_im is not None else None
    return re, im


@pytest.mark.parametrize("kind", KINDS)
def test_gkyp_matrix_equals_its_previous_definition_bit_for_bit(kind):
    # the builder sums in the previous order, so verified certificates (and the record's max_eig)
    # are unchanged to the last bit
    rng = np.random.default_rng(9)
    band = band_of(kind)
    for _ in range(10):
        n, m, p = (int(k) for k in rng.integers(1, 4, size=3))
        sys = random_system(rng, n, m, p, direct=True)
        P, Q = hermitian(rng, n, band.is_complex), hermitian(rng, n, band.is_complex)
        gamma = float(rng.uniform(0.5, 3.0))
        cplx = band.is_complex
        re, im = previous_lmi_parts(sys, band, (P.real, P.imag if cplx else None),
                                    (Q.real, Q.imag if cplx else None), gamma**2)
        M = re + 1j * im if cplx else re.astype(complex)
        assert_array_equal(gkyp_matrix(sys, band, P, Q, gamma), 0.5 * (M + M.conj().T))


def previous_theorem1_matrices(mode_i, band_i, band_j, Ps_i, P_i, Q_i, Q_j, gamma_i):
    """Reference: fdsc.switching.theorem1_matrices before the builder (NumPy branch, verbatim)."""
    A, B, C, D = mode_i.A, mode_i.B, mode_i.C, mode_i.D
    n, m, p = A.shape[0], B.shape[1], C.shape[0]
    kron = np.kron
    Sig = kron(band_i.psi.real, Q_i) - kron(band_j.psi.real, Q_j)
    F1 = np.vstack([A, np.eye(n)])
    M1 = F1.T @ (kron(PHI, Ps_i) + Sig) @ F1
    F2 = np.block([[A, B], [np.eye(n), np.zeros((n, m))]])
    G2 = np.block([[C, D], [np.zeros((m, n)), np.eye(m)]])
    g = gamma_i**2
    out = np.block([[np.eye(p), np.zeros((p, m))], [np.zeros((m, p)), np.zeros((m, m))]])
    inn = np.block([[np.zeros((p, p)), np.zeros((p, m))], [np.zeros((m, p)), np.eye(m)]])
    M2 = F2.T @ (kron(PHI, P_i) + Sig) @ F2 + G2.T @ out @ G2 - g * (G2.T @ inn @ G2)
    return M1, M2


@pytest.mark.parametrize(("kind_i", "kind_j"), [("LF", "HF"), ("HF", "LF"), ("EF", "HF")])
def test_theorem1_matrices_equal_their_previous_definition_bit_for_bit(kind_i, kind_j):
    rng = np.random.default_rng(10)
    for _ in range(10):
        n, m, p = (int(k) for k in rng.integers(1, 4, size=3))
        mode = random_system(rng, n, m, p, direct=True)
        Ps, P, Qi, Qj = (hermitian(rng, n, False) for _ in range(4))
        args = (mode, band_of(kind_i), band_of(kind_j), Ps, P, Qi, Qj, float(rng.uniform(0.5, 3)))
        for new, old in zip(theorem1_matrices(*args), previous_theorem1_matrices(*args),
                            strict=True):
            assert_array_equal(new, old)


def random_synthesis_data(rng, n, m1, mu, p, cplx):
    plant = Plant(rng.standard_normal((n, n)), rng.standard_normal((n, m1)),
                  rng.standard_normal((n, mu)), rng.standard_normal((p, n)),
                  0.3 * rng.standard_normal((p, m1)), rng.standard_normal((p, mu)))
    X = rng.standard_normal((n, n)) + 3 * np.eye(n)
    Y = rng.standard_normal((mu, n))
    return plant, X, Y, hermitian(rng, n, cplx), hermitian(rng, n, cplx)


@pytest.mark.parametrize("kind", ["LF", "MF", "HF"])
def test_synthesis_band_lmi_projects_to_dual_lemma1(kind):
    # the slack terms vanish on N = [A_Kᵀ C_Kᵀ; I 0; 0 I], which leaves Lemma 1 for the dual
    # realization (A_Kᵀ, C_Kᵀ, B1ᵀ, D1ᵀ) with K = Y X⁻¹: this ties the block-by-block weight of
    # the synthesis LMI to the shared builder
    rng = np.random.default_rng(11)
    band = band_of(kind)
    for _ in range(5):
        plant, X, Y, P, Q = random_synthesis_data(rng, 3, 2, 2, 2, band.is_complex)
        g, sigma = 1.9, float(rng.uniform(0.0, 2.0))
        re, im = _band_lmi(plant, band, X, Y, pair(P), pair(Q), g, sigma)
        L = re.value + (1j * im.value if im is not None else 0)
        K = Y @ np.linalg.inv(X)
        cl = plant.closed_loop(K)
        n, p = 3, 2
        N = np.vstack([np.hstack([cl.A.T, cl.C.T]), np.eye(n, n + p), np.eye(p, n + p, n)])
        dre, dim = kyp_matrix(cl.A.T, cl.C.T, cl.B.T, cl.D.T, pair(P), [(band.psi, pair(Q), 1)], g)
        assert_allclose(N.T @ L @ N, assemble(dre, dim), rtol=1e-9, atol=1e-9)


def test_hinf_lmi_is_the_dual_bounded_real_lemma():
    rng = np.random.default_rng(12)
    for _ in range(5):
        plant, X, Y, _, _ = random_synthesis_data(rng, 3, 2, 2, 2, False)
        X = X @ X.T  # the H∞ LMI's X is the symmetric P of the bounded real lemma
        cl = plant.closed_loop(Y @ np.linalg.inv(X))
        ref, _ = kyp_matrix(cl.A.T, cl.C.T, cl.B.T, cl.D.T, X, [], 2.4)
        assert_allclose(_hinf_lmi(plant, X, Y, 2.4).value, ref, rtol=1e-9, atol=1e-9)


@pytest.mark.parametrize(
    ("call", "exc", "match"),
    [
        (lambda: kyp_weight(np.eye(2), backend="torch"), ValueError,
         r"backend must be one of \('numpy', 'cvxpy'\), but found 'torch'"),
        (lambda: kyp_weight(np.eye(2), [(Band.lf(1.0).psi, np.eye(2), 2)]), ValueError,
         r"terms\[0\]: sign must be 1 or -1, but found 2"),
        (lambda: kyp_weight(np.eye(2), [(Band.lf(1.0).psi, np.eye(3), 1)]), DimensionError,
         r"terms\[0\] Q \(real part\): expected shape \(2, 2\) but found \(3, 3\)"),
        (lambda: kyp_weight(np.eye(2), [(np.eye(3), np.eye(2), 1)]), DimensionError,
         r"terms\[0\] psi: expected shape \(2, 2\) but found \(3, 3\)"),
        (lambda: kyp_weight((np.eye(2), np.zeros((2, 1)))), DimensionError,
         r"P \(imaginary part\): expected shape \(2, 2\) but found \(2, 1\)"),
        (lambda: kyp_outer(np.eye(4), np.eye(3)), DimensionError,
         r"W: expected shape \(6, 6\) but found \(4, 4\)"),
        (lambda: kyp_outer(np.eye(4), np.eye(2), np.ones((3, 1))), DimensionError,
         r"B: expected shape \(2, 1\) but found \(3, 1\)"),
        (lambda: kyp_outer(np.eye(4), np.ones((2, 3))), DimensionError,
         r"A must be a square 2-D array, but found shape \(2, 3\)"),
        (lambda: kyp_outer(np.eye(4), np.eye(2), np.ones(2)), DimensionError,
         r"B must be a 2-D array, but found shape \(2,\)"),
        (lambda: kyp_matrix(np.eye(3), np.ones((3, 1)), np.ones((1, 3)), np.zeros((1, 1)),
                            np.eye(2), [], 1.0), DimensionError,
         r"P \(real part\): expected shape \(3, 3\) but found \(2, 2\)"),
        (lambda: supply_parts(np.ones((2, 3)), np.ones((1, 1))), DimensionError,
         r"D: expected shape \(2, 1\) but found \(1, 1\)"),
        (lambda: kyp_matrix(np.eye(2), np.ones((2, 1)), np.ones((1, 3)), np.zeros((1, 1)),
                            np.eye(2), [], 1.0), DimensionError,
         r"C: expected shape \(1, 2\) but found \(1, 3\)"),
        (lambda: kyp_matrix(np.eye(2), np.ones((2, 1)), np.ones((1, 2)), np.zeros((1, 2)),
                            np.eye(2), [], 1.0), DimensionError,
         r"D: expected shape \(1, 1\) but found \(1, 2\)"),
        (lambda: theorem1_matrices(LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]]), Band.lf(1.0),
                                   Band.hf(2.0), [[1.0]], [[1.0]], [[1.0]], [[1.0]], 1.0,
                                   backend=np), ValueError, r"backend must be one of"),
    ],
)
def test_bad_builder_inputs(call, exc, match):
    with pytest.raises(exc, match=match):
        call()
