"""A minimal contact-vv solver plugin (reports/README.md, "Solver plugins"): Hertz's
frictionless pressure p_n = p0 sqrt(1 - r²/a0²), sampled at the case grid's cell centres.

The entry point ``hertz_example = "hertz_example:record"`` gives contact-vv the record;
contact-vv then runs it with ``--solver hertz_example``, compares it with every other
solver (``hertz_example-ic``, ``hertz_example-analytic``), reports and gates it.
"""

from __future__ import annotations

import math

import numpy as np

from cases import Case, RunResult, StepResult
from reports.plugin import SolverRecord

#: p0 is multiplied by this; a test sets 1.1 to show the gates catch a wrong solver
SCALE = 1.0


def budget(quantity: str, metric: str) -> float:
    """Expected error against the exact solution: a closed form sampled on cells."""
    return {"rel": 0.005, "l2": 0.01, "max": 0.02, "cells": 0.5}.get(metric, 0.02)


def record() -> SolverRecord:
    """What contact-vv knows of this solver: its module, budget and cell size."""
    return SolverRecord("hertz_example", __name__, budget=budget,
                        style={"color": "C4", "ls": "-", "marker": "^", "ms": 3})


def supports(case: Case) -> str | None:
    """None for a frictionless sphere under a normal load, else why not."""
    f = case.friction
    if case.kind != "static" or f.mu1 > 0 or f.mu2 > 0 or case.load.tangential_mode != "none":
        return "hertz_example solves frictionless normal contact of a sphere only"
    return None


def solve(case: Case, *, progress: bool = False, on_output=None) -> RunResult:
    """Hertz's pressure on the case grid, one output step."""
    a0, p0 = case.hertz_scales
    p0 *= SCALE
    x, y = case.grid.x, case.grid.y
    r2 = (x[:, None] ** 2 + y[None, :] ** 2) / a0**2
    p_n = p0 * np.sqrt(np.clip(1.0 - r2, 0.0, None))
    step = StepResult(
        scalars={"step": 0.0, "P": 2.0 / 3.0 * math.pi * a0**2 * p0, "p_max": p0,
                 "contact_area": math.pi * a0**2, "a_x": a0, "a_y": a0},
        x=x, y=y, surface={"p_n": p_n})
    if on_output is not None:
        on_output(step)
    return RunResult(case=case.name, solver="hertz_example", param=case.param, steps=[step])
