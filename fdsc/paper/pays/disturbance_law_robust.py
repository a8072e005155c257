"""The law on the disturbance estimate as a controller can build it, for the chapter
'disturbance_law': measurement noise on the estimate, which the decisions, the realization's
copies and every candidate that reads ŵ all see (:func:`robust_result`); an estimate from
sampled measurements with a backward-difference derivative or a wrong model
(:func:`measured_result`); the step independence of the decisions (:func:`step_check`,
:func:`hold_check`); one draw under the chosen law for the chapter's figure (:func:`law_run`);
the direct realization with a certified dwell (:func:`direct_realization`); and the
Geromel–Colaneri min-switching law as a certified control (:func:`min_switching_certificate`).
"""

from __future__ import annotations

import functools
import warnings
from dataclasses import dataclass

import numpy as np

import fdsc
from fdsc.paper.pays.disturbance_law_draws import SEED, Draw, _example, lqr, seeded_draw
from fdsc.paper.pays.disturbance_law_runs import candidates, law_supervisor
from fdsc.paper.pays.fixed_designs import FixedSet
from fdsc.paper.shared.cache import cached

__all__ = ["ESTIMATE_NOISE_TONES", "noisy_estimate", "robust_result", "step_check", "MEASURED_VARIANTS",
           "MEASURED_DT", "measured_result", "min_switching_certificate", "hold_check",
           "min_switching_summary", "LawRun", "law_run", "direct_realization"]


#: Tones of the measurement noise on the estimate (a random-phase multisine with Rayleigh
#: amplitudes, log-uniform over the tone ranges of both bands widened threefold).
ESTIMATE_NOISE_TONES = 16


def noisy_estimate(example, dr: Draw, snr_db: float, rng: np.random.Generator) -> fdsc.Piecewise:
    """The disturbance estimate with measurement noise: ``d`` plus broadband noise of power
    ``10^(−SNR/10)`` (each segment of ``d`` has power 1), present over the whole run.

    Parameters
    ----------
    example : Example
    dr : Draw
    snr_db : float
        Signal-to-noise ratio of the estimate in dB (power of d over power of the noise).
    rng : numpy.random.Generator

    Returns
    -------
    fdsc.Piecewise

    Examples
    --------
    >>> from fdsc.paper.reproduced.paper_cases import aircraft_example
    >>> from fdsc.paper.pays.disturbance_law_draws import draw
    >>> ex = aircraft_example()
    >>> dr = draw(ex, np.random.default_rng(0))
    >>> w = noisy_estimate(ex, dr, 20.0, np.random.default_rng(1))
    >>> round(w.parts[0].power() - dr.d.parts[0].power(), 3)       # uncorrelated tones: powers add
    0.01
    """
    lo, hi = example.lf_tones[0] / 3.0, example.hf_tones[1] * 3.0
    m = ESTIMATE_NOISE_TONES
    w = np.exp(rng.uniform(np.log(lo), np.log(hi), m))
    a = rng.rayleigh(1.0, m)
    a = a * np.sqrt(10.0 ** (-snr_db / 10.0) / (0.5 * np.sum(a**2)))
    nu = fdsc.Sinusoids(a, w, rng.uniform(0.0, 2 * np.pi, m))
    breaks = list(dr.d.breaks)
    parts = [p + nu for p in dr.d.parts]
    if dr.horizon > breaks[-1]:
        breaks.append(dr.horizon)
        parts.append(nu)
    return fdsc.Piecewise(breaks, parts)


def robust_result(example: str, index: int, law: str, fs: FixedSet, snr_db: float,
                  seed: int = SEED) -> dict:
    """Draw ``index`` under a law on a noisy estimate, as built (decisions, copies and candidates
    that read ŵ on the noisy estimate) and as the idealization where only the decisions see the
    noise, against the same law on the exact estimate; and the fixed controller chosen in
    advance on the same noisy estimate (unaffected unless it reads ŵ).

    Parameters
    ----------
    example : {"aircraft", "generic"}
    index : int
    law : str
        ``candidates/law/realization/λ/h``.
    fs : FixedSet
    snr_db : float
        SNR of the estimate (dB).
    seed : int, optional
        Of the draw; the noise's generator is seeded by ``[seed, index, 1]``.

    Returns
    -------
    dict
        Energies over the fixed controller chosen in advance on the exact estimate: ``noisy``
        (the law as built), ``decisions_only``, ``exact``, ``fixed_noisy`` (the chosen fixed
        controller on the noisy estimate); ``switches_noisy``, ``switches_exact``.
    """
    ex, dr = seeded_draw(example, index, seed)
    what = noisy_estimate(ex, dr, snr_db, np.random.default_rng([seed, index, 1]))
    sup, _shown, lam, h = law_supervisor(example, law, fs)
    exact = sup.prepare(dr.d, dr.horizon)
    built = sup.prepare(dr.d, dr.horizon, estimate=what)
    ideal = sup.prepare(dr.d, dr.horizon, estimate=what, copies_on_estimate=False)
    chosen = fs.controllers[fs.chosen]
    ref = exact.energy_of(chosen)
    a, b = exact.run(forgetting=lam, hysteresis=h), built.run(forgetting=lam, hysteresis=h)
    c = ideal.run(forgetting=lam, hysteresis=h)
    return {"noisy": b.energy / ref, "decisions_only": c.energy / ref, "exact": a.energy / ref,
            "fixed_noisy": built.energy_of(chosen) / ref, "switches_noisy": b.switches,
            "switches_exact": a.switches}


