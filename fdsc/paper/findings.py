"""The book's answer on one screen: the findings of the whole reproduction, from the record.

:func:`findings` reads the reproduction record (and, for two numbers the record does not hold, the
cached chapter results) and returns a :class:`Findings` whose :meth:`~Findings.prose` gives the
formatted numbers the landing page glues: what was reproduced, whether FDSC pays against the
{comparator set}, why not, what would pay, and what the paper gets wrong.
"""

from dataclasses import dataclass

import numpy as np

from fdsc.paper.record import PAPER_FIGURES, figure_status
from fdsc.paper.shared.comparators import COMPARATORS, best_fixed
from fdsc.paper.shared.prose import count, num, pct, span, times

__all__ = ["Findings", "findings", "law_sentence", "PRINTED_BOUNDS"]

#: The record entries of the four bounds printed beside the gains (Sec. IV), in the paper's order.
PRINTED_BOUNDS = ("bound_f1", "bound_f2", "bound_f3", "bound_e")
_SWITCHED = ("FDSC", "FDSC (dwell)", "FDSC (HF best)")
_REPRODUCED = ("match", "close")
_NOT = ("differs", "not reproducible")


@dataclass(frozen=True)
class Findings:
    """The numbers of the landing page's "Findings at a glance".

    Parameters
    ----------
    verdicts : dict
        ``{verdict: number of entries}`` over the entries that set a printed number beside ours
        (match, close, differs, not reproducible).
    gains_reproduced : int
        The paper's four printed gains (K_f1, K_f2, K_f3, K_e) whose recomputation matches or is
        close.
    claims : dict
        ``{PASS, PARTLY, FAIL: count}`` of the claims checklist.
    figures_redrawn, figures_total : int
        Paper figures redrawn from recorded data, and paper figures with content (Fig. 2, the
        code-availability box, excluded).
    n_cases : int
        Simulation cases of the paper on the aircraft (stationary, ρ_p and ρ_t grids).
    best_wins : dict
        ``{fixed controller: cases where it is the best fixed controller}`` over those cases.
    switched_wins : int
        Cases where a switched controller has less energy than every fixed one.
    lf_switches : int
        Switches of the printed law under the LF tones (paper Fig. 4's run).
    lf_horizon : float
        Its horizon (s).
    lf_ratio : float
        FDSC's energy under the LF tones over PassC-LF's.
    hf_open_loop_ratio : float
        The open loop's energy under the HF tones over PassC-HF's in steady state (the runs of
        500 s from rest carry a start-up transient that the claim is not about).
    airframe_mode, fast_pole, w_h : float
        ``|λ|`` of the open-loop airframe's modes (rad/s), the fast pole of the K_f1 loop (rad/s), and
        the HF band's edge ϖ_h (rad/s).
    ideal : dict
        ``{example: least energy of the ideal segment law over the best fixed controller's}``
        along the ρ_t family.
    crossover, crossover_printed : float
        ρ_p where FDSC's energy reaches PassC-LF's (paper Fig. 7), ours and printed.
    bounds : dict
        ``{printed bound entry: (printed value, verdict)}``.
    q_gammas : tuple of float
        γ_1, γ_2 for which Theorem 1's LMIs are feasible with the printed Q's.
    thm1_feasible, thm1_diverging, thm1_clean, thm1_sliding : int
        Mode pairs of the counterexample search for which Theorem 1's LMIs are feasible, those that
        diverge under the printed law (measured ẋ), and of these the runs without sliding (inside
        the theorem's hypothesis) and those that slide or chatter (outside it).
    thm1_multiplier : float
        The growth per turn of the exact counterexample (return map, no sliding).
    law : dict
        ``{example: summary}`` of the law on the disturbance estimate on the test draws of the
        full non-stationary study (:func:`fdsc.paper.pays.disturbance_law.load_full`), or of the
        record's seeded subset where the full study is absent.
    """

    verdicts: dict
    gains_reproduced: int
    claims: dict
    figures_redrawn: int
    figures_total: int
    n_cases: int
    best_wins: dict
    switched_wins: int
    lf_switches: int
    lf_horizon: float
    lf_ratio: float
    hf_open_loop_ratio: float
    airframe_mode: float
    fast_pole: float
    w_h: float
    ideal: dict
    crossover: float
    crossover_printed: float
    bounds: dict
    q_gammas: tuple
    thm1_feasible: int
    thm1_diverging: int
    thm1_clean: int
    thm1_sliding: int
    thm1_multiplier: float
    law: dict

    def prose(self):
        """The formatted numbers the landing page quotes.

        Returns
        -------
        dict
            ``{name: text}`` for :func:`fdsc.paper.shared.prose.glue_numbers`.
        """
        v, c = self.verdicts, self.claims
        wins = ", ".join(f"{name} in {count(k)}" for name, k in
                         sorted(self.best_wins.items(), key=lambda kv: -kv[1]) if k)
        out = {
            "n_printed": count(sum(v.values())),
            "gains_reproduced": count(self.gains_reproduced),
            "n_reproduced": count(sum(v[k] for k in _REPRODUCED)),
            "n_match": count(v["match"]), "n_close": count(v["close"]),
            "n_differs": count(v["differs"]), "n_not_reproducible": count(v["not reproducible"]),
            "figures_redrawn": count(self.figures_redrawn), "figures_total": count(self.figures_total),
            "claims_pass": count(c["PASS"]), "claims_partly": count(c["PARTLY"]),
            "claims_fail": count(c["FAIL"]),
            "n_cases": count(self.n_cases), "best_wins": wins,
            "switched_wins": count(self.switched_wins),
            "lf_switches": count(self.lf_switches), "lf_horizon": num(self.lf_horizon),
            "lf_ratio": times(self.lf_ratio), "hf_open_loop_ratio": times(self.hf_open_loop_ratio),
            "airframe_mode": num(self.airframe_mode), "fast_pole": num(self.fast_pole),
            "w_h": num(self.w_h, 2),
            "crossover": num(self.crossover), "crossover_printed": num(self.crossover_printed, 1),
            "q_gamma_1": num(self.q_gammas[0]), "q_gamma_2": num(self.q_gammas[1]),
            "thm1_feasible": count(self.thm1_feasible), "thm1_diverging": count(self.thm1_diverging),
            "thm1_clean": count(self.thm1_clean), "thm1_sliding": count(self.thm1_sliding),
            "thm1_multiplier": times(self.thm1_multiplier),
        }
        for example, ratio in self.ideal.items():
            out[f"ideal_{example}"] = times(ratio)
        out["law_sentence"] = law_sentence(self.law)
        def states(r):
            k = r.get("fixed_controllers", {}).get(r["fixed_in_advance"], {}).get("states")
            return "a static gain" if k == 0 else f"{k} states" if k else "a controller"

        law = self.law
        if len({r["fixed_in_advance"] for r in law.values()}) == 1:
            name = next(iter(law.values()))["fixed_in_advance"]
            where = {"aircraft": "the aircraft", "generic": "the generic example"}
            out["law_chosen_phrase"] = (f"{name} on both plants, with " + " and ".join(
                f"{states(r)} on {where.get(e, e)}" for e, r in law.items()))
        else:
            out["law_chosen_phrase"] = "; ".join(f"{r['fixed_in_advance']} ({states(r)}) on the {e}"
                                                 for e, r in law.items())
        lose = []
        for r in law.values():
            per = r.get("robustness", {}).get("snr_db", {})
            bad = [float(k) for k, v in per.items() if v["median"] >= 1.0]
            lose.append(max(bad) if bad else None)
        out["law_noise"] = ("the gain does not survive a noisy estimate: at an SNR of "
                            f"{min(x for x in lose if x is not None):g} dB the law loses on "
                            + ("both plants" if all(x is not None for x in lose) else "one plant")
                            if any(x is not None for x in lose) else
                            "the gain survives the noisy estimates tried")
        for example, r in self.law.items():
            out |= {f"law_{example}_chosen": r["fixed_in_advance"],
                    f"law_{example}_fdsc": times(r["fdsc_median_ratio"]["FDSC"]),
                    f"law_{example}_value": times(r["reference_median_ratio"]),
                    f"law_{example}_median": times(r["median_ratio_vs_fixed_in_advance"]),
                    f"law_{example}_win": pct(r["win_rate_vs_fixed_in_advance"]),
                    f"law_{example}_n": count(r["draws_test"])}
        bad = [f"{printed} ({verdict})" for printed, verdict in self.bounds.values()
               if verdict in _NOT]
        out["bounds_bad"] = count(len(bad))
        out["bounds_bad_list"] = ", ".join(bad) if bad else "none"
        return out


