"""Chapter 'theorem1', continued: the result of the seeded search.

The outcomes and diagnoses of every case of :mod:`fdsc.paper.repairs.theorem1_cases` gathered in one
result (counts, families, causes, the divergent and the clean runs), and the smallest divergent
case printed as the chapter shows it.
"""

from dataclasses import dataclass

import numpy as np

from fdsc.paper.repairs.theorem1_cases import (
    _LAWS,
    _READING,
    CAUSES,
    CLEAN_LIMIT,
    DT_FRACTION,
    FAMILIES,
    MAX_STEPS,
    N_INITIAL,
    REFINE,
    SLOW_CONSTANTS,
    SearchCase,
    _outcomes,
    diagnose,
    search_case,
)
from fdsc.paper.repairs.theorem1_exact import ExactTurn, exact_applies, exact_turn
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.prose import count, matrix_text, num, pct

__all__ = ["SearchResult", "counterexample_search", "smallest_case", "smallest_table"]


@dataclass(frozen=True)
class SearchResult:
    """The counterexample search (see :func:`counterexample_search`).

    Parameters
    ----------
    cases : tuple of SearchCase
        Every case tried.
    outcomes : tuple of CaseOutcome
        One per feasible case and law.
    diagnoses : tuple of Diagnosis
        One per divergent outcome.
    """

    cases: tuple
    outcomes: tuple
    diagnoses: tuple

    def counts(self) -> dict:
        """Cases tried, refused (not Hurwitz), solver failures, Theorem 1 feasible, and per law
        the diverging runs and the sampling artefacts (growing on dt only).

        Returns
        -------
        dict
        """
        out = {"tried": len(self.cases),
               "not_hurwitz": sum(c.status == "not Hurwitz" for c in self.cases),
               "solver_failures": sum(c.status == "solver" for c in self.cases),
               "infeasible": sum(c.status == "infeasible" for c in self.cases),
               "feasible": sum(c.status == "feasible" for c in self.cases)}
        for law in _LAWS:
            oc = [o for o in self.outcomes if o.law == law]
            out[f"diverging_{law}"] = sum(o.diverging for o in oc)
            out[f"sampling_artefacts_{law}"] = sum(o.grew_coarse and not o.diverging for o in oc)
        kinds = self.run_kinds()
        out["clean_previous"] = sum(k == "clean" for k, _ in kinds.values())
        out["sliding_previous"] = sum(k == "sliding" for k, _ in kinds.values())
        return out

    def by_family(self) -> list:
        """One row per family: tried, feasible, diverging under each law.

        Returns
        -------
        list of dict
        """
        rows = []
        for fam in FAMILIES:
            cs = [c for c in self.cases if c.family == fam]
            oc = [o for o in self.outcomes if o.family == fam]
            rows.append({"family": fam, "tried": len(cs),
                         "feasible": sum(c.status == "feasible" for c in cs),
                         **{f"diverging ({law})": sum(o.diverging and o.law == law for o in oc)
                            for law in _LAWS},
                         **{f"sampling artefacts ({law})": sum(
                             o.grew_coarse and not o.diverging and o.law == law for o in oc)
                            for law in _LAWS}})
        return rows

    def family_table(self) -> list:
        """:meth:`by_family` as text with reader-facing column names (the readings of ẋ by name).

        Returns
        -------
        list of dict
        """
        names = {f"{kind} ({law})": f"{kind} ({_READING[law]})"
                 for kind in ("diverging", "sampling artefacts") for law in _LAWS}
        return [{names.get(k, k): (v if isinstance(v, str) else count(v)) for k, v in r.items()}
                for r in self.by_family()]

    def diagnosis_table(self) -> list:
        """One row per divergent run, every cell text (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        list of dict
            Family, seed, reading of ẋ, the log growth of V over the jumps and over the flows,
            the share of switches at which V increases and of samples in one-sample dwells, the
            spectral abscissa of ½(A₀ + A₁) and the cause.
        """
        return [{"family": d.family, "seed": str(d.seed), "reading of ẋ": _READING[d.law],
                 "log growth, jumps": num(d.log_growth_jumps),
                 "log growth, flows": num(d.log_growth_flows),
                 "switches with V up": pct(d.frac_up), "one-sample dwells": pct(d.chatter, 1),
                 "abscissa of (A₀+A₁)/2": num(d.average_abscissa), "cause": d.cause}
                for d in self.diagnoses]

    def divergent(self) -> list:
        """The divergent outcomes, smallest first (fewest states, then family order, then seed).

        Returns
        -------
        list of CaseOutcome
        """
        order = {f: k for k, f in enumerate(FAMILIES)}
        cases = {(c.family, c.seed): c for c in self.cases}
        return sorted((o for o in self.outcomes if o.diverging),
                      key=lambda o: (cases[o.family, o.seed].n, order[o.family], o.seed, o.law))

    def case(self, family: str, seed: int) -> SearchCase:
        """The case of a family and seed.

        Parameters
        ----------
        family : str
        seed : int

        Returns
        -------
        SearchCase
        """
        for c in self.cases:
            if (c.family, c.seed) == (family, seed):
                return c
        raise KeyError(f"no case {family!r}/{seed}")

    def exact(self, family: str, seed: int, law: str = "previous") -> ExactTurn:
        """The exact return map (:func:`~fdsc.paper.repairs.theorem1_exact.exact_turn`) of a case.

        Parameters
        ----------
        family : str
        seed : int
        law : {"previous", "candidate"}, optional

        Returns
        -------
        ExactTurn
        """
        c = self.case(family, seed)
        return exact_turn(c.modes, c.bands, c.Q, law=law)

    def run_kinds(self, limit: float = CLEAN_LIMIT) -> dict:
        """Each divergent run under the printed law (measured ẋ): clean or sliding, and how decided.

        Where the exact return map applies (two states, turning flows) it decides: a run is
        sliding if a switch of its cycle lands where the mode switched in is beaten at once.
        Otherwise a run is clean if at most ``limit`` of its samples lie in one-sample dwells.

        Parameters
        ----------
        limit : float
            Largest one-sample-dwell share of a clean run decided on samples.

        Returns
        -------
        dict of (str, int) to (str, str)
            ``(family, seed)`` → ``("clean" or "sliding", "exact" or "sampled")``.
        """
        out = {}
        for d in self.diagnoses:
            if d.law != "previous":
                continue
            c = self.case(d.family, d.seed)
            if exact_applies(c.modes, c.bands, c.Q, law=d.law):
                clean = self.exact(d.family, d.seed, d.law).clean
                out[d.family, d.seed] = ("clean" if clean else "sliding", "exact")
            else:
                out[d.family, d.seed] = ("clean" if d.chatter <= limit else "sliding", "sampled")
        return out

    def clean(self, limit: float = CLEAN_LIMIT) -> list:
        """The divergent runs under the printed law (measured ẋ) that do not slide, inside
        Theorem 1's no-sliding assumption (decided as in :meth:`run_kinds`).

        Parameters
        ----------
        limit : float
            Largest share of samples in one-sample dwells, where the exact map does not apply.

        Returns
        -------
        list of Diagnosis
        """
        kinds = self.run_kinds(limit)
        return [d for d in self.diagnoses
                if d.law == "previous" and kinds[d.family, d.seed][0] == "clean"]

    def exact_counterexample(self) -> tuple:
        """The first clean divergent run (in the order of :meth:`divergent`) whose exact return
        map proves divergence: Theorem 1's LMIs hold, no switch slides, multiplier > 1.

        Returns
        -------
        (CaseOutcome, ExactTurn)

        Raises
        ------
        LookupError
            If no run is proved divergent.
        """
        for o in self.divergent():
            c = self.case(o.family, o.seed)
            if o.law == "previous" and exact_applies(c.modes, c.bands, c.Q, law=o.law):
                turn = self.exact(o.family, o.seed, o.law)
                if turn.proves_divergence:
                    return o, turn
        raise LookupError("no divergent run of the search is proved divergent by its return map")

    def dwell_rows(self, limit: float = CLEAN_LIMIT) -> list:
        """One row per divergent run, clean runs under the measured ẋ first: family, seed, reading
        of ẋ (reader-facing), share of samples in one-sample dwells, whether it is clean and
        what decided it (:meth:`run_kinds`).

        Parameters
        ----------
        limit : float
            Largest one-sample-dwell share of a clean run.

        Returns
        -------
        list of dict
            Every cell text (:mod:`fdsc.paper.shared.prose`).
        """
        kinds = self.run_kinds(limit)
        clean = {k for k, (kind, _) in kinds.items() if kind == "clean"}
        how = {"exact": "return map", "sampled": "one-sample dwells"}
        rows = [({"family": d.family, "seed": str(d.seed), "reading of ẋ": _READING[d.law],
                  "one-sample dwells": pct(d.chatter, 1),
                  "clean": ("n/a" if d.law != "previous"
                            else "yes" if (d.family, d.seed) in clean else "no (slides)"),
                  "decided by": ("n/a" if d.law != "previous"
                                 else how[kinds[d.family, d.seed][1]])},
                 (d.law != "previous", (d.family, d.seed) not in clean, d.chatter, d.seed))
                for d in self.diagnoses]
        return [r for r, _ in sorted(rows, key=lambda rk: rk[1])]

    def prose(self) -> dict:
        """The search's numbers as text for the chapter (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        dict of str
            Counts of cases and runs (``tried``, ``feasible``, ``not_hurwitz``,
            ``solver_failures``, ``diverging_measured``, ``diverging_candidate``,
            ``artefacts_measured``, ``artefacts_candidate``), the clean runs (``n_clean``,
            ``clean_limit``, ``clean_max``), the sliding ones (``n_dirty``, ``chatter_min``,
            ``chatter_max`` over the measured runs that slide), how many were decided by the
            exact return map (``n_exact``), the divergent runs by family (``div_spiral``, the stretched
            spirals; ``div_other``, the other families), the diagnoses (``n_diag``;
            ``n_flows_down``, runs whose flows decrease V; ``n_avg_unstable``, runs whose average
            dynamics is unstable; ``cause_<reading>_<cause>`` per reading ``measured`` or
            ``candidate`` and cause ``chattering``, ``V``, ``flows``, ``other``), and the grid
            constants.
        """
        cnt = self.counts()
        clean = self.clean()
        kinds = self.run_kinds()
        dirty = [d.chatter for d in self.diagnoses
                 if d.law == "previous" and kinds[d.family, d.seed][0] == "sliding"]
        return {"tried": count(cnt["tried"]), "feasible": count(cnt["feasible"]),
                "not_hurwitz": count(cnt["not_hurwitz"]),
                "solver_failures": count(cnt["solver_failures"]),
                "infeasible": count(cnt["infeasible"]),
                "diverging_measured": count(cnt["diverging_previous"]),
                "diverging_candidate": count(cnt["diverging_candidate"]),
                "artefacts_measured": count(cnt["sampling_artefacts_previous"]),
                "artefacts_candidate": count(cnt["sampling_artefacts_candidate"]),
                "n_clean": count(len(clean)), "clean_limit": pct(CLEAN_LIMIT),
                "clean_max": pct(max((d.chatter for d in clean), default=0.0), 1),
                "n_dirty": count(len(dirty)),
                "n_exact": count(sum(how == "exact" for _, how in kinds.values())),
                "chatter_min": pct(min(dirty, default=0.0), 1),
                "chatter_max": pct(max(dirty, default=0.0)),
                "n_initial": count(N_INITIAL), "slow": num(SLOW_CONSTANTS, 2),
                "dtf": num(DT_FRACTION, 1), "maxsteps": count(MAX_STEPS), "refine": count(REFINE),
                **self._diagnosis_prose()}

    def _diagnosis_prose(self):
        rows = self.by_family()
        n_div = {r["family"]: sum(r[f"diverging ({law})"] for law in _LAWS) for r in rows}
        cause_key = {"chattering": "chattering", "V jumps up at switches": "V",
                     "V grows during flows": "flows", "other": "other"}
        reading = {"previous": "measured", "candidate": "candidate"}
        return {"div_spiral": count(n_div["spiral-2"]),
                "div_other": count(sum(v for f, v in n_div.items() if f != "spiral-2")),
                "n_diag": count(len(self.diagnoses)),
                "n_flows_down": count(sum(d.log_growth_flows < 0 for d in self.diagnoses)),
                "n_avg_unstable": count(sum(d.average_abscissa >= 0 for d in self.diagnoses)),
                **{f"cause_{reading[law]}_{cause_key[cause]}": count(n)
                   for law, c in self.causes().items() for cause, n in c.items()}}

    def causes(self) -> dict:
        """Number of divergent runs per cause and law.

        Returns
        -------
        dict
        """
        return {law: {cause: sum(d.cause == cause and d.law == law for d in self.diagnoses)
                      for cause in CAUSES} for law in _LAWS}


