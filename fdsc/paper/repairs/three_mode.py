"""Chapter 'three_modes': FDSC with K_f1, K_f2 and K_f3 (Theorem 1 with I = 3), a middle-frequency
score that works for real signals, and a comparison with the two-mode FDSC and the fixed gains on
disturbances with middle-frequency content.

The printed MF score ``[ẋ; x]ᵀ(Re Ψ_MF ⊗ Q)[ẋ; x] = −ẋᵀQẋ − ϖ₁ϖ₂xᵀQx`` is negative at every
instant; the second-order score of :mod:`fdsc.scores` has the weight ``−(ω² − ϖ₁²)(ω² − ϖ₂²)``,
positive exactly inside Ω_2, and needs ẍ. Theorem 1's LMIs for three modes are those of
:mod:`fdsc.three_mode`.
"""

from dataclasses import dataclass

import numpy as np

from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.data import (
    STATIONARY_DT,
    aircraft,
    hf_disturbance,
    lf_disturbance,
    paper_bands,
    paper_fdsc,
    paper_gains,
    paper_modes,
)
from fdsc.paper.shared.prose import num, pct
from fdsc.paper.shared.results import RecordPart, entry
from fdsc.scores import frequency_weight, law_weight, score_matrix
from fdsc.signals import Piecewise, Sinusoids
from fdsc.simulate import simulate, time_grid
from fdsc.stream import Case, simulate_batch
from fdsc.three_mode import ScoreCertificate, certify_scores, design_scores

__all__ = [
    "record_part",
    "THREE_GAINS",
    "MF_TONES",
    "three_modes",
    "three_bands",
    "ScoreWeights",
    "score_weights",
    "three_mode_certificates",
    "ThreeModeCertificates",
    "comparison_disturbances",
    "ComparisonTable",
    "comparison",
    "display_name",
    "XddotCost",
    "xddot_cost",
    "law_variants",
]

#: The gains of the three modes, in the order of the bands Ω_1 (LF), Ω_2 (MF), Ω_3 (HF).
THREE_GAINS = ("K_f1", "K_f2", "K_f3")
#: Middle-frequency test tones (rad/s), inside Ω_2 = [1, 10].
MF_TONES = (2.0, 4.0, 6.0)
#: γ_tol of the Remark 4 design (as the two-mode design of :func:`fdsc.paper.shared.data.our_q`).
GAMMA_TOL = 10.0


def three_modes() -> list:
    """The closed loops with K_f1, K_f2, K_f3 (paper Sec. IV gains).

    Returns
    -------
    list of LTISystem
    """
    plant, gains = aircraft(), paper_gains()
    return [plant.closed_loop(gains[k]) for k in THREE_GAINS]


def three_bands() -> list:
    """Ω_1, Ω_2, Ω_3 (paper eq. (55)): LF ϖ_l = 1, MF [1, 10], HF ϖ_h = 10.

    Returns
    -------
    list of Band
    """
    b = paper_bands()
    return [b["LF"], b["MF"], b["HF"]]


def law_variants() -> dict:
    """The three-mode laws compared, as ``name → (law_weights, description)``.

    * ``"FDSC-3 (2nd order, Q = I)"``: every score second-order, product form (instantaneously
      exact for a tone), Q_k = I (the law is invariant to a common scale of the Q's);
    * ``"FDSC-3 (printed scores, Q = I)"``: every score as printed (``Re Ψ ⊗ Q`` on ``[ẋ; x]``),
      Q_k = I: the MF score is negative at every instant;
    * ``"FDSC-3 (Remark 4 Q's)"``: LF and HF printed, MF second-order, the Q's of the Remark 4 design
      (:func:`three_mode_certificates`).

    Returns
    -------
    dict
    """
    bands, eye = three_bands(), np.eye(2)
    design = three_mode_certificates().design
    mixed = [1, 2, 1]
    return {
        "FDSC-3 (2nd order, Q = I)": ([law_weight(b, eye, order=2) for b in bands],
                                      "all scores second-order (product form), Q = I"),
        "FDSC-3 (printed scores, Q = I)": ([law_weight(b, eye) for b in bands],
                                           "printed scores Re Psi (x) Q, Q = I"),
        "FDSC-3 (Remark 4 Q's)": ([law_weight(b, q, order=o) for b, q, o in
                                   zip(bands, design.Q, mixed, strict=True)],
                                  "LF, HF printed, MF second-order; Q's of the Remark 4 design"),
    }


