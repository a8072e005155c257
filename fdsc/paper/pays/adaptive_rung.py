"""The adaptive-regulation rung of the ladder: an adaptive Youla–Kučera feedforward on the best
fixed controller, on the stored study's draws.

The law (:class:`fdsc.adaptive.AdaptiveFeedforward`) is the stored study's best fixed controller
reading x and ŵ (the optimal LTI controller of the class, ``u = K x + Q(s) ŵ``) plus an FIR
filter of samples of ŵ whose taps recursive least squares fits online to the disturbance at
hand: adaptive regulation in the sense of Landau et al.'s benchmark, with the same information
as the predictive law (x and samples of ŵ at the same step). Its taps, memory and regularization
are chosen on :data:`N_TRAIN` training draws among :data:`GRID` (least mean log energy), then it
runs on the first :data:`N_TEST` test draws of each example, on the exact estimate.

**Under measurement noise** (:data:`NOISE_LEVEL`, as the noise study
:mod:`fdsc.paper.pays.information` defines it: the class's mean power over the variance of white
noise on the samples, band-limited to the sampler's Nyquist frequency), on the same draws, the
law adapts on the fixed controller redesigned for that noise
(:func:`fdsc.measurement_noise.optimal_lti_in_noise`), reads noisy samples (seeded by the draw's
index) and pays its base's expected noise cost, as the predictive law with a confidence check does
there; its regularization is chosen again on the training draws (its taps and memory are the
exact estimate's). Beside it, the best fixed controller (x, ŵ) at that level (the noise study's,
:func:`fdsc.paper.pays.information.level_design`): its exact energy plus its expected noise cost.

``python -m fdsc adaptive-rung [--workers W] [--replace]`` runs it and writes
:data:`ADAPTIVE_FILE` (with its wall time and host), which the ladder chapter reads.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np

from fdsc.adaptive import AdaptiveFeedforward
from fdsc.paper.pays.disturbance_law_draws import seeded_draw
from fdsc.paper.pays.ladder import law_band
from fdsc.paper.pays.stored_study import map_draws, stored_fixed_set
from fdsc.paper.pays.study_command import load_stored, study_main
from fdsc.paper.shared.stats import bootstrap_median

__all__ = ["GRID", "N_TEST", "N_TRAIN", "NOISE_LEVEL", "ADAPTIVE_FILE", "adaptive_energy", "adaptive_study",
           "summary", "noise_summary", "load_adaptive", "main"]

#: The settings tried on the training draws: (taps, memory in s, regularization).
GRID = tuple((taps, memory, reg) for taps, memory in ((16, 4.0), (32, 8.0), (64, 16.0))
             for reg in (1e-4, 1e-3, 1e-2, 1e-1, 1.0))
#: Test draws per example (the stored study's first) and training draws (its first).
N_TEST, N_TRAIN = 24, 4
#: The noise level (dB) of the run under measurement noise (the class's mean power over the
#: noise's variance on the samples).
NOISE_LEVEL = 20.0
#: The stored result, which the book reads.
ADAPTIVE_FILE = Path("book") / "data" / "adaptive_rung.json"


def adaptive_energy(example: str, index: int, seed: int, setting: tuple, base, noise: float = 0.0,
                    base_noise: float = 0.0) -> float:
    """The adaptive law's energy on one draw of the class.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    index, seed : int
    setting : (int, float, float)
        Taps, memory (s), regularization.
    base : Controller
        The fixed controller it adapts on (its gain on x must be the LQ gain).
    noise : float, optional
        The variance of the noise on the samples it reads (seeded by ``index``; default none).
    base_noise : float, optional
        The expected noise power its base's continuous filter adds (per second of the draw).

    Returns
    -------
    float
    """
    ex, dr = seeded_draw(example, index, seed)
    _band, step = law_band(example)
    taps, memory, reg = setting
    law = AdaptiveFeedforward(ex.plant, step, taps=int(taps), memory=float(memory), regularization=float(reg),
                              base=base)
    return law.run(dr.d, dr.horizon, noise=noise, seed=index).energy + dr.horizon * base_noise


def _closed_energy(example, index, seed, ctrl):
    """A fixed controller's exact energy on one draw (closed form)."""
    from fdsc._closed_energy import closed_form_energies

    ex, dr = seeded_draw(example, index, seed)
    return float(closed_form_energies(ex.plant.closed_loop(ctrl), [dr.d], [dr.horizon])[0][0])


