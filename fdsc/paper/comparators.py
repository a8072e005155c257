"""The one comparator set: the fixed controllers that every "best fixed" statement of the book,
the claims checklist and the report compares against.

On the aircraft these are the open loop (K = 0), the paper's three fixed gains (PassC-EF = K_e,
PassC-LF = K_f1, PassC-HF = K_f3) and the best certified HF design (the printed K_f3 is not the
best HF design its own LMIs allow: chapter 'passive_controllers'); on the generic example, the open
loop and its three designs (H∞, LF, HF). "The best fixed controller" of a case is the member of
the set with the least output energy in that case; comparisons among the paper's four controllers
only are said so in words ("among the paper's four controllers").

The record's entry ``comparators`` names the set of each example and, for each family of cases,
how often each member is the best.
"""

from collections.abc import Mapping

import numpy as np

from .examples import OPEN_LOOP
from .results import RecordPart, entry

__all__ = ["HF_BEST", "COMPARATORS", "DEFINITION", "PAPER_FOUR", "comparators", "best_fixed",
           "record_part"]

#: Name of the best certified HF design (:func:`fdsc.paper.passive_controllers.hf_best`).
HF_BEST = "HF best"

#: ``{example: the fixed controllers compared}``, in the order the book lists them.
COMPARATORS = {
    "aircraft": (OPEN_LOOP, "PassC-EF", "PassC-LF", "PassC-HF", HF_BEST),
    "generic": (OPEN_LOOP, "PassC-EF", "PassC-LF", "PassC-HF"),
}

#: The paper's own comparison (paper Figs. 4–8): not the comparator set.
PAPER_FOUR = ("PassC-EF", "PassC-LF", "PassC-HF", "FDSC")

#: The set in words, for the book's glossary and captions.
DEFINITION = ("the open loop (K = 0), PassC-EF (the H∞ gain), PassC-LF and PassC-HF, and, on the "
              "aircraft, the best certified HF design")


def comparators(example="aircraft"):
    """The comparator set of an example.

    Parameters
    ----------
    example : {"aircraft", "generic"}

    Returns
    -------
    tuple of str

    Raises
    ------
    ValueError
        If the example is not one of :data:`COMPARATORS`.

    Examples
    --------
    >>> comparators("generic")
    ('open loop', 'PassC-EF', 'PassC-LF', 'PassC-HF')
    """
    if example not in COMPARATORS:
        raise ValueError(f"example must be one of {tuple(COMPARATORS)}, but found {example!r}")
    return COMPARATORS[example]


def best_fixed(energy, example="aircraft"):
    """The best fixed controller of one case: the member of the comparator set of least energy.

    Parameters
    ----------
    energy : mapping of str to float or (m,) array_like
        ``{controller: ∫zᵀz}`` of one case, or of ``m`` cases (arrays); must hold every member
        of the set (it may hold more controllers, which are ignored).
    example : {"aircraft", "generic"}

    Returns
    -------
    name : str or (m,) ndarray of str
    energy : float or (m,) ndarray
        Ties go to the member listed first.

    Raises
    ------
    KeyError
        If a member of the set is missing from ``energy`` (named).
    TypeError
        If ``energy`` is not a mapping.

    Examples
    --------
    >>> best_fixed({"open loop": 3.0, "PassC-EF": 2.0, "PassC-LF": 1.0, "PassC-HF": 5.0,
    ...             "HF best": 4.0, "FDSC": 0.5})
    ('PassC-LF', 1.0)
    """
    if not isinstance(energy, Mapping):
        raise TypeError(f"energy must be a mapping of controller to energy, but found "
                        f"{type(energy).__name__}")
    names = comparators(example)
    missing = [n for n in names if n not in energy]
    if missing:
        raise KeyError(f"energy lacks the comparators {missing} of the {example} example "
                       f"(the set is {names})")
    stack = np.array([np.asarray(energy[n], dtype=float) for n in names])
    k = np.argmin(stack, axis=0)
    if stack.ndim == 1:
        return names[int(k)], float(stack[int(k)])
    return np.array(names)[k], stack[k, np.arange(stack.shape[1])]


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
    from .baselines import baselines
    from .generic_example import generic_study
    from .monte_carlo import monte_carlo

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
