"""An example for the "does FDSC pay?" chapters: a plant, its fixed gains and its FDSC designs,
run side by side through the library's public API only (as a user with another plant would).

The aircraft of the paper (:func:`fdsc.paper.reproduced.paper_cases.aircraft_example`) and the generic
example (:func:`fdsc.paper.pays.generic_example.generic_example`) are both :class:`Example`; the
baselines, the sweeps and the Monte-Carlo study take any :class:`Example`.
"""

from dataclasses import dataclass

import numpy as np

import fdsc

__all__ = ["OPEN_LOOP", "TIE_RTOL", "beats", "Example", "Comparison"]

#: Name of the open loop (K = 0) among an example's fixed gains.
OPEN_LOOP = "open loop"

#: Energies within this relative distance are a tie, not a win: a switched controller that runs
#: one mode throughout has that fixed gain's energy up to rounding, which differs between machines.
TIE_RTOL = 1e-6


def beats(ratio):
    """Where an energy ratio (controller over reference) is a win: below 1 by more than a tie.

    Parameters
    ----------
    ratio : float or array_like

    Returns
    -------
    bool or ndarray of bool

    Examples
    --------
    >>> beats([0.5, 1.0 - 1e-9, 1.2]).tolist()
    [True, False, False]
    """
    return np.asarray(ratio) < 1.0 - TIE_RTOL


