"""Chapter 'ladder': the strongest fixed controllers of each example for its class of
non-stationary disturbances, and the one chosen in advance that every "does it pay" of Part II
is judged against (the designs: :mod:`fdsc.paper.pays.fixed_designs`, re-exported here).
"""

from __future__ import annotations

import math

import numpy as np

import fdsc
from fdsc.paper.pays.disturbance_law_draws import _example
from fdsc.paper.pays.fixed_designs import (
    CAP_FACTOR,
    DYN_RATIOS,
    FAMILIES,
    FRONT_POINTS,
    N_TUNE,
    RECORD_MAXITER,
    TUNE_MAXITER,
    U_PENALTY,
    FixedSet,
    fixed_set,
    law_front_gains,
    static_front,
    tuning_draws,
)
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.results import RecordPart, entry

__all__ = ["N_TUNE", "CAP_FACTOR", "FRONT_POINTS", "DYN_RATIOS", "U_PENALTY", "TUNE_MAXITER",
           "RECORD_MAXITER", "FAMILIES", "FixedSet", "fixed_set", "tuning_draws", "static_front",
           "law_front_gains", "dynamic_front", "record_part", "N_RECORD", "family_summary", "answer",
           "N_RECHECK", "RECHECKED", "recheck_designs"]

#: Draws of the record's study (the same as chapter 'ladder''s record subset).
N_RECORD = 12


def dynamic_front(example: str) -> fdsc.DynamicFront:
    """The dynamic front of an example (:func:`fdsc.dynamic_front` at :data:`DYN_RATIOS`).

    Parameters
    ----------
    example : {"aircraft", "generic"}

    Returns
    -------
    fdsc.DynamicFront
    """
    ex = _example(example)
    return fdsc.dynamic_front(ex.plant, ex.bands["LF"], ex.bands["HF"], DYN_RATIOS, u_penalty=U_PENALTY)


def _finite(x):
    return None if x is None or not math.isfinite(x) else float(x)


#: Stored test draws per example on which the build recomputes every fixed controller's energy.
N_RECHECK = 1
#: The fixed controllers whose band peaks the build recomputes from their stored matrices.
RECHECKED = ("fixed_in_advance", "best_found", "fixed_in_advance_x")


@cached
def recheck_designs(example: str) -> dict:
    """The stored study's fixed controllers of one example, rechecked now: the band peaks, H∞
    norm and expected power of the chosen ones (:data:`RECHECKED`) recomputed from their stored
    matrices, and every fixed controller's energy on the first :data:`N_RECHECK` test draws by two
    methods (:func:`fdsc.paper.pays.disturbance_law_full.recheck_stored`).

    Parameters
    ----------
    example : {"aircraft", "generic"}

    Returns
    -------
    dict
        ``{"peaks": {name: largest relative difference of its peaks and power}, "draws": ...}``.
    """
    from fdsc.paper.pays.disturbance_law_draws import segment_class
    from fdsc.paper.pays.stored_study import load_full, stored_fixed_set

    full = load_full()
    ex, fs = _example(example), stored_fixed_set(full, example)
    r = full[example]
    cls = segment_class(example)
    peaks = {}
    for key in RECHECKED:
        name = r[key]
        loop = fs.controllers[name].closed_loop(ex.plant)
        now = [fdsc.band_peak(loop, ex.bands["LF"]).gamma, fdsc.band_peak(loop, ex.bands["HF"]).gamma,
               fdsc.band_peak(loop, fdsc.Band.entire()).gamma, fdsc.expected_power(loop, cls)]
        was = [fs.info[name][k] for k in ("lf", "hf", "hinf", "expected_power")]
        peaks[name] = float(max(abs(a / b - 1.0) for a, b in zip(now, was, strict=True)))
    from fdsc.paper.pays.disturbance_law_full import recheck_stored

    return {"peaks": peaks, "draws": recheck_stored(full, example, N_RECHECK)}


