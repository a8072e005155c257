"""The study of chapter 'disturbance_law': the choices on the training half, the numbers on the
test half, the targets, and the answer in words (see :mod:`fdsc.paper.pays.disturbance_law`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from fdsc.paper.pays.disturbance_law_draws import DECIDE_EVERY, RESTART
from fdsc.paper.pays.disturbance_law_runs import REFERENCE_FAMILIES, law_supervisor, settings
from fdsc.paper.pays.fixed_designs import FixedSet
from fdsc.paper.shared.examples import beats

__all__ = ["HEADROOM_MIN", "SHARE_MIN_DRAWS", "share_clause",
           "MAX_SWITCHES_PER_CHANGE", "TARGETS", "FAMILIES", "scored_settings", "law_key", "Study",
           "LAW_WORDS", "describe",
           "answer", "choose", "share_words"]

#: The reference's least relative gain over the fixed controller chosen in advance for a draw to
#: count in the share of it that a law realizes.
HEADROOM_MIN = 0.01
#: The fewest such draws on which the share is stated (on fewer, the chapter says how few).
SHARE_MIN_DRAWS = 10
#: The most switches per change of the dominating band a law may make to be chosen: one to
#: follow the change, and two of indecision.
MAX_SWITCHES_PER_CHANGE = 3.0
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
    n_train : int, optional
        How many of ``draws`` (the first ones) train; default half of them.
    """

    example: str
    seed: int
    draws: tuple
    fixed: FixedSet
    law: str
    reference: str
    n_train: int | None = None

    @property
    def fixed_in_advance(self) -> str:
        """The fixed controller chosen in advance."""
        return self.fixed.chosen

    @property
    def train(self) -> tuple:
        """The training half."""
        return self.draws[:self._split]

    @property
    def test(self) -> tuple:
        """The scored half."""
        return self.draws[self._split:]

    @property
    def _split(self) -> int:
        return len(self.draws) // 2 if self.n_train is None else self.n_train

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


#: The candidate sets and laws in words.
LAW_WORDS = {"gains": "the cost law over the comparator set's gains and three front points",
             "ideal pair": "the band-power law over PassC-LF and PassC-HF",
             "tuned pair": "gains tuned for LF- and for HF-dominated segments",
             "tuned filtered pair": "filtered controllers tuned for LF- and for HF-dominated segments"}


def describe(law: dict) -> str:
    """A stored law's setting in words.

    Parameters
    ----------
    law : dict
        ``{"candidates", "law", ...}`` as the study stores it.

    Returns
    -------
    str

    Examples
    --------
    >>> describe({"candidates": "tuned pair", "law": "cost"})
    'the predictive-cost supervisor switching between gains tuned for LF- and for HF-dominated segments'
    """
    cand = law["candidates"]
    if cand in ("gains", "ideal pair"):
        return LAW_WORDS[cand]
    kind = "predictive-cost supervisor" if law["law"] == "cost" else "band-power law"
    return f"the {kind} switching between {LAW_WORDS[cand]}"


def share_words(share) -> str:
    """The share of the reference's gain a law realizes, in words (it may exceed all of it: the
    law also switches inside a segment).

    Parameters
    ----------
    share : float or None

    Returns
    -------
    str

    Examples
    --------
    >>> share_words(0.834), share_words(1.024), share_words(None)
    ('83 %', 'all of it and more (102 %)', 'nothing measurable')
    """
    from fdsc.paper.shared.prose import pct

    if share is None:
        return "nothing measurable"
    if share > 1:
        return f"all of it and more ({round(100 * share):d} %)"
    return pct(max(share, 0.0)) if share >= 0 else "none of it (it loses)"


def _noise_words(rob):
    """What a noisy estimate does to the law, against the fixed controller chosen in advance
    reading the same noisy estimate (per draw, the law's ratio over that controller's own)."""
    if not rob:
        return ""
    from fdsc.paper.shared.prose import count
    from fdsc.paper.shared.stats import median_ci_words

    per = rob["snr_db"]
    top, low = max(per, key=float), min(per, key=float)

    def same(level):
        v = per[level]
        return median_ci_words(np.asarray(v["ratios"], float) / np.asarray(v["fixed_ratios"], float))

    return (f"; on a noisy estimate, against that fixed controller reading the same estimate, the "
            f"law has a median {same(top)} at {float(top):g} dB and {same(low)} at {float(low):g} dB "
            f"(its first {count(rob['draws'])} test draws)")


def _reference_words(r):
    """The clairvoyant reference's median over the fixed controller chosen in advance, with its
    bootstrap interval where the study stores its per-draw ratios."""
    from fdsc.paper.shared.prose import times
    from fdsc.paper.shared.stats import median_ci_words

    per_draw = r.get("reference_ratio", {}).get(r.get("reference_family"))
    if per_draw:
        return median_ci_words(per_draw)
    return times(r["reference_median_ratio"])


