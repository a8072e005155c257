"""The strongest fixed controllers of each example for its disturbance class (chapter
'fixed_controllers'): every fixed controller the book compares a switching law with, the one
chosen in advance among them, and the controllers designed for each type of segment that the
value of switching is measured with.

The class is that of chapter 'disturbance_law': seeded non-stationary draws
(:func:`fdsc.paper.pays.disturbance_law_draws.draw`), the first half of a study's draws for
training, the second for scoring. The fixed controllers, all from the library's public API:

* the **comparator set** of Part I's comparisons (the open loop, PassC-EF, PassC-LF, PassC-HF,
  and on the aircraft the best certified HF design);
* the **static front**: :data:`FRONT_POINTS` gains of least HF peak with the LF peak at most β
  (:func:`fdsc.pareto_front`), each checked against a direct search for a gain that beats it in
  both bands (:func:`fdsc.dominating_gain`);
* the **LQR gain** of ``∫‖C x + D2 u‖²``;
* the **dynamic front**: frequency-weighted H∞ state feedback at :data:`DYN_RATIOS`
  (:func:`fdsc.dynamic_front`), controllers with the weight's states;
* the **H2 controllers** for the class's mean spectrum (a shaping filter fitted to the tones of
  the tuning draws, :func:`fdsc.fit_shaping_filter`), reading x alone or x and ŵ
  (:func:`fdsc.h2_controller`);
* the **tuned controllers**: least mean log energy over the tuning draws
  (:func:`fdsc.tune_controller`), a static gain and a filtered one (n filter states), each
  also with its H∞ norm capped at :data:`CAP_FACTOR` times the least H∞ norm of a state feedback;
* the **tuned controllers that read ŵ** (:func:`ff_poles`), the information every law on the
  disturbance estimate has: the tuned gain or filtered controller with a static feedforward of
  ŵ, or with a feedforward through first-order filters of ŵ of fixed poles, tuned the same way;
  and the LQR gain with the widest of these feedforwards (``LQR + ŵ filter``, the predictive
  law's base).

The **fixed controller chosen in advance** is the one of least mean log energy over the training
half among all of them (the best fixed controller with the information of the laws: x and ŵ);
the best among those that read x alone is kept beside it (:attr:`FixedSet.chosen_x`). For the
**value of switching**, the same designs are made for each type of
segment (LF- and HF-dominated pieces of the tuning draws, each run from rest): the clairvoyant
switching reference switches between the two at the breaks (chapter 'disturbance_law').
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field

import numpy as np

import fdsc
from fdsc.paper.pays.disturbance_law_draws import RESTART, _example, seeded_draw, segment_class
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.comparators import comparators

__all__ = ["N_TUNE", "CAP_FACTOR", "FRONT_POINTS", "DYN_RATIOS", "U_PENALTY", "TUNE_MAXITER",
           "RECORD_MAXITER", "FF_MAXITER", "FF_ROUNDS", "RECORD_ROUNDS", "FAMILIES", "FixedSet", "fixed_set",
           "tuning_draws", "static_front",
           "law_front_gains", "ff_poles", "OPTIMAL_LTI", "best_found"]

#: Tuning draws (the first training draws) the tuned designs and the shaping filters see.
N_TUNE = 30
#: The H∞ cap of the capped tuned designs: this times the least H∞ norm of a static gain.
CAP_FACTOR = 1.1
#: Points of the static front, evenly spaced in log from the LF design's LF peak to the H∞ gain's.
FRONT_POINTS = 9
#: The ratios w_LF / w_HF of the dynamic front, and the penalty on u that bounds its gains.
DYN_RATIOS = tuple(float(r) for r in np.geomspace(0.1, 100.0, 7))
U_PENALTY = 1e-2
#: Nelder–Mead iterations per start of the tuned designs (the full study), and of the record's
#: subset (the same designs with a shorter search, stated where the record reports them).
TUNE_MAXITER, RECORD_MAXITER = 1500, 250
#: Iterations per start of the front's search and of its dominance check.
FRONT_MAXITER, CHECK_MAXITER = 200, 300
#: The families, in the order the book lists them.
FAMILIES = ("comparator set", "static front", "LQR", "dynamic front", "H2", "tuned", "tuned (x, ŵ)",
            "optimal LTI")
#: The name of the optimal LTI controller of the class (reading x and ŵ) in the fixed set.
OPTIMAL_LTI = "optimal LTI (x, ŵ)"
#: Nelder–Mead iterations per round of the feedforward designs (a round also sets the feedforward
#: gains exactly; the rounds end when one gains less than 1e-9).
FF_MAXITER = 300
#: Rounds of the feedforward designs: the full study's, and the record's subset's.
FF_ROUNDS, RECORD_ROUNDS = 6, 2


def ff_poles(example: str) -> dict:
    """The feedforwards of the tuned controllers that read ŵ: ``{name: (feedback structure,
    feedforward)}`` — a static feedforward, eight first-order filters with poles from 0.03 to
    30 rad/s, and ten from 0.03 rad/s to the top of the class's HF tones (the band where the
    disturbance's phase matters most).

    Parameters
    ----------
    example : {"aircraft", "generic"}

    Returns
    -------
    dict
    """
    top = float(_example(example).hf_tones[1])
    return {"tuned + ŵ": ("static", "static"),
            "tuned filtered + ŵ": ("filtered", "static"),
            "tuned filtered + ŵ filter": ("filtered", tuple(np.geomspace(0.03, 30.0, 8))),
            "tuned filtered + wide ŵ filter": ("filtered", tuple(np.geomspace(0.03, top, 10)))}



@dataclass(frozen=True)
class FixedSet:
    """Every fixed controller of one example, and the one chosen in advance (see :func:`fixed_set`).

    Parameters
    ----------
    example : str
    n, seed : int
        The study's draws (half train) and seed.
    n_tune : int
        The tuning draws (the first training draws).
    names : tuple of str
        In the order of :data:`FAMILIES`.
    controllers : dict
        ``{name: fdsc.Controller}``.
    family : dict
        ``{name: family}``.
    info : dict
        ``{name: {"lf", "hf", "hinf", "states", "size", "reads_estimate", "slowest",
        "expected_power"}}``: band peaks, H∞ norm, the controller's states, its largest gain from
        x to u, the slowest closed-loop time constant (s) and the mean output power in steady
        state under the class's mean spectrum (:func:`fdsc.expected_power`).
    train_score : dict
        ``{name: mean log energy over the training half}``.
    chosen : str
        The fixed controller chosen in advance.
    front_checks : list of dict
        Per static-front point: its peaks and whether a direct search beat it in both bands.
    design_checks : dict
        ``{LMI design: {"band", "peak", "search_peak", "optimal"}}``: whether a direct search
        lowers the peak the design was made for.
    pairs : dict
        ``{family: (LF-type controller, HF-type controller)}`` for the value of switching.
    pair_scores : dict
        ``{family: mean log energy of each of the pair over the tuning pieces of its type}``.
    tuning : dict
        ``{name: fdsc.TuneResult}``.
    shaping : fdsc.LTISystem
        The class's shaping filter.
    chosen_x : str
        The best fixed controller that reads x alone (least training score among them).
    chosen_found : str
        The best fixed controller reading x and ŵ found by the designs and the local searches,
        the optimal LTI controller of the class left out (:func:`best_found`).
    """

    example: str
    n: int
    seed: int
    n_tune: int
    names: tuple
    controllers: dict
    family: dict
    info: dict
    train_score: dict
    chosen: str
    front_checks: list
    design_checks: dict
    pairs: dict
    pair_scores: dict
    tuning: dict = field(repr=False)
    shaping: fdsc.LTISystem = field(repr=False)
    chosen_x: str = ""
    chosen_found: str = ""

    def ranking(self) -> list:
        """The names by training score, best first."""
        return sorted(self.names, key=lambda n: (self.train_score[n], self.names.index(n)))

    def best_of(self, family: str) -> str:
        """The member of a family of least training score.

        Parameters
        ----------
        family : str
            One of :data:`FAMILIES`.

        Returns
        -------
        str
        """
        members = [n for n in self.names if self.family[n] == family]
        return min(members, key=lambda n: self.train_score[n])


def tuning_draws(example: str, n: int, seed: int) -> list:
    """The tuning draws of a study of ``n`` draws: its first ``min(N_TUNE, n // 2)`` draws.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    n : int
        The study's draws.
    seed : int

    Returns
    -------
    list of Draw
    """
    return [seeded_draw(example, i, seed)[1] for i in range(min(N_TUNE, n // 2))]


def _pieces_by_type(draws):
    """``{"LF": [(part, length)], "HF": [...]}``: every segment of the draws, to run from rest."""
    out = {"LF": [], "HF": []}
    for dr in draws:
        br = dr.d.breaks
        for k, part in enumerate(dr.d.parts):
            length = round(min(float(br[k + 1]), dr.horizon) - float(br[k]), 6)
            if length > 0:
                out[dr.dominant[k]].append((part, length))
    return out


def _tones(pairs):
    """Frequencies and time-weighted powers of the tones of ``[(signal, length)]``."""
    w = np.concatenate([p.frequencies for p, _L in pairs])
    P = np.concatenate([L * p.amplitudes ** 2 / 2 for p, L in pairs])
    return w, P / sum(L for _p, L in pairs)


@functools.cache
@cached
def static_front(example: str) -> tuple:
    """The static front of an example and its dominance checks.

    Parameters
    ----------
    example : {"aircraft", "generic"}

    Returns
    -------
    front : fdsc.ParetoFront
        :data:`FRONT_POINTS` bounds from 1.02 times the LF design's LF peak to the H∞ gain's.
    checks : list of dict
        Per point: ``beta``, ``lf``, ``hf``, ``certified`` (Lemma 1 certifies its peaks),
        ``dominated`` (a direct search from the neighbouring points and the LQR gain found a gain
        beating it in both bands), ``by`` (that gain's ``[hf, lf]``, or None).
    """
    ex = _example(example)
    lo = fdsc.band_peak(ex.closed_loop("PassC-LF"), ex.bands["LF"]).gamma
    hi = fdsc.band_peak(ex.closed_loop("PassC-EF"), ex.bands["LF"]).gamma
    lo, hi = min(lo, hi) * 1.02, max(lo, hi)
    betas = [lo * (hi / lo) ** f for f in np.linspace(0.0, 1.0, FRONT_POINTS)]
    front = fdsc.pareto_front(ex.plant, ex.bands["HF"], ex.bands["LF"], betas, maxiter=FRONT_MAXITER)
    gains = [p.K if p is not None else None for p in front.points]
    K_lqr = fdsc.lqr_gain(ex.plant)
    checks = []
    for j, p in enumerate(front.points):
        if p is None:
            checks.append({"beta": float(front.betas[j]), "lf": None, "hf": None, "certified": None,
                           "dominated": None, "by": None})
            continue
        starts = [g for g in (gains[j - 1] if j else None, gains[j + 1] if j + 1 < len(gains) else None)
                  if g is not None] + [K_lqr]
        found = fdsc.dominating_gain(ex.plant, ex.bands["HF"], ex.bands["LF"], p.peak, starts,
                                     maxiter=CHECK_MAXITER)
        checks.append({"beta": float(p.beta), "lf": float(p.peak[1]), "hf": float(p.peak[0]),
                       "certified": p.certified, "dominated": found is not None,
                       "by": None if found is None else [float(v) for v in found[1]]})
    return front, checks


def law_front_gains(example: str) -> tuple:
    """The front points the cost law switches among: the two ends and the middle of the static
    front (names ``front 1``, ``front 5``, ``front 9``), so that the law's candidates do not grow
    with the front's resolution.

    Parameters
    ----------
    example : {"aircraft", "generic"}

    Returns
    -------
    names : tuple of str
    gains : tuple of ndarray
    """
    front, _checks = static_front(example)
    pts = [(j, p) for j, p in enumerate(front.points) if p is not None]
    keep = sorted({pts[0][0], pts[len(pts) // 2][0], pts[-1][0]})
    return tuple(f"front {j + 1}" for j in keep), tuple(front.points[j].K for j in keep)


def _design_checks(ex):
    """Whether a direct search (:func:`fdsc.optimize_gain`) lowers the band peak each LMI band
    design was made for: a design, not an optimum, when it does by more than 0.1 %."""
    out = {}
    for name, band in (("PassC-LF", ex.bands["LF"]), ("PassC-HF", ex.bands["HF"]),
                       ("PassC-EF", fdsc.Band.entire())):
        peak = fdsc.band_peak(ex.closed_loop(name), band).gamma
        try:
            found = fdsc.optimize_gain(ex.plant, band, ex.gains[name], n_starts=1).gamma_sweep
        except fdsc.IterationLimitError:
            found = math.nan                        # the search did not settle: no verdict
        out[name] = {"band": band.label, "peak": float(peak), "search_peak": float(found),
                     "optimal": None if math.isnan(found) else bool(found >= peak * (1 - 1e-3))}
    return out


def _tune(plant, pieces, starts, maxiter, name, structure="static", cap=None, corner=1.0):
    return fdsc.tune_controller(plant, [p for p, _L in pieces], [L for _p, L in pieces], starts,
                                structure=structure, hinf_cap=cap, corner=corner, maxiter=maxiter,
                                name=name)


@cached
def fixed_set(example: str, n: int, seed: int) -> FixedSet:
    """Every fixed controller of an example for its class, and the one chosen in advance.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    n : int
        The study's draws (the first half trains).
    seed : int

    Returns
    -------
    FixedSet
    """
    ex = _example(example)
    plant = ex.plant
    names, ctrls, fam, tuning = [], {}, {}, {}

    def add(name, c, family):
        names.append(name)
        ctrls[name] = fdsc.as_controller(c, plant, name)
        fam[name] = family

    for nm in comparators(example):
        add(nm, ex.gains[nm], "comparator set")
    front, checks = static_front(example)
    for j, p in enumerate(front.points):
        if p is not None:
            add(f"front {j + 1}", p.K, "static front")
    K_lqr = fdsc.lqr_gain(plant)
    add("LQR", K_lqr, "LQR")
    dyn = fdsc.dynamic_front(plant, ex.bands["LF"], ex.bands["HF"], DYN_RATIOS, u_penalty=U_PENALTY)
    for j, d in enumerate(dyn.designs):
        if d is not None:
            add(f"weighted H∞ {j + 1}", d.controller, "dynamic front")
    tune = tuning_draws(example, n, seed)
    whole = [(dr.d, dr.horizon) for dr in tune]
    edge = [math.sqrt(ex.bands["LF"].upper * ex.bands["HF"].lower)]
    by_type = _pieces_by_type(tune)
    shaping = fdsc.fit_shaping_filter(*_tones(by_type["LF"] + by_type["HF"]), edge)
    add("H2 (x)", fdsc.h2_controller(plant, shaping, reads="x"), "H2")
    add("H2 (x, ŵ)", fdsc.h2_controller(plant, shaping, reads="x+w"), "H2")
    maxiter = TUNE_MAXITER if len(tune) >= N_TUNE else RECORD_MAXITER
    cap = CAP_FACTOR * min(fdsc.band_peak(ctrls[k].closed_loop(plant), fdsc.Band.entire()).gamma
                           for k in names
                           if fam[k] in ("comparator set", "static front") and k != "open loop")
    # the search starts from the LQR gain and from the band design of the class's main band
    # (the aircraft's PassC-LF; the generic example's middle front point)
    mid = [p for p in front.points if p is not None]
    starts = [K_lqr, ex.gains["PassC-LF"] if example == "aircraft" else mid[len(mid) // 2].K]
    for label, kw in (("tuned", {}), ("tuned (H∞ cap)", {"cap": cap})):
        res = _tune(plant, whole, starts, maxiter, label, **kw)
        tuning[label] = res
        add(label, res.controller, "tuned")
        fres = _tune(plant, whole, [res.controller.D], maxiter, label.replace("tuned", "tuned filtered"),
                     structure="filtered", corner=edge[0], **kw)
        tuning[fres.controller.name] = fres
        add(fres.controller.name, fres.controller, "tuned")
    # the same, reading ŵ too: the information every law on the disturbance estimate has
    ff_iter = min(maxiter, FF_MAXITER)
    ff_rounds = FF_ROUNDS if len(tune) >= N_TUNE else RECORD_ROUNDS
    for label, (structure, ff) in ff_poles(example).items():
        start = ctrls["tuned"].D if structure == "static" else ctrls["tuned filtered"]
        res = fdsc.tune_controller(plant, [p for p, _L in whole], [L for _p, L in whole], [start],
                                   structure=structure, feedforward=ff, maxiter=ff_iter, rounds=ff_rounds,
                                   name=label)
        tuning[label] = res
        add(label, res.controller, "tuned (x, ŵ)")
    # the LQR gain with the widest of these feedforwards tuned for the class (the predictive law's base)
    wide = ff_poles(example)["tuned filtered + wide ŵ filter"][1]
    res = fdsc.tune_controller(plant, [p for p, _L in whole], [L for _p, L in whole], [K_lqr],
                               structure="held", feedforward=wide, name="LQR + ŵ filter")
    tuning["LQR + ŵ filter"] = res
    add("LQR + ŵ filter", res.controller, "tuned (x, ŵ)")
    # the optimal LTI controller of the class, reading x and ŵ: the Wiener–Hopf optimum for the
    # class's mean spectrum (no draws), to which every other fixed controller is compared
    cls = segment_class(example)
    opt = fdsc.optimal_lti(plant, cls, name=OPTIMAL_LTI)
    tuning[OPTIMAL_LTI] = opt
    add(OPTIMAL_LTI, opt.controller, "optimal LTI")
    # the pairs for the value of switching: each design made for one type of segment
    pairs, pair_scores = {}, {}
    pairs["LQR + ŵ filter"] = tuple(
        fdsc.tune_controller(plant, [p for p, _L in by_type[typ] or by_type["HF" if typ == "LF" else "LF"]],
                             [L for _p, L in by_type[typ] or by_type["HF" if typ == "LF" else "LF"]], [K_lqr],
                             structure="held", feedforward=wide,
                             name=f"LQR + ŵ filter for {typ} segments").controller for typ in ("LF", "HF"))
    for fam_name in ("tuned", "tuned filtered", "H2 (x)", "H2 (x, ŵ)"):
        pair = []
        for typ in ("LF", "HF"):
            pcs = by_type[typ] or by_type["LF" if typ == "HF" else "HF"]
            label = f"{fam_name} for {typ} segments"
            if fam_name == "tuned":
                c = _tune(plant, pcs, [ctrls["tuned"].D], maxiter, label).controller
            elif fam_name == "tuned filtered":
                c = _tune(plant, pcs, [ctrls["tuned filtered"]], maxiter, label,
                          structure="filtered").controller
            else:
                F = fdsc.fit_shaping_filter(*_tones(pcs), edge)
                c = fdsc.h2_controller(plant, F, reads="x" if fam_name == "H2 (x)" else "x+w", name=label)
            pair.append(c)
        pairs[fam_name] = tuple(pair)
    # the training half's score of every fixed controller, exactly
    train = [seeded_draw(example, i, seed)[1] for i in range(n // 2)]
    from fdsc.tuning import _ClassEnergies

    energies = _ClassEnergies([dr.d for dr in train], [dr.horizon for dr in train])
    info, score = {}, {}
    for nm in names:
        c = ctrls[nm]
        loop = c.closed_loop(plant)
        stable = loop.is_hurwitz()
        info[nm] = {"lf": fdsc.band_peak(loop, ex.bands["LF"]).gamma if stable else math.inf,
                    "hf": fdsc.band_peak(loop, ex.bands["HF"]).gamma if stable else math.inf,
                    "hinf": fdsc.band_peak(loop, fdsc.Band.entire()).gamma if stable else math.inf,
                    "states": c.n_states, "size": c.size(), "reads_estimate": c.reads_estimate,
                    "slowest": (1.0 / float(np.min(np.abs(loop.poles().real)))) if stable else math.inf,
                    "expected_power": fdsc.expected_power(loop, cls) if stable else math.inf}
        score[nm] = float(np.mean(np.log(energies(loop)))) if stable else math.inf
    for fam_name, pair in pairs.items():
        pair_scores[fam_name] = [float(np.mean(np.log(energies(c.closed_loop(plant))))) for c in pair]
    chosen = min(names, key=lambda k: (score[k], names.index(k)))
    chosen_x = min((k for k in names if not ctrls[k].reads_estimate),
                   key=lambda k: (score[k], names.index(k)))
    return FixedSet(example, n, seed, len(tune), tuple(names), ctrls, fam, info, score, chosen, checks,
                    _design_checks(ex), pairs, pair_scores, tuning, shaping, chosen_x,
                    best_found(names, fam, ctrls, score))


def best_found(names, family, controllers, score) -> str:
    """The fixed controller reading x and ŵ of least training score among the designs and the
    local searches (every family but the optimal LTI controller of the class).

    Parameters
    ----------
    names : sequence of str
    family, controllers, score : dict
        Per name: its family, its controller and its training score.

    Returns
    -------
    str
    """
    return min((k for k in names if controllers[k].reads_estimate and family[k] != "optimal LTI"),
               key=lambda k: (score[k], list(names).index(k)))


def _slowest_ok(fs: FixedSet, name: str) -> bool:
    """Whether a copy restarted every ``RESTART`` seconds can predict the controller's cost."""
    return fs.info[name]["slowest"] <= RESTART