def step_check(example: str, index: int, law: str, fs: FixedSet, dts=(1e-3, 5e-4), seed: int = SEED) -> dict:
    """The law on one draw with its switched run stepped by the library's simulator at two steps,
    against the exact run: the decisions must not depend on the step.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    index : int
    law : str
        ``candidates/law/realization/λ/h``.
    fs : FixedSet
    dts : (float, float), optional
        The steps (s), each dividing the decision interval and every break of the draw.
    seed : int, optional

    Returns
    -------
    dict
        ``same_switches`` (bool: the three runs switch at the same instants), ``switches``,
        ``energy_rel_diff`` (largest relative difference of the stepped energies from the exact
        one).
    """
    from fdsc._grid_run import _run_on_grid

    _ex, dr = seeded_draw(example, index, seed)
    sup, _shown, lam, h = law_supervisor(example, law, fs)
    prep = sup.prepare(dr.d, dr.horizon)
    mu = prep.mu(lam)
    sigma = prep.decide(mu, hysteresis=h)
    exact = prep.run_sequence(sigma)
    runs = [_run_on_grid(prep, sigma, mu, dt) for dt in dts]
    same = all(np.array_equal(r.switch_times, exact.switch_times)
               and np.array_equal(r.sequence, exact.sequence) for r in runs)
    return {"same_switches": bool(same), "switches": exact.switches,
            "energy_rel_diff": float(max(abs(r.energy / exact.energy - 1) for r in runs))}


#: The measured-estimate variants of :func:`measured_result`: name → (derivative, A scale).
MEASURED_VARIANTS = {"sampled": ("exact", 1.0), "backward": ("backward", 1.0),
                     "A+10%": ("exact", 1.1), "A-10%": ("exact", 0.9)}
#: The sampling step (s) of the measured runs: the book's simulation step.
MEASURED_DT = 1e-3


def measured_result(example: str, index: int, law: str, fs: FixedSet, seed: int = SEED) -> dict:
    """Draw ``index`` under a law run on sampled measurements (:meth:`fdsc.Supervisor.run_measured`
    at :data:`MEASURED_DT`) in each of :data:`MEASURED_VARIANTS`, against the fixed controller
    chosen in advance run on the same plant (the true one); and the min-switching control.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    index : int
    law : str
        ``candidates/law/realization/λ/h``.
    fs : FixedSet
    seed : int, optional

    Returns
    -------
    dict
        ``{variant: {"ratio", "switches", "diverged"}}``, ``"exact"`` (the exact engine on the
        exact estimate) and ``"min_switching"``.
    """
    ex, dr = seeded_draw(example, index, seed)
    sup, _shown, lam, h = law_supervisor(example, law, fs)
    chosen = fs.controllers[fs.chosen]
    prep = sup.prepare(dr.d, dr.horizon)
    refs = {}                       # the chosen controller's energy on the plant of each scale of A

    def ref(scale):
        if scale not in refs:
            p = ex.plant
            loop = chosen.closed_loop(fdsc.Plant(scale * p.A, p.B1, p.B2, p.C, p.D1, p.D2))
            refs[scale] = prep.energy_of(loop)
        return refs[scale]

    a = prep.run(forgetting=lam, hysteresis=h)
    out = {"exact": {"ratio": a.energy / ref(1.0), "switches": a.switches,
                     "diverged": a.diverged_at is not None}}
    for name, (derivative, scale) in MEASURED_VARIANTS.items():
        r = sup.run_measured(dr.d, dr.horizon, MEASURED_DT, derivative=derivative, true_A=scale * ex.plant.A,
                             forgetting=lam, hysteresis=h)
        out[name] = {"ratio": r.energy / ref(scale), "switches": r.switches,
                     "diverged": r.diverged_at is not None}
    _names, gains = candidates(example)
    loops = [ex.plant.closed_loop(G) for G in gains]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", fdsc.UnstableRunWarning)
        m = fdsc.simulate_stream(loops, dr.d, dr.horizon, MEASURED_DT,
                                 law_weights=min_switching_certificate(example).law_weights())
    out["min_switching"] = {"ratio": m.energy / ref(1.0), "switches": int(m.switches),
                            "diverged": any(issubclass(w.category, fdsc.UnstableRunWarning) for w in caught)}
    return out