def share_clause(r: dict, share) -> str:
    """The share of the clairvoyant reference's gain the law realizes, where there is one to
    speak of: the reference gains in median and on at least :data:`SHARE_MIN_DRAWS` draws.

    Parameters
    ----------
    r : dict
        An example of the stored study (``reference_median_ratio``, ``draws_with_headroom``).
    share : float or None
        The law's median share of the reference's gain.

    Returns
    -------
    str
        A clause to append to a sentence on the reference.

    Examples
    --------
    >>> share_clause({"reference_median_ratio": 1.11, "draws_with_headroom": 3}, 0.68)[:40]
    ', more energy than that fixed controller'
    >>> share_clause({"reference_median_ratio": 0.9, "draws_with_headroom": 3}, 0.68)
    ' (it gains at least 1 % on 3 test draws only, too few to state a share)'
    >>> share_clause({"reference_median_ratio": 0.9, "draws_with_headroom": 40}, 0.68)
    ', of which the law realizes 68 % (in median over the 40 draws where it gains)'
    """
    from fdsc.paper.shared.prose import count

    n = r.get("draws_with_headroom", 0)
    if r["reference_median_ratio"] >= 1:
        return (", more energy than that fixed controller: switching between these designs at the "
                "true breaks does not pay (a reference, not a bound: a law that does more than "
                "switch can go below it)")
    if share is None or n < SHARE_MIN_DRAWS:
        return f" (it gains at least 1 % on {count(n)} test draws only, too few to state a share)"
    return (f", of which the law realizes {share_words(share)} (in median over the {count(n)} draws where "
            "it gains)")


def answer(full: dict) -> dict:
    """Per example, the chapter's answer (Markdown) from the stored full study: the best law
    against the fixed controller chosen in advance, the value of switching, the paper's FDSC.

    Parameters
    ----------
    full : dict

    Returns
    -------
    dict
        ``{example: str}``.
    """
    from fdsc.paper.shared.prose import count, pct, times

    out = {}
    for example in ("aircraft", "generic"):
        r = full[example]
        share = r["reference_share_median"]
        printed = r["fdsc_median_ratio"]["FDSC"]
        ci, fdsc_words = "", times(printed)
        if "ladder" in r:
            from fdsc.paper.shared.prose import times_ci

            ci = f" [95 % interval {times_ci(r['ladder']['summary']['gain switching']).split('[')[1]}"
            fdsc_words = times_ci(r["ladder"]["summary"]["FDSC"]).replace("[", "[95 % interval ")
        out[example] = (
            f"the best law, {describe(r['law'])}, has a median "
            f"{times(r['median_ratio_vs_fixed_in_advance'])}{ci} "
            f"the energy of *{r['fixed_in_advance']}*, the best fixed controller with equal information "
            f"(95th percentile {times(r['p95_ratio_vs_fixed_in_advance'])}, less energy on "
            f"{pct(r['win_rate_vs_fixed_in_advance'])} of {count(r['draws_test'])} test draws)"
            f"{_noise_words(full.get('robustness', {}).get(example))}. Switching clairvoyantly at the breaks "
            f"between controllers designed for each type of segment reaches a median "
            f"{_reference_words(r)}"
            + share_clause(r, share)
            + f". The paper's FDSC has a median {fdsc_words}.")
    return out


#: The law families whose best setting (on the training half) the study scores beside the law.
FAMILIES = ("gains/cost", "ideal pair/band_power", "tuned pair/band_power", "tuned pair/cost",
            "tuned filtered pair/band_power", "tuned filtered pair/cost")


def scored_settings(example, train, seed, fs) -> tuple:
    """The settings a study scores on its test draws, from its training draws alone: the law
    chosen (first) and the best setting of each of :data:`FAMILIES`.

    Parameters
    ----------
    example : str
    train : sequence of dict
        :func:`fdsc.paper.pays.disturbance_law_runs.draw_result` of the training draws (every
        setting run).
    seed : int
    fs : FixedSet

    Returns
    -------
    tuple of str
        The test draws need these settings only (:func:`choose` makes the same choices from the
        training half).
    """
    st = Study(example, seed, tuple(train), fs, settings()[0], REFERENCE_FAMILIES[0], n_train=len(train))
    present = [p for p in FAMILIES if any(k.startswith(p) for k in settings())]
    return tuple(dict.fromkeys([st.best_of(""), *(st.best_of(p) for p in present)]))


def choose(example, draws, seed, fs):
    """The study of an example from its draws: the law (under the switching limit) and the
    reference family chosen on the training half.

    Parameters
    ----------
    example : str
    draws : sequence of dict
        :func:`fdsc.paper.pays.disturbance_law_runs.draw_result` of every draw, train half first.
    seed : int
    fs : FixedSet

    Returns
    -------
    Study
    """
    st = Study(example, seed, tuple(draws), fs, settings()[0], REFERENCE_FAMILIES[0])
    law = st.best_of("")
    ref = min(REFERENCE_FAMILIES,
              key=lambda f: np.mean(np.log(st.reference_ratio(f, st.train))))
    return Study(example, seed, tuple(draws), fs, law, ref)
