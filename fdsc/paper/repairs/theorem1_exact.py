"""Chapter 'theorem1', continued: the exact counterexample (the return-map proof).

In two states with d = 0 the printed law (paper eq. (31)) is homogeneous: every score is a
quadratic form in x, so the sets where a mode is left are cones bounded by rays through 0, and
between two rays the loop runs one linear mode, x(t) = e^{A_i t} x. The growth from a switching
ray back to the same ray is then an exact product of the gains of matrix exponentials, with the
crossing times in closed form, and it is the same factor for every state on that ray. If no ray
makes the law slide (paper Remark 7, Theorem 1's no-sliding hypothesis) and the factor exceeds 1,
every run that switches diverges although Theorem 1's LMIs hold: a counterexample with no
sampling, horizon or tolerance in it.

**The law on rays.** With the forms ``S_ij`` of :func:`fdsc.switching_forms`, mode i is left
where ``xᵀ S_ij x > 0``. On the unit circle ``q_i(θ) = u(θ)ᵀ S_ij u(θ)`` with ``u = (cos θ,
sin θ)`` is ``m + R cos(2θ − φ)``, so its zeros are at most two lines (four rays), found in
closed form. A mode whose eigenvalues are complex turns monotonically (its angular speed
``u⊥ᵀ A u`` has one sign on the circle), so it leaves through the first of its *exit rays* (zeros
where ``q_i`` turns positive in its sense of rotation) that it meets, and no other ray can come
first. Exit rays come in antipodal pairs (``q_i`` is even), so from an exit ray of one mode the
other mode runs to its own exit ray, which is less than half a turn away, and the first mode
then runs back to the first mode's exit line: one cycle has two switches, the return map to a
ray is linear and, by the odd symmetry x → −x, half a turn gives the whole turn.

**Transversality.** At a switch from i to j on the unit ray r (unit normal n pointing in i's
sense of rotation), both flows cross the ray in the same direction if ``nᵀA_0 r`` and ``nᵀA_1 r``
are both positive; and j keeps the lead it was switched in with if ``rᵀ S_ji r < 0`` (under the
measured ẋ the two modes' sets differ, and where ``xᵀS_ij x > 0`` and ``xᵀS_ji x > 0`` each mode
prefers the other: the sampled law alternates at every sample, the chattering region). Under
each candidate's own ẋ, ``S_ji = −S_ij`` and the ray is common to both modes; j then keeps the
lead exactly when its flow leaves the ray into its own cone, i.e. when the two flows cross in
the same direction; if they point against each other the ray is a Filippov sliding ray.
"""

from dataclasses import dataclass

import numpy as np

from fdsc._dwell_signals import switched_states
from fdsc.exceptions import DimensionError
from fdsc.lyapunov_jumps import switching_forms
from fdsc.paper.repairs.theorem1_witness import lmi_witness
from fdsc.paper.shared.prose import num, times

__all__ = ["ExactTurn", "exact_turn", "exact_applies", "q_scaling_turns", "RAY_TOL", "CONE_LABELS",
           "Q_SCALES"]

#: A switch counts as landing on the entering mode's own boundary (decided by its flow) if
#: ``|rᵀ S_ji r| / ‖S_ji‖₂`` is at most this.
RAY_TOL = 1e-9

#: Labels of a cone between two zeros of the law's forms (see :meth:`ExactTurn.cones`).
CONE_LABELS = ("mode 0", "mode 1", "either", "chattering")

_TWO_PI = 2.0 * np.pi

#: Factors applied to Q_0 by :func:`q_scaling_turns`.
Q_SCALES = (1e-4, 1e-2, 1.0, 1e2, 1e4, 1e6, 2e6, 3e6, 1e7)