@dataclass(frozen=True)
class Example:
    """A plant with its fixed state-feedback gains and FDSC designs.

    Parameters
    ----------
    name : str
        Short name ("aircraft", "generic").
    plant : fdsc.Plant
        The open-loop plant (one disturbance input).
    bands : dict
        ``{"LF": Band, "HF": Band}``: the two ranges of the FDSC modes.
    gains : dict
        ``{controller name: (m_u, n) ndarray}``: the fixed gains, the open loop (zeros) first.
    designs : dict
        ``{controller name: (FDSC, SwitchRule)}``: the switched controllers and their laws.
    lf_tones, hf_tones : tuple of float
        ``(ω_min, ω_max)`` in rad/s: where random LF and HF tones are drawn (inside the bands).
    horizon, dt : float
        Run length and step (s) of the example's runs.

    Raises
    ------
    ValueError
        If the bands are not ``{"LF", "HF"}``, a tone range is empty or outside its band, or a
        name repeats between ``gains`` and ``designs``.
    """

    name: str
    plant: fdsc.Plant
    bands: dict
    gains: dict
    designs: dict
    lf_tones: tuple
    hf_tones: tuple
    horizon: float
    dt: float

    def __post_init__(self):
        if set(self.bands) != {"LF", "HF"}:
            raise ValueError(f"bands must be {{'LF': Band, 'HF': Band}}, but found keys {sorted(self.bands)}")
        for key, (lo, hi) in (("lf_tones", self.lf_tones), ("hf_tones", self.hf_tones)):
            band = self.bands[key[:2].upper()]
            if not 0 < lo < hi or not (band.contains(lo) and band.contains(hi)):
                raise ValueError(f"{key} must be 0 < ω_min < ω_max inside {band.label}, but found "
                                 f"({lo}, {hi})")
        both = set(self.gains) & set(self.designs)
        if both:
            raise ValueError(f"controller names repeat between gains and designs: {sorted(both)}")

    @property
    def names(self) -> tuple:
        """Every controller: the fixed gains, then the switched designs."""
        return tuple(self.gains) + tuple(self.designs)

    @property
    def fixed_names(self) -> tuple:
        """The fixed gains (open loop included)."""
        return tuple(self.gains)

    def closed_loop(self, name: str) -> fdsc.LTISystem:
        """The closed loop of a fixed gain.

        Parameters
        ----------
        name : str
            One of :attr:`fixed_names`.

        Returns
        -------
        fdsc.LTISystem
        """
        return self.plant.closed_loop(self.gains[name])

    def cases(self, d, horizon: float | None = None, dt: float | None = None, *, label=None,
              names=None) -> list:
        """One :class:`fdsc.Case` per controller for the disturbance ``d``, from rest.

        Parameters
        ----------
        d : Sinusoids, Piecewise or Sampled
            The disturbance.
        horizon, dt : float, optional
            Run length and step (default the example's).
        label : object, optional
            Stored as ``(name, label)`` in each case.
        names : sequence of str, optional
            A subset of :attr:`names` (default all).

        Returns
        -------
        list of fdsc.Case
        """
        horizon = self.horizon if horizon is None else horizon
        dt = self.dt if dt is None else dt
        out = []
        for name in self.names if names is None else names:
            if name in self.gains:
                out.append(fdsc.Case(self.closed_loop(name), d, horizon, dt, label=(name, label)))
            elif name in self.designs:
                ctrl, rule = self.designs[name]
                out.append(ctrl.case(d, horizon, dt, rule=rule, label=(name, label)))
            else:
                raise ValueError(f"names must be controllers of the example {self.names}, but found {name!r}")
        return out

    def segment_ideal(self, d: fdsc.Piecewise, horizon: float, modes: tuple, *,
                      dt: float | None = None) -> float:
        """∫zᵀz of the ideal segment law: on each piece of ``d``, the fixed gain meant for the band
        that dominates it, the state carried over at the breaks (a law that knows the signal).

        Parameters
        ----------
        d : fdsc.Piecewise
            Pieces of sums of tones.
        horizon : float
            Run length (s), a multiple of ``dt``; the breaks must lie on the grid.
        modes : tuple of str
            ``(LF controller, HF controller)``: the fixed gains run where the LF or the HF band
            holds the larger share of a piece's power (:meth:`fdsc.Sinusoids.dominance`); the LF
            controller where ``d`` is zero (before its first break, after its last).
        dt : float, optional
            Step (default the example's).

        Returns
        -------
        float
            Its energy; ``inf`` if a segment diverged.

        Raises
        ------
        TypeError
            If ``d`` is not a :class:`fdsc.Piecewise`.
        ValueError
            If a mode is not one of the example's fixed gains, or a break is not on the grid.
        """
        if not isinstance(d, fdsc.Piecewise):
            raise TypeError(f"d must be an fdsc.Piecewise, but found {type(d).__name__}")
        for m in modes:
            if m not in self.gains:
                raise ValueError(f"modes must name fixed gains of the example {self.fixed_names}, "
                                 f"but found {m!r}")
        dt = self.dt if dt is None else dt
        zero = fdsc.Sinusoids([0.0], [1.0])
        pieces = [(0.0, d.breaks[0], zero)] + [(d.breaks[k], d.breaks[k + 1], p)
                                                for k, p in enumerate(d.parts)]
        pieces.append((d.breaks[-1], horizon, zero))
        x, total = np.zeros(self.plant.A.shape[0]), 0.0
        for t0, t1, part in pieces:
            t0, t1 = min(t0, horizon), min(t1, horizon)
            if t1 <= t0:
                continue
            steps = (t1 - t0) / dt
            if abs(steps - round(steps)) > 1e-9 * steps:
                raise ValueError(f"the piece [{t0:g}, {t1:g}) s must begin and end on the grid of "
                                 f"dt = {dt:g} s")
            silent = not np.any(part.amplitudes)
            lf_wins = silent or part.dominance(self.bands["LF"]) >= part.dominance(self.bands["HF"])
            shifted = fdsc.Sinusoids(part.amplitudes, part.frequencies, part.phases + part.frequencies * t0)
            loop = self.closed_loop(modes[0] if lf_wins else modes[1])
            r = fdsc.simulate_stream(loop, shifted, t1 - t0, dt, x0=x)
            if r.diverged_at is not None:
                return float("inf")
            total += r.energy
            x = r.x_final
        return float(total)

    def energies_of(self, controller, disturbances, horizons=None, *, dt: float | None = None) -> np.ndarray:
        """∫zᵀz of one more fixed controller (a gain or an :class:`fdsc.Controller`) under every
        disturbance, from rest, by the same simulator and step as :meth:`compare`.

        Parameters
        ----------
        controller : (m_u, n) array_like or fdsc.Controller
        disturbances : sequence of Sinusoids, Piecewise or Sampled
        horizons : sequence of float, optional
            Default the example's horizon for all.
        dt : float, optional
            Default the example's.

        Returns
        -------
        ndarray
        """
        loop = self.plant.closed_loop(controller)
        horizons = [self.horizon] * len(disturbances) if horizons is None else list(horizons)
        dt = self.dt if dt is None else dt
        cases = [fdsc.Case(loop, d, h, dt) for d, h in zip(disturbances, horizons, strict=True)]
        return fdsc.simulate_batch(cases).energy.copy()

    def compare(self, disturbances, horizons=None, *, dt: float | None = None,
                names=None, executor=None) -> "Comparison":
        """Every controller under every disturbance, in one :func:`fdsc.simulate_batch` call.

        Parameters
        ----------
        disturbances : sequence of Sinusoids, Piecewise or Sampled
            One disturbance per point.
        horizons : sequence of float, optional
            Run length per point (default the example's horizon for all).
        dt : float, optional
            Step (default the example's).
        names : sequence of str, optional
            Controllers (default all).
        executor : concurrent.futures.Executor or dask.distributed.Client, optional
            Run the cases there instead of on this process's threads (:func:`fdsc.simulate_batch`;
            the numbers are the same bit for bit).

        Returns
        -------
        Comparison
        """
        names = self.names if names is None else tuple(names)
        horizons = [self.horizon] * len(disturbances) if horizons is None else list(horizons)
        if len(horizons) != len(disturbances):
            raise ValueError(f"horizons must have one entry per disturbance ({len(disturbances)}), "
                             f"but found {len(horizons)}")
        cases = []
        for i, (d, h) in enumerate(zip(disturbances, horizons, strict=True)):
            cases += self.cases(d, h, dt, label=i, names=names)
        batch = fdsc.simulate_batch(cases, executor=executor)
        k = len(names)
        return Comparison(names, {n: batch.energy[j::k].copy() for j, n in enumerate(names)},
                          batch.input_energy[::k].copy(),
                          {n: batch.diverged[j::k].copy() for j, n in enumerate(names)},
                          {n: batch.switches[j::k].copy() for j, n in enumerate(names) if n in self.designs})


