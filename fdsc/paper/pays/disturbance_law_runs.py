"""One draw of the non-stationary class under every controller of the study (chapter
'disturbance_law'): every fixed controller of :func:`fdsc.paper.pays.fixed_designs.fixed_set`,
the paper's FDSC variants, the laws on the disturbance estimate over each of their candidate
sets and settings, the clairvoyant references, and for each law run the steps of u it makes.

The laws' candidate sets (:data:`CANDIDATE_SETS`), all realized through copies with K0 the LQR
gain:

* ``gains``: the cost law over the comparator set's gains whose copies can predict their cost
  and three points of the static front (:func:`candidates`);
* ``ideal pair``: the band-power law over PassC-LF and PassC-HF (the paper's FDSC pair);
* ``tuned pair`` and ``tuned filtered pair``: the band-power law and the cost law over the two
  controllers tuned for LF-dominated and for HF-dominated segments (controllers with states
  for the filtered pair: their copies carry them).

The clairvoyant **references** switch at the breaks to the controller designed for the segment's
type, realized through copies as the laws are (the state carried over): the value of switching.
"""

from __future__ import annotations

import math

import numpy as np

import fdsc
from fdsc.paper.pays.disturbance_law_draws import (
    DECIDE_EVERY,
    HYSTERESES,
    IDEAL_PAIR,
    LAMBDAS,
    RESTART,
    SEED,
    _example,
    lqr,
    seeded_draw,
)
from fdsc.paper.pays.fixed_designs import FixedSet, law_front_gains
from fdsc.paper.shared.comparators import comparators
from fdsc.paper.shared.data import STATIONARY_DT

__all__ = ["CANDIDATE_SETS", "PAIR_FAMILIES", "REFERENCE_FAMILIES", "settings", "candidates",
           "law_candidates", "law_supervisor", "draw_result", "segment_choice"]

#: The candidate sets of the laws and the laws run on each.
CANDIDATE_SETS = {"gains": ("cost",), "ideal pair": ("band_power",), "tuned pair": ("band_power", "cost"),
                  "tuned filtered pair": ("band_power", "cost")}
#: The fixed designs' family behind each pair.
PAIR_FAMILIES = {"tuned pair": "tuned", "tuned filtered pair": "tuned filtered"}
#: The families whose per-segment-type pairs give a clairvoyant reference.
REFERENCE_FAMILIES = ("tuned", "tuned filtered", "H2 (x)", "H2 (x, ŵ)")


def settings() -> list:
    """Every setting ``candidates/law/copies/λ/h`` of the study, in a fixed order.

    Returns
    -------
    list of str

    Examples
    --------
    >>> settings()[0], len(settings())
    ('gains/cost/copies/0.05/0.1', 54)
    """
    return [f"{cand}/{law}/copies/{lam:g}/{h:g}" for cand, laws in CANDIDATE_SETS.items() for law in laws
            for lam in LAMBDAS for h in HYSTERESES]


def _time_constant(loop):
    return 1.0 / float(np.min(np.abs(np.linalg.eigvals(loop.A).real)))


def candidates(example: str = "aircraft") -> tuple:
    """The cost law's gains: the comparator set's members whose copies can predict their cost,
    and the two ends and the middle of the static front.

    A copy restarted every :data:`RESTART` seconds cannot see the cost of a loop whose slowest
    mode has a longer time constant (the response is still building up when the copy restarts),
    so such a loop looks cheap while it is quiet and is left out (the generic example's open
    loop; the aircraft's PassC-HF). Every gain stays a fixed baseline.

    Parameters
    ----------
    example : {"aircraft", "generic"}

    Returns
    -------
    names : tuple of str
    gains : tuple of ndarray
    """
    ex = _example(example)
    names = [n for n in comparators(example) if _time_constant(ex.closed_loop(n)) <= RESTART]
    gains = [ex.gains[n] for n in names]
    fn, fg = law_front_gains(example)
    return tuple(names) + fn, tuple(gains) + fg


