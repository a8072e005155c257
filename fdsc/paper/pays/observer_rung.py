"""The ladder with ŵ built by a disturbance observer from noisy measurements of x (no ẋ measured).

Every controller reads the state through a sensor, ``x_m = x + v``, v white Gaussian noise on each
state, band-limited to the Nyquist frequency Ω of the predictive law's sampler, at a stated
signal-to-noise ratio per state (:data:`LEVELS`: the state's mean power on the class, in the loop
of the best fixed controller with the exact estimate, over the noise's variance in that band).
Whatever reads ŵ reads it from one **disturbance observer**, part of the controller and the same for
every rung: the steady-state Kalman–Bucy filter of the plant augmented with d as a random walk
of intensity q (:func:`kalman_bucy`), run in continuous time as the laws' feedforward is, its
input u known to it (the controller computes u). Its q is chosen, at each level, for the least
expected cost of the best fixed controller with the exact estimate when it reads ŵ through the
observer (:func:`choose_intensity`; a closed form, no draws).

Because the observer knows u, its error does not depend on u: for any controller, in closed
loop, ``ŵ = F(s) d + N(s) v`` with F and N fixed (:func:`observer_filters`; ``F(0) = 1``). So:

* a **fixed controller** reading x and ŵ becomes, with the observer, one controller reading x_m
  alone (:func:`with_observer`), whose energy on a draw is exact on d plus the noise's expected
  energy (the horizon times its loop's power from v, :func:`sensor_noise_power`: the cross
  term has mean zero); a controller reading x alone reads x_m;
* the **predictive law with a confidence check** keeps its gain and base, its base now reading
  ``F(s) d`` (:func:`filtered_base`: the same loop on d as the fixed controller with the
  observer), its identifications reading samples of ``F(s) d + N(s) v`` (the noise drawn for
  each identification's window from the stationary law of the samples of ``N(s) v``, the
  sensor's noise band-limited to the sampler's Nyquist frequency as for the fixed controllers,
  seeded), and it divides each identified tone by ``F(jω)`` (it knows its observer) before
  correcting; plus the noise's
  expected energy through its gain and base, as for the fixed controller.

At each level: the best fixed controller, chosen by its expected power among the stored study's
controllers (those reading ŵ through the observer; not redesigned for it), the best reading x
alone, the law (its setting chosen on training draws among the windows of
:data:`fdsc.paper.pays.information.WINDOWS` and not predicting), and the stored non-causal limit
(which reads d exactly), on the first test draws of the stored study.

The observer and the law that reads through it are in :mod:`fdsc.paper.pays.observer_loop` (their
names are re-exported here).

``python -m fdsc observer-rung [--workers W] [--replace]`` runs it and writes
:data:`OBSERVER_FILE`, which the ladder chapter reads.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np

from fdsc._closed_energy import closed_form_energies
from fdsc.controller import Controller
from fdsc.optimal_lti import expected_power
from fdsc.paper.pays.disturbance_law_draws import _example, seeded_draw, segment_class
from fdsc.paper.pays.information import CONFIDENCE, FALLBACK, N_TEST, N_TRAIN, UPDATE, WINDOWS
from fdsc.paper.pays.ladder import MAX_TONES, law_band
from fdsc.paper.pays.observer_loop import (
    ObservedLaw,
    filtered_base,
    kalman_bucy,
    observer_filters,
    sensor_loop,
    sensor_noise_power,
    with_observer,
)
from fdsc.paper.pays.stored_study import map_draws, stored_fixed_set
from fdsc.paper.pays.study_command import load_stored, study_main
from fdsc.paper.shared.stats import bootstrap_median
from fdsc.plant import LTISystem

__all__ = ["LEVELS", "INTENSITIES", "INTENSITY_TOL", "OBSERVER_FILE", "kalman_bucy", "observer_filters",
           "with_observer",
           "filtered_base", "sensor_loop", "sensor_noise_power", "sensor_densities", "choose_intensity",
           "ObservedLaw", "level_design", "law_energy", "fixed_energy", "observer_study", "summary",
           "load_observer", "main"]

#: Sensor signal-to-noise ratios per state (dB).
LEVELS = (40.0, 20.0, 0.0)
#: The observer's random-walk intensities tried, times the class's power (1/s).
INTENSITIES = tuple(10.0 ** k for k in range(-2, 9))
#: The observer's intensity is the least of :data:`INTENSITIES` whose expected cost is within this
#: share of the least (:func:`choose_intensity`).
INTENSITY_TOL = 1e-3
#: The stored result, which the book reads.
OBSERVER_FILE = Path("book") / "data" / "observer_rung.json"
EXAMPLES = ("aircraft", "generic")


def sensor_densities(example: str, level: float, reference: Controller) -> np.ndarray:
    """The sensor's noise densities at a level: each state's mean power on the class in the loop of
    ``reference`` (exact estimate) over ``10^(level/10)``, spread flat over the band ``|ω| ≤ Ω``
    of the law's sampler (variance ``S Ω / π``).

    Parameters
    ----------
    example : {"aircraft", "generic"}
    level : float
        dB.
    reference : Controller

    Returns
    -------
    (n,) ndarray
    """
    plant, cls = _example(example).plant, segment_class(example)
    loop = plant.closed_loop(reference)
    n = plant.n_states
    _band, step = law_band(example)
    nyq = math.pi / step
    powers = [expected_power(LTISystem(loop.A, loop.B, np.eye(loop.A.shape[0])[[i]], np.zeros((1, 1))), cls)
              for i in range(n)]
    return np.array(powers) / 10.0 ** (level / 10.0) / (nyq / math.pi)


def _expected(example, ctrl, densities):
    """The expected power of a controller reading x alone with the sensor's noise: on the class,
    plus the noise's."""
    plant, cls = _example(example).plant, segment_class(example)
    _band, step = law_band(example)
    return (expected_power(plant.closed_loop(ctrl), cls)
            + sensor_noise_power(plant, ctrl, densities, math.pi / step))