@dataclass(frozen=True)
class Comparison:
    """Energies of every controller at every point (see :meth:`Example.compare`).

    Parameters
    ----------
    names : tuple of str
        Controllers, in order.
    energy : dict
        ``{name: (m,) ndarray}``: ∫zᵀz over each run (``inf`` where the run diverged).
    input_energy : (m,) ndarray
        ∫d² over each run.
    diverged : dict
        ``{name: (m,) bool ndarray}``.
    switches : dict
        ``{switched controller: (m,) int ndarray}``.
    """

    names: tuple
    energy: dict
    input_energy: np.ndarray
    diverged: dict
    switches: dict

    def ratio(self) -> dict:
        """``{name: (m,) ndarray}``: ∫zᵀz / ∫d², the energy ratio of each run."""
        return {n: self.energy[n] / self.input_energy for n in self.names}

    def best(self, among) -> tuple:
        """The controller of least energy among ``among`` at each point, and that energy.

        Parameters
        ----------
        among : sequence of str
            The controllers compared.

        Returns
        -------
        names : (m,) ndarray of str
        energy : (m,) ndarray
        """
        among = tuple(among)
        stack = np.array([self.energy[n] for n in among])
        k = np.argmin(stack, axis=0)
        return np.array(among)[k], stack[k, np.arange(stack.shape[1])]