@dataclass(frozen=True)
class ScoreWeights:
    """The scores' frequency weights w(ω) (average score over a tone / avg xᵀQx).

    Parameters
    ----------
    omega : (K,) ndarray
        Frequencies in rad/s.
    printed : dict of str to (K,) ndarray
        Weights of the printed scores (``Re Ψ``) for "LF", "MF", "HF".
    second : dict of str to (K,) ndarray
        Weights of the second-order scores for "LF", "MF", "HF".
    """

    omega: np.ndarray
    printed: dict
    second: dict

    @property
    def printed_mf_max(self) -> float:
        """Largest weight of the printed MF score over the grid (< 0)."""
        return float(self.printed["MF"].max())

    @property
    def mf_positive_range(self) -> tuple:
        """Smallest and largest grid frequency where the second-order MF weight is positive."""
        pos = self.omega[self.second["MF"] > 0]
        return float(pos.min()), float(pos.max())

    def prose(self) -> dict:
        """The numbers the chapter quotes, as text (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        dict of str
            ``printed_mf_max`` (the printed MF score's largest weight), ``mf_lo`` and ``mf_hi``
            (where the second-order MF weight is positive on the grid, rad/s).
        """
        lo, hi = self.mf_positive_range
        return {"printed_mf_max": num(self.printed_mf_max), "mf_lo": num(lo), "mf_hi": num(hi)}


def score_weights(omega=None) -> ScoreWeights:
    """Frequency weights of the printed and the second-order scores on Ω_1, Ω_2, Ω_3.

    Parameters
    ----------
    omega : (K,) array_like, optional
        Frequencies in rad/s (default 2001 log-spaced points in [0.01, 1000]).

    Returns
    -------
    ScoreWeights

    Examples
    --------
    >>> sw = score_weights([0.5, 0.99, 1.01, 5.0, 9.99, 10.01])
    >>> sw.printed_mf_max < 0, sw.mf_positive_range
    (True, (1.01, 9.99))
    """
    omega = np.logspace(-2, 3, 2001) if omega is None else np.asarray(omega, dtype=float)
    bands = dict(zip(("LF", "MF", "HF"), three_bands(), strict=True))
    return ScoreWeights(omega, {k: frequency_weight(b, omega) for k, b in bands.items()},
                        {k: frequency_weight(b, omega, order=2) for k, b in bands.items()})


@dataclass(frozen=True)
class ThreeModeCertificates:
    """The least γ's for which the LMIs (T1-1'), (T1-2') of :mod:`fdsc.three_mode` (Theorem 1 for
    three modes) are feasible, for the three-mode laws.

    Parameters
    ----------
    design : ScoreCertificate
        Remark 4 design: LF and HF scores printed, MF second-order, in-band mode K_f2,
        γ_j = γ_tol, η_k ≤ 1, objective γ_2² + ϖ_2²η_2².
    equal_q : ScoreCertificate
        The LMIs' solution for the second-order law with Q_k = I.
    equal_q_scaled : ScoreCertificate
        The same law with Q_k = 10⁻⁴ I (the law is the same; the feasible γ's are not).
    mf_peak : float
        Peak of σ_max of the K_f2 loop over Ω_2 (Lemma 1 bound of the mode alone).
    """

    design: ScoreCertificate
    equal_q: ScoreCertificate
    equal_q_scaled: ScoreCertificate
    mf_peak: float

    def prose(self) -> dict:
        """The numbers the chapter quotes, as text (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        dict of str
            The Remark 4 design: ``gamma_tol`` (γ of the other modes), ``design_g2`` and
            ``design_eta2`` (γ₂, η₂ of the MF mode), ``design_q2`` (largest eigenvalue of its
            Q₂); ``mf_peak`` (K_f2's peak on Ω₂); the second-order law with Q_k = I:
            ``eq_g1``, ``eq_g2``, ``eq_g3``, and with Q_k = 10⁻⁴ I: ``eqs_g2``, ``eqs_g3``.
        """
        d, e, es = self.design, self.equal_q, self.equal_q_scaled
        return {"gamma_tol": num(float(d.gammas[0]), 2), "design_g2": num(float(d.gammas[1])),
                "design_eta2": num(float(d.etas[1])),
                "design_q2": num(float(np.linalg.eigvalsh(d.Q[1]).max())),
                "mf_peak": num(self.mf_peak),
                **{f"eq_g{k + 1}": num(float(g)) for k, g in enumerate(e.gammas)},
                "eqs_g2": num(float(es.gammas[1])), "eqs_g3": num(float(es.gammas[2]))}


