"""Part I of the book, *The paper, reproduced*: one entry module per chapter, named like its
notebook, with its sibling modules.

``frequency_ranges`` (Sec. II-A; ``dominance``, ``paley_wiener``, ``proposition1``),
``gkyp_lemma`` (Lemma 1; ``gamma_slip``), ``passive_controllers`` (the gains of Sec. IV and paper
Fig. 3; ``passive_gains``, ``passive_sensitivity``, ``passive_crosscheck``, and the four printed
bounds in ``printed_bounds`` with ``bound_search`` and ``bound_match``), ``frequency_selective``
(Sec. III; ``proposition1_cases``, ``fd_epf``), ``switching_law`` (paper eq. (31)), ``theorem1``
(``theorem1_statement1``, ``theorem1_statements23``), ``stationary`` (paper Figs. 4-6;
``stationary_figures``, ``stationary_claims``), ``nonstationary`` (paper Figs. 7 and 8;
``nonstationary_sweeps``, ``nonstationary_objectives``); the paper's simulation cases with every
controller of the book (``paper_cases``) and the claims checklist (``claims``).

A module here imports the library, :mod:`fdsc.paper.shared` and this part only.
"""

__all__ = []  # used through its modules
