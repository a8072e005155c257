"""The fixed controller chosen in advance in the paper's cases (fdsc.paper.reproduced.chosen_cases):
its closed-form energies equal the switched loops' simulator's at the book's step, case by case."""

import numpy as np
import pytest

import fdsc
from fdsc.paper.reproduced.chosen_cases import chosen_cases, chosen_energies
from fdsc.paper.reproduced.paper_cases import baselines
from fdsc.paper.shared.data import STATIONARY_DT, aircraft
from fdsc.paper.shared.fixed_choice import fixed_in_advance


def test_every_case_of_the_paper_in_the_order_of_the_baselines():
    ch = chosen_energies()
    base = baselines()
    for family in ("stationary", "mixed", "piecewise"):
        assert len(ch[family]) == len(base.family(family))
    assert ch["name"] == fixed_in_advance("aircraft")[0]
    # every energy positive and finite
    assert all(np.isfinite(e) and e > 0 for f in ("stationary", "mixed", "piecewise") for e in ch[f])


@pytest.mark.parametrize("k", [1, 2, -1])      # HF stationary, the first ρ_p case, the last ρ_t case
def test_the_closed_form_is_the_simulators_energy(k):
    family, d, h = chosen_cases()[k]
    name, c = fixed_in_advance("aircraft")
    run = fdsc.simulate_stream(aircraft().closed_loop(c), d, h, STATIONARY_DT).energy
    ch = chosen_energies()
    flat = ch["stationary"] + ch["mixed"] + ch["piecewise"]
    assert flat[k] == pytest.approx(run, rel=1e-9)


def test_only_the_aircraft_has_the_papers_cases():
    with pytest.raises(ValueError, match="example must be 'aircraft'"):
        chosen_energies("generic")
