"""A Monte-Carlo study, not a chapter of the book: does FDSC pay on random disturbances? (The book
answers on a class of disturbances, with equal information and a bound, in Part II; this study,
run from Python, remains as the paper layer's example of a study scaled out on an executor.)
Seeded draws of tones (random
frequencies inside the bands, phases, amplitudes and dominance degree α) and band-limited
coloured noise of prescribed α (through the sampled-input path, first-order hold), every
controller of an example run under each (:meth:`fdsc.paper.shared.examples.Example.compare`), FDSC's
energy against the best comparator of each draw and against the fixed controller chosen in
advance.

"Chosen in advance" is the fixed controller of least mean steady-state energy ratio over a
separate pilot set of draws (another seed), computed in closed form
(:func:`fdsc.steady_state_gain`): what a designer who knows the distribution of the disturbances,
but not the draw, would fix.
"""

from dataclasses import dataclass

import numpy as np

import fdsc
from fdsc._closed_energy import closed_form_energies
from fdsc._validation import as_choice, as_count, as_positive
from fdsc.paper.pays.generic_example import generic_example
from fdsc.paper.reproduced.paper_cases import aircraft_example
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.examples import Example, beats
from fdsc.paper.shared.fixed_choice import fixed_in_advance

__all__ = [
    "SEED",
    "PILOT_SEED",
    "NOISE_SEED",
    "N_DRAWS",
    "N_PILOT",
    "N_TONES",
    "NOISE_ALPHAS",
    "NOISE_REPEATS",
    "QUANTILES",
    "ALPHA_BINS",
    "EXAMPLES",
    "Draws",
    "draw_tones",
    "band_noise",
    "MonteCarlo",
    "monte_carlo",
]

#: Seeds of the draws, of the pilot set that picks the fixed controller in advance, of the noise.
SEED, PILOT_SEED, NOISE_SEED = 14, 1014, 2014
#: Number of tone draws per example, and of pilot draws (closed form, no simulation).
N_DRAWS, N_PILOT = 100, 2000
#: Tones per band in a draw.
N_TONES = 3
#: Prescribed α (HF share of the power) of the coloured-noise runs, each repeated with new noise.
NOISE_ALPHAS = (0.1, 0.3, 0.5, 0.7, 0.9)
NOISE_REPEATS = 2
#: Quantiles reported of the energy ratios.
QUANTILES = (0.05, 0.25, 0.5, 0.75, 0.95)
#: Edges of the α bins of the win rates.
ALPHA_BINS = (0.0, 0.2, 0.4, 0.6, 0.8, 1.0)
#: The examples, by name.
EXAMPLES = ("aircraft", "generic")


def _example(name):
    as_choice("example", name, EXAMPLES)
    return aircraft_example() if name == "aircraft" else generic_example()


@dataclass(frozen=True)
class Draws:
    """Random sums of tones, one per draw (see :func:`draw_tones`).

    Parameters
    ----------
    alpha : (m,) ndarray
        HF share of the power of each draw (its dominance degree on the HF band).
    disturbances : tuple of Sinusoids
        Power 1 each.
    """

    alpha: np.ndarray
    disturbances: tuple


def draw_tones(example: Example, n: int, rng: np.random.Generator) -> Draws:
    """``n`` random sums of :data:`N_TONES` LF and :data:`N_TONES` HF tones of total power 1.

    Per draw: α uniform in (0, 1); frequencies log-uniform in the example's ``lf_tones`` and
    ``hf_tones``; phases uniform in [0, 2π); amplitudes uniform in [0.5, 1.5], then the LF and
    the HF part each scaled so that the HF part holds the share α of the power.

    Parameters
    ----------
    example : Example
    n : int
        Number of draws (≥ 1).
    rng : numpy.random.Generator

    Returns
    -------
    Draws

    Examples
    --------
    >>> from fdsc.paper.reproduced.paper_cases import aircraft_example
    >>> d = draw_tones(aircraft_example(), 2, np.random.default_rng(0))
    >>> [round(x.power(), 12) for x in d.disturbances]
    [1.0, 1.0]
    >>> bool(abs(d.disturbances[0].dominance(aircraft_example().bands["HF"]) - d.alpha[0]) < 1e-12)
    True
    """
    n = as_count("n", n, 1)
    if not isinstance(rng, np.random.Generator):
        raise TypeError(f"rng must be a numpy.random.Generator, but found {type(rng).__name__}")
    alphas, out = [], []
    for _ in range(n):
        alpha = rng.uniform(0.0, 1.0)
        parts = []
        for (lo, hi), share in ((example.lf_tones, 1.0 - alpha), (example.hf_tones, alpha)):
            w = np.exp(rng.uniform(np.log(lo), np.log(hi), N_TONES))
            a = rng.uniform(0.5, 1.5, N_TONES)
            ph = rng.uniform(0.0, 2 * np.pi, N_TONES)
            a = a * np.sqrt(share / (0.5 * np.sum(a**2)))
            parts.append(fdsc.Sinusoids(a, w, ph))
        alphas.append(alpha)
        out.append(parts[0] + parts[1])
    return Draws(np.array(alphas), tuple(out))


