"""Defaults that light modules need without importing the heavy ones that own them."""

#: γ_tol of paper Remark 4 used by default (not printed in the paper; the book shows the sensitivity).
#: Exported as :data:`fdsc.switching.DEFAULT_GAMMA_TOL`.
DEFAULT_GAMMA_TOL = 10.0