@cached
def three_mode_certificates() -> ThreeModeCertificates:
    """Solve Theorem 1's LMIs for the three-mode laws on the aircraft (paper Sec. IV gains).

    Returns
    -------
    ThreeModeCertificates

    Notes
    -----
    Theorem 1 (paper eqs. (33), (34)) with I = 3 and the law's scores on ``[ẍ; ẋ; x]``; ḋ is a
    second input with gain η. The design follows paper Remark 4 (paper eq. (53)).
    """
    from fdsc.frequency import band_peak

    modes, bands = three_modes(), three_bands()
    mixed = [score_matrix(bands[0]), score_matrix(bands[1], order=2), score_matrix(bands[2])]
    w2 = bands[1].upper ** 2
    design = design_scores(modes, mixed, 1, rate_weight=w2, gamma_tol=GAMMA_TOL)
    second = [score_matrix(b, order=2) for b in bands]
    equal = certify_scores(modes, second, [np.eye(2)] * 3, rate_weight=w2)
    scaled = certify_scores(modes, second, [1e-4 * np.eye(2)] * 3, rate_weight=w2)
    return ThreeModeCertificates(design, equal, scaled, band_peak(modes[1], bands[1]).gamma)


def comparison_disturbances(horizon: float) -> dict:
    """The disturbances of the comparison, by name.

    MF tones at :data:`MF_TONES`; the paper's LF and HF disturbances (paper eqs. (56), (57));
    LF + MF + HF (the three MF tones added to both); and a piecewise LF → MF → HF sequence, each part
    a third of the horizon.

    Parameters
    ----------
    horizon : float
        Run length in s (a multiple of 3 ms so that the piecewise breaks lie on the grid).

    Returns
    -------
    dict of str to Sinusoids or Piecewise
    """
    mf = Sinusoids([1.0] * len(MF_TONES), list(MF_TONES))
    out = {f"MF tone {w:g} rad/s": Sinusoids([1.0], [w]) for w in MF_TONES}
    out["LF (paper eq. (56))"] = lf_disturbance()
    out["HF (paper eq. (57))"] = hf_disturbance()
    out["LF + MF + HF"] = lf_disturbance() + mf + hf_disturbance()
    third = horizon / 3
    out["LF -> MF -> HF"] = Piecewise([0.0, third, 2 * third, horizon],
                                      (lf_disturbance(), mf, hf_disturbance()))
    return out


