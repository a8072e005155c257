"""Appendix 'printed_bounds', continued: the four bounds printed beside the gains of Sec. IV,
searched for among time-domain quantities of the simulations of Sec. IV.

The quantity the text states (σ_max over the gain's band) reproduces only the bound printed
beside K_f2 (:mod:`fdsc.paper.reproduced.printed_bounds`). Sec. IV also computes time-domain
quantities (paper Fig. 6 plots the running L2-induced ratio ``√(∫₀ᵗ zᵀz / ∫₀ᵗ d²)``), so a
printed bound may be one of them, read at the end of some run. This module runs every printed
gain under every test signal of Sec. IV in one streamed batch and compares, for each gain,
every quantity below with the bound printed beside it:

* the L2-induced ratio ``√(∫₀ᵀ zᵀz / ∫₀ᵀ d²)`` from rest, and the energy ratio
  ``∫₀ᵀ zᵀz / ∫₀ᵀ d²`` (its square: the paper writes γ where γ² belongs), at the "round"
  horizons :data:`ROUND_HORIZONS` that lie inside the signal's run;
* the limits of both as T → ∞ for the sums of sinusoids (closed form,
  :func:`fdsc.frequency.steady_state_gain`);
* the peak gain of each output alone, ``max |z_i(t)| / max |d(t)|`` over the samples in
  ``[0, T)``, at the same horizons (from min/max traces, so no full trace is kept), named
  ``"peak gain of <output>"`` (:func:`output_label`).

A quantity picked after the fact as the nearest of several hundred is no evidence of what the
paper computed, even when it equals the printed digits: the module gives no verdict. It reports
the hits (quantities equal to the printed value to its precision), the nearest quantities, how
many lie within 1 % of the printed value and how many hits that many would give by chance
(:attr:`BoundMatch.chance_hits`); the one verdict of each bound is that of the quantity the text
states (:mod:`fdsc.paper.reproduced.printed_bounds`). The first time each running ratio crosses the printed
value is recorded for information only: a continuous curve that sweeps through a range crosses
every value in it.
"""

import math
from dataclasses import dataclass

import numpy as np

from fdsc._validation import as_positive
from fdsc.frequency import steady_state_gain
from fdsc.paper.reproduced.bound_match import (
    ENERGY_RATIO,
    L2_RATIO,
    BoundMatch,
    Crossing,
    TimeDomainCandidate,
    first_crossing,
    match_bound,
    output_label,
)
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.data import (
    STATIONARY_DT,
    aircraft,
    hf_disturbance,
    lf_disturbance,
    mixed_disturbance,
    paper_data,
    paper_gains,
    piecewise_disturbance,
)
from fdsc.paper.shared.names import GAIN_ORDER
from fdsc.paper.shared.results import pick
from fdsc.signals import Sinusoids
from fdsc.stream import Case, simulate_batch

__all__ = [
    "ROUND_HORIZONS",
    "RHO_P_GRID",
    "RHO_T_GRID",
    "STATIONARY_RUN",
    "MIXED_RUN",
    "PIECEWISE_T",
    "RHO_P_STAR",
    "L2_RATIO",
    "ENERGY_RATIO",
    "STEADY_STATE",
    "SearchSignal",
    "search_signals",
    "output_label",
    "TimeDomainCandidate",
    "BoundMatch",
    "match_bound",
    "first_crossing",
    "Crossing",
    "TimeDomainBoundSearch",
    "time_domain_bound_search",
]

