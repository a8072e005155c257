"""Chapter 'ladder': what can any controller do on the class? From the non-causal limit down to the
paper's law, every rung with the information of the laws (x and the estimate ŵ) where it reads
the disturbance, each scored against the best fixed controller with that information.

The rungs, per test draw of the non-stationary class (:mod:`fdsc.paper.pays.disturbance_law_draws`):

* the **non-causal limit** (:func:`fdsc.noncausal_limit`): the least energy any controller reaches
  knowing the whole draw in advance — a bound;
* the **predictive law** (:class:`fdsc.PredictiveLaw`): the LQ gain with the class's best
  feedforward filter of ŵ for it (``LQR + ŵ filter``), corrected to the adjoint of the tones it
  identifies in the last seconds of ŵ — realizable; its window and its test of a fit chosen on
  training draws (:data:`PREDICTIVE_GRID`);
* the same law with the current segment's tones **known** (ideal identification, no break
  foreseen) — a reference;
* the **band-scheduled feedforward**: the LQ gain with a feedforward filter of ŵ designed for
  each type of segment, switched at the true breaks (a reference) or by the band-power law on ŵ
  (realizable, its forgetting and hysteresis chosen on training draws);
* the **best fixed controller with the information of the laws** (x and ŵ), chosen in advance
  among every fixed controller (:func:`fdsc.paper.pays.fixed_designs.fixed_set`), and the best
  one that reads x alone;
* the gain-switching laws of chapter 'disturbance_law' and the paper's FDSC (from the same draws).

Every energy is exact between the breaks of the draw (no step). The ratio of each rung to the
best fixed controller (x, ŵ) is summarized by its median with a bootstrap 95 % interval, its win
rate, and, for the causal laws, the share of the headroom (in log) between the best fixed
controller and the limit that it takes.
"""

from __future__ import annotations

import math

import numpy as np

import fdsc
from fdsc.paper.pays.disturbance_law_draws import (
    DECIDE_EVERY,
    HYSTERESES,
    LAMBDAS,
    RESTART,
    SEED,
    _example,
    seeded_draw,
)
from fdsc.paper.pays.fixed_designs import FixedSet
from fdsc.paper.shared.stats import bootstrap_median

__all__ = ["PREDICTIVE_GRID", "N_CHOOSE", "law_band", "predictive_law", "scheduled",
           "choose_settings", "ladder_draw", "ladder_noisy", "direct_dwell", "summarize", "bootstrap_median",
           "RUNGS", "RUNG_WORDS", "MAX_TONES", "N_RECHECK", "recheck_ladder",
           "best_realizable", "answer", "record_part", "REALIZABLE", "FIXED_RUNGS", "SINCE_BREAK",
           "control_rows", "control_energy", "control_peak", "excess_by_time", "N_PEAK", "PEAK_DT"]

#: The predictive law's settings tried on the training draws: seconds of ŵ per identification
#: and the largest share of the window's power its fit may leave unexplained; and the most tones
#: it identifies (fixed).
PREDICTIVE_GRID = {"window": (1.0, 2.0, 4.0), "max_residual": (0.03, 0.3)}
MAX_TONES = 12
#: Training draws the settings are chosen on (the first ones).
N_CHOOSE = 16
#: The rungs in the order of the ladder (top: the limit), with what each reads.
#: The rung every other is scored against (its own ratio is 1 on every draw).
REFERENCE = "best fixed (x, ŵ)"
RUNGS = ("limit", "known tones", "predictive", "scheduled at breaks", "scheduled", "best fixed (x, ŵ)",
         "best found (x, ŵ)", "best fixed (x)", "gain switching", "FDSC")
