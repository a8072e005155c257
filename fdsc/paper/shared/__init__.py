"""Shared machinery of the paper layer: what every part of the book uses, and nothing of any part.

The paper's data and setup (:mod:`.data`, the JSON files shipped as package data in
``fdsc/paper/data``), the one name map (:mod:`.names`), the one verdict rule (:mod:`.verdict`),
the printed inputs in the record (:mod:`.inputs`), what a chapter contributes to the record
(:mod:`.results`), the one number formatter of the prose (:mod:`.prose`), the one style map of
the figures (:mod:`.style`) and the paper's figures (:mod:`.plotting`, with :mod:`.plotting_runs`
and :mod:`.plotting_axes`), HTML tables (:mod:`.report`), the per-run results cache
(:mod:`.cache`), the versions of the build (:mod:`.environment`), an example plant with its
fixed and switched controllers (:mod:`.examples`), the one comparator set behind every "best
fixed" (:mod:`.comparators`), and the certified dwell time of the paper's two FDSC modes
(:mod:`.dwell_time`), which Parts II and III both quote.

Nothing here imports :mod:`fdsc.paper.reproduced`, :mod:`fdsc.paper.pays`,
:mod:`fdsc.paper.repairs` or :mod:`fdsc.paper.appendix` (``tests/paper/test_layout.py``).
"""

__all__ = []  # used through its modules
