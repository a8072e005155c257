"""The fixed controller chosen in advance for Part II's class (:mod:`fdsc.paper.shared.fixed_choice`)
in every simulation case of the paper: its energies in closed form.

The controller is fixed, so its loop is linear and time-invariant: its energy from rest under
the paper's tones (or pieces of tones) is the closed form of the loop's modal form
(:func:`fdsc._closed_energy.closed_form_energies`, the method that scores Part II's fixed
controllers), not a run of the switched loops' simulator. The simulator at the book's step
gives the same energies to rounding (about 1e-12 relative: tested), but takes about a second per
case where the closed form takes milliseconds for all 34.
"""

from fdsc._closed_energy import closed_form_energies
from fdsc.paper.reproduced.nonstationary_sweeps import family_signal, mixed_sweep, piecewise_sweep
from fdsc.paper.shared.cache import cached
from fdsc.paper.shared.data import STATIONARY_HORIZON, aircraft, paper_disturbance

__all__ = ["chosen_cases", "chosen_energies"]


def chosen_cases() -> list:
    """The paper's simulation cases in the order of :func:`chosen_energies`: the stationary LF
    and HF cases, then the ρ_p and ρ_t families of paper Figs. 7 and 8.

    Returns
    -------
    list of (str, disturbance, float)
        ``(family, d, horizon)``, family one of ``"stationary"``, ``"mixed"``, ``"piecewise"``.
    """
    cases = [("stationary", paper_disturbance(k), float(STATIONARY_HORIZON)) for k in ("LF", "HF")]
    for family, sweep in (("mixed", mixed_sweep()), ("piecewise", piecewise_sweep())):
        for p, h in zip(sweep.param, sweep.horizon, strict=True):
            cases.append((family, family_signal(family, p)[0], float(h)))
    return cases


@cached
def chosen_energies(example: str = "aircraft") -> dict:
    """The fixed controller chosen in advance in every simulation case of the paper, from rest,
    in closed form (module docstring).

    Parameters
    ----------
    example : {"aircraft"}
        The paper's cases are the aircraft's.

    Returns
    -------
    dict
        ``{"name": str, "stationary": [E_LF, E_HF], "mixed": [...], "piecewise": [...]}`` (∫zᵀz
        at the points of :func:`fdsc.paper.reproduced.paper_cases.baselines`).

    Raises
    ------
    ValueError
        If ``example`` is not ``"aircraft"``.
    """
    from fdsc.paper.shared.fixed_choice import fixed_in_advance

    if example != "aircraft":
        raise ValueError("example must be 'aircraft' (the paper's cases are the aircraft's), "
                         f"but found {example!r}")
    name, c = fixed_in_advance(example)
    cases = chosen_cases()
    energies, _method = closed_form_energies(aircraft().closed_loop(c), [d for _f, d, _h in cases],
                                             [h for _f, _d, h in cases])
    out = {"name": name, "stationary": [], "mixed": [], "piecewise": []}
    for (family, _d, _h), e in zip(cases, energies, strict=True):
        out[family].append(float(e))
    return out
