"""Chapter 'disturbance_law': does a switching law that decides on the disturbance estimate pay?

Seeded non-stationary draws on both examples: 6–10 segments of lengths 20 s + Exp(mean 80 s) on
a 10 ms grid, each LF- or HF-dominated with probability ½ (the dominating band holding the share
α ~ U[0.8, 1] of the power), three tones per band log-uniform in the example's tone ranges, or,
with probability :data:`NOISE_SHARE`, band-limited noise (:data:`NOISE_TONES` tones per band with
Rayleigh amplitudes, a random-phase multisine); unit power per segment, random phases.

Against them: the predictive-cost supervisor and the band-power law of :mod:`fdsc.supervisor`,
tuned on the first half of the draws (forgetting λ, hysteresis h, realization direct or through
copies) and scored on the second half; the fixed gains of the comparator set and of the
multi-band Pareto front (:func:`fdsc.pareto_front`); the best of them chosen in advance on the
training half (least mean log energy); the best of each test draw (oracle); the ideal segment
law (PassC-LF on LF-dominated pieces, PassC-HF on HF ones); and the clairvoyant per-segment
oracle (on each piece the candidate with the least energy from the carried-over state). All
energies are exact integrals (:mod:`fdsc._blocks`), from rest.

The record computes a seeded subset (:data:`N_RECORD` draws per example); the full study
(:data:`N_FULL` draws per example) runs behind ``python -m fdsc disturbance-law --full`` on a
process pool or a Dask client, and writes :data:`FULL_FILE`, which the chapter reads.
"""

from __future__ import annotations

import functools
import json
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

import fdsc

from .._validation import as_choice, as_count
from .baselines import aircraft_example
from .cache import cached
from .comparators import comparators
from .examples import beats
from .generic_example import generic_example
from .results import RecordPart, entry

__all__ = ["SEED", "N_RECORD", "N_FULL", "LAMBDAS", "HYSTERESES", "DECIDE_EVERY", "RESTART",
           "NOISE_SHARE", "NOISE_TONES", "HEADROOM_MIN", "FULL_FILE", "Draw", "draw", "front",
           "candidates", "lqr", "certificate", "draw_result", "Study", "study", "rho_t_family",
           "record_part", "full_study", "load_full"]

SEED = 32
#: Draws per example in the record (half train, half test) and in the full study.
N_RECORD, N_FULL = 16, 500
#: The tuning grid (on the training half).
LAMBDAS, HYSTERESES = (0.05, 0.2, 1.0), (0.1, 0.3)
#: The law's decision interval and restart period (s).
DECIDE_EVERY, RESTART = 0.1, 20.0
#: Probability that a segment is band-limited noise, and its tones per band.
NOISE_SHARE, NOISE_TONES = 0.25, 6
#: Where ``--full`` writes the full study (relative to the repository root).
FULL_FILE = Path("book") / "data" / "disturbance_law_full.json"
#: The fixed gains the ideal segment law holds on LF- and HF-dominated pieces.
IDEAL_PAIR = ("PassC-LF", "PassC-HF")
#: Bounds on the LF peak of the Pareto front, as fractions of the way (in log) from the LF
#: design's LF peak to the H∞ design's.
FRONT_FRACTIONS = (0.0, 0.5, 1.0)
#: The oracle's least relative gain over the fixed gain chosen in advance for a draw to count
#: in the median share of the oracle's gain that the law realizes.
HEADROOM_MIN = 0.01
#: Nelder–Mead iterations per start of the front's search (the peaks agree with 400 to 4 digits).
FRONT_MAXITER = 200


@functools.cache
def _example(name):
    as_choice("example", name, ("aircraft", "generic"))
    return aircraft_example() if name == "aircraft" else generic_example()


@dataclass(frozen=True)
class Draw:
    """One non-stationary disturbance (see :func:`draw`).

    Parameters
    ----------
    d : fdsc.Piecewise
    horizon : float
        Run length (s): the end of the last segment, up to the next decision point.
    dominant : tuple of str
        "LF" or "HF" per segment.
    noise : tuple of bool
        Whether each segment is band-limited noise.
    """

    d: fdsc.Piecewise
    horizon: float
    dominant: tuple
    noise: tuple

    @property
    def changes(self) -> int:
        """Changes of the dominating band between consecutive segments."""
        return int(sum(a != b for a, b in zip(self.dominant[:-1], self.dominant[1:], strict=True)))


