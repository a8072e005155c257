"""Chapter 'ladder': does a switching law that decides on the disturbance estimate pay
against the strongest fixed controller, and what is switching worth at all?

Seeded non-stationary draws on both examples (:mod:`fdsc.paper.pays.disturbance_law_draws`): the
first half of a study's draws trains, the second scores. Against every law: the **fixed
controller chosen in advance** (least mean log energy over the training half among every fixed
controller of :func:`fdsc.paper.pays.fixed_designs.fixed_set`: the comparator set, the static
and dynamic fronts, the LQR gain, the H2 designs for the class's spectrum and the controllers
tuned on the class). The laws (:data:`fdsc.paper.pays.disturbance_law_runs.CANDIDATE_SETS`),
realized through copies, are tuned on the training half: the setting of least mean log energy
ratio among those that switch at most :data:`MAX_SWITCHES_PER_CHANGE` times per change of the
dominating band. The **value of switching** is the clairvoyant reference: the controllers
designed for each segment type, switched at the breaks. All energies are exact integrals from
rest; the paper's FDSC variants run on the library's simulator at 1 ms.

The full study (:data:`N_FULL` draws per example) runs behind ``python -m fdsc disturbance-law``
on a process pool or a Dask client and writes a file that the chapter and the record read; the
build rechecks a stated subset of it (:func:`recheck_law`: the chosen law on the first stored test
draws, recomputed from the stored controllers and the draws' seeds). :func:`study` runs the whole
procedure on a seeded subset of draws (the tuned designs with a shorter search), for whoever wants
to try it at other sizes.
"""

from __future__ import annotations

import math

import numpy as np

from fdsc._validation import as_count
from fdsc.paper.pays.disturbance_law_draws import (
    DECIDE_EVERY,
    HYSTERESES,
    IDEAL_PAIR,
    LAMBDAS,
    RESTART,
    SEED,
    certificate,
)
from fdsc.paper.pays.disturbance_law_full import (
    FULL_FILE,
    N_FULL,
    N_ROBUST,
    ROBUST_SNR_DB,
    full_study,
    load_full,
    measured_robustness,
    recheck_stored,
    robustness,
    stored_fixed_set,
)
from fdsc.paper.pays.disturbance_law_runs import draw_result, law_supervisor
from fdsc.paper.pays.disturbance_law_study import (
    HEADROOM_MIN,
    LAW_WORDS,
    MAX_SWITCHES_PER_CHANGE,
    TARGETS,
    Study,
    answer,
    choose,
    describe,
    law_key,
    share_words,
)
from fdsc.paper.pays.fixed_designs import fixed_set
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.results import RecordPart, entry

__all__ = ["SEED", "N_RECORD", "N_FULL", "LAMBDAS", "HYSTERESES", "DECIDE_EVERY", "RESTART", "FULL_FILE",
           "IDEAL_PAIR", "HEADROOM_MIN", "MAX_SWITCHES_PER_CHANGE", "TARGETS", "Study", "study",
           "rho_t_family", "record_part", "full_study", "load_full", "law_key", "N_ROBUST", "ROBUST_SNR_DB",
           "robustness", "measured_robustness", "certificate", "recheck_stored", "recheck_law",
           "N_RECHECK_LAW",
    "stored_fixed_set", "answer", "describe",
           "LAW_WORDS", "choose", "share_words"]

#: Draws per example of :func:`study`'s default subset (half train, half test).
N_RECORD = 12
#: Stored test draws per example on which the build recomputes the chosen law (:func:`recheck_law`).
N_RECHECK_LAW = 2


@cached
def study(example: str = "aircraft", n: int = N_RECORD, seed: int = SEED) -> Study:
    """The seeded study of one example (half of the draws train, half test).

    Parameters
    ----------
    example : {"aircraft", "generic"}
    n : int, optional
        Draws (≥ 4).
    seed : int, optional

    Returns
    -------
    Study
    """
    n = as_count("n", n, 4)
    fs = fixed_set(example, n, seed)
    return choose(example, [draw_result(example, i, seed, fs) for i in range(n)], seed, fs)


