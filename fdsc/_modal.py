"""Exact runs of a stable LTI system driven by sums of exponentials, in its eigenbasis.

Internal: the engine of the non-causal limit (:mod:`fdsc.noncausal`), of the feedforward laws
(:mod:`fdsc.feedforward`) and of the tuning of controllers that read ŵ (:mod:`fdsc.tuning`).

On a piece of length L the system ``ẋ = A x + Σ_k b_k e^{s_k (τ − a_k)}``,
``z = C x + Σ_k d_k e^{s_k (τ − a_k)}`` (τ ∈ [0, L] the time since the piece began, the complex
vectors ``b_k``, ``d_k`` in conjugate pairs so that x and z are real) has the state, in the
eigenbasis ``A = V Λ V⁻¹``,

    η_p(τ) = e^{λ_p τ} h_p + Σ_k β_pk e^{s_k (τ − a_k)} / (s_k − λ_p),
    h_p = η_p(0) − Σ_k β_pk e^{−s_k a_k} / (s_k − λ_p),      β = V⁻¹ b,

so z is a sum of terms ``g e^{e (τ − a)}`` with one term per input exponential and one per
mode. Each term is **anchored** where it is largest: an exponential that decays along the piece
(Re s ≤ 0, the tones and the modes) at its start (a = 0), one that grows (Re s > 0, the
backward-decaying tails of an anti-causal signal) at its end (a = L), so no term overflows
however long the piece. Every integral ``∫₀ᴸ e^{p(τ−a)} e^{q(τ−b)} dτ`` is then a closed form in
φ₁(x) = (eˣ − 1)/x and the divided difference of exp with arguments of real part ≤ 0, computed
without cancellation; ``∫ z zᵀ`` is their sum weighted by the terms' coefficients. Exact: no
quadrature, no step, no dependence on the pieces' lengths.

Requires A diagonalizable with a well-conditioned eigenbasis (:data:`EIG_COND`) and no input
exponential on a pole (``s_k ≠ λ_p``); both are checked and refused by name.
"""

from __future__ import annotations

import numpy as np

from .exceptions import UnstableError

__all__ = []

#: The largest condition number of the eigenbasis the engine accepts.
EIG_COND = 1e8
#: Below this |x| φ₁(x) is summed as its Taylor series.
_SERIES = 0.25


def phi1(x):
    """φ₁(x) = (eˣ − 1)/x elementwise for complex x (1 at 0), accurate for every x with Re x ≤ 0
    and |x| moderate."""
    x = np.asarray(x, dtype=complex)
    out = np.empty_like(x)
    small = np.abs(x) < _SERIES
    xs = x[small]
    term = np.ones_like(xs)
    acc = np.ones_like(xs)
    for k in range(2, 16):
        term = term * xs / k
        acc = acc + term
    out[small] = acc
    xl = x[~small]
    out[~small] = (np.exp(xl) - 1.0) / xl
    return out


def divided(x, y):
    """(eˣ − eʸ)/(x − y) elementwise for Re x, Re y ≤ 0 (eˣ where x = y), without cancellation."""
    x, y = np.broadcast_arrays(np.asarray(x, dtype=complex), np.asarray(y, dtype=complex))
    first = (x - y).real <= 0                       # e^y φ₁(x − y) with Re(x − y) ≤ 0, else swapped
    lo = np.where(first, y, x)
    hi = np.where(first, x, y)
    return np.exp(lo) * phi1(hi - lo)


def pair_integrals(p, ap, q, aq, L, *, pairs=False):
    """``I[i, j] = ∫₀ᴸ e^{p_i (τ − ap_i L)} e^{q_j (τ − aq_j L)} dτ`` for exponents p, q and anchors
    ap, aq in {0, 1} (start or end of the piece), each term bounded on the piece; with ``pairs``,
    ``I[i] = ∫₀ᴸ e^{p_i (τ − ap_i L)} e^{q_i (τ − aq_i L)} dτ`` (p and q of one length)."""
    p, q = np.asarray(p, dtype=complex), np.asarray(q, dtype=complex)
    ap, aq = np.asarray(ap, dtype=bool), np.asarray(aq, dtype=bool)
    if pairs:
        P, Qm, AP, AQ = p, q, ap, aq
    else:
        P, Qm = np.broadcast_arrays(p[:, None], q[None, :])
        AP, AQ = np.broadcast_arrays(ap[:, None], aq[None, :])
    out = np.empty(P.shape, dtype=complex)
    both0 = ~AP & ~AQ
    bothL = AP & AQ
    mixed = AP != AQ
    out[both0] = L * phi1((P[both0] + Qm[both0]) * L)
    out[bothL] = L * phi1(-(P[bothL] + Qm[bothL]) * L)
    # one anchored at 0 (exponent e0, Re ≤ 0), the other at L (exponent eL, Re ≥ 0):
    # ∫ e^{e0 τ} e^{eL (τ − L)} = (e^{e0 L} − e^{−eL L}) / (e0 + eL)
    if np.any(mixed):
        e0 = np.where(AP, Qm, P)[mixed]
        eL = np.where(AP, P, Qm)[mixed]
        out[mixed] = L * divided(e0 * L, -eL * L)
    return out