def law_sentence(law):
    """One sentence per example: against the fixed controller chosen in advance, whether the best
    law on the disturbance estimate pays and by how much, what switching is worth at all (the
    clairvoyant switching reference), and what is left on a noisy estimate and on sampled
    measurements.

    Parameters
    ----------
    law : dict
        ``{example: summary}`` (see :class:`Findings`).

    Returns
    -------
    str
    """
    parts = []
    for example, r in law.items():
        ratio, win = r["median_ratio_vs_fixed_in_advance"], r["win_rate_vs_fixed_in_advance"]
        against = f"the fixed controller chosen in advance ({r['fixed_in_advance']})"
        verb = "it pays" if ratio < 1 and win > 0.5 else "it does not pay"
        text = (f"on the {example} example {verb}: the best such law has a median energy {times(ratio)} "
                f"that of {against} and less on {pct(win)} of {count(r['draws_test'])} test draws, where "
                f"switching clairvoyantly at the breaks between controllers designed for each type of "
                f"segment reaches {times(r['reference_median_ratio'])}")
        parts.append(text + _noise_clause(r.get("robustness")) + _measured_clause(r.get("measured")))
    return "; ".join(parts)


def _measured_clause(m):
    """The medians on sampled measurements (backward difference, model errors), or ``""``."""
    if not m:
        return ""
    med = [v["median"] for k, v in m["variants"].items() if k not in ("exact", "min_switching")]
    return ("; on sampled measurements (a backward difference, A off by 10 %) its medians are "
            f"{span(min(med), max(med), fmt=times)}")