@dataclass(frozen=True)
class ComparisonTable:
    """Energy ratios ∫zᵀz/∫d², switch counts and time shares of every controller on every
    disturbance.

    Parameters
    ----------
    horizon, dt : float
        Run length and step in s.
    disturbances : tuple of str
        Row names.
    controllers : tuple of str
        Column names.
    ratio : (D, C) ndarray
        ∫zᵀz / ∫d² over the run.
    switches : (D, C) int ndarray
        Number of switches.
    time_share : (D, C, 3) ndarray
        Time share of mode 1, 2, 3 (for the two-mode FDSC: LF, —, HF; fixed gains: 1 in their
        own slot).
    """

    horizon: float
    dt: float
    disturbances: tuple
    controllers: tuple
    ratio: np.ndarray
    switches: np.ndarray
    time_share: np.ndarray

    def value(self, disturbance: str, controller: str) -> float:
        """The energy ratio of one run.

        Parameters
        ----------
        disturbance : str
            Row name (one of :attr:`disturbances`).
        controller : str
            Column name (one of :attr:`controllers`).

        Returns
        -------
        float
        """
        return float(self.ratio[self.disturbances.index(disturbance),
                                self.controllers.index(controller)])

    def rows(self) -> list:
        """One row per disturbance: the energy ratio of every controller.

        Returns
        -------
        list of dict
        """
        return [{"disturbance": d, **{c: float(self.ratio[k, j])
                                      for j, c in enumerate(self.controllers)}}
                for k, d in enumerate(self.disturbances)]

    def table(self) -> list:
        """One row per controller (reader-facing name, :func:`display_name`), the energy ratio on
        every disturbance as text (:mod:`fdsc.paper.shared.prose`), for
        :func:`fdsc.paper.shared.report.html_table`.

        Returns
        -------
        list of dict
            Keys ``controller`` and the names of :attr:`disturbances`.
        """
        return [{"controller": display_name(c),
                 **{d: num(float(self.ratio[k, j])) for k, d in enumerate(self.disturbances)}}
                for j, c in enumerate(self.controllers)]

    def prose(self) -> dict:
        """The numbers the chapter quotes, as text (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        dict of str
            ``horizon`` (s) and ``dt_ms``; on the MF tones: ``mf3_max`` (worst ratio of the
            second-order three-mode law), ``mf2_ours_min``, ``mf2_paper_min`` (best of the
            two-mode FDSC with our and the printed Q's), ``mfpass`` (worst of PassC-MF); the
            printed scores' largest MF time share ``printed_mf_share``, the Remark 4 law's
            smallest HF time share ``r4_hf_share``; the ratios of the second-order three-mode
            law (``*_3``) and of the two-mode FDSC with our Q's (``*_2``) on the LF (``lf``),
            HF (``hf``), LF + MF + HF (``mix``) and piecewise (``pw``) disturbances, PassC-HF on
            HF (``hf_pass``) and PassC-LF on LF + MF + HF (``mix_lf``).
        """
        three, three_p = "FDSC-3 (2nd order, Q = I)", "FDSC-3 (printed scores, Q = I)"
        mf = [d for d in self.disturbances if d.startswith("MF tone")]
        k3 = self.controllers.index(three_p)
        kq = self.controllers.index("FDSC-3 (Remark 4 Q's)")
        out = {"horizon": num(self.horizon, 2), "dt_ms": num(self.dt * 1e3, 2),
               "mf3_max": num(max(self.value(d, three) for d in mf)),
               "mf2_ours_min": num(min(self.value(d, "FDSC-2 (our Q's)") for d in mf)),
               "mf2_paper_min": num(min(self.value(d, "FDSC-2 (paper Q's)") for d in mf)),
               "mfpass": num(max(self.value(d, "PassC-MF") for d in mf)),
               "printed_mf_share": pct(float(self.time_share[:, k3, 1].max()), 1),
               "r4_hf_share": pct(float(self.time_share[:, kq, 2].min()), 1),
               "hf_pass": num(self.value("HF (paper eq. (57))", "PassC-HF")),
               "mix_lf": num(self.value("LF + MF + HF", "PassC-LF"))}
        for name, key in (("LF (paper eq. (56))", "lf"), ("HF (paper eq. (57))", "hf"),
                          ("LF + MF + HF", "mix"), ("LF -> MF -> HF", "pw")):
            out[f"{key}_3"] = num(self.value(name, three))
            out[f"{key}_2"] = num(self.value(name, "FDSC-2 (our Q's)"))
        return out

    def best(self, disturbance: str) -> str:
        """The controller with the smallest ratio on one disturbance.

        Parameters
        ----------
        disturbance : str
            Row name (one of :attr:`disturbances`).

        Returns
        -------
        str
        """
        return self.controllers[int(np.argmin(self.ratio[self.disturbances.index(disturbance)]))]


def display_name(name: str) -> str:
    """The reader-facing name of a controller or disturbance of :func:`comparison`.

    Parameters
    ----------
    name : str

    Returns
    -------
    str

    Examples
    --------
    >>> display_name("FDSC-2 (paper Q's)"), display_name("LF -> MF -> HF")
    ('FDSC-2 (printed Q)', 'LF → MF → HF')
    """
    return (name.replace("paper Q's", "printed Q").replace("our Q's", "our Q")
            .replace("Remark 4 Q's", "Remark 4 Q").replace("->", "→"))


#: Fixed gains: name → (gain, slot of its band in the time-share array).
_FIXED = {"PassC-EF": ("K_e", None), "PassC-LF": ("K_f1", 0), "PassC-MF": ("K_f2", 1),
          "PassC-HF": ("K_f3", 2)}


