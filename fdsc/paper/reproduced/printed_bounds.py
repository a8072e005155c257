"""Appendix 'printed_bounds': the four bounds printed beside the gains of Sec. IV, one verdict
each, and every reading tried.

Sec. IV prints beside each gain K a bound "σ_max(G(jω), K) < b for all ω ∈ Ω". The quantity the
text states is the band peak of σ_max for the printed gain's closed loop over Ω, which Lemma 1
certifies as well (:mod:`fdsc.paper.reproduced.gkyp_lemma`); its verdict against b
(:func:`fdsc.paper.shared.verdict.verdict`) is the bound's one verdict. Every other reading, the
frequency-domain quantities below and the time-domain search of :mod:`fdsc.paper.reproduced.bound_search`,
is picked after the fact as the nearest of many: it is reported with what it would give (a
``match`` at best, never ``close``: :data:`fdsc.paper.shared.verdict.VERDICT_RULES`) and with how many
equal values chance alone would give among that many, but it does not decide the verdict.

The record entries ``bound_f1`` … ``bound_e`` (:func:`printed_bound_entries`) are contributed by
the chapter :mod:`fdsc.paper.reproduced.passive_controllers`, which designs the gains they compare with.
"""

import itertools
from dataclasses import dataclass

import numpy as np

from fdsc.frequency import band_peak, sigma_max
from fdsc.paper.reproduced.bound_search import BoundMatch, output_label, time_domain_bound_search
from fdsc.paper.reproduced.gkyp_lemma import gain_band_table
from fdsc.paper.reproduced.passive_gains import recompute_gains
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.data import aircraft, paper_bands, paper_data, paper_gains
from fdsc.paper.shared.names import GAIN_BANDS, GAIN_ORDER
from fdsc.paper.shared.prose import count, excess, num, pct, times
from fdsc.paper.shared.results import RecordPart, entry, pick
from fdsc.paper.shared.verdict import verdict
from fdsc.plant import LTISystem

__all__ = [
    "BOUND_IDS",
    "PRINTED_DECIMALS",
    "PrintedBound",
    "PrintedBounds",
    "printed_bounds",
    "printed_bound_entries",
]

#: The record entry of each printed bound.
BOUND_IDS = {"K_f1": "bound_f1", "K_f2": "bound_f2", "K_f3": "bound_f3", "K_e": "bound_e"}

#: Decimals of the printed bounds (Sec. IV prints four).
PRINTED_DECIMALS = 4

#: The ranges as the notes name them.
_BAND_WORDS = {"LF": "the LF range Ω_1", "MF": "the MF range Ω_2", "HF": "the HF range Ω_3",
               "EF": "the entire range Ω_e"}

# the readings of the record entries (the first six are those the record's schema requires)
_STATED, _LEMMA1 = ("band peak of the printed gain (the stated quantity)",
                    "Lemma 1's gamma for the printed gain")
_FREQ, _NEAREST, _HITS, _SEARCHED = ("frequency-domain candidates",
                                     "time domain, nearest of the quantities searched",
                                     "time domain, equal to the printed value",
                                     "time domain, quantities searched")


def _and(names):
    if len(names) < 2:
        return names[0] if names else "none"
    return ", ".join(names[:-1]) + " and " + names[-1]


