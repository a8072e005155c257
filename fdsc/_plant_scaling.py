"""The units of a plant taken out before a synthesis LMI, and put back into its result.

The synthesis LMIs are solved with an absolute strictness margin and absolute solver tolerances,
so their answer must not hang on the units in which z, d and u are given: a disturbance scaled
by 10⁻⁴ makes γ² ≈ 10⁻⁸ γ₁², the size of the margin. :func:`normalize_plant` returns the same
plant in units where the blocks are of one size,

    d = a_d d̃,    u = a_u ũ,    z̃ = c_z z,

with ``a_d`` and ``a_u`` the reciprocal norms of B1 and B2 and ``c_z`` that of
``[C, D1 a_d, D2 a_u]``. Each factor is read from a block that the other two rescalings leave
alone, and is taken as it is (not rounded), so a plant whose z, d or u is rescaled gives the same
normalized plant up to rounding, hence the same LMI and the same design. A gain ``ũ = K̃ x`` of the
normalized plant is ``u = a_u K̃ x``, and a bound γ̃ from d̃ to z̃ is ``γ = γ̃ / (c_z a_d)`` from d
to z.

The state is left in its units: a diagonal balancing of A (powers of two) made the weighted
designs of the book's two examples fail at more scales than it mended.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .plant import Plant

__all__ = ["PlantScaling", "normalize_plant"]


def _reciprocal_norm(*blocks) -> float:
    """1 / the 2-norm of the first block that is not zero (1 if every block is zero)."""
    for b in blocks:
        s = float(np.linalg.norm(b, 2)) if b.size else 0.0
        if s > 0:
            return 1.0 / s
    return 1.0


@dataclass(frozen=True)
class PlantScaling:
    """A plant in normalized units and the factors that lead back (module docstring).

    Parameters
    ----------
    plant : Plant
        The normalized plant.
    a_d, a_u, c_z : float
        ``d = a_d d̃``, ``u = a_u ũ``, ``z̃ = c_z z``.
    """

    plant: Plant
    a_d: float
    a_u: float
    c_z: float

    def gain(self, K_n: np.ndarray) -> np.ndarray:
        """The gain from x to u of the normalized plant's gain ``K_n`` (from x to ũ)."""
        return self.a_u * K_n

    def gamma(self, gamma_n: float) -> float:
        """The gain bound from d to z of a bound ``gamma_n`` from d̃ to z̃."""
        return gamma_n / (self.c_z * self.a_d)


def normalize_plant(plant: Plant) -> PlantScaling:
    """The plant in units where B1, B2 and the output ``[C, D1, D2]`` have unit norm.

    Parameters
    ----------
    plant : Plant

    Returns
    -------
    PlantScaling
        A block that is zero is left alone (D1 decides d's unit when B1 is zero, D2 u's when B2
        is).

    Examples
    --------
    >>> p = Plant([[-1.0]], [[1e-4]], [[2.0]], [[1e6]], [[0.0]], [[0.0]])
    >>> sc = normalize_plant(p)
    >>> sc.plant.B1.item(), sc.plant.B2.item(), sc.plant.C.item(), sc.gamma(1.0)
    (1.0, 1.0, 1.0, 100.0)
    """
    B1, B2, C, D1, D2 = plant.B1, plant.B2, plant.C, plant.D1, plant.D2
    a_d = _reciprocal_norm(B1, D1)
    a_u = _reciprocal_norm(B2, D2)
    c_z = _reciprocal_norm(np.hstack([C, a_d * D1, a_u * D2]))
    scaled = Plant(plant.A, a_d * B1, a_u * B2, c_z * C, (c_z * a_d) * D1, (c_z * a_u) * D2)
    return PlantScaling(scaled, a_d, a_u, c_z)