@cached
def comparison(horizon: float = 150.0, dt: float = STATIONARY_DT) -> ComparisonTable:
    """Run every controller on every disturbance of :func:`comparison_disturbances`.

    Controllers: the three-mode laws of :func:`law_variants`, the two-mode FDSC with the paper's and
    with our Q's (:func:`fdsc.paper.shared.data.paper_fdsc`), and PassC-EF/LF/MF/HF. All from rest, with
    the measured ẋ and ẍ (the mode active just before each sample).

    Parameters
    ----------
    horizon, dt : float, optional
        Run length and step in s.

    Returns
    -------
    ComparisonTable
    """
    dists = comparison_disturbances(horizon)
    plant, gains = aircraft(), paper_gains()
    modes3 = three_modes()
    pm = paper_modes()
    two = {"FDSC-2 (paper Q's)": pm["Q"], "FDSC-2 (our Q's)": list(paper_fdsc().certificate.Q)}
    variants = law_variants()
    controllers = tuple(variants) + tuple(two) + tuple(_FIXED)
    cases = []
    for dname, d in dists.items():
        for name, (W, _) in variants.items():
            cases.append(Case(modes3, d, horizon, dt, law_weights=W, label=(dname, name, "3")))
        for name, Q in two.items():
            cases.append(Case(pm["modes"], d, horizon, dt, law_bands=pm["bands"], law_Q=list(Q),
                              label=(dname, name, "2")))
        for name, (k, _) in _FIXED.items():
            cases.append(Case(plant.closed_loop(gains[k]), d, horizon, dt, label=(dname, name, "1")))
    res = simulate_batch(cases)
    D, C = len(dists), len(controllers)
    ratio = (res.energy / res.input_energy).reshape(D, C)
    switches = res.switches.reshape(D, C)
    share = np.zeros((D * C, 3))
    for k, (case, r) in enumerate(zip(res.cases, res, strict=True)):
        kind, name = case.label[2], case.label[1]
        if kind == "3":
            share[k] = r.time_share
        elif kind == "2":
            share[k, [0, 2]] = r.time_share
        elif _FIXED[name][1] is not None:
            share[k, _FIXED[name][1]] = 1.0
    return ComparisonTable(float(horizon), float(dt), tuple(dists), controllers, ratio, switches,
                           share.reshape(D, C, 3))


@dataclass(frozen=True)
class XddotCost:
    """How the law's decisions change when ẍ is estimated instead of measured.

    Along one run of the second-order three-mode law (exact ẍ = A_σẋ + Bḋ), the law's choice is
    recomputed at every sample with ẍ replaced by the backward difference of ẋ over ``steps``
    samples; ``disagreement[k]`` is the fraction of samples at which the choice differs.

    Parameters
    ----------
    disturbance : str
        Name of the disturbance of the run.
    dt : float
        Step of the run in s.
    steps : tuple of int
        Differencing intervals in samples.
    disagreement : (S,) ndarray
        Fraction of samples with another choice, per interval.
    """

    disturbance: str
    dt: float
    steps: tuple
    disagreement: np.ndarray

    def prose(self) -> dict:
        """The numbers the chapter quotes, as text (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        dict of str
            Per differencing interval ``s`` (samples): ``fd_s`` (share of samples with another
            choice) and ``fd_ms_s`` (the interval in ms).
        """
        out = {}
        for s, v in zip(self.steps, self.disagreement, strict=True):
            out[f"fd_{s}"] = pct(float(v), 1)
            out[f"fd_ms_{s}"] = num(s * self.dt * 1e3, 2)
        return out