@dataclass(frozen=True)
class PrintedBound:
    """One printed bound, its one verdict and every reading tried (see :func:`printed_bounds`).

    Parameters
    ----------
    gain, band : str
        The printed gain and the band its bound is printed for.
    paper : float
        The printed bound.
    peak : float
        The band peak of σ_max for the printed gain: the quantity the text states.
    omega_peak : float
        Where the peak is attained, in rad/s.
    lemma1 : float
        Lemma 1's γ for the same gain and band (the same quantity, certified).
    candidates : dict
        ``{reading: value}``: the other frequency-domain quantities tried, picked after the
        fact (our recomputed gain's LMI γ and band peak, σ_max at ω = 0, the squared peak,
        the band peak of each output alone).
    crossings : tuple of float
        Frequencies in rad/s where σ_max of the printed gain equals the printed value.
    search : BoundMatch
        The time-domain search for this bound.
    first_crossings : dict
        ``{"<quantity>, <signal>": t}``: first time each running ratio reaches the printed
        value (s), for information only.
    rounding : tuple of float
        ``(least, largest)`` band peak over the gains the printed digits allow: the corners of
        the box of half a unit of the last printed decimal around every entry of the printed
        gain (the peak is smooth in the gain there, so to first order its extremes over the box
        are at corners). Whether the inequality's verdict survives the rounding of the gain.
    decimals : int
        Decimals printed.
    """

    gain: str
    band: str
    paper: float
    peak: float
    omega_peak: float
    lemma1: float
    candidates: dict
    crossings: tuple
    search: BoundMatch
    first_crossings: dict
    rounding: tuple
    decimals: int = PRINTED_DECIMALS

    @property
    def verdict(self) -> str:
        """The bound's one verdict: the stated quantity against the printed value."""
        return verdict(self.paper, self.peak, self.decimals)

    @property
    def holds(self) -> bool:
        """The printed inequality holds for the printed gain (peak below the printed value)."""
        return self.peak < self.paper

    @property
    def holds_within_rounding(self) -> bool:
        """Whether some gain the printed digits allow satisfies the printed inequality."""
        return self.rounding[0] < self.paper

    @property
    def factor(self) -> float:
        """``peak / paper``."""
        return self.peak / self.paper

    @property
    def nearest_candidate(self) -> tuple:
        """``(reading, value)`` of the frequency-domain candidate nearest to the printed value."""
        name = min(self.candidates, key=lambda c: abs(self.candidates[c] - self.paper))
        return name, self.candidates[name]

    def _equal(self, value):
        return verdict(self.paper, value, self.decimals, after_the_fact=True) == "match"

    def readings(self) -> list:
        """Every reading tried, as plain values: the stated quantity, Lemma 1's γ, the
        frequency-domain candidates, then the nearest time-domain quantities and every hit.

        Returns
        -------
        list of dict
            ``reading, domain ("frequency" or "time"), value, equals the printed digits, would
            give`` (its verdict if it were the bound's quantity: a quantity picked after the
            fact gives ``match`` or ``differs``, never ``close``) ``, picked after the fact``.
        """
        def row(reading, domain, value, after):
            return {"reading": reading, "domain": domain, "value": float(value),
                    "equals the printed digits": bool(self._equal(value)),
                    "would give": verdict(self.paper, value, self.decimals, after_the_fact=after),
                    "picked after the fact": after}

        return ([row(_STATED, "frequency", self.peak, False),
                 row(_LEMMA1, "frequency", self.lemma1, False)]
                + [row(k, "frequency", v, True) for k, v in self.candidates.items()]
                + [row(c.describe(value=False), "time", c.value, True) for c in self.search.shown])

    def stated(self) -> str:
        """The stated quantity against the printed value, in words (why the verdict).

        Returns
        -------
        str

        Examples
        --------
        >>> pb = printed_bounds()
        >>> [pb[g].stated() for g in ("K_f2", "K_e")]  # doctest: +NORMALIZE_WHITESPACE
        ['the band peak is within 0.07 % of the printed value but above it, so the printed
         inequality fails for the printed gain, and for every gain its printed digits allow
         (their band peaks are at least 0.40279)',
         'the inequality holds, but the printed value is the band peak ×1.77, so it is not the
         peak the design attains']
        """
        lo = self.rounding[0]
        allowed = (f", and for every gain its printed digits allow (their band peaks are at least "
                   f"{num(lo, 5)})" if not self.holds_within_rounding else
                   f", though a gain its printed digits allow has band peak {num(lo, 5)}"
                   if not self.holds else "")
        if self.verdict in ("match", "close"):
            return (f"the band peak is within {pct(abs(self.peak - self.paper) / self.paper, 2)}"
                    " of the printed value" + (" and below it" if self.holds else
                                                " but above it, so the printed inequality fails "
                                                "for the printed gain" + allowed))
        if self.holds:
            return (f"the inequality holds, but the printed value is the band peak "
                    f"{times(1 / self.factor)}, so it is not the peak the design attains")
        return (f"the band peak is the printed value {times(self.factor)}, so the printed "
                "inequality fails for the printed gain" + allowed)

    def note(self, settings: dict) -> str:
        """The note of the bound's record entry, in reader language.

        Parameters
        ----------
        settings : dict
            What the time-domain search ran (:meth:`fdsc.paper.reproduced.bound_search.
            TimeDomainBoundSearch.settings`).

        Returns
        -------
        str
        """
        s = self.search
        name, value = self.nearest_candidate
        freq_hits = [k for k, v in self.candidates.items() if self._equal(v)]
        text = (f"The paper prints σ_max(G(jω), {self.gain}) < {self.paper} on "
                f"{_BAND_WORDS[self.band]}. For the printed gain the band peak of σ_max, the "
                f"quantity the text states, is {num(self.peak, 4)} (at ω = {num(self.omega_peak)}"
                f" rad/s; Lemma 1 certifies {num(self.lemma1, 4)}): {self.stated()}. "
                f"Verdict: {self.verdict}, by the quantity the text states. ")
        text += (f"Of {count(len(self.candidates))} other frequency-domain readings tried "
                 "afterwards (our recomputed gain, σ_max at ω = 0, the squared peak, each output "
                 "alone), " + (f"{', '.join(freq_hits)} equal the printed digits"
                               if freq_hits else "none equals the printed digits")
                 + f"; nearest: {name}, {num(value, 4)}. ")
        horizons = settings["horizons_s"]
        text += (f"A search over {count(s.n_candidates)} time-domain quantities (L2 and energy "
                 f"ratios from rest and peak gains, under the {count(len(settings['signals']))} "
                 f"test signals of Sec. IV, at horizons of {num(int(horizons[0]))} to "
                 f"{num(int(horizons[-1]))} s and in steady state) ")
        if s.hits:
            first = s.hits[0].describe()
            one = len(s.hit_values) == 1
            text += (f"finds {count(len(s.hits))} equal to the printed digits"
                     + (f", all one number: {first}" if one and len(s.hits) > 1 else f": {first}"
                        if one else ": " + "; ".join(h.describe() for h in s.hits))
                     + f". {count(s.n_within_close)} of the {count(s.n_candidates)} lie within 1 % "
                     f"of the printed value, so by chance alone about {num(s.chance_hits, 2)} of "
                     "them would equal the printed digits: a value found by searching is no "
                     "evidence of how the bound was computed, and it does not decide the verdict.")
        else:
            within = count(s.n_within_close) if s.n_within_close else "none"
            text += (f"finds none equal to the printed digits (nearest: {s.best.describe()}; "
                     f"{within} within 1 %).")
        return text

    def inequality(self) -> dict:
        """The printed inequality and whether it holds for the printed gain (for the record).

        Returns
        -------
        dict
            ``statement`` (in words), ``subject`` (the gain it is printed for), ``quantity``
            (the band peak), ``bound`` (the printed value), ``holds`` (quantity < bound),
            ``quantity_within_rounding`` (least and largest band peak over the gains the printed
            digits allow) and ``holds_within_rounding`` (the least below the bound).

        Examples
        --------
        >>> ineq = printed_bounds()["K_e"].inequality()
        >>> ineq["statement"], ineq["holds"]
        ('σ_max(G(jω), K_e) < 0.7125 for every ω in the entire range Ω_e', True)
        """
        return {"statement": f"σ_max(G(jω), {self.gain}) < {self.paper} for every ω in "
                             f"{_BAND_WORDS[self.band]}", "subject": self.gain,
                "quantity": float(self.peak), "bound": float(self.paper), "holds": bool(self.holds),
                "quantity_within_rounding": [float(v) for v in self.rounding],
                "holds_within_rounding": bool(self.holds_within_rounding)}

    def to_entry(self, settings: dict) -> dict:
        """The record entry of this bound (``bound_f1``, ``bound_f2``, ``bound_f3``, ``bound_e``).

        Parameters
        ----------
        settings : dict
            What the time-domain search ran.

        Returns
        -------
        dict
        """
        s = self.search
        return entry(
            BOUND_IDS[self.gain], f"Sec. IV, the bound printed beside {self.gain}", self.paper,
            self.peak, self.verdict, self.note(settings), inequality=self.inequality(),
            readings={
                _STATED: self.peak, _LEMMA1: self.lemma1, _FREQ: dict(self.candidates),
                _NEAREST: s.best.to_dict(), _HITS: [h.to_dict() for h in s.hits],
                _SEARCHED: int(s.n_candidates),
                "time domain, within 1 % of the printed value": int(s.n_within_close),
                "time domain, hits expected by chance": float(s.chance_hits),
                "time domain, search": settings,
                "time domain, first crossings (s)": dict(self.first_crossings),
                "band peak frequency (rad/s)": self.omega_peak,
                "frequencies where sigma_max equals the printed value (rad/s)": list(self.crossings),
                "every reading": self.readings(),
            })


