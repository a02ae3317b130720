"""The output steps of a case (:mod:`cases.steps`), the one definition every solver
writes by: the half-space solver's step numbers on generated cases of every kind, and
the closed forms' among them (a fretting closed form has cycle 1 only); a case whose
outputs lie outside its run, or whose distance is not a whole number of steps, is
refused when it is loaded, naming the key.  (The FEM's, on every bundled quick point:
``tests/test_suite_quick_gates.py``.)"""

from __future__ import annotations

import pytest
from case_generator import user_case
from hypothesis import HealthCheck, given, settings

import analytic
import halfspace
from cases.loader import load_case
from cases.model import CaseError
from cases.steps import output_steps

PIN = ('kind = "sliding_wear"\n[materials.a]\nE = 210000.0\nnu = 0.3\ni1 = 1e-8\n'
       "[materials.b]\nE = 210000.0\nnu = 0.3\n[geometry]\nR = 20.0\n[grid]\nLx = 1.0\n"
       "nx = 21\n[friction]\nmu = 0.3\n[load]\nP = 10.0\n[sliding_wear]\n")


def _load(text: str, tmp_path):
    path = tmp_path / "case.toml"
    path.write_text(text)
    return load_case(path)


@settings(max_examples=12, derandomize=True, deadline=None, database=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])
@given(text=user_case(kinds=("hertz", "partial_slip", "pin", "fretting")))
def test_the_solvers_write_the_cases_output_steps(text, tmp_path):
    for case in _load(text, tmp_path):
        expected = output_steps(case)
        numbers = [s.number(i) for i, s in enumerate(halfspace.solve(case).steps)]
        assert numbers == expected, text
        if analytic.supports(case) is None:  # the closed form's cycle 1 of a fretting run
            numbers = [s.number(i) for i, s in enumerate(analytic.solve(case).steps)]
            assert numbers and set(numbers) <= set(expected), text


@pytest.mark.parametrize("table, words", [
    ("step = 1.0\ndistance = 10.0\noutput_s = [12.0]\n", "sliding_wear.output_s"),
    ("step = 1.0\ndistance = 10.0\noutput_s = [-1.0]\n", "sliding_wear.output_s"),
    ("step = 3.0\ndistance = 10.0\n", "not a whole number of steps"),
])
def test_outputs_outside_the_run_are_refused_when_loaded(table, words, tmp_path):
    with pytest.raises(CaseError, match=words):
        _load(PIN + table, tmp_path)


def test_a_pin_without_output_distances_writes_its_start_and_end(tmp_path):
    """The same for every solver (the FEM used to write every step, the others two)."""
    (case,) = _load(PIN + "step = 2.0\ndistance = 10.0\n", tmp_path)
    assert output_steps(case) == [0, 5]


def test_the_normal_loading_of_a_coupled_contact():
    """cases.steps.normal_fractions: contact radii (load ∝ a³, approach ∝ a²) from a fifth
    to 0.98 by one ratio, then 1; the ratio 1 + 0.01/(|β| μ) within [1.1, 1.4] (a work
    count: 7 increments for the bundled spence, β μ = 0.0023, 19 at β μ = 0.5); the
    first contact at least two cells wide."""
    import dataclasses

    import numpy as np

    from cases.loader import load_case
    from cases.steps import normal_fractions

    case = load_case("spence", quick=True)[0]
    f = np.array(normal_fractions(case))
    radii = f ** (1 / 3)
    assert len(f) == 7 and f[-1] == 1.0 and radii[0] == pytest.approx(0.2)
    assert radii[-2] == pytest.approx(0.98)
    ratios = radii[1:-1] / radii[:-2]
    np.testing.assert_allclose(ratios, ratios[0])
    assert ratios[0] <= 1.4
    a0, _ = case.hertz_scales
    held = case.with_changes(load=dataclasses.replace(case.load, P=None,
                                                      approach=a0 * a0 / case.R))
    np.testing.assert_allclose(np.array(normal_fractions(held)) ** 0.5, radii)
    strong = case.with_changes(friction=dataclasses.replace(case.friction, mu1=8.7, mu2=8.7))
    assert len(normal_fractions(strong)) == 19  # |β| μ = 0.5: the ratio 1.1
    coarse = case.with_changes(grid=dataclasses.replace(case.grid, nx=9, ny=9))
    first = normal_fractions(coarse)[0] ** (1 / 3) * case.hertz_scales[0]
    assert first >= 2 * coarse.grid.dx * (1 - 1e-12)
