"""The ladder under measurement noise: what a controller that reads a noisy estimate ŵ = d + n
can still gain by predicting the disturbance.

On the stored study's draws (:mod:`fdsc.paper.pays.disturbance_law_full`) and its fixed
controllers, at each noise level of :data:`LEVELS` (the class's mean power of d over the
variance of white noise on the samples, band-limited to the Nyquist frequency of the predictive
law's sampler; :func:`fdsc.measurement_noise.noise_density`):

* the **best fixed controller (x, ŵ) at that level**: the controller of least expected power with
  the noise among the stored comparator set and the optimal ``u = K x + Q(s) ŵ`` redesigned for
  that noise (:func:`fdsc.measurement_noise.optimal_lti_in_noise`); its energy on a draw is its
  exact energy on d plus the noise's expected energy (the horizon times
  :func:`fdsc.measurement_noise.noise_power`; the cross term has mean zero);
* the **best fixed controller (x)**: the stored study's, which reads no ŵ and sees no noise;
* the **predictive law with a confidence check** (:class:`fdsc.confident.ConfidentPredictiveLaw`)
  on the redesigned optimal controller as its base, its samples carrying the noise (seeded per
  draw), plus the noise its base's continuous filter reads (in expectation, as for the fixed
  controllers); at one level also with a computation delay of one update. Its setting is chosen
  on :data:`N_TRAIN` training draws at each level, by the mean log energy: one of the windows
  :data:`WINDOWS`, or :data:`FALLBACK` (not predicting at all: the law is then the best fixed
  controller at that level, which its training draws found better than every window);
* the **non-causal limit** (stored): the bound, which reads d exactly.

On the exact estimate, also the **model error** of :data:`SCALES`: the plant's A scaled, the
law and the fixed controllers designed on the model (A itself), ŵ = d; the limit is the true
plant's.

``python -m fdsc information [--workers W] [--replace]`` runs it and writes :data:`INFO_FILE`
(with its wall time and host), which the book reads; the book rechecks one draw.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np

import fdsc
from fdsc._closed_energy import closed_form_energies
from fdsc.confident import ConfidentPredictiveLaw
from fdsc.measurement_noise import noise_density, noise_loop, noise_power, optimal_lti_in_noise
from fdsc.paper.pays.disturbance_law_draws import _example, seeded_draw, segment_class
from fdsc.paper.pays.ladder import MAX_TONES, law_band
from fdsc.paper.pays.stored_study import map_draws, stored_fixed_set
from fdsc.paper.pays.study_command import load_stored, study_main
from fdsc.paper.shared.stats import bootstrap_median

__all__ = ["LEVELS", "N_TEST", "N_TRAIN", "WINDOWS", "FALLBACK", "CONFIDENCE", "DELAY_LEVEL", "SCALES",
           "INFO_FILE", "reference_name",
           "level_design", "law_energy", "information_study", "summary", "model_error_summary",
           "load_information", "recheck", "main"]

#: Noise levels (dB): the mean power of d over the noise's variance; inf is the exact estimate.
LEVELS = (math.inf, 40.0, 20.0, 10.0, 0.0)
#: Test draws per example (the stored study's first test draws) and training draws (its first).
N_TEST, N_TRAIN = 24, 4
#: The law's windows tried on the training draws (s); its confidence threshold and update.
WINDOWS, CONFIDENCE, UPDATE = (2.0, 4.0, 8.0, 12.0, 16.0), 0.5, 0.5
#: The law's setting that does not predict: it runs the best fixed controller at that noise level
#: (:func:`reference_name`), chosen where the training draws find it better than every window.
FALLBACK = "fixed"
#: The level at which the law also runs with a computation delay of one update.
DELAY_LEVEL = 20.0
#: The scales of A of the model-error variants (on the exact estimate).
SCALES = (1.1, 0.9)
#: The stored result, which the book reads.
INFO_FILE = Path("book") / "data" / "information_study.json"
#: The rungs, in the order of the ladder.
RUNGS = ("limit", "predictive (confident)", "best fixed (x, ŵ)", "best fixed (x)")


def _key(level):
    return "exact" if math.isinf(level) else f"{level:g} dB"


def reference_name(design: dict) -> str:
    """The best fixed controller at a noise level: of the best reading (x, ŵ) and the best reading
    x alone, the one of least expected power with the noise (the reference of :func:`summary`,
    and what the law runs in its setting :data:`FALLBACK`).

    Parameters
    ----------
    design : dict
        :func:`level_design`'s result, or a stored row (``best``, ``best_x``, ``expected_power``
        or ``powers``).

    Returns
    -------
    str
        The controller's name (a stored name or ``"optimal LTI in noise"``).

    Examples
    --------
    >>> reference_name({"best": "a", "best_x": "b", "powers": {"a": 1.0, "b": 2.0}})
    'a'
    >>> reference_name({"best": "a", "best_x": "b", "expected_power": {"a": 1.0, "b": 0.5}})
    'b'
    """
    p = design["powers"] if "powers" in design else design["expected_power"]
    return design["best"] if p[design["best"]] <= p[design["best_x"]] else design["best_x"]


def level_design(example: str, level: float, full: dict) -> dict:
    """The fixed controllers at one noise level: the noise's density and band, the redesigned
    optimal controller, and every stored controller's expected power with the noise.

    Parameters
    ----------
    example : {"aircraft", "generic"}
    level : float
        dB (inf: no noise).
    full : dict
        The stored study.

    Returns
    -------
    dict
        ``density``, ``nyquist``, ``variance``, ``optimal`` (:class:`NoisyOptimalLTI`),
        ``powers`` ({name: expected power with the noise}), ``noise`` ({name: its noise part}),
        ``best`` (the (x, ŵ) controller of least expected power: a stored name or
        ``"optimal LTI in noise"``), ``best_x`` (the stored study's best reading x alone).
    """
    ex, cls = _example(example), segment_class(example)
    _band, step = law_band(example)
    nyq = math.pi / step
    S = noise_density(cls.power, level, nyq)
    fs = stored_fixed_set(full, example)
    opt = optimal_lti_in_noise(ex.plant, cls, S, nyq, name="optimal LTI in noise")
    powers, noise = {}, {}
    info = full[example]["fixed_controllers"]
    for name in fs.names:
        c = fs.controllers[name]
        noise[name] = noise_power(noise_loop(ex.plant, c), S, nyq) if c.reads_estimate and S > 0 else 0.0
        powers[name] = info[name]["expected_power"] + noise[name]
    powers["optimal LTI in noise"], noise["optimal LTI in noise"] = opt.power, opt.noise_power
    reading = [k for k in powers if k == "optimal LTI in noise" or fs.controllers[k].reads_estimate]
    return {"density": S, "nyquist": nyq, "variance": S * nyq / math.pi, "optimal": opt, "powers": powers,
            "noise": noise, "best": min(reading, key=powers.get), "best_x": fs.chosen_x}


def _plant(example, scale):
    p = _example(example).plant
    return p if scale == 1.0 else fdsc.Plant(scale * p.A, p.B1, p.B2, p.C, p.D1, p.D2)


def law_energy(example: str, index: int, seed: int, level: float, window: float, base, base_noise: float,
               delay: float = 0.0, scale: float = 1.0) -> float:
    """The confident predictive law's energy on one draw at one noise level, with the expected
    energy of the noise its base reads (``base_noise`` per second).

    Parameters
    ----------
    example : {"aircraft", "generic"}
    index, seed : int
    level : float
    window : float
    base : Controller
    base_noise : float
    delay : float, optional
    scale : float, optional
        The true plant's A is ``scale`` times the model's.

    Returns
    -------
    float
    """
    ex, dr = seeded_draw(example, index, seed)
    band, step = law_band(example)
    S = noise_density(segment_class(example).power, level, math.pi / step)
    law = ConfidentPredictiveLaw(ex.plant, band, window=window, step=step, update=UPDATE, max_tones=MAX_TONES,
                                 base=base, confidence=CONFIDENCE, delay=delay,
                                 true_A=None if scale == 1.0 else scale * ex.plant.A)
    run = law.run(dr.d, dr.horizon, noise=S * (math.pi / step) / math.pi, seed=index)
    return run.energy + dr.horizon * base_noise


def _fixed_energy(example, index, seed, ctrl, scale=1.0):
    """The exact energy of a fixed controller on one draw (closed form), on the plant with A
    scaled."""
    _ex, dr = seeded_draw(example, index, seed)
    return float(closed_form_energies(_plant(example, scale).closed_loop(ctrl), [dr.d], [dr.horizon])[0][0])


def _model_error_row(example, index, seed, scale, best, best_x):
    """The fixed rungs and the limit on one draw on the plant with A scaled."""
    _ex, dr = seeded_draw(example, index, seed)
    return {"limit": fdsc.noncausal_limit(_plant(example, scale), dr.d, dr.horizon).energy,
            "best fixed (x, ŵ)": _fixed_energy(example, index, seed, best, scale),
            "best fixed (x)": _fixed_energy(example, index, seed, best_x, scale)}


def information_study(full: dict, *, n_test: int = N_TEST, n_train: int = N_TRAIN, executor=None) -> dict:
    """The study (module docstring) on the stored study ``full``.

    Parameters
    ----------
    full : dict
        The stored study (:func:`fdsc.paper.pays.stored_study.load_full`).
    n_test, n_train : int, optional
    executor : optional
        Where the runs go (:func:`fdsc.paper.pays.stored_study.map_draws`).

    Returns
    -------
    dict
        Per example and level: the chosen controllers, the law's window and its training scores,
        and per test draw (``test_indices``) the energy of every rung.
    """
    from fdsc.paper.shared.cache import study_fingerprint
    from fdsc.paper.shared.environment import build_commit

    seed = full["seed"]
    out = {"commit": build_commit(), "fingerprint": study_fingerprint("fdsc.paper.pays.information"),
           "stored_study": {"commit": full["commit"], "fingerprint": full["fingerprint"]},
           "seed": seed, "levels": [_key(v) for v in LEVELS], "n_test": n_test, "n_train": n_train,
           "windows": list(WINDOWS), "fallback": FALLBACK, "confidence": CONFIDENCE, "update": UPDATE,
           "delay_level": _key(DELAY_LEVEL)}
    designs = {(ex, lv): level_design(ex, lv, full) for ex in ("aircraft", "generic") for lv in LEVELS}
    # training: every window at every level
    train_args = [(ex, i, seed, lv, w, designs[ex, lv]["optimal"].controller,
                   designs[ex, lv]["optimal"].noise_power)
                  for ex in ("aircraft", "generic") for lv in LEVELS for w in WINDOWS for i in range(n_train)]
    train = map_draws(law_energy, train_args, executor)
    score = {}
    for a, e in zip(train_args, train, strict=True):
        score.setdefault((a[0], a[3], a[4]), []).append(math.log(e))
    # not predicting: the best fixed controller at the level on the same training draws (its exact
    # energy on d plus the noise's expected energy, as on the test draws)
    fsets = {ex: stored_fixed_set(full, ex) for ex in ("aircraft", "generic")}

    def controller(ex, name, lv=math.inf):
        return designs[ex, lv]["optimal"].controller if name == "optimal LTI in noise" \
            else fsets[ex].controllers[name]

    fb_args = [(ex, i, seed, controller(ex, reference_name(designs[ex, lv]), lv))
               for ex in ("aircraft", "generic") for lv in LEVELS for i in range(n_train)]
    fb_keys = [(ex, lv, i) for ex in ("aircraft", "generic") for lv in LEVELS for i in range(n_train)]
    for (ex, lv, i), e in zip(fb_keys, map_draws(_fixed_energy, fb_args, executor), strict=True):
        dz = designs[ex, lv]
        noise = seeded_draw(ex, i, seed)[1].horizon * dz["noise"][reference_name(dz)]
        score.setdefault((ex, lv, FALLBACK), []).append(math.log(e + noise))
    settings = (*WINDOWS, FALLBACK)
    chosen = {(ex, lv): min(settings, key=lambda w, ex=ex, lv=lv: float(np.mean(score[ex, lv, w])))
              for ex in ("aircraft", "generic") for lv in LEVELS}
    test_idx = {ex: full[ex]["test_indices"][:n_test] for ex in ("aircraft", "generic")}
    args = []
    for ex in ("aircraft", "generic"):
        for lv in LEVELS:
            opt = designs[ex, lv]["optimal"]
            if chosen[ex, lv] == FALLBACK:
                continue        # the law is the best fixed controller at this level: nothing to run
            for i in test_idx[ex]:
                args.append((ex, i, seed, lv, chosen[ex, lv], opt.controller, opt.noise_power, 0.0, 1.0))
                if lv == DELAY_LEVEL:
                    args.append((ex, i, seed, lv, chosen[ex, lv], opt.controller, opt.noise_power, UPDATE,
                                 1.0))
    # the model-error variants on the exact estimate
    n_plain = len(args)
    for ex in ("aircraft", "generic"):
        opt = designs[ex, math.inf]["optimal"]
        if chosen[ex, math.inf] == FALLBACK:
            continue
        for scale in SCALES:
            for i in test_idx[ex]:
                args.append((ex, i, seed, math.inf, chosen[ex, math.inf], opt.controller, 0.0, 0.0, scale))
    runs = map_draws(law_energy, args, executor)
    law = {(a[0], a[3], a[1], a[7]): e for a, e in zip(args[:n_plain], runs[:n_plain], strict=True)}
    law_scaled = {(a[0], a[8], a[1]): e for a, e in zip(args[n_plain:], runs[n_plain:], strict=True)}
    m_args = [(ex, i, seed, scale, controller(ex, designs[ex, math.inf]["best"]),
               controller(ex, designs[ex, math.inf]["best_x"]))
              for ex in ("aircraft", "generic") for scale in SCALES for i in test_idx[ex]]
    m_rows = map_draws(_model_error_row, m_args, executor)
    model_rows = {}
    for a, r in zip(m_args, m_rows, strict=True):
        model_rows.setdefault((a[0], a[3]), []).append(r)
    opt_args = [(ex, i, seed, designs[ex, lv]["optimal"].controller) for ex in ("aircraft", "generic")
                for lv in LEVELS for i in test_idx[ex]]
    opt_e = dict(zip([(a[0], lv, a[1]) for a, lv in zip(opt_args, [lv for ex in ("aircraft", "generic")
                                                                     for lv in LEVELS for _ in test_idx[ex]],
                                                        strict=True)],
                     map_draws(_fixed_energy, opt_args, executor), strict=True))
    for ex in ("aircraft", "generic"):
        st = full[ex]
        pos = {i: k for k, i in enumerate(st["test_indices"])}
        horizon = {i: seeded_draw(ex, i, seed)[1].horizon for i in test_idx[ex]}
        res = {"test_indices": test_idx[ex], "horizons": [horizon[i] for i in test_idx[ex]]}
        for lv in LEVELS:
            dz = designs[ex, lv]
            best, best_x = dz["best"], dz["best_x"]

            def fixed(name, i, ex=ex, dz=dz, lv=lv, st=st, pos=pos, horizon=horizon):
                if name == "optimal LTI in noise":
                    clean = opt_e[ex, lv, i]
                else:
                    clean = st["fixed_energy"][name][pos[i]]
                return clean + horizon[i] * dz["noise"][name]

            ref = reference_name(dz)

            def ref_energy(i, ref=ref, best_x=best_x, st=st, pos=pos, fixed=fixed):
                return st["fixed_energy"][best_x][pos[i]] if ref == best_x else fixed(ref, i)

            fallback = chosen[ex, lv] == FALLBACK
            law_e = [ref_energy(i) if fallback else law[ex, lv, i, 0.0] for i in test_idx[ex]]
            row = {"density": dz["density"], "variance": dz["variance"], "nyquist": dz["nyquist"],
                   "best": best, "best_x": best_x, "window": chosen[ex, lv], "fallback": ref,
                   "train_scores": {f"{w:g}" if w != FALLBACK else w: float(np.mean(score[ex, lv, w]))
                                    for w in settings},
                   "expected_power": {k: dz["powers"][k] for k in (best, best_x, "optimal LTI in noise")},
                   "noise_power": {k: dz["noise"][k] for k in (best, best_x, "optimal LTI in noise")},
                   "optimal_states": dz["optimal"].controller.n_states,
                   "optimal_converged": bool(dz["optimal"].converged),
                   "energies": {"limit": [st["ladder"]["energies"]["limit"][pos[i]] for i in test_idx[ex]],
                                "predictive (confident)": law_e,
                                "best fixed (x, ŵ)": [fixed(best, i) for i in test_idx[ex]],
                                "best fixed (x)": [st["fixed_energy"][best_x][pos[i]] for i in test_idx[ex]],
                                "optimal LTI in noise": [fixed("optimal LTI in noise", i)
                                                         for i in test_idx[ex]]}}
            if lv == DELAY_LEVEL:
                row["energies"]["predictive (delay)"] = law_e if fallback else [law[ex, lv, i, UPDATE]
                                                                                for i in test_idx[ex]]
            res[_key(lv)] = row
        res["model_error"] = {}
        d0 = designs[ex, math.inf]
        for scale in SCALES:
            rows = model_rows[ex, scale]
            fb = "best fixed (x, ŵ)" if reference_name(d0) == d0["best"] else "best fixed (x)"
            no_law = chosen[ex, math.inf] == FALLBACK
            res["model_error"][f"{scale:g}"] = {
                "best": d0["best"], "best_x": d0["best_x"], "window": chosen[ex, math.inf],
                "energies": {"limit": [r["limit"] for r in rows],
                             "predictive (confident)": [r[fb] for r in rows] if no_law
                             else [law_scaled[ex, scale, i] for i in test_idx[ex]],
                             "best fixed (x, ŵ)": [r["best fixed (x, ŵ)"] for r in rows],
                             "best fixed (x)": [r["best fixed (x)"] for r in rows]}}
        out[ex] = res
    return out


def _ratios(row, ref_name):
    e = {k: np.asarray(v, dtype=float) for k, v in row["energies"].items()}
    out = {"reference": ref_name}
    for rung, v in e.items():
        r = v / e[ref_name]
        med, lo, hi = bootstrap_median(r)
        out[rung] = (med, lo, hi, float(np.mean(r < 1.0)))
    return out


def summary(info: dict, example: str) -> list:
    """Per level: each rung over the best fixed controller at that level (the one of least
    expected power of the best (x, ŵ) and (x)): median with its bootstrap 95 % interval, and
    the share of draws on which it has less energy.

    Parameters
    ----------
    info : dict
        :func:`information_study`'s result.
    example : {"aircraft", "generic"}

    Returns
    -------
    list of dict
        ``{"level", "reference", rung: (median, lo, hi, wins)}``.
    """
    rows = []
    for key in info["levels"]:
        row = info[example][key]
        ref = "best fixed (x, ŵ)" if reference_name(row) == row["best"] else "best fixed (x)"
        rows.append({"level": key} | _ratios(row, ref))
    return rows


def model_error_summary(info: dict, example: str) -> list:
    """Per scale of A: each rung over the best fixed controller (x, ŵ) of the exact estimate,
    both run on the true plant (as :func:`summary`).

    Parameters
    ----------
    info : dict
        :func:`information_study`'s result.
    example : {"aircraft", "generic"}

    Returns
    -------
    list of dict
        ``{"scale", "reference", rung: (median, lo, hi, wins)}``.
    """
    return [{"scale": float(k)} | _ratios(row, "best fixed (x, ŵ)")
            for k, row in info[example]["model_error"].items()]


def load_information(path=None):
    """The stored study of this module.

    Parameters
    ----------
    path : path, optional
        Default :data:`INFO_FILE` in the repository this package lies in.

    Returns
    -------
    dict or None
        None if the file is absent.
    """
    return load_stored(INFO_FILE, path)


def recheck(info: dict, full: dict, example: str = "generic", level: str = "20 dB", k: int = 0) -> dict:
    """Recompute the law and the best fixed (x, ŵ) on one stored test draw at one level.

    Parameters
    ----------
    info : dict
        The stored result (:func:`load_information`).
    full : dict
        The stored study it was computed on.
    example : {"aircraft", "generic"}, optional
    level : str, optional
        One of ``info["levels"]``.
    k : int, optional
        Which of the stored test draws.

    Returns
    -------
    dict
        ``{"law": (stored, recomputed), "fixed": (stored, recomputed)}``.
    """
    lv = math.inf if level == "exact" else float(level.split()[0])
    row, i = info[example][level], info[example]["test_indices"][k]
    dz = level_design(example, lv, full)
    opt = dz["optimal"]
    if row["window"] == FALLBACK:
        # the law is the best fixed controller at this level: its energy is that controller's
        ref = reference_name(dz)
        ctrl = (opt.controller if ref == "optimal LTI in noise"
                else stored_fixed_set(full, example).controllers[ref])
        law = _fixed_energy(example, i, info["seed"], ctrl) + info[example]["horizons"][k] * dz["noise"][ref]
    else:
        law = law_energy(example, i, info["seed"], lv, row["window"], opt.controller, opt.noise_power)
    best = dz["best"]
    if best == "optimal LTI in noise":
        clean = _fixed_energy(example, i, info["seed"], opt.controller)
    else:
        clean = full[example]["fixed_energy"][best][full[example]["test_indices"].index(i)]
    fixed = clean + info[example]["horizons"][k] * dz["noise"][best]
    return {"law": (row["energies"]["predictive (confident)"][k], law),
            "fixed": (row["energies"]["best fixed (x, ŵ)"][k], fixed)}


def main(argv=None) -> int:
    """``python -m fdsc information [--workers W] [--n-test N] [--n-train N] [--out FILE | --replace]``
    (:func:`fdsc.paper.pays.study_command.study_main`).

    Parameters
    ----------
    argv : list of str, optional

    Returns
    -------
    int
        0 on success.
    """
    return study_main(argv, prog="python -m fdsc information",
                      description="the ladder under measurement noise, on the stored study's draws",
                      file=INFO_FILE, study=information_study,
                      options=(("n_test", N_TEST, 2, None), ("n_train", N_TRAIN, 1, None)))


if __name__ == "__main__":
    sys.exit(main())