@dataclass(frozen=True)
class PrintedBounds:
    """The four printed bounds (see :func:`printed_bounds`).

    Parameters
    ----------
    bounds : tuple of PrintedBound
        In the order of :data:`fdsc.paper.shared.names.GAIN_ORDER`.
    settings : dict
        What the time-domain search ran (signals and their runs, horizons, quantities, step).
    """

    bounds: tuple
    settings: dict

    def __getitem__(self, gain: str) -> PrintedBound:
        """The bound printed beside one gain.

        Parameters
        ----------
        gain : str

        Returns
        -------
        PrintedBound
        """
        return pick(self.bounds, "gain", gain)

    def rows(self) -> list:
        """One row per bound, formatted: ``gain, band, printed, peak, lemma1, factor, holds,
        verdict, why``.

        Returns
        -------
        list of dict
        """
        return [{"gain": b.gain, "band": b.band, "printed": f"{b.paper:.{b.decimals}f}",
                 "peak": num(b.peak, 4), "lemma1": num(b.lemma1, 4), "factor": times(b.factor, 5),
                 "holds": "yes" if b.holds else "no", "verdict": b.verdict, "why": b.stated()}
                for b in self.bounds]

    def reading_rows(self, domain: str | None = None) -> list:
        """Every reading of every bound, formatted: ``gain, printed, reading, value, equal,
        would_give, after``.

        Parameters
        ----------
        domain : {"frequency", "time"}, optional
            Only the readings of one domain (default both).

        Returns
        -------
        list of dict
        """
        return [{"gain": b.gain, "printed": f"{b.paper:.{b.decimals}f}", "reading": r["reading"],
                 "value": num(r["value"], 5), "equal": "yes" if r["equals the printed digits"] else "",
                 "would_give": r["would give"], "after": "yes" if r["picked after the fact"] else ""}
                for b in self.bounds for r in b.readings() if domain in (None, r["domain"])]

    def search_rows(self) -> list:
        """One row per bound, formatted: the nearest time-domain quantity, the hits, the
        quantities within 1 % and the hits to expect by chance.

        Returns
        -------
        list of dict
        """
        return [{"gain": b.gain, "printed": f"{b.paper:.{b.decimals}f}",
                 "nearest": b.search.best.describe(value=False),
                 "value": num(b.search.best.value, 5),
                 "diff": num(abs(b.search.best.value - b.paper), 2),
                 "hits": count(len(b.search.hits)), "within": count(b.search.n_within_close),
                 "chance": num(b.search.chance_hits, 2)} for b in self.bounds]

    def crossing_rows(self) -> list:
        """The running ratios that reach a printed bound, formatted: ``gain, ratio, t``.

        Returns
        -------
        list of dict
        """
        return [{"gain": b.gain, "ratio": k, "t": num(t, 4)}
                for b in self.bounds for k, t in b.first_crossings.items()]

    def prose(self) -> dict:
        """The numbers and words the book quotes about the bounds (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        dict
            ``{name: text}``: per gain ``<gain>_printed``, ``_peak``, ``_lemma1``, ``_factor``
            (peak / printed), ``_inverse`` (printed / peak), ``_verdict``, ``_stated``,
            ``_within``, ``_chance``, ``_hits``, ``_omega_peak``, ``_rounding_least`` (the least
            band peak over the gains the printed digits allow); ``n_close``, ``n_differs``,
            ``n_hold``, ``n_fail`` (printed inequalities true and false for the printed gains),
            ``hold_gains``, ``fail_gains``, ``fail_by`` (each failing gain with how far its band
            peak lies above the printed bound),
            ``verdicts`` (all four in one phrase), ``searched``, ``n_signals``, ``n_horizons``,
            ``horizon_first``, ``horizon_last``, ``dt_ms``, ``hit_gains``, ``hit_what``.
        """
        out = {"n_close": count(sum(b.verdict in ("match", "close") for b in self.bounds)),
               "n_differs": count(sum(b.verdict == "differs" for b in self.bounds)),
               "n_hold": count(sum(b.holds for b in self.bounds)),
               "n_fail": count(sum(not b.holds for b in self.bounds)),
               "hold_gains": _and([b.gain for b in self.bounds if b.holds]),
               "fail_gains": _and([b.gain for b in self.bounds if not b.holds]),
               "fail_by": _and([f"{b.gain} {excess(b.peak, b.paper)}" for b in self.bounds
                                if not b.holds]),
               "verdicts": ", ".join(f"{b.gain} ({b.paper}): {b.verdict}" for b in self.bounds),
               "searched": count(self.bounds[0].search.n_candidates),
               "n_signals": count(len(self.settings["signals"])),
               "n_horizons": count(len(self.settings["horizons_s"])),
               "horizon_first": num(int(self.settings["horizons_s"][0])),
               "horizon_last": num(int(self.settings["horizons_s"][-1])),
               "dt_ms": num(self.settings["dt_s"] * 1e3, 1),
               "hit_gains": " and ".join(b.gain for b in self.bounds if b.search.hits) or "none"}
        hits = [b.search.hits[0] for b in self.bounds if b.search.hits]
        kinds = {(h.quantity, h.horizon) for h in hits}
        out["hit_what"] = (f"the {hits[0].quantity} from rest over T = {num(int(hits[0].horizon))} s"
                           if len(kinds) == 1 else "time-domain quantities")
        for b in self.bounds:
            g, s = b.gain, b.search
            out |= {f"{g}_printed": f"{b.paper:.{b.decimals}f}", f"{g}_peak": num(b.peak, 4),
                    f"{g}_lemma1": num(b.lemma1, 4), f"{g}_factor": times(b.factor),
                    f"{g}_inverse": times(1 / b.factor), f"{g}_verdict": b.verdict,
                    f"{g}_stated": b.stated(), f"{g}_within": count(s.n_within_close),
                    f"{g}_chance": num(s.chance_hits, 2), f"{g}_hits": count(len(s.hits)),
                    f"{g}_omega_peak": num(b.omega_peak),
                    f"{g}_rounding_least": num(b.rounding[0], 5),
                    f"{g}_nearest_td": s.best.describe()}
        return out

    def to_record(self) -> RecordPart:
        """Record entries ``bound_f1``, ``bound_f2``, ``bound_f3``, ``bound_e``.

        Returns
        -------
        RecordPart
        """
        return RecordPart(tuple(b.to_entry(self.settings) for b in self.bounds))