@cached
def counterexample_search(families: tuple = tuple(FAMILIES.items())) -> SearchResult:
    """The seeded search for Theorem 1 counterexamples.

    Parameters
    ----------
    families : tuple of (str, int)
        ``(family, number of seeds)``; seeds run from 0.

    Returns
    -------
    SearchResult

    Notes
    -----
    Theorem 1 (paper eqs. (33), (34)) with d = 0 claims convergence (statement (1)) under the law
    of paper eq. (31); a run grows if ``‖x(T)‖ > ‖x(0)‖`` and ``‖x(T)‖ > ‖x(T/2)‖`` for one of
    :data:`N_INITIAL` initial states after T = :data:`SLOW_CONSTANTS` slowest time constants, or
    if it overflows; a case is divergent if it grows on the grid dt and on dt / :data:`REFINE`.
    """
    cases = tuple(search_case(fam, s) for fam, count in families for s in range(count))
    outcomes = tuple(_outcomes([c for c in cases if c.status == "feasible"]))
    by_key = {(c.family, c.seed): c for c in cases}
    diagnoses = tuple(diagnose(by_key[o.family, o.seed], o) for o in outcomes if o.diverging)
    return SearchResult(cases, outcomes, diagnoses)


# ---------------------------------------------------------------------------------------------
# the record
# ---------------------------------------------------------------------------------------------