def choose_intensity(example: str, reference: Controller, densities) -> tuple:
    """The observer's intensity q of :data:`INTENSITIES` (times the class's power): the least whose
    expected power for ``reference`` reading ŵ through it is within :data:`INTENSITY_TOL` of the
    least.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    reference : Controller
        Reads x and ŵ.
    densities : (n,) array_like

    Returns
    -------
    (float, dict)
        q, and ``{q: expected power}`` over the grid.
    """
    plant, cls = _example(example).plant, segment_class(example)
    scores = {}
    for r in INTENSITIES:
        q = r * cls.power
        Ae, L, _G, _P = kalman_bucy(plant, densities, q)
        scores[q] = _expected(example, with_observer(reference, plant, Ae, L), densities)
    best = min(scores.values())
    # the least q whose cost is within INTENSITY_TOL of the least: where the cost is flat in q, the
    # slowest observer (the least noise bandwidth), not the one rounding happens to favour
    return min(q for q, v in scores.items() if v <= best * (1 + INTENSITY_TOL)), scores


def level_design(example: str, level: float, full: dict) -> dict:
    """The observer and the fixed controllers at one sensor noise level (module docstring).

    Parameters
    ----------
    example : {"aircraft", "generic"}
    level : float
        dB.
    full : dict
        The stored study.

    Returns
    -------
    dict
        ``densities``, ``nyquist``, ``q`` and ``q_scores`` (the observer), ``powers`` and
        ``noise`` ({stored name: expected power with the sensor's noise, and its noise part}),
        ``best`` (the controller reading ŵ, through the observer, of least expected power),
        ``best_x`` (the one reading x alone), ``reference`` (the better of the two) and ``base``
        (the stored study's best fixed controller (x, ŵ), the law's base).
    """
    plant = _example(example).plant
    fs = stored_fixed_set(full, example)
    base = fs.controllers[fs.chosen]
    S = sensor_densities(example, level, base)
    q, q_scores = choose_intensity(example, base, S)
    Ae, L, _G, _P = kalman_bucy(plant, S, q)
    _band, step = law_band(example)
    nyq = math.pi / step
    powers, noise = {}, {}
    cls = segment_class(example)
    for name in fs.names:
        c = with_observer(fs.controllers[name], plant, Ae, L)
        loop = plant.closed_loop(c)
        if not loop.is_hurwitz():
            continue                                  # unstable with the observer: not a candidate
        noise[name] = sensor_noise_power(plant, c, S, nyq)
        powers[name] = expected_power(loop, cls) + noise[name]
    reading = [k for k in powers if fs.controllers[k].reads_estimate]
    alone = [k for k in powers if not fs.controllers[k].reads_estimate]
    best, best_x = min(reading, key=powers.get), min(alone, key=powers.get)
    return {"densities": S.tolist(), "nyquist": nyq, "q": q,
            "q_scores": {f"{k:g}": v for k, v in q_scores.items()},
            "powers": powers, "noise": noise, "best": best, "best_x": best_x,
            "reference": best if powers[best] <= powers[best_x] else best_x, "base": fs.chosen}


def _observer(example, design):
    plant = _example(example).plant
    Ae, L, G, _P = kalman_bucy(plant, design["densities"], design["q"])
    return plant, Ae, L, G


