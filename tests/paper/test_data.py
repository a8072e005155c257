import numpy as np
import pytest
from numpy.testing import assert_allclose

from fdsc.paper.shared.data import (
    aircraft,
    hf_disturbance,
    lf_disturbance,
    paper_bands,
    paper_data,
    paper_gains,
)


def test_aircraft_matches_printed_matrices():
    p = aircraft()
    # reference: Sec. VI, A_long and B^u_long as printed
    assert_allclose(p.A, [[-1.175, 0.9871], [-8.458, -0.8776]], atol=0)
    assert_allclose(p.B2, [[-0.194, -0.03593], [-19.29, -3.803]], atol=0)
    assert p.B1.shape == (2, 1) and p.C.shape == (3, 2) and p.D2.shape == (3, 2)


def test_every_data_entry_has_a_source():
    for name in ("aircraft", "controllers", "switching", "simulation"):
        for key, entry in paper_data(name).items():
            if key.startswith("_"):
                continue
            assert "source" in entry and entry["source"], (name, key)


def test_printed_gains_stabilize():
    p = aircraft()
    for name, K in paper_gains().items():
        assert p.closed_loop(K).is_hurwitz(), name


def test_paper_bands():
    b = paper_bands()
    assert (b["LF"].upper, b["MF"].lower, b["MF"].upper, b["HF"].lower) == (1.0, 1.0, 10.0, 10.0)


def test_missing_data_file():
    with pytest.raises(ValueError, match="name must be one of .*aircraft"):
        paper_data("nonexistent")


def test_paper_disturbances():
    t = np.array([0.3, 1.7])
    assert_allclose(lf_disturbance()(t), np.sin(0.1 * t) + np.sin(0.2 * t) + np.sin(0.3 * t))
    assert_allclose(hf_disturbance()(t), np.sin(100 * t) + np.sin(200 * t) + np.sin(300 * t))


def test_paper_fdsc_is_built_once_per_q_and_cannot_be_changed():
    from fdsc.paper.shared.data import paper_fdsc, paper_modes

    printed = paper_fdsc("paper")
    assert paper_fdsc("paper") is printed
    # the same matrices given explicitly: one design, whatever the container
    given = paper_fdsc([np.array(q) for q in paper_modes()["Q"]])
    assert paper_fdsc(tuple(np.array(q).tolist() for q in paper_modes()["Q"])) is given
    assert given is not printed
    assert_allclose(given.certificate.gammas, printed.certificate.gammas, rtol=1e-12)
    with pytest.raises(ValueError, match="read-only"):
        printed.gains[0][0, 0] = 1.0
    with pytest.raises(ValueError, match="read-only"):
        printed.certificate.Q[0][0, 0] = 1.0
    # another Q gives another design; an invalid Q still meets the design's own check
    other = paper_fdsc([2.0 * np.array(q) for q in paper_modes()["Q"]])
    assert other is not given
    with pytest.raises(ValueError, match="Q must be one of"):
        paper_fdsc("printed")