def _matrix(a):
    # 7 significant digits: the designed Q's can sit at the LMI margin (~1e-8)
    return [[float(f"{v:.7g}") for v in row] for row in np.atleast_2d(np.asarray(a, dtype=float))]


def smallest_case(search: SearchResult) -> dict:
    """The smallest divergent case written out (matrices to 7 significant digits).

    Parameters
    ----------
    search : SearchResult

    Returns
    -------
    dict
        Family, seed, law, A_0, A_1, B, C, the LF and HF edges, Q_0, Q_1, the γ's, the initial
        state, the final ratio and the eigenvalues of both modes (empty dict if none diverges).
    """
    div = search.divergent()
    if not div:
        return {}
    o = div[0]
    c = search.case(o.family, o.seed)
    return {"family": o.family, "seed": o.seed, "law": o.law, "A_0": _matrix(c.modes[0].A),
            "A_1": _matrix(c.modes[1].A), "B": _matrix(c.modes[0].B), "C": _matrix(c.modes[0].C),
            "w_l": float(c.bands[0].upper), "w_h": float(c.bands[1].lower),
            "Q_0": _matrix(c.Q[0]), "Q_1": _matrix(c.Q[1]), "q_source": c.q_source,
            "gammas": [float(g) for g in c.gammas], "x0": _matrix(o.worst_x0),
            "final_ratio": o.final_ratio, "horizon": o.horizon, "dt": o.dt,
            "eig_A_0": [str(np.round(e, 4)) for e in np.linalg.eigvals(c.modes[0].A)],
            "eig_A_1": [str(np.round(e, 4)) for e in np.linalg.eigvals(c.modes[1].A)]}


