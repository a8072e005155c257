import json

import numpy as np
import pytest

from fdsc import simulate_stream
from fdsc.frequency import steady_state_gain
from fdsc.paper.reproduced.nonstationary import (
    P2_WINDOWS,
    SWEEP_NAMES,
    SweepStudy,
    crossover,
    crossover_in,
    extended_piecewise,
    mixed_sweep,
    p1_global,
    p2_localized,
    piecewise_sweep,
    sweep_cases,
)
from fdsc.paper.shared.data import aircraft, mixed_disturbance, paper_gains, piecewise_disturbance

# a coarser step than the book's keeps these runs to a few seconds; the logic is the same
DT = 2e-3


@pytest.fixture(scope="module")
def mixed():
    return mixed_sweep(5, dt=DT)


@pytest.fixture(scope="module")
def pw():
    return piecewise_sweep(2, dt=DT)


def test_fixed_gain_energies_are_quadratic_in_rho_p(mixed):
    # z = z_h + ρ z_l for a fixed gain, so ∫zᵀz = a + 2bρ + cρ²: a parabola through three points of
    # the sweep predicts the other two (this fails if a case is assigned the wrong ρ_p or name)
    rho = mixed.param
    for name in ("PassC-EF", "PassC-LF", "PassC-HF"):
        coef = np.polyfit(rho[[0, 2, 4]], mixed.energy[name][[0, 2, 4]], 2)
        np.testing.assert_allclose(np.polyval(coef, rho[[1, 3]]), mixed.energy[name][[1, 3]], rtol=1e-9)
    # the input energy: 500 s of six unit-or-ρ tones, mean power (3 + 3ρ²)/2, cross terms O(1)
    np.testing.assert_allclose(mixed.input_energy, 750 * (1 + rho**2), rtol=5e-3)


def test_sweep_entries_match_single_runs(mixed, pw):
    i = 3
    case = sweep_cases(mixed_disturbance(mixed.param[i]), 500.0, DT, names=("FDSC",))[0]
    one = simulate_stream(case.modes, case.d, case.horizon, case.dt, law_bands=case.law_bands,
                          law_Q=case.law_Q)
    assert one.energy == pytest.approx(mixed.energy["FDSC"][i], rel=1e-12)
    assert one.switches == mixed.switches["FDSC"][i]
    cl = aircraft().closed_loop(paper_gains()["K_f1"])
    r = simulate_stream(cl, piecewise_disturbance(500.0, 0.5, 0.1), 750 + 500, DT, cumulative_every=0.1)
    assert r.energy == pytest.approx(pw.energy["PassC-LF"][1], rel=1e-12)
    # the worst window of (P.2), recomputed from the stream's own windows
    for w in P2_WINDOWS:
        t0, ez, ed = r.window_energies(w)
        j = np.argmax(ez / ed)
        assert pw.worst_window[w]["PassC-LF"][1] == pytest.approx(ez[j] / ed[j], rel=1e-12)
        assert pw.worst_window_start[w]["PassC-LF"][1] == pytest.approx(t0[j])
    # the record's figure data: lengths and unscaled energies
    fig = pw.to_figure()
    assert fig["paper_figure"] == 8 and fig["rho_t"] == [0.0, 0.5] and fig["horizon"] == [1000.0, 1250.0]
    assert fig["energy"]["PassC-HF"] == pw.energy["PassC-HF"].tolist() and fig["passc_hf_scale"] == 0.01
    json.dumps(fig, allow_nan=False)


def test_crossover_is_bisected_by_full_runs(mixed):
    c = crossover(mixed, "PassC-LF", tol=0.02)
    assert c.sign_changes == 1 and c.width <= 0.02
    lo, hi = c.bracket
    assert mixed.param[0] <= lo < hi <= mixed.param[-1]
    # every evaluation moved the end of the bracket that its sign says
    for p, e_fdsc, e_lf in c.evaluations:
        assert (p <= lo) if e_fdsc < e_lf else (p >= hi)
    assert c.evaluations[-1][0] in (lo, hi)
    assert crossover_in(mixed, "PassC-LF") == pytest.approx(mixed.param[np.argmax(c.gap >= 0)])
    # PassC-HF is never beaten by... FDSC always beats it: no sign change, no bracket
    never = crossover(mixed, "PassC-HF")
    assert never.bracket is None and never.value is None and never.sign_changes == 0


@pytest.mark.parametrize("kwargs, match", [
    ({"rival": "FDSC"}, "rival must be one of"),
    ({"rival": "PassC-LF", "tol": 0.0}, "tol must be"),
    ({"rival": "PassC-LF", "runs": "mixed"}, "runs must be a SweepRuns"),
])
def test_crossover_bad_inputs(mixed, kwargs, match):
    kwargs = {"runs": mixed, **kwargs}
    with pytest.raises(ValueError, match=match):
        crossover(kwargs.pop("runs"), **kwargs)


def test_extended_piecewise_grid_is_checked():
    with pytest.raises(ValueError, match="grid must be at least two increasing values"):
        extended_piecewise((1.0, 0.5))


