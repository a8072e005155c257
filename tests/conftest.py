"""Shared setup of the test tree (tests/README.md says what the tree holds).

What a test may assert about a solve
------------------------------------
An LMI (cvxpy + Clarabel) or a local search (Nelder–Mead) returns one of many optimizers that
are optimal to its tolerance, and which one depends on rounding, so on the CPU and the BLAS: the
aircraft's H∞ gain moved by 2.5e-4 between two machines while its γ agreed to 1e-6. A test asserts

* the optimal value (γ, the objective), to the solver's accuracy (Clarabel: ~1e-6 relative);
* what the returned design achieves, computed by the test (band peak or H∞ norm by
  ``fdsc.band_peak``, energy on stated draws, stability); where γ_lmi lies above the best
  achievable value, bracket the achieved value between that optimum (found independently: a
  Riccati bisection, a direct search) and γ_lmi instead of matching it;
* feasibility margins, and structure the code imposes (symmetry, P ≻ 0, P_0 == P_1 when the
  code makes them one variable).

Never a gain K, a Q, P, X, Y, a filter's coefficients or a tuned controller's matrices to a
tight tolerance, nor two solves' optimizers against each other (not even one problem in two
representations). Unique quantities may be compared: an LQR/Riccati gain, a closed form, a
noise-free tone's amplitude and frequency, one computation repeated on one input (a cache round
trip, processes against threads). Docstring Examples print an optimal value or what a design
achieves, not an optimizer's digits.
"""

import sys
from pathlib import Path

# the tests import helpers that live beside them (check_book_html, compare_records)
sys.path.insert(0, str(Path(__file__).resolve().parent))
