"""Is the ladder a property of this class? The ladder's main rungs on variants of the class
(chapter 'ladder'): segments four times shorter and four times longer, a dominating band with a
share α of the power anywhere in [0.5, 1], and a class whose every segment is band-limited noise
(:data:`NOISE_VARIANT_TONES` tones per band with Rayleigh amplitudes and random phases: Gaussian in
distribution, and at the law's window far too many tones to resolve, so its future is not
predictable from a short past).

For each variant the best fixed controllers are tuned again on the variant's own training draws
(the structures chosen for the main class, started from its controllers), the predictive law
keeps the main class's setting, and every rung is scored on the variant's test draws against
the variant's best fixed controller (x, ŵ).
"""

from __future__ import annotations

import numpy as np

import fdsc
from fdsc.paper.pays.disturbance_law_draws import SEED, _example, draw, segment_class
from fdsc.paper.pays.fixed_designs import FF_MAXITER, FixedSet, ff_poles

__all__ = ["VARIANTS", "VARIANT_WORDS", "NOISE_VARIANT_TONES", "N_TUNE_VARIANT", "N_TEST_VARIANT",
           "variant_draw", "variant_controllers", "variant_row", "submit_variant_tuning", "variant_study"]

#: Tones per band of a segment of the noise variant.
NOISE_VARIANT_TONES = 40
#: The variants: keyword arguments of :func:`fdsc.paper.pays.disturbance_law_draws.draw`.
VARIANTS = {"shorter": {"length_scale": 0.25}, "longer": {"length_scale": 4.0},
            "alpha": {"alpha": (0.5, 1.0)},
            "noise": {"noise_share": 1.0, "noise_tones": NOISE_VARIANT_TONES}}
#: The variants in words.
VARIANT_WORDS = {"shorter": "segments 4× shorter", "longer": "segments 4× longer",
                 "alpha": "dominance α in [0.5, 1]", "noise": "every segment band-limited noise"}
#: Tuning and test draws per variant and example (the longer variant's test draws are halved: each
#: is four times as long).
N_TUNE_VARIANT, N_TEST_VARIANT = 12, 24


def variant_draw(example: str, variant: str, index: int, seed: int = SEED):
    """Draw ``index`` of a variant (its generator seeded by ``[seed, 1000 + variant's rank, index]``).

    Parameters
    ----------
    example : {"aircraft", "generic"}
    variant : str
        One of :data:`VARIANTS`.
    index : int
    seed : int, optional

    Returns
    -------
    Draw
    """
    from fdsc._validation import as_choice

    variant = as_choice("variant", variant, tuple(VARIANTS))
    rank = list(VARIANTS).index(variant)
    return draw(_example(example), np.random.default_rng([seed, 1000 + rank, index]), **VARIANTS[variant])


def variant_controllers(example: str, variant: str, fs: FixedSet, seed: int = SEED,
                        n_tune: int = N_TUNE_VARIANT) -> dict:
    """The best fixed controllers tuned on a variant's training draws: ``{"best fixed (x, ŵ)",
    "best fixed (x)"}``, with the structures of the main class's choices (the optimal LTI
    controller designed again for the variant's mean spectrum, which only its segments' lengths
    change).

    Parameters
    ----------
    example : {"aircraft", "generic"}
    variant : str
    fs : FixedSet
        The main class's fixed controllers.
    seed : int, optional
    n_tune : int, optional
        Its tuning draws (the first ones of the variant).

    Returns
    -------
    dict
    """
    plant = _example(example).plant
    tune = [variant_draw(example, variant, i, seed) for i in range(n_tune)]
    ds, hs = [dr.d for dr in tune], [dr.horizon for dr in tune]
    out = {}
    for rung, name in (("best fixed (x, ŵ)", fs.chosen), ("best fixed (x)", fs.chosen_x)):
        c = fs.controllers[name]
        spec = ff_poles(example).get(name)
        if fs.family.get(name) == "optimal LTI":      # designed again for the variant's spectrum
            cls = segment_class(example, VARIANTS[variant].get("length_scale", 1.0))
            out[rung] = fdsc.optimal_lti(plant, cls, name=name).controller
            continue
        if spec is not None:                          # a tuned controller that reads ŵ
            structure, ff = spec
            start = fs.controllers["tuned filtered"] if structure == "filtered" else fs.controllers["tuned"].D
            res = fdsc.tune_controller(plant, ds, hs, [start], structure=structure, feedforward=ff,
                                       maxiter=FF_MAXITER, name=name)
        elif name.startswith("tuned filtered"):
            res = fdsc.tune_controller(plant, ds, hs, [c], structure="filtered", maxiter=FF_MAXITER,
                                       name=name)
        elif name.startswith("tuned"):
            res = fdsc.tune_controller(plant, ds, hs, [c.D], maxiter=FF_MAXITER, name=name)
        else:                                         # a design that is not tuned: kept as it is
            out[rung] = c
            continue
        out[rung] = res.controller
    return out


