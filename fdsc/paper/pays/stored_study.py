"""The stored full study of Part II: where it lies, how it is read, and its fixed controllers
rebuilt from it; and one way to map the study's draws over an executor (shared by the law's
study, the ladder and its variants).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from fdsc._validation import as_choice
from fdsc.paper.pays.fixed_designs import FixedSet

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
        If ``example`` is not one of the two examples.
    KeyError
        Naming the key the stored study lacks (the example, or ``fixed_in_advance``'s controller).
    """
    import fdsc

    r = _stored_example(full, example)

    def ctrl(m, name):
        E, F = (m["E"], m["F"]) if "E" in m else (None, None)
        A = np.asarray(m["A"], dtype=float).reshape(len(m["A"]), -1) if m["A"] else np.zeros((0, 0))
        n = len(m["D"][0])
        B = np.asarray(m["B"], dtype=float).reshape(A.shape[0], -1) if A.size else np.zeros((0, n))
        C = np.asarray(m["C"], dtype=float).reshape(len(m["D"]), -1)
        return fdsc.Controller(A, B, C, np.asarray(m["D"], dtype=float), E=E, F=F, name=name)

    fc = r["fixed_controllers"]
    names = tuple(fc)
    info = {k: {x: v[x] for x in ("lf", "hf", "hinf", "states", "size", "reads_estimate", "slowest")}
            for k, v in fc.items()}
    pairs = {f: tuple(ctrl(m, f"{f} for {t} segments") for m, t in zip(p, ("LF", "HF"), strict=True))
             for f, p in r["pairs"].items()}
    ctrls = {k: ctrl(v["matrices"], k) for k, v in fc.items()}
    x_only = [k for k in names if not ctrls[k].reads_estimate]
    chosen_x = min(x_only, key=lambda k: (fc[k]["train_score"], names.index(k)))
    return FixedSet(example, full["n"], full["seed"], 0, names, ctrls,
                    {k: v["family"] for k, v in fc.items()}, info,
                    {k: v["train_score"] for k, v in fc.items()}, r["fixed_in_advance"], [], {}, pairs,
                    {}, {}, None, chosen_x)


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
    FileNotFoundError
        If an explicit ``path`` is not a file, naming it.
    ValueError
        If the file is not valid JSON (e.g. truncated), naming it and where the JSON breaks.
    """
    if path is None:
        path = Path(__file__).resolve().parents[3] / FULL_FILE
        if not path.is_file():
            return None
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"path: the stored study {path} does not exist (or is not a file)")
    try:
        return json.loads(path.read_text(encoding="utf-8"))
    except json.JSONDecodeError as exc:
        raise ValueError(f"path: the stored study {path} is not valid JSON ({exc.msg} at line "
                         f"{exc.lineno}, column {exc.colno}): truncated or damaged? rerun python -m "
                         "fdsc disturbance-law") from None
