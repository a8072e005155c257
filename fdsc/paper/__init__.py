"""The paper layer: the reproduction of Zhang, Heiland, Benner and Du, chapter by chapter.

One module per book chapter, named like its notebook (``frequency_ranges``, ``gkyp_lemma``,
``passive_controllers``, ``frequency_selective``, ``theorem1``, ``switching_law``,
``stationary``, ``environment``), plus the paper's data and setup (:mod:`fdsc.paper.data`,
shipped as package data), the name map (:mod:`fdsc.paper.names`), the verdict rule
(:mod:`fdsc.paper.verdict`), the reproduction record (:mod:`fdsc.paper.record`) and the
command line (:mod:`fdsc.paper.cli`). The library :mod:`fdsc` never imports this package.
"""

__all__ = []  # the layer is used through its modules (fdsc.paper.data, fdsc.paper.record, ...)
