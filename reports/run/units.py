"""One unit of a run: one solver on one sweep point, with its failures captured (never
raised), its results checked for non-finite values, and its output steps handed to a
writer as the solver computes them."""

from __future__ import annotations

import errno
import math
import numbers
import time
import traceback
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from cases.model import Case, CaseError
from cases.result import RunResult, StepResult, save_step, vm_max_below, vm_max_location
from reports.registry import solvers
from reports.run.deadline import Overrun, deadline
from reports.run.plan import CasePlan
from reports.store import layout


@dataclass
class UnitOutcome:
    """The result of one solver on one sweep point, or why there is none."""

    index: int
    solver: str
    param: str
    result: RunResult | None
    wall_s: float
    error: str = ""
    #: '' | 'case' (bad input) | 'solver' (did not converge) | 'overrun' (past its
    #: deadline) | 'disk' (the disk is full: :func:`disk_full`) | 'internal'
    kind: str = ""
    detail: str = ""
    cell_size: float = math.nan  # the solver's representative cell size [mm]
    steps_written: int = 0  # output steps already saved as they were computed


#: how the units of a plan are run (in this process, :func:`serial_executor`; on a Dask
#: cluster, :class:`reports.run.cluster.DaskExecutor`): (plan, units, progress) -> outcomes
Executor = Callable[[CasePlan, list[tuple[int, str]], bool], Iterable[UnitOutcome]]


#: scalars a numerical solver must report as finite numbers when it reports them
FINITE_SCALARS = ("P", "contact_area", "p_max", "w_max", "wear_volume", "vm_max")


def _check_result(result: RunResult, solver: str, case: Case) -> None:
    """A result is not trusted (a plugin's least of all): a scalar that is not a number,
    or a surface field not on the case's grid, fails the run naming it; so does NaN or
    Inf in a numerical solver's fields or key scalars (Inf in any solver's scalars too);
    a closed form may leave what it does not cover as NaN."""
    shape = (case.grid.nx, case.grid.ny)
    for k, step in enumerate(result.steps):
        for key, value in step.scalars.items():
            if not isinstance(value, numbers.Real | np.number | np.bool_):
                raise RuntimeError(f"scalar {key} = {value!r} at output step {k} is not a "
                                   "number")
        for name, arr in step.surface.items():
            if np.shape(arr) != shape:
                raise RuntimeError(f"surface {name} at output step {k} has the shape "
                                   f"{np.shape(arr)}, not the case grid's {shape}")
    nan_allowed = solvers.record(solver).closed_form
    for k, step in enumerate(result.steps):
        for key, value in step.scalars.items():
            if isinstance(value, float) and (math.isinf(value) or (
                    math.isnan(value) and key in FINITE_SCALARS and not nan_allowed)):
                raise RuntimeError(f"non-finite scalar {key} = {value} at output step {k}")
    if nan_allowed:
        return
    for k, step in enumerate(result.steps):
        arrays = [(f"surface {n}", a) for n, a in step.surface.items()]
        arrays += [(f"plane {p} {n}", a) for p, pl in step.planes.items()
                   for n, a in pl.fields.items()]
        for what, arr in arrays:
            arr = np.asarray(arr)
            if arr.dtype.kind in "fc" and not np.all(np.isfinite(arr)):
                raise RuntimeError(f"non-finite values in {what} at output step {k}")


class StepWriter:
    """Saves each output step of one unit into ``root`` as it arrives, with the scalars
    the reports derive (:func:`derive`), so that the step is written once; ``count`` is
    how many it has saved."""

    def __init__(self, root: Path, solver: str, param: str, case: Case):
        self.root, self.solver, self.param, self.case = root, solver, param, case
        self.count = 0

    def __call__(self, step: StepResult) -> None:
        derive(step, self.case)
        save_step(layout.step_file(self.root, self.solver, self.param,
                                   step.number(self.count)), step)
        self.count += 1


#: the errors of a disk that cannot take more (full, or over the user's quota)
DISK_FULL = (errno.ENOSPC, errno.EDQUOT)


def disk_full(exc: BaseException) -> bool:
    """Whether ``exc`` says the disk cannot take more: the machine's fault, not a
    solver's."""
    return isinstance(exc, OSError) and exc.errno in DISK_FULL


def disk_error(exc: OSError) -> str:
    """``exc`` of a full disk in words, with the file it was writing where known."""
    return f"{exc.strerror or exc}" + (f": {exc.filename}" if exc.filename else "")


