"""Part II of the book, *Does FDSC pay?*: one entry module per chapter, named like its notebook.

``baselines`` (the paper's cases against the comparator set), ``generic_example`` (a plant where
band-limited design matters), ``monte_carlo`` (seeded random tones: a study outside the book, the
scale-out example's), ``disturbance_law`` (a law on
the disturbance estimate; ``disturbance_law_draws``, ``disturbance_law_robust``), the record's
entry on the comparator set (``comparator_wins``) and the part's figures (``plotting_pays``,
``plotting_generic``, ``plotting_law``).

A module here imports the library, :mod:`fdsc.paper.shared`, Part I and this part only.
"""

__all__ = []  # used through its modules
