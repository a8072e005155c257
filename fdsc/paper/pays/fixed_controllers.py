"""Chapter 'fixed_controllers': the strongest fixed controllers of each example for its class of
non-stationary disturbances, and the one chosen in advance that every "does it pay" of Part II
is judged against (the designs: :mod:`fdsc.paper.pays.fixed_designs`, re-exported here).
"""

from __future__ import annotations

import math

import numpy as np

import fdsc
from fdsc.paper.pays.disturbance_law_draws import SEED, _example
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
from fdsc.paper.shared.results import RecordPart, entry

__all__ = ["N_TUNE", "CAP_FACTOR", "FRONT_POINTS", "DYN_RATIOS", "U_PENALTY", "TUNE_MAXITER",
           "RECORD_MAXITER", "FAMILIES", "FixedSet", "fixed_set", "tuning_draws", "static_front",
           "law_front_gains", "dynamic_front", "record_part", "N_RECORD", "family_summary", "answer"]

#: Draws of the record's study (the same as chapter 'disturbance_law''s record subset).
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


def record_part(n: int = N_RECORD, seed: int = SEED) -> RecordPart:
    """Record entries ``pareto_front``, ``dynamic_front`` and ``fixed_controllers`` (new).

    Parameters
    ----------
    n, seed : int, optional
        The study whose training half chooses (the record's subset).

    Returns
    -------
    RecordPart
    """
    fronts, dyn, fixed = {}, {}, {}
    for example in ("aircraft", "generic"):
        front, checks = static_front(example)
        fronts[example] = [{"beta": float(b), "gamma_hf": None if p is None else float(p.peak[0]),
                            "gamma_lf": None if p is None else float(p.peak[1]),
                            "certified": None if p is None else p.certified,
                            "dominated_by_search": c["dominated"]}
                           for b, p, c in zip(front.betas, front.points, checks, strict=True)]
        fs = fixed_set(example, n, seed)
        dyn[example] = [{"ratio": float(r), "gamma_lf": _finite(fs.info[f"weighted H∞ {j + 1}"]["lf"])
                         if f"weighted H∞ {j + 1}" in fs.info else None,
                         "gamma_hf": _finite(fs.info[f"weighted H∞ {j + 1}"]["hf"])
                         if f"weighted H∞ {j + 1}" in fs.info else None,
                         "states": fs.info.get(f"weighted H∞ {j + 1}", {}).get("states")}
                        for j, r in enumerate(DYN_RATIOS)]
        fixed[example] = {"chosen": fs.chosen, "tuning_draws": fs.n_tune,
                          "controllers": {k: {"family": fs.family[k], "gamma_lf": _finite(fs.info[k]["lf"]),
                                              "gamma_hf": _finite(fs.info[k]["hf"]),
                                              "hinf": _finite(fs.info[k]["hinf"]),
                                              "states": fs.info[k]["states"],
                                              "reads_estimate": fs.info[k]["reads_estimate"],
                                              "train_mean_log_energy": _finite(fs.train_score[k])}
                                          for k in fs.names},
                          "design_checks": fs.design_checks}
    best = {e: fixed[e]["chosen"] for e in fixed}
    note_f = (f"the static front: {FRONT_POINTS} gains of least HF peak with the LF peak at most β (a direct "
              "search, each point certified by Lemma 1 and checked against a second search for a gain "
              "that beats it in both bands).")
    note_d = ("frequency-weighted H∞ state feedback (band weights on z, the H∞ LMI on the weighted plant) at "
              f"{len(DYN_RATIOS)} ratios of the LF to the HF weight: controllers with states.")
    note_x = ("every fixed controller of the study (comparator set, static and dynamic fronts, LQR, H2 "
              "for the class's spectrum, tuned on the class) with its band peaks and its mean log energy "
              f"over the record's {n // 2} training draws; chosen in advance: "
              + ", ".join(f"{e} {v}" for e, v in best.items()) + ".")
    return RecordPart((
        entry("pareto_front", "our computation (multi-band synthesis)", None, fronts, "new", note_f),
        entry("dynamic_front", "our computation (weighted H∞ synthesis)", None, dyn, "new", note_d),
        entry("fixed_controllers", "our computation (the strongest fixed controllers)", None, fixed, "new",
              note_x),
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