def record_part() -> RecordPart:
    """Record entries ``pareto_front``, ``dynamic_front`` and ``fixed_controllers`` (new), read
    from the stored full study, with the build's recheck of a stated subset
    (:func:`recheck_designs`).

    Returns
    -------
    RecordPart
    """
    from fdsc.paper.pays.stored_study import load_full

    full = load_full()
    if full is None or "front_checks" not in full.get("generic", {}):
        why = "the stored study is not in this checkout, or older than this chapter"
        return RecordPart(tuple(entry(i, "our computation", None, None, "new", why)
                                for i in ("pareto_front", "dynamic_front", "fixed_controllers")))
    fronts, dyn, fixed = {}, {}, {}
    for example in ("aircraft", "generic"):
        r = full[example]
        fc = r["fixed_controllers"]
        fronts[example] = [{"beta": c["beta"], "gamma_hf": c["hf"], "gamma_lf": c["lf"],
                            "certified": c["certified"], "dominated_by_search": c["dominated"]}
                           for c in r["front_checks"]]
        dyn[example] = [{"ratio": float(ratio), "gamma_lf": _finite(fc[f"weighted H∞ {j + 1}"]["lf"])
                         if f"weighted H∞ {j + 1}" in fc else None,
                         "gamma_hf": _finite(fc[f"weighted H∞ {j + 1}"]["hf"])
                         if f"weighted H∞ {j + 1}" in fc else None,
                         "states": fc.get(f"weighted H∞ {j + 1}", {}).get("states")}
                        for j, ratio in enumerate(DYN_RATIOS)]
        fixed[example] = {"chosen": r["fixed_in_advance"], "best_found": r["best_found"],
                          "chosen_x": r["fixed_in_advance_x"], "tuning_draws": N_TUNE,
                          "controllers": {k: {"family": v["family"], "gamma_lf": _finite(v["lf"]),
                                              "gamma_hf": _finite(v["hf"]), "hinf": _finite(v["hinf"]),
                                              "states": v["states"], "reads_estimate": v["reads_estimate"],
                                              "expected_power": _finite(v["expected_power"]),
                                              "train_mean_log_energy": _finite(v["train_score"])}
                                          for k, v in fc.items()},
                          "optimal_lti": r["optimal_lti"], "design_checks": r["design_checks"],
                          "recheck": recheck_designs(example)}
    best = {e: fixed[e]["chosen"] for e in fixed}
    stored = f"stored full study (commit {full['commit'][:12]}): "
    note_f = (stored + f"the static front: {FRONT_POINTS} gains of least HF peak with the LF peak at "
              "most β (a direct search, each point certified by Lemma 1 and checked against a second "
              "search for a gain that beats it in both bands).")
    note_d = (stored + "frequency-weighted H∞ state feedback (band weights on z, the H∞ LMI on the "
              f"weighted plant) at {len(DYN_RATIOS)} ratios of the LF to the HF weight: controllers with "
              "states.")
    note_x = (stored + "every fixed controller of the study (comparator set, static and dynamic fronts, LQR, "
              "H2 for the class's spectrum, tuned on the class, the optimal LTI controller of the class) "
              f"with its band peaks and its mean log energy over the study's {full['n'] // 2} training "
              "draws; chosen in advance: " + ", ".join(f"{e} {v}" for e, v in best.items()) + ". The build "
              "recomputes the chosen controllers' band peaks and every controller's energy on the first "
              f"{N_RECHECK} test draw of each example.")
    return RecordPart((
        entry("pareto_front", "our computation (multi-band synthesis, stored study)", None, fronts, "new",
              note_f),
        entry("dynamic_front", "our computation (weighted H∞ synthesis, stored study)", None, dyn, "new",
              note_d),
        entry("fixed_controllers", "our computation (the strongest fixed controllers, stored study)", None,
              fixed, "new", note_x),
    ))