def law_candidates(example: str, cand: str, fs: FixedSet) -> tuple:
    """``(names, controllers)`` of a candidate set (:data:`CANDIDATE_SETS`).

    Parameters
    ----------
    example : {"aircraft", "generic"}
    cand : str
    fs : FixedSet

    Returns
    -------
    tuple
    """
    ex = _example(example)
    if cand == "gains":
        return candidates(example)
    if cand == "ideal pair":
        return IDEAL_PAIR, tuple(ex.gains[n] for n in IDEAL_PAIR)
    fam = PAIR_FAMILIES[cand]
    return (f"{fam} for LF", f"{fam} for HF"), tuple(fs.pairs[fam])


def law_supervisor(example: str, key: str, fs: FixedSet) -> tuple:
    """The supervisor of a setting ``candidates/law/realization/λ/h``.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    key : str
    fs : FixedSet

    Returns
    -------
    sup : fdsc.Supervisor
    names : tuple of str
    forgetting, hysteresis : float
    """
    ex = _example(example)
    cand, law, real, lam, h = key.split("/")
    names, ctrls = law_candidates(example, cand, fs)
    K0 = lqr(example) if real == "copies" else None
    bands = [ex.bands["LF"], ex.bands["HF"]] if law == "band_power" else None
    sup = fdsc.Supervisor(ex.plant, list(ctrls), law=law, bands=bands, decide_every=DECIDE_EVERY,
                          restart=RESTART, K0=K0)
    return sup, tuple(names), float(lam), float(h)


def segment_choice(prep, dr) -> list:
    """The type of segment on each piece of a prepared run: 0 for LF-dominated, 1 for HF.

    Parameters
    ----------
    prep : fdsc.Prepared
    dr : Draw

    Returns
    -------
    list of int
    """
    out = []
    for t0, *_r in prep.grid.pieces:
        j = int(np.searchsorted(dr.d.breaks, t0 + 1e-9, side="right") - 1)
        out.append(0 if not 0 <= j < len(dr.dominant) or dr.dominant[j] == "LF" else 1)
    return out


def _stats(prep, lam, h, step=True):
    """``(energy, switches, diverged, largest step of u over its RMS)`` of one law setting (the
    step NaN when ``step`` is false: not measured)."""
    mu = prep.mu(lam)
    sigma = prep.decide(mu, hysteresis=h)
    r = prep.run_sequence(sigma)
    jump = 0.0 if step else math.nan
    if step and r.switches:
        c = prep.control(sigma)
        jump = float(c["jumps"].max() / c["rms"]) if c["rms"] > 0 else float("inf")
    return (r.energy, r.switches, r.diverged_at is not None, jump)


def _fdsc_energies(ex, dr):
    """The paper's FDSC variants on the draw, by the library's simulator at the book's step."""
    names = list(ex.designs)
    cases = [fdsc.Case(ex.designs[n][0].modes, dr.d, dr.horizon, STATIONARY_DT,
                       law_bands=list(ex.designs[n][0].bands), law_Q=list(ex.designs[n][0].Q),
                       rule=ex.designs[n][1]) for n in names]
    runs = fdsc.simulate_batch(cases)
    return {n: (float(runs.energy[k]), int(runs.switches[k]), bool(runs.diverged[k]))
            for k, n in enumerate(names)}


