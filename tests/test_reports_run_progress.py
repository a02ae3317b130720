"""Progress that ends (issue 48): a long unit shows its own steps with an ETA, labelled with
what runs, below the case's bar — here a worn-pin FEM unit, shortened to five sliding
increments."""

from __future__ import annotations

import re

import pytest

from reports.run.plan import plan_case
from reports.run.units import serial_executor

pytestmark = pytest.mark.fem


def test_a_worn_pin_fem_unit_shows_its_own_steps_with_an_eta(capsys):
    plan = plan_case("pin_on_disk", ["fem"], quick=True, overrides={
        "sliding_wear.distance": 32.0, "sliding_wear.output_s": [32.0]})
    first = plan.units()[:1]  # μ = 0
    (outcome,) = serial_executor(plan, first, progress=True)
    assert outcome.result is not None, outcome.error
    err = capsys.readouterr().err
    # tqdm's line: the label, the steps done of the total (4 increments and s = 0), the
    # elapsed time and the time left; cleared when the unit ends (the case's bar stays)
    assert re.search(r"fem pin_on_disk mu=0: +\d+%\|[^|]*\| *[1-4]/5 "
                     r"\[\d\d:\d\d<\d\d:\d\d", err), err
    assert err.rstrip("\r").endswith(" ")
    quiet = serial_executor(plan, first, progress=False)
    assert next(iter(quiet)).result is not None
    assert "fem pin_on_disk" not in capsys.readouterr().err
