"""Tests of the chapter module fdsc.paper.repairs.three_mode."""

import numpy as np
import pytest

from fdsc.paper.repairs import three_mode as tm
from fdsc.paper.shared.prose import num


def test_score_weights_printed_mf_negative_second_order_in_band():
    sw = tm.score_weights()
    # printed MF weight −(ω² + ϖ₁ϖ₂) ≤ −10 (fdsc.Band.real_weight): never positive
    assert sw.printed_mf_max < -9.99
    lo, hi = sw.mf_positive_range
    assert 1.0 < lo < 1.01 and 9.9 < hi < 10.0


def test_certificates():
    c = tm.three_mode_certificates()
    # Remark 4 design: in-band γ_MF is K_f2's MF peak (0.4028, Lemma 1 of the mode alone) up to
    # the LMI's conservatism; out-of-band γ's at γ_tol
    assert c.mf_peak <= c.design.gammas[1] < 1.01 * c.mf_peak
    np.testing.assert_allclose(c.design.gammas[[0, 2]], tm.GAMMA_TOL, rtol=1e-6)
    for cert in (c.design, c.equal_q, c.equal_q_scaled):
        assert all(v < 0 for v in cert.max_eigs.values()) and cert.sweep_max < 0


@pytest.fixture(scope="module")
def short_table():
    return tm.comparison(horizon=15.0)


def test_comparison_shape_and_printed_mf_never_wins(short_table):
    t = short_table
    assert t.ratio.shape == (len(t.disturbances), len(t.controllers))
    np.testing.assert_allclose(t.time_share.sum(axis=2)[:, [0, 1, 2, 3, 4, 6, 7, 8]], 1.0,
                               atol=1e-12)
    k = t.controllers.index("FDSC-3 (printed scores, Q = I)")
    # the printed MF score is negative at every instant: MF wins only if the others are lower
    assert t.time_share[:, k, 1].max() < 0.05


def test_three_mode_beats_two_mode_on_mf_tones(short_table):
    t = short_table
    for w in tm.MF_TONES:
        d = f"MF tone {w:g} rad/s"
        three = t.value(d, "FDSC-3 (2nd order, Q = I)")
        assert three < 0.5 * t.value(d, "FDSC-2 (our Q's)")
        assert three < 0.5 * t.value(d, "FDSC-2 (paper Q's)")


def test_xddot_cost_grows_with_lag():
    c = tm.xddot_cost(horizon=3.0, steps=(1, 10))
    assert c.disagreement[0] < c.disagreement[1]


def test_record_entry():
    part = tm.record_part()
    (e,) = part.entries
    assert e["id"] == "three_mode" and e["verdict"] == "new" and e["paper"] is None


def test_prose_and_table_are_text_with_reader_names(short_table):
    t = short_table
    p = t.prose()
    assert all(isinstance(v, str) for v in p.values())
    # the worst MF ratio of the three-mode law, as fdsc.paper.shared.prose prints it
    worst = max(t.value(f"MF tone {w:g} rad/s", "FDSC-3 (2nd order, Q = I)") for w in tm.MF_TONES)
    assert p["mf3_max"] == num(worst)
    rows = t.table()
    assert len(rows) == len(t.controllers) and all(isinstance(v, str) for r in rows for v in r.values())
    names = [r["controller"] for r in rows]
    assert "FDSC-2 (printed Q)" in names and not any("Q's" in n for n in names)
    assert tm.display_name("LF -> MF -> HF") == "LF → MF → HF"
    sw = tm.score_weights([0.5, 0.99, 1.01, 5.0, 9.99, 10.01]).prose()
    # printed MF weight −(ω² + ϖ₁ϖ₂) at its largest, ω = 0.5: −10.25, to 3 significant digits
    assert sw == {"printed_mf_max": "−10.2", "mf_lo": "1.01", "mf_hi": "9.99"}
    fd = tm.xddot_cost(horizon=3.0, steps=(1, 10)).prose()
    assert set(fd) == {"fd_1", "fd_10", "fd_ms_1", "fd_ms_10"} and fd["fd_ms_10"] == "10"


def test_record_note_has_no_code_formatting():
    (e,) = tm.record_part().entries
    assert "Psi" not in e["note"] and "x''" not in e["note"] and "gammas" not in e["note"]
