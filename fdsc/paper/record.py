"""The reproduction record: every printed number beside ours, with a verdict.

``python -m fdsc reproduce --out DIR`` writes :func:`reproduction_record` to
``DIR/reproduction.json``; the book's introduction renders the same entries.
"""




from .data import (
    STATIONARY_DT,
    STATIONARY_HORIZON,
    our_q,
    paper_data,
    paper_gains,
)
from .environment import environment
from .frequency_selective import prop1_cases, prop1_summary, table1_trends
from .gkyp_lemma import gain_band_table, printed_bounds
from .names import GAIN_ORDER
from .passive_controllers import bound_candidates, gain_comparison, hf_best, recompute_gains, sigma_curves
from .stationary import stationary_runs
from .theorem1 import theorem1_table
from .verdict import VERDICTS, verdict

__all__ = [
    "reproduction_record",
    "FIGURE_IDS",
    "PAPER_FIGURES",
    "figure_status",
]


#: The record's figure entries, named by content, with the number of the paper figure each
#: reproduces (numbers of the compiled tex, whose Fig. 2 is the code-availability box).
FIGURE_IDS = {"sigma_max": 3, "lf_outputs": 4, "hf_outputs": 5, "hf_l2": 6}


#: Every figure of the paper (compiled numbering): what it shows and the chapter that redraws it
#: (None: not redrawn yet).
PAPER_FIGURES = {
    1: ("the closed loop with FDSC (block diagram)", "switching_law"),
    2: ("code and data availability box (no data)", None),
    3: ("sigma_max of the closed loops with K_f1, K_f2, K_f3, K_e", "passive_controllers"),
    4: ("q, delta_E, delta_PTV under the LF disturbance, four controllers", "stationary"),
    5: ("the same under the HF disturbance", "stationary"),
    6: ("L2-induced norm over time under the HF disturbance", "stationary"),
    7: ("output energy over [0, 500] against rho_p (mixed disturbance)", None),
    8: ("output energy over [0, 1000 + 500 rho_t] against rho_t (piecewise disturbance)", None),
}


def figure_status(record):
    """One row per paper figure: number, content, chapter, record entry and status.

    Parameters
    ----------
    record : dict
        The reproduction record (its ``figures`` say which figures have data).

    Returns
    -------
    list of dict
        ``figure, shows, chapter, record_entry, status`` with status ``redrawn from recorded
        data``, ``drawn (no data)``, ``nothing to reproduce`` or ``not reproduced yet``.
    """
    by_number = {v["paper_figure"]: k for k, v in record["figures"].items() if "paper_figure" in v}
    rows = []
    for num, (shows, chapter) in PAPER_FIGURES.items():
        entry = by_number.get(num)
        if entry is not None:
            status = "redrawn from recorded data"
        elif chapter is not None:
            status = "drawn (no data)"
        elif num == 2:
            status = "nothing to reproduce"
        else:
            status = "not reproduced yet"
        rows.append({"figure": f"paper Fig. {num}", "shows": shows, "chapter": chapter or "",
                     "record_entry": entry or "", "status": status})
    return rows


def _by_gain_band(table, key):
    out = {}
    for row in table:
        out.setdefault(row["gain"], {})[row["band"]] = row[key]
    return out


def _paper_bounds():
    ctrl = paper_data("controllers")
    return {g: {ctrl[g]["band"]: ctrl[g]["bound"]} for g in GAIN_ORDER}


def _worst(verdicts):
    return max(verdicts, key=VERDICTS.index)


def reproduction_record():
    """The reproduction record ``{"entries": [...], "figures": {...}, "environment": {...}}``.

    Entries (ids fixed by the issues): ``sigma_peak`` (band peaks of σ_max for each
    printed gain and band, against the printed bounds) and ``lemma1_gamma`` (Lemma 1's
    certified γ for the same pairs, against the same bounds).
    """
    table = gain_band_table()
    bounds = printed_bounds(table)
    per_gain = {b["gain"]: b["verdict"] for b in bounds}
    lmi_verdicts = {b["gain"]: verdict(b["paper"], b["lmi_gamma"]) for b in bounds}
    worst_rel = max(abs(r["rel_diff"]) for r in table)
    ratios = ", ".join(f"{b['gain']} {b['paper']}/{b['peak']:.4f}" for b in bounds)
    entries = [
        {"id": "sigma_peak", "source": "Sec. IV, bounds printed beside K_f1, K_f2, K_f3, K_e; paper Fig. 3",
         "paper": _paper_bounds(), "recomputed": _by_gain_band(table, "peak"),
         "omega_peak": _by_gain_band(table, "omega_peak"),
         "verdict": _worst(per_gain.values()), "verdicts": per_gain,
         "note": ("sup of sigma_max(G(jw)) over each band (grid + local refinement, tail bound "
                  "for HF/EF) for the printed gains; in-band printed/recomputed: " + ratios +
                  ". Which quantity the printed bounds are is examined in the passive-controller "
                  "chapter.")},
        {"id": "lemma1_gamma", "source": "Lemma 1 (eq. gKYP_LMI) applied to the printed gains",
         "paper": _paper_bounds(), "recomputed": _by_gain_band(table, "lmi_gamma"),
         "max_eig": _by_gain_band(table, "max_eig"), "status": _by_gain_band(table, "status"),
         "verdict": _worst(lmi_verdicts.values()), "verdicts": lmi_verdicts,
         "note": (f"smallest gamma certified by the gKYP LMI (cvxpy + Clarabel, real embedding "
                  f"for MF); equals the swept band peak within {worst_rel:.1e} relative on all "
                  f"16 gain/band pairs, so Lemma 1 is lossless here and the printed bounds are "
                  f"not Lemma 1's value for the printed gains either.")},
    ]
    entries += _passive_entries()
    entries += _selectiveness_entries()
    sw_entries, figures = _switching_entries_and_figures()
    entries += sw_entries
    return {"entries": entries, "figures": figures, "environment": environment()}