@functools.cache
@cached
def min_switching_certificate(example: str = "aircraft") -> fdsc.MinSwitchingCertificate:
    """The Geromel–Colaneri min-switching law over the cost law's gains, with its L2-gain
    certificate (:func:`fdsc.min_switching`): the certified negative control.

    Parameters
    ----------
    example : {"aircraft", "generic"}

    Returns
    -------
    fdsc.MinSwitchingCertificate
    """
    ex = _example(example)
    _names, gains = candidates(example)
    return fdsc.min_switching([ex.plant.closed_loop(K) for K in gains])


def hold_check(example: str, index: int, law: str, fs: FixedSet, dts=(MEASURED_DT, MEASURED_DT / 2),
               seed: int = SEED) -> dict:
    """The law run on sampled measurements with the exact derivative at two steps, against the
    exact run: how the hold of the estimate between samples costs with the step.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    index : int
    law : str
        ``candidates/law/realization/λ/h``.
    fs : FixedSet
    dts : (float, float), optional
        The sampling steps (s).
    seed : int, optional

    Returns
    -------
    dict
        ``excess`` (the relative excess energy over the exact run at each step), ``same_switches``
        (bool per step: the switch instants equal the exact run's).
    """
    _ex, dr = seeded_draw(example, index, seed)
    sup, _shown, lam, h = law_supervisor(example, law, fs)
    exact = sup.prepare(dr.d, dr.horizon).run(forgetting=lam, hysteresis=h)
    excess, same = [], []
    for dt in dts:
        r = sup.run_measured(dr.d, dr.horizon, dt, forgetting=lam, hysteresis=h)
        excess.append(r.energy / exact.energy - 1.0)
        same.append(bool(np.array_equal(r.switch_times, exact.switch_times)))
    return {"dts": list(dts), "excess": excess, "same_switches": same}


def min_switching_summary(example: str) -> dict:
    """The min-switching certificate's numbers for the study's file.

    Parameters
    ----------
    example : {"aircraft", "generic"}

    Returns
    -------
    dict
        ``l2_bound`` (ρ), ``rate`` (γ of its Metzler matrix), ``candidates`` (names).
    """
    c = min_switching_certificate(example)
    return {"l2_bound": c.l2_bound, "rate": c.rate, "candidates": list(candidates(example)[0])}


@dataclass(frozen=True)
class LawRun:
    """One draw under the chosen law, for the chapter's figure (see :func:`law_run`).

    Parameters
    ----------
    draw : Draw
    names : tuple of str
        The candidates.
    run : fdsc.SupervisedRun
        With the monitoring signals.
    ratio : float
        Its energy over the fixed controller chosen in advance's.
    """

    draw: Draw
    names: tuple
    run: fdsc.SupervisedRun
    ratio: float


def law_run(example: str, index: int, law: str, fs: FixedSet, seed: int = SEED) -> LawRun:
    """Draw ``index`` of the seeded sequence under a law, with its monitoring signals.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    index : int
    law : str
        ``candidates/law/realization/λ/h``.
    fs : FixedSet
        Its energy is divided by the fixed controller chosen in advance's.
    seed : int, optional

    Returns
    -------
    LawRun
    """
    _ex, dr = seeded_draw(example, index, seed)
    sup, shown, lam, h = law_supervisor(example, law, fs)
    prep = sup.prepare(dr.d, dr.horizon)
    r = prep.run(forgetting=lam, hysteresis=h)
    return LawRun(dr, tuple(shown), r, r.energy / prep.energy_of(fs.controllers[fs.chosen]))


def direct_realization(example: str, index: int, law: str, seed: int = SEED) -> dict:
    """The cost law over the gains on draw ``index`` realized directly (u = K_σ x) with the
    Geromel–Colaneri dwell time of the gains enforced, against its realization through copies.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    index : int
    law : str
        A setting; its λ and h are used.
    seed : int, optional

    Returns
    -------
    dict
        ``dwell`` (s, None if none was certified up to 10³ s), ``direct`` and ``copies``
        (energies), ``direct_switches``, ``copies_switches``.
    """
    ex, dr = seeded_draw(example, index, seed)
    _names, gains = candidates(example)
    lam, h = (float(v) for v in law.split("/")[-2:])
    loops = [ex.plant.closed_loop(K) for K in gains]
    try:
        tau = fdsc.geromel_colaneri_dwell(loops, tau_max=1e3).tau
    except fdsc.SolverError:
        tau = None
    prep = fdsc.Supervisor(ex.plant, list(gains), decide_every=0.1, restart=20.0).prepare(dr.d, dr.horizon)
    direct = prep.run(forgetting=lam, hysteresis=h, min_dwell=tau or 0.0)
    copies = prep.with_K0(lqr(example)).run(forgetting=lam, hysteresis=h)
    return {"dwell": tau, "direct": direct.energy, "copies": copies.energy,
            "direct_switches": direct.switches, "copies_switches": copies.switches}
