"""The record's entry ``comparators``: the comparator set of each example and, for each family
of cases, how often each member is the best (chapter 'baselines' shows it).
"""

import numpy as np

from fdsc.paper.pays.baselines import baselines
from fdsc.paper.pays.generic_example import generic_study
from fdsc.paper.pays.monte_carlo import monte_carlo
from fdsc.paper.shared.comparators import DEFINITION, best_fixed, comparators
from fdsc.paper.shared.results import RecordPart, entry

__all__ = ["record_part"]


def _counts(winners, names):
    winners = list(np.atleast_1d(winners))
    return {n: int(sum(w == n for w in winners)) for n in names}


def record_part():
    """Record entry ``comparators`` (new): the set of each example, and who is best where.

    For the aircraft, every simulation case of the paper (the stationary LF and HF cases and the
    ρ_p and ρ_t grids of paper Figs. 7 and 8) and the Monte-Carlo tone draws; for the generic
    example, its stationary cases, its two sweeps and its tone draws.

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
    for example, key in (("aircraft", "aircraft"), ("generic", "generic")):
        mc = monte_carlo(example)
        best[key]["monte carlo tones"] = _counts(best_fixed(mc.energy, example)[0],
                                                 comparators(example))
    n_cases = sum(best["aircraft"][f][n] for f in ("stationary", "mixed", "piecewise") for n in air)
    wins = {n: sum(best["aircraft"][f][n] for f in ("stationary", "mixed", "piecewise")) for n in air}
    note = (f"the fixed controllers that every 'best fixed' statement compares against: "
            f"{DEFINITION}. Over the {n_cases} simulation cases of the paper on the aircraft the "
            "best is " + ", ".join(f"{n} in {k}" for n, k in wins.items() if k) + ".")
    return RecordPart((entry(
        "comparators", "our definition (the fixed controllers of every 'best fixed' statement)", None,
        {"aircraft": {"names": list(air), "best": best["aircraft"]},
         "generic": {"names": list(gen), "best": best["generic"]}}, "new", note),))