_BOUND_IDS = {"K_f1": "bound_f1", "K_f2": "bound_f2", "K_f3": "bound_f3", "K_e": "bound_e"}


def _passive_entries():
    """Entries K_f1..K_e (gains), bound_f1..bound_e (printed bounds), hf_best."""
    results = recompute_gains()
    entries = []
    for row in gain_comparison(results):
        band = row["band"]
        how = "H-infinity state-feedback LMI" if band == "EF" else f"{band} synthesis LMI"
        entries.append({
            "id": row["name"], "source": f"Sec. IV, {row['name']}",
            "paper": row["paper_K"], "recomputed": row["ours_K"], "verdict": row["verdict"],
            "note": (f"{how} (derived in the passive-controller chapter"
                     + ("" if band == "EF" else f"; stability LMI with epsilon = "
                        f"{results[row['name']].epsilon:g}")
                     + ("; sigma = 0" if band == "HF" else "") + f"); relative difference "
                     f"{row['rel_diff']:.2e}; in-band gain of the printed gain "
                     f"{row['gamma_paper_gain']:.4f}, of ours {row['gamma_sweep']:.4f} "
                     f"(LMI bound {row['gamma_lmi']:.4f}). "
                     + ("The HF LMI is only sufficient and depends on sigma; see hf_best."
                        if band == "HF" else
                        "The optimal gains are high-gain and gamma is flat along the gain's size, "
                        "so only a few digits are determined."))})
    for b in bound_candidates(results):
        primary_ok = b["primary_verdict"] in ("match", "close")
        entries.append({
            "id": _BOUND_IDS[b["gain"]], "source": f"Sec. IV, bound printed beside {b['gain']}",
            # the number that decided the verdict: the primary quantity, unless only a candidate
            # matched
            "paper": b["paper"], "verdict": b["verdict"],
            "recomputed": b["value"] if b["verdict"] == "match" and not primary_ok else b["primary"],
            "candidates": b["candidates"], "crossings_rad_s": b["crossings"],
            "note": (f"the printed claim is sigma_max(G(jw), {b['gain']}) < {b['paper']} on the "
                     f"{b['band']} band; the in-band peak of the printed gain is {b['primary']:.4f} "
                     f"({b['primary_verdict']}). "
                     + ("" if primary_ok else
                        f"Nearest of the candidates tried (picked after the fact, so at best a "
                        f"match, never close): {b['best']} = {b['value']:.4f} ({b['best_verdict']}). "
                        "Tried: " + ", ".join(b["candidates"]) + "."))})
    hb = hf_best()
    entries.append({
        "id": "hf_best", "source": "Sec. IV, K_f3 and paper Fig. 3 (HF design)",
        "paper": {"K": paper_data("controllers")["K_f3"]["value"],
                  "in_band": hb["K_f3_in_band"], "out_of_band": hb["K_f3_out_of_band"]},
        "recomputed": {"K": hb["K"], "sigma": hb["sigma"], "gamma_lmi": hb["gamma_lmi"],
                       "in_band": hb["in_band"], "out_of_band": hb["out_of_band"]},
        "verdict": "new",
        "note": (f"not printed by the paper: best certified HF design over the sigma grid: "
                 f"in-band gain {hb['in_band']:.4f} "
                 f"(LMI {hb['gamma_lmi']:.4f}) and out-of-band peak {hb['out_of_band']:.4f}, "
                 f"against {hb['K_f3_in_band']:.4f} and {hb['K_f3_out_of_band']:.1f} for the printed "
                 f"K_f3 ('paper' holds K_f3's values recomputed from the printed gain).")})
    return entries