@cached
def xddot_cost(horizon: float = 15.0, dt: float = STATIONARY_DT, steps: tuple = (1, 3, 10)) -> XddotCost:
    """The cost of ẍ: decisions of the second-order law with ẍ from a finite difference of ẋ.

    Parameters
    ----------
    horizon, dt : float, optional
        Run length and step in s.
    steps : tuple of int, optional
        Differencing intervals in samples (``ẍ ≈ (ẋ_k − ẋ_{k−s})/(s·dt)``).

    Returns
    -------
    XddotCost
        On the LF + MF + HF disturbance (its fastest tone, 300 rad/s, turns 0.3 rad per ms).
    """
    name = "LF + MF + HF"
    d = comparison_disturbances(horizon)[name]
    modes = three_modes()
    W = np.array(law_variants()["FDSC-3 (2nd order, Q = I)"][0])
    t = time_grid(horizon, dt)
    sim = simulate(modes, d, t, law_weights=list(W))
    A = np.array([m.A for m in modes])
    B = modes[0].B[:, 0]
    xdd = np.einsum("kij,kj->ki", A[sim.sigma], sim.xdot) + np.outer(d.derivative(t), B)

    def choice(xdd_est):
        v = np.hstack([xdd_est, sim.xdot, sim.x])
        return np.argmax(np.einsum("ka,iab,kb->ki", v, W, v), axis=1)

    ref = choice(xdd)
    out = []
    for s in steps:
        est = np.empty_like(xdd)
        est[s:] = (sim.xdot[s:] - sim.xdot[:-s]) / (s * dt)
        est[:s] = xdd[:s]
        out.append(float(np.mean(choice(est)[s:] != ref[s:])))
    return XddotCost(name, float(dt), tuple(int(s) for s in steps), np.array(out))


def record_part() -> RecordPart:
    """Record entry ``three_mode`` (new).

    Returns
    -------
    RecordPart
    """
    sw = score_weights()
    cert = three_mode_certificates()
    table = comparison()
    cost = xddot_cost()
    fdsc3 = "FDSC-3 (2nd order, Q = I)"
    mf_rows = [d for d in table.disturbances if d.startswith("MF tone")]
    rec = {
        "printed_mf_weight_max": sw.printed_mf_max,
        "second_order_mf_positive_range": list(sw.mf_positive_range),
        "design": {"gammas": cert.design.gammas, "etas": cert.design.etas,
                   "Q": cert.design.Q, "status": cert.design.status},
        "mf_peak_K_f2": cert.mf_peak,
        "equal_q_gammas": {"Q=I": cert.equal_q.gammas, "Q=1e-4 I": cert.equal_q_scaled.gammas},
        "energy_ratio": {r["disturbance"]: {k: v for k, v in r.items() if k != "disturbance"}
                         for r in table.rows()},
        "switches": {d: dict(zip(table.controllers, table.switches[k].tolist(), strict=True))
                     for k, d in enumerate(table.disturbances)},
        "xddot_finite_difference_disagreement": dict(zip((f"{s} samples" for s in cost.steps),
                                                         cost.disagreement.tolist(), strict=True)),
    }
    worst3 = max(table.value(d, fdsc3) for d in mf_rows)
    best2 = min(min(table.value(d, "FDSC-2 (our Q's)"), table.value(d, "FDSC-2 (paper Q's)"))
                for d in mf_rows)
    note = (
        "The printed MF score sees only Re Ψ for real signals and is negative at every instant "
        f"(largest frequency weight {num(sw.printed_mf_max)}); a second-order score on "
        "[ẍ; ẋ; x] has the weight −(ω² − ϖ₁²)(ω² − ϖ₂²), positive exactly inside "
        f"Ω₂ = [{num(three_bands()[1].lower, 1)}, {num(three_bands()[1].upper, 1)}] rad/s, at the cost "
        "of measuring or estimating ẍ. With all three scores second-order and Q = I the three-mode "
        f"FDSC reaches energy ratios up to {num(worst3)} on MF tones where the two-mode FDSC "
        f"reaches at best {num(best2)}. Theorem 1's LMIs extended to three modes are feasible "
        f"down to γ_MF = {num(float(cert.design.gammas[1]), 4)} with the Remark 4 design (K_f2's "
        "MF peak " f"{num(cert.mf_peak, 4)}), but its law sits in the HF mode most of the time; "
        "with Q = I they are feasible only for loose γ's ("
        + "; ".join(f"γ_{m} = {num(float(g))}" for m, g in zip(("LF", "MF", "HF"), cert.equal_q.gammas,
                                                               strict=True)) + ").")
    return RecordPart((entry("three_mode", "Theorem 1 with I = 3 (K_f1, K_f2, K_f3), Sec. III-IV "
                             "(not in the paper)", None, rec, "new", note,
                             horizon=table.horizon, dt=table.dt),))
