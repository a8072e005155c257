"""The paper layer: the reproduction of Zhang, Heiland, Benner and Du, laid out like the book.

Subpackages in the book's order, each holding one entry module per chapter (named like its
notebook: the chapter's ``record_part()`` and every public name of the chapter) with its sibling
modules (each at most 600 lines):

* :mod:`fdsc.paper.shared`: what every part uses (the paper's data, the name map, the verdict
  rule, record parts, prose, figure style and the paper's figures, the results cache, the
  examples and the one comparator set); it imports no part;
* :mod:`fdsc.paper.reproduced`: Part I, *The paper, reproduced*;
* :mod:`fdsc.paper.pays`: Part II, *Does FDSC pay?*;
* :mod:`fdsc.paper.repairs`: the repairs and extensions (told in Part I's chapters and an appendix);
* :mod:`fdsc.paper.appendix`: the reproduction report.

A part imports the library, the shared machinery and earlier parts, never a later one. Above
the parts: the reproduction record (:mod:`fdsc.paper.record`, the sum of the chapters' record
parts), the landing page's findings (:mod:`fdsc.paper.findings`) and the command line
(:mod:`fdsc.paper.cli`). ``tests/paper/test_layout.py`` keeps these rules.

The library :mod:`fdsc` never imports this package.
"""

__all__ = []  # the layer is used through its modules (fdsc.paper.shared.data, fdsc.paper.record, ...)
