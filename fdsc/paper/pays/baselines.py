"""Chapter 'simulations': does FDSC pay on the paper's aircraft? Every simulation case of the paper
(stationary LF and HF, the ρ_p and ρ_t families of paper Figs. 7 and 8) with the open loop, the
paper's three fixed gains, the best certified HF design, FDSC as printed, FDSC with a minimum
dwell time, and FDSC with the best HF design in place of K_f3 (its Q's designed by Theorem 1 /
paper Remark 4).

The runs are those of :mod:`fdsc.paper.reproduced.paper_cases` (chapters 'simulations' and
'nonstationary' set FDSC beside the same runs); this module re-exports them and adds the chapter's
figures and its record entries.
"""

import numpy as np

import fdsc
from fdsc._validation import as_count
from fdsc.paper.reproduced.paper_cases import (
    DWELL_TAU,
    FDSC_DWELL,
    FDSC_HF_BEST,
    FIXED,
    HF_BEST,
    SWITCHED,
    Baselines,
    Scenario,
    aircraft_example,
    baselines,
)
from fdsc.paper.reproduced.passive_sensitivity import hf_best
from fdsc.paper.shared.results import RecordPart

__all__ = [
    "HF_BEST",
    "FDSC_DWELL",
    "FDSC_HF_BEST",
    "FIXED",
    "SWITCHED",
    "DWELL_TAU",
    "aircraft_example",
    "Scenario",
    "Baselines",
    "baselines",
    "hf_best",
    "sigma_curves",
    "record_part",
]


def sigma_curves(n: int = 600) -> tuple:
    """σ_max(ω) of every fixed controller of :func:`aircraft_example`, log-spaced over
    [10⁻², 10⁴] rad/s (the printed tones lie in [0.1, 300] rad/s).

    Parameters
    ----------
    n : int, optional
        Grid points (≥ 2).

    Returns
    -------
    omega : (n,) ndarray
    sigma : dict
        ``{fixed controller: (n,) ndarray}``.

    Examples
    --------
    >>> w, s = sigma_curves(3)
    >>> w.tolist(), round(float(s["open loop"][-1]), 4)   # the open loop rolls off like 16/ω
    ([0.01, 10.0, 10000.0], 0.0016)
    """
    ex = aircraft_example()
    omega = np.logspace(-2, 4, as_count("n", n, minimum=2))
    return omega, {k: fdsc.sigma_max(ex.closed_loop(k), omega) for k in FIXED}


def record_part() -> RecordPart:
    """Record entries ``baselines`` and ``hf_good_in_band``.

    Returns
    -------
    RecordPart
    """
    return baselines().to_record()