def variant_row(example: str, variant: str, index: int, seed: int, controllers: dict, settings: dict) -> dict:
    """The main rungs' energies on test draw ``index`` of a variant.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    variant : str
    index, seed : int
    controllers : dict
        :func:`variant_controllers` and ``"fs"`` (the main class's fixed set: the law's base).
    settings : dict
        The predictive law's setting (chosen on the main class).

    Returns
    -------
    dict
    """
    from fdsc.paper.pays.ladder import predictive_law

    ex = _example(example)
    dr = variant_draw(example, variant, index, seed)
    law = predictive_law(example, controllers["fs"], settings["window"], settings["max_residual"])
    row = {"limit": fdsc.noncausal_limit(ex.plant, dr.d, dr.horizon).energy,
           "known tones": law.run_known(dr.d, dr.horizon).energy,
           "predictive": law.run(dr.d, dr.horizon).energy}
    for rung in ("best fixed (x, ŵ)", "best fixed (x)"):
        row[rung] = fdsc.loop_energy(controllers[rung].closed_loop(ex.plant), dr.d, dr.horizon)
    return row


def submit_variant_tuning(example: str, fs: FixedSet, seed: int = SEED, executor=None,
                          n_tune: int = N_TUNE_VARIANT):
    """The variants' best fixed controllers (:func:`variant_controllers`), submitted to the
    executor without waiting (:func:`fdsc.paper.pays.stored_study.submit_draws`).

    Parameters
    ----------
    example : {"aircraft", "generic"}
    fs : FixedSet
    seed : int, optional
    executor : optional
    n_tune : int, optional

    Returns
    -------
    Pending
        Its ``result()``: one ``{rung: controller}`` per variant, in the order of :data:`VARIANTS`.
    """
    from fdsc.paper.pays.stored_study import submit_draws

    return submit_draws(variant_controllers, [(example, v, fs, seed, n_tune) for v in VARIANTS], executor)


def variant_study(example: str, fs: FixedSet, settings: dict, seed: int = SEED, executor=None, *,
                  n_tune: int = N_TUNE_VARIANT, n_test: int = N_TEST_VARIANT, tuned=None) -> dict:
    """Every variant of one example: per rung the summary (median, bootstrap interval, win rate,
    share of the headroom) against the variant's best fixed controller (x, ŵ).

    Parameters
    ----------
    example : {"aircraft", "generic"}
    fs : FixedSet
    settings : dict
    seed : int, optional
    executor : optional
    n_tune, n_test : int, optional
        Tuning and test draws per variant (the longer variant's test draws halved).
    tuned : Pending, optional
        The variants' controllers already submitted (:func:`submit_variant_tuning` with the same
        arguments), so that their long tunings share the workers with other runs; default tuned
        here.

    Returns
    -------
    dict
        ``{variant: {"draws", "summary", "ratios", "energies"}}`` (the energies per rung and draw).
    """
    from fdsc.paper.pays.ladder import summarize
    from fdsc.paper.pays.stored_study import map_draws

    out = {}
    tuned = (submit_variant_tuning(example, fs, seed, executor, n_tune) if tuned is None else tuned).result()
    for variant, ctrls in zip(VARIANTS, tuned, strict=True):
        ctrls = ctrls | {"fs": fs}
        n = max(1, n_test // 2) if variant == "longer" else n_test
        idx = range(n_tune, n_tune + n)
        rows = map_draws(variant_row, [(example, variant, i, seed, ctrls, settings) for i in idx], executor)
        ref = np.array([r["best fixed (x, ŵ)"] for r in rows])
        ratios = {k: (np.array([r[k] for r in rows]) / ref).tolist() for k in rows[0]}
        out[variant] = {"draws": n, "summary": summarize(ratios), "ratios": ratios,
                        "energies": {k: [r[k] for r in rows] for k in rows[0]}}
    return out
