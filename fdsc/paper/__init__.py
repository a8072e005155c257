"""The paper layer: the reproduction of Zhang, Heiland, Benner and Du, chapter by chapter.

One entry module per book chapter, named like its notebook: it holds the chapter's
``record_part()`` and re-exports every public name of the chapter, whose code may live in
sibling modules (each at most 600 lines). By the book's parts:

* I. The paper, reproduced: ``frequency_ranges`` (with ``dominance``, ``paley_wiener``,
  ``proposition1``), ``gkyp_lemma`` (``gamma_slip``), ``passive_controllers``
  (``passive_gains``, ``passive_sensitivity``, ``passive_crosscheck``), ``frequency_selective``
  (``proposition1_cases``, ``fd_epf``), ``switching_law``, ``theorem1``
  (``theorem1_statement1``, ``theorem1_statements23``), ``stationary`` (``stationary_figures``,
  ``stationary_claims``), ``nonstationary`` (``nonstationary_sweeps``,
  ``nonstationary_objectives``);
* II. Does FDSC pay?: ``baselines``, ``generic_example``, ``monte_carlo``, ``examples``,
  ``comparators``;
* III. Repairs and extensions: ``wellposed`` (``wellposed_regions``, ``wellposed_rules``),
  ``dwell_time``, ``theorem1_counterexamples`` (``theorem1_cases``, ``theorem1_search``,
  ``theorem1_gap``, ``theorem1_witness``), ``three_mode``;
* appendices: ``reproduction_report``, ``printed_bounds`` (``bound_search``, ``bound_match``),
  ``environment``;
* shared infrastructure: the paper's data and setup (:mod:`fdsc.paper.data`, shipped as package
  data), the name map (:mod:`fdsc.paper.names`), the verdict rule (:mod:`fdsc.paper.verdict`),
  ``inputs``, ``results``, ``prose``, ``style``, ``claims``, the reproduction record
  (:mod:`fdsc.paper.record`), ``cache``, the command line (:mod:`fdsc.paper.cli`), the figures
  (``plotting`` with ``plotting_runs`` and ``plotting_axes``, ``plotting_pays``,
  ``plotting_generic``), ``report`` and ``findings``.

The library :mod:`fdsc` never imports this package.
"""

__all__ = []  # the layer is used through its modules (fdsc.paper.data, fdsc.paper.record, ...)
