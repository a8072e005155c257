"""Scores of the switching law for real signals: the printed first-order scores and a
second-order middle-frequency score.

The law of paper eq. (31) picks ``argmax_i vᵀ W_i v``. For a real trajectory and the printed
scores, ``v = [ẋ; x]`` and ``W_i = Re Ψ_i ⊗ Q_i``. Here every score is a weight on
``v = [ẍ; ẋ; x]`` (3n entries) of the form ``W = m ⊗ Q`` with a real symmetric (3, 3) factor m.

**Average over a real sinusoid.** For ``x(t) = Re(X e^{jωt})`` (X complex), ``ẋ = Re(jωX e^{jωt})``
and ``ẍ = Re(−ω²X e^{jωt})``; for real symmetric Q the averages over a period are
``avg xᵀQx = ½ X*QX``, ``avg ẋᵀQẋ = ω² avg xᵀQx``, ``avg ẍᵀQẍ = ω⁴ avg xᵀQx``,
``avg ẍᵀQx = −ω² avg xᵀQx`` and ``avg ẋᵀQx = avg ẍᵀQẋ = 0``. Hence

    avg vᵀ(m ⊗ Q)v = w(ω) · avg xᵀQx,   w(ω) = m₁₁ω⁴ + m₂₂ω² + m₃₃ − 2 m₁₃ ω²,

the *frequency weight* of the score (:func:`frequency_weight`).

**The printed MF score cannot work.** With m = Re Ψ_MF (order 1),
``vᵀWv = −ẋᵀQẋ − ϖ₁ϖ₂ xᵀQx < 0`` at every instant, whatever the signal. More generally no real
weight on ``[ẋ; x]`` selects a bounded band: its w(ω) = m₂₂ω² + m₃₃ is monotone in ω². A band
``[ϖ₁, ϖ₂]`` needs the quartic ``−(ω² − ϖ₁²)(ω² − ϖ₂²)``, i.e. ẍ.

**Second-order scores** (``order=2``), all with the weight ``−(ω² − ϖ₁²)(ω² − ϖ₂²)`` for MF:

* ``form="product"`` (default): ``−(ẍ + ϖ₁²x)ᵀQ(ẍ + ϖ₂²x)`` (symmetrized). For a single tone
  ``ẍ = −ω²x`` at every instant, so the score is ``−(ω² − ϖ₁²)(ω² − ϖ₂²) xᵀQx`` *at every
  instant*, not only on average: its sign is the band test itself.
* ``form="diagonal"``: ``−ẍᵀQẍ + (ϖ₁² + ϖ₂²)ẋᵀQẋ − ϖ₁²ϖ₂² xᵀQx``; same average, but the ẋ
  term is in quadrature with x, so for a tone the score oscillates about its average and changes
  sign within a period.

For LF and HF, ``order=2`` gives the product form ``±(ẍᵀQx + ϖ²xᵀQx)`` with weights
``ϖ_l² − ω²`` and ``ω² − ϖ_h²``, the printed first-order weights.

The cost: ẍ must be measured or estimated. With ``ẋ = A_σ x + B d``, ``ẍ = A_σ ẋ + B ḋ``; the
disturbance's derivative enters, and an estimate by differencing ẋ adds a lag and amplifies noise.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from ._validation import as_choice, as_matrix, as_vector, check_type
from .bands import Band
from .energy import check_weight
from .exceptions import DimensionError

__all__ = ["score_matrix", "law_weight", "frequency_weight", "score_average", "SCORE_ORDERS",
           "SCORE_FORMS"]

#: Orders of a score: 1 uses ``[ẋ; x]`` (paper eq. (31)), 2 uses ``[ẍ; ẋ; x]``.
SCORE_ORDERS = (1, 2)
#: Forms of the second-order MF score (see the module docstring).
SCORE_FORMS = ("product", "diagonal")


def score_matrix(band: Band, *, order: int = 1, form: str = "product") -> np.ndarray:
    """The real symmetric (3, 3) factor m of a score ``vᵀ(m ⊗ Q)v`` on ``v = [ẍ; ẋ; x]``.

    Parameters
    ----------
    band : Band
        The score's range (LF, MF, HF or the entire range).
    order : {1, 2}, optional
        1: ``Re Ψ`` of the band on ``[ẋ; x]`` (the printed score, paper eq. (31)); 2: the
        second-order score (LF, MF, HF only).
    form : {"product", "diagonal"}, optional
        Form of the second-order MF score (see the module docstring); "diagonal" exists for MF
        only. Ignored for ``order=1``.

    Returns
    -------
    (3, 3) ndarray
        The factor m (first row and column zero for ``order=1``).

    Raises
    ------
    TypeError
        If ``band`` is not a :class:`~fdsc.Band`.
    ValueError
        If ``order`` or ``form`` is unknown, ``order=2`` is asked for the entire range, or
        ``form="diagonal"`` for a band other than MF.

    Notes
    -----
    Order 1 is ``Re Ψ`` of paper eq. (7) placed on ``[ẋ; x]``, as the law of paper eq. (31) sees it
    for real signals. Order 2 is derived in the module docstring (not in the paper).

    Examples
    --------
    >>> score_matrix(Band.mf(1.0, 10.0), order=2)
    array([[  -1. ,    0. ,  -50.5],
           [   0. ,    0. ,    0. ],
           [ -50.5,    0. , -100. ]])
    >>> score_matrix(Band.hf(10.0))[1:, 1:]
    array([[   1.,    0.],
           [   0., -100.]])
    """
    check_type("band", band, Band)
    order = as_choice("order", order, SCORE_ORDERS)
    form = as_choice("form", form, SCORE_FORMS)
    m = np.zeros((3, 3))
    if order == 1:
        m[1:, 1:] = band.psi.real
        return m
    if band.kind == "EF":
        raise ValueError("order=2 needs a band with limits (LF, MF or HF); the entire range has "
                         "no frequency weight")
    if form == "diagonal" and band.kind != "MF":
        raise ValueError(f"form='diagonal' is defined for the MF band only, found {band.kind}")
    if band.kind == "MF":
        a, b = band.lower**2, band.upper**2
        if form == "product":
            m[0, 0], m[0, 2], m[2, 0], m[2, 2] = -1.0, -(a + b) / 2, -(a + b) / 2, -a * b
        else:
            m[0, 0], m[1, 1], m[2, 2] = -1.0, a + b, -a * b
        return m
    # LF: ẍᵀQx + ϖ²xᵀQx has the weight ϖ² − ω²; HF is its negative with ϖ = ϖ_h
    s = 1.0 if band.kind == "LF" else -1.0
    w2 = band.upper**2 if band.kind == "LF" else band.lower**2
    m[0, 2] = m[2, 0] = s * 0.5
    m[2, 2] = s * w2
    return m


def law_weight(band: Band, Q: ArrayLike, *, order: int = 1, form: str = "product") -> np.ndarray:
    """The law's weight ``W = m ⊗ Q`` on ``v = [ẍ; ẋ; x]`` (3n × 3n) for one mode.

    Parameters
    ----------
    band : Band
        The score's range.
    Q : (n, n) array_like
        The mode's Q (symmetric positive definite).
    order : {1, 2}, optional
        1: the printed score ``[ẋ; x]ᵀ(Re Ψ ⊗ Q)[ẋ; x]`` (paper eq. (31)) in the lower-right
        2n × 2n block; 2: the second-order score (see :func:`score_matrix`).
    form : {"product", "diagonal"}, optional
        Form of the second-order MF score.

    Returns
    -------
    (3n, 3n) ndarray
        Symmetric weight, for ``law_weights`` of :func:`fdsc.simulate` and :class:`fdsc.Case`.

    Raises
    ------
    TypeError
        If ``band`` is not a :class:`~fdsc.Band`.
    ValueError
        If Q is not symmetric positive definite, or ``order``/``form`` are invalid (see
        :func:`score_matrix`).
    DimensionError
        If Q is not square.

    Notes
    -----
    The printed MF score (``order=1``) is ``−ẋᵀQẋ − ϖ₁ϖ₂xᵀQx``: negative at every instant.

    Examples
    --------
    >>> W = law_weight(Band.mf(1.0, 10.0), np.eye(1))
    >>> W
    array([[  0.,   0.,   0.],
           [  0.,  -1.,   0.],
           [  0.,   0., -10.]])
    >>> law_weight(Band.mf(1.0, 10.0), np.eye(1), order=2)[0]
    array([ -1. ,   0. , -50.5])
    """
    m = score_matrix(band, order=order, form=form)
    Qa = np.asarray(Q)
    if Qa.ndim != 2 or Qa.shape[0] != Qa.shape[1]:
        raise DimensionError(f"Q must be a square 2-D array, but found shape {Qa.shape}")
    Q = check_weight(Qa, Qa.shape[0])
    return np.kron(m, Q)


def frequency_weight(band: Band, omega: ArrayLike, *, order: int = 1,
                     form: str = "product") -> np.ndarray:
    """The score's weight w(ω): its average over a real sinusoid at ω divided by avg xᵀQx.

    Parameters
    ----------
    band : Band
        The score's range.
    omega : float or array_like
        Frequencies in rad/s (finite, real).
    order : {1, 2}, optional
        Order of the score (see :func:`score_matrix`).
    form : {"product", "diagonal"}, optional
        Form of the second-order MF score.

    Returns
    -------
    ndarray
        ``w(ω) = m₁₁ω⁴ + m₂₂ω² + m₃₃ − 2m₁₃ω²``, of the shape of ``omega``.

    Raises
    ------
    TypeError, ValueError
        As :func:`score_matrix`; ValueError also for a non-finite or complex ``omega``.

    Notes
    -----
    For ``order=1`` this is :meth:`fdsc.Band.real_weight`, ``Re([jω;1]*Ψ[jω;1])`` of paper
    eq. (7): for MF ``−(ω² + ϖ₁ϖ₂)``, negative at every frequency. For ``order=2`` and MF it is
    ``−(ω² − ϖ₁²)(ω² − ϖ₂²)``, positive exactly inside ``(ϖ₁, ϖ₂)``.

    Examples
    --------
    >>> mf = Band.mf(1.0, 10.0)
    >>> frequency_weight(mf, [0.5, 2.0, 20.0])
    array([ -10.25,  -14.  , -410.  ])
    >>> frequency_weight(mf, [0.5, 2.0, 20.0], order=2)
    array([-7.48125e+01,  2.88000e+02, -1.19700e+05])
    """
    m = score_matrix(band, order=order, form=form)
    w = as_vector("omega", np.ravel(omega)).reshape(np.shape(omega))
    w2 = w**2
    return m[0, 0] * w2**2 + (m[1, 1] - 2.0 * m[0, 2]) * w2 + m[2, 2]


def score_average(W: ArrayLike, omega: ArrayLike, X: ArrayLike) -> np.ndarray:
    """Average of ``vᵀWv`` over a period for the real sinusoid ``x(t) = Re(X e^{jωt})``.

    Parameters
    ----------
    W : (3n, 3n) or (2n, 2n) array_like
        Symmetric weight on ``[ẍ; ẋ; x]`` or ``[ẋ; x]``.
    omega : float or array_like
        Frequencies in rad/s (finite, real, > 0 for a proper period; 0 gives the constant X.real).
    X : (n,) array_like
        Complex amplitude (phasor) of x.

    Returns
    -------
    ndarray
        ``½ Re(V* W V)`` with ``V = [(jω)²X; jωX; X]`` (or ``[jωX; X]``), of the shape of
        ``omega``.

    Raises
    ------
    DimensionError
        If W is not (3n, 3n) or (2n, 2n) for the n entries of X.
    ValueError
        If W is not symmetric or an entry is not finite.

    Notes
    -----
    For ``W = m ⊗ Q`` this equals ``frequency_weight(…)(ω) · ½ X*QX`` (module docstring): the
    independent check of :func:`frequency_weight`. For ω = 0 the "sinusoid" is constant only if X
    is real; the formula then averages nothing and returns ``½ X*WX``-type values.

    Examples
    --------
    >>> W = law_weight(Band.mf(1.0, 10.0), np.eye(1), order=2)
    >>> float(score_average(W, 2.0, [1.0]))    # w(2) = 288, avg x² = 1/2
    144.0
    """
    X = np.atleast_1d(np.asarray(X, dtype=complex))
    if X.ndim != 1 or not np.all(np.isfinite(X)):
        raise ValueError(f"X must be a finite 1-D complex vector, but found shape {X.shape}")
    n = X.size
    W = as_matrix("W", W, square=True)
    if W.shape[0] not in (2 * n, 3 * n):
        raise DimensionError(f"W must be ({3 * n}, {3 * n}) on [ẍ; ẋ; x] or ({2 * n}, {2 * n}) on "
                             f"[ẋ; x] for X with {n} entries, but found {W.shape}")
    if not np.allclose(W, W.T, rtol=1e-12, atol=1e-12 * max(1.0, float(np.abs(W).max()))):
        raise ValueError("W must be symmetric")
    w = as_vector("omega", np.ravel(omega))
    k = W.shape[0] // n
    # V = [(jω)^(k−1) X; …; jω X; X], one row per frequency
    V = np.concatenate([((1j * w) ** p)[:, None] * X[None, :] for p in range(k - 1, -1, -1)],
                       axis=1)
    out = 0.5 * np.real(np.einsum("ki,ij,kj->k", V.conj(), W, V))
    return out.reshape(np.shape(omega))
