"""The predictive law with a confidence check on the class's variants: does predicting pay, or
at least never lose, where the past predicts less?

On each variant of :data:`fdsc.paper.pays.ladder_variants.VARIANTS` (segments 4× shorter and 4×
longer, a dominating share α anywhere in [0.5, 1], every segment band-limited noise) and on each
example, with the exact estimate ŵ = d:

* the **best fixed controller (x, ŵ) of the variant**: the optimal LTI controller of the class
  (``u = K x + Q(s) ŵ``, :func:`fdsc.optimal_lti`) designed again for the variant's mean spectrum,
  as the stored study's variants have it (its energy there is rechecked by the tests);
* the **predictive law with a confidence check** (:class:`fdsc.confident.ConfidentPredictiveLaw`)
  on that controller as its base, with the main class's confidence threshold and update; its
  setting chosen on the variant's first :data:`N_TRAIN` draws (the stored study's tuning draws of
  the variant, never its test draws), by their mean log energy, among the windows of
  :data:`fdsc.paper.pays.information.WINDOWS` and :data:`FALLBACK` (not predicting: the law is
  then its base, the variant's best fixed controller, and has its energy on every draw);
* stored beside them, from the stored study's variants on the same test draws: the non-causal
  limit (recomputed here too, for the record's check), the best fixed controller reading x alone
  and the predictive law of the main ladder without the check (its setting the main class's).

``python -m fdsc variant-laws [--workers W] [--replace]`` runs it and writes
:data:`VARIANT_FILE` (with its wall time and host), which the ladder chapter reads.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np

import fdsc
from fdsc._closed_energy import closed_form_energies
from fdsc.confident import ConfidentPredictiveLaw
from fdsc.paper.pays.disturbance_law_draws import _example, segment_class
from fdsc.paper.pays.information import CONFIDENCE, FALLBACK, UPDATE, WINDOWS
from fdsc.paper.pays.ladder import MAX_TONES, law_band
from fdsc.paper.pays.ladder_variants import N_TEST_VARIANT, N_TUNE_VARIANT, VARIANTS, variant_draw
from fdsc.paper.pays.stored_study import map_draws
from fdsc.paper.pays.study_command import load_stored, study_main
from fdsc.paper.shared.stats import bootstrap_median

__all__ = ["N_TRAIN", "FALLBACK", "VARIANT_FILE", "RUNGS", "variant_base", "law_run", "base_energy",
           "variant_law_study", "summary", "load_variant_laws", "recheck", "main"]

#: Training draws per variant and example: the variant's first (its stored study's tuning draws).
N_TRAIN = 4
#: The stored result, which the book reads.
VARIANT_FILE = Path("book") / "data" / "variant_laws.json"
#: The rungs stored per test draw; the last three are the stored study's, on the same draws.
RUNGS = ("limit", "predictive (confident)", "best fixed (x, ŵ)", "best fixed (x)", "predictive")
EXAMPLES = ("aircraft", "generic")


def variant_base(example: str, variant: str):
    """The variant's best fixed controller (x, ŵ): the optimal LTI controller designed for the
    variant's mean spectrum (only its segments' lengths change it).

    Parameters
    ----------
    example : {"aircraft", "generic"}
    variant : str
        One of :data:`fdsc.paper.pays.ladder_variants.VARIANTS`.

    Returns
    -------
    fdsc.OptimalLTI
        The design (its ``controller`` and expected ``power``).
    """
    if variant not in VARIANTS:
        raise ValueError(f"variant must be one of {sorted(VARIANTS)}, but found {variant!r}")
    cls = segment_class(example, VARIANTS[variant].get("length_scale", 1.0))
    return fdsc.optimal_lti(_example(example).plant, cls, name="optimal LTI (x, ŵ)")


def law_run(example: str, variant: str, index: int, seed: int, window: float, base) -> tuple:
    """The confident predictive law on draw ``index`` of a variant.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    variant : str
    index, seed : int
    window : float
        The law's window (s).
    base : Controller
        Its base (:func:`variant_base`'s controller).

    Returns
    -------
    (float, float)
        The energy, and the share of the identifications whose correction was applied (their
        confidence at least the threshold).
    """
    ex = _example(example)
    dr = variant_draw(example, variant, index, seed)
    band, step = law_band(example)
    law = ConfidentPredictiveLaw(ex.plant, band, window=window, step=step, update=UPDATE, max_tones=MAX_TONES,
                                 base=base, confidence=CONFIDENCE)
    run = law.run(dr.d, dr.horizon)
    alphas = np.array([a for _t, a in law.confidences], dtype=float)
    applied = float(np.mean(np.nan_to_num(alphas, nan=-1.0) >= CONFIDENCE)) if alphas.size else 0.0
    return float(run.energy), applied


def base_energy(example: str, variant: str, index: int, seed: int, base) -> float:
    """The exact energy of a fixed controller on draw ``index`` of a variant (closed form).

    Parameters
    ----------
    example : {"aircraft", "generic"}
    variant : str
    index, seed : int
    base : Controller

    Returns
    -------
    float
    """
    dr = variant_draw(example, variant, index, seed)
    loop = _example(example).plant.closed_loop(base)
    return float(closed_form_energies(loop, [dr.d], [dr.horizon])[0][0])


def _limit(example, variant, index, seed):
    dr = variant_draw(example, variant, index, seed)
    return float(fdsc.noncausal_limit(_example(example).plant, dr.d, dr.horizon).energy)


def _test_indices(variant):
    n = max(1, N_TEST_VARIANT // 2) if variant == "longer" else N_TEST_VARIANT
    return list(range(N_TUNE_VARIANT, N_TUNE_VARIANT + n))


def variant_law_study(full: dict, *, n_train: int = N_TRAIN, executor=None) -> dict:
    """The study (module docstring) on the stored study ``full``'s variants.

    Parameters
    ----------
    full : dict
        The stored study (:func:`fdsc.paper.pays.stored_study.load_full`): its seed, and its
        variants' stored energies on the same test draws.
    n_train : int, optional
        Training draws per variant and example (at most the stored study's tuning draws, so that
        no test draw trains).
    executor : optional
        Where the runs go (:func:`fdsc.paper.pays.stored_study.map_draws`).

    Returns
    -------
    dict
        Per example and variant: the chosen setting and every setting's training score, the test
        indices and horizons, and per test draw the energy of every rung of :data:`RUNGS` and the
        law's share of applied corrections.
    """
    from fdsc.paper.shared.cache import study_fingerprint
    from fdsc.paper.shared.environment import build_commit

    if not 1 <= n_train <= N_TUNE_VARIANT:
        raise ValueError(f"n_train must lie in [1, {N_TUNE_VARIANT}] (the variants' tuning draws), "
                         f"but found {n_train!r}")
    seed = full["seed"]
    out = {"commit": build_commit(), "fingerprint": study_fingerprint("fdsc.paper.pays.variant_laws"),
           "stored_study": {"commit": full["commit"], "fingerprint": full["fingerprint"]},
           "seed": seed, "n_train": n_train, "windows": list(WINDOWS), "fallback": FALLBACK,
           "confidence": CONFIDENCE, "update": UPDATE, "variants": list(VARIANTS)}
    keys = [(ex, v) for ex in EXAMPLES for v in VARIANTS]
    designs = dict(zip(keys, map_draws(variant_base, keys, executor), strict=True))
    # the longest runs first, so that the two workers finish together
    order = {("aircraft", "longer"): 0, ("generic", "longer"): 2}

    def by_cost(args):
        return sorted(args, key=lambda a: (order.get((a[0], a[1]), 1), a[0] != "aircraft"))

    train_args = by_cost([(ex, v, i, seed, w, designs[ex, v].controller)
                          for ex, v in keys for w in WINDOWS for i in range(n_train)])
    fb_args = [(ex, v, i, seed, designs[ex, v].controller) for ex, v in keys for i in range(n_train)]
    score = {}
    for a, (e, _applied) in zip(train_args, map_draws(law_run, train_args, executor), strict=True):
        score.setdefault((a[0], a[1], a[4]), []).append(math.log(e))
    for a, e in zip(fb_args, map_draws(base_energy, fb_args, executor), strict=True):
        score.setdefault((a[0], a[1], FALLBACK), []).append(math.log(e))
    settings = (*WINDOWS, FALLBACK)
    chosen = {k: min(settings, key=lambda w, k=k: float(np.mean(score[(*k, w)]))) for k in keys}
    test = {k: _test_indices(k[1]) for k in keys}
    law_args = by_cost([(ex, v, i, seed, chosen[ex, v], designs[ex, v].controller)
                        for ex, v in keys if chosen[ex, v] != FALLBACK for i in test[ex, v]])
    laws = {(a[0], a[1], a[2]): r
            for a, r in zip(law_args, map_draws(law_run, law_args, executor), strict=True)}
    ref_args = [(ex, v, i, seed, designs[ex, v].controller) for ex, v in keys for i in test[ex, v]]
    refs = dict(zip([(a[0], a[1], a[2]) for a in ref_args], map_draws(base_energy, ref_args, executor),
                    strict=True))
    lim_args = [(ex, v, i, seed) for ex, v in keys for i in test[ex, v]]
    lims = dict(zip([a[:3] for a in lim_args], map_draws(_limit, lim_args, executor), strict=True))
    for ex in EXAMPLES:
        out[ex] = {}
        for v in VARIANTS:
            stored = full[ex]["ladder"]["variants"][v]["energies"]
            idx = test[ex, v]
            if len(stored["limit"]) != len(idx):
                raise ValueError(f"the stored study's variant {v!r} of {ex} has {len(stored['limit'])} test "
                                 f"draws, not the {len(idx)} this study scores")
            fallback = chosen[ex, v] == FALLBACK
            law = [refs[ex, v, i] if fallback else laws[ex, v, i][0] for i in idx]
            out[ex][v] = {
                "window": chosen[ex, v], "base_power": float(designs[ex, v].power),
                "base_states": int(designs[ex, v].controller.n_states),
                "train_scores": {(f"{w:g}" if w != FALLBACK else w): float(np.mean(score[ex, v, w]))
                                 for w in settings},
                "test_indices": idx,
                "horizons": [float(variant_draw(ex, v, i, seed).horizon) for i in idx],
                "applied": [0.0 if fallback else laws[ex, v, i][1] for i in idx],
                "energies": {"limit": [lims[ex, v, i] for i in idx], "predictive (confident)": law,
                             "best fixed (x, ŵ)": [refs[ex, v, i] for i in idx],
                             "best fixed (x)": list(stored["best fixed (x)"]),
                             "predictive": list(stored["predictive"])},
                "stored_reference": list(stored["best fixed (x, ŵ)"]),
                "stored_limit": list(stored["limit"])}
    return out


def summary(res: dict, example: str) -> dict:
    """Per variant: each rung over the variant's best fixed controller (x, ŵ): median with its
    bootstrap 95 % interval, the share of draws with less energy, and for the law its median
    share of the log headroom to the limit (per draw) with its interval.

    Parameters
    ----------
    res : dict
        :func:`variant_law_study`'s result (or the stored one, :func:`load_variant_laws`).
    example : {"aircraft", "generic"}

    Returns
    -------
    dict
        ``{variant: {"window", "draws", rung: {"median", "low", "high", "wins"}, "share": (median, lo,
        hi), "applied": median share of corrections applied}}``.
    """
    if example not in EXAMPLES:
        raise ValueError(f"example must be one of {EXAMPLES}, but found {example!r}")
    out = {}
    for v in res["variants"]:
        row = res[example][v]
        e = {k: np.asarray(x, dtype=float) for k, x in row["energies"].items()}
        ref = e["best fixed (x, ŵ)"]
        s = {"window": row["window"], "draws": int(ref.size), "applied": float(np.median(row["applied"]))}
        for rung in RUNGS:
            q = e[rung] / ref
            m, lo, hi = bootstrap_median(q)
            s[rung] = {"median": m, "low": lo, "high": hi, "wins": float(np.mean(q < 1.0))}
        share = np.log(e["predictive (confident)"] / ref) / np.log(e["limit"] / ref)
        s["share"] = bootstrap_median(share)
        out[v] = s
    return out


def load_variant_laws(path=None):
    """The stored study of this module.

    Parameters
    ----------
    path : path, optional
        Default :data:`VARIANT_FILE` in the repository this package lies in.

    Returns
    -------
    dict or None
        None if the file is absent.
    """
    return load_stored(VARIANT_FILE, path)


def recheck(res: dict, example: str = "generic", variant: str = "noise", k: int = 0) -> dict:
    """Recompute the law and the best fixed controller on one stored test draw of a variant.

    Parameters
    ----------
    res : dict
        The stored result (:func:`load_variant_laws`).
    example : {"aircraft", "generic"}, optional
    variant : str, optional
    k : int, optional
        Which of the variant's stored test draws.

    Returns
    -------
    dict
        ``{"law": (stored, recomputed), "fixed": (stored, recomputed)}``.
    """
    row = res[example][variant]
    i = row["test_indices"][k]
    base = variant_base(example, variant).controller
    fixed = base_energy(example, variant, i, res["seed"], base)
    law = (fixed if row["window"] == FALLBACK
           else law_run(example, variant, i, res["seed"], row["window"], base)[0])
    return {"law": (row["energies"]["predictive (confident)"][k], law),
            "fixed": (row["energies"]["best fixed (x, ŵ)"][k], fixed)}


def main(argv=None) -> int:
    """``python -m fdsc variant-laws [--workers W] [--n-train N] [--out FILE | --replace]``
    (:func:`fdsc.paper.pays.study_command.study_main`).

    Parameters
    ----------
    argv : list of str, optional

    Returns
    -------
    int
        0 on success.
    """
    return study_main(argv, prog="python -m fdsc variant-laws",
                      description="the predictive law with a confidence check on the class's variants, "
                                  "on the stored study's variant draws",
                      file=VARIANT_FILE, study=variant_law_study,
                      options=(("n_train", N_TRAIN, 1, N_TUNE_VARIANT),))


if __name__ == "__main__":
    sys.exit(main())
