"""Tests of fdsc.paper.shared.examples (an example's controllers run side by side)."""

import numpy as np
import pytest

import fdsc
from fdsc.paper.shared.examples import OPEN_LOOP, Example


@pytest.fixture(scope="module")
def example():
    # a damped oscillator with two synthesized gains; one FDSC design with a dwell-time law
    plant = fdsc.Plant([[0.0, 1.0], [-4.0, -0.4]], [[0.0], [1.0]], [[0.0], [1.0]],
                       [[1.0, 0.0], [0.0, 0.0]], [[0.0], [0.0]], [[0.0], [0.1]])
    bands = {"LF": fdsc.Band.lf(0.5), "HF": fdsc.Band.hf(5.0)}
    ctrl = fdsc.FDSC.synthesize(plant, [bands["LF"], bands["HF"]], in_band=1)
    gains = {OPEN_LOOP: np.zeros((1, 2)), "LF": ctrl.gains[0], "HF": ctrl.gains[1]}
    return Example("toy", plant, bands, gains,
                   {"FDSC": (ctrl, fdsc.PRINTED), "FDSC (dwell)": (ctrl, fdsc.SwitchRule.dwell_time(0.05))},
                   (0.1, 0.5), (5.0, 20.0), 4.0, 1e-3)


def test_compare_puts_each_controller_in_its_slot(example):
    # reference: every run alone with the full-trajectory simulator (another code path)
    ds = [fdsc.Sinusoids([1.0, 0.5], [0.3, 12.0]), fdsc.Sinusoids([0.2], [8.0], [1.0])]
    comp = example.compare(ds, [4.0, 2.0])
    for i, d in enumerate(ds):
        t = fdsc.time_grid([4.0, 2.0][i], 1e-3)
        for name in example.fixed_names:
            ref = fdsc.simulate(example.closed_loop(name), d, t).energy()
            np.testing.assert_allclose(comp.energy[name][i], ref, rtol=1e-9)
        ctrl, rule = example.designs["FDSC (dwell)"]
        run = ctrl.simulate(d, t, rule=rule)
        np.testing.assert_allclose(comp.energy["FDSC (dwell)"][i], run.energy(), rtol=1e-9)
        assert comp.switches["FDSC (dwell)"][i] == run.switch_times.size
        np.testing.assert_allclose(comp.input_energy[i], run.input_energy(), rtol=1e-9)
    assert set(comp.switches) == {"FDSC", "FDSC (dwell)"}
    assert comp.switches["FDSC (dwell)"].sum() > 0   # the switched runs did switch


def test_ratio_and_best(example):
    comp = example.compare([fdsc.Sinusoids([1.0], [0.3])], names=(OPEN_LOOP, "LF", "HF"))
    names, energy = comp.best((OPEN_LOOP, "LF", "HF"))
    k = int(np.argmin([comp.energy[n][0] for n in (OPEN_LOOP, "LF", "HF")]))
    assert names[0] == (OPEN_LOOP, "LF", "HF")[k] and energy[0] == comp.energy[names[0]][0]
    np.testing.assert_allclose(comp.ratio()["LF"], comp.energy["LF"] / comp.input_energy, rtol=0)


@pytest.mark.parametrize(("change", "match"), [
    ({"bands": {"LF": fdsc.Band.lf(0.5)}}, "bands must be"),
    ({"lf_tones": (0.1, 0.9)}, "lf_tones must be"),
    ({"hf_tones": (0.0, 20.0)}, "hf_tones must be"),
    ({"hf_tones": (20.0, 5.0)}, "hf_tones must be"),
])
def test_bad_examples(example, change, match):
    fields = {k: getattr(example, k) for k in ("name", "plant", "bands", "gains", "designs", "lf_tones",
                                                "hf_tones", "horizon", "dt")}
    with pytest.raises(ValueError, match=match):
        Example(**{**fields, **change})


def test_bad_names_and_horizons(example):
    with pytest.raises(ValueError, match="repeat between gains and designs"):
        Example(example.name, example.plant, example.bands, {**example.gains, "FDSC": np.zeros((1, 2))},
                example.designs, example.lf_tones, example.hf_tones, 1.0, 1e-3)
    with pytest.raises(ValueError, match="names must be controllers"):
        example.cases(fdsc.Sinusoids([1.0], [1.0]), names=("nope",))
    with pytest.raises(ValueError, match="one entry per disturbance"):
        example.compare([fdsc.Sinusoids([1.0], [1.0])], [1.0, 2.0])


def test_segment_ideal_carries_the_state_over_the_breaks(example):
    # reference: one uninterrupted run of the same gain (the pieces are one signal cut in two,
    # so cutting must change nothing but the quadrature: each piece has an even number of steps)
    tones = fdsc.Sinusoids([1.0, 0.3], [8.0, 15.0], [0.2, 1.0])
    cut = fdsc.Piecewise([0.0, 1.0, 3.0], [tones, tones])
    ref = fdsc.simulate(example.closed_loop("HF"), cut, fdsc.time_grid(3.0, 1e-3)).energy()
    np.testing.assert_allclose(example.segment_ideal(cut, 3.0, ("LF", "HF")), ref, rtol=1e-9)
    # an LF piece then an HF piece: each gain on its own piece
    slow = fdsc.Sinusoids([1.0], [0.2])
    both = fdsc.Piecewise([0.0, 2.0, 4.0], [slow, tones])
    e = example.segment_ideal(both, 4.0, ("LF", "HF"))
    first = fdsc.simulate_stream(example.closed_loop("LF"), slow, 2.0, 1e-3)
    shifted = fdsc.Sinusoids(tones.amplitudes, tones.frequencies, tones.phases + 2.0 * tones.frequencies)
    second = fdsc.simulate_stream(example.closed_loop("HF"), shifted, 2.0, 1e-3, x0=first.x_final)
    np.testing.assert_allclose(e, first.energy + second.energy, rtol=1e-12)


def test_segment_ideal_bad_inputs(example):
    with pytest.raises(TypeError, match="d must be an fdsc.Piecewise"):
        example.segment_ideal(fdsc.Sinusoids([1.0], [1.0]), 1.0, ("LF", "HF"))
    d = fdsc.Piecewise([0.0, 0.0105, 1.0], [fdsc.Sinusoids([1.0], [1.0])] * 2)
    with pytest.raises(ValueError, match="modes must name fixed gains"):
        example.segment_ideal(d, 1.0, ("LF", "FDSC"))
    with pytest.raises(ValueError, match="must begin and end on the grid"):
        example.segment_ideal(d, 1.0, ("LF", "HF"))
