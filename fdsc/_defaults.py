"""Defaults that light modules need without importing the heavy ones that own them."""

#: γ_tol of paper Remark 4 used by default (not printed in the paper; the book shows the sensitivity).
#: Exported as :data:`fdsc.switching.DEFAULT_GAMMA_TOL`.
DEFAULT_GAMMA_TOL = 10.0

#: Largest working memory (bytes) a simulation allocates unless told otherwise (``max_memory``
#: of :func:`fdsc.simulate.simulate`, and of :func:`fdsc.stream.simulate_stream` per run).
#: Exported as :data:`fdsc.simulate.DEFAULT_MAX_MEMORY`.
DEFAULT_MAX_MEMORY = 4 * 2**30
