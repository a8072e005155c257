"""Certificates that close the gap in the proof of Theorem 1: Lyapunov jumps and the law's regions.

The proof of Theorem 1 (paper eq. (37)) uses ``V = xᵀ P^s_σ x`` and shows, from (T1-1), that V
decreases *between* switches. It never compares V across a switch, where ``P^s`` jumps from
``P^s_i`` to ``P^s_j``, and under the law with the measured ẋ (paper eq. (31), ẋ = A_σ(t⁻) x) a
mode also runs where (T1-1) says nothing. This module poses the conditions that make the
argument complete, for any modes, ranges and Q's, and solves them as LMIs.

**The law's quadratic forms** (d = 0). With ``F_i = [A_i; I]`` and the score of candidate k,
``s_k(ẋ, x) = [ẋ; x]ᵀ (Ψ_k ⊗ Q_k) [ẋ; x]``:

* measured ẋ (``law="previous"``): while i is active, ẋ = A_i x and j beats i where
  ``xᵀ S_ij x > 0`` with ``S_ij = F_iᵀ (Ψ_j⊗Q_j − Ψ_i⊗Q_i) F_i``;
* each candidate's own ẋ (``law="candidate"``): j beats i where ``xᵀ S_ij x > 0`` with
  ``S_ij = F_jᵀ (Ψ_j⊗Q_j) F_j − F_iᵀ (Ψ_i⊗Q_i) F_i`` (so ``S_ji = −S_ij``).

**Where mode i runs.** Mode i is chosen at x either because it was active and no j beats it
(*stay set*: ``xᵀ S_ij x ≤ 0`` for all j ≠ i), or because the active mode k was beaten by i
(*switch-in set*: ``xᵀ S_ki x ≥ 0``). Under the candidate reading the switch-in set lies in the
stay set. Under the measured reading it does not: where ``xᵀ S_ij x > 0`` and ``xᵀ S_ji x > 0``
each mode prefers the other and the sampled law alternates at every sample (the *chattering
region*); there mode i runs on samples where its stay condition fails.

**The certificate** (a multiple Lyapunov function ``V = xᵀ P_σ x``, Branicky 1998; S-procedure
for the sets, Johansson & Rantzer 1998). Find ``P_i ≻ 0``, ``μ_ij, ν_ki, τ_ij ≥ 0`` with

    (flow, stay)       He(P_i A_i) − Σ_j μ_ij S_ij ≺ 0                for every i,
    (flow, switch-in)  He(P_i A_i) + ν_ki S_ki ≺ 0                     for every k ≠ i (measured),
    (jump)             P_j − P_i + τ_ij S_ij ⪯ 0                        for every i ≠ j.

The first makes V decrease while i stays (on ``xᵀ S_ij x ≤ 0`` it gives
``xᵀ He(P_i A_i) x < Σ_j μ_ij xᵀ S_ij x ≤ 0``); Theorem 1's (T1-1), ``He(P^s_i A_i) − S_ij ≺ 0``,
is this condition with μ_ij = 1 (two modes). The second covers the samples on which i runs
after being switched in. The third says that V does not increase when the law switches from i
to j: at such an x, ``xᵀ S_ij x ≥ 0``, so ``xᵀ (P_j − P_i) x ≤ −τ_ij xᵀ S_ij x ≤ 0``. Together:
V decreases along every run of the sampled law with d = 0 (up to the O(Δt) error of sampling
the law), so the switched loop is asymptotically stable — with or without sliding.

With ``condition="common"`` all ``P_i`` are one matrix P (a common quadratic Lyapunov function
on the law's regions; the jump conditions then hold with τ = 0).

*A consequence.* If the chattering region of the measured law holds a point x̄ (both
``x̄ᵀ S_ij x̄ > 0`` and ``x̄ᵀ S_ji x̄ > 0``), the two jump conditions add up to
``τ_ij S_ij + τ_ji S_ji ⪯ 0``, which fails at x̄ unless ``τ_ij = τ_ji = 0``; then
``P_j ⪯ P_i ⪯ P_j``. So wherever the measured law chatters, "no jump up" forces a common P:
a pair of modes without a common quadratic Lyapunov function (such as the paper's) cannot be
certified this way under the measured law.

**With a disturbance** (:func:`certify_switching_gain`, the gap in the proof of statements (2)
and (3)): the same three conditions on ``(x, d)`` with ``F_i = [A_i B; I 0]``, the supply
``Gᵀ diag(I, −γ_i² I) G`` added to the flow conditions (so the stay condition with μ = 1 is
Theorem 1's (T1-2)), the jump condition ``diag(P_j − P_i, 0) + τ_ij S_ij ⪯ 0`` on the
``(x, d)`` switching set, and ``P_i ⪰ 0``. Integrating along a run from ``x(0) = 0``:

    ∫ zᵀz dt ≤ Σ_i γ_i² ∫_{mode i} dᵀd dt − V(T) ≤ Σ_i γ_i² ∫_{mode i} dᵀd dt,

i.e. statement (3) with β_i weighted by the disturbance energy spent in mode i and no residue,
and statement (2) with ``ε_T = 0``.

Numerics: the forms S are scaled to unit norm (the multipliers absorb the scale). The stability
problem is homogeneous in ``(P, μ, ν, τ)``; it is normalized by ``I ⪯ P_i ⪯ κ I`` with
κ = :data:`P_CONDITION_LIMIT`, the modes are divided by the largest ``‖A_i‖`` (a change of time
scale) and the decay margin ε of the flow conditions (``≺ −ε I``) is maximized: the loop is
certified if ε exceeds the strictness margin. Every LMI is evaluated after the solve in the
original data.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import cvxpy as cp
import numpy as np

from ._modes import LAWS
from ._validation import as_choice, as_positive, check_type
from .bands import PHI, Band
from .energy import check_weight
from .exceptions import InfeasibleError, VerificationError
from .kyp import supply_parts
from .lmi import DEFAULT_MARGIN, _sym, solve_checked
from .plant import LTISystem, as_system

__all__ = ["SwitchingCertificate", "switching_forms", "certify_switching", "certify_switching_gain",
           "SWITCH_CONDITIONS", "P_CONDITION_LIMIT", "JUMP_TOL"]

#: The gap-closing conditions: a Lyapunov matrix per mode with jump conditions, or a common one.
SWITCH_CONDITIONS = ("jump", "common")
#: Normalization of the stability certificate: ``I ⪯ P_i ⪯ κ I`` (homogeneous problem).
P_CONDITION_LIMIT = 1e6
#: The jump LMIs are non-strict (a common P meets them with equality); at the solution their
#: largest eigenvalue may exceed 0 by at most this fraction of ``max_i ‖P_i‖``.
JUMP_TOL = 1e-7


@dataclass(frozen=True)
class SwitchingCertificate:
    """A multiple (or common) Lyapunov function certifying the switched loop under the law.

    Parameters
    ----------
    P : list of (n, n) ndarray
        ``P_i`` (symmetric positive (semi)definite), one per mode; all equal for
        ``condition="common"``.
    mu : dict
        Multiplier of the stay set, keyed ``(i, j)``: of ``S_ij`` in mode i's stay condition.
    nu : dict
        Multiplier of the switch-in set, keyed ``(k, i)`` (empty for ``law="candidate"``).
    tau : dict
        Multiplier of the switching set in the jump condition from i to j, keyed ``(i, j)``
        (empty for ``condition="common"``).
    gammas : (I,) ndarray
        γ_i of the gain certificate (NaN for the stability certificate).
    decay : float
        Stability certificate: a decay rate (1/s) of V between switches,
        ``min_i (−λ_max(flow LMI_i) / λ_max(P_i))``, so ``V̇ ≤ −decay·V`` while a mode runs in
        its set. Gain certificate: ``−λ_max`` of the flow LMIs (their margin).
    max_eigs : dict
        Largest eigenvalue of each LMI at the solution, keyed ``("stay", i)``,
        ``("switch-in", k, i)`` and ``("jump", i, j)``.
    law : {"previous", "candidate"}
        Reading of ẋ in the law.
    condition : {"jump", "common"}
        The gap-closing condition.
    status : str
        cvxpy status of the solve.
    solve_time : float
        Wall-clock seconds of the solve.

    Notes
    -----
    Closes the gap in the proof of Theorem 1 (paper eq. (37)): the jumps of V at switches and the
    samples on which the measured-ẋ law (paper eq. (31)) runs a mode outside its stay set.
    """

    P: list
    mu: dict
    nu: dict
    tau: dict
    gammas: np.ndarray
    decay: float
    max_eigs: dict
    law: str
    condition: str
    status: str
    solve_time: float


def _validate(modes, bands, Q, law, condition):
    if not isinstance(modes, list | tuple) or len(modes) < 2:
        raise ValueError(f"modes must list at least two closed loops, found {modes!r:.60}")
    modes = [as_system(m, f"modes[{k}]") for k, m in enumerate(modes)]
    if not isinstance(bands, list | tuple) or len(bands) != len(modes):
        raise ValueError(f"bands must list one range per mode ({len(modes)}), found {bands!r:.80}")
    for k, b in enumerate(bands):
        check_type(f"bands[{k}]", b, Band)
        if b.is_complex:
            raise ValueError(f"bands[{k}]: the law's forms are implemented for real Ψ (LF, HF, "
                             "entire); an MF range is complex")
    n = modes[0].n_states
    for k, m in enumerate(modes):
        if m.A.shape != (n, n) or not np.array_equal(m.B, modes[0].B) or not np.array_equal(
                m.D, modes[0].D) or m.C.shape != modes[0].C.shape:
            raise ValueError(f"modes must share B, D and the state and output dimensions; mode {k} "
                             "differs from mode 0")
    if not isinstance(Q, list | tuple) or len(Q) != len(modes):
        raise ValueError(f"Q must list one matrix per mode ({len(modes)}), found {Q!r:.80}")
    Q = [check_weight(q, n) for q in Q]
    as_choice("law", law, LAWS)
    as_choice("condition", condition, SWITCH_CONDITIONS)
    return modes, list(bands), Q


def _forms(modes, bands, Q, law, with_input):
    """S_ij of the law on x (``with_input=False``) or on (x, d), keyed (i, j), i ≠ j."""
    n = modes[0].n_states
    I = len(modes)  # noqa: E741  (the paper's symbol)
    W = [np.kron(b.psi.real, q) for b, q in zip(bands, Q, strict=True)]
    if with_input:
        F = [np.block([[m.A, m.B], [np.eye(n), np.zeros((n, m.B.shape[1]))]]) for m in modes]
    else:
        F = [np.vstack([m.A, np.eye(n)]) for m in modes]
    S = {}
    for i in range(I):
        for j in range(I):
            if i == j:
                continue
            if law == "previous":
                S[i, j] = _sym(F[i].T @ (W[j] - W[i]) @ F[i])
            else:
                S[i, j] = _sym(F[j].T @ W[j] @ F[j] - F[i].T @ W[i] @ F[i])
    return S


def switching_forms(modes: list[LTISystem], bands: list[Band], Q: list[np.ndarray], *,
                    law: str = "previous") -> dict:
    """The quadratic forms ``S_ij`` of the switching law with d = 0: j beats i where ``xᵀS_ij x > 0``.

    Parameters
    ----------
    modes : list of LTISystem
        Closed loops ``(A_i, B, C_i, D)`` of the modes (I ≥ 2), sharing B and D.
    bands : list of Band
        Range Ω_i of each mode's law term (real Ψ).
    Q : list of (n, n) array_like
        Q_i of the law (symmetric positive definite).
    law : {"previous", "candidate"}, optional
        Measured ẋ = A_i x of the active mode i, or each candidate's own ẋ = A_j x.

    Returns
    -------
    dict of (int, int) to (n, n) ndarray
        ``S_ij`` for every ordered pair i ≠ j (symmetric).

    Raises
    ------
    ValueError
        If fewer than two modes are given, the lists differ in length, the modes do not share
        B and D, a band is complex, a Q is not symmetric positive definite, or ``law`` is unknown.
    TypeError
        If a band is not a :class:`~fdsc.Band`.

    Notes
    -----
    The law is paper eq. (31), ``σ = argmax_k [ẋ; x]ᵀ (Ψ_k ⊗ Q_k) [ẋ; x]``. Under the measured
    reading, ``−S_ij`` is the Ψ-part of Theorem 1's (T1-1) (paper eq. (33)).

    Examples
    --------
    One state, LF (ϖ = 1) against HF (ϖ = 10), Q's = 1, ẋ = −x: LF scores −1 + 1 = 0 and HF
    scores 1 − 100 = −99, so HF never beats LF:

    >>> from fdsc import LTISystem, Band
    >>> m = LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]])
    >>> S = switching_forms([m, m], [Band.lf(1.0), Band.hf(10.0)], [np.eye(1), np.eye(1)])
    >>> S[0, 1], S[1, 0]
    (array([[-99.]]), array([[99.]]))
    """
    modes, bands, Q = _validate(modes, bands, Q, law, "jump")
    return _forms(modes, bands, Q, law, with_input=False)


def _unit(S):
    """S / ‖S‖₂ and the norm (1 for a zero form)."""
    nrm = float(np.linalg.norm(S, 2))
    return (S / nrm, nrm) if nrm > 0 else (S, 1.0)


def _lmis(n_modes, law, condition, flow, S, P):
    """The stay, switch-in and jump LMI expressions with their multipliers (cvxpy)."""
    nonneg = {"nonneg": True}
    mu = {(i, j): cp.Variable(name=f"mu_{i}{j}", **nonneg) for i in range(n_modes) for j in range(n_modes)
          if i != j}
    nu = ({(k, i): cp.Variable(name=f"nu_{k}{i}", **nonneg) for k in range(n_modes) for i in range(n_modes)
           if k != i} if law == "previous" else {})
    tau = ({(i, j): cp.Variable(name=f"tau_{i}{j}", **nonneg) for i in range(n_modes) for j in range(n_modes)
            if i != j} if condition == "jump" else {})
    flows, jumps = {}, {}
    for i in range(n_modes):
        flows["stay", i] = flow[i] - sum(mu[i, j] * S[i, j] for j in range(n_modes) if j != i)
        for k in range(n_modes):
            if k != i and nu:
                flows["switch-in", k, i] = flow[i] + nu[k, i] * S[k, i]
    for (i, j), t in tau.items():
        jumps["jump", i, j] = P(j) - P(i) + t * S[i, j]
    return flows, jumps, mu, nu, tau


def _evaluate(n_modes, flow_np, S, Pnp, mu, nu, tau):
    """The same LMIs in NumPy at given values (original data)."""
    flows, jumps = {}, {}
    for i in range(n_modes):
        flows["stay", i] = flow_np[i] - sum(mu[i, j] * S[i, j] for j in range(n_modes) if j != i)
        for k in range(n_modes):
            if k != i and nu:
                flows["switch-in", k, i] = flow_np[i] + nu[k, i] * S[k, i]
    for (i, j), t in tau.items():
        jumps["jump", i, j] = Pnp(j) - Pnp(i) + t * S[i, j]
    return flows, jumps


def _check(flows, jumps, Ps, status, what, psd):
    eigs = {k: float(np.linalg.eigvalsh(_sym(M)).max()) for k, M in {**flows, **jumps}.items()}
    bad = {k: eigs[k] for k in flows if not eigs[k] < 0}
    scale = max(float(np.linalg.norm(p, 2)) for p in Ps)
    bad.update({k: eigs[k] for k in jumps if not eigs[k] <= JUMP_TOL * scale})
    if bad:
        raise VerificationError(f"{what}: LMIs not satisfied at the solution: {bad}", status)
    low = min(float(np.linalg.eigvalsh(p).min()) for p in Ps)
    if not (low >= -JUMP_TOL * scale if psd else low > 0):
        raise VerificationError(f"{what}: a P_i is not positive definite (eigenvalue {low:.3g})",
                                status)
    return eigs


def certify_switching(modes: list[LTISystem], bands: list[Band], Q: list[np.ndarray], *,
                      law: str = "previous", condition: str = "jump",
                      margin: float = DEFAULT_MARGIN) -> SwitchingCertificate:
    """Stability (d = 0) of the switched loop under the law, with the jumps of V accounted for.

    Parameters
    ----------
    modes : list of LTISystem
        Closed loops ``(A_i, B, C_i, D)`` (I ≥ 2), sharing B and D; they need not be Hurwitz.
    bands : list of Band
        Range Ω_i of each mode's law term (real Ψ).
    Q : list of (n, n) array_like
        Q_i of the law (symmetric positive definite).
    law : {"previous", "candidate"}, optional
        Reading of ẋ in the law (see :func:`switching_forms`).
    condition : {"jump", "common"}, optional
        One ``P_i`` per mode with the jump conditions, or one common P.
    margin : float, optional
        Strictness margin: the decay margin ε of the normalized problem must exceed it.

    Returns
    -------
    SwitchingCertificate
        ``gammas`` is NaN.

    Raises
    ------
    ValueError, TypeError
        On inputs :func:`switching_forms` rejects, an unknown ``condition``, or a ``margin``
        that is not positive.
    InfeasibleError
        If the best decay margin is not above ``margin`` (no certificate).
    SolverError
        On any other solver failure.
    VerificationError
        If an LMI does not hold at the returned solution.

    Notes
    -----
    The conditions and their derivation are in the module docstring; the stay condition with
    μ_ij = 1 is Theorem 1's (T1-1), paper eq. (33), and the certificate closes the gap in the
    proof of statement (1) (paper eq. (37)).

    Examples
    --------
    Two modes ``−x`` and ``−2x`` share the Lyapunov function x², so both conditions hold:

    >>> from fdsc import LTISystem, Band
    >>> modes = [LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]]),
    ...          LTISystem([[-2.0]], [[1.0]], [[1.0]], [[0.0]])]
    >>> cert = certify_switching(modes, [Band.lf(1.0), Band.hf(10.0)], [np.eye(1), np.eye(1)])
    >>> cert.decay > 0, all(v <= 1e-7 for k, v in cert.max_eigs.items() if k[0] == "jump")
    (True, True)
    """
    modes, bands, Q = _validate(modes, bands, Q, law, condition)
    margin = as_positive("margin", margin)
    n, I = modes[0].n_states, len(modes)  # noqa: E741
    S = _forms(modes, bands, Q, law, with_input=False)
    unit = {k: _unit(s) for k, s in S.items()}
    a = max(float(np.linalg.norm(m.A, 2)) for m in modes)
    if condition == "common":
        Pc = cp.Variable((n, n), symmetric=True, name="P")
        Pv = [Pc] * I
    else:
        Pv = [cp.Variable((n, n), symmetric=True, name=f"P_{i}") for i in range(I)]
    flow = [Pv[i] @ (modes[i].A / a) + (modes[i].A / a).T @ Pv[i] for i in range(I)]
    flows, jumps, mu, nu, tau = _lmis(I, law, condition, flow, {k: u[0] for k, u in unit.items()},
                                      lambda i: Pv[i])
    eps = cp.Variable(name="decay")
    cons = [eps <= 1.0]
    for P in (Pv[:1] if condition == "common" else Pv):
        cons += [P >> np.eye(n), P << P_CONDITION_LIMIT * np.eye(n)]
    cons += [_sym(M) << -eps * np.eye(n) for M in flows.values()]
    cons += [_sym(M) << 0 for M in jumps.values()]
    what = f"switching certificate ({condition}, law={law})"
    t0 = time.perf_counter()
    status = solve_checked(cp.Problem(cp.Maximize(eps), cons), what)
    elapsed = time.perf_counter() - t0
    if not float(eps.value) > margin:
        raise InfeasibleError(f"{what}: no certificate; the best decay margin is "
                              f"{float(eps.value):.3g}, not above margin = {margin:g}",
                              f"{status}, decay margin {float(eps.value):.3g} <= {margin:g}")
    Ps = [_sym(np.array(P.value)) for P in Pv]
    # undo the scaling: flow LMI × a, each S_ij × its norm
    mu_v = {k: a * float(v.value) / unit[k][1] for k, v in mu.items()}
    nu_v = {k: a * float(v.value) / unit[k][1] for k, v in nu.items()}
    tau_v = {k: float(v.value) / unit[k][1] for k, v in tau.items()}
    flow_np = [Ps[i] @ modes[i].A + modes[i].A.T @ Ps[i] for i in range(I)]
    fl, ju = _evaluate(I, flow_np, S, lambda i: Ps[i], mu_v, nu_v, tau_v)
    eigs = _check(fl, ju, Ps, status, what, psd=False)
    top = [float(np.linalg.eigvalsh(p).max()) for p in Ps]
    decay = min(-eigs[k] / top[k[-1]] for k in fl)
    return SwitchingCertificate(Ps, mu_v, nu_v, tau_v, np.full(I, np.nan), decay, eigs, law,
                                condition, status, elapsed)


def certify_switching_gain(modes: list[LTISystem], bands: list[Band], Q: list[np.ndarray], *,
                           law: str = "previous", condition: str = "jump",
                           margin: float = DEFAULT_MARGIN) -> SwitchingCertificate:
    """L2 gains γ_i of the switched loop under the law, with the jumps of V accounted for.

    Minimizes Σ γ_i² subject to the flow, switch-in and jump conditions on ``(x, d)`` (module
    docstring) with ``P_i ⪰ 0``: from ``x(0) = 0``, ``∫zᵀz ≤ Σ_i γ_i² ∫_{mode i} dᵀd`` with no
    switching residue.

    Parameters
    ----------
    modes : list of LTISystem
        Closed loops (I ≥ 2), sharing B and D.
    bands : list of Band
        Range Ω_i of each mode's law term (real Ψ).
    Q : list of (n, n) array_like
        Q_i of the law (symmetric positive definite).
    law : {"previous", "candidate"}, optional
        Reading of ẋ in the law.
    condition : {"jump", "common"}, optional
        One ``P_i`` per mode with the jump conditions, or one common P.
    margin : float, optional
        Strictness margin of the flow LMIs (with the forms scaled to unit norm).

    Returns
    -------
    SwitchingCertificate
        With the γ_i.

    Raises
    ------
    ValueError, TypeError
        As :func:`certify_switching`.
    InfeasibleError
        If no γ's satisfy the conditions.
    SolverError
        On any other solver failure.
    VerificationError
        If an LMI does not hold at the returned solution.

    Notes
    -----
    The stay condition with μ = 1 is Theorem 1's (T1-2), paper eq. (34); the certificate proves
    statements (2) and (3) (paper eqs. (35), (36)) with ε_T = ε_∞ = 0 and β_i weighted by the
    disturbance energy spent in mode i.

    Examples
    --------
    Modes ``1/(s + 1)`` and ``1/(s + 2)`` (H∞ norms 1 and 1/2) with one storage function:

    >>> from fdsc import LTISystem, Band
    >>> modes = [LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]]),
    ...          LTISystem([[-2.0]], [[1.0]], [[1.0]], [[0.0]])]
    >>> cert = certify_switching_gain(modes, [Band.lf(1.0), Band.hf(10.0)],
    ...                               [np.eye(1), np.eye(1)], condition="common")
    >>> bool(np.all(cert.gammas < 1.1)), cert.decay > 0
    (True, True)
    """
    modes, bands, Q = _validate(modes, bands, Q, law, condition)
    margin = as_positive("margin", margin)
    n, I = modes[0].n_states, len(modes)  # noqa: E741
    m = modes[0].B.shape[1]
    S = _forms(modes, bands, Q, law, with_input=True)
    unit = {k: _unit(s) for k, s in S.items()}
    E = np.hstack([np.eye(n), np.zeros((n, m))])
    if condition == "common":
        Pc = cp.Variable((n, n), symmetric=True, name="P")
        Pv = [Pc] * I
    else:
        Pv = [cp.Variable((n, n), symmetric=True, name=f"P_{i}") for i in range(I)]
    g = [cp.Variable(name=f"gamma_sq_{i}", nonneg=True) for i in range(I)]

    def lyap(P, mode):
        # [A B; I 0]ᵀ (Φ⊗P) [A B; I 0], with Φ⊗P = [[0, P], [P, 0]]
        F = np.block([[mode.A, mode.B], [np.eye(n), np.zeros((n, m))]])
        if isinstance(P, cp.Expression):
            return F.T @ cp.bmat([[np.zeros((n, n)), P], [P, np.zeros((n, n))]]) @ F
        return F.T @ np.kron(PHI, P) @ F

    sup = [supply_parts(md.C, md.D) for md in modes]
    flow = [lyap(Pv[i], modes[i]) + sup[i][0] - g[i] * sup[i][1] for i in range(I)]
    flows, jumps, mu, nu, tau = _lmis(I, law, condition, flow, {k: u[0] for k, u in unit.items()},
                                      lambda i: E.T @ Pv[i] @ E)
    cons = [P >> 0 for P in (Pv[:1] if condition == "common" else Pv)]
    cons += [_sym(M) << -margin * np.eye(n + m) for M in flows.values()]
    cons += [_sym(M) << 0 for M in jumps.values()]
    what = f"switching gain certificate ({condition}, law={law})"
    t0 = time.perf_counter()
    status = solve_checked(cp.Problem(cp.Minimize(cp.sum(cp.hstack(g))), cons), what)
    elapsed = time.perf_counter() - t0
    Ps = [_sym(np.array(P.value)) for P in Pv]
    gam = np.sqrt(np.array([max(float(v.value), 0.0) for v in g]))
    mu_v = {k: float(v.value) / unit[k][1] for k, v in mu.items()}
    nu_v = {k: float(v.value) / unit[k][1] for k, v in nu.items()}
    tau_v = {k: float(v.value) / unit[k][1] for k, v in tau.items()}
    flow_np = [lyap(Ps[i], modes[i]) + sup[i][0] - gam[i] ** 2 * sup[i][1] for i in range(I)]
    fl, ju = _evaluate(I, flow_np, S, lambda i: E.T @ Ps[i] @ E, mu_v, nu_v, tau_v)
    eigs = _check(fl, ju, Ps, status, what, psd=True)
    decay = -max(eigs[k] for k in fl)
    return SwitchingCertificate(Ps, mu_v, nu_v, tau_v, gam, decay, eigs, law, condition, status,
                                elapsed)