def draw(example, rng: np.random.Generator) -> Draw:
    """One seeded non-stationary disturbance of the module docstring's distribution.

    Parameters
    ----------
    example : Example
    rng : numpy.random.Generator

    Returns
    -------
    Draw

    Examples
    --------
    >>> dr = draw(aircraft_example(), np.random.default_rng(0))
    >>> 6 <= len(dr.dominant) <= 10, [round(p.power(), 12) for p in dr.d.parts][:2]
    (True, [1.0, 1.0])
    """
    k = int(rng.integers(6, 11))
    lengths = np.round((20.0 + rng.exponential(80.0, k)) * 100.0) / 100.0
    parts, dom, noise = [], [], []
    for _ in range(k):
        lf = bool(rng.random() < 0.5)
        alpha = rng.uniform(0.8, 1.0)
        is_noise = bool(rng.random() < NOISE_SHARE)
        m = NOISE_TONES if is_noise else 3
        sums = []
        for (lo, hi), share in ((example.lf_tones, alpha if lf else 1 - alpha),
                                (example.hf_tones, 1 - alpha if lf else alpha)):
            w = np.exp(rng.uniform(np.log(lo), np.log(hi), m))
            a = rng.rayleigh(1.0, m) if is_noise else rng.uniform(0.5, 1.5, m)
            a = a * np.sqrt(share / (0.5 * np.sum(a**2)))
            sums.append(fdsc.Sinusoids(a, w, rng.uniform(0.0, 2 * np.pi, m)))
        parts.append(sums[0] + sums[1])
        dom.append("LF" if lf else "HF")
        noise.append(is_noise)
    breaks = np.round(np.r_[0.0, np.cumsum(lengths)] * 100.0) / 100.0
    horizon = math.ceil(breaks[-1] / DECIDE_EVERY - 1e-9) * DECIDE_EVERY
    return Draw(fdsc.Piecewise(breaks, parts), round(horizon, 6), tuple(dom), tuple(noise))


@functools.cache
@cached
def front(example: str = "aircraft") -> fdsc.ParetoFront:
    """The multi-band Pareto front of the example: least HF peak with the LF peak at most β, β
    from the LF design's LF peak to the H∞ design's (:data:`FRONT_FRACTIONS`, in log)."""
    ex = _example(example)
    lo = fdsc.band_peak(ex.closed_loop("PassC-LF"), ex.bands["LF"]).gamma
    hi = fdsc.band_peak(ex.closed_loop("PassC-EF"), ex.bands["LF"]).gamma
    lo, hi = min(lo, hi) * 1.02, max(lo, hi)
    betas = [lo * (hi / lo) ** f for f in FRONT_FRACTIONS]
    return fdsc.pareto_front(ex.plant, ex.bands["HF"], ex.bands["LF"], betas, maxiter=FRONT_MAXITER)


def lqr(example: str = "aircraft") -> np.ndarray:
    """K0 of the realization through copies: the LQR gain of (A, B2, C, D2)."""
    return fdsc.lqr_gain(_example(example).plant)


def candidates(example: str = "aircraft") -> tuple:
    """The law's candidates: ``(names, gains)`` of the comparator set and the Pareto front's
    points (``"front 1"`` … in increasing order of the LF bound)."""
    ex = _example(example)
    names = list(comparators(example))
    gains = [ex.gains[n] for n in names]
    for j, K in enumerate(front(example).gains()):
        names.append(f"front {j + 1}")
        gains.append(K)
    return tuple(names), tuple(gains)


@functools.cache
@cached
def certificate(example: str = "aircraft"):
    """The Geromel–Colaneri dwell time of the FDSC pair's closed loops (PassC-LF, PassC-HF):
    what the direct realization of a law switching between them would have to enforce, or None
    if none up to 10⁴ s is found."""
    ex = _example(example)
    loops = [ex.closed_loop(n) for n in IDEAL_PAIR]
    try:
        return fdsc.geromel_colaneri_dwell(loops, tau_max=1e4)
    except fdsc.SolverError:
        return None


def _configs(example):
    """The tuning grid: (law, realization, λ, h). Every law is realized through copies (with
    K0 the LQR gain), which is stable for any switching on the decision grid; the direct
    realization turns a switch to a high gain into a spike of u (the chapter shows one)."""
    return [(law, "copies", lam, h) for law in ("cost", "band_power") for lam in LAMBDAS
            for h in HYSTERESES]