def _zeros(S):
    """Angles in [0, 2π) where ``u(θ)ᵀ S u(θ) = 0`` changes sign, sorted (none if S is semidefinite)."""
    a, b, c = S[0, 0], S[0, 1], S[1, 1]
    m, h = 0.5 * (a + c), 0.5 * (a - c)
    R = float(np.hypot(h, b))
    if R <= abs(m):
        return np.zeros(0)
    phi, d = np.arctan2(b, h), np.arccos(-m / R)
    th = 0.5 * np.array([phi + d, phi - d])
    return np.sort(np.concatenate([th, th + np.pi]) % _TWO_PI)


def _slope(S, th):
    """dq/dθ of ``q(θ) = u(θ)ᵀ S u(θ)``."""
    u, up = _unit(th), _normal(th)
    return 2.0 * float(u @ S @ up)


def _unit(th):
    return np.array([np.cos(th), np.sin(th)])


def _normal(th):
    return np.array([-np.sin(th), np.cos(th)])


def _ahead(frm, to, sense):
    """Angle in [0, 2π) swept from ``frm`` to ``to`` turning in ``sense`` (+1 ccw, −1 cw)."""
    return float((sense * (to - frm)) % _TWO_PI)


def _crossing(A, x, th, alpha, beta):
    """First t > 0 at which e^{At} x lies on the line at angle th, and e^{At} x there.

    With eigenvalues α ± jβ, ``e^{At} = e^{αt}(cos βt·I + sin βt·N)``, ``N = (A − αI)/β``, so
    ``nᵀ e^{At} x = e^{αt}(a cos βt + b sin βt)`` with ``a = nᵀx``, ``b = nᵀNx``: its zeros are
    βt = atan2(−a, b) + kπ, one per half turn of the flow.
    """
    n = _normal(th)
    N = (A - alpha * np.eye(2)) / beta
    a, b = float(n @ x), float(n @ N @ x)
    phase = float(np.arctan2(-a, b) % np.pi)
    t = (phase if phase > 0 else np.pi) / beta
    return t, np.exp(alpha * t) * (np.cos(beta * t) * x + np.sin(beta * t) * (N @ x))


