"""Chapter 'switching_law': what the printed law does in continuous time, and three well-posed laws.

1. **The conflict region.** With the measured ẋ = A_a x + B d (a the active mode), mode a
   *holds itself* at (x, d) if its own score wins there: ``argmax_j s_j^(a)(x, d) = a``. For two
   modes every point of the state space is of one of four kinds: only mode 1 holds itself (the
   law settles in 1), only mode 2 does, both do (the mode active on arrival stays: the law has
   memory), or neither does. In the last set the sampled law switches at every sample (1, 2, 1,
   …), so as dt → 0 the loop follows the *implicit* dynamics ``ẋ = ½(A_1 + A_2) x + B d`` with the
   input ``u = ½(K_1 + K_2) x`` on average, and every sample spent there is a switch. (The
   Filippov inclusion ``ẋ ∈ co{A_1 x + B d, A_2 x + B d}`` admits any mix there; sampling picks
   ½.) For d = 0 the scores are quadratic forms in x, so the four sets are cones; a disturbance
   moves them.
2. **Convergence.** Runs at dt, dt/2, …, dt/16: energy, time shares, switch count × dt (→ the
   time spent in the chattering set), the share of mode 1 inside that set (→ ½) and the
   actuator rate ``|Δu|/dt`` at the switches (which grows like 1/dt).
3. **Well-posed laws** (:class:`fdsc.SwitchRule`): hysteresis (relative margin), minimum dwell
   time and a moving-window FD-EEF law (paper Remark 6), each against its parameter on the
   paper's stationary, mixed and piecewise cases, at dt and dt/2.
"""

import numpy as np

from fdsc.paper.pays.disturbance_law_draws import certificate as geromel_colaneri_certificate
from fdsc.paper.repairs.wellposed_regions import (
    D_REF as D_REF,  # imported from here by the chapter's notebook
)
from fdsc.paper.repairs.wellposed_regions import (
    REGION_KINDS,
    ConvergenceRow,
    ConvergenceStudy,
    LawRegions,
    convergence_study,
    holds_itself,
    law_regions,
    region_codes,
)
from fdsc.paper.repairs.wellposed_rules import (
    _FIXED,
    LAW_CASES,
    LAW_GRIDS,
    LAW_TITLES,
    DwellLawCheck,
    LawStudy,
    against_comparators,
    comparator_energies,
    comparator_table,
    dwell_law_check,
    law_study,
)
from fdsc.paper.shared.dwell_time import dwell_certificate
from fdsc.paper.shared.prose import num
from fdsc.paper.shared.results import RecordPart, entry

__all__ = [
    "REGION_KINDS",
    "holds_itself",
    "region_codes",
    "LawRegions",
    "law_regions",
    "ConvergenceRow",
    "ConvergenceStudy",
    "convergence_study",
    "LAW_GRIDS",
    "LAW_CASES",
    "LawStudy",
    "law_study",
    "DwellLawCheck",
    "dwell_law_check",
    "comparator_energies",
    "against_comparators",
    "comparator_table",
    "LAW_TITLES",
    "dwell_conditions",
    "record_part",
]


def _sliding_entry(regions, conv):
    spread = {c: conv.energy_spread(c) for c in conv.cases()}
    rec = {"angular_share_d0": {q: dict(zip(REGION_KINDS, map(float, s), strict=True))
                                for q, s in regions.angular_share.items()},
           "trajectory_share_by_kind": dict(zip(REGION_KINDS, map(float, np.bincount(
               regions.traj_codes, minlength=4) / regions.traj_codes.size), strict=True)),
           "convergence": [{"case": r.case, "dt": r.dt, "energy": r.energy, "share_hf": r.share_hf,
                            "switches": r.switches, "switches_x_dt": r.switch_time,
                            "chatter_time": r.chatter_time,
                            "share_mode1_in_chatter": r.share_lf_in_chatter,
                            "du_max": r.du_max, "du_median": r.du_median, "rate_max": r.rate_max}
                           for r in conv.rows],
           "energy_spread": spread}
    return entry("sliding", "paper Remark 7 (sliding motion assumed absent; nothing printed)", None,
                 rec, "new",
                 "The printed law with the measured ẋ: inside the set where neither mode holds "
                 "itself (the chattering region) the sampled law switches at every sample (mode 1's "
                 "share there tends to ½), and on the border of that set it slides (mode 1 at every "
                 "other sample); time shares and switch count × dt converge as dt → 0 while the "
                 "energy scatters by a few per cent without a trend; the actuator rate ‖Δu‖/dt "
                 "grows like 1/dt.", horizon=conv.horizon)