#: Horizons (s) a simulation might have used; a signal is read only at those inside its run.
ROUND_HORIZONS = (1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 300.0, 500.0, 1000.0, 1500.0)
#: ρ_p of the mixed disturbances d_h + ρ_p d_l (paper Fig. 7 sweeps [0, 0.5]).
RHO_P_GRID = (0.1, 0.2, 0.3, 0.4, 0.5)
#: ρ_t of the piecewise disturbance, paper eq. (58) (paper Fig. 8 sweeps [0, 0.5]).
RHO_T_GRID = (0.1, 0.5)
#: Run length (s) under the LF and HF disturbances: not printed, so the longest round horizon.
STATIONARY_RUN = 1500.0
#: Run length (s) under the mixed disturbances: t ∈ [0, 500] (Sec. IV, paper Fig. 7).
MIXED_RUN = 500.0
#: T and ρ*_p of the piecewise disturbance (Sec. IV); its run is [0, 2T + ρ_t T).
PIECEWISE_T, RHO_P_STAR = 500.0, 0.1
#: The horizon of a steady-state limit.
STEADY_STATE = math.inf


@dataclass(frozen=True)
class SearchSignal:
    """A test signal of Sec. IV and the length of its run.

    Parameters
    ----------
    label : str
        Its name in tables and in the record.
    d : Sinusoids or Piecewise
        The disturbance.
    run : float
        Length of the run in s.
    """

    label: str
    d: object
    run: float

    @property
    def stationary(self) -> bool:
        """A sum of sinusoids (it has steady-state limits)."""
        return isinstance(self.d, Sinusoids)


def search_signals() -> tuple:
    """The test signals of Sec. IV: LF, HF, the mixed ones and the piecewise ones.

    Returns
    -------
    tuple of SearchSignal
        LF (paper eq. (56)) and HF (paper eq. (57)) over :data:`STATIONARY_RUN`; d_h + ρ_p d_l
        for ρ_p in :data:`RHO_P_GRID` over :data:`MIXED_RUN`; paper eq. (58) with T = 500,
        ρ*_p = 0.1 and ρ_t in :data:`RHO_T_GRID` over its whole length.

    Examples
    --------
    >>> [(s.label, s.run) for s in search_signals()][-1]
    ('piecewise, ρ_t = 0.5', 1250.0)
    """
    out = [SearchSignal("LF", lf_disturbance(), STATIONARY_RUN),
           SearchSignal("HF", hf_disturbance(), STATIONARY_RUN)]
    out += [SearchSignal(f"mixed, ρ_p = {r:g}", mixed_disturbance(r), MIXED_RUN) for r in RHO_P_GRID]
    out += [SearchSignal(f"piecewise, ρ_t = {r:g}", piecewise_disturbance(PIECEWISE_T, r, RHO_P_STAR),
                         (2 + r) * PIECEWISE_T) for r in RHO_T_GRID]
    return tuple(out)


