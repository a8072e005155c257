"""How close the predictive law's tone identification comes to the Cramér–Rao bound under white
sampling noise.

For each example of Part II, at the law's own band and step (:func:`fdsc.paper.pays.ladder.law_band`):
one tone at a low, a middle and a high frequency of the class's HF tones, white Gaussian noise on
the samples at several SNRs (the tone's power over the noise's variance, i.e. its power in the band
the law samples), windows of 1 and 4 s. Per cell, the RMS error of the identified frequency over
seeded trials divided by the exact bound (:func:`fdsc.tone_bound.frequency_bound`; 1 is efficient),
and the share of trials that returned no tone in the band. Three identifications:

* **law**: as :class:`fdsc.PredictiveLaw` identifies (ESPRIT on the second differences of the
  samples, 48 lags, its rank tolerance);
* **raw**: the same ESPRIT on the samples themselves (its lag matrix built from y, not from its
  second differences), 48 lags;
* **raw N/3**: the same with lags a third of the window;
* **confident**: :func:`fdsc.confident.raw_esprit`, the identification of
  :class:`fdsc.confident.ConfidentPredictiveLaw` (samples themselves, lags a third of the window
  up to 160, its rank set by the noise floor).

Second differences multiply a tone of frequency ω by (2 sin(ωh/2))², white noise by 6 on average:
at the aircraft's fine step a tone low in the band drowns in the differenced noise.

    python benchmarks/bench_identification.py [--trials 100]

A benchmark, not a test: it prints a table and states the host.
"""

import argparse
import math
import os

import numpy as np

from fdsc._tones import _esprit
from fdsc.confident import raw_esprit
from fdsc.predictive import DEFAULT_LAGS, DEFAULT_RANK_TOL, EDGE_SHARE
from fdsc.tone_bound import frequency_bound

#: Per example: the law's band and step (as fdsc.paper.pays.ladder.law_band computes them) and
#: three tones across the class's HF tones.
EXAMPLES = {"aircraft": ((math.sqrt(1.0 * 10.0), 360.0), math.pi / (2.5 * 360.0), (12.0, 55.0, 250.0)),
            "generic": ((math.sqrt(1.0 * 10.0), 48.0), math.pi / (2.5 * 48.0), (12.0, 20.0, 38.0))}
WINDOWS = (1.0, 4.0)
SNR_DB = (40.0, 20.0, 10.0, 0.0)
PHASE = 0.7


def _identify(y, step, band, lags, raw):
    """ESPRIT's frequencies in the band (the law's rank tolerance, one tone at most)."""
    if raw == "confident":
        return raw_esprit(y, step, band, max_tones=1)
    if raw:
        y = np.cumsum(np.cumsum(y))     # its second differences are the samples themselves
    return _esprit(y, step, band[0], band[1], 1, lags, DEFAULT_RANK_TOL, EDGE_SHARE)


def cell(band, step, omega, window, snr_db, trials, seed):
    n = int(window / step) + 1
    t = -step * np.arange(n)[::-1]
    clean = np.cos(omega * t + PHASE)
    sigma2 = 0.5 / 10 ** (snr_db / 10)
    rng = np.random.default_rng(seed)
    methods = {"law": (DEFAULT_LAGS, False), "raw": (DEFAULT_LAGS, True), "raw N/3": (n // 3, True),
               "confident": (0, "confident")}
    err = {m: [] for m in methods}
    miss = dict.fromkeys(methods, 0)
    for _ in range(trials):
        y = clean + math.sqrt(sigma2) * rng.standard_normal(n)
        for m, (lags, raw) in methods.items():
            w = _identify(y, step, band, min(lags, n // 2 - 2), raw)
            if w.size == 0:
                miss[m] += 1
            else:
                err[m].append(w[np.argmin(np.abs(w - omega))] - omega)
    bound = frequency_bound(t, [omega], [1.0], [PHASE], sigma2)[0]
    out = {}
    for m in methods:
        rms = math.sqrt(np.mean(np.square(err[m]))) if err[m] else math.nan
        out[m] = (rms / bound, miss[m] / trials)
    return n, out


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--trials", type=int, default=100)
    args = parser.parse_args(argv)
    print(f"host: {os.cpu_count()} CPUs, 1-minute load {os.getloadavg()[0]:.2f}; {args.trials} trials "
          "per cell; RMS error / Cramér–Rao bound (share of trials with no tone)")
    for example, (band, step, tones) in EXAMPLES.items():
        print(f"\n{example}: band ({band[0]:.3g}, {band[1]:.3g}) rad/s, step {step * 1e3:.3g} ms")
        print(f"{'tone':>6} {'window':>7} {'SNR dB':>7} | {'law':>16} | {'raw':>16} | {'raw N/3':>16} | "
              f"{'confident':>16}")
        for k, omega in enumerate(tones):
            for window in WINDOWS:
                for snr in SNR_DB:
                    n, out = cell(band, step, omega, window, snr, args.trials, [k, int(window), int(snr)])
                    row = " | ".join(f"{r:>8.2f} ({100 * m:>3.0f} %)" for r, m in out.values())
                    print(f"{omega:>6.0f} {window:>5.0f} s {snr:>7.0f} | {row}")


if __name__ == "__main__":
    main()