def band_noise(example: Example, alpha: float, horizon: float, dt: float,
               rng: np.random.Generator) -> fdsc.Sampled:
    """Band-limited white noise of power 1 whose HF part holds the share ``alpha`` of the power.

    White Gaussian samples are filtered by an ideal band-pass (the FFT bins of the record inside
    the example's ``lf_tones`` range for the LF part, inside ``hf_tones`` for the HF part), each
    part scaled to its share of the power; the sum is held by a first-order hold.

    Parameters
    ----------
    example : Example
    alpha : float
        HF share of the power, in [0, 1].
    horizon, dt : float
        Length (s) and sample spacing (s) of the record.
    rng : numpy.random.Generator

    Returns
    -------
    Sampled
        ``round(horizon / dt) + 1`` samples, ``hold="foh"``.

    Notes
    -----
    By Parseval the shares are exact for the samples (the record is periodic in the FFT); the
    first-order hold adds what a straight line between samples adds (at most ``dt²/8 max|d̈|``,
    about ``(ω dt)²/8`` relative at the fastest tone ω).

    Examples
    --------
    >>> from fdsc.paper.reproduced.paper_cases import aircraft_example
    >>> ex = aircraft_example()
    >>> s = band_noise(ex, 0.3, 20.0, 1e-3, np.random.default_rng(0))
    >>> s.values.size, round(float(np.mean(s.values ** 2)), 12)
    (20001, 1.0)
    """
    alpha = float(alpha)
    horizon, dt = as_positive("horizon", horizon), as_positive("dt", dt)
    if not 0.0 <= alpha <= 1.0:
        raise ValueError(f"alpha must be in [0, 1], but found {alpha}")
    if not isinstance(rng, np.random.Generator):
        raise TypeError(f"rng must be a numpy.random.Generator, but found {type(rng).__name__}")
    m = round(horizon / dt) + 1
    white = np.fft.rfft(rng.standard_normal(m))
    w = 2 * np.pi * np.fft.rfftfreq(m, dt)
    values = np.zeros(m)
    for (lo, hi), share in ((example.lf_tones, 1.0 - alpha), (example.hf_tones, alpha)):
        if hi > np.pi / dt:
            raise ValueError(f"the tone range ({lo}, {hi}) rad/s reaches above the Nyquist frequency "
                             f"π/dt = {np.pi / dt:.4g} rad/s of dt = {dt}")
        part = np.fft.irfft(np.where((w >= lo) & (w <= hi), white, 0.0), m)
        if share > 0:
            values += part * np.sqrt(share / np.mean(part**2))
    return fdsc.Sampled(values, dt, hold="foh")


