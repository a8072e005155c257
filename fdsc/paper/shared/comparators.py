"""The one comparator set: the fixed controllers that every "best comparator" statement of the
book, the claims checklist and the report compares against.

On the aircraft these are the open loop (K = 0), the paper's three fixed gains (PassC-EF = K_e,
PassC-LF = K_f1, PassC-HF = K_f3) and the best certified HF design (the printed K_f3 is not the
best HF design its own LMIs allow: chapter 'passive_controllers'); on the generic example, the open
loop and its three designs (H∞, LF, HF). "The best comparator" of a case is the member of the
set with the least output energy in that case (Part II's "best fixed controller" is another
thing: the best fixed controller with equal information); comparisons among the paper's four controllers
only are said so in words ("among the paper's four controllers").

The record's entry ``comparators`` (who is best where) is computed in
:mod:`fdsc.paper.pays.comparator_wins`.
"""

from collections.abc import Mapping

import numpy as np

from fdsc.paper.shared.examples import OPEN_LOOP

__all__ = ["HF_BEST", "COMPARATORS", "DEFINITION", "PAPER_FOUR", "comparators", "best_fixed"]

#: Name of the best certified HF design (:func:`fdsc.paper.reproduced.passive_controllers.hf_best`).
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
    """The best comparator of one case: the member of the comparator set of least energy.

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