def test_p1_against_closed_form(mixed):
    p1 = p1_global(mixed)
    assert [r.case for r in p1.rows][:2] == ["LF, paper eq. (56)", "HF, paper eq. (57)"]
    # the second half of a 500 s run has shed PassC-HF's transient (pole −0.0165: e^{−4.1} ≈ 2 %)
    for r in p1.rows:
        assert r.tail_ratio["PassC-HF"] == pytest.approx(r.passc_hf_limit, rel=0.03)
    hf_loop = aircraft().closed_loop(paper_gains()["K_f3"])
    d = mixed_disturbance(0.5)
    assert p1.rows[-1].passc_hf_limit == pytest.approx(
        steady_state_gain(hf_loop, d.frequencies, d.amplitudes) ** 2, rel=1e-12)
    assert p1.rows[-1].alpha_in == pytest.approx(1 / 1.25)
    assert p1.gamma_in == pytest.approx(1.6051, abs=1e-4)   # the HF band peak of the printed K_f3
    table = p1.table()
    assert set(SWEEP_NAMES) <= set(table[0]) and len(table) == len(p1.rows)
    with pytest.raises(ValueError, match="mixed must be the SweepRuns"):
        p1_global("mixed")


def test_p2_meets_and_table(pw):
    p2 = p2_localized(pw, gamma_tol=5.0)
    for w in P2_WINDOWS:
        assert p2.worst[w]["PassC-LF"] == pytest.approx(np.sqrt(pw.worst_window[w]["PassC-LF"].max()))
        assert p2.meets("PassC-LF")[w] == (p2.worst[w]["PassC-LF"] < 5.0)
    assert not any(p2.meets("PassC-HF").values())       # PassC-HF amplifies the LF segment by ~1e3
    rows = {r["controller"]: r for r in p2.table()}
    assert rows["PassC-HF"]["meets γ_tol for"] == "none"
    with pytest.raises(ValueError, match="gamma_tol must be"):
        p2_localized(pw, gamma_tol=-1)
    with pytest.raises(ValueError, match="piecewise must be the SweepRuns"):
        p2_localized(extended_piecewise((0.5, 1.0), dt=DT))


def test_sweep_study_record_part(mixed, pw):
    ext = extended_piecewise((0.5, 2.0), dt=DT)
    cross = {r: crossover(mixed, r, tol=0.05) for r in ("PassC-LF", "PassC-EF")}
    ext_cross = {r: crossover(ext, r, tol=0.1) for r in ("PassC-LF", "PassC-EF")}
    p1, p2 = p1_global(mixed), p2_localized(pw)
    study = SweepStudy(mixed, pw, cross, ext, ext_cross, p1, p2, mixed, pw, cross, p1, p2)
    part = study.to_record()
    ids = [e["id"] for e in part.entries]
    assert ids == ["mixed_crossover", "piecewise_crossover", "sweep_step_halving", "p1_global",
                   "p2_localized"]
    assert set(part.figures) == {"mixed_sweep", "piecewise_sweep"}
    fig7 = part.figures["mixed_sweep"]
    assert fig7["crossover"]["PassC-LF"] == cross["PassC-LF"].value and fig7["crossover"]["paper"] == 0.2
    # the same runs twice: nothing changes with "dt/2"
    assert all(v == 0 for f in study.max_rel_change().values() for v in f.values())
    # FDSC beats PassC-LF over the whole printed ρ_t range, loses beyond it (ρ_t = 2)
    by_id = {e["id"]: e for e in part.entries}
    assert by_id["piecewise_crossover"]["recomputed"]["in_paper_range"]["PassC-LF"] is None
    assert 0.5 < by_id["piecewise_crossover"]["recomputed"]["extended"]["PassC-LF"] < 2.0
    json.dumps({"entries": list(part.entries), "figures": part.figures}, allow_nan=False)


def test_scaled_crossing_solves_the_drawn_curves(mixed):
    from fdsc import simulate_batch
    from fdsc.paper.reproduced.nonstationary import scaled_crossing

    rho = scaled_crossing(mixed, 1 / 5000)
    assert 0.15 < rho < 0.25
    # at the root, full runs of the two fixed gains give PassC-HF / 5000 = PassC-LF
    cases = sweep_cases(mixed_disturbance(rho), 500.0, DT, names=("PassC-HF", "PassC-LF"))
    e = simulate_batch(cases).energy
    assert e[0] / 5000 == pytest.approx(e[1], rel=1e-9)
    assert scaled_crossing(mixed, 1e-9) is None          # scaled far down: never crosses
    with pytest.raises(ValueError, match="runs must be a mixed sweep"):
        scaled_crossing(piecewise_sweep(2, dt=DT), 1 / 5000)


def test_comparator_check_prose_counts_and_factors():
    # made-up energies: FDSC better than the best fixed controller at one point of three
    from fdsc.paper.reproduced.nonstationary import ComparatorCheck

    check = ComparatorCheck("mixed", np.array([0.0, 0.1, 0.2]), ("open loop", "open loop", "PassC-LF"),
                            np.array([1.0, 2.0, 4.0]), np.array([0.5, 3.0, 8.0]),
                            np.array([1.0, 2.0, 9.0]))
    text = check.prose()
    assert check.n_fdsc_better == 1
    assert text["n_better"] == "1" and text["n"] == "3"
    assert text["winners"] == "open loop at 2, PassC-LF at 1"
    assert text["ratio"] == "×0.500 to ×2.00"
    assert text["open_loop_better"] == "1"