@dataclass(frozen=True)
class ExactTurn:
    """The return map of the printed law in two states with d = 0 (see :func:`exact_turn`).

    Parameters
    ----------
    law : {"previous", "candidate"}
        Reading of ẋ: measured (as printed) or each candidate's own.
    A : (2, 2, 2) ndarray
        The modes' state matrices.
    S : (2, 2, 2) ndarray
        ``S[i]``: mode i is left where ``xᵀ S[i] x > 0`` (the forms S_01, S_10).
    sense : (2,) ndarray of int
        Sense of rotation of each mode's flow (+1 counter-clockwise, −1 clockwise).
    start_angle : float
        The ray the cycle starts on (rad): an exit ray of mode ``1 − start_mode``, where
        ``start_mode`` is switched in.
    start_mode : int
        The mode that runs first.
    angles : (2,) ndarray
        Rays (rad, in [0, 2π)) of the cycle's two switches; the second lies on the start's line.
    leaving : (2,) ndarray of int
        Mode left at each switch.
    dwells : (2,) ndarray
        Crossing times (s): how long each mode runs before its switch.
    gains : (2,) ndarray
        ``‖x‖`` at each switch over ``‖x‖`` at the previous one (exact: ``‖e^{A t} r‖``).
    normal_speeds : (2, 2) ndarray
        ``normal_speeds[k, i] = nᵀ A_i r`` (rad/s) on the ray of switch k, with n the unit normal
        in the leaving mode's sense: both positive if both flows cross the ray the same way.
    entry_margins : (2,) ndarray
        ``−rᵀ S_j r / ‖S_j‖₂`` of the entering mode j at each switch: its lead when switched in
        (0 on the common ray of the candidate reading).
    sliding : (2,) ndarray of bool
        The entering mode is beaten at once (it was switched in where it loses, or the two
        flows point against each other): the switch starts sliding or chattering.
    lmi_holds : bool
        Theorem 1's LMIs (paper eqs. (33), (34)) hold at the explicit witness of
        :func:`fdsc.paper.repairs.theorem1_witness.lmi_witness` (checked by eigenvalues).
    gammas : (2,) ndarray
        γ_i of that witness.
    """

    law: str
    A: np.ndarray
    S: np.ndarray
    sense: np.ndarray
    start_angle: float
    start_mode: int
    angles: np.ndarray
    leaving: np.ndarray
    dwells: np.ndarray
    gains: np.ndarray
    normal_speeds: np.ndarray
    entry_margins: np.ndarray
    sliding: np.ndarray
    lmi_holds: bool
    gammas: np.ndarray

    @property
    def clean(self) -> bool:
        """No switch of the cycle slides (Theorem 1's no-sliding hypothesis holds on it)."""
        return not bool(self.sliding.any())

    @property
    def antipodal(self) -> bool:
        """The cycle ends on the ray opposite its start (half a turn), not on the start itself."""
        # the second switch lies on the start's line: 0 or π ahead of the start
        return bool(abs(_ahead(self.start_angle, self.angles[1], 1) - np.pi) < 0.5 * np.pi)

    @property
    def multiplier(self) -> float:
        """Growth of ‖x‖ from a ray back to the same ray (one full turn when both modes turn the
        same way): ``(g₀g₁)²`` after a half turn, ``g₀g₁`` otherwise; NaN if a switch slides."""
        if not self.clean:
            return float("nan")
        g = float(np.prod(self.gains))
        return g * g if self.antipodal else g

    @property
    def period(self) -> float:
        """Time (s) from a ray back to the same ray."""
        return float(self.dwells.sum()) * (2.0 if self.antipodal else 1.0)

    @property
    def growth_rate(self) -> float:
        """Exponential growth rate ``log(multiplier)/period`` (1/s) of every run that switches."""
        return float(np.log(self.multiplier) / self.period)

    @property
    def proves_divergence(self) -> bool:
        """Theorem 1's LMIs hold, no switch slides, and the multiplier exceeds 1."""
        return bool(self.lmi_holds and self.clean and self.multiplier > 1.0)

    def cones(self) -> list:
        """The cones between consecutive zeros of both forms, labelled at their bisectors.

        Returns
        -------
        list of (float, float, str)
            ``(start, end, label)`` with angles in rad (``end`` may exceed 2π for the cone that
            wraps around) and the label one of :data:`CONE_LABELS`: the mode that runs there,
            "either" (neither is left: the active one stays) or "chattering" (each is left).
        """
        z = np.unique(np.concatenate([_zeros(s) for s in self.S]))
        if z.size == 0:
            z = np.array([0.0])
        ends = np.append(z[1:], z[0] + _TWO_PI)
        out = []
        for lo, hi in zip(z, ends, strict=True):
            u = _unit(0.5 * (lo + hi))
            left = [float(u @ s @ u) > 0 for s in self.S]
            label = CONE_LABELS[3 if all(left) else 2 if not any(left) else 1 if left[0] else 0]
            out.append((float(lo), float(hi), label))
        return out

    def switch_times(self, turns: int = 1) -> tuple[np.ndarray, np.ndarray]:
        """Switching instants and the mode sequence of ``turns`` returns to the start ray.

        Parameters
        ----------
        turns : int, optional
            Number of returns (≥ 1).

        Returns
        -------
        switch_times : (m,) ndarray
            Instants (s) of the switches, the start at t = 0.
        sequence : (m + 1,) ndarray of int
            Active mode on each interval.
        """
        if int(turns) < 1:
            raise ValueError(f"turns must be at least 1, but found {turns!r}")
        reps = int(turns) * (2 if self.antipodal else 1)
        times_ = np.cumsum(np.tile(self.dwells, reps))
        seq = np.tile([self.start_mode, 1 - self.start_mode], reps + 1)[: times_.size + 1]
        return times_, seq

    def trajectory(self, turns: int = 1, samples: int = 400) -> tuple[np.ndarray, np.ndarray]:
        """The exact run from the unit state on the start ray over ``turns`` returns.

        Computed with :func:`fdsc.switched_states` (matrix exponentials), independently of the
        closed-form crossings.

        Parameters
        ----------
        turns : int, optional
            Number of returns to the start ray (≥ 1).
        samples : int, optional
            Samples per dwell (≥ 2), each switching instant included.

        Returns
        -------
        t : (k,) ndarray
            Times (s).
        x : (k, 2) ndarray
            States.
        """
        st, seq = self.switch_times(turns)
        edges = np.concatenate([[0.0], st])
        t = np.unique(np.concatenate([np.linspace(a, b, int(samples))
                                      for a, b in zip(edges[:-1], edges[1:], strict=True)]))
        return t, switched_states(list(self.A), _unit(self.start_angle), st, seq, t)

    def rows(self) -> list:
        """The cycle's switches as a table, every cell text (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        list of dict
            Per switch: the ray (degrees), the switch, the crossing time, the gain since the
            previous switch, both modes' normal speeds, the entry margin and whether it slides.
        """
        return [{"ray [°]": num(float(np.degrees(th))), "switch": f"mode {i} → mode {1 - i}",
                 "crossing time [s]": num(float(t)), "gain of ‖x‖": times(float(g)),
                 "normal speed, mode 0 [rad/s]": num(float(sp[0])),
                 "normal speed, mode 1 [rad/s]": num(float(sp[1])),
                 "entry margin": num(float(e)), "slides": "yes" if sl else "no"}
                for th, i, t, g, sp, e, sl in zip(self.angles, self.leaving, self.dwells,
                                                  self.gains, self.normal_speeds,
                                                  self.entry_margins, self.sliding, strict=True)]

    def prose(self) -> dict:
        """The return map's numbers as text (:mod:`fdsc.paper.shared.prose`).

        Returns
        -------
        dict of str
            ``multiplier`` (×, per return to the same ray), ``half`` (per half turn),
            ``period`` (s), ``rate`` (1/s), ``dwell_0``, ``dwell_1`` (s, per mode),
            ``angle_0``, ``angle_1`` (degrees of the two switching rays), ``speed_min``
            (smallest normal speed, rad/s), ``margin_min`` (smallest entry margin),
            ``gamma`` (the witness's γ's), ``lmi`` ("hold" or "fail").
        """
        dw = {int(m): float(d) for m, d in zip(self.leaving, self.dwells, strict=True)}
        return {"multiplier": times(self.multiplier),
                "half": times(float(np.prod(self.gains))),
                "period": num(self.period), "rate": num(self.growth_rate),
                "dwell_0": num(dw[0]), "dwell_1": num(dw[1]),
                "angle_0": num(float(np.degrees(self.angles[0]))),
                "angle_1": num(float(np.degrees(self.angles[1]))),
                "speed_min": num(float(self.normal_speeds.min())),
                "margin_min": num(float(self.entry_margins.min())),
                "gamma": " and ".join(num(float(g)) for g in self.gammas),
                "lmi": "hold" if self.lmi_holds else "fail"}


