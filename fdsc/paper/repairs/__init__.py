"""The repairs and extensions, a layer after Parts I and II: told in Part I's chapters on the
switching law and on Theorem 1 and in the appendix on three modes.

``wellposed`` (chapter 'switching_law', its repairs: paper Remarks 6 and 7; ``wellposed_regions``,
``wellposed_rules``), ``theorem1_counterexamples`` (chapter 'theorem1', its tests;
``theorem1_cases``, ``theorem1_search``, ``theorem1_gap``, ``theorem1_witness``) and ``three_mode``
(appendix 'three_modes').

A module here imports the library, :mod:`fdsc.paper.shared`, the layers of Parts I and II and this
layer only.
"""

__all__ = []  # used through its modules
