"""Chapter 'disturbance_law': does a switching law that decides on the disturbance estimate pay
against the strongest fixed controller, and what is switching worth at all?

Seeded non-stationary draws on both examples (:mod:`fdsc.paper.pays.disturbance_law_draws`): the
first half of a study's draws trains, the second scores. Against every law: the **fixed
controller chosen in advance** (least mean log energy over the training half among every fixed
controller of :func:`fdsc.paper.pays.fixed_designs.fixed_set`: the comparator set, the static
and dynamic fronts, the LQR gain, the H2 designs for the class's spectrum and the controllers
tuned on the class). The laws (:data:`fdsc.paper.pays.disturbance_law_runs.CANDIDATE_SETS`),
realized through copies, are tuned on the training half: the setting of least mean log energy
ratio among those that switch at most :data:`MAX_SWITCHES_PER_CHANGE` times per change of the
dominating band. The **value of switching** is the clairvoyant reference: the controllers
designed for each segment type, switched at the breaks. All energies are exact integrals from
rest; the paper's FDSC variants run on the library's simulator at 1 ms.

The record computes a seeded subset (:data:`N_RECORD` draws per example, the tuned designs with a
shorter search); the full study (:data:`N_FULL` draws per example) runs behind
``python -m fdsc disturbance-law`` on a process pool or a Dask client, and writes a file that the
chapter reads.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fdsc._validation import as_count
from fdsc.paper.pays.disturbance_law_draws import (
    DECIDE_EVERY,
    HYSTERESES,
    IDEAL_PAIR,
    LAMBDAS,
    RESTART,
    SEED,
    certificate,
)
from fdsc.paper.pays.disturbance_law_robust import (
    MEASURED_DT,
    MEASURED_VARIANTS,
    measured_result,
    min_switching_summary,
    robust_result,
)
from fdsc.paper.pays.disturbance_law_runs import REFERENCE_FAMILIES, draw_result, law_supervisor, settings
from fdsc.paper.pays.fixed_designs import FixedSet, fixed_set
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.examples import beats
from fdsc.paper.shared.results import RecordPart, entry

__all__ = ["SEED", "N_RECORD", "N_FULL", "LAMBDAS", "HYSTERESES", "DECIDE_EVERY", "RESTART", "FULL_FILE",
           "IDEAL_PAIR", "HEADROOM_MIN", "MAX_SWITCHES_PER_CHANGE", "TARGETS", "Study", "study",
           "rho_t_family", "record_part", "full_study", "load_full", "law_key", "N_ROBUST", "ROBUST_SNR_DB",
           "robustness", "measured_robustness", "certificate", "stored_fixed_set"]

#: Draws per example in the record (half train, half test) and in the full study.
N_RECORD, N_FULL = 12, 500
#: Where the full study is stored (relative to the repository root).
FULL_FILE = Path("book") / "data" / "disturbance_law_full.json"
#: The reference's least relative gain over the fixed controller chosen in advance for a draw to
#: count in the share of it that a law realizes.
HEADROOM_MIN = 0.01
#: The most switches per change of the dominating band a law may make to be chosen: one to
#: follow the change, and two of indecision.
MAX_SWITCHES_PER_CHANGE = 3.0
#: Test draws per example and SNRs (dB) of the study of a noisy estimate.
N_ROBUST, ROBUST_SNR_DB = 40, (20.0, 10.0, 0.0)
#: The targets a law must meet against the fixed controller chosen in advance (median, least win
#: rate, largest 95th percentile of the energy ratio on the test draws).
TARGETS = {"generic": {"median": 0.9, "win_rate": 0.75, "p95": 1.05},
           "aircraft": {"median": 1.0, "win_rate": 0.0, "p95": math.inf}}


def law_key(law: dict) -> str:
    """The setting ``candidates/law/realization/λ/h`` of a law's parameters as the study stores them.

    Parameters
    ----------
    law : dict
        ``{"candidates", "law", "realization", "forgetting", "hysteresis"}``.

    Returns
    -------
    str

    Examples
    --------
    >>> law_key({"candidates": "gains", "law": "cost", "realization": "copies", "forgetting": 1.0,
    ...          "hysteresis": 0.1})
    'gains/cost/copies/1/0.1'
    """
    return "{candidates}/{law}/{realization}/{forgetting:g}/{hysteresis:g}".format(**law)


@dataclass(frozen=True)
class Study:
    """The non-stationary study of one example (see :func:`study`).

    Parameters
    ----------
    example : str
    seed : int
    draws : tuple of dict
        :func:`fdsc.paper.pays.disturbance_law_runs.draw_result` of every draw, train half first.
    fixed : FixedSet
        Every fixed controller and the one chosen in advance.
    law : str
        The setting chosen on the training half.
    reference : str
        The family whose clairvoyant reference is best on the training half.
    """

    example: str
    seed: int
    draws: tuple
    fixed: FixedSet
    law: str
    reference: str

    @property
    def fixed_in_advance(self) -> str:
        """The fixed controller chosen in advance."""
        return self.fixed.chosen

    @property
    def train(self) -> tuple:
        """The training half."""
        return self.draws[:len(self.draws) // 2]

    @property
    def test(self) -> tuple:
        """The scored half."""
        return self.draws[len(self.draws) // 2:]

    def _ref(self, r):
        return r["fixed"][self.fixed_in_advance]

    def ratio(self, law=None, draws=None) -> np.ndarray:
        """A law's energy over the fixed controller chosen in advance's, per draw.

        Parameters
        ----------
        law : str, optional
            A setting (default the chosen one).
        draws : sequence of dict, optional
            Default the test half.

        Returns
        -------
        ndarray
        """
        law = self.law if law is None else law
        return np.array([r["runs"][law][0] / self._ref(r) for r in (self.test if draws is None else draws)])

    def switches_per_change(self, law=None, draws=None) -> float:
        """A law's switches over the changes of the dominating band, summed over the draws.

        Parameters
        ----------
        law : str, optional
        draws : sequence of dict, optional
            Default the test half.

        Returns
        -------
        float
        """
        law = self.law if law is None else law
        draws = self.test if draws is None else draws
        ch = sum(r["changes"] for r in draws)
        return float(sum(r["runs"][law][1] for r in draws) / ch) if ch else math.nan

    def settings_table(self) -> list:
        """Every setting on the training half: mean log ratio and switches per change (the
        choice's trade-off).

        Returns
        -------
        list of dict
        """
        return [{"law": k, "log_ratio": float(np.mean(np.log(self.ratio(k, self.train)))),
                 "switches_per_change": self.switches_per_change(k, self.train)} for k in settings()]

    def best_of(self, prefix: str, constrained: bool = True) -> str:
        """The setting of least training mean log ratio among those starting with ``prefix``.

        Parameters
        ----------
        prefix : str
            E.g. ``"tuned pair/band_power"``.
        constrained : bool, optional
            Only settings with at most :data:`MAX_SWITCHES_PER_CHANGE` (when any has).

        Returns
        -------
        str
        """
        rows = [r for r in self.settings_table() if r["law"].startswith(prefix)]
        ok = [r for r in rows if r["switches_per_change"] <= MAX_SWITCHES_PER_CHANGE] if constrained else rows
        return min(ok or rows, key=lambda r: r["log_ratio"])["law"]

    def fixed_ratio(self, name: str, draws=None) -> np.ndarray:
        """A fixed controller's energy over the one chosen in advance's, per draw.

        Parameters
        ----------
        name : str
        draws : sequence of dict, optional

        Returns
        -------
        ndarray
        """
        return np.array([r["fixed"][name] / self._ref(r) for r in (self.test if draws is None else draws)])

    def fdsc_ratio(self, variant: str) -> np.ndarray:
        """An FDSC variant's energy over the fixed controller chosen in advance's, per test draw.

        Parameters
        ----------
        variant : str

        Returns
        -------
        ndarray
        """
        return np.array([r["fdsc"][variant][0] / self._ref(r) for r in self.test])

    def reference_ratio(self, family=None, draws=None) -> np.ndarray:
        """The clairvoyant switching reference's energy over the fixed controller chosen in
        advance's, per draw (the value of switching).

        Parameters
        ----------
        family : str, optional
            Default the one chosen on the training half.
        draws : sequence of dict, optional

        Returns
        -------
        ndarray
        """
        family = self.reference if family is None else family
        draws = self.test if draws is None else draws
        return np.array([r["reference"][family] / self._ref(r) for r in draws])

    def share(self) -> np.ndarray:
        """Share of the reference's log-gain over the fixed controller chosen in advance that the
        law realizes, per test draw (NaN where the reference gains less than :data:`HEADROOM_MIN`)."""
        law, ref = self.ratio(), self.reference_ratio()
        out = np.full(law.size, np.nan)
        ok = ref < 1.0 / (1.0 + HEADROOM_MIN)
        out[ok] = np.log(law[ok]) / np.log(ref[ok])
        return out

    def control_steps(self) -> np.ndarray:
        """The law's largest step of u at a switch over u's RMS, per test draw (0 without one)."""
        return np.array([r["runs"][self.law][3] for r in self.test])

    def meets(self) -> dict:
        """Whether the chosen law meets the example's :data:`TARGETS`."""
        q, t = self.ratio(), TARGETS[self.example]
        got = {"median": float(np.median(q)), "win_rate": float(np.mean(beats(q))),
               "p95": float(np.quantile(q, 0.95))}
        return {"targets": t, "got": got,
                "met": bool(got["median"] <= t["median"] and got["win_rate"] >= t["win_rate"]
                            and got["p95"] <= t["p95"])}

    def summary(self) -> dict:
        """The record's fields (entry ``supervisor``, one example) on the test draws."""
        q = self.ratio()
        cand, law, real, lam, h = self.law.split("/")
        ref = self.reference_ratio()
        share = self.share()
        sup, _names, _l, _h = law_supervisor(self.example, self.law, self.fixed)
        cert = sup.certificate()
        return {
            "draws_test": len(self.test), "draws_train": len(self.train), "seed": self.seed,
            "fixed_in_advance": self.fixed_in_advance,
            "fixed_in_advance_family": self.fixed.family[self.fixed_in_advance],
            "median_ratio_vs_fixed_in_advance": float(np.median(q)),
            "p95_ratio_vs_fixed_in_advance": float(np.quantile(q, 0.95)),
            "win_rate_vs_fixed_in_advance": float(np.mean(beats(q))),
            "reference_family": self.reference,
            "reference_median_ratio": float(np.median(ref)),
            "reference_win_rate": float(np.mean(beats(ref))),
            "reference_share_median": float(np.nanmedian(share)) if np.any(np.isfinite(share)) else None,
            "draws_with_headroom": int(np.sum(np.isfinite(share))),
            "oracle_median_ratio_vs_fixed_in_advance": float(np.median(
                [r["oracle"] / self._ref(r) for r in self.test])),
            "ideal_median_ratio_vs_fixed_in_advance": float(np.median(
                [r["ideal"] / self._ref(r) for r in self.test])),
            "fdsc_median_ratio": {v: float(np.median(self.fdsc_ratio(v))) for v in self.test[0]["fdsc"]},
            "switches_per_change": self.switches_per_change(),
            "largest_control_step_median": float(np.median(self.control_steps())),
            "diverged": int(sum(r["runs"][self.law][2] for r in self.test)),
            "certified": cert.stable,
            "certificate": {"checks": cert.checks, "assumptions": list(cert.assumptions),
                            "l2_bound": cert.l2_bound},
            "meets_targets": self.meets()["met"],
            "law": {"candidates": cand, "law": law, "realization": real, "forgetting": float(lam),
                    "hysteresis": float(h), "decide_every": DECIDE_EVERY, "restart": RESTART, "K0": "LQR"},
        }


def _choose(example, draws, seed, fs):
    st = Study(example, seed, tuple(draws), fs, settings()[0], REFERENCE_FAMILIES[0])
    law = st.best_of("")
    ref = min(REFERENCE_FAMILIES,
              key=lambda f: np.mean(np.log(st.reference_ratio(f, st.train))))
    return Study(example, seed, tuple(draws), fs, law, ref)


def _map(fn, args, executor):
    if executor is None:
        return [fn(*a) for a in args]
    if hasattr(executor, "gather"):                 # a dask.distributed Client
        return executor.gather([executor.submit(fn, *a, pure=False) for a in args])
    return list(executor.map(fn, *zip(*args, strict=True)))


@cached
def study(example: str = "aircraft", n: int = N_RECORD, seed: int = SEED) -> Study:
    """The seeded study of one example (half of the draws train, half test).

    Parameters
    ----------
    example : {"aircraft", "generic"}
    n : int, optional
        Draws (≥ 4).
    seed : int, optional

    Returns
    -------
    Study
    """
    n = as_count("n", n, 4)
    fs = fixed_set(example, n, seed)
    return _choose(example, [draw_result(example, i, seed, fs) for i in range(n)], seed, fs)


@cached
def rho_t_family(example: str, law: str, n: int = N_RECORD, seed: int = SEED) -> dict:
    """The paper's ρ_t family (the aircraft's T = 500 s; the generic example's own T) under a law,
    against the fixed controller chosen in advance (of the study of ``n`` draws).

    Parameters
    ----------
    example : {"aircraft", "generic"}
    law : str
        A setting.
    n, seed : int, optional
        The study whose fixed controllers are used.

    Returns
    -------
    dict
        ``{"rho_t": [...], "ratio_vs_fixed_in_advance": [...]}``.
    """
    from fdsc.paper.pays.generic_example import RHO_T, piecewise_disturbance
    from fdsc.paper.reproduced.nonstationary_sweeps import family_signal
    from fdsc.paper.shared.data import paper_data

    fs = fixed_set(example, n, seed)
    sup, _names, lam, h = law_supervisor(example, law, fs)
    lo, hi = paper_data("simulation")["rho_t_range"]["value"]
    grid = np.linspace(lo, hi, 11) if example == "aircraft" else RHO_T
    out = {"rho_t": [], "ratio_vs_fixed_in_advance": []}
    for p in grid:
        d, horizon = family_signal("piecewise", p) if example == "aircraft" else piecewise_disturbance(p)
        horizon = math.ceil(horizon / DECIDE_EVERY - 1e-9) * DECIDE_EVERY
        prep = sup.prepare(d, horizon)
        r = prep.run(forgetting=lam, hysteresis=h)
        out["rho_t"].append(float(p))
        out["ratio_vs_fixed_in_advance"].append(r.energy / prep.energy_of(fs.controllers[fs.chosen]))
    return out


def _controller_record(c) -> dict:
    """A controller's matrices for the stored study (so that its numbers can be checked)."""
    out = {k: getattr(c, k).tolist() for k in "ABCD"}
    if c.F is not None:
        out["E"], out["F"] = c.E.tolist(), c.F.tolist()
    return out


def full_study(n: int = N_FULL, *, seed: int = SEED, executor=None, out=None) -> dict:
    """The full study of both examples.

    Parameters
    ----------
    n : int, optional
        Draws per example (half train, half test).
    seed : int, optional
    executor : concurrent.futures.Executor or dask.distributed.Client, optional
        Where the draws run (default here, one after the other); the numbers do not depend on it.
    out : path, optional
        The JSON file to write (None: none).

    Returns
    -------
    dict
        ``commit``, ``fingerprint``, ``n``, ``seed``, and per example the summary
        (:meth:`Study.summary`) with every test draw's ratios for every fixed controller, FDSC
        variant, law family and reference, and the fixed controllers' matrices.
    """
    from fdsc.paper.shared.cache import fingerprint
    from fdsc.paper.shared.environment import build_commit

    n = as_count("n", n, 4)
    result = {"commit": build_commit(), "fingerprint": fingerprint(), "n": n, "seed": seed}
    for example in ("aircraft", "generic"):
        fs = fixed_set(example, n, seed)
        draws = _map(draw_result, [(example, i, seed, fs) for i in range(n)], executor)
        st = _choose(example, draws, seed, fs)
        result[example] = st.summary() | {
            "test_indices": [r["index"] for r in st.test],
            "ratio_vs_fixed_in_advance": st.ratio().tolist(),
            "fixed_ratio": {k: st.fixed_ratio(k).tolist() for k in fs.names},
            "fdsc_ratio": {v: st.fdsc_ratio(v).tolist() for v in st.test[0]["fdsc"]},
            "reference_ratio": {f: st.reference_ratio(f).tolist() for f in REFERENCE_FAMILIES},
            "family_best": {p: st.best_of(p) for p in ("gains/cost", "ideal pair/band_power",
                                                       "tuned pair/band_power", "tuned pair/cost",
                                                       "tuned filtered pair/band_power",
                                                       "tuned filtered pair/cost")},
            "family_ratio": {p: st.ratio(st.best_of(p)).tolist()
                             for p in ("gains/cost", "ideal pair/band_power", "tuned pair/band_power",
                                       "tuned pair/cost", "tuned filtered pair/band_power",
                                       "tuned filtered pair/cost")},
            "settings": st.settings_table(),
            "oracle_ratio": [r["oracle"] / r["fixed"][fs.chosen] for r in st.test],
            "ideal_ratio": [r["ideal"] / r["fixed"][fs.chosen] for r in st.test],
            "control_steps": st.control_steps().tolist(),
            "fixed_controllers": {k: {"family": fs.family[k], **fs.info[k], "train_score": fs.train_score[k],
                                      "matrices": _controller_record(fs.controllers[k])} for k in fs.names},
            "pairs": {f: [_controller_record(c) for c in pair] for f, pair in fs.pairs.items()},
        }
    result["robustness"] = robustness(result, n=min(N_ROBUST, n - n // 2), executor=executor)
    result["measured"] = measured_robustness(result, n=min(N_ROBUST, n - n // 2), executor=executor)
    if out is not None:
        Path(out).parent.mkdir(parents=True, exist_ok=True)
        Path(out).write_text(json.dumps(result, indent=1))
    return result


def stored_fixed_set(full: dict, example: str) -> FixedSet:
    """The fixed controllers of a stored full study, rebuilt from their stored matrices (to
    recompute stored draws without redoing the designs).

    Parameters
    ----------
    full : dict
        The full study (:func:`load_full`).
    example : {"aircraft", "generic"}

    Returns
    -------
    FixedSet
        With the stored names, families, band peaks, scores, choice and pairs; no tuning details.
    """
    import fdsc

    r = full[example]

    def ctrl(m, name):
        E, F = (m["E"], m["F"]) if "E" in m else (None, None)
        A = np.asarray(m["A"], dtype=float).reshape(len(m["A"]), -1) if m["A"] else np.zeros((0, 0))
        n = len(m["D"][0])
        B = np.asarray(m["B"], dtype=float).reshape(A.shape[0], -1) if A.size else np.zeros((0, n))
        C = np.asarray(m["C"], dtype=float).reshape(len(m["D"]), -1)
        return fdsc.Controller(A, B, C, np.asarray(m["D"], dtype=float), E=E, F=F, name=name)

    fc = r["fixed_controllers"]
    names = tuple(fc)
    info = {k: {x: v[x] for x in ("lf", "hf", "hinf", "states", "size", "reads_estimate", "slowest")}
            for k, v in fc.items()}
    pairs = {f: tuple(ctrl(m, f"{f} for {t} segments") for m, t in zip(p, ("LF", "HF"), strict=True))
             for f, p in r["pairs"].items()}
    ctrls = {k: ctrl(v["matrices"], k) for k, v in fc.items()}
    return FixedSet(example, full["n"], full["seed"], 0, names, ctrls,
                    {k: v["family"] for k, v in fc.items()}, info,
                    {k: v["train_score"] for k, v in fc.items()}, r["fixed_in_advance"], [], {}, pairs,
                    {}, {}, None)


def robustness(full: dict, *, n: int = N_ROBUST, snrs=ROBUST_SNR_DB, executor=None) -> dict:
    """The law chosen in the full study on its first ``n`` test draws per example, on a noisy
    estimate as a controller would build it (:func:`robust_result`).

    Parameters
    ----------
    full : dict
        The full study (:func:`full_study`).
    n : int, optional
        Test draws per example.
    snrs : sequence of float, optional
        SNRs of the estimate in dB.
    executor : concurrent.futures.Executor or dask.distributed.Client, optional

    Returns
    -------
    dict
        ``{example: {"draws", "exact_median", "exact_win_rate", "snr_db": {snr: {"median",
        "win_rate", "decisions_only_median", "fixed_median", "switches_ratio"}}}}``, each against
        the fixed controller chosen in advance on the exact estimate.
    """
    n = as_count("n", n, 1)
    out = {}
    for example in ("aircraft", "generic"):
        r = full[example]
        fs = stored_fixed_set(full, example)
        key = law_key(r["law"])
        first = full["n"] // 2
        args = [(example, first + i, key, fs, float(snr), full["seed"]) for snr in snrs for i in range(n)]
        res = _map(robust_result, args, executor)
        per = {}
        for k, snr in enumerate(snrs):
            part = res[k * n:(k + 1) * n]
            noisy = np.array([p["noisy"] for p in part])
            per[str(float(snr))] = {
                "median": float(np.median(noisy)), "win_rate": float(np.mean(beats(noisy))),
                "p95": float(np.quantile(noisy, 0.95)),
                "decisions_only_median": float(np.median([p["decisions_only"] for p in part])),
                "fixed_median": float(np.median([p["fixed_noisy"] for p in part])),
                "switches_ratio": float(sum(p["switches_noisy"] for p in part)
                                        / max(1, sum(p["switches_exact"] for p in part)))}
        exact = np.array([p["exact"] for p in res[:n]])
        out[example] = {"draws": n, "exact_median": float(np.median(exact)),
                        "exact_win_rate": float(np.mean(beats(exact))), "snr_db": per}
    return out


def measured_robustness(full: dict, *, n: int = N_ROBUST, executor=None) -> dict:
    """The law chosen in the full study on its first ``n`` test draws per example, run on
    sampled measurements (:func:`measured_result`).

    Parameters
    ----------
    full : dict
        The full study (:func:`full_study`).
    n : int, optional
        Test draws per example.
    executor : concurrent.futures.Executor or dask.distributed.Client, optional

    Returns
    -------
    dict
        ``{example: {"draws", "dt", "variants": {name: {"median", "win_rate", "p95",
        "switches_ratio", "diverged"}}, "min_switching": {...}, "commit"}}``.
    """
    from fdsc.paper.shared.environment import build_commit

    n = as_count("n", n, 1)
    out = {}
    for example in ("aircraft", "generic"):
        r = full[example]
        fs = stored_fixed_set(full, example)
        key = law_key(r["law"])
        first = full["n"] // 2
        res = _map(measured_result, [(example, first + i, key, fs, full["seed"]) for i in range(n)], executor)
        per = {}
        for name in ("exact", *MEASURED_VARIANTS, "min_switching"):
            ratio = np.array([p[name]["ratio"] for p in res])
            per[name] = {"median": float(np.median(ratio)), "p95": float(np.quantile(ratio, 0.95)),
                         "win_rate": float(np.mean(beats(ratio))),
                         "switches_ratio": float(sum(p[name]["switches"] for p in res)
                                                 / max(1, sum(p["exact"]["switches"] for p in res))),
                         "diverged": int(sum(p[name]["diverged"] for p in res))}
        out[example] = {"draws": n, "dt": MEASURED_DT, "variants": per,
                        "min_switching": min_switching_summary(example), "commit": build_commit()}
    return out


def load_full(path=None):
    """The full study written by :func:`full_study`.

    Parameters
    ----------
    path : path, optional
        Default :data:`FULL_FILE` in the repository this package lies in (whatever the working
        directory).

    Returns
    -------
    dict or None
        None if the file is absent (outside a checkout of the repository).
    """
    path = Path(__file__).resolve().parents[3] / FULL_FILE if path is None else Path(path)
    if not path.is_file():
        return None
    return json.loads(path.read_text())


def record_part() -> RecordPart:
    """Record entry ``supervisor`` (new): the record's subset of the study, per example."""
    sup = {}
    for example in ("aircraft", "generic"):
        st = study(example)
        sup[example] = st.summary() | {"rho_t_ratio_vs_fixed_in_advance":
                                       rho_t_family(example, st.law)["ratio_vs_fixed_in_advance"]}
    note = ("the law on the disturbance estimate, tuned on the first half of "
            f"{N_RECORD} seeded non-stationary draws per example and scored on the second, against "
            "the fixed controller chosen in advance among every fixed controller: "
            + "; ".join(f"{e}: median {v['median_ratio_vs_fixed_in_advance']:.3g}× {v['fixed_in_advance']}, "
                        f"wins {v['win_rate_vs_fixed_in_advance']:.0%}; clairvoyant switching "
                        f"{v['reference_median_ratio']:.3g}×" for e, v in sup.items())
            + ". The record's subset checks the stored full study at build time.")
    return RecordPart((entry("supervisor", "our computation (a law on the disturbance estimate)", None, sup,
                             "new", note),))