@dataclass(frozen=True)
class MonteCarlo:
    """Every controller of an example under random disturbances (see :func:`monte_carlo`).

    Parameters
    ----------
    example : str
        The example's name.
    names, fixed, switched : tuple of str
        All controllers; the fixed ones; the switched ones.
    seed, pilot_seed, noise_seed : int
        The seeds.
    alpha : (m,) ndarray
        α of each tone draw.
    energy : dict
        ``{controller: (m,) ndarray}``: ∫zᵀz of each tone draw (``inf`` if it diverged).
    in_advance : str
        The fixed controller chosen in advance (the stored choice of Part II's study,
        :mod:`fdsc.paper.shared.fixed_choice`); its energies are in ``energy`` (those of the tone
        draws in closed form, :func:`fdsc._closed_energy.closed_form_energies`; of the noise runs
        by the simulator).
    pilot : dict
        ``{member of the comparator set: mean steady-state energy ratio over the pilot draws}``
        (the earlier choice among the comparator set alone, kept for the record).
    noise_alpha : (k,) ndarray
        Prescribed α of each noise run.
    noise_energy : dict
        ``{controller: (k,) ndarray}``.
    noise_measured_alpha : (k,) ndarray
        α of each noise record measured by :func:`fdsc.dominance_degree` (no taper).
    diverged : dict
        ``{controller: number of runs (tones and noise) that diverged}``.
    """

    example: str
    names: tuple
    fixed: tuple
    switched: tuple
    seed: int
    pilot_seed: int
    noise_seed: int
    alpha: np.ndarray
    energy: dict
    in_advance: str
    pilot: dict
    noise_alpha: np.ndarray
    noise_energy: dict
    noise_measured_alpha: np.ndarray
    diverged: dict

    def oracle(self, noise: bool = False) -> tuple:
        """The best comparator of each draw and its energy.

        Parameters
        ----------
        noise : bool, optional
            The noise runs instead of the tone draws.

        Returns
        -------
        names : (m,) ndarray of str
        energy : (m,) ndarray
        """
        e = self.noise_energy if noise else self.energy
        stack = np.array([e[n] for n in self.fixed])
        k = np.argmin(stack, axis=0)
        return np.array(self.fixed)[k], stack[k, np.arange(stack.shape[1])]

    def ratio(self, name: str, against: str = "oracle", noise: bool = False) -> np.ndarray:
        """Energy of a controller over the reference's, per draw.

        Parameters
        ----------
        name : str
            A controller of :attr:`names`.
        against : {"oracle", "advance"}, optional
            The best comparator of each draw, or the one chosen in advance.
        noise : bool, optional
            The noise runs instead of the tone draws.

        Returns
        -------
        (m,) ndarray
        """
        as_choice("against", against, ("oracle", "advance"))
        e = self.noise_energy if noise else self.energy
        ref = self.oracle(noise)[1] if against == "oracle" else e[self.in_advance]
        return e[name] / ref

    def quantiles(self, name: str, against: str = "oracle", noise: bool = False) -> np.ndarray:
        """:data:`QUANTILES` of :meth:`ratio`.

        Parameters
        ----------
        name : str
            A controller of :attr:`names`.
        against : {"oracle", "advance"}, optional
            The best comparator of each draw, or the one chosen in advance.
        noise : bool, optional
            The noise runs instead of the tone draws.

        Returns
        -------
        (5,) ndarray
        """
        return np.quantile(self.ratio(name, against, noise), QUANTILES)

    def win_rate(self, name: str, against: str = "oracle", noise: bool = False) -> float:
        """Share of draws in which a controller has less energy than the reference (beyond a tie,
        :data:`~fdsc.paper.shared.examples.TIE_RTOL`).

        Parameters
        ----------
        name : str
            A controller of :attr:`names`.
        against : {"oracle", "advance"}, optional
            The best comparator of each draw, or the one chosen in advance.
        noise : bool, optional
            The noise runs instead of the tone draws.

        Returns
        -------
        float
        """
        return float(np.mean(beats(self.ratio(name, against, noise))))

    def win_rate_by_alpha(self, name: str, against: str = "oracle") -> np.ndarray:
        """Win rate of a controller in each bin of :data:`ALPHA_BINS` (NaN for an empty bin).

        Parameters
        ----------
        name : str
            A controller of :attr:`names`.
        against : {"oracle", "advance"}, optional
            The best comparator of each draw, or the one chosen in advance.

        Returns
        -------
        (5,) ndarray
        """
        r = beats(self.ratio(name, against))
        k = np.clip(np.digitize(self.alpha, ALPHA_BINS) - 1, 0, len(ALPHA_BINS) - 2)
        return np.array([r[k == b].mean() if np.any(k == b) else np.nan
                         for b in range(len(ALPHA_BINS) - 1)])

    def oracle_counts(self) -> dict:
        """``{fixed controller: number of tone draws it is the best fixed one}``."""
        names = self.oracle()[0]
        return {n: int(np.sum(names == n)) for n in self.fixed}

    def best_switched(self) -> str:
        """The switched controller with the highest win rate against the oracle."""
        return max(self.switched, key=lambda n: (self.win_rate(n), -np.median(self.ratio(n))))

    def summary(self) -> dict:
        """Quantiles and win rates of every switched controller (tones and noise), for the record.

        Returns
        -------
        dict
        """
        out = {}
        sources = ("tones", "noise") if self.noise_alpha.size else ("tones",)
        for n in self.switched:
            out[n] = {f"{src}_{against}": {"quantiles": self.quantiles(n, against, src == "noise").tolist(),
                                           "win_rate": self.win_rate(n, against, src == "noise")}
                      for src in sources for against in ("oracle", "advance")}
            out[n]["win_rate_by_alpha"] = self.win_rate_by_alpha(n).tolist()
        return out

    def pays(self) -> str:
        """One sentence: when FDSC (its best-performing law) pays on this example, with numbers."""
        n = self.best_switched()
        rates = self.win_rate_by_alpha(n)
        good = [f"{ALPHA_BINS[b]:.1f}–{ALPHA_BINS[b + 1]:.1f}" for b in range(len(rates)) if rates[b] >= 0.5]
        med = float(np.median(self.ratio(n)))
        adv = self.win_rate(n, "advance")
        where = (f"it beats the best comparator of the draw in most draws only for α in "
                 f"{', '.join(good)}" if good else
                 "in no bin of α does it beat the best comparator of the draw in most draws: "
                 "FDSC does not pay on these disturbances")
        return (f"On the {self.example} example, {n} beats the best comparator of the draw in "
                f"{100 * self.win_rate(n):.0f} % of the {self.alpha.size} tone draws (median energy "
                f"{med:.3g} times that controller's) and the controller fixed in advance "
                f"({self.in_advance}) in {100 * adv:.0f} %; {where}.")

    def to_record(self) -> dict:
        """This example's part of the record entry ``monte_carlo``."""
        return {"seeds": {"tones": self.seed, "pilot": self.pilot_seed, "noise": self.noise_seed},
                "draws": int(self.alpha.size), "noise_runs": int(self.noise_alpha.size),
                "quantile_levels": list(QUANTILES), "alpha_bins": list(ALPHA_BINS),
                "in_advance": self.in_advance, "oracle_counts": self.oracle_counts(),
                "diverged": self.diverged, "switched": self.summary(), "sentence": self.pays()}