def adaptive_study(full: dict, *, n_test: int = N_TEST, n_train: int = N_TRAIN, executor=None) -> dict:
    """The rung on the stored study ``full`` (module docstring).

    Parameters
    ----------
    full : dict
        The stored study.
    n_test, n_train : int, optional
    executor : optional

    Returns
    -------
    dict
        Per example: the setting chosen and every setting's training score, the test indices
        and per test draw the law's energy and the stored reference's.
    """
    from fdsc.paper.shared.cache import study_fingerprint
    from fdsc.paper.shared.environment import build_commit

    seed = full["seed"]
    out = {"commit": build_commit(), "fingerprint": study_fingerprint("fdsc.paper.pays.adaptive_rung"),
           "stored_study": {"commit": full["commit"], "fingerprint": full["fingerprint"]},
           "seed": seed, "n_test": n_test, "n_train": n_train, "grid": [list(g) for g in GRID]}
    examples = ("aircraft", "generic")
    bases = {ex: stored_fixed_set(full, ex).controllers[full[ex]["fixed_in_advance"]] for ex in examples}
    targs = [(ex, i, seed, g, bases[ex]) for ex in examples for g in GRID for i in range(n_train)]
    scores = {}
    for a, e in zip(targs, map_draws(adaptive_energy, targs, executor), strict=True):
        scores.setdefault((a[0], a[3]), []).append(math.log(e) if e > 0 and math.isfinite(e) else math.inf)
    chosen = {ex: min(GRID, key=lambda g, ex=ex: float(np.mean(scores[ex, g]))) for ex in examples}
    idx = {ex: full[ex]["test_indices"][:n_test] for ex in ("aircraft", "generic")}
    args = [(ex, i, seed, chosen[ex], bases[ex]) for ex in ("aircraft", "generic") for i in idx[ex]]
    energies = map_draws(adaptive_energy, args, executor)
    k = 0
    for ex in ("aircraft", "generic"):
        st = full[ex]
        e = energies[k:k + len(idx[ex])]
        k += len(idx[ex])
        out[ex] = {"reference": st["fixed_in_advance"], "setting": list(chosen[ex]),
                   "train_scores": {"/".join(f"{v:g}" for v in g): float(np.mean(scores[ex, g]))
                                    for g in GRID},
                   "test_indices": idx[ex], "energies": e,
                   "reference_energies": st["ladder"]["energies"]["best fixed (x, ŵ)"][:len(idx[ex])],
                   "predictive_energies": st["ladder"]["energies"]["predictive"][:len(idx[ex])],
                   "limit_energies": st["ladder"]["energies"]["limit"][:len(idx[ex])]}
    noisy = _noise_part(full, chosen, idx, n_train, executor)
    for ex in examples:
        out[ex]["noise"] = noisy[ex]
    out["noise_level"] = NOISE_LEVEL
    return out