class Modal:
    """The eigenbasis of a stable A with C (module docstring)."""

    def __init__(self, A, C, where="the system"):
        A = np.asarray(A, dtype=float)
        lam, V = np.linalg.eig(A)
        if lam.size and np.max(lam.real) >= 0:
            k = int(np.argmax(lam.real))
            raise UnstableError(f"{where} is not Hurwitz (an eigenvalue at {complex(lam[k]):.4g})",
                                complex(lam[k]))
        if lam.size and np.linalg.cond(V) > EIG_COND:
            raise ValueError(f"{where}: its eigenbasis is ill-conditioned (condition number "
                             f"{np.linalg.cond(V):.3g} > {EIG_COND:.0e}); balance or reduce the realization")
        self.A, self.lam, self.V, self.Vi = A, lam, V, np.linalg.inv(V) if lam.size else V
        self.C = np.asarray(C, dtype=float)
        self.CV = self.C @ V

    def piece(self, x0, s, a, b, d, L):
        """One piece: ``(e, anchors, g, x(L))`` with z(τ) = Σ_t g_t e^{e_t (τ − anchors_t L)}.

        Parameters: x0 (n,), s (K,) complex exponents, a (K,) bool anchors (True: at the piece's
        end), b (K, n) and d (K, p) complex coefficients, L > 0.
        """
        lam = self.lam
        s = np.asarray(s, dtype=complex)
        a = np.asarray(a, dtype=bool)
        beta = np.asarray(b, dtype=complex) @ self.Vi.T                  # (K, n) in the eigenbasis
        den = s[:, None] - lam[None, :]                                    # (K, n)
        if den.size and np.min(np.abs(den)) <= 1e-10 * (1.0 + np.max(np.abs(lam))):
            raise ValueError("an input exponential lies on a pole of the system (resonance): the "
                             "engine's closed form does not apply")
        coef = beta / den                                                  # particular part
        at0 = np.ones(s.size, dtype=complex)                               # e^{−s a L}
        at0[a] = np.exp(-s[a] * L)
        h = self.Vi @ np.asarray(x0, dtype=float) - (coef * at0[:, None]).sum(axis=0)
        g_in = coef @ self.CV.T + np.asarray(d, dtype=complex)             # (K, p)
        g_md = (self.CV * h[None, :]).T                                    # (n, p)
        e = np.concatenate([s, lam])
        anchors = np.concatenate([a, np.zeros(lam.size, dtype=bool)])
        g = np.vstack([g_in, g_md])
        ends = np.ones(s.size, dtype=complex)                              # e^{s (L − a L)}
        ends[~a] = np.exp(s[~a] * L)
        eta = np.exp(lam * L) * h + (coef * ends[:, None]).sum(axis=0)
        xL = (self.V @ eta).real
        return e, anchors, g, xL

    @staticmethod
    def gram(e, anchors, g, L, *, bound=False):
        """``∫₀ᴸ z zᵀ dτ`` (p, p) of z(τ) = Σ_t g_t e^{e_t (τ − anchors_t L)} (real z); with
        ``bound``, also ``Σ_ij |g_i|·|I_ij|·|g_j|`` ≥ its trace, the size of the terms it sums
        (its trace has lost its digits to cancellation where it is ≲ eps times this).

        Terms of the same exponent and anchor are first summed into one (z is linear in their
        coefficients: the disturbance and an exact estimate of it give the same tones), and the
        integrals' matrix, Hermitian (``I_ji`` is the conjugate of ``I_ij``), is formed on and
        above its diagonal only."""
        ee, an, g = _merged(np.asarray(e, dtype=complex), np.asarray(anchors, dtype=bool), np.asarray(g))
        Imat = _hermitian_integrals(ee, an, L)
        G = (g.conj().T @ Imat @ g).real
        if not bound:
            return G
        ag = np.abs(g)
        return G, float(np.sum(ag * (np.abs(Imat) @ ag)))


def _merged(e, anchors, g):
    """The terms with equal exponent and anchor summed into the first of them (order kept)."""
    if e.size < 2:
        return e, anchors, g
    keys = list(zip(e.real.tolist(), e.imag.tolist(), anchors.tolist(), strict=True))
    first = {}
    for t, key in enumerate(keys):
        first.setdefault(key, t)
    if len(first) == e.size:
        return e, anchors, g
    keep = np.fromiter(first.values(), dtype=np.int64, count=len(first))
    slot = {key: r for r, key in enumerate(first)}
    rank = np.fromiter((slot[key] for key in keys), dtype=np.int64, count=e.size)
    merged = np.zeros((keep.size, g.shape[1]), dtype=np.result_type(g, complex))
    np.add.at(merged, rank, g)
    return e[keep], anchors[keep], merged


def _hermitian_integrals(e, anchors, L):
    """``pair_integrals(conj(e), anchors, e, anchors, L)``, formed on and above the diagonal
    (every entry at once where no term is anchored at the piece's end)."""
    if not anchors.any():
        return L * phi1((e.conj()[:, None] + e[None, :]) * L)
    k = e.size
    i, j = np.triu_indices(k)
    vals = pair_integrals(e.conj()[i], anchors[i], e[j], anchors[j], L, pairs=True)
    out = np.empty((k, k), dtype=complex)
    out[i, j] = vals
    out[j, i] = vals.conj()
    return out


def tone_terms(t0, w, amp, ph):
    """Exponents and complex amplitudes of ``Σ_j a_j sin(ω_j t + φ_j)`` as a function of
    τ = t − t0: ``Σ_j c_j e^{jω_j τ} + conj``, returned as (2J,) exponents and (2J,) amplitudes."""
    w, amp, ph = (np.asarray(v, dtype=float) for v in (w, amp, ph))
    c = amp * np.exp(1j * (w * t0 + ph)) / 2j
    return np.concatenate([1j * w, -1j * w]), np.concatenate([c, c.conj()])