@dataclass(frozen=True)
class TimeDomainBoundSearch:
    """The printed bounds against time-domain quantities (see :func:`time_domain_bound_search`).

    Parameters
    ----------
    bounds : tuple of BoundMatch
        One per gain, in the order of :data:`fdsc.paper.shared.names.GAIN_ORDER`.
    candidates : tuple of TimeDomainCandidate
        Every quantity computed.
    crossings : tuple of Crossing
        One per gain, signal and running ratio.
    signals : dict
        ``{label: length of its run in s}``.
    horizons : tuple of float
        The round horizons asked for (s).
    t_cum : dict
        ``{signal: (M,) ndarray}``: coarse grid of the running ratios (s).
    l2_curves : dict
        ``{signal: {gain: (M,) ndarray}}``: running L2 ratios on ``t_cum``.
    dt, coarse_step, peak_bin : float
        Step, coarse grid and min/max bin of the runs (s).
    """

    bounds: tuple
    candidates: tuple
    crossings: tuple
    signals: dict
    horizons: tuple
    t_cum: dict
    l2_curves: dict
    dt: float
    coarse_step: float
    peak_bin: float

    def __getitem__(self, gain: str) -> BoundMatch:
        """The bound of one gain.

        Parameters
        ----------
        gain : str
            Name of the gain.

        Returns
        -------
        BoundMatch
        """
        return pick(self.bounds, "gain", gain)

    @property
    def quantities(self) -> tuple:
        """The quantities tried, in order."""
        return tuple(dict.fromkeys(c.quantity for c in self.candidates))

    @property
    def tried(self) -> dict:
        """Counts of what was tried: gains, signals, quantities, round horizons used, candidates
        per bound."""
        used = sorted({c.horizon for c in self.candidates if math.isfinite(c.horizon)})
        return {"gains": len(self.bounds), "signals": len(self.signals), "quantities": len(self.quantities),
                "round_horizons_s": [float(h) for h in used],
                "candidates_per_bound": int(self.bounds[0].n_candidates)}

    def rows(self) -> list:
        """One row per bound: ``gain, paper, signal, quantity, horizon, value, abs_diff, hits,
        within_1pct, chance_hits`` (the nearest candidate, the number of hits, of candidates
        within 1 % and of hits to expect by chance).

        Returns
        -------
        list of dict
            For :func:`fdsc.paper.shared.report.html_table`.
        """
        return [{"gain": b.gain, "paper": b.paper, **b.rows()[0], "hits": len(b.hits),
                 "within_1pct": b.n_within_close, "chance_hits": b.chance_hits} for b in self.bounds]

    def crossing_rows(self, gain: str | None = None) -> list:
        """The running ratios that reach the printed bound: ``gain, signal, quantity, t``.

        Parameters
        ----------
        gain : str, optional
            Only this gain (default all).

        Returns
        -------
        list of dict
        """
        return [vars(c).copy() for c in self.crossings
                if math.isfinite(c.t) and gain in (None, c.gain)]

    def settings(self) -> dict:
        """What the search ran: ``signals`` (``{label: run in s}``), ``horizons_s`` (the round
        horizons used), ``quantities`` and ``dt_s``.

        Returns
        -------
        dict
        """
        return {"signals": {k: float(v) for k, v in self.signals.items()},
                "horizons_s": self.tried["round_horizons_s"], "quantities": list(self.quantities),
                "dt_s": self.dt}

    def readings(self, gain: str) -> dict:
        """The search's readings of one printed bound, as plain values (for its record entry).

        Parameters
        ----------
        gain : str
            The printed gain.

        Returns
        -------
        dict
            ``nearest`` and ``hits`` (each ``{signal, quantity, horizon_s, value}``),
            ``searched`` (quantities per bound), ``within_1pct``, ``chance_hits`` and
            ``first_crossings_s`` (``{"<quantity>, <signal>": t}``, for information only).
        """
        b = self[gain]
        return {"nearest": b.best.to_dict(), "hits": [h.to_dict() for h in b.hits],
                "searched": int(b.n_candidates), "within_1pct": int(b.n_within_close),
                "chance_hits": float(b.chance_hits),
                "first_crossings_s": {f"{c['quantity']}, {c['signal']}": float(c["t"])
                                      for c in self.crossing_rows(gain)}}


def _check_grid(name, seconds, step, what):
    k = round(seconds / step)
    if k < 1 or abs(k * step - seconds) > 1e-9 * seconds:
        raise ValueError(f"{name} ({seconds:g} s) must be a multiple of {what} ({step:g} s)")


