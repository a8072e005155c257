"""Chapter 'frequency_selective': Sec. III, FD-EEF/FD-EPF, Proposition 1 on random cases, paper
Remark 1, the FD-EPF of the aircraft loops, paper Table I.
"""

from dataclasses import dataclass

import numpy as np

from fdsc._validation import frozen_array
from fdsc.energy import steady_state_power
from fdsc.paper.reproduced.fd_epf import EPFAircraft, EPFSeries, epf_aircraft, epf_time_series
from fdsc.paper.reproduced.proposition1_cases import (
    PROP1_KINDS,
    Prop1Case,
    Prop1Cases,
    Prop1Summary,
    prop1_cases,
    prop1_summary,
)
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.data import hf_disturbance, lf_disturbance, paper_modes
from fdsc.paper.shared.prose import count, num
from fdsc.paper.shared.results import RecordPart, entry
from fdsc.paper.shared.verdict import worst_verdict
from fdsc.signals import Sinusoids
from fdsc.simulate import simulate, time_grid

__all__ = [
    "record_part",
    "PROP1_KINDS",
    "Prop1Case",
    "Prop1Cases",
    "Prop1Summary",
    "prop1_cases",
    "prop1_summary",
    "alpha_mix",
    "REMARK1_ALPHAS",
    "PowerVsAlpha",
    "power_vs_alpha",
    "EPFSeries",
    "epf_time_series",
    "EPFAircraft",
    "epf_aircraft",
    "Table1Check",
    "Table1Trends",
    "table1_trends",
]


def alpha_mix(alpha: float) -> Sinusoids:
    """The paper's LF and HF tones mixed to dominance degree α(Ω_3) = α and unit mean power.

    ``d = √(2α/3) d_h + √(2(1 − α)/3) d_l`` with d_l, d_h the disturbances of paper eqs. (56),
    (57) (three unit tones each, mean power 3/2).

    Parameters
    ----------
    alpha : float
        Dominance degree of the HF range Ω_3, in [0, 1].

    Returns
    -------
    Sinusoids

    Raises
    ------
    ValueError
        If alpha lies outside [0, 1].

    Examples
    --------
    >>> from fdsc.bands import Band
    >>> round(alpha_mix(0.25).dominance(Band.hf(10.0)), 12)
    0.25
    """
    alpha = float(alpha)
    if not 0.0 <= alpha <= 1.0:
        raise ValueError(f"alpha must lie in [0, 1], found {alpha}")
    scale = np.sqrt(2.0 / 3.0)  # three unit tones have mean power 3/2
    return hf_disturbance().scaled(scale * np.sqrt(alpha)) + lf_disturbance().scaled(
        scale * np.sqrt(1.0 - alpha))


#: The dominance degrees of the paper Remark 1 curves: 0 to 1 in steps of 1/40.
REMARK1_ALPHAS = tuple(float(a) for a in np.linspace(0.0, 1.0, 41))


@dataclass(frozen=True)
class PowerVsAlpha:
    """Steady-state average FD-EPF of the law's terms against the dominance degree α(Ω_3).

    Parameters
    ----------
    alpha : (k,) ndarray
        Dominance degrees.
    curves : dict
        ``{label: (k,) ndarray}``: P_a of each (loop, band, Q) against α.
    in_band, out_of_band : dict
        ``{label: (k,) ndarray}``: the in-band and out-of-band parts of P_a.
    crossing : dict
        ``{label: α* or None}``: where P_a changes sign (None: no sign change in [0, 1]).
    """

    alpha: np.ndarray
    curves: dict
    in_band: dict
    out_of_band: dict
    crossing: dict

    def __post_init__(self):
        object.__setattr__(self, "alpha", frozen_array(np.asarray(self.alpha, dtype=float)))
        for name in ("curves", "in_band", "out_of_band"):
            for label, v in getattr(self, name).items():
                if np.shape(v) != self.alpha.shape:
                    raise ValueError(f"{name}[{label!r}] must have shape {self.alpha.shape} (one "
                                     f"value per alpha), but found {np.shape(v)}")

    def prose(self) -> dict:
        """The sign changes the chapter quotes, formatted (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        dict
            ``{"cross_<gain>_<lf|hf>": text}`` for each loop and term (``n/a``: no sign change);
            five digits, enough to tell the K_f3 loop's crossings from 1.
        """
        out = {}
        for label, a in self.crossing.items():
            key = label.split(" loop")[0] + ("_hf" if "Ω_3" in label else "_lf")
            out[f"cross_{key}"] = num(float("nan") if a is None else a, 5 if a and a > 0.99 else 3)
        return out

    def to_record(self) -> RecordPart:
        """Record entry ``remark1_crossings`` (new): the dominance degree where each term of the
        law changes sign on each loop.

        Returns
        -------
        RecordPart
        """
        return RecordPart((entry(
            "remark1_crossings", "Sec. III, paper Remark 1 (nothing printed)", None,
            dict(self.crossing), "new",
            "steady-state average FD-EPF of the law's terms (Omega_1, Q_1) and (Omega_3, Q_2), "
            "paper's Q's, on the K_f1 and K_f3 loops, disturbance mixing the paper's LF and HF "
            "tones at dominance alpha (unit mean power): P_a is affine in alpha and changes sign "
            "at alpha* = P_a(0) / (P_a(0) - P_a(1)) (none if it does not change sign in [0, 1]). The "
            "sign the law sees depends on the active loop, not only on the disturbance's dominance."),))