def _rounding_range(plant, K, band, decimals=PRINTED_DECIMALS):
    """Least and largest band peak over the corners of the box of gains that print as ``K``."""
    half = 0.5 * 10.0 ** -decimals
    K = np.asarray(K, dtype=float)
    peaks = [band_peak(plant.closed_loop(K + half * np.reshape(signs, K.shape)), band).gamma
             for signs in itertools.product((-1.0, 1.0), repeat=K.size)]
    return float(min(peaks)), float(max(peaks))


@cached
def printed_bounds() -> PrintedBounds:
    """The four printed bounds, each with its one verdict and every reading tried.

    The frequency-domain readings: the band peak of the printed gain (the stated quantity) and
    Lemma 1's γ (:func:`fdsc.paper.reproduced.gkyp_lemma.gain_band_table`); after the fact, the LMI γ and
    the band peak of our recomputed gain (:func:`fdsc.paper.reproduced.passive_controllers.recompute_gains`),
    σ_max at ω = 0, the squared band peak (the γ/γ² slip of Lemma 1) and the band peak of each
    output alone; the frequencies where σ_max of the printed gain equals the printed value. The
    time-domain readings: :func:`fdsc.paper.reproduced.bound_search.time_domain_bound_search`.

    Returns
    -------
    PrintedBounds

    Examples
    --------
    >>> pb = printed_bounds()
    >>> [(b.gain, b.verdict) for b in pb.bounds]
    [('K_f1', 'differs'), ('K_f2', 'close'), ('K_f3', 'differs'), ('K_e', 'differs')]
    """
    plant, printed, bands = aircraft(), paper_gains(), paper_bands()
    ctrl, table, ours = paper_data("controllers"), gain_band_table(), recompute_gains()
    search = time_domain_bound_search()
    out = []
    for gain in GAIN_ORDER:
        kind = GAIN_BANDS[gain]
        band, pair, paper = bands[kind], table.pair(gain, kind), ctrl[gain]["bound"]
        cl = plant.closed_loop(printed[gain])
        cands = {"synthesis LMI bound of our recomputed gain": ours[gain].gamma_lmi,
                 "band peak of our recomputed gain": ours[gain].gamma_sweep,
                 "σ_max at ω = 0": float(sigma_max(cl, [0.0])[0]),
                 "squared band peak (γ² read for γ)": pair.peak**2}
        for k, label in enumerate(plant.names["output_names"]):
            sub = LTISystem(cl.A, cl.B, cl.C[[k]], cl.D[[k]])
            cands[f"band peak of output {output_label(label)} alone"] = band_peak(sub, band).gamma
        w = np.geomspace(1e-4, 1e5, 20001)
        above = sigma_max(cl, w) - paper
        crossings = tuple(w[np.nonzero(np.diff(np.sign(above)))[0]].tolist())
        out.append(PrintedBound(gain, kind, paper, pair.peak, pair.omega_peak, pair.lmi_gamma,
                                {k: float(v) for k, v in cands.items()}, crossings, search[gain],
                                search.readings(gain)["first_crossings_s"],
                                _rounding_range(plant, printed[gain], band)))
    return PrintedBounds(tuple(out), search.settings())


def printed_bound_entries() -> RecordPart:
    """Record entries ``bound_f1`` … ``bound_e``: one verdict per printed bound, every reading.

    Returns
    -------
    RecordPart
    """
    return printed_bounds().to_record()
