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