#: Each rung in words (the glossary defines them).
RUNG_WORDS = {
    "limit": "non-causal limit (knows the whole draw)",
    "known tones": "LQ + adjoint of the current tones, known",
    "predictive": "predictive law (tones identified in ŵ)",
    "scheduled at breaks": "LQ + feedforward per segment type, switched at the breaks",
    "scheduled": "LQ + feedforward per segment type, switched on ŵ",
    "best fixed (x, ŵ)": "best fixed controller reading x and ŵ",
    "best found (x, ŵ)": "best fixed controller reading x and ŵ found by design and local search",
    "best fixed (x)": "best fixed controller reading x alone",
    "gain switching": "best law switching controllers on ŵ",
    "FDSC": "the paper's FDSC",
}
#: The fixed rungs whose control effort and robustness are reported (with the predictive law,
#: whose feedback is its base's).
FIXED_RUNGS = ("best fixed (x, ŵ)", "best found (x, ŵ)", "best fixed (x)")
#: Edges (s) of the bins of time since the last break of the disturbance in which the predictive
#: law's excess over the known-tones reference is summed.
SINCE_BREAK = (0.0, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0, math.inf)
#: The causal rungs whose share of the headroom is reported.
REALIZABLE = ("predictive", "scheduled", "gain switching", "FDSC")


def law_band(example: str) -> tuple:
    """``((lo, hi), step)``: where the predictive law identifies tones — from the geometric mean
    of the bands' edges to 1.2 times the top of the class's HF tones — and its sampling step
    π/(2.5 hi).

    Parameters
    ----------
    example : {"aircraft", "generic"}

    Returns
    -------
    tuple
    """
    ex = _example(example)
    lo = math.sqrt(ex.bands["LF"].upper * ex.bands["HF"].lower)
    hi = 1.2 * float(ex.hf_tones[1])
    return (lo, hi), math.pi / (2.5 * hi)


def predictive_law(example: str, fs: FixedSet, window: float, max_residual: float) -> fdsc.PredictiveLaw:
    """The predictive law of an example at one setting, its base the class's ``LQR + ŵ filter``.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    fs : FixedSet
    window, max_residual : float

    Returns
    -------
    fdsc.PredictiveLaw
    """
    band, step = law_band(example)
    return fdsc.PredictiveLaw(_example(example).plant, band, window=window, max_tones=MAX_TONES, step=step,
                              update=0.5, max_residual=max_residual, base=fs.controllers["LQR + ŵ filter"])


def scheduled(example: str, fs: FixedSet, decided: bool = True) -> fdsc.Supervisor:
    """The band-scheduled feedforward: the LQ gain with the feedforward designed for LF- and for
    HF-dominated segments (``fs.pairs["LQR + ŵ filter"]``), in the direct realization (only the
    feedforward switches); decided by the band-power law on ŵ, or held per segment.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    fs : FixedSet
    decided : bool, optional

    Returns
    -------
    fdsc.Supervisor
    """
    ex = _example(example)
    bands = [ex.bands["LF"], ex.bands["HF"]] if decided else None
    return fdsc.Supervisor(ex.plant, list(fs.pairs["LQR + ŵ filter"]),
                           law="band_power" if decided else "cost", bands=bands, decide_every=DECIDE_EVERY,
                           restart=RESTART)


def _segment_choice(prep, dr):
    from fdsc.paper.pays.disturbance_law_runs import segment_choice

    return segment_choice(prep, dr)


def _setting_score(example, fs, window, max_residual, index, seed):
    """log of the predictive law's energy on training draw ``index`` at one setting."""
    dr = seeded_draw(example, index, seed)[1]
    return math.log(predictive_law(example, fs, window, max_residual).run(dr.d, dr.horizon).energy)


