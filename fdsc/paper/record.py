"""The reproduction record: every printed number beside ours, with a verdict.

``python -m fdsc reproduce --out DIR`` writes :func:`reproduction_record` to
``DIR/reproduction.json``; the book's landing page reads its findings from it and the report
renders every entry. The chapters are computed by several processes at once (:data:`JOBS_ENV`),
which share their results through the cache folder (:func:`fdsc.paper.shared.cache.shared_results`).
"""

import importlib
import multiprocessing
import os
from concurrent.futures import ProcessPoolExecutor

from fdsc.paper.pays import (
    baselines,
    comparator_wins,
    disturbance_law,
    fixed_controllers,
    generic_example,
    ladder,
)
from fdsc.paper.repairs import theorem1_counterexamples, three_mode, wellposed
from fdsc.paper.reproduced import (
    claims,
    frequency_ranges,
    frequency_selective,
    gkyp_lemma,
    nonstationary,
    passive_controllers,
    stationary,
    switching_law,
    theorem1,
)
from fdsc.paper.shared import inputs
from fdsc.paper.shared.cache import cached, shared_results, worker_threads
from fdsc.paper.shared.environment import environment
from fdsc.paper.shared.names import FIGURE_IDS
from fdsc.paper.shared.results import RecordPart

__all__ = [
    "reproduction_record",
    "JOBS_ENV",
    "record_jobs",
    "chapter_parts",
    "FIGURE_IDS",
    "CHAPTERS",
    "PAPER_FIGURES",
    "figure_status",
]


#: Every figure of the paper (compiled numbering): what it shows and the chapter that redraws it
#: (None: not redrawn yet).
PAPER_FIGURES = {
    1: ("the closed loop with FDSC (block diagram)", "switching_law"),
    2: ("code and data availability box (no data)", None),
    3: ("sigma_max of the closed loops with K_f1, K_f2, K_f3, K_e", "gkyp_lemma"),
    4: ("q, delta_E, delta_PTV under the LF disturbance, four controllers", "simulations"),
    5: ("the same under the HF disturbance", "simulations"),
    6: ("L2-induced norm over time under the HF disturbance", "simulations"),
    7: ("output energy over [0, 500] against rho_p (mixed disturbance)", "simulations"),
    8: ("output energy over [0, 1000 + 500 rho_t] against rho_t (piecewise disturbance)",
        "simulations"),
}


def figure_status(record):
    """One row per paper figure: number, content, chapter, record entry and status.

    Parameters
    ----------
    record : dict
        The reproduction record (its ``figures`` say which figures have data).

    Returns
    -------
    list of dict
        ``figure, shows, chapter, record_entry, status`` with status ``redrawn from recorded
        data``, ``drawn (no data)``, ``nothing to reproduce`` or ``not reproduced yet``.
    """
    by_number = {v["paper_figure"]: k for k, v in record["figures"].items() if "paper_figure" in v}
    rows = []
    for num, (shows, chapter) in PAPER_FIGURES.items():
        entry = by_number.get(num)
        if entry is not None:
            status = "redrawn from recorded data"
        elif chapter is not None:
            status = "drawn (no data)"
        elif num == 2:
            status = "nothing to reproduce"
        else:
            status = "not reproduced yet"
        rows.append({"figure": f"paper Fig. {num}", "shows": shows, "chapter": chapter or "",
                     "record_entry": entry or "", "status": status})
    return rows


#: The chapters that contribute to the record, in the record's order (first the printed inputs).
CHAPTERS = (inputs, frequency_ranges, gkyp_lemma, passive_controllers, frequency_selective, theorem1,
            theorem1_counterexamples, switching_law, stationary, nonstationary, wellposed, three_mode,
            fixed_controllers, baselines, generic_example, comparator_wins, disturbance_law,
            ladder)


#: The book page that computes each chapter module's entries (the report links to it); entries
#: listed in :data:`ENTRY_PAGES` are shown on another page than their module's.
PAGES = {"inputs": "frequency_ranges", "wellposed": "switching_law", "three_mode": "three_modes",
         "theorem1_counterexamples": "theorem1", "stationary": "simulations", "nonstationary": "simulations",
         "baselines": "simulations", "comparator_wins": "simulations", "fixed_controllers": "ladder",
         "disturbance_law": "ladder"}
ENTRY_PAGES = {"bound_f1": "printed_bounds", "bound_f2": "printed_bounds",
               "bound_f3": "printed_bounds", "bound_e": "printed_bounds"}


