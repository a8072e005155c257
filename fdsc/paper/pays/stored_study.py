"""The stored full study of Part II: where it lies, how it is read, and its fixed controllers
rebuilt from it; and one way to map the study's draws over an executor (shared by the law's
study, the ladder and its variants).
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np

from fdsc._validation import as_choice, as_finite_real, as_matrix
from fdsc.paper.pays.fixed_designs import FixedSet, best_found

__all__ = ["FULL_FILE", "map_draws", "submit_draws", "load_full", "stored_fixed_set"]

#: Where the full study is stored (relative to the repository root).
FULL_FILE = Path("book") / "data" / "disturbance_law_full.json"


def map_draws(fn, args, executor):
    """``[fn(*a) for a in args]``, here, on a concurrent.futures executor or on a Dask client.

    Parameters
    ----------
    fn : callable
    args : list of tuple
    executor : Executor or dask.distributed.Client or None

    Returns
    -------
    list
    """
    if executor is None:
        return [fn(*a) for a in args]
    if hasattr(executor, "gather"):                 # a dask.distributed Client
        return executor.gather([executor.submit(fn, *a, pure=False) for a in args])
    return list(executor.map(fn, *zip(*args, strict=True)))


class Pending:
    """Runs submitted by :func:`submit_draws`; :meth:`result` waits for them, in order."""

    def __init__(self, fn, args, futures, executor):
        self._fn, self._args, self._futures, self._executor = fn, args, futures, executor

    def result(self) -> list:
        """``[fn(*a) for a in args]`` (here, now, without an executor)."""
        if self._futures is None:
            return [self._fn(*a) for a in self._args]
        if hasattr(self._executor, "gather"):
            return self._executor.gather(self._futures)
        return [f.result() for f in self._futures]


def submit_draws(fn, args, executor) -> Pending:
    """:func:`map_draws` without waiting: the runs start on the executor now and
    :meth:`Pending.result` collects them (without an executor they run when it is called), so that
    a few long runs share the workers with the next map instead of leaving one idle.

    Parameters
    ----------
    fn : callable
    args : list of tuple
    executor : Executor or dask.distributed.Client or None

    Returns
    -------
    Pending
    """
    if executor is None:
        return Pending(fn, args, None, None)
    if hasattr(executor, "gather"):
        return Pending(fn, args, [executor.submit(fn, *a, pure=False) for a in args], executor)
    return Pending(fn, args, [executor.submit(fn, *a) for a in args], executor)


def _stored_example(full, example) -> dict:
    """The stored study of one example, refused by name (which key is missing) if ``full`` is not
    a stored study holding it."""
    example = as_choice("example", example, ("aircraft", "generic"))
    if not isinstance(full, dict):
        raise TypeError(f"full must be the stored full study (the dict load_full returns), but found "
                        f"{type(full).__name__}" + (" (load_full() returns None outside a checkout "
                                                     "of the repository)" if full is None else ""))
    missing = [k for k in ("n", "seed", example) if k not in full]
    if missing:
        raise KeyError(f"full: the stored study has no key {missing[0]!r} (found {sorted(full)})")
    r = full[example]
    for key in ("fixed_controllers", "fixed_in_advance", "pairs", "law", "test_indices", "fixed_ratio"):
        if key not in r:
            raise KeyError(f"full[{example!r}]: the stored study has no key {key!r}")
    if r["fixed_in_advance"] not in r["fixed_controllers"]:
        raise KeyError(f"full[{example!r}]['fixed_in_advance'] names {r['fixed_in_advance']!r}, which "
                       f"has no stored controller in full[{example!r}]['fixed_controllers']")
    return r


#: The stored peaks and sizes of a fixed controller (:attr:`FixedSet.info`).
_INFO = ("lf", "hf", "hinf", "states", "size", "reads_estimate", "slowest", "expected_power")


def stored_fixed_set(full: dict, example: str) -> FixedSet:
    """The fixed controllers of a stored full study, rebuilt from their stored matrices (to
    recompute stored draws without redoing the designs).

    Parameters
    ----------
    full : dict
        The full study (:func:`load_full`).
    example : {"aircraft", "generic"}

    Returns
    -------
    FixedSet
        With the stored names, families, band peaks, scores, choice and pairs; no tuning details.

    Raises
    ------
    TypeError
        If ``full`` is not a dict (e.g. None: :func:`load_full` outside a checkout).
    ValueError
        If ``example`` is not one of the two examples, or a stored controller's matrices or
        score are not finite numbers of consistent shapes (naming the controller).
    KeyError
        Naming the key the stored study lacks (the example, ``fixed_in_advance``'s controller,
        or a controller's matrix, family, score or peaks).
    """
    r = _stored_example(full, example)
    fc, pairs_stored = r["fixed_controllers"], r["pairs"]
    where = f"full[{example!r}]"
    for key, value in (("fixed_controllers", fc), ("pairs", pairs_stored)):
        if not isinstance(value, dict) or (key == "fixed_controllers" and not value):
            raise ValueError(f"{where}[{key!r}] must be a non-empty object of controllers, but found "
                             f"{type(value).__name__}" + (" (empty)" if isinstance(value, dict) else ""))
    names = tuple(fc)
    info, family, score, ctrls = {}, {}, {}, {}
    for k, v in fc.items():
        at = f"{where}['fixed_controllers'][{k!r}]"
        if not isinstance(v, dict):
            raise ValueError(f"{at} must be an object, but found {type(v).__name__}")
        for key in ("family", "train_score", "matrices", *_INFO):
            if key not in v:
                raise KeyError(f"{at}: the stored study has no key {key!r}")
        info[k] = {x: v[x] for x in _INFO}
        family[k] = v["family"]
        score[k] = as_finite_real(f"{at}['train_score']", v["train_score"])
        ctrls[k] = _stored_controller(v["matrices"], k, f"{at}['matrices']")
    pairs = {}
    for f, p in pairs_stored.items():
        at = f"{where}['pairs'][{f!r}]"
        if not isinstance(p, list) or len(p) != 2:
            raise ValueError(f"{at} must be a pair of controllers (LF, HF), but found {p!r:.80}")
        pairs[f] = tuple(_stored_controller(m, f"{f} for {t} segments", f"{at}[{j}]")
                         for j, (m, t) in enumerate(zip(p, ("LF", "HF"), strict=True)))
    x_only = [k for k in names if not ctrls[k].reads_estimate]
    if not x_only:
        raise ValueError(f"{where}['fixed_controllers'] has no controller that reads x alone (the best "
                         "fixed controller (x) is chosen among them)")
    chosen_x = min(x_only, key=lambda k: (score[k], names.index(k)))
    return FixedSet(example, full["n"], full["seed"], 0, names, ctrls, family, info, score,
                    r["fixed_in_advance"], [], {}, pairs, {}, {}, None, chosen_x,
                    best_found(names, family, ctrls, score))


def _stored_controller(m, name, at):
    """The controller of stored matrices ``m``; a missing matrix, a non-numeric or non-finite
    entry or inconsistent shapes are refused naming ``at`` (where in the study it lies)."""
    import fdsc

    if not isinstance(m, dict):
        raise ValueError(f"{at} must be an object of matrices, but found {type(m).__name__}")
    for key in ("A", "B", "C", "D", *(("F",) if "E" in m else ()), *(("E",) if "F" in m else ())):
        if key not in m:
            raise KeyError(f"{at}: the stored study has no matrix {key!r}")
    try:
        D = as_matrix("D", m["D"])
        outputs, inputs = D.shape
        k = len(m["A"])                             # the controller's states (none: A = [])
        A = as_matrix("A", m["A"], (k, k)) if k else np.zeros((0, 0))
        B = as_matrix("B", m["B"], (k, inputs)) if k else np.zeros((0, inputs))
        C = as_matrix("C", m["C"], (outputs, k)) if k else np.zeros((outputs, 0))
        E, F = (m["E"], m["F"]) if "E" in m else (None, None)
        return fdsc.Controller(A, B, C, D, E=E, F=F, name=name)
    except (ValueError, TypeError) as exc:
        raise ValueError(f"{at}: the stored matrices of {name!r} do not make a controller ({exc})") from None


def load_full(path=None):
    """The full study written by :func:`full_study`.

    Parameters
    ----------
    path : path, optional
        Default :data:`FULL_FILE` in the repository this package lies in (whatever the working
        directory).

    Returns
    -------
    dict or None
        None if ``path`` is not given and the default file is absent (outside a checkout of the
        repository: the book and the findings then fall back on the record).

    Raises
    ------
    TypeError
        If ``path`` is not a str or os.PathLike.
    FileNotFoundError
        If an explicit ``path`` is not a file, naming it.
    ValueError
        If the file is not UTF-8 text (a binary file), not valid JSON (e.g. truncated), naming
        it and where it breaks, or JSON that is not an object (a study is one).
    """
    if path is None:
        path = Path(__file__).resolve().parents[3] / FULL_FILE
        if not path.is_file():
            return None
    if not isinstance(path, str | os.PathLike):
        raise TypeError(f"path must be the stored study's file (a str or os.PathLike), but found "
                        f"{type(path).__name__}")
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"path: the stored study {path} does not exist (or is not a file)")
    try:
        full = json.loads(path.read_text(encoding="utf-8"))
    except UnicodeDecodeError as exc:
        raise ValueError(f"path: the stored study {path} is not UTF-8 text (byte {exc.start} cannot be "
                         "decoded): a binary or damaged file? rerun python -m fdsc disturbance-law") from None
    except json.JSONDecodeError as exc:
        raise ValueError(f"path: the stored study {path} is not valid JSON ({exc.msg} at line "
                         f"{exc.lineno}, column {exc.colno}): truncated or damaged? rerun python -m "
                         "fdsc disturbance-law") from None
    if not isinstance(full, dict):
        raise ValueError(f"path: {path} holds JSON but not a stored study (a {type(full).__name__}, where "
                         "an object with 'n', 'seed', 'aircraft' and 'generic' is expected)")
    return full
