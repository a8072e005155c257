"""Chapter 'switching_law': the switching law (paper eq. (31)) in action, σ(t) against the
time-localized dominance, and the region where the law cannot settle.
"""


import numpy as np

from ..simulate import simulate, time_grid
from .data import (
    STATIONARY_DT,
    our_q,
    paper_modes,
    piecewise_disturbance,
)

__all__ = [
    "switching_statistics",
    "law_conflict",
]


def switching_statistics(*, T=100.0, rho_t=0.2, rho_p_star=0.1, dt=STATIONARY_DT, laws=None):
    """σ(t) along the piecewise disturbance of paper Fig. 8 (shortened to T), for several law variants.

    Returns
    -------
    dict
        ``t`` (bin starts), ``bin`` (bin length, s), ``breaks``, and per variant ``sigma`` (share
        of each bin spent in the HF mode, so chattering is not aliased), ``switches``,
        ``share`` (fraction in the HF mode per disturbance segment), ``single_sample_dwell``
        (fraction of dwell intervals lasting one sample: the signature of chattering).
    """
    d = piecewise_disturbance(T, rho_t, rho_p_star)
    t = time_grid(d.breaks[-1], dt)
    pm = paper_modes()
    laws = laws or {"paper Q, measured ẋ": (pm["Q"], "previous"),
                    "paper Q, candidate ẋ": (pm["Q"], "candidate"),
                    "our Q, measured ẋ": (our_q().Q, "previous")}
    every = 20
    starts = np.arange(0, t.size, every)
    out = {"t": t[starts], "breaks": d.breaks, "variants": {}, "bin": every * dt}
    for label, (Q, law) in laws.items():
        sim = simulate(pm["modes"], d, t, law_bands=pm["bands"], law_Q=Q, law=law)
        seg = d.segment_of(t)
        share = [float(np.mean(sim.sigma[seg == k] == 1)) for k in range(len(d.parts))]
        sw = np.flatnonzero(np.diff(sim.sigma)) + 1
        dwell = np.diff(np.concatenate([[0], sw, [t.size - 1]]))
        out["variants"][label] = {
            # the share of each bin spent in mode 1: σ chatters at the sampling rate, so every
            # n-th sample of σ would alias; the per-bin share holds every sample
            "sigma": np.add.reduceat(sim.sigma, starts) / np.diff(np.append(starts, t.size)),
            "switches": int(sw.size), "share_hf": share,
            "single_sample_dwell": float(np.mean(dwell <= 1)) if dwell.size else 0.0,
            "energy": sim.energy()}
    return out


def law_conflict(sim, modes, law_bands, law_Q):
    """Where the printed law with the measured ẋ cannot settle, along a simulated run.

    With ẋ = A_σ(t⁻) x + B d the score of every candidate depends on the mode active just before
    t. At a sample, mode i "prefers" the mode with the best score computed with ẋ = A_i x + B d. The
    law cannot settle where every mode prefers another (for two modes: mode 1 prefers mode 2 and
    mode 2 prefers mode 1): whichever is active, the next sample switches. That set is a region of
    the (x, d) space, not the surface where two scores are equal.

    Parameters
    ----------
    sim : SimResult
        A run of the switched loop.
    modes : list of LTISystem
    law_bands : list of Band
    law_Q : list of (n, n) array_like

    Returns
    -------
    dict
        ``in_region`` (fraction of samples in the region), ``switches_in_region`` (fraction of
        switches taken at a sample in the region), ``n_switches``.
    """
    n_modes = len(modes)
    scores = np.empty((n_modes, n_modes, sim.t.size))  # [active i, candidate j, k]
    for i, m in enumerate(modes):
        xdot = sim.x @ m.A.T + np.outer(sim.d, m.B[:, 0])
        v = np.hstack([xdot, sim.x])
        for j, (b, Q) in enumerate(zip(law_bands, law_Q, strict=True)):
            W = np.kron(b.psi.real, np.asarray(Q, dtype=float))
            scores[i, j] = np.einsum("kr,rc,kc->k", v, W, v)
    prefers = scores.argmax(axis=1)  # [active i, k]
    region = np.all(prefers != np.arange(n_modes)[:, None], axis=0)
    sw = np.flatnonzero(np.diff(sim.sigma)) + 1
    return {"in_region": float(region.mean()),
            "switches_in_region": float(region[sw].mean()) if sw.size else 0.0,
            "n_switches": int(sw.size)}