def _validate(modes, bands, Q, law):
    if not isinstance(modes, list | tuple) or len(modes) != 2:
        raise ValueError(f"modes must list exactly two closed loops, but found {modes!r:.60}")
    S = switching_forms(list(modes), bands, Q, law=law)
    A = np.array([np.asarray(m.A, dtype=float) for m in modes])
    if A.shape[1:] != (2, 2):
        raise DimensionError(f"modes must have 2 states (the law's sets are cones in the plane), "
                             f"but found A of shape {A.shape[1:]}")
    spin = []
    for i, a in enumerate(A):
        ev = np.linalg.eigvals(a)
        if abs(ev[0].imag) == 0.0:
            raise ValueError(f"mode {i} must have complex eigenvalues (a flow that turns), but "
                             f"found {ev.real}: a real mode need not leave its cone")
        spin.append((float(ev[0].real), abs(float(ev[0].imag))))
    forms = np.array([S[0, 1], S[1, 0]])
    for i, s in enumerate(forms):
        if _zeros(s).size == 0:
            raise ValueError(f"mode {i} has no exit ray (its switching form is semidefinite): "
                             "once active it is never left, or left everywhere")
    return A, forms, spin


def exact_applies(modes, bands, Q, *, law: str = "previous") -> bool:
    """Whether :func:`exact_turn` applies: two 2-state modes whose flows turn, each with an exit ray.

    Parameters
    ----------
    modes, bands, Q, law
        As for :func:`exact_turn`.

    Returns
    -------
    bool
        False for more than 2 states, a mode with real eigenvalues or a semidefinite form (the
        return map does not exist or is not the whole story); the inputs are not validated.
    """
    if len(modes) != 2 or any(np.shape(m.A) != (2, 2) for m in modes):
        return False
    if any(np.linalg.eigvals(np.asarray(m.A, dtype=float))[0].imag == 0.0 for m in modes):
        return False
    S = switching_forms(list(modes), bands, Q, law=law)
    return all(_zeros(S[i, 1 - i]).size > 0 for i in range(2))


