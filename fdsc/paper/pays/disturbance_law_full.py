"""The full study of chapter 'disturbance_law', stored: every draw of both examples under every
controller on an executor (:func:`full_study`), the runs on a noisy estimate and on sampled
measurements, the stored file and the fixed controllers rebuilt from it.
"""

from __future__ import annotations

import json
import math
import sys
import time
from pathlib import Path

import numpy as np

from fdsc._closed_energy import MODAL, SCHUR, closed_form_energies
from fdsc._validation import as_count
from fdsc.paper.pays.disturbance_law_draws import SEED
from fdsc.paper.pays.disturbance_law_robust import (
    MEASURED_DT,
    MEASURED_VARIANTS,
    measured_result,
    min_switching_summary,
    robust_result,
)
from fdsc.paper.pays.disturbance_law_runs import REFERENCE_FAMILIES, draw_result
from fdsc.paper.pays.disturbance_law_study import FAMILIES, choose, law_key, scored_settings
from fdsc.paper.pays.fixed_designs import FixedSet, fixed_set
from fdsc.paper.pays.stored_study import FULL_FILE, _stored_example, load_full, map_draws, stored_fixed_set
from fdsc.paper.shared.examples import beats

__all__ = ["N_FULL", "N_MIN", "FULL_FILE", "N_ROBUST", "ROBUST_SNR_DB", "full_study", "stored_fixed_set",
           "robustness", "measured_robustness", "load_full", "map_draws"]

#: Draws per example of the full study.
N_FULL = 500
#: Fewest draws per example a study takes (:func:`full_study`; as
#: :func:`fdsc.paper.pays.disturbance_law.study`): half train, half test.
N_MIN = 4
#: Test draws per example and SNRs (dB) of the study of a noisy estimate.
N_ROBUST, ROBUST_SNR_DB = 40, (20.0, 10.0, 0.0)

def _controller_record(c) -> dict:
    """A controller's matrices for the stored study (so that its numbers can be checked)."""
    out = {k: getattr(c, k).tolist() for k in "ABCD"}
    if c.F is not None:
        out["E"], out["F"] = c.E.tolist(), c.F.tolist()
    return out


class _Clock:
    """Wall seconds of each phase of a study, in order."""

    def __init__(self):
        self.seconds, self._t = {}, time.perf_counter()

    def __call__(self, phase):
        now = time.perf_counter()
        self.seconds[phase] = round(now - self._t, 1)
        self._t = now
        print(f"full study: {phase} took {self.seconds[phase]:.0f} s", file=sys.stderr, flush=True)