def draw_result(example: str, index: int, seed: int = SEED) -> dict:
    """Every controller on draw ``index`` of the seeded sequence (a plain dict, picklable)."""
    ex = _example(example)
    dr = draw(ex, np.random.default_rng([seed, index]))
    names, gains = candidates(example)
    K0 = lqr(example)
    sup = fdsc.Supervisor(ex.plant, gains, decide_every=DECIDE_EVERY, restart=RESTART)
    prep = sup.prepare(dr.d, dr.horizon)
    fixed = {n: prep.fixed(i) for i, n in enumerate(names)}
    oracle, _choice = prep.clairvoyant()
    lf, hf = names.index(IDEAL_PAIR[0]), names.index(IDEAL_PAIR[1])
    dom = {}
    for (t0, _t1, *_r), k in zip(prep.grid.pieces, range(len(prep.grid.pieces)), strict=True):
        j = int(np.searchsorted(dr.d.breaks, t0 + 1e-9, side="right") - 1)
        dom[k] = dr.dominant[j] if 0 <= j < len(dr.dominant) else "LF"
    ideal = prep.segment_law([lf if dom[k] == "LF" else hf for k in range(len(prep.grid.pieces))])
    pair = fdsc.Supervisor(ex.plant, [gains[lf], gains[hf]], law="band_power",
                           bands=[ex.bands["LF"], ex.bands["HF"]], decide_every=DECIDE_EVERY,
                           restart=RESTART).prepare(dr.d, dr.horizon)
    preps = {("cost", "copies"): prep.with_K0(K0), ("band_power", "copies"): pair.with_K0(K0)}
    runs = {}
    for law, real, lam, h in _configs(example):
        r = preps[(law, real)].run(forgetting=lam, hysteresis=h)
        runs[f"{law}/{real}/{lam:g}/{h:g}"] = (r.energy, r.switches, r.diverged_at is not None)
    return {"index": index, "horizon": dr.horizon, "changes": dr.changes, "segments": len(dr.dominant),
            "fixed": fixed, "oracle": oracle, "ideal": ideal, "runs": runs,
            "input_energy": prep.input_energy}