def entry_page(module_name, entry_id):
    """The book page (file stem) that computes an entry of a chapter module.

    Parameters
    ----------
    module_name : str
        The chapter module's name (``fdsc.paper.<chapter>``).
    entry_id : str
        The entry's id.

    Returns
    -------
    str

    Examples
    --------
    >>> entry_page("fdsc.paper.repairs.wellposed", "x")
    'switching_law'
    >>> entry_page("fdsc.paper.reproduced.passive_controllers", "bound_e")
    'printed_bounds'
    """
    short = module_name.rsplit(".", 1)[-1]
    return ENTRY_PAGES.get(entry_id, PAGES.get(short, short))


#: Environment variable: how many processes compute the record's chapters (default: the number
#: of CPUs, at most 4; 1 computes them in this process, one after the other).
JOBS_ENV = "FDSC_JOBS"

# the chapters that take longest are started first (a scheduling hint: the record does not
# depend on it); the others follow in the order of CHAPTERS
_LONGEST_FIRST = (nonstationary, passive_controllers, theorem1_counterexamples, wellposed,
                  ladder, fixed_controllers, frequency_selective, three_mode, generic_example,
                  disturbance_law, theorem1, baselines, stationary, gkyp_lemma)


def record_jobs():
    """The number of processes for the record: ``$FDSC_JOBS``, or the CPUs (at most 4).

    Returns
    -------
    int

    Raises
    ------
    ValueError
        If ``FDSC_JOBS`` is set to anything but a whole number ≥ 1.
    """
    value = os.environ.get(JOBS_ENV)
    if value is None or value == "":
        return max(1, min(os.cpu_count() or 1, 4))
    try:
        jobs = int(value)
    except ValueError:
        jobs = 0
    if jobs < 1:
        raise ValueError(f"{JOBS_ENV} must be a whole number of processes ≥ 1, found {value!r}")
    return jobs


def _chapter_part(name):
    return importlib.import_module(name).record_part()


def chapter_parts(chapters, jobs):
    """Every chapter's ``record_part()``, in the order given, computed by ``jobs`` processes.

    Parameters
    ----------
    chapters : sequence of module
        Chapter modules of :mod:`fdsc.paper` (each with ``record_part()``).
    jobs : int
        Processes (1: this process, one chapter after the other). The worker processes are
        started fresh (``spawn``) and inherit the environment, so inside
        :func:`~fdsc.paper.shared.cache.shared_results` they share the results folder; its per-key
        locks make a process that needs a result another one is computing wait for it. Each
        worker's BLAS and numba threads are capped so that the workers share the CPUs
        (:func:`~fdsc.paper.shared.cache.worker_threads`).

    Returns
    -------
    list of RecordPart
    """
    if jobs == 1 or len(chapters) < 2:
        return [chapter.record_part() for chapter in chapters]
    rank = {m.__name__: i for i, m in enumerate(_LONGEST_FIRST)}
    order = sorted(chapters, key=lambda m: rank.get(m.__name__, len(rank)))
    workers = min(jobs, len(chapters))
    with worker_threads(workers), ProcessPoolExecutor(
            workers, mp_context=multiprocessing.get_context("spawn")) as pool:
        futures = {m.__name__: pool.submit(_chapter_part, m.__name__) for m in order}
        return [futures[m.__name__].result() for m in chapters]


@cached
def reproduction_record():
    """The reproduction record ``{"entries": [...], "figures": {...}, "claims": [...],
    "environment": {...}}``.

    The sum of the chapters' record parts (each chapter's ``record_part()``, computed by
    :func:`record_jobs` processes: :func:`chapter_parts`), in the order of :data:`CHAPTERS`,
    the claims checklist (:func:`fdsc.paper.reproduced.claims.claims_checklist`) with its step-halving
    entry, and the environment. The format is the JSON Schema
    ``fdsc/paper/data/record.schema.json``.

    Returns
    -------
    dict
    """
    with shared_results():  # the chapters and the claims ask for the same runs: compute them once
        part, entries = RecordPart(), []
        for chapter, chapter_part in zip(CHAPTERS, chapter_parts(CHAPTERS, record_jobs()), strict=True):
            part = part + chapter_part
            entries += [{**e, "chapter": entry_page(chapter.__name__, e["id"])}
                        for e in chapter_part.entries]
        halving = claims.halving_record()
        part = part + halving
        entries += [{**e, "chapter": "report"} for e in halving.entries]
        checklist = [row.to_dict() for row in claims.claims_checklist()]
    return {"entries": entries, "figures": dict(part.figures), "claims": checklist,
            "environment": environment()}
