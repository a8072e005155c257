"""The reproduction record: every printed number beside ours, with a verdict.

``python -m fdsc reproduce --out DIR`` writes :func:`reproduction_record` to
``DIR/reproduction.json``; the book's introduction renders the same entries.
"""


from . import (
    baselines,
    claims,
    frequency_ranges,
    frequency_selective,
    generic_example,
    gkyp_lemma,
    inputs,
    monte_carlo,
    nonstationary,
    passive_controllers,
    stationary,
    switching_law,
    theorem1,
    theorem1_counterexamples,
    three_mode,
    wellposed,
)
from .cache import cached, shared_results
from .environment import environment
from .names import FIGURE_IDS
from .results import RecordPart

__all__ = [
    "reproduction_record",
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
    3: ("sigma_max of the closed loops with K_f1, K_f2, K_f3, K_e", "passive_controllers"),
    4: ("q, delta_E, delta_PTV under the LF disturbance, four controllers", "stationary"),
    5: ("the same under the HF disturbance", "stationary"),
    6: ("L2-induced norm over time under the HF disturbance", "stationary"),
    7: ("output energy over [0, 500] against rho_p (mixed disturbance)", "nonstationary"),
    8: ("output energy over [0, 1000 + 500 rho_t] against rho_t (piecewise disturbance)",
        "nonstationary"),
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
            baselines, generic_example, monte_carlo)


@cached
def reproduction_record():
    """The reproduction record ``{"entries": [...], "figures": {...}, "claims": [...],
    "environment": {...}}``.

    The sum of the chapters' record parts (each chapter's ``record_part()``), in the order of
    :data:`CHAPTERS`, the claims checklist (:func:`fdsc.paper.claims.claims_checklist`) with its
    step-halving entry, and the environment. The format is the JSON Schema
    ``fdsc/paper/data/record.schema.json``.

    Returns
    -------
    dict
    """
    with shared_results():  # the chapters and the claims ask for the same runs: compute them once
        part = RecordPart()
        for chapter in CHAPTERS:
            part = part + chapter.record_part()
        part = part + claims.halving_record()
        checklist = [row.to_dict() for row in claims.claims_checklist()]
    return {"entries": list(part.entries), "figures": dict(part.figures), "claims": checklist,
            "environment": environment()}