def _exits(S, sense):
    """Exit rays of a mode: zeros of its form where it turns positive in the mode's sense."""
    return np.array([th for th in _zeros(S) if sense * _slope(S, th) > 0])


def _switch(A, S, sense, th, i, ray_tol):
    """Normal speeds, entry margin and sliding flag of the switch i → j on the ray th."""
    j = 1 - i
    r, n = _unit(th), sense[i] * _normal(th)
    speeds = np.array([float(n @ a @ r) for a in A])
    lead = -float(r @ S[j] @ r) / float(np.linalg.norm(S[j], 2))
    if abs(lead) > ray_tol:
        return speeds, lead, lead < 0
    # on j's own boundary: j stays only if its flow leaves the ray into its own cone
    return speeds, 0.0, bool(sense[j] * _slope(S[j], th) >= 0)


def exact_turn(modes, bands, Q, *, law: str = "previous", start_mode: int = 0,
               ray_tol: float = RAY_TOL) -> ExactTurn:
    """The exact return map of the printed law for two 2-state modes with d = 0.

    Parameters
    ----------
    modes : sequence of two LTISystem
        Closed loops ``(A_i, B, C_i, D)`` with 2 states, sharing B and D; each A_i with complex
        eigenvalues (its flow turns about 0).
    bands : sequence of two Band
        Range Ω_i of each mode's score (real Ψ: LF, HF or the entire range).
    Q : sequence of two (2, 2) array_like
        Q_i of the law (symmetric positive definite).
    law : {"previous", "candidate"}, optional
        Measured ẋ = A_σ x (as printed) or each candidate's own ẋ.
    start_mode : {0, 1}, optional
        The mode switched in on the start ray.
    ray_tol : float, optional
        See :data:`RAY_TOL`.

    Returns
    -------
    ExactTurn

    Raises
    ------
    ValueError
        If there are not two modes, a mode has real eigenvalues or no exit ray, ``start_mode``
        is not 0 or 1, or the inputs fail :func:`fdsc.switching_forms`.
    DimensionError
        If the modes do not have 2 states.

    Notes
    -----
    The law is paper eq. (31) with d = 0; Theorem 1 is paper eqs. (33)–(36), its no-sliding
    hypothesis paper Remark 7. The start is the first exit ray of mode ``1 − start_mode``
    counter-clockwise from θ = 0; mode ``start_mode`` runs to its next exit ray in its sense of
    rotation (crossing time in closed form), the other mode back to the start's line. The
    witness of Theorem 1's LMIs needs Hurwitz modes; otherwise ``lmi_holds`` is False.

    Examples
    --------
    Two copies of one spiral never switch in effect (both legs run the same flow), so the
    multiplier over a full turn is ``e^{2πα/β}`` for eigenvalues α ± jβ:

    >>> from fdsc import LTISystem, Band
    >>> A = np.array([[-0.1, 1.0], [-1.0, -0.1]])
    >>> m = LTISystem(A, [[0.0], [1.0]], [[1.0, 0.0]], [[0.0]])
    >>> Q = [np.eye(2), np.diag([1.0, 3.0])]
    >>> turn = exact_turn([m, m], [Band.lf(1.0), Band.hf(1.0)], Q)
    >>> bool(np.isclose(turn.multiplier, np.exp(-0.2 * np.pi))), turn.clean
    (True, True)
    """
    if start_mode not in (0, 1):
        raise ValueError(f"start_mode must be 0 or 1, but found {start_mode!r}")
    A, S, spin = _validate(modes, bands, Q, law)
    sense = np.array([1 if float(_normal(0.0) @ a @ _unit(0.0)) > 0 else -1 for a in A])
    if law == "candidate":
        # one common set of rays: S_10 = −S_01 exactly, so both forms share their zeros
        exits = [_exits(S[0], sense[0]), np.array([th for th in _zeros(S[0])
                                                   if sense[1] * _slope(S[1], th) > 0])]
    else:
        exits = [_exits(S[k], sense[k]) for k in range(2)]
    start = float(exits[1 - start_mode][0])
    th, x = start, _unit(start)
    angles, leaving, dwells, gains, speeds, margins, slides = [], [], [], [], [], [], []
    for i in (start_mode, 1 - start_mode):
        # the next exit ray of mode i in its sense; the flow turns monotonically, so no other
        # zero of its form is met first
        nxt = min(exits[i], key=lambda e, i=i: _ahead(th, e, sense[i]) or _TWO_PI)
        t, y = _crossing(A[i], x, nxt, *spin[i])
        g = float(np.linalg.norm(y) / np.linalg.norm(x))
        sp, lead, slide = _switch(A, S, sense, nxt, i, ray_tol)
        angles.append(float(nxt))
        leaving.append(i)
        dwells.append(t)
        gains.append(g)
        speeds.append(sp)
        margins.append(lead)
        slides.append(slide)
        th, x = float(nxt), y / np.linalg.norm(y)
    holds, gammas = False, np.full(2, np.nan)
    if all(np.linalg.eigvals(a).real.max() < 0 for a in A):
        w = lmi_witness(list(modes), bands, Q)
        holds, gammas = w.holds(), np.asarray(w.gammas, dtype=float)
    return ExactTurn(law, A, S, sense, start, int(start_mode), np.array(angles),
                     np.array(leaving), np.array(dwells), np.array(gains), np.array(speeds),
                     np.array(margins), np.array(slides), bool(holds), gammas)


