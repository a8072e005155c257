"""The adaptive-regulation rung of the ladder: an adaptive Youla–Kučera feedforward on the best
fixed controller, on the stored study's draws.

The law (:class:`fdsc.adaptive.AdaptiveFeedforward`) is the stored study's best fixed controller
reading x and ŵ (the optimal LTI controller of the class, ``u = K x + Q(s) ŵ``) plus an FIR
filter of samples of ŵ whose taps recursive least squares fits online to the disturbance at
hand: adaptive regulation in the sense of Landau et al.'s benchmark, with the same information
as the predictive law (x and samples of ŵ at the same step). Its taps, memory and regularization
are chosen on :data:`N_TRAIN` training draws among :data:`GRID` (least mean log energy), then it
runs on the first :data:`N_TEST` test draws of each example, on the exact estimate.

``python -m fdsc adaptive-rung [--workers W] [--replace]`` runs it and writes
:data:`ADAPTIVE_FILE` (with its wall time and host), which the ladder chapter reads.
"""

from __future__ import annotations

import json
import math
import os
import sys
import time
from pathlib import Path

import numpy as np

from fdsc.adaptive import AdaptiveFeedforward
from fdsc.paper.pays.disturbance_law_draws import seeded_draw
from fdsc.paper.pays.ladder import law_band
from fdsc.paper.pays.stored_study import load_full, map_draws, stored_fixed_set
from fdsc.paper.shared.stats import bootstrap_median

__all__ = ["GRID", "N_TEST", "N_TRAIN", "ADAPTIVE_FILE", "adaptive_energy", "adaptive_study", "summary",
           "load_adaptive", "main"]

#: The settings tried on the training draws: (taps, memory in s, regularization).
GRID = tuple((taps, memory, reg) for taps, memory in ((16, 4.0), (32, 8.0), (64, 16.0))
             for reg in (1e-4, 1e-3, 1e-2, 1e-1, 1.0))
#: Test draws per example (the stored study's first) and training draws (its first).
N_TEST, N_TRAIN = 24, 4
#: The stored result, which the book reads.
ADAPTIVE_FILE = Path("book") / "data" / "adaptive_rung.json"


def adaptive_energy(example: str, index: int, seed: int, setting: tuple, base) -> float:
    """The adaptive law's energy on one draw of the class.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    index, seed : int
    setting : (int, float, float)
        Taps, memory (s), regularization.
    base : Controller
        The fixed controller it adapts on (its gain on x must be the LQ gain).

    Returns
    -------
    float
    """
    ex, dr = seeded_draw(example, index, seed)
    _band, step = law_band(example)
    taps, memory, reg = setting
    law = AdaptiveFeedforward(ex.plant, step, taps=int(taps), memory=float(memory), regularization=float(reg),
                              base=base)
    return law.run(dr.d, dr.horizon).energy


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


def load_adaptive(path=None):
    """The stored result of this module.

    Parameters
    ----------
    path : path, optional
        Default :data:`ADAPTIVE_FILE` in the repository this package lies in.

    Returns
    -------
    dict or None
        None if the file is absent.
    """
    path = Path(__file__).resolve().parents[3] / ADAPTIVE_FILE if path is None else Path(path)
    if not path.is_file():
        return None
    return json.loads(path.read_text(encoding="utf-8"))


def main(argv=None) -> int:
    """``python -m fdsc adaptive-rung [--workers W] [--n-test N] [--n-train N] [--out F | --replace]``.

    Parameters
    ----------
    argv : list of str, optional

    Returns
    -------
    int
        0 on success.
    """
    import argparse
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    ap = argparse.ArgumentParser(prog="python -m fdsc adaptive-rung",
                                 description="the adaptive-regulation rung on the stored study's draws")
    ap.add_argument("--workers", type=int, default=min(os.cpu_count() or 1, 4))
    ap.add_argument("--n-test", type=int, default=N_TEST)
    ap.add_argument("--n-train", type=int, default=N_TRAIN)
    ap.add_argument("--out", default="out/adaptive_rung.json")
    ap.add_argument("--replace", action="store_true", help=f"write {ADAPTIVE_FILE}, which the book reads")
    args = ap.parse_args(argv)
    if args.workers < 1 or args.n_test < 2 or args.n_train < 1:
        ap.error("--workers ≥ 1, --n-test ≥ 2 and --n-train ≥ 1 are required")
    full = load_full()
    if full is None:
        ap.error("the stored study book/data/disturbance_law_full.json is missing")
    out = Path(__file__).resolve().parents[3] / ADAPTIVE_FILE if args.replace else Path(args.out)
    for var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ.setdefault(var, "1")
    t0, load0 = time.perf_counter(), os.getloadavg()[0]
    with ProcessPoolExecutor(args.workers, mp_context=multiprocessing.get_context("spawn")) as ex:
        res = adaptive_study(full, n_test=args.n_test, n_train=args.n_train, executor=ex)
    res["seconds"] = round(time.perf_counter() - t0, 1)
    res["host"] = {"cpus": os.cpu_count(), "workers": args.workers, "load_before": round(load0, 2),
                   "load_after": round(os.getloadavg()[0], 2)}
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(res, indent=1) + "\n", encoding="utf-8")
    print(f"adaptive rung: {res['seconds']:.0f} s on {args.workers} workers; written to {out}",
          file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