def _eigenvalues_text(a):
    def one(e):
        if abs(e.imag) < 1e-12 * max(abs(e.real), 1.0):
            return num(float(e.real), 4)
        return f"{num(float(e.real), 4)} {'+' if e.imag > 0 else '−'} {num(abs(float(e.imag)), 4)}i"
    ev = np.linalg.eigvals(np.asarray(a, dtype=float))
    return ", ".join(one(e) for e in ev[np.lexsort((ev.imag, ev.real))])


def smallest_table(search: SearchResult) -> list:
    """The smallest divergent case (:func:`smallest_case`) as a table, every cell text
    (matrices through :func:`fdsc.paper.shared.prose.matrix_text`).

    Parameters
    ----------
    search : SearchResult

    Returns
    -------
    list of dict
        ``quantity``, ``value``; empty if no case diverges.
    """
    small = smallest_case(search)
    if not small:
        return []
    names = {"A_0": "A₀", "A_1": "A₁", "B": "B", "C": "C", "Q_0": "Q₀", "Q_1": "Q₁", "x0": "initial state"}
    rows = [{"quantity": v, "value": matrix_text(small[k])} for k, v in names.items()]
    rows += [{"quantity": f"eigenvalues of {names[k]}", "value": _eigenvalues_text(small[k])}
             for k in ("A_0", "A_1")]
    source = {"design": "paper Remark 4", "random": "random, Theorem 1's LMIs feasible"}
    rows.append({"quantity": "Q's from", "value": source[small["q_source"]]})
    return rows