def run_unit(fn: Callable[..., RunResult], case: Case, solver: str, index: int,
             progress: bool = False,
             on_output: Callable[[StepResult], None] | None = None,
             limit_s: float = math.inf) -> UnitOutcome:
    """Run one solver on one sweep point; failures are captured, never raised.
    ``on_output`` receives each output step as soon as the solver has it; the run is
    stopped after ``limit_s`` seconds (:mod:`reports.run.deadline`)."""
    t0 = time.perf_counter()
    try:
        with deadline(limit_s, "the run"):
            result = fn(case, progress=progress, on_output=on_output)
        if not isinstance(result, RunResult) or not result.steps:
            raise RuntimeError(f"returned {type(result).__name__} without output steps")
        _check_result(result, solver, case)
    except CaseError as exc:
        return UnitOutcome(index, solver, case.param, None, time.perf_counter() - t0,
                           error=str(exc), kind="case")
    except Overrun as exc:
        return UnitOutcome(index, solver, case.param, None, time.perf_counter() - t0,
                           error=str(exc), kind="overrun")
    except RuntimeError as exc:
        return UnitOutcome(index, solver, case.param, None, time.perf_counter() - t0,
                           error=str(exc), kind="solver", detail=traceback.format_exc())
    except (Exception, SystemExit) as exc:  # a bug in a solver: keep going with the others
        if disk_full(exc):  # writing its output steps, or a solver's own files
            return UnitOutcome(index, solver, case.param, None, time.perf_counter() - t0,
                               error=disk_error(exc), kind="disk")
        return UnitOutcome(index, solver, case.param, None, time.perf_counter() - t0,
                           error=f"{type(exc).__name__}: {exc}", kind="internal",
                           detail=traceback.format_exc())
    result.solver, result.param = solver, case.param
    result.case = case.name
    add_derived(result, case)
    return UnitOutcome(index, solver, case.param, result, time.perf_counter() - t0,
                       cell_size=solvers.record(solver).cell_size(case))


def add_derived(result: RunResult, case: Case) -> None:
    """The derived scalars (:func:`derive`) of every output step of ``result``."""
    for step in result.steps:
        derive(step, case)


#: the σ_VM maximum and its location, one definition for every solver with stress planes
VM_SCALARS = ("vm_max", "vm_max_x", "vm_max_y", "vm_max_z")


def derive(step: StepResult, case: Case) -> None:
    """Scalars the reports derive from every solver's fields alike: the σ_VM maximum and
    its location over the stress planes (:func:`cases.result.vm_max_location`, crossing at
    the case's plane centre), in place of what the solver says where it returns planes,
    so that ``summary.csv``, the report and the gate read one definition and a solver's
    mislabelled scalar cannot reach them; ``vm_max_below``
    (:func:`cases.result.vm_max_below`) when the case sets ``stress.z_below``."""
    if step.planes:
        found = vm_max_location(step.planes, *case.plane_centre)
        if math.isfinite(found[0]):
            step.scalars.update(zip(VM_SCALARS, found, strict=True))
    if case.stress.z_below is not None:
        step.scalars["vm_max_below"] = vm_max_below(step.planes, case.stress.z_below)


def failure_line(case: str, outcome: UnitOutcome) -> str:
    where = f"{case}" + (f" [{outcome.param}]" if outcome.param else "")
    if outcome.kind == "disk":
        return f"{where}: the disk is full: solver {outcome.solver}'s results could not " \
            f"be written ({outcome.error})"
    what = {"case": "rejected the case", "solver": "did not converge",
            "overrun": "was stopped", "internal": "crashed"}.get(outcome.kind, "failed")
    return f"{where}: solver {outcome.solver} {what}: {outcome.error}"


def serial_executor(plan: CasePlan, units: list[tuple[int, str]],
                    progress: bool) -> Iterator[UnitOutcome]:
    """Run units one after the other in this process; output steps are written into the
    staging directory as they are computed (``steps_written`` of each outcome).  With
    ``progress`` each solver shows its own steps (load steps, sliding increments,
    cycles) with an ETA, below the case's bar."""
    fns = {s: solvers.resolve(s) for s in {s for _, s in units}}
    for i, s in units:
        case = plan.points[i]
        writer = StepWriter(plan.staging, s, case.param, case) if plan.staging else None
        outcome = run_unit(fns[s], case, s, i, progress=progress, on_output=writer,
                           limit_s=plan.limits.deadline(case, s))
        outcome.steps_written = writer.count if writer is not None else 0
        yield outcome
