"""Chapter 'fixed_controllers': the strongest fixed controllers of each example for its class of
non-stationary disturbances, and the one chosen in advance that every "does it pay" of Part II
is judged against (the designs: :mod:`fdsc.paper.pays.fixed_designs`, re-exported here).
"""

from __future__ import annotations

import math

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
           "law_front_gains", "dynamic_front", "record_part", "N_RECORD"]

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