def choose_settings(example: str, fs: FixedSet, seed: int = SEED, n: int = N_CHOOSE, executor=None) -> dict:
    """The predictive law's setting and the scheduled law's forgetting and hysteresis of least
    mean log energy on the first ``n`` training draws.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    fs : FixedSet
    seed : int, optional
    n : int, optional
    executor : optional
        Where the runs go (:func:`fdsc.paper.pays.disturbance_law_full.map_draws`).

    Returns
    -------
    dict
        ``{"window", "max_residual", "max_tones", "forgetting", "hysteresis", "scores"}``.
    """
    from fdsc.paper.pays.stored_study import map_draws

    n = min(n, fs.n // 2)
    draws = [seeded_draw(example, i, seed)[1] for i in range(n)]
    grid = [(w, m) for w in PREDICTIVE_GRID["window"] for m in PREDICTIVE_GRID["max_residual"]]
    logs = map_draws(_setting_score, [(example, fs, w, m, i, seed) for w, m in grid for i in range(n)],
                     executor)
    scores = {k: float(np.mean(logs[j * n:(j + 1) * n])) for j, k in enumerate(grid)}
    w, m = min(scores, key=lambda k: (scores[k], k))
    sup = scheduled(example, fs)
    sched = {}
    for dr in draws:
        prep = sup.prepare(dr.d, dr.horizon)
        for lam in LAMBDAS:
            for h in HYSTERESES:
                sched.setdefault((lam, h), []).append(
                    math.log(prep.run(forgetting=lam, hysteresis=h).energy))
    lam, h = min(sched, key=lambda k: (float(np.mean(sched[k])), k))
    return {"window": float(w), "max_residual": float(m), "max_tones": MAX_TONES, "forgetting": float(lam),
            "hysteresis": float(h), "scores": {f"{k[0]:g}/{k[1]:g}": v for k, v in scores.items()}}


def control_rows(plant) -> np.ndarray:
    """The rows of z that hold only ``D2 u`` (no x, no d): their energy is the control effort as
    z weighs it.

    Parameters
    ----------
    plant : fdsc.Plant

    Returns
    -------
    (p,) bool ndarray
    """
    return (np.all(plant.C == 0, axis=1) & np.all(plant.D1 == 0, axis=1)
            & np.any(plant.D2 != 0, axis=1))


def control_energy(plant, controller, d, horizon: float) -> float:
    """``∫ ‖(D2 u)_rows‖²`` of a fixed controller on one draw (the rows of :func:`control_rows`),
    exact (:func:`fdsc.loop_energy` of the closed loop with those outputs).

    Parameters
    ----------
    plant : fdsc.Plant
    controller : fdsc.Controller
    d : fdsc.Piecewise or fdsc.Sinusoids
    horizon : float

    Returns
    -------
    float
    """
    loop = plant.closed_loop(controller)
    rows = control_rows(plant)
    return float(fdsc.loop_energy(fdsc.LTISystem(loop.A, loop.B, loop.C[rows], loop.D[rows]), d, horizon))


#: Test draws on which the peak of the control effort of the fixed rungs is measured, and the
#: step (s) of those sampled runs.
N_PEAK, PEAK_DT = 3, 1e-3


def control_peak(plant, controller, d, horizon: float, dt: float = PEAK_DT) -> float:
    """The largest ``|(D2 u)_r|`` over the rows of :func:`control_rows` of a fixed controller on
    one draw, sampled every ``dt`` (:func:`fdsc.simulate_stream` with traces).

    Parameters
    ----------
    plant : fdsc.Plant
    controller : fdsc.Controller
    d : fdsc.Piecewise or fdsc.Sinusoids
    horizon, dt : float

    Returns
    -------
    float
    """
    loop = plant.closed_loop(controller)
    rows = control_rows(plant)
    run = fdsc.simulate_stream(fdsc.LTISystem(loop.A, loop.B, loop.C[rows], loop.D[rows]), d,
                               round(horizon / dt) * dt, dt, trace_every=100 * dt)
    return float(max(np.abs(run.trace.z_lo).max(), np.abs(run.trace.z_hi).max()))


def excess_by_time(run, ref, d, edges=SINCE_BREAK) -> dict:
    """The energy of ``run`` over ``ref`` (two runs of a :class:`fdsc.PredictiveLaw` on the same
    pieces) summed in bins of time since the last break of ``d``.

    Parameters
    ----------
    run, ref : fdsc.PredictiveRun
    d : fdsc.Piecewise or fdsc.Sinusoids
    edges : sequence of float, optional
        The bins' edges (s).

    Returns
    -------
    dict
        ``{"excess", "reference", "seconds"}``: per bin, the excess energy, the reference's
        energy and the seconds of the run in it.
    """
    if run.pieces.shape != ref.pieces.shape or not np.allclose(run.pieces[:, :2], ref.pieces[:, :2]):
        raise ValueError("run and ref must be integrated on the same pieces")
    breaks = np.asarray(d.breaks if isinstance(d, fdsc.Piecewise) else [0.0], dtype=float)
    t0 = run.pieces[:, 0]
    last = breaks[np.clip(np.searchsorted(breaks, t0 + 1e-9, side="right") - 1, 0, None)]
    b = np.clip(np.searchsorted(np.asarray(edges), t0 - last, side="right") - 1, 0, len(edges) - 2)
    nb = len(edges) - 1
    return {"excess": np.bincount(b, run.pieces[:, 2] - ref.pieces[:, 2], nb).tolist(),
            "reference": np.bincount(b, ref.pieces[:, 2], nb).tolist(),
            "seconds": np.bincount(b, run.pieces[:, 1] - run.pieces[:, 0], nb).tolist()}


def ladder_draw(example: str, index: int, seed: int, fs: FixedSet, settings: dict) -> dict:
    """The energies of the ladder's computed rungs on draw ``index``.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    index : int
    seed : int
    fs : FixedSet
    settings : dict
        :func:`choose_settings`.

    Returns
    -------
    dict
        ``{rung: energy}`` for the limit, the predictive law (and its tones known), the
        scheduled feedforward (at the breaks and decided), the best fixed controllers (x, ŵ)
        (the one chosen in advance and the best found by design and search) and (x);
        ``index``; ``control``: the control effort (:func:`control_energy`) of the fixed rungs and
        the predictive law; ``excess``: the predictive law over its tones known, by time since
        the last break (:func:`excess_by_time`).
    """
    ex, dr = seeded_draw(example, index, seed)
    law = predictive_law(example, fs, settings["window"], settings["max_residual"])
    sup = scheduled(example, fs)
    prep = sup.prepare(dr.d, dr.horizon)
    known, pred = law.run_known(dr.d, dr.horizon), law.run(dr.d, dr.horizon)
    fixed = {"best fixed (x, ŵ)": fs.chosen, "best found (x, ŵ)": fs.chosen_found,
             "best fixed (x)": fs.chosen_x}
    control = {rung: control_energy(ex.plant, fs.controllers[name], dr.d, dr.horizon)
               for rung, name in fixed.items()}
    control["predictive"] = float(pred.output_energy[control_rows(ex.plant)].sum())
    return {"index": index,
            "limit": fdsc.noncausal_limit(ex.plant, dr.d, dr.horizon).energy,
            "known tones": known.energy,
            "predictive": pred.energy,
            "scheduled at breaks": prep.segment_law(_segment_choice(prep, dr)),
            "scheduled": prep.run(forgetting=settings["forgetting"],
                                  hysteresis=settings["hysteresis"]).energy,
            **{rung: prep.energy_of(fs.controllers[name]) for rung, name in fixed.items()},
            "control": control, "excess": excess_by_time(pred, known, dr.d)}


def direct_dwell(example: str, fs: FixedSet, law: str):
    """The gain-switching law's candidates in the direct realization (u from the active
    candidate alone, no copies) and the Geromel–Colaneri dwell time that certifies it.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    fs : FixedSet
    law : str
        The chosen setting ``candidates/law/realization/λ/h``.

    Returns
    -------
    (fdsc.Supervisor, float or None)
        None if no dwell up to 10³ s is certified.
    """
    from fdsc.paper.pays.disturbance_law_runs import law_candidates

    ex = _example(example)
    cand, kind = law.split("/")[:2]
    _names, ctrls = law_candidates(example, cand, fs)
    bands = [ex.bands["LF"], ex.bands["HF"]] if kind == "band_power" else None
    sup = fdsc.Supervisor(ex.plant, list(ctrls), law=kind, bands=bands, decide_every=DECIDE_EVERY,
                          restart=RESTART)
    try:
        tau = fdsc.geromel_colaneri_dwell(sup.switched_loops(), tau_max=1e3).tau
    except fdsc.SolverError:
        tau = None
    return sup, tau


def ladder_noisy(example: str, index: int, seed: int, fs: FixedSet, settings: dict, snr_db: float,
                 law: str | None = None, tau=None) -> dict:
    """The realizable rungs that read ŵ on a noisy estimate (the noise of chapter
    'disturbance_law', seeded by ``[seed, index, 1]``), each over the best fixed controller
    (x, ŵ) on the same noisy estimate; and that controller over itself on the exact one.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    index, seed : int
    fs : FixedSet
    settings : dict
    snr_db : float

    law : str, optional
        The gain-switching law's setting: run also in the direct realization with the dwell
        ``tau`` enforced, deciding on the noisy estimate (no copies carry the noise into u).
    tau : float, optional
        Its certified dwell (:func:`direct_dwell`).

    Returns
    -------
    dict
        ``{"predictive", "scheduled", "fixed_noise_cost"}`` ratios, and ``"gain switching
        (direct)"`` when ``law`` is given and a dwell is certified.
    """
    from fdsc.paper.pays.disturbance_law_robust import noisy_estimate

    ex, dr = seeded_draw(example, index, seed)
    what = noisy_estimate(ex, dr, snr_db, np.random.default_rng([seed, index, 1]))
    pred = predictive_law(example, fs, settings["window"], settings["max_residual"])
    sup = scheduled(example, fs)
    built = sup.prepare(dr.d, dr.horizon, estimate=what)
    best = fs.controllers[fs.chosen]
    ref = built.energy_of(best)
    exact = sup.prepare(dr.d, dr.horizon).energy_of(best)
    out = {"predictive": pred.run(dr.d, dr.horizon, estimate=what).energy / ref,
           "scheduled": built.run(forgetting=settings["forgetting"],
                                  hysteresis=settings["hysteresis"]).energy / ref,
           "fixed_noise_cost": ref / exact}
    if law is not None and tau is not None:
        sup_d, _tau = direct_dwell(example, fs, law)
        lam, h = (float(v) for v in law.split("/")[-2:])
        run = sup_d.prepare(dr.d, dr.horizon, estimate=what).run(forgetting=lam, hysteresis=h, min_dwell=tau)
        out["gain switching (direct)"] = run.energy / ref
    return out


def summarize(ratios: dict) -> dict:
    """Per rung: median with its bootstrap interval, win rate, 95th percentile; per causal law the
    median share of the headroom (log ratio over the limit's log ratio, per draw).

    Parameters
    ----------
    ratios : dict
        ``{rung: per-draw ratios to the best fixed controller (x, ŵ)}`` (the limit among them).

    Returns
    -------
    dict
    """
    from fdsc.paper.shared.examples import beats

    out = {}
    lim = np.log(np.asarray(ratios["limit"], dtype=float))
    for rung, q in ratios.items():
        q = np.asarray(q, dtype=float)
        m, lo, hi = bootstrap_median(q)
        row = {"median": m, "low": lo, "high": hi, "win_rate": float(np.mean(beats(q))),
               "p95": float(np.quantile(q, 0.95)), "draws": int(q.size)}
        if rung in REALIZABLE or rung in ("known tones", "scheduled at breaks"):
            share = np.log(q) / lim
            row["headroom_share"] = bootstrap_median(share)
        out[rung] = row
    return out


#: Test draws of the stored study the build recomputes per example (the build-time check).
N_RECHECK = 1


def recheck_ladder(full: dict, example: str, k: int = N_RECHECK) -> dict:
    """The ladder's computed rungs on the stored study's first ``k`` test draws, recomputed now
    from the stored controllers and settings, against the stored ratios.

    Parameters
    ----------
    full : dict
        The stored full study (:func:`fdsc.paper.pays.disturbance_law.load_full`).
    example : {"aircraft", "generic"}
    k : int, optional
        Test draws recomputed, between 1 and the stored ladder's test draws.

    Returns
    -------
    dict
        ``{"draws", "rungs", "largest_difference"}`` (the largest relative difference of a ratio).

    Raises
    ------
    TypeError
        If ``full`` is not a dict (e.g. None: :func:`load_full` outside a checkout).
    ValueError
        If ``example`` is not one of the two examples, or ``k`` is not a count between 1 and the
        stored test draws (as :func:`fdsc.paper.pays.disturbance_law_full.recheck_stored`).
    KeyError
        Naming the key the stored study lacks (the example, its ``ladder``, or what the ladder
        keeps).
    """
    from fdsc._validation import as_count
    from fdsc.paper.pays.stored_study import _stored_example, stored_fixed_set

    r = _stored_example(full, example)
    if "ladder" not in r:
        raise KeyError(f"full[{example!r}]: the stored study has no key 'ladder' (a study computed before "
                       "the ladder: rerun python -m fdsc disturbance-law)")
    lad = r["ladder"]
    for key in ("test_indices", "settings", "ratios"):
        if key not in lad:
            raise KeyError(f"full[{example!r}]['ladder']: the stored study has no key {key!r}")
    k = as_count("k", k, 1)
    if k > len(lad["test_indices"]):
        raise ValueError(f"k must be at most the {len(lad['test_indices'])} stored test draws of the ladder, "
                         f"but found {k}")
    fs = stored_fixed_set(full, example)
    worst = 0.0
    for j, index in enumerate(lad["test_indices"][:k]):
        row = ladder_draw(example, index, full["seed"], fs, lad["settings"])
        ref = row["best fixed (x, ŵ)"]
        for rung, ratios in lad["ratios"].items():
            if rung in row:
                worst = max(worst, abs(row[rung] / ref / ratios[j] - 1.0))
    return {"draws": k, "rungs": sum(r in lad["ratios"] for r in RUNGS), "largest_difference": worst}


def best_realizable(summary: dict) -> str:
    """The realizable rung of least median ratio.

    Parameters
    ----------
    summary : dict

    Returns
    -------
    str
    """
    return min((r for r in REALIZABLE if r in summary), key=lambda r: summary[r]["median"])


def answer(full: dict) -> dict:
    """Per example, the ladder's answer in one sentence (Markdown), from the stored study: the
    best realizable controller against the best fixed controller with equal information and the
    limit.

    Parameters
    ----------
    full : dict

    Returns
    -------
    dict
        ``{example: str}``.
    """
    from fdsc.paper.shared.prose import count, pct, share_ci, times_ci

    out = {}
    for example in ("aircraft", "generic"):
        lad = full[example]["ladder"]
        s = lad["summary"]
        best = best_realizable(s)
        b, lim, x = s[best], s["limit"], s["best fixed (x)"]
        share = share_ci(b["headroom_share"])
        out[example] = (
            f"the best realizable controller is the {RUNG_WORDS[best]}: a median {times_ci(b)} the energy "
            f"of the best fixed controller reading x and ŵ, less energy on {pct(b['win_rate'])} of "
            f"{count(b['draws'])} test draws, where no controller can go below the non-causal "
            f"limit's {times_ci(lim)}; per draw it takes a median {share} of that headroom (in "
            f"log). The best fixed controller reading x alone has {times_ci(x)}.")
    return out


def record_part():
    """Record entry ``ladder`` (new): the stored study's ladder per example (stored, with its
    commit) and the build's recomputation of its first test draw.

    Returns
    -------
    RecordPart
    """
    from fdsc.paper.pays.stored_study import load_full
    from fdsc.paper.shared.results import RecordPart, entry

    full = load_full()
    if full is None or "ladder" not in full.get("aircraft", {}):
        return RecordPart((entry("ladder", "our computation (the ladder)", None, None, "new",
                                 "the stored study is not in this checkout"),))
    value = {}
    for example in ("aircraft", "generic"):
        lad = full[example]["ladder"]
        value[example] = {"summary": lad["summary"], "settings": lad["settings"],
                          "recheck": recheck_ladder(full, example)}
    words = answer(full)
    note = (f"stored full study (commit {full['commit'][:12]}): "
            + " ".join(f"{e.capitalize()}: {w}" for e, w in words.items())
            + " The build recomputes the first test draw of each example from the stored "
              "controllers.")
    return RecordPart((entry("ladder", "our computation (the ladder, stored study)", None, value, "new",
                             note),))