def draw_result(example: str, index: int, seed: int = SEED, fs: FixedSet | None = None, keys=None,
                steps=None) -> dict:
    """Every controller of the study on draw ``index`` of the seeded sequence.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    index : int
        The draw (its generator is seeded by ``[seed, index]``).
    seed : int, optional
    fs : FixedSet
        The study's fixed controllers (:func:`fdsc.paper.pays.fixed_designs.fixed_set`).
    keys : sequence of str, optional
        The law settings run (default every one, :func:`settings`): a training draw needs every
        setting (the choice), a test draw only those the study scores
        (:func:`fdsc.paper.pays.disturbance_law_study.scored_settings`).
    steps : sequence of str, optional
        The settings whose largest step of u is measured (default every one run; the others
        report NaN): the study reports it for the chosen law on the test draws only.

    Returns
    -------
    dict
        Plain and picklable: ``fixed`` (``{name: energy}`` of every fixed controller), ``fdsc``
        (``{variant: (energy, switches, diverged)}``), ``oracle`` (the clairvoyant per-segment
        oracle among the cost law's gains), ``ideal`` (PassC-LF on LF-dominated pieces, PassC-HF
        on HF ones), ``reference`` (``{family: energy}`` of the clairvoyant switching between the
        family's two per-type designs), ``runs`` (``{setting: (energy, switches, diverged,
        largest step of u over its RMS)}`` of the settings ``keys``), ``changes``, ``segments``,
        ``horizon``, ``input_energy``.

    Raises
    ------
    ValueError
        If ``fs`` is missing, or ``keys`` or ``steps`` names a setting that is not one of
        :func:`settings` (``steps`` also: not one of ``keys``).
    """
    if fs is None:
        raise ValueError("fs must be the study's FixedSet (fdsc.paper.pays.fixed_designs.fixed_set)")
    every = settings()
    keys = every if keys is None else list(keys)
    bad = [k for k in keys if k not in every]
    if bad:
        raise ValueError(f"keys must be settings of the study (fdsc.paper.pays.disturbance_law_runs."
                         f"settings()), but found {bad[0]!r}")
    steps = set(keys) if steps is None else set(steps)
    if not steps <= set(keys):
        raise ValueError(f"steps must be among keys (the settings run), but found "
                         f"{sorted(steps - set(keys))[0]!r}")
    ex, dr = seeded_draw(example, index, seed)
    K0 = lqr(example)
    names, gains = candidates(example)
    sup = fdsc.Supervisor(ex.plant, list(gains), decide_every=DECIDE_EVERY, restart=RESTART)
    prep = sup.prepare(dr.d, dr.horizon)
    fixed = {n: prep.energy_of(fs.controllers[n]) for n in fs.names}
    oracle, _choice = prep.clairvoyant()
    choice = segment_choice(prep, dr)
    reference = {}
    for fam in REFERENCE_FAMILIES:              # through copies, as the laws: any controller may be one
        ref = fdsc.Supervisor(ex.plant, list(fs.pairs[fam]), decide_every=DECIDE_EVERY, restart=RESTART,
                              K0=K0)
        reference[fam] = ref.prepare(dr.d, dr.horizon).segment_law(choice)
    runs = {}
    preps = {}
    for key in keys:
        cand, law, _real, lam, h = key.split("/")
        if (cand, law) not in preps:
            if cand == "gains":
                preps[(cand, law)] = prep.with_K0(K0)
            else:
                s, _n, _l, _h = law_supervisor(example, key, fs)
                preps[(cand, law)] = s.prepare(dr.d, dr.horizon)
        runs[key] = _stats(preps[(cand, law)], float(lam), float(h), key in steps)
    if ("ideal pair", "band_power") not in preps:
        s, _n, _l, _h = law_supervisor(example, "ideal pair/band_power/copies/1/0", fs)
        preps[("ideal pair", "band_power")] = s.prepare(dr.d, dr.horizon)
    ideal_prep = preps[("ideal pair", "band_power")]
    ideal = ideal_prep.with_K0(None).segment_law(segment_choice(ideal_prep, dr))
    return {"index": index, "horizon": dr.horizon, "changes": dr.changes, "segments": len(dr.dominant),
            "fixed": fixed, "fdsc": _fdsc_energies(ex, dr), "oracle": oracle, "ideal": ideal,
            "reference": reference, "runs": runs, "input_energy": prep.input_energy}
