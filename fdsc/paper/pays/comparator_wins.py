"""The record's entry ``comparators``: the comparator set of each example and, for each family
of cases, how often each member is the best (chapter 'simulations' shows it).
"""

import numpy as np

from fdsc.paper.pays.baselines import baselines
from fdsc.paper.pays.fixed_designs import FAMILIES
from fdsc.paper.pays.generic_example import generic_study
from fdsc.paper.pays.stored_study import load_full
from fdsc.paper.shared.comparators import DEFINITION, best_fixed, comparators
from fdsc.paper.shared.fixed_choice import fixed_in_advance
from fdsc.paper.shared.results import RecordPart, entry

__all__ = ["record_part"]


def _counts(winners, names):
    winners = list(np.atleast_1d(winners))
    return {n: int(sum(w == n for w in winners)) for n in names}


def record_part():
    """Record entry ``comparators`` (new): the set of each example, and who is best where.

    For the aircraft, every simulation case of the paper (the stationary LF and HF cases and the
    ρ_p and ρ_t grids of paper Figs. 7 and 8); for the generic example, its stationary cases
    and its two sweeps.

    Returns
    -------
    RecordPart
    """
    air, gen = comparators("aircraft"), comparators("generic")
    base = baselines()
    best = {"aircraft": {}, "generic": {}}
    for family in ("stationary", "mixed", "piecewise"):
        scen = base.family(family)
        best["aircraft"][family] = _counts([best_fixed(s.energy, "aircraft")[0] for s in scen], air)
    study = generic_study()
    for family, comp in (("stationary", study.stationary), ("mixed", study.rho_p_sweep),
                         ("piecewise", study.rho_t_sweep)):
        best["generic"][family] = _counts(best_fixed(comp.energy, "generic")[0], gen)
    n_cases = sum(best["aircraft"][f][n] for f in ("stationary", "mixed", "piecewise") for n in air)
    wins = {n: sum(best["aircraft"][f][n] for f in ("stationary", "mixed", "piecewise")) for n in air}
    every, chosen = {}, {}
    full = load_full()
    for example in ("aircraft", "generic"):
        # every fixed controller of Part II, as the stored study designed them
        fc = full[example]["fixed_controllers"] if full is not None else {}
        every[example] = {fam: [n for n, v in fc.items() if v["family"] == fam] for fam in FAMILIES}
        chosen[example] = fixed_in_advance(example)[0]
    note = (f"the comparator set of the paper's setting: {DEFINITION}. Over the {n_cases} simulation "
            "cases of the paper on the aircraft its best member is "
            + ", ".join(f"{n} in {k}" for n, k in wins.items() if k)
            + ". Every fixed controller of Part II (by family), and the one chosen in advance (stored "
            "choice of the full study): " + ", ".join(f"{e} {c}" for e, c in chosen.items()) + ".")
    return RecordPart((entry(
        "comparators", "our definition (the fixed controllers every comparison is made against)", None,
        {e: {"names": list(comparators(e)), "best": best[e], "every_fixed_controller": every[e],
             "chosen_in_advance": chosen[e]} for e in ("aircraft", "generic")}, "new", note),))