def full_study(n: int = N_FULL, *, seed: int = SEED, executor=None, out=None) -> dict:
    """The full study of both examples.

    Parameters
    ----------
    n : int, optional
        Draws per example (half train, half test), at least :data:`N_MIN`.
    seed : int, optional
    executor : concurrent.futures.Executor or dask.distributed.Client, optional
        Where the draws run (default here, one after the other); the numbers do not depend on it.
    out : path, optional
        The JSON file to write (None: none).

    Returns
    -------
    dict
        ``commit``, ``fingerprint`` (:func:`fdsc.paper.shared.cache.study_fingerprint`: the
        sources the study imports), ``n``, ``seed``, and per example the summary
        (:meth:`Study.summary`) with every test draw's ratios for every fixed controller, FDSC
        variant, law family and reference, and the fixed controllers' matrices; ``phase_seconds``
        (the wall time of each phase, in order).
    """
    from fdsc.paper.shared.cache import study_fingerprint
    from fdsc.paper.shared.environment import build_commit

    n = as_count("n", n, N_MIN)
    result = {"commit": build_commit(), "fingerprint": study_fingerprint(), "n": n, "seed": seed}
    clock = _Clock()
    # the two examples' fixed controllers are tuned at once (each tuning is serial, and the
    # longest single task of the study)
    sets = map_draws(fixed_set, [(example, n, seed) for example in ("aircraft", "generic")], executor)
    clock("fixed controllers")
    for example, fs in zip(("aircraft", "generic"), sets, strict=True):
        # every setting on the training draws (the choice), on the test draws only those scored
        train = map_draws(draw_result, [(example, i, seed, fs, None, ()) for i in range(n // 2)], executor)
        keys = scored_settings(example, train, seed, fs)
        test = map_draws(draw_result, [(example, i, seed, fs, keys, keys[:1]) for i in range(n // 2, n)],
                         executor)
        st = choose(example, train + test, seed, fs)
        if st.law != keys[0]:                       # the same choice from the same training draws
            raise RuntimeError(f"{example}: the law chosen on all draws ({st.law}) is not the one the "
                               f"test draws were run for ({keys[0]})")
        clock(f"{example}: draws")
        result[example] = st.summary() | {
            "test_indices": [r["index"] for r in st.test],
            "ratio_vs_fixed_in_advance": st.ratio().tolist(),
            "fixed_ratio": {k: st.fixed_ratio(k).tolist() for k in fs.names},
            "fixed_energy": {k: [r["fixed"][k] for r in st.test] for k in fs.names},
            "fdsc_ratio": {v: st.fdsc_ratio(v).tolist() for v in st.test[0]["fdsc"]},
            "reference_ratio": {f: st.reference_ratio(f).tolist() for f in REFERENCE_FAMILIES},
            "family_best": {p: st.best_of(p) for p in FAMILIES},
            "family_ratio": {p: st.ratio(st.best_of(p)).tolist() for p in FAMILIES},
            "settings": st.settings_table(),
            "oracle_ratio": [r["oracle"] / r["fixed"][fs.chosen] for r in st.test],
            "ideal_ratio": [r["ideal"] / r["fixed"][fs.chosen] for r in st.test],
            "control_steps": st.control_steps().tolist(),
            "fixed_controllers": {k: {"family": fs.family[k], **fs.info[k], "train_score": fs.train_score[k],
                                      "matrices": _controller_record(fs.controllers[k])} for k in fs.names},
            "pairs": {f: [_controller_record(c) for c in pair] for f, pair in fs.pairs.items()},
            "fixed_in_advance_x": fs.chosen_x,
            "best_found": fs.chosen_found,
            "optimal_lti": _optimal_record(fs),
            "front_checks": fs.front_checks,
            "design_checks": fs.design_checks,
            "ladder": ladder_study(example, fs, st, seed, executor),
        }
        clock(f"{example}: ladder")
    result["robustness"] = robustness(result, n=min(N_ROBUST, n - n // 2), executor=executor)
    clock("noisy estimate")
    result["measured"] = measured_robustness(result, n=min(N_ROBUST, n - n // 2), executor=executor)
    clock("sampled measurements")
    result["phase_seconds"] = clock.seconds
    if out is not None:
        Path(out).parent.mkdir(parents=True, exist_ok=True)
        Path(out).write_text(json.dumps(result, indent=1))
    return result


def ladder_study(example: str, fs: FixedSet, st, seed: int, executor=None) -> dict:
    """The ladder of one example on the study's test draws (chapter 'ladder'): the settings
    chosen on training draws, per test draw the energy of every rung and its ratio to the best
    fixed controller (x, ŵ), their summary, and the realizable rungs on a noisy estimate.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    fs : FixedSet
    st : Study
        The study of the same draws (:func:`choose`): the gain-switching law and FDSC per draw.
    seed : int
    executor : optional

    Returns
    -------
    dict
    """
    from fdsc.paper.pays.ladder import (
        N_CHOOSE,
        N_PEAK,
        PEAK_DT,
        SINCE_BREAK,
        choose_settings,
        direct_dwell,
        ladder_draw,
        ladder_noisy,
        summarize,
    )
    from fdsc.paper.pays.ladder_variants import (
        N_TEST_VARIANT,
        N_TUNE_VARIANT,
        submit_variant_tuning,
        variant_study,
    )

    idx = [r["index"] for r in st.test]
    small = len(idx) < N_TEST_VARIANT                 # a study smaller than the full one: variants too
    n_tune = min(N_TUNE_VARIANT, len(idx)) if small else N_TUNE_VARIANT
    # the variants' tunings (a few long runs) start first and share the workers with the draws
    tuned = submit_variant_tuning(example, fs, seed, executor, n_tune)
    settings = choose_settings(example, fs, seed, n=min(N_CHOOSE, len(st.train)), executor=executor)
    rows = map_draws(ladder_draw, [(example, i, seed, fs, settings) for i in idx], executor)
    ref = np.array([r["best fixed (x, ŵ)"] for r in rows])
    energies = {k: [r[k] for r in rows] for k in rows[0] if k not in ("index", "control", "excess")}
    ratios = {k: (np.asarray(v) / ref).tolist() for k, v in energies.items()}
    control = {k: [r["control"][k] for r in rows] for k in rows[0]["control"]}
    excess = {key: [r["excess"][key] for r in rows] for key in ("excess", "reference", "seconds")}
    fixed_names = {"best fixed (x, ŵ)": fs.chosen, "best found (x, ŵ)": fs.chosen_found,
                   "best fixed (x)": fs.chosen_x}
    peaks = map_draws(_fixed_peaks, [(example, i, seed, fs, fixed_names) for i in idx[:N_PEAK]], executor)
    ratios["gain switching"] = [r["runs"][st.law][0] / r["fixed"][fs.chosen] for r in st.test]
    ratios["FDSC"] = [r["fdsc"]["FDSC"][0] / r["fixed"][fs.chosen] for r in st.test]
    energies["gain switching"] = [r["runs"][st.law][0] for r in st.test]
    energies["FDSC"] = [r["fdsc"]["FDSC"][0] for r in st.test]
    m = min(N_ROBUST, len(idx))
    noisy = {}
    _sup, tau = direct_dwell(example, fs, st.law)
    for snr in ROBUST_SNR_DB:
        res = map_draws(ladder_noisy, [(example, i, seed, fs, settings, float(snr), st.law, tau)
                                       for i in idx[:m]], executor)
        noisy[str(float(snr))] = {k: [r[k] for r in res] for k in res[0]}
    noisy["direct_dwell"] = tau
    return {"settings": settings, "test_indices": idx, "energies": energies, "ratios": ratios,
            "summary": summarize(ratios), "control": control, "fixed_names": fixed_names,
            "control_peak": {k: [p[k] for p in peaks] for k in fixed_names}, "peak_draws": len(peaks),
            "peak_dt": PEAK_DT,
            "excess_by_time": {"edges": [None if math.isinf(e) else e for e in SINCE_BREAK], **excess},
            "noisy": noisy, "noisy_draws": m,
            "exact_on_noisy_draws": {k: ratios[k][:m] for k in ("predictive", "scheduled")},
            "variants": variant_study(example, fs, settings, seed, executor, n_tune=n_tune,
                                      n_test=min(N_TEST_VARIANT, len(idx)), tuned=tuned)}


def _fixed_peaks(example, index, seed, fs, names):
    """The peak control effort of the ladder's fixed rungs on one draw (:func:`control_peak`)."""
    from fdsc.paper.pays.disturbance_law_draws import seeded_draw
    from fdsc.paper.pays.ladder import control_peak

    ex, dr = seeded_draw(example, index, seed)
    return {rung: control_peak(ex.plant, fs.controllers[name], dr.d, dr.horizon)
            for rung, name in names.items()}


def _optimal_record(fs) -> dict:
    """What the study keeps of the optimal LTI controller's design (:func:`fdsc.optimal_lti`)."""
    from fdsc.paper.pays.fixed_designs import OPTIMAL_LTI

    opt = fs.tuning.get(OPTIMAL_LTI)
    if opt is None:
        return {}
    return {"power": opt.power, "full_power": opt.full_power, "wiener": opt.wiener,
            "densities": opt.densities.tolist(), "powers": opt.powers.tolist(),
            "converged": bool(opt.converged), "change": opt.change, "states": opt.controller.n_states}


def _stored_law(full, example):
    """The stored study's fixed controllers, chosen law and first test draw of one example."""
    return stored_fixed_set(full, example), law_key(full[example]["law"]), full["n"] // 2


def recheck_stored(full: dict, example: str, k: int = 2) -> dict:
    """Every fixed controller's energy over the chosen one's on the stored study's first ``k``
    test draws, recomputed now from the stored controllers and draw seeds.

    Parameters
    ----------
    full : dict
        The full study (:func:`load_full`).
    example : {"aircraft", "generic"}
    k : int, optional
        Test draws recomputed.

    Returns
    -------
    dict
        ``draws`` (k), ``controllers`` (how many ratios per draw), ``largest_difference`` (the
        largest relative difference between a ratio recomputed by the engine that computed the
        study, :meth:`fdsc.Prepared.energy_of`, and the stored one), ``second_method`` (how many
        energies, one per controller and draw, the chosen one's included, a second, independent
        method computed by each of its closed forms: ``{"modal closed form": …, "Schur closed
        form": …}``; never by the block engine),
        ``second_difference`` (the largest relative difference between a ratio by the second
        method and the stored one: an error of the engine itself shows here, while the first
        difference, the engine against its own numbers, cannot see it) and ``chosen``.

    Notes
    -----
    The second method integrates each fixed loop from rest in closed form, piece by piece of the
    disturbance: in its real modal form (the eigenvectors' similarity formed by compensated
    products) where the eigenvectors are well conditioned, in its complex Schur form elsewhere
    (:func:`fdsc._closed_energy.closed_form_energies`). It shares none of the engine's Taylor
    series, doublings or separated coordinates.

    Raises
    ------
    TypeError
        If ``full`` is not a dict (e.g. None: :func:`load_full` outside a checkout).
    ValueError
        If ``example`` is not one of the two examples, or ``k`` is not a count between 1 and the
        stored test draws.
    KeyError
        Naming the key the stored study lacks (the example, or ``fixed_in_advance``'s controller).
    """
    import fdsc
    from fdsc.paper.pays.disturbance_law_draws import DECIDE_EVERY, RESTART, seeded_draw

    r = _stored_example(full, example)
    k = as_count("k", k, 1)
    if k > len(r["test_indices"]):
        raise ValueError(f"k must be at most the {len(r['test_indices'])} stored test draws, but found {k}")
    fs = stored_fixed_set(full, example)
    worst = second = 0.0
    methods = {MODAL: 0, SCHUR: 0}
    for j, index in enumerate(r["test_indices"][:k]):
        ex, dr = seeded_draw(example, index, full["seed"])
        K = fdsc.lqr_gain(ex.plant)          # any candidates: a fixed loop's energy is its own
        prep = fdsc.Supervisor(ex.plant, [K, K], decide_every=DECIDE_EVERY,
                               restart=RESTART).prepare(dr.d, dr.horizon)
        names = list(dict.fromkeys([fs.chosen, *r["fixed_ratio"]]))
        engine = {name: prep.energy_of(fs.controllers[name]) for name in names}
        closed = {}
        for name in names:
            loop = fs.controllers[name].closed_loop(ex.plant)
            e, method = closed_form_energies(loop, [dr.d], [dr.horizon])
            closed[name], methods[method] = float(e[0]), methods[method] + 1
        for name, ratios in r["fixed_ratio"].items():
            worst = max(worst, abs(engine[name] / engine[fs.chosen] / ratios[j] - 1.0))
            second = max(second, abs(closed[name] / closed[fs.chosen] / ratios[j] - 1.0))
    return {"draws": k, "controllers": len(r["fixed_ratio"]), "largest_difference": worst,
            "second_method": methods, "second_difference": second,
            "chosen": fs.chosen}


def robustness(full: dict, *, n: int = N_ROBUST, snrs=ROBUST_SNR_DB, executor=None) -> dict:
    """The law chosen in the full study on its first ``n`` test draws per example, on a noisy
    estimate as a controller would build it (:func:`robust_result`).

    Parameters
    ----------
    full : dict
        The full study (:func:`full_study`).
    n : int, optional
        Test draws per example.
    snrs : sequence of float, optional
        SNRs of the estimate in dB.
    executor : concurrent.futures.Executor or dask.distributed.Client, optional

    Returns
    -------
    dict
        ``{example: {"draws", "exact_ratios", "exact_median", "exact_win_rate", "snr_db": {snr:
        {"ratios", "decisions_only_ratios", "fixed_ratios", "median", "win_rate",
        "decisions_only_median", "fixed_median", "switches_ratio"}}}}`` (the ratios per draw, for
        intervals), each against the fixed controller chosen in advance on the exact estimate.
    """
    n = as_count("n", n, 1)
    out = {}
    for example in ("aircraft", "generic"):
        fs, key, first = _stored_law(full, example)
        args = [(example, first + i, key, fs, float(snr), full["seed"]) for snr in snrs for i in range(n)]
        res = map_draws(robust_result, args, executor)
        per = {}
        for k, snr in enumerate(snrs):
            part = res[k * n:(k + 1) * n]
            noisy = np.array([p["noisy"] for p in part])
            per[str(float(snr))] = {
                "ratios": noisy.tolist(),
                "decisions_only_ratios": [float(p["decisions_only"]) for p in part],
                "fixed_ratios": [float(p["fixed_noisy"]) for p in part],
                "median": float(np.median(noisy)), "win_rate": float(np.mean(beats(noisy))),
                "p95": float(np.quantile(noisy, 0.95)),
                "decisions_only_median": float(np.median([p["decisions_only"] for p in part])),
                "fixed_median": float(np.median([p["fixed_noisy"] for p in part])),
                "switches_ratio": float(sum(p["switches_noisy"] for p in part)
                                        / max(1, sum(p["switches_exact"] for p in part)))}
        exact = np.array([p["exact"] for p in res[:n]])
        out[example] = {"draws": n, "exact_ratios": exact.tolist(), "exact_median": float(np.median(exact)),
                        "exact_win_rate": float(np.mean(beats(exact))), "snr_db": per}
    return out


def measured_robustness(full: dict, *, n: int = N_ROBUST, executor=None) -> dict:
    """The law chosen in the full study on its first ``n`` test draws per example, run on
    sampled measurements (:func:`measured_result`).

    Parameters
    ----------
    full : dict
        The full study (:func:`full_study`).
    n : int, optional
        Test draws per example.
    executor : concurrent.futures.Executor or dask.distributed.Client, optional

    Returns
    -------
    dict
        ``{example: {"draws", "dt", "variants": {name: {"ratios", "median", "win_rate", "p95",
        "switches_ratio", "diverged"}}, "min_switching": {...}, "commit"}}`` (the ratios per draw).
    """
    from fdsc.paper.shared.environment import build_commit

    n = as_count("n", n, 1)
    out = {}
    for example in ("aircraft", "generic"):
        fs, key, first = _stored_law(full, example)
        args = [(example, first + i, key, fs, full["seed"]) for i in range(n)]
        res = map_draws(measured_result, args, executor)
        per = {}
        for name in ("exact", *MEASURED_VARIANTS, "min_switching"):
            ratio = np.array([p[name]["ratio"] for p in res])
            per[name] = {"ratios": ratio.tolist(), "median": float(np.median(ratio)),
                         "p95": float(np.quantile(ratio, 0.95)),
                         "win_rate": float(np.mean(beats(ratio))),
                         "switches_ratio": float(sum(p[name]["switches"] for p in res)
                                                 / max(1, sum(p["exact"]["switches"] for p in res))),
                         "diverged": int(sum(p[name]["diverged"] for p in res))}
        out[example] = {"draws": n, "dt": MEASURED_DT, "variants": per,
                        "min_switching": min_switching_summary(example), "commit": build_commit()}
    return out