@cached
def power_vs_alpha(alphas: tuple = REMARK1_ALPHAS) -> PowerVsAlpha:
    """Paper Remark 1: steady-state average FD-EPF of both modes against the dominance degree.

    For each FDSC loop (K_f1, K_f3) and each term of the law ((Ω_1, Q_1), (Ω_3, Q_2)), ``P_a``
    is affine in α (mean powers add), so the sign change lies at ``α* = P_l / (P_l − P_h)`` with
    P_l, P_h the values at α = 0, 1.

    Parameters
    ----------
    alphas : sequence of float, optional
        Dominance degrees α(Ω_3) in [0, 1] (default :data:`REMARK1_ALPHAS`).

    Returns
    -------
    PowerVsAlpha

    Notes
    -----
    P_a is the average FD-EPF of paper eq. (28), evaluated exactly in steady state; the
    disturbance is :func:`alpha_mix`.

    Examples
    --------
    >>> pv = power_vs_alpha((0.0, 1.0))
    >>> sorted(pv.crossing)[0]
    'K_f1 loop, Ω_1, Q_1'
    """
    pm = paper_modes()
    alphas = np.asarray(alphas, dtype=float)
    curves, ins, outs, crossing = {}, {}, {}, {}
    for mname, mode in zip(pm["names"], pm["modes"], strict=True):
        for bname, band, Q in zip(("Ω_1, Q_1", "Ω_3, Q_2"), pm["bands"], pm["Q"], strict=True):
            label = f"{mname} loop, {bname}"
            splits = [steady_state_power(mode, alpha_mix(a), band, Q) for a in alphas]
            curves[label] = np.array([s.total for s in splits])
            ins[label] = np.array([s.in_band for s in splits])
            outs[label] = np.array([s.out_of_band for s in splits])
            p0 = steady_state_power(mode, alpha_mix(0.0), band, Q).total
            p1 = steady_state_power(mode, alpha_mix(1.0), band, Q).total
            crossing[label] = p0 / (p0 - p1) if (p0 - p1) != 0 and 0 <= p0 / (p0 - p1) <= 1 else None
    return PowerVsAlpha(alphas, curves, ins, outs, crossing)


@dataclass(frozen=True)
class Table1Check:
    """One row of paper Table I against the dominance degree α_i.

    Parameters
    ----------
    quantity : str
        The quantity of the row.
    claimed : {"up", "down"}
        The trend the paper claims as α_i grows.
    values : (k,) ndarray
        The quantity at each α_i.
    observed : str
        ``"up"``, ``"down"``, ``"non-decreasing"``, ``"non-increasing"`` or ``"not monotone"``.
    verdict : {"match", "differs"}
        Whether the observed trend is the claimed one.
    """

    quantity: str
    claimed: str
    values: np.ndarray
    observed: str
    verdict: str


def _trend(values):
    diffs = np.diff(values)
    if np.all(diffs > 0):
        return "up"
    if np.all(diffs < 0):
        return "down"
    if np.all(diffs >= 0):
        return "non-decreasing"
    if np.all(diffs <= 0):
        return "non-increasing"
    return "not monotone"


