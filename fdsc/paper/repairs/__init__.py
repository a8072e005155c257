"""Part III of the book, *Repairs and extensions*: one entry module per chapter.

``wellposed`` (chapter 'wellposed_laws': paper Remarks 6 and 7; ``wellposed_regions``,
``wellposed_rules``), ``theorem1_counterexamples`` (``theorem1_cases``, ``theorem1_search``,
``theorem1_gap``, ``theorem1_witness``) and ``three_mode`` (chapter 'three_modes').

A module here imports the library, :mod:`fdsc.paper.shared`, Parts I and II and this part only.
"""

__all__ = []  # used through its modules
