"""Statistics the book quotes beside its medians: one bootstrap for every interval."""

import numpy as np

__all__ = ["BOOT", "BOOT_SEED", "bootstrap_median"]

#: Bootstrap resamples of the medians' intervals, and their seed.
BOOT, BOOT_SEED = 2000, 7


def bootstrap_median(x, n: int = BOOT, seed: int = BOOT_SEED) -> tuple:
    """The median of x and a percentile-bootstrap 95 % interval for it (seeded).

    Parameters
    ----------
    x : (N,) array_like
    n : int, optional
        Resamples.
    seed : int, optional

    Returns
    -------
    (median, low, high)

    Examples
    --------
    >>> m, lo, hi = bootstrap_median(np.arange(1.0, 101.0))
    >>> m, bool(lo < m < hi)
    (50.5, True)
    """
    x = np.asarray(x, dtype=float)
    rng = np.random.default_rng(seed)
    med = np.median(x[rng.integers(0, x.size, (n, x.size))], axis=1)
    lo, hi = np.quantile(med, [0.025, 0.975])
    return float(np.median(x)), float(lo), float(hi)
