"""Chapter 'frequency_selective', continued: the FD-EPF of the aircraft loops.

The instantaneous FD-EPF of both law terms and its running average along the closed loops of
the printed gains (the FDSC modes K_f1 and K_f3 among them), from rest, under the paper's LF and
HF disturbances.
"""

from dataclasses import dataclass

import numpy as np

from fdsc._validation import as_choice
from fdsc.energy import instantaneous_power
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.data import aircraft, paper_disturbance, paper_gains, paper_modes
from fdsc.paper.shared.prose import count, num
from fdsc.paper.shared.results import RecordPart, entry
from fdsc.simulate import envelope, simulate, time_grid

__all__ = ["EPFAircraft", "EPFSeries", "epf_aircraft", "epf_time_series"]


@dataclass(frozen=True)
class EPFSeries:
    """Instantaneous FD-EPF of both law terms along an LTI closed loop (see
    :func:`epf_time_series`).

    Parameters
    ----------
    gain : str
        The printed gain whose closed loop was simulated (K_f1 and K_f3: the FDSC modes).
    disturbance : {"LF", "HF"}
        The paper's disturbance.
    t : (k,) ndarray
        Bin starts in s.
    bin : float
        Bin length in s.
    P_t_lo, P_t_hi : dict
        ``{"LF": (k,), "HF": (k,)}``: min/max of the instantaneous FD-EPF per bin.
    P_a : dict
        ``{"LF": (k,), "HF": (k,)}``: the running average at the bin starts.
    """

    gain: str
    disturbance: str
    t: np.ndarray
    bin: float
    P_t_lo: dict
    P_t_hi: dict
    P_a: dict

    @property
    def final_average(self) -> dict:
        """``{"LF": P_a, "HF": P_a}`` at the end of the run."""
        return {k: float(v[-1]) for k, v in self.P_a.items()}

    @property
    def selective(self) -> bool:
        """The term of the disturbance's own range ends positive and the other term negative."""
        other = "HF" if self.disturbance == "LF" else "LF"
        avg = self.final_average
        return bool(avg[self.disturbance] > 0 > avg[other])


@cached
def epf_time_series(gain: str, disturbance: str, *, horizon: float = 200.0, dt: float = 1e-3,
                    every: int = 20) -> EPFSeries:
    """Instantaneous FD-EPF of both law terms along an LTI closed loop (from rest).

    Parameters
    ----------
    gain : {"K_f1", "K_f2", "K_f3", "K_e"}
        The printed gain whose closed loop is simulated (K_f1 and K_f3 are the FDSC modes).
    disturbance : {"LF", "HF"}
        The paper's LF (paper eq. (56)) or HF (paper eq. (57)) disturbance.
    horizon, dt : float, optional
        Run length and step in s.
    every : int, optional
        Samples per bin of the decimated record.

    Returns
    -------
    EPFSeries

    Notes
    -----
    The instantaneous FD-EPF is paper eq. (29) with the law's (Ω_1, Q_1) and (Ω_3, Q_2); the
    running average is paper eq. (28) over [0, t].
    """
    gains = paper_gains()
    as_choice("gain", gain, tuple(gains))
    pm = paper_modes()
    cl = aircraft().closed_loop(gains[gain])
    d = paper_disturbance(disturbance)
    sim = simulate(cl, d, time_grid(horizon, dt))
    lo, hi, avg = {}, {}, {}
    for kind, band, Q in zip(("LF", "HF"), pm["bands"], pm["Q"], strict=True):
        p = instantaneous_power(sim.x, sim.xdot, band, Q)
        run = np.concatenate([[p[0]], np.cumsum(0.5 * (p[1:] + p[:-1])) * dt / sim.t[1:]])
        # P_t oscillates at up to twice the fastest tone: keep its min/max per bin, not every
        # n-th sample (which would alias); the running average P_a is smooth
        _, lo[kind], hi[kind] = envelope(sim.t, p, every)
        avg[kind] = run[::every]
    return EPFSeries(gain, disturbance, sim.t[::every], every * dt, lo, hi, avg)


#: The (gain, disturbance) pairs of the aircraft FD-EPF figure.
_EPF_PAIRS = (("K_f1", "LF"), ("K_f1", "HF"), ("K_f3", "LF"), ("K_f3", "HF"))


@dataclass(frozen=True)
class EPFAircraft:
    """The FD-EPF of the two FDSC loops under the paper's two disturbances.

    Parameters
    ----------
    series : tuple of EPFSeries
        One per (gain, disturbance) in the order K_f1/LF, K_f1/HF, K_f3/LF, K_f3/HF.
    horizon : float
        Run length in s.
    """

    series: tuple
    horizon: float

    def get(self, gain: str, disturbance: str) -> EPFSeries:
        """The series of one loop under one disturbance.

        Parameters
        ----------
        gain : {"K_f1", "K_f3"}
            The loop.
        disturbance : {"LF", "HF"}
            The disturbance.

        Returns
        -------
        EPFSeries
        """
        for s in self.series:
            if (s.gain, s.disturbance) == (gain, disturbance):
                return s
        raise KeyError(f"no series for gain {gain!r} and disturbance {disturbance!r}")

    def prose(self) -> dict:
        """The numbers the chapter quotes, formatted (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        dict
            ``{name: text}``: ``epf_horizon``, ``epf_n_selective``, ``epf_n_runs`` and the
            running averages at the horizon ``pa_<gain>_<disturbance>_<term>``.
        """
        out = {"epf_horizon": num(float(self.horizon)) if not float(self.horizon).is_integer()
               else count(int(self.horizon)),
               "epf_n_selective": count(sum(s.selective for s in self.series)),
               "epf_n_runs": count(len(self.series))}
        for s in self.series:
            for kind, value in s.final_average.items():
                out[f"pa_{s.gain}_{s.disturbance}_{kind}"] = num(value)
        return out

    def to_record(self) -> RecordPart:
        """Record entry ``epf_aircraft_signs`` (new): the running averages at the horizon and
        whether each run is frequency-selective.

        Returns
        -------
        RecordPart
        """
        rec = {f"{s.gain}, {s.disturbance} disturbance": {**s.final_average, "selective": s.selective}
               for s in self.series}
        n_sel = sum(s.selective for s in self.series)
        return RecordPart((entry(
            "epf_aircraft_signs", "Sec. III, Proposition 1 on the aircraft loops (nothing printed)",
            None, rec, "new",
            f"running average FD-EPF of the law's LF term (Omega_1, Q_1) and HF term (Omega_3, Q_2) "
            f"at t = {self.horizon:g} s, from rest; selective = the term of the disturbance's range "
            f"positive, the other negative: {n_sel} of {len(self.series)} runs."),))


@cached
def epf_aircraft(*, horizon: float = 200.0) -> EPFAircraft:
    """:func:`epf_time_series` for both FDSC loops under both paper disturbances.

    Parameters
    ----------
    horizon : float, optional
        Run length in s.

    Returns
    -------
    EPFAircraft

    Notes
    -----
    Proposition 1 (paper eqs. (21), (22)) predicts the signs of the running averages (paper
    eq. (28)) in steady state.
    """
    return EPFAircraft(tuple(epf_time_series(g, d, horizon=horizon) for g, d in _EPF_PAIRS),
                       float(horizon))