def _pilot(example, n, seed):
    """Mean steady-state energy ratio of each fixed controller over ``n`` pilot draws."""
    draws = draw_tones(example, n, np.random.default_rng(seed))
    tones = [(d.frequencies, d.amplitudes) for d in draws.disturbances]
    return {name: float(np.mean([float(g) ** 2 for g in
                                 fdsc.steady_state_gains(example.closed_loop(name), tones)]))
            for name in example.fixed_names}


@cached
def monte_carlo(example: str = "aircraft", *, n: int = N_DRAWS, seed: int = SEED,
                noise_repeats: int = NOISE_REPEATS, executor=None) -> MonteCarlo:
    """Seeded Monte-Carlo of an example: ``n`` tone draws and the coloured-noise runs.

    Parameters
    ----------
    example : {"aircraft", "generic"}
        The example (:func:`fdsc.paper.reproduced.paper_cases.aircraft_example` or
        :func:`fdsc.paper.pays.generic_example.generic_example`).
    n : int, optional
        Tone draws (default :data:`N_DRAWS`).
    seed : int, optional
        Seed of the tone draws.
    noise_repeats : int, optional
        Noise records per value of :data:`NOISE_ALPHAS` (0: none).
    executor : concurrent.futures.Executor or dask.distributed.Client, optional
        Run the simulations there (:func:`fdsc.simulate_batch`): a study far larger than the
        book's (``n`` of 10⁴–10⁶) scales out on a Dask cluster with the same numbers, bit for
        bit, as on this machine's threads. A study run with an executor is not stored in the
        results cache.

    Returns
    -------
    MonteCarlo
    """
    ex = _example(example)
    n = as_count("n", n, 1)
    draws = draw_tones(ex, n, np.random.default_rng(seed))
    comp = ex.compare(list(draws.disturbances), executor=executor)
    rng = np.random.default_rng(NOISE_SEED)
    alphas = np.repeat(np.asarray(NOISE_ALPHAS, float), as_count("noise_repeats", noise_repeats, 0))
    noise = [band_noise(ex, a, ex.horizon, ex.dt, rng) for a in alphas]
    measured = np.array([fdsc.dominance_degree(s.values, ex.dt, ex.bands["HF"], window="boxcar")
                         for s in noise])
    if noise:
        ncomp = ex.compare(noise, executor=executor)
        noise_energy, noise_div = ncomp.energy, ncomp.diverged
    else:
        noise_energy = {k: np.zeros(0) for k in ex.names}
        noise_div = {k: np.zeros(0, bool) for k in ex.names}
    pilot = _pilot(ex, N_PILOT, PILOT_SEED)
    fixed = ex.fixed_names
    switched = tuple(ex.designs)
    # the fixed controller chosen in advance for the non-stationary class, stored by Part II's study
    choice, ctrl = fixed_in_advance(example)
    energy = dict(comp.energy)
    # its tone draws in closed form (the same numbers as the simulator's to rounding, ~1e-12;
    # a simulation of its 27 or 61 states at the example's step is 500× slower)
    energy[choice] = closed_form_energies(ex.plant.closed_loop(ctrl), list(draws.disturbances),
                                          [ex.horizon] * n)[0]
    noise_energy = dict(noise_energy)
    noise_energy[choice] = ex.energies_of(ctrl, noise) if noise else np.zeros(0)
    diverged = {k: int(comp.diverged[k].sum() + noise_div[k].sum()) for k in ex.names}
    diverged[choice] = int(np.sum(~np.isfinite(energy[choice])) + np.sum(~np.isfinite(noise_energy[choice])))
    return MonteCarlo(example, ex.names + (choice,), fixed, switched, int(seed), PILOT_SEED, NOISE_SEED,
                      draws.alpha, energy, choice, pilot, alphas, noise_energy, measured, diverged)
