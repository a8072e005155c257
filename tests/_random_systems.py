"""Seeded random test systems shared by the unit tests."""

import numpy as np

from fdsc import LTISystem


def random_stable_system(rng, n=None, m=None, p=None, direct=True):
    """A random stable LTI system with well-separated poles (real parts in [-3, -0.1])."""
    n = int(rng.integers(1, 5)) if n is None else n
    m = int(rng.integers(1, 3)) if m is None else m
    p = int(rng.integers(1, 4)) if p is None else p
    V = rng.standard_normal((n, n)) + 2 * np.eye(n)
    re = -rng.uniform(0.1, 3.0, n)
    im = rng.uniform(0.0, 5.0, n)
    # build a real A with some complex pole pairs through 2x2 rotation blocks
    J = np.diag(re)
    for k in range(0, n - 1, 2):
        if rng.random() < 0.5:
            J[k, k + 1], J[k + 1, k] = im[k], -im[k]
            J[k + 1, k + 1] = J[k, k]
    A = V @ J @ np.linalg.inv(V)
    B = rng.standard_normal((n, m))
    C = rng.standard_normal((p, n))
    D = 0.3 * rng.standard_normal((p, m)) if direct else np.zeros((p, m))
    return LTISystem(A, B, C, D)