def law_energy(example: str, index: int, seed: int, design: dict, window: float, base: Controller) -> tuple:
    """The law with the observer on one draw: its energy with the expected energy of the sensor's
    noise through its gain and base, and the share of its corrections applied.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    index, seed : int
    design : dict
        :func:`level_design`'s.
    window : float
    base : Controller
        The stored best fixed controller (x, ŵ) (``design["base"]``).

    Returns
    -------
    (float, float)
    """
    plant, Ae, L, G = _observer(example, design)
    _ex, dr = seeded_draw(example, index, seed)
    band, step = law_band(example)
    law = ObservedLaw(plant, band, observer=(Ae, L, G), densities=design["densities"], base=base,
                      window=window,
                      step=step, update=UPDATE, max_tones=MAX_TONES, confidence=CONFIDENCE)
    run = law.run(dr.d, dr.horizon, seed=index)
    alphas = np.array([a for _t, a in law.confidences], dtype=float)
    applied = float(np.mean(np.nan_to_num(alphas, nan=-1.0) >= CONFIDENCE)) if alphas.size else 0.0
    return float(run.energy + dr.horizon * design["noise"][design["base"]]), applied


def fixed_energy(example: str, index: int, seed: int, design: dict, ctrl: Controller, name: str) -> float:
    """A fixed controller's energy on one draw with the observer and the sensor's noise: exact on d,
    plus the noise's expected energy.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    index, seed : int
    design : dict
    ctrl : Controller
        The stored controller (before its observer).
    name : str
        Its stored name (for its noise power in ``design``).

    Returns
    -------
    float
    """
    plant, Ae, L, _G = _observer(example, design)
    _ex, dr = seeded_draw(example, index, seed)
    c = with_observer(ctrl, plant, Ae, L)
    clean = float(closed_form_energies(plant.closed_loop(c), [dr.d], [dr.horizon])[0][0])
    return clean + dr.horizon * design["noise"][name]


def observer_study(full: dict, *, n_test: int = N_TEST, n_train: int = N_TRAIN, executor=None) -> dict:
    """The study (module docstring) on the stored study ``full``.

    Parameters
    ----------
    full : dict
        The stored study (:func:`fdsc.paper.pays.stored_study.load_full`).
    n_test, n_train : int, optional
        Test draws (the stored study's first) and training draws (its first draws).
    executor : optional

    Returns
    -------
    dict
    """
    from fdsc.paper.shared.cache import study_fingerprint
    from fdsc.paper.shared.environment import build_commit

    if n_test < 2 or n_train < 1:
        raise ValueError(f"n_test ≥ 2 and n_train ≥ 1 are required, but found {n_test!r} and {n_train!r}")
    seed = full["seed"]
    out = {"commit": build_commit(), "fingerprint": study_fingerprint("fdsc.paper.pays.observer_rung"),
           "stored_study": {"commit": full["commit"], "fingerprint": full["fingerprint"]},
           "seed": seed, "levels": [f"{v:g} dB" for v in LEVELS], "n_test": n_test, "n_train": n_train,
           "windows": list(WINDOWS), "fallback": FALLBACK, "confidence": CONFIDENCE, "update": UPDATE,
           "intensities": list(INTENSITIES)}
    keys = [(ex, lv) for ex in EXAMPLES for lv in LEVELS]
    designs = dict(zip(keys, map_draws(level_design, [(ex, lv, full) for ex, lv in keys], executor),
                       strict=True))
    fsets = {ex: stored_fixed_set(full, ex) for ex in EXAMPLES}
    bases = {ex: fsets[ex].controllers[fsets[ex].chosen] for ex in EXAMPLES}
    # training: every window, and not predicting (the reference at the level), on the first draws
    targs = [(ex, i, seed, designs[ex, lv], w, bases[ex])
             for ex, lv in keys for w in WINDOWS for i in range(n_train)]
    score = {}
    for a, (e, _ap) in zip(targs, map_draws(law_energy, targs, executor), strict=True):
        key = next(k for k in keys if designs[k] is a[3])
        score.setdefault((*key, a[4]), []).append(math.log(e))
    fargs = [(ex, i, seed, designs[ex, lv], fsets[ex].controllers[designs[ex, lv]["reference"]],
              designs[ex, lv]["reference"]) for ex, lv in keys for i in range(n_train)]
    for (ex, lv, _i), e in zip([(ex, lv, i) for ex, lv in keys for i in range(n_train)],
                               map_draws(fixed_energy, fargs, executor), strict=True):
        score.setdefault((ex, lv, FALLBACK), []).append(math.log(e))
    settings = (*WINDOWS, FALLBACK)
    chosen = {k: min(settings, key=lambda w, k=k: float(np.mean(score[(*k, w)]))) for k in keys}
    idx = {ex: full[ex]["test_indices"][:n_test] for ex in EXAMPLES}
    largs = [(ex, i, seed, designs[ex, lv], chosen[ex, lv], bases[ex]) for ex, lv in keys
             if chosen[ex, lv] != FALLBACK for i in idx[ex]]
    laws = {}
    for a, r in zip(largs, map_draws(law_energy, largs, executor), strict=True):
        key = next(k for k in keys if designs[k] is a[3])
        laws[(*key, a[1])] = r
    rungs = ("best", "best_x")
    xargs = [(ex, i, seed, designs[ex, lv], fsets[ex].controllers[designs[ex, lv][r]], designs[ex, lv][r])
             for ex, lv in keys for r in rungs for i in idx[ex]]
    xkeys = [(ex, lv, r, i) for ex, lv in keys for r in rungs for i in idx[ex]]
    fixed = dict(zip(xkeys, map_draws(fixed_energy, xargs, executor), strict=True))
    for ex in EXAMPLES:
        st = full[ex]
        pos = {i: k for k, i in enumerate(st["test_indices"])}
        res = {"test_indices": idx[ex], "horizons": [seeded_draw(ex, i, seed)[1].horizon for i in idx[ex]]}
        for lv in LEVELS:
            dz, key = designs[ex, lv], (ex, lv)
            ref = "best" if dz["reference"] == dz["best"] else "best_x"
            fb = chosen[key] == FALLBACK
            res[f"{lv:g} dB"] = {
                **{k: dz[k] for k in ("densities", "nyquist", "q", "q_scores", "best", "best_x", "reference",
                                      "base")},
                "expected_power": {dz[r]: dz["powers"][dz[r]] for r in rungs}
                | {"base": dz["powers"][dz["base"]]},
                "noise_power": {dz[r]: dz["noise"][dz[r]] for r in rungs},
                "window": chosen[key],
                "train_scores": {(f"{w:g}" if w != FALLBACK else w): float(np.mean(score[(*key, w)]))
                                 for w in settings},
                "applied": [0.0 if fb else laws[(*key, i)][1] for i in idx[ex]],
                "energies": {"limit": [st["ladder"]["energies"]["limit"][pos[i]] for i in idx[ex]],
                             "predictive (observer)": [fixed[ex, lv, ref, i] if fb else laws[(*key, i)][0]
                                                       for i in idx[ex]],
                             "best fixed (x, ŵ)": [fixed[ex, lv, "best", i] for i in idx[ex]],
                             "best fixed (x)": [fixed[ex, lv, "best_x", i] for i in idx[ex]]}}
        out[ex] = res
    return out