@dataclass(frozen=True)
class Table1Trends:
    """The rows of paper Table I checked against the dominance degree (see :func:`table1_trends`).

    Parameters
    ----------
    alpha : (k,) ndarray
        The dominance degrees α_i.
    checks : tuple of Table1Check
        One per row of the table.
    horizon, dt : float
        Length and step in s of the switched simulations.
    """

    alpha: np.ndarray
    checks: tuple
    horizon: float
    dt: float

    def check(self, quantity: str) -> Table1Check:
        """The check of one row.

        Parameters
        ----------
        quantity : str
            The row's quantity (e.g. ``"β_i"``).

        Returns
        -------
        Table1Check
        """
        for c in self.checks:
            if c.quantity == quantity:
                return c
        raise KeyError(f"quantity must be one of {[c.quantity for c in self.checks]}, but found "
                       f"{quantity!r}")

    @property
    def n_match(self) -> int:
        """Number of rows whose observed trend is the claimed one."""
        return sum(c.verdict == "match" for c in self.checks)

    @property
    def beta_range(self) -> tuple:
        """Smallest and largest time share β_i of the in-band mode over α_i."""
        beta = self.check("β_i").values
        return float(beta.min()), float(beta.max())

    def rows(self) -> list:
        """One row per check: ``quantity, claimed, observed, values`` (text), ``verdict``.

        Returns
        -------
        list of dict
        """
        return [{"quantity": c.quantity, "claimed": c.claimed, "observed": c.observed,
                 "values": ", ".join(num(float(v), 4) for v in c.values), "verdict": c.verdict}
                for c in self.checks]

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``t1_alphas``, ``t1_horizon``, ``t1_match``, ``t1_rows``,
            ``t1_beta_min``, ``t1_beta_max``.
        """
        lo, hi = self.beta_range
        horizon = float(self.horizon)
        return {"t1_alphas": ", ".join(num(float(a), 2) for a in self.alpha),
                "t1_horizon": count(int(horizon)) if horizon.is_integer() else num(horizon),
                "t1_match": count(self.n_match), "t1_rows": count(len(self.checks)),
                "t1_beta_min": num(lo), "t1_beta_max": num(hi)}

    def to_record(self) -> RecordPart:
        """Record entry ``table1_checks``.

        Returns
        -------
        RecordPart
        """
        t1 = {c.quantity: {"claimed": c.claimed, "observed": c.observed, "values": c.values,
                           "verdict": c.verdict} for c in self.checks}
        return RecordPart((entry(
            "table1_checks", "Sec. III, Table I", {c.quantity: c.claimed for c in self.checks},
            t1, worst_verdict([c.verdict for c in self.checks]),
            "mode i = PassC-HF (Omega_3, Q_2), mode j = PassC-LF (Omega_1, Q_1), disturbance "
            "mixing the paper's LF and HF tones at dominance alpha_i; steady-state rows exact, "
            f"time shares from switched simulations of {self.horizon:g} s (paper's Q's).",
            alpha=self.alpha),))


@cached
def table1_trends(alphas: tuple = (0.2, 0.5, 0.8, 0.95, 0.99), *, horizon: float = 100.0,
                  dt: float = 1e-3) -> Table1Trends:
    """The rows of paper Table I checked against the dominance degree α_i of the in-band range Ω_3.

    Mode i is the HF controller K_f3 with (Ω_3, Q_2), mode j the LF controller K_f1 with
    (Ω_1, Q_1); the disturbance is :func:`alpha_mix`. Steady-state rows are exact; the time
    shares come from switched simulations (default law: measured ẋ) over ``horizon``.

    Parameters
    ----------
    alphas : sequence of float, optional
        Increasing dominance degrees in [0, 1].
    horizon, dt : float, optional
        Length and step in s of the switched simulations.

    Returns
    -------
    Table1Trends

    Notes
    -----
    Paper Table I lists how the FD-EPF terms (paper eq. (28)) and the time shares β_i of the
    law (paper eq. (31)) move as α_i grows; a row matches when the observed trend is the
    claimed one (non-strict monotony counts).
    """
    pm = paper_modes()
    (cl_j, cl_i), (band_j, band_i), (Q_j, Q_i) = pm["modes"], pm["bands"], pm["Q"]
    alphas = np.asarray(alphas, dtype=float)
    pin, pout, pa, pj, Ti, Tj = [], [], [], [], [], []
    t = time_grid(horizon, dt)
    for a in alphas:
        d = alpha_mix(a)
        s = steady_state_power(cl_i, d, band_i, Q_i)
        pin.append(abs(s.in_band))
        pout.append(abs(s.out_of_band))
        pa.append(s.total)
        pj.append(steady_state_power(cl_j, d, band_j, Q_j).total)
        sim = simulate(pm["modes"], d, t, law_bands=pm["bands"], law_Q=pm["Q"])
        share = sim.time_share()
        Ti.append(share[1] * horizon)
        Tj.append(share[0] * horizon)
    beta = np.array(Ti) / horizon
    spec = [("|P_a^in(Ω_i, Q_i, A_i, B_i)|", "up", pin), ("|P_a^out(Ω_i, Q_i, A_i, B_i)|", "down", pout),
            ("P_a(Ω_i, Q_i, A_i, B_i)", "up", pa), ("max_j P_a(Ω_j, Q_j, A_j, B_j)", "down", pj),
            ("T_i (time in mode i)", "up", Ti), ("Σ_j T_j", "down", Tj), ("β_i", "up", beta)]
    checks = []
    for name, claim, vals in spec:
        v = np.asarray(vals, dtype=float)
        observed = _trend(v)
        ok = observed == claim or (claim == "up" and observed == "non-decreasing") or (
            claim == "down" and observed == "non-increasing")
        checks.append(Table1Check(name, claim, v, observed, "match" if ok else "differs"))
    return Table1Trends(alphas, tuple(checks), horizon, dt)


def record_part() -> RecordPart:
    """Record entries of the chapter (Sec. III).

    ``prop1_checks``, ``prop1_short_windows`` (new), ``table1_checks``,
    ``remark1_crossings`` (new) and ``epf_aircraft_signs`` (new).

    Returns
    -------
    RecordPart
    """
    return (prop1_cases(144).to_record() + table1_trends().to_record()
            + power_vs_alpha().to_record() + epf_aircraft().to_record())