def _law_record(study, law):
    return {"parameters": list(LAW_GRIDS[law]),
            "energy": {c: [study.energy[(law, p, c)] for p in LAW_GRIDS[law]] for c in LAW_CASES},
            "energy_half_dt": {c: [study.energy_half[(law, p, c)] for p in LAW_GRIDS[law]]
                               for c in LAW_CASES},
            "switches": {c: [study.switches[(law, p, c)] for p in LAW_GRIDS[law]] for c in LAW_CASES},
            "switches_half_dt": {c: [study.switches_half[(law, p, c)] for p in LAW_GRIDS[law]]
                                 for c in LAW_CASES},
            "well_posed": [study.well_posed(law, p) for p in LAW_GRIDS[law]],
            "default": study.default(law)}


def _reference_record(study):
    return {name: {c: study.energy[(name, 0.0, c)] for c in LAW_CASES} for name in ("printed", *_FIXED)} | {
        "printed_switches": {c: study.switches[("printed", 0.0, c)] for c in LAW_CASES},
        "printed_switches_half_dt": {c: study.switches_half[("printed", 0.0, c)] for c in LAW_CASES}}


def dwell_conditions(tau_d: float) -> dict:
    """Whether the two sufficient dwell-time conditions the book computes for the paper's two FDSC
    modes (the closed loops of K_f1 and K_f3, d = 0) certify a dwell τ_d, in words.

    The mode-wise bound τ* = ln μ / (2λ) of :func:`fdsc.paper.shared.dwell_time.dwell_certificate`
    (this chapter) and the Geromel–Colaneri condition of
    :func:`fdsc.paper.pays.disturbance_law_draws.certificate` (chapter 'ladder'), which is less
    conservative: a dwell one of them does not certify, the other may.

    Parameters
    ----------
    tau_d : float
        The dwell time in s.

    Returns
    -------
    dict of str
        ``modewise`` ("certifies" or "does not certify" τ_d), ``gc`` (the same for the
        Geromel–Colaneri condition) and ``gc_text`` (what that condition certifies for the two
        modes: "every dwell time down to … s, the least its search tries", "every dwell time from
        … s on" or "no dwell time up to 10⁴ s").
    """
    tau_star = dwell_certificate().bound.tau
    gc = geromel_colaneri_certificate("aircraft")
    if gc is None:
        gc_text, gc_ok = "no dwell time up to 10⁴ s", False
    else:
        gc_ok = tau_d >= gc.tau
        gc_text = (f"every dwell time down to {num(gc.tau)} s, the least its search tries"
                   if gc.bracket[0] == 0.0 else f"every dwell time from {num(gc.tau)} s on")
    verb = {True: "certifies", False: "does not certify"}
    return {"modewise": verb[tau_d > tau_star], "gc": verb[gc_ok], "gc_text": gc_text}


def record_part() -> RecordPart:
    """Record entries ``sliding``, ``hysteresis_dwell`` (with the certified dwell time of
    :func:`fdsc.paper.shared.dwell_time.dwell_certificate`) and ``eef_switching`` (all new).

    Returns
    -------
    RecordPart
    """
    regions, conv, study = law_regions(), convergence_study(), law_study()
    dwell = dwell_certificate().record_dict()
    check = dwell_law_check()
    dwell["dwell_law_check"] = {"tau": check.tau, "horizon": check.horizon,
                                "max_final_ratio": float(check.final_ratio.max()),
                                "switches": check.switches.tolist()}
    reference = _reference_record(study)
    hd = {"hysteresis": _law_record(study, "hysteresis"), "dwell": _law_record(study, "dwell"),
          "hysteresis_absolute": _law_record(study, "hysteresis_abs"),
          "reference": reference, "cases": list(LAW_CASES), "dt": study.dt,
          "against_comparators": against_comparators(study, comparator_energies(dt=study.dt))}
    hd["dwell_time_bound"] = dwell
    return RecordPart((
        _sliding_entry(regions, conv),
        entry("hysteresis_dwell", "paper Remark 7 (hysteresis, minimum dwell time; nothing printed)",
              None, hd, "new",
              "Energies and switch counts at dt and dt/2 of the hysteresis (relative and absolute "
              "margin) and minimum-dwell-time laws on the paper's stationary, mixed (ρ_p = 0.1) "
              "and piecewise (T = 500 s, ρ_t = 0.2) cases; a law passes the step-halving test if "
              "no case's switch count grows by more than half (or two switches) when dt halves."),
        entry("eef_switching", "paper Remark 6 (an FD-EEF-based law; nothing printed)", None,
              {"window": _law_record(study, "window"), "reference": reference,
               "cases": list(LAW_CASES), "dt": study.dt}, "new",
              "The law on the score averaged over the last T_w seconds (the FD-EEF of the recent "
              "past per unit time), with the measured ẋ, against T_w."),
    ))