@cached
def time_domain_bound_search(horizons: tuple = ROUND_HORIZONS, *, dt: float = STATIONARY_DT,
                             coarse_step: float = 0.1, peak_bin: float = 1.0,
                             decimals: int = 4) -> TimeDomainBoundSearch:
    """Each printed bound of Sec. IV against time-domain quantities of its gain's closed loop.

    Every printed gain runs from rest under every signal of :func:`search_signals`, in one
    :func:`fdsc.simulate_batch` call, up to the end of the signal or the largest horizon,
    whichever comes first. The quantities are those of the module docstring: L2 and energy ratios
    at each horizon inside the run and as T → ∞ (sums of sinusoids only), and the peak gain of each
    output at each horizon. Each bound is then matched by :func:`match_bound`, and the first time
    each running ratio reaches it is recorded by :func:`first_crossing`.

    Parameters
    ----------
    horizons : tuple of float, optional
        Horizons T in s, multiples of ``coarse_step`` and ``peak_bin``.
    dt : float, optional
        Step of the runs in s.
    coarse_step : float, optional
        Grid (s) of the running integrals; an even number of steps.
    peak_bin : float, optional
        Bin (s) of the min/max traces behind the peak gains.
    decimals : int, optional
        Decimals of the printed bounds.

    Returns
    -------
    TimeDomainBoundSearch

    Raises
    ------
    ValueError
        If a horizon is not a positive multiple of ``coarse_step`` and ``peak_bin``, or if
        ``coarse_step`` or ``peak_bin`` does not fit ``dt``.

    Notes
    -----
    The integrals are Simpson's rule on the samples (:mod:`fdsc.stream`); the peak gains are
    maxima over the samples in ``[0, T)``.

    Examples
    --------
    >>> s = time_domain_bound_search((1.0, 2.0))
    >>> s.tried["candidates_per_bound"], s["K_e"].hits    # 9 signals x 2 horizons x 5, 7 x 2
    (104, ())
    """
    horizons = tuple(sorted({float(as_positive("horizons", h)) for h in horizons}))
    for h in horizons:
        _check_grid("horizons", h, coarse_step, "coarse_step")
        _check_grid("horizons", h, peak_bin, "peak_bin")
    plant, gains = aircraft(), paper_gains()
    printed = {k: v["bound"] for k, v in paper_data("controllers").items() if k in GAIN_ORDER}
    signals = search_signals()
    outputs = plant.names["output_names"]
    runs = {s.label: min(s.run, horizons[-1]) for s in signals}
    cases = [Case(plant.closed_loop(gains[g]), s.d, runs[s.label], dt, label=(g, s.label))
             for g in GAIN_ORDER for s in signals]
    batch = simulate_batch(cases, cumulative_every=coarse_step, trace_every=peak_bin)
    cands = {g: [] for g in GAIN_ORDER}
    crossings, t_cum, l2 = [], {}, {s.label: {} for s in signals}
    for case, res in zip(cases, batch, strict=True):
        g, label = case.label
        t, ratio = res.running_l2()
        t_cum[label], l2[label][g] = t, ratio
        zmax = np.maximum(np.abs(res.trace.z_lo), np.abs(res.trace.z_hi))
        dmax = np.maximum(np.abs(res.trace.d_lo), np.abs(res.trace.d_hi))
        for T in (h for h in horizons if h <= runs[label]):
            k, nb = round(T / coarse_step), round(T / peak_bin)
            peak = zmax[:nb].max(axis=0) / dmax[:nb].max()
            cands[g] += [TimeDomainCandidate(g, label, L2_RATIO, T, float(ratio[k])),
                         TimeDomainCandidate(g, label, ENERGY_RATIO, T, float(ratio[k] ** 2))]
            cands[g] += [TimeDomainCandidate(g, label, f"peak gain of {output_label(name)}", T, float(p))
                         for name, p in zip(outputs, peak, strict=True)]
        crossings += [Crossing(g, label, L2_RATIO, first_crossing(t, ratio, printed[g])),
                      Crossing(g, label, ENERGY_RATIO, first_crossing(t, ratio**2, printed[g]))]
    for g in GAIN_ORDER:
        cl = plant.closed_loop(gains[g])
        for s in (s for s in signals if s.stationary):
            ss = steady_state_gain(cl, s.d.frequencies, s.d.amplitudes)
            cands[g] += [TimeDomainCandidate(g, s.label, L2_RATIO, STEADY_STATE, ss),
                         TimeDomainCandidate(g, s.label, ENERGY_RATIO, STEADY_STATE, ss**2)]
    bounds = tuple(match_bound(g, printed[g], cands[g], decimals=decimals) for g in GAIN_ORDER)
    return TimeDomainBoundSearch(bounds, tuple(c for g in GAIN_ORDER for c in cands[g]), tuple(crossings),
                                 {s.label: float(runs[s.label]) for s in signals}, horizons, t_cum, l2,
                                 float(dt), float(coarse_step), float(peak_bin))