def q_scaling_turns(modes, bands, Q, *, law: str = "previous", scales=Q_SCALES) -> list:
    """The exact return map with Q_0 scaled: whether a counterexample depends on the relative size
    of its Q's. Theorem 1's LMIs hold for any Q's (so only the law changes), and the law is
    unchanged when both Q's are scaled by one factor, so scaling Q_1 by c is scaling Q_0 by 1/c.

    Parameters
    ----------
    modes, bands, Q, law
        As :func:`exact_turn`.
    scales : sequence of float, optional
        Factors applied to Q_0.

    Returns
    -------
    list of dict
        One per factor: ``factor``, ``norm_ratio`` (‖Q_0‖₂ / ‖Q_1‖₂ after scaling),
        ``multiplier`` (None where there is no clean return map), ``diverges`` (Theorem 1's LMIs
        hold, no switch slides and the multiplier exceeds 1) and ``why`` (the reason where
        there is no clean return map: a switch slides, or a mode is never left).
    """
    out = []
    for c in scales:
        Qs = [np.array(Q[0], dtype=float) * float(c), np.array(Q[1], dtype=float)]
        row = {"factor": float(c),
               "norm_ratio": float(np.linalg.norm(Qs[0], 2) / np.linalg.norm(Qs[1], 2))}
        try:
            t = exact_turn(modes, bands, Qs, law=law)
        except ValueError as err:
            out.append(row | {"multiplier": None, "diverges": False, "why": str(err).split(":")[0]})
            continue
        out.append(row | {"multiplier": float(t.multiplier) if t.clean else None,
                          "diverges": bool(t.proves_divergence),
                          "why": "" if t.clean else "a switch slides"})
    return out
