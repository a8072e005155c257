"""Statistics the book quotes beside its medians: one bootstrap for every interval."""

import numpy as np

__all__ = ["BOOT", "BOOT_SEED", "bootstrap_median", "median_ci_words"]

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


def median_ci_words(x) -> str:
    """The median of per-draw ratios with its bootstrap 95 % interval, ``×m [lo, hi]``
    (:func:`bootstrap_median`, :func:`fdsc.paper.shared.prose.times_ci`).

    Parameters
    ----------
    x : (N,) array_like
        Ratios, one per draw.

    Returns
    -------
    str

    Examples
    --------
    >>> median_ci_words([0.8, 0.9, 0.95, 1.1, 1.2])
    '×0.950 [0.800, 1.20]'
    """
    from fdsc.paper.shared.prose import times_ci

    m, lo, hi = bootstrap_median(np.asarray(x, dtype=float))
    return times_ci({"median": m, "low": lo, "high": hi})
