"""How close the predictive law's tone identification comes to the Cramér–Rao bound.

One tone in white Gaussian noise at several SNRs (the tone's power over the noise's variance),
windows of several lengths; the RMS error of the frequency that :func:`fdsc.identify_tones`
returns, over seeded trials, divided by the exact bound :func:`fdsc.tone_bound.frequency_bound`
(1 is efficient). Two choices of the lag matrix's width: the default (fixed) and a third of the
window; and, as a remedy to try, the window low-passed and decimated to a Nyquist frequency of
1.5 times the band's top before the identification (the identification works on second
differences, which raise white noise at the law's fine step far above a tone in the band). A
trial that returns not exactly one tone counts as a miss (reported apart).

    python benchmarks/bench_identification.py [--trials 200]

A benchmark, not a test: it prints a table and states the host.
"""

import argparse
import os
import warnings

import numpy as np
from scipy.signal import decimate

from fdsc.predictive import DEFAULT_LAGS, identify_tones
from fdsc.tone_bound import frequency_bound

STEP = 0.0035          # s: about the predictive law's step on the aircraft
OMEGA, PHASE = 21.0, 0.7
BAND = (8.0, 40.0)
WINDOWS = (128, 573, 1143)
SNR_DB = (40.0, 20.0, 10.0, 0.0)


def trial_errors(n, snr_db, lags, trials, rng, q=1):
    t = -np.arange(n)[::-1] * STEP
    clean = np.cos(OMEGA * t + PHASE)
    sigma2 = 0.5 / 10 ** (snr_db / 10)
    errors, misses = [], 0
    for _ in range(trials):
        y = clean + np.sqrt(sigma2) * rng.standard_normal(n)
        if q > 1:
            y = decimate(y[::-1], q, ftype="fir", zero_phase=True)[::-1]
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            est = identify_tones(y, STEP * q, BAND, max_tones=1, lags=min(lags, y.size // 2 - 1))
        if est.frequencies.size != 1:
            misses += 1
            continue
        errors.append(est.frequencies[0] - OMEGA)
    bound = frequency_bound(t, [OMEGA], [1.0], [PHASE], sigma2)[0]
    rms = float(np.sqrt(np.mean(np.square(errors)))) if errors else float("nan")
    return rms, bound, misses


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--trials", type=int, default=200)
    args = parser.parse_args(argv)
    print(f"host: {os.cpu_count()} CPUs, 1-minute load {os.getloadavg()[0]:.2f}; one tone of "
          f"{OMEGA} rad/s, step {STEP} s, {args.trials} trials per cell")
    q = max(1, int(np.pi / STEP // (1.5 * BAND[1])))
    head = f"{'lags':>5} {'RMS/CRB':>8} {'misses':>6}"
    print(f"{'':>16}| as the law identifies | lags a third of the window | decimated by {q}")
    print(f"{'window':>7} {'SNR dB':>7} | {head} | {head} | {head}")
    for n in WINDOWS:
        for snr in SNR_DB:
            row = []
            for lags, qq in ((DEFAULT_LAGS, 1), (n // 3, 1), (n // (3 * q), q)):
                if n // qq < 32:
                    row.append(f"{'(window too short)':>21}")
                    continue
                lags = max(3, min(lags, n // (2 * qq) - 1))
                rms, bound, misses = trial_errors(n, snr, lags, args.trials,
                                                  np.random.default_rng([n, int(snr)]), qq)
                row.append(f"{lags:>5} {rms / bound:>8.2f} {misses:>6}")
            print(f"{n:>7} {snr:>7.0f} | " + " | ".join(row))


if __name__ == "__main__":
    main()