@dataclass(frozen=True)
class Study:
    """The non-stationary study of one example (see :func:`study`).

    Parameters
    ----------
    example : str
    seed : int
    draws : tuple of dict
        :func:`draw_result` of every draw, train half first.
    law : str
        The setting chosen on the training half (``law/realization/λ/h``).
    fixed_in_advance : str
        The fixed gain of least mean log energy over the training half (comparator set and
        Pareto front).
    certified : bool
        The chosen law is certified: realized through copies, it is stable for any switching
        on the decision grid.
    """

    example: str
    seed: int
    draws: tuple
    law: str
    fixed_in_advance: str
    certified: bool

    @property
    def test(self) -> tuple:
        """The scored half."""
        return self.draws[len(self.draws) // 2:]

    def _arr(self, f, draws=None):
        return np.array([f(r) for r in (self.test if draws is None else draws)])

    def ratio_vs_fixed_in_advance(self, law=None, draws=None) -> np.ndarray:
        law = self.law if law is None else law
        return self._arr(lambda r: r["runs"][law][0] / r["fixed"][self.fixed_in_advance], draws)

    def best_of(self, law: str) -> str:
        """The setting of ``law`` ("cost" or "band_power") of least mean log ratio to the fixed
        gain chosen in advance on the training half."""
        train = self.draws[:len(self.draws) // 2]
        keys = [k for k in train[0]["runs"] if k.startswith(law + "/")]
        return min(keys, key=lambda k: np.mean(np.log(self.ratio_vs_fixed_in_advance(k, train))))

    def ratio_vs_best_fixed(self) -> np.ndarray:
        return self._arr(lambda r: r["runs"][self.law][0] / min(r["fixed"].values()))

    def oracle_share(self) -> np.ndarray:
        """Share of the clairvoyant oracle's log-gain over the fixed gain chosen in advance that
        the law realizes (1: as good as the oracle; 0: no better than the fixed gain; < 0:
        worse); NaN on draws where the oracle gains less than :data:`HEADROOM_MIN` (a share of
        nothing is not a number)."""
        def share(r):
            ref = r["fixed"][self.fixed_in_advance]
            gain = math.log(ref / r["oracle"])
            if gain < math.log1p(HEADROOM_MIN):
                return float("nan")
            return math.log(ref / r["runs"][self.law][0]) / gain
        return self._arr(share)

    def oracle_ratio(self) -> np.ndarray:
        """The clairvoyant oracle's energy over the fixed gain chosen in advance (the headroom)."""
        return self._arr(lambda r: r["oracle"] / r["fixed"][self.fixed_in_advance])

    def ideal_ratio(self) -> np.ndarray:
        return self._arr(lambda r: r["ideal"] / r["fixed"][self.fixed_in_advance])

    def switches_per_change(self) -> float:
        sw = sum(r["runs"][self.law][1] for r in self.test)
        ch = sum(r["changes"] for r in self.test)
        return float(sw / ch) if ch else float("nan")

    def diverged(self) -> int:
        return int(sum(r["runs"][self.law][2] for r in self.test))

    def summary(self) -> dict:
        q = self.ratio_vs_fixed_in_advance()
        law, real, lam, h = self.law.split("/")
        return {
            "draws_test": len(self.test), "draws_train": len(self.draws) - len(self.test),
            "seed": self.seed,
            "fixed_in_advance": self.fixed_in_advance,
            "median_ratio_vs_fixed_in_advance": float(np.median(q)),
            "p95_ratio_vs_fixed_in_advance": float(np.quantile(q, 0.95)),
            "win_rate_vs_fixed_in_advance": float(np.mean(beats(q))),
            "median_ratio_vs_best_fixed_per_draw": float(np.median(self.ratio_vs_best_fixed())),
            "oracle_share_median": (float(np.nanmedian(self.oracle_share()))
                                    if np.any(np.isfinite(self.oracle_share())) else None),
            "draws_with_headroom": int(np.sum(np.isfinite(self.oracle_share()))),
            "oracle_median_ratio_vs_fixed_in_advance": float(np.median(self.oracle_ratio())),
            "ideal_median_ratio_vs_fixed_in_advance": float(np.median(self.ideal_ratio())),
            "switches_per_change": self.switches_per_change(),
            "diverged": self.diverged(),
            "certified": self.certified,
            "law": {"law": law, "realization": real, "forgetting": float(lam), "hysteresis": float(h),
                    "decide_every": DECIDE_EVERY, "restart": RESTART, "K0": "LQR"},
        }


def _choose(example, draws, seed):
    train = draws[:len(draws) // 2]
    names = list(train[0]["fixed"])
    logs = {n: np.mean([math.log(r["fixed"][n]) for r in train]) for n in names}
    adv = min(names, key=lambda n: (logs[n], names.index(n)))
    laws = list(train[0]["runs"])
    score = {law: np.mean([math.log(r["runs"][law][0] / r["fixed"][adv]) for r in train])
             for law in laws}
    best = min(laws, key=lambda law: (score[law], laws.index(law)))
    real = best.split("/")[1]
    return Study(example, seed, tuple(draws), best, adv, real == "copies")


def _map(fn, args, executor):
    if executor is None:
        return [fn(*a) for a in args]
    if hasattr(executor, "gather"):                 # a dask.distributed Client
        return executor.gather([executor.submit(fn, *a, pure=False) for a in args])
    return list(executor.map(fn, *zip(*args, strict=True)))


@cached
def study(example: str = "aircraft", n: int = N_RECORD, seed: int = SEED) -> Study:
    """The seeded study of one example on ``n`` draws (half train, half test)."""
    n = as_count("n", n, 2)
    draws = [draw_result(example, i, seed) for i in range(n)]
    return _choose(example, draws, seed)


def rho_t_family(example: str, law: str) -> dict:
    """The paper's ρ_t family (the aircraft's T = 500 s; the generic example's own T) under the
    chosen law: its energy over the best fixed gain of the comparator set at each ρ_t."""
    from .data import paper_data
    from .generic_example import RHO_T, piecewise_disturbance
    from .nonstationary_sweeps import family_signal

    ex = _example(example)
    names, gains = candidates(example)
    lf, hf = names.index(IDEAL_PAIR[0]), names.index(IDEAL_PAIR[1])
    kind, real, lam, h = law.split("/")
    lo, hi = paper_data("simulation")["rho_t_range"]["value"]
    grid = np.linspace(lo, hi, 11) if example == "aircraft" else RHO_T
    out = {"rho_t": [], "ratio_vs_best_fixed": []}
    for p in grid:
        d, horizon = family_signal("piecewise", p) if example == "aircraft" else piecewise_disturbance(p)
        horizon = math.ceil(horizon / DECIDE_EVERY - 1e-9) * DECIDE_EVERY
        if kind == "cost":
            sup = fdsc.Supervisor(ex.plant, gains, decide_every=DECIDE_EVERY, restart=RESTART,
                                  K0=lqr(example) if real == "copies" else None)
        else:
            sup = fdsc.Supervisor(ex.plant, [gains[lf], gains[hf]], law="band_power",
                                  bands=[ex.bands["LF"], ex.bands["HF"]], decide_every=DECIDE_EVERY,
                                  restart=RESTART, K0=lqr(example) if real == "copies" else None)
        prep = sup.prepare(d, horizon)
        r = prep.run(forgetting=float(lam), hysteresis=float(h))
        base = fdsc.Supervisor(ex.plant, gains).prepare(d, horizon)
        best = min(base.fixed(names.index(k)) for k in comparators(example))
        out["rho_t"].append(float(p))
        out["ratio_vs_best_fixed"].append(r.energy / best)
    return out


def full_study(n: int = N_FULL, *, seed: int = SEED, executor=None, out=FULL_FILE) -> dict:
    """The full study of both examples (``n`` draws each), on ``executor`` if given; writes
    ``out`` (JSON: the summaries and every test draw's ratio) and returns it."""
    from .cache import fingerprint
    from .environment import build_commit

    n = as_count("n", n, 2)
    result = {"commit": build_commit(), "fingerprint": fingerprint(), "n": n, "seed": seed}
    for example in ("aircraft", "generic"):
        front(example)
        draws = _map(draw_result, [(example, i, seed) for i in range(n)], executor)
        st = _choose(example, draws, seed)
        result[example] = st.summary() | {
            "ratio_vs_fixed_in_advance": st.ratio_vs_fixed_in_advance().tolist(),
            "oracle_ratio": st.oracle_ratio().tolist(), "ideal_ratio": st.ideal_ratio().tolist(),
            "ratio_vs_best_fixed_per_draw": st.ratio_vs_best_fixed().tolist(),
            "fixed_ratio_vs_fixed_in_advance": {
                n: st._arr(lambda r, n=n, a=st.fixed_in_advance: r["fixed"][n] / r["fixed"][a]).tolist()
                for n in st.test[0]["fixed"]},
            "band_power_ratio_vs_fixed_in_advance": st.ratio_vs_fixed_in_advance(
                st.best_of("band_power")).tolist(),
            "band_power_law": st.best_of("band_power")}
    if out is not None:
        Path(out).parent.mkdir(parents=True, exist_ok=True)
        Path(out).write_text(json.dumps(result, indent=1))
    return result


def load_full(path=FULL_FILE):
    """The full study written by :func:`full_study`, or None if absent."""
    path = Path(path)
    if not path.is_file():
        return None
    return json.loads(path.read_text())


def record_part() -> RecordPart:
    """Record entries ``pareto_front`` and ``supervisor`` (new)."""
    fronts, sup = {}, {}
    for example in ("aircraft", "generic"):
        fr = front(example)
        fronts[example] = [{"beta": float(b), "gamma_hf": None if p is None else float(p.peak[0]),
                            "gamma_lf": None if p is None else float(p.peak[1]),
                            "certified": None if p is None else p.certified}
                           for b, p in zip(fr.betas, fr.points, strict=True)]
        st = study(example)
        sup[example] = st.summary() | {"rho_t_ratio_vs_best_fixed":
                                       rho_t_family(example, st.law)["ratio_vs_best_fixed"]}
    note_f = ("single state-feedback gains of least HF peak with the LF peak at most β (a direct "
              "search, each point certified by Lemma 1): the strongest fixed baselines.")
    note_s = ("the law that decides on the disturbance estimate, tuned on the first half of "
              f"{N_RECORD} seeded non-stationary draws per example and scored on the second: "
              + "; ".join(f"{e}: median {v['median_ratio_vs_fixed_in_advance']:.3g}× the fixed gain "
                          f"chosen in advance ({v['fixed_in_advance']}), wins "
                          f"{v['win_rate_vs_fixed_in_advance']:.0%}" for e, v in sup.items()) + ".")
    return RecordPart((
        entry("pareto_front", "our computation (multi-band synthesis)", None, fronts, "new", note_f),
        entry("supervisor", "our computation (a law on the disturbance estimate)", None, sup, "new",
              note_s),
    ))