@cached
def rho_t_family(example: str, law: str) -> dict:
    """The paper's ρ_t family (the aircraft's T = 500 s; the generic example's own T) under a law,
    against the fixed controller chosen in advance, both from the stored study's controllers.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    law : str
        A setting.

    Returns
    -------
    dict
        ``{"rho_t": [...], "ratio_vs_fixed_in_advance": [...]}``.
    """
    from fdsc.paper.pays.generic_example import RHO_T, piecewise_disturbance
    from fdsc.paper.reproduced.nonstationary_sweeps import family_signal
    from fdsc.paper.shared.data import paper_data

    fs = stored_fixed_set(load_full(), example)
    sup, _names, lam, h = law_supervisor(example, law, fs)
    lo, hi = paper_data("simulation")["rho_t_range"]["value"]
    grid = np.linspace(lo, hi, 11) if example == "aircraft" else RHO_T
    out = {"rho_t": [], "ratio_vs_fixed_in_advance": []}
    for p in grid:
        d, horizon = family_signal("piecewise", p) if example == "aircraft" else piecewise_disturbance(p)
        horizon = math.ceil(horizon / DECIDE_EVERY - 1e-9) * DECIDE_EVERY
        prep = sup.prepare(d, horizon)
        r = prep.run(forgetting=lam, hysteresis=h)
        out["rho_t"].append(float(p))
        out["ratio_vs_fixed_in_advance"].append(r.energy / prep.energy_of(fs.controllers[fs.chosen]))
    return out


@cached
def recheck_law(example: str, k: int = N_RECHECK_LAW) -> dict:
    """The chosen law's energy over the fixed controller chosen in advance on the stored study's
    first ``k`` test draws, recomputed now from the stored controllers, setting and draw seeds.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    k : int, optional
        Test draws recomputed (≥ 1).

    Returns
    -------
    dict
        ``{"draws", "law", "ratios", "stored", "largest_difference"}`` (relative).

    Raises
    ------
    FileNotFoundError
        If the stored study is not in this checkout.
    ValueError
        If ``k`` is not a count between 1 and the stored test draws.
    """
    from fdsc.paper.pays.disturbance_law_draws import seeded_draw

    full = load_full()
    if full is None:
        raise FileNotFoundError("the stored full study is not in this checkout")
    r = full[example]
    k = as_count("k", k, 1)
    if k > len(r["test_indices"]):
        raise ValueError(f"k must be at most the {len(r['test_indices'])} stored test draws, but found {k}")
    fs = stored_fixed_set(full, example)
    sup, _names, lam, h = law_supervisor(example, law_key(r["law"]), fs)
    ratios = []
    for index in r["test_indices"][:k]:
        dr = seeded_draw(example, index, full["seed"])[1]
        prep = sup.prepare(dr.d, dr.horizon)
        law = prep.run(forgetting=lam, hysteresis=h).energy
        ratios.append(law / prep.energy_of(fs.controllers[fs.chosen]))
    stored = r["ratio_vs_fixed_in_advance"][:k]
    return {"draws": k, "law": r["law"], "ratios": ratios, "stored": stored,
            "largest_difference": float(max(abs(a / b - 1.0) for a, b in zip(ratios, stored, strict=True)))}


#: The stored study's summary of each example that the record entry carries (as stored).
STORED_SUMMARY = ("law", "fixed_in_advance", "fixed_in_advance_family", "draws_train", "draws_test",
                  "median_ratio_vs_fixed_in_advance", "p95_ratio_vs_fixed_in_advance",
                  "win_rate_vs_fixed_in_advance", "reference_family", "reference_median_ratio",
                  "reference_share_median", "fdsc_median_ratio", "switches_per_change",
                  "largest_control_step_median", "diverged", "certified", "certificate", "meets_targets")


def record_part() -> RecordPart:
    """Record entry ``supervisor`` (new): the stored study's law per example, the chosen law
    recomputed on its first test draws (:func:`recheck_law`) and along the ρ_t family."""
    full = load_full()
    if full is None:
        return RecordPart((entry("supervisor", "our computation (a law on the disturbance estimate)", None,
                                 None, "new", "the stored study is not in this checkout"),))
    sup = {}
    for example in ("aircraft", "generic"):
        r = full[example]
        sup[example] = {k: r[k] for k in STORED_SUMMARY if k in r} | {
            "recheck": recheck_law(example),
            "rho_t_ratio_vs_fixed_in_advance":
                rho_t_family(example, law_key(r["law"]))["ratio_vs_fixed_in_advance"]}
    note = (f"stored full study (commit {full['commit'][:12]}): the law on the disturbance estimate, tuned "
            f"on the first half of {full['n']} seeded non-stationary draws per example and scored on the "
            "second, against the fixed controller chosen in advance: "
            + "; ".join(f"{e}: median {v['median_ratio_vs_fixed_in_advance']:.3g}× {v['fixed_in_advance']}, "
                        f"wins {v['win_rate_vs_fixed_in_advance']:.0%}; clairvoyant switching "
                        f"{v['reference_median_ratio']:.3g}×" for e, v in sup.items())
            + f". The build recomputes the chosen law on the first {N_RECHECK_LAW} test draws of each "
              "example.")
    return RecordPart((entry("supervisor",
                             "our computation (a law on the disturbance estimate, stored study)", None, sup,
                             "new", note),))
