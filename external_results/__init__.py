"""Results of another code as a solver of the suite: ``external:NAME`` reads the files
the case's ``[external.NAME]`` table names (:mod:`external_results.spec`; the user's
guide: ``docs/external-results.md``) and gives them to the comparisons like any
solver's output.

- :mod:`.frame` reads a file (meshio, or a CSV table) into the suite's frame and units;
- :mod:`.interpolate` interpolates nodal values on the surface and inside the body;
- :mod:`.step` builds the output step: the grid's surface fields, the stress planes,
  the scalars, each with one definition for every file.

The protocol of :mod:`reports.registry.solvers`, with the result set's ``name``:
``solve(case, *, progress, on_output, name)``, ``supports(case, *, name)``.
"""

from __future__ import annotations

import time
from collections.abc import Callable

from cases.model import Case, one_case
from cases.result import RunResult, StepResult

from .frame import read, scalar_rows
from .spec import Spec, spec
from .step import step_result

__all__ = ["solve", "supports", "spec", "Spec"]


def supports(case: Case, *, name: str) -> str | None:
    """None: the case's ``[external.NAME]`` table is valid and every file it names gives
    its output step: every mapped field and scalar, a contact surface and, where
    stresses are mapped, a body that holds the case's stress planes (otherwise the
    CaseError names the key, the file and the likely cause).  Asked while the run is
    planned, so that a bad file replaces no earlier result: each file is read as the
    run reads it (reading files costs little beside a solver)."""
    s = spec(case, name)
    rows = scalar_rows(s)
    for path, number in zip(s.files, s.steps, strict=True):
        step_result(read(path, s, number, rows), case, s, number)
    return None


def solve(case: Case, *, progress: bool = False,
          on_output: Callable[[StepResult], None] | None = None, name: str) -> RunResult:
    """The output steps of ``case`` read from the files of ``[external.NAME]``, one per
    file, in order (:mod:`external_results.step`)."""
    case = one_case(case, f"external:{name}")
    s = spec(case, name)
    t0 = time.perf_counter()
    steps, rows = [], scalar_rows(s)
    for path, number in zip(s.files, s.steps, strict=True):
        step = step_result(read(path, s, number, rows), case, s, number)
        step.scalars["wall_s"] = time.perf_counter() - t0
        steps.append(step)
        if on_output is not None:
            on_output(step)
    return RunResult(case=case.name, solver=f"external:{name}", param=case.param,
                     steps=steps, meta={"files": [str(p) for p in s.files]})