def _noise_clause(rob):
    """How much of the gain is left on a noisy estimate, or ``""``."""
    if not rob:
        return ""
    per = rob["snr_db"]
    snr = max(per, key=float)
    worse = [s for s in per if per[s]["median"] >= 1.0]
    text = f"; with the estimate's noise at {float(snr):g} dB the median is {times(per[snr]['median'])}"
    if worse:
        text += f", and from {max(float(s) for s in worse):g} dB on the law loses"
    return text


def _law(record):
    from fdsc.paper.pays.disturbance_law import load_full

    full = load_full()
    if full is not None:
        out = {e: dict(full[e]) for e in ("generic", "aircraft")}
        for e in out:
            if "measured" in full:
                out[e]["measured"] = full["measured"][e]
            if "robustness" in full:
                out[e]["robustness"] = full["robustness"][e]
        return out
    rec = _entries(record)["supervisor"]["recomputed"]
    return {e: rec[e] for e in ("generic", "aircraft")}


def _entries(record):
    return {e["id"]: e for e in record["entries"]}


def _ideal_generic():
    from fdsc.paper.pays.generic_example import generic_study

    study = generic_study()
    _, best = best_fixed(study.rho_t_sweep.energy, "generic")
    return float(np.min(study.ideal_rho_t / best))


