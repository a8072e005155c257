"""Appendix 'printed_bounds': the four bounds printed beside the gains in Sec. IV, in one place.

Each bound has one verdict (its record entry, :func:`fdsc.paper.passive_controllers.
printed_bound_entries`) and the readings tried: the stated quantity (σ_max over the gain's band),
Lemma 1's γ, the other frequency-domain candidates and a search over time-domain quantities.
"""

from dataclasses import dataclass

from .names import GAIN_BANDS, GAIN_ORDER
from .passive_controllers import printed_bound_entries
from .prose import count, num

__all__ = ["BoundReading", "PrintedBounds", "printed_bounds_appendix"]

_ID = {"K_f1": "bound_f1", "K_f2": "bound_f2", "K_f3": "bound_f3", "K_e": "bound_e"}


@dataclass(frozen=True)
class BoundReading:
    """One printed bound and its readings.

    Parameters
    ----------
    gain, band : str
        The printed gain and the band its bound is stated on.
    printed : float
        The printed bound.
    peak, lemma1 : float
        σ_max over the band for the printed gain (the stated quantity) and Lemma 1's γ.
    verdict : str
        The one verdict of the bound.
    hits : tuple of dict
        Time-domain quantities equal to the printed value to its precision.
    nearest : dict
        The nearest time-domain quantity.
    searched : int
        Time-domain quantities searched per bound.
    """

    gain: str
    band: str
    printed: float
    peak: float
    lemma1: float
    verdict: str
    hits: tuple
    nearest: dict
    searched: int

    def time_domain(self) -> str:
        """The time-domain reading in words."""
        if self.hits:
            return "; ".join(f"{h['quantity']} under {h['signal']}, T = {num(h['horizon_s'])} s"
                             for h in self.hits) + " (equal to the printed digits)"
        return (f"none equal; nearest {self.nearest['quantity']} under {self.nearest['signal']}, "
                f"T = {num(self.nearest['horizon_s'])} s: {num(self.nearest['value'], 5)}")


@dataclass(frozen=True)
class PrintedBounds:
    """The four printed bounds (see :func:`printed_bounds_appendix`).

    Parameters
    ----------
    bounds : tuple of BoundReading
        In the order K_f1, K_f2, K_f3, K_e.
    """

    bounds: tuple

    def rows(self) -> list:
        """Table rows: gain, band, printed, σ_max peak, Lemma 1's γ, verdict, time domain."""
        return [{"gain": b.gain, "band": b.band, "printed": num(b.printed, 4),
                 "peak": num(b.peak, 4), "lemma1": num(b.lemma1, 4), "verdict": b.verdict,
                 "time": b.time_domain()} for b in self.bounds]

    def prose(self) -> dict:
        """The formatted numbers of the appendix's text.

        Returns
        -------
        dict
        """
        by = {b.gain: b for b in self.bounds}
        out = {"n_close": count(sum(b.verdict in ("match", "close") for b in self.bounds)),
               "n_not": count(sum(b.verdict == "not reproducible" for b in self.bounds)),
               "n_hit": count(sum(bool(b.hits) for b in self.bounds)),
               "searched": count(self.bounds[0].searched),
               "hit_gains": " and ".join(b.gain for b in self.bounds if b.hits) or "none",
               "hit_horizons": " and ".join(sorted({num(h["horizon_s"]) for b in self.bounds
                                                    for h in b.hits})) or "none"}
        for g, b in by.items():
            out |= {f"{g}_printed": num(b.printed, 4), f"{g}_peak": num(b.peak, 4),
                    f"{g}_verdict": b.verdict}
        return out


def printed_bounds_appendix() -> PrintedBounds:
    """The four printed bounds with their one verdict and every reading tried.

    Returns
    -------
    PrintedBounds
    """
    entries = {e["id"]: e for e in printed_bound_entries().entries}
    out = []
    for gain in GAIN_ORDER:
        e = entries[_ID[gain]]
        r = e["readings"]
        out.append(BoundReading(
            gain, GAIN_BANDS[gain], float(e["paper"]),
            float(r["band peak of the printed gain (the stated quantity)"]),
            float(r["Lemma 1's gamma for the printed gain"]), e["verdict"],
            tuple(r["time domain, equal to the printed value"]),
            r["time domain, nearest of the quantities searched"],
            int(r["time domain, quantities searched"])))
    return PrintedBounds(tuple(out))
