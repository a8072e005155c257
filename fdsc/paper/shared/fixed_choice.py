"""The fixed controller chosen in advance of each example, as the full study chose it (stored).

Part II's full study (``python -m fdsc disturbance-law --replace``) chooses, per example, the
fixed controller of least mean log energy over the training half of its draws among every fixed
controller (chapter 'fixed_controllers'), and stores its name, family and matrices in the
package data file ``fdsc/paper/data/fixed_in_advance.json`` with the commit and the sources'
fingerprint it was computed at. Every "does it pay" of the book is judged against it: the
chapters of Part I read it here (they cannot import Part II), those of Part II too. A test
checks it against the stored study, and the record's subset recomputes the choice's procedure.
"""

from __future__ import annotations

import json
from importlib import resources

import numpy as np

import fdsc
from fdsc._validation import as_choice

__all__ = ["FILE", "stored_choice", "fixed_in_advance", "write_choice", "NAME"]

#: The package data file of the stored choice.
FILE = "fixed_in_advance.json"
#: How the book names it.
NAME = "the fixed controller chosen in advance"


def stored_choice() -> dict:
    """The stored file: ``{"commit", "fingerprint", "n", "seed", example: {"name", "family",
    "states", "reads_estimate", "matrices"}}``.

    Returns
    -------
    dict

    Raises
    ------
    FileNotFoundError
        If the full study has never been stored.
    """
    path = resources.files("fdsc.paper") / "data" / FILE
    return json.loads(path.read_text(encoding="utf-8"))


def _controller(m, name):
    D = np.asarray(m["D"], dtype=float)
    A = np.asarray(m["A"], dtype=float).reshape(len(m["A"]), -1) if m["A"] else np.zeros((0, 0))
    B = np.asarray(m["B"], dtype=float).reshape(A.shape[0], -1) if A.size else np.zeros((0, D.shape[1]))
    C = np.asarray(m["C"], dtype=float).reshape(D.shape[0], -1)
    E, F = (m["E"], m["F"]) if "E" in m else (None, None)
    return fdsc.Controller(A, B, C, D, E=E, F=F, name=name)


def fixed_in_advance(example: str) -> tuple:
    """``(name, controller)`` of the example's fixed controller chosen in advance.

    Parameters
    ----------
    example : {"aircraft", "generic"}

    Returns
    -------
    name : str
    controller : fdsc.Controller

    Examples
    --------
    >>> name, c = fixed_in_advance("aircraft")
    >>> c.n_inputs, c.n_controls
    (2, 2)
    """
    as_choice("example", example, ("aircraft", "generic"))
    r = stored_choice()[example]
    return r["name"], _controller(r["matrices"], r["name"])


def write_choice(full: dict, path) -> dict:
    """Write the stored choice of a full study (the CLI's ``--replace`` does).

    Parameters
    ----------
    full : dict
        The full study.
    path : path
        The file to write (the package data file).

    Returns
    -------
    dict
        What was written.
    """
    out = {k: full[k] for k in ("commit", "fingerprint", "n", "seed")}
    for example in ("aircraft", "generic"):
        r = full[example]
        name = r["fixed_in_advance"]
        c = r["fixed_controllers"][name]
        out[example] = {"name": name, "family": c["family"], "states": c["states"],
                        "reads_estimate": c["reads_estimate"], "matrices": c["matrices"]}
    from pathlib import Path

    Path(path).write_text(json.dumps(out, indent=1) + "\n", encoding="utf-8")
    return out
