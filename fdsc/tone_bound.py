"""The Cramér–Rao bound of tone frequencies: how well any unbiased identification can do.

A law that predicts the disturbance identifies its tones from samples
``y_k = Σ_i a_i cos(ω_i t_k + φ_i) + v_k`` (``v_k`` white Gaussian, variance σ²). No unbiased
estimator of the frequencies has a smaller covariance than the inverse of the Fisher information,
which for Gaussian noise is ``J = JᵀJ / σ²`` with J the Jacobian of the noiseless samples with
respect to the parameters ``(a_i, ω_i, φ_i)``. :func:`frequency_bound` computes it exactly for any
sampling times and any number of tones (no large-sample approximation); for one tone sampled
uniformly, N samples a step h apart, it tends to the classical

    var(ω̂) ≥ 24 σ² / (a² h² N (N² − 1))            (rad/s)²,

(Rife and Boorstyn 1974; Kay 1993, Example 3.14, in rad/s). An identification is near-efficient
where its frequency error is within a small factor of the bound's standard deviation.
"""

from __future__ import annotations

import numpy as np

from ._validation import as_positive, as_vector

__all__ = ["frequency_bound", "single_tone_bound"]


def frequency_bound(times, frequencies, amplitudes, phases, noise_variance: float) -> np.ndarray:
    """The Cramér–Rao bound of each tone's frequency, exactly, for samples at ``times``.

    Parameters
    ----------
    times : (N,) array_like
        The sampling instants (s).
    frequencies, amplitudes, phases : (K,) array_like
        The tones ``a_i cos(ω_i t + φ_i)``: ω_i in rad/s, a_i ≠ 0.
    noise_variance : float
        σ² of the white Gaussian noise on each sample.

    Returns
    -------
    (K,) ndarray
        The least standard deviation (rad/s) of any unbiased estimate of each ω_i, with the
        amplitudes and phases unknown too.

    Raises
    ------
    ValueError
        If the lengths of the tones' arrays differ, an amplitude is 0, there are fewer samples
        than the 3K parameters, or the Fisher information is singular (two tones at one
        frequency, or a tone at 0 or at the Nyquist frequency, whose frequency the samples
        cannot tell).

    Examples
    --------
    One tone of 20 rad/s, 1,000 samples 10 ms apart (32 periods), SNR a²/(2σ²) = 50: the exact
    bound and the classical large-sample one agree to 1 %.

    >>> t = np.arange(1000) * 0.01
    >>> exact = frequency_bound(t, [20.0], [1.0], [0.4], 0.01)[0]
    >>> bool(abs(exact / single_tone_bound(1000, 0.01, 1.0, 0.01) - 1) < 0.01)
    True
    """
    t = as_vector("times", times)
    w = as_vector("frequencies", frequencies)
    a = as_vector("amplitudes", amplitudes, w.size)
    p = as_vector("phases", phases, w.size)
    s2 = as_positive("noise_variance", noise_variance)
    if np.any(a == 0):
        raise ValueError("amplitudes must be nonzero (a tone of amplitude 0 has no frequency to estimate)")
    K = w.size
    if t.size < 3 * K:
        raise ValueError(f"times: {t.size} samples cannot determine the {3 * K} parameters of {K} tones")
    arg = np.outer(t, w) + p                    # (N, K)
    c, s = np.cos(arg), np.sin(arg)
    J = np.hstack([c, -a * t[:, None] * s, -a * s])   # d/da, d/dω, d/dφ
    info = J.T @ J / s2
    # the Fisher information in units that make it well conditioned (the columns' norms)
    scale = np.sqrt(np.diag(info))
    normed = info / np.outer(scale, scale)
    if np.linalg.cond(normed) > 1e12:
        raise ValueError("the Fisher information is singular: the samples cannot tell these tones' "
                         "frequencies apart (two tones at one frequency, or a tone at 0 or at the "
                         "Nyquist frequency)")
    inv = np.linalg.inv(normed) / np.outer(scale, scale)
    return np.sqrt(np.diag(inv)[K:2 * K])


def single_tone_bound(n: int, step: float, amplitude: float, noise_variance: float) -> float:
    """The classical large-sample bound of one tone's frequency: ``√(24σ² / (a² h² N (N² − 1)))``.

    Parameters
    ----------
    n : int
        N, the number of uniform samples (≥ 2).
    step : float
        h, their spacing (s).
    amplitude : float
        a, the tone's amplitude.
    noise_variance : float
        σ².

    Returns
    -------
    float
        The standard deviation bound (rad/s); :func:`frequency_bound` is exact for any N.

    Examples
    --------
    >>> round(single_tone_bound(100, 0.1, 1.0, 1.0), 6)
    0.048992
    """
    if not isinstance(n, int | np.integer) or isinstance(n, bool) or n < 2:
        raise ValueError(f"n must be a whole number ≥ 2, but found {n!r}")
    h = as_positive("step", step)
    a = abs(float(amplitude))
    if not a > 0 or not np.isfinite(a):
        raise ValueError(f"amplitude must be a nonzero finite number, but found {amplitude!r}")
    s2 = as_positive("noise_variance", noise_variance)
    return float(np.sqrt(24.0 * s2 / (a * a * h * h * n * (n * n - 1.0))))