def findings(record):
    """The findings of the reproduction, read from the record.

    Parameters
    ----------
    record : dict
        The reproduction record (:func:`fdsc.paper.record.reproduction_record`).

    Returns
    -------
    Findings

    Raises
    ------
    KeyError
        If the record lacks an entry the findings need (named).
    """
    e = _entries(record)
    needed = ("K_f1", "K_f2", "K_f3", "K_e", "comparators", "baselines", "supervisor",
              "mixed_crossover", "thm1_gammas", "theorem1_counterexamples", *PRINTED_BOUNDS)
    missing = [k for k in needed if k not in e]
    if missing:
        raise KeyError(f"the record lacks the entries {missing} that the findings read")
    verdicts = {v: sum(x["verdict"] == v for x in record["entries"]) for v in _REPRODUCED + _NOT}
    claims = {v: sum(c["verdict"] == v for c in record["claims"]) for v in ("PASS", "PARTLY", "FAIL")}
    status = figure_status(record)
    redrawn = sum(r["status"] == "redrawn from recorded data" for r in status)
    total = sum(1 for n in PAPER_FIGURES if n != 2)
    best = e["comparators"]["recomputed"]["aircraft"]["best"]
    families = ("stationary", "mixed", "piecewise")
    best_wins = {n: sum(best[f][n] for f in families) for n in COMPARATORS["aircraft"]}
    base = e["baselines"]["recomputed"]
    switched_wins = sum(base["wins"].get(n, 0) for n in _SWITCHED)
    stat = base["stationary"]
    lf_fig = record["figures"]["lf_outputs"]
    crossover = e["mixed_crossover"]
    tc = e["theorem1_counterexamples"]["recomputed"]["counts"]
    airframe, fast_pole, w_h = _poles()
    gains = sum(e[k]["verdict"] in _REPRODUCED for k in ("K_f1", "K_f2", "K_f3", "K_e"))
    return Findings(
        verdicts=verdicts, gains_reproduced=gains, claims=claims, figures_redrawn=redrawn,
        figures_total=total,
        n_cases=sum(best_wins.values()), best_wins=best_wins, switched_wins=switched_wins,
        lf_switches=int(lf_fig["switches"]["FDSC"]), lf_horizon=float(lf_fig["horizon"]),
        lf_ratio=stat["LF"]["FDSC"] / stat["LF"]["PassC-LF"],
        hf_open_loop_ratio=_hf_open_loop_steady(),
        airframe_mode=airframe, fast_pole=fast_pole, w_h=w_h,
        ideal={"aircraft": float(min(base["ideal_segment_law_rho_t"]["ratio_to_best_fixed"])),
               "generic": _ideal_generic()},
        crossover=float(crossover["recomputed"]["PassC-LF"]), crossover_printed=float(crossover["paper"]),
        bounds={k: (e[k]["paper"], e[k]["verdict"]) for k in PRINTED_BOUNDS},
        q_gammas=tuple(float(g) for g in e["thm1_gammas"]["recomputed"]["paper_Q"]),
        thm1_feasible=int(tc["feasible"]), thm1_diverging=int(tc["diverging_previous"]),
        thm1_clean=int(tc["clean_previous"]), thm1_sliding=int(tc["sliding_previous"]),
        thm1_multiplier=float(e["theorem1_counterexamples"]["recomputed"]["exact"]["multiplier"]),
        law=_law(record))


def _hf_open_loop_steady():
    """The open loop's steady-state energy under the HF tones over PassC-HF's (K_f3)."""
    import fdsc
    from fdsc.paper.shared.data import aircraft, hf_disturbance, paper_gains

    plant, K, d = aircraft(), paper_gains()["K_f3"], hf_disturbance()
    ratio = [fdsc.steady_state_gain(plant.closed_loop(G), d.frequencies, d.amplitudes)
             for G in (np.zeros_like(K), K)]
    return (ratio[0] / ratio[1]) ** 2


def _poles():
    """``|λ|`` of the airframe's open-loop modes, the fast pole of the K_f1 loop, and ϖ_h."""
    from fdsc.paper.shared.data import aircraft, paper_bands, paper_gains

    plant, gains = aircraft(), paper_gains()
    airframe = float(np.max(np.abs(np.linalg.eigvals(plant.A))))
    fast = float(np.max(np.abs(np.linalg.eigvals(plant.A + plant.B2 @ gains["K_f1"]))))
    return airframe, fast, float(paper_bands()["HF"].lower)