def _noise_part(full, chosen, idx, n_train, executor):
    """The law under measurement noise at :data:`NOISE_LEVEL` (module docstring): per example its
    regularization chosen on the training draws, and per test draw its energy, the best fixed
    controller's at that level and the horizon."""
    from fdsc.paper.pays.information import level_design

    seed, examples = full["seed"], ("aircraft", "generic")
    designs = {ex: level_design(ex, NOISE_LEVEL, full) for ex in examples}
    var = {ex: designs[ex]["variance"] for ex in examples}
    base = {ex: designs[ex]["optimal"].controller for ex in examples}
    base_noise = {ex: designs[ex]["optimal"].noise_power for ex in examples}
    grid = {ex: [(*chosen[ex][:2], g[2]) for g in GRID if tuple(g[:2]) == tuple(chosen[ex][:2])]
            for ex in examples}
    targs = [(ex, i, seed, g, base[ex], var[ex], base_noise[ex]) for ex in examples for g in grid[ex]
             for i in range(n_train)]
    scores = {}
    for a, e in zip(targs, map_draws(adaptive_energy, targs, executor), strict=True):
        scores.setdefault((a[0], a[3]), []).append(math.log(e) if e > 0 and math.isfinite(e) else math.inf)
    pick = {ex: min(grid[ex], key=lambda g, ex=ex: float(np.mean(scores[ex, g]))) for ex in examples}
    args = [(ex, i, seed, pick[ex], base[ex], var[ex], base_noise[ex]) for ex in examples for i in idx[ex]]
    law = map_draws(adaptive_energy, args, executor)
    out, k = {}, 0
    for ex in examples:
        dz = designs[ex]
        best = dz["best"]
        ctrl = dz["optimal"].controller if best == "optimal LTI in noise" else \
            stored_fixed_set(full, ex).controllers[best]
        clean = map_draws(_closed_energy, [(ex, i, seed, ctrl) for i in idx[ex]], executor)
        horizons = [seeded_draw(ex, i, seed)[1].horizon for i in idx[ex]]
        out[ex] = {"setting": list(pick[ex]), "variance": var[ex], "base_noise_power": base_noise[ex],
                   "train_scores": {"/".join(f"{v:g}" for v in g): float(np.mean(scores[ex, g]))
                                    for g in grid[ex]},
                   "energies": law[k:k + len(idx[ex])], "horizons": horizons, "reference": best,
                   "reference_energies": [c + h * dz["noise"][best]
                                          for c, h in zip(clean, horizons, strict=True)]}
        k += len(idx[ex])
    return out


def summary(res: dict, example: str) -> dict:
    """The adaptive law, the predictive law and the limit over the reference on the same draws:
    ``{rung: (median, lo, hi, wins)}``.

    Parameters
    ----------
    res : dict
        :func:`adaptive_study`'s result.
    example : {"aircraft", "generic"}

    Returns
    -------
    dict
    """
    r = res[example]
    ref = np.asarray(r["reference_energies"], float)
    out = {}
    for rung, key in (("adaptive", "energies"), ("predictive", "predictive_energies"),
                      ("limit", "limit_energies")):
        x = np.asarray(r[key], float) / ref
        out[rung] = (*bootstrap_median(x), float(np.mean(x < 1.0)))
    return out


def noise_summary(res: dict, example: str) -> tuple:
    """The adaptive law under measurement noise over the best fixed controller (x, ŵ) at the same
    level, on the same draws: ``(median, lo, hi, wins)``.

    Parameters
    ----------
    res : dict
        :func:`adaptive_study`'s result.
    example : {"aircraft", "generic"}

    Returns
    -------
    tuple
    """
    r = res[example]["noise"]
    x = np.asarray(r["energies"], float) / np.asarray(r["reference_energies"], float)
    return (*bootstrap_median(x), float(np.mean(x < 1.0)))


def load_adaptive(path=None):
    """The stored study of this module.

    Parameters
    ----------
    path : path, optional
        Default :data:`ADAPTIVE_FILE` in the repository this package lies in.

    Returns
    -------
    dict or None
        None if the file is absent.
    """
    return load_stored(ADAPTIVE_FILE, path)


def main(argv=None) -> int:
    """``python -m fdsc adaptive-rung [--workers W] [--n-test N] [--n-train N] [--out FILE | --replace]``
    (:func:`fdsc.paper.pays.study_command.study_main`).

    Parameters
    ----------
    argv : list of str, optional

    Returns
    -------
    int
        0 on success.
    """
    return study_main(argv, prog="python -m fdsc adaptive-rung",
                      description="the adaptive-regulation rung on the stored study's draws",
                      file=ADAPTIVE_FILE, study=adaptive_study,
                      options=(("n_test", N_TEST, 2, None), ("n_train", N_TRAIN, 1, None)))


if __name__ == "__main__":
    sys.exit(main())