def family_summary(full: dict, example: str) -> dict:
    """From the stored full study: per family, its member of least training score and how it
    does on the test draws against the fixed controller chosen in advance.

    Parameters
    ----------
    full : dict
        The stored full study (:func:`fdsc.paper.pays.disturbance_law.load_full`).
    example : {"aircraft", "generic"}

    Returns
    -------
    dict
        ``{family: {"name", "median", "low", "high", "p95", "chosen_wins"}}`` (``low``, ``high``:
        the median's bootstrap 95 % interval; ``chosen_wins``: share of test draws on which the
        chosen controller has less energy), in the order of :data:`FAMILIES`.
    """
    r = full[example]
    fc = r["fixed_controllers"]
    out = {}
    for fam in FAMILIES:
        members = [k for k, v in fc.items() if v["family"] == fam and math.isfinite(v["train_score"])]
        if not members:
            continue
        best = min(members, key=lambda k: fc[k]["train_score"])
        q = np.asarray(r["fixed_ratio"][best])
        from fdsc.paper.shared.stats import bootstrap_median

        _m, lo, hi = bootstrap_median(q)
        out[fam] = {"name": best, "median": float(np.median(q)), "low": lo, "high": hi,
                    "p95": float(np.quantile(q, 0.95)), "chosen_wins": float(np.mean(q > 1.0 + 1e-6))}
    return out


def answer(full: dict) -> str:
    """The chapter's answer in one paragraph (Markdown), from the stored full study.

    Parameters
    ----------
    full : dict

    Returns
    -------
    str
    """
    from fdsc.paper.shared.prose import count, pct, times_ci
    from fdsc.paper.shared.stats import median_ci_words

    parts = []
    for example in ("aircraft", "generic"):
        r = full[example]
        fams = family_summary(full, example)
        chosen = r["fixed_in_advance"]
        fc = r["fixed_controllers"][chosen]
        kind = (f"a controller with {fc['states']} states" if fc["states"] else "a static gain")
        old = fams["comparator set"]
        front = fams["static front"]
        wins = (f"on {pct(old['chosen_wins'])} of the draws against either"
                if pct(old["chosen_wins"]) == pct(front["chosen_wins"]) else
                f"on {pct(old['chosen_wins'])} and {pct(front['chosen_wins'])} of the draws")
        # the closest of every other fixed controller on the test draws, by median ratio
        rivals = {k: np.asarray(v, dtype=float) for k, v in r["fixed_ratio"].items() if k != chosen}
        near = min(rivals, key=lambda k: float(np.median(rivals[k])))
        near_wins = float(np.mean(rivals[near] > 1.0))
        parts.append(
            f"On the **{example}** example the fixed controller chosen in advance is *{chosen}* ({kind}, "
            f"{r['fixed_in_advance_family']} family). The best member of the comparator set, chosen the "
            f"same way ({old['name']}), has a median {times_ci(old)} its energy on "
            f"{count(r['draws_test'])} test draws (median [bootstrap 95 % interval]), the best point of "
            f"the static front ({front['name']}) {times_ci(front)}; the chosen controller has less energy "
            f"than they do {wins}. The closest of all the other fixed controllers on the test draws is "
            f"*{near}* ({r['fixed_controllers'][near]['family']}): median "
            f"{median_ci_words(rivals[near])}, "
            f"and the chosen controller has less energy on {pct(near_wins)} of the draws, so the choice "
            "made on the training draws is among the best, not alone at the top."
            + _x_only(r))
    return " ".join(parts)


def _x_only(r) -> str:
    """The sentence on the best fixed controller reading x alone (stored studies that have it)."""
    from fdsc.paper.shared.prose import pct
    from fdsc.paper.shared.stats import median_ci_words

    name = r.get("fixed_in_advance_x")
    if not name or name == r["fixed_in_advance"]:
        return ""
    q = np.asarray(r["fixed_ratio"][name], dtype=float)
    more = pct(float(np.mean(q > 1.0)))
    return (f" The best fixed controller reading x alone, *{name}*, has a median "
            f"{median_ci_words(q)} the energy of the chosen one (more on {more} "
            "of the draws): knowing the disturbance estimate pays by itself.")