def _selectiveness_entries():
    """Entries prop1_checks and table1_checks (Sec. III)."""
    rows = prop1_cases(144)
    summ = prop1_summary(rows)
    tt = table1_trends()
    t1 = {r["quantity"]: {"claimed": r["claimed"], "observed": r["observed"],
                          "values": r["values"], "verdict": r["verdict"]} for r in tt["rows"]}
    return [
        {"id": "prop1_checks", "source": "Sec. III, Proposition 1",
         "paper": "S(Omega_in) > 0 and S(Omega_out) < 0 for frequency-limited states",
         "recomputed": summ,
         "verdict": "differs" if summ["failed"] else "match",
         "note": ("seeded random stable systems (n = 2, 3), frequency-limited sums of sinusoids and "
                  "random positive-definite Q's. Holds for every steady state with LF/HF ranges; "
                  "fails for MF as in-band range (for real signals the MF weight is negative at "
                  "every frequency) and for short windows that contain the transient.")},
        {"id": "table1_checks", "source": "Sec. III, Table I",
         "paper": {r["quantity"]: r["claimed"] for r in tt["rows"]},
         "recomputed": t1, "alpha": tt["alpha"],
         "verdict": _worst([r["verdict"] for r in tt["rows"]]),
         "note": ("mode i = PassC-HF (Omega_3, Q_2), mode j = PassC-LF (Omega_1, Q_1), disturbance "
                  "mixing the paper's LF and HF tones at dominance alpha_i; steady-state rows exact, "
                  f"time shares from switched simulations of {tt['horizon']:g} s (paper's Q's).")},
    ]


def _sigma_max_figure():
    curves = sigma_curves(paper_gains())
    return {"paper_figure": FIGURE_IDS["sigma_max"], "omega": curves["omega"],
            "sigma_max": curves["sigma"], "band_limits": [1.0, 10.0],
            "units": {"omega": "rad/s", "sigma_max": "1 (largest singular value of G(jw))"}}


def _switching_entries_and_figures():
    """Entries Q_1, Q_2, thm1_gammas and the figures sigma_max, lf_outputs, hf_outputs, hf_l2
    (paper Figs. 3-6)."""
    sw = paper_data("switching")
    ours = our_q()
    table = theorem1_table()
    paper_row = table[0]
    entries = []
    for k, name in enumerate(("Q_1", "Q_2")):
        entries.append({
            "id": name, "source": f"Sec. IV, {name}", "paper": sw[name]["value"],
            "recomputed": ours.Q[k], "verdict": "not reproducible",
            "note": ("the paper prints the Q's but not gamma_tol nor the Q's scale, which the "
                     "Remark 4 design needs (Q enters Theorem 1 only through differences); ours: "
                     "Remark 4 design with gamma_tol = "
                     f"{table[2]['gamma_tol']:g} (in-band mode PassC-HF): it reaches gamma_2 = "
                     f"{ours.gammas[1]:.4f} by driving Q_1 to the margin; the printed Q's certify "
                     f"only gamma = ({paper_row['gamma_1']:.4g}, {paper_row['gamma_2']:.4g}).")})
    entries.append({
        "id": "thm1_gammas", "source": "Theorem 1, paper Remark 4 (gammas not printed)",
        "paper": None,
        "recomputed": {"paper_Q": [paper_row["gamma_1"], paper_row["gamma_2"]],
                       "ours": {f"gamma_tol={r['gamma_tol']:g}": [r["gamma_1"], r["gamma_2"]]
                                for r in table[1:]}},
        "verdict": "new",
        "note": "the paper prints no gammas; these are the values Theorem 1 certifies."})
    figures = {"sigma_max": _sigma_max_figure()}
    for fig, kind in (("lf_outputs", "LF"), ("hf_outputs", "HF")):
        runs = stationary_runs(kind)
        figures[fig] = {"paper_figure": FIGURE_IDS[fig], "disturbance": kind,
                        "horizon": STATIONARY_HORIZON, "dt": STATIONARY_DT,
                        "energy": {k: v for k, v in runs["energy"].items() if k != "FDSC (our Q)"},
                        "energy_fdsc_our_q": runs["energy"]["FDSC (our Q)"],
                        "switches": runs["switches"],
                        "units": {"horizon": "s", "dt": "s",
                                  "energy": "integral of z'z over [0, horizon] (z as printed, s)"}}
        if kind == "HF":
            figures["hf_l2"] = {
                "paper_figure": FIGURE_IDS["hf_l2"], "horizon": STATIONARY_HORIZON,
                "l2_induced_norm_final": {k: float(v[-1]) for k, v in runs["l2"].items()},
                "l2_induced_norm_steady_state": runs["l2_steady"],
                "units": {"horizon": "s", "l2_induced_norm": "1 (sqrt of an energy ratio)"},
                "note": "running ratio from rest at the horizon; steady state = its limit for the "
                        "fixed gains (closed form); FDSC has no closed form"}
    return entries, figures