def summary(res: dict, example: str) -> list:
    """Per level: each rung over the best fixed controller at that level (the better of the best
    reading ŵ through the observer and the best reading x alone): median with its bootstrap 95 %
    interval, the share of draws with less energy, and the law's median share of the log
    headroom to the limit.

    Parameters
    ----------
    res : dict
        :func:`observer_study`'s result, or the stored one.
    example : {"aircraft", "generic"}

    Returns
    -------
    list of dict
        ``{"level", "reference", "window", rung: (median, lo, hi, wins), "share": (median, lo, hi)}``.
    """
    if example not in EXAMPLES:
        raise ValueError(f"example must be one of {EXAMPLES}, but found {example!r}")
    rows = []
    for key in res["levels"]:
        row = res[example][key]
        ref = "best fixed (x, ŵ)" if row["reference"] == row["best"] else "best fixed (x)"
        e = {k: np.asarray(v, dtype=float) for k, v in row["energies"].items()}
        out = {"level": key, "reference": ref, "window": row["window"]}
        for rung, v in e.items():
            q = v / e[ref]
            out[rung] = (*bootstrap_median(q), float(np.mean(q < 1.0)))
        gap = np.log(e["limit"] / e[ref])
        out["share"] = bootstrap_median(np.log(e["predictive (observer)"] / e[ref]) / gap)
        rows.append(out)
    return rows


def load_observer(path=None):
    """The stored study of this module.

    Parameters
    ----------
    path : path, optional
        Default :data:`OBSERVER_FILE` in the repository this package lies in.

    Returns
    -------
    dict or None
        None if the file is absent.
    """
    return load_stored(OBSERVER_FILE, path)


def main(argv=None) -> int:
    """``python -m fdsc observer-rung [--workers W] [--n-test N] [--n-train N] [--out FILE | --replace]``
    (:func:`fdsc.paper.pays.study_command.study_main`).

    Parameters
    ----------
    argv : list of str, optional

    Returns
    -------
    int
        0 on success.
    """
    return study_main(argv, prog="python -m fdsc observer-rung",
                      description="the ladder with ŵ from a disturbance observer on noisy measurements of x, "
                                  "on the stored study's draws",
                      file=OBSERVER_FILE, study=observer_study,
                      options=(("n_test", N_TEST, 2, None), ("n_train", N_TRAIN, 1, None)))


if __name__ == "__main__":
    sys.exit(main())
