"""Run a case (every sweep point) through the chosen solvers and write ``DIR/<case>/``.

The output layout is described in :mod:`reports.layout`.  Everything is written into a
staging directory ``DIR/.<case>.partial``; the manifest is written last and the staging
directory is then renamed onto ``DIR/<case>``, so a case directory is either complete or
absent, and files of two runs are never mixed.  A run that fails (a solver that does not
converge, raises, or returns non-finite fields) leaves only the staging directory, with
``failed.json`` naming the cause; ``report`` and ``gate`` flag it.  A solver whose entry
point takes ``on_output`` (the half-space solver) hands over each output step as soon as
it is computed, and the serial runner writes it into the staging directory at once, so
an interrupted long run keeps the steps it finished there (``fields/<solver>/<param>/``).
Runs do not resume: re-running says so, discards the staging directory and restarts the
case cleanly.
"""

from __future__ import annotations

import dataclasses
import inspect
import json
import math
import os
import shutil
import sys
import time
import traceback
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
from tqdm.auto import tqdm

from cases.loader import case_path, load_case
from cases.model import Case, CaseError
from cases.result import SUMMARY_COLUMNS, RunResult, StepResult, atomic_path, save_step

from . import layout, manifest, solvers
from .compare import METRICS_COLUMNS, compare_point, step_number
from .errors import SolverUnavailable, UserError
from .scales import hertz_scales
from .tolerances import check_keys

#: solvers whose results may hold NaN where a closed form says nothing
NAN_ALLOWED = frozenset({"analytic"})


# ------------------------------------------------------------------ planning


def expected_radius(case: Case) -> float:
    """The largest contact radius the case should reach [mm] (an a-priori estimate).

    Hertz a0 (load or displacement control); for sliding wear Argatov's worn-pin radius
    a = (a0⁴ + 4 i_w P s R / π)^(1/4) at the final distance, i_w the largest wear
    coefficient of either body.
    """
    a0, _ = hertz_scales(case)
    if case.sliding_wear is not None and case.load.P is not None:
        i_w = max(case.a.i1, case.a.i2, case.b.i1, case.b.i2)
        s = case.sliding_wear.distance
        return (a0**4 + 4.0 * i_w * case.load.P * s * case.R / math.pi) ** 0.25
    return a0


def check_fits(case: Case) -> None:
    """Refuse a case whose contact cannot fit in the potential contact grid.

    The solvers detect a contact touching the grid edge during the run; this catches
    the hopeless cases before any work: the expected radius must leave at least one
    cell free on each side.
    """
    a = expected_radius(case)
    g = case.grid
    for key, half, cell in (("grid.Lx", g.Lx / 2, g.dx), ("grid.Ly", g.Ly / 2, g.dy)):
        if a >= half - cell:
            where = f" [{case.param}]" if case.param else ""
            raise CaseError(
                f"{key} = {2 * half:g} mm{where}: the expected contact radius {a:.4g} mm "
                f"reaches the edge of the potential contact grid (half-width {half:g} mm, "
                f"cell {cell:.3g} mm); enlarge grid.Lx/grid.Ly")


@dataclass
class CasePlan:
    """What to run for one case: its sweep points and the solvers that apply."""

    name: str
    source: Path
    points: list[Case]
    solvers: list[str]
    skipped: dict[str, str] = field(default_factory=dict)
    quick: bool = False
    overrides: dict[str, Any] = field(default_factory=dict)
    sweep: dict[str, Any] | None = None
    dir_name: str = ""
    staging: Path | None = None  # set by execute(): where output steps are streamed

    def units(self) -> list[tuple[int, str]]:
        """(point index, solver) pairs to run, point-major, solvers in registry order."""
        return [(i, s) for i, case in enumerate(self.points) for s in self.solvers
                if s in self.applicable(case)]

    def applicable(self, case: Case) -> list[str]:
        return [s for s in self.solvers if solvers.applies(s, case)]


def select_solvers(requested: list[str] | None) -> tuple[list[str], dict[str, str]]:
    """(usable solvers, {skipped solver: reason}).

    Without an explicit request every registered solver is tried and unavailable ones
    are skipped; an explicitly requested solver that cannot load is an error.
    """
    known = solvers.names()
    if requested:
        unknown = [s for s in requested if s not in known]
        if unknown:
            raise UserError(f"unknown solver(s) {', '.join(unknown)} (known: {', '.join(known)})")
        for s in requested:
            solvers.resolve(s)  # raises SolverUnavailable with the reason
        return [s for s in known if s in requested], {}
    usable, skipped = [], {}
    for s in known:
        ok, reason = solvers.available(s)
        if ok:
            usable.append(s)
        else:
            skipped[s] = reason
    if not usable:
        raise SolverUnavailable("no solver is available: " + "; ".join(skipped.values()))
    return usable, skipped


def plan_case(ref: str | Path, solver_names: list[str], *, quick: bool = False,
              overrides: dict[str, Any] | None = None, skipped: dict[str, str] | None = None,
              points: list[Case] | None = None, sweep: dict[str, Any] | None = None,
              dir_name: str | None = None) -> CasePlan:
    """Load and validate a case (``CaseError`` on bad input) and plan its runs."""
    source = case_path(ref)
    if points is None:
        points = load_case(source, quick=quick, overrides=overrides)
    for case in points:
        check_keys(case, solvers.names())
        check_fits(case)
    name = points[0].name
    plan = CasePlan(name=name, source=source, points=points, solvers=list(solver_names),
                    skipped=dict(skipped or {}), quick=quick, overrides=dict(overrides or {}),
                    sweep=sweep, dir_name=dir_name or name)
    for s in plan.solvers:
        if not any(s in plan.applicable(c) for c in points):
            plan.skipped[s] = ("no closed-form solution for this case" if s == "analytic"
                               else "does not support this case")
    return plan


# ------------------------------------------------------------------ one unit


@dataclass
class UnitOutcome:
    """The result of one solver on one sweep point, or why there is none."""

    index: int
    solver: str
    param: str
    result: RunResult | None
    wall_s: float
    error: str = ""
    kind: str = ""  # '' | 'case' (bad input) | 'solver' (did not converge) | 'internal'
    detail: str = ""


#: scalars a numerical solver must report as finite numbers when it reports them
FINITE_SCALARS = ("P", "contact_area", "p_max", "w_max", "wear_volume", "vm_max")


def _check_finite(result: RunResult, solver: str) -> None:
    """NaN or Inf in a numerical solver's fields or key scalars fails the run (Inf in any
    solver's scalars too); a closed form may leave what it does not cover as NaN."""
    for k, step in enumerate(result.steps):
        for key, value in step.scalars.items():
            if isinstance(value, float) and (math.isinf(value) or (
                    math.isnan(value) and key in FINITE_SCALARS and solver not in NAN_ALLOWED)):
                raise RuntimeError(f"non-finite scalar {key} = {value} at output step {k}")
    if solver in NAN_ALLOWED:
        return
    for k, step in enumerate(result.steps):
        arrays = [(f"surface {n}", a) for n, a in step.surface.items()]
        arrays += [(f"plane {p} {n}", a) for p, pl in step.planes.items()
                   for n, a in pl.fields.items()]
        for what, arr in arrays:
            arr = np.asarray(arr)
            if arr.dtype.kind in "fc" and not np.all(np.isfinite(arr)):
                raise RuntimeError(f"non-finite values in {what} at output step {k}")


def takes_on_output(fn: Callable[..., RunResult]) -> bool:
    """Whether a solver entry point accepts an ``on_output`` callback."""
    try:
        return "on_output" in inspect.signature(fn).parameters
    except (TypeError, ValueError):
        return False


def step_writer(root: Path, solver: str, param: str) -> Callable[[StepResult], None]:
    """A callback saving each output step of one unit into ``root`` as it arrives."""
    count = 0

    def write(step: StepResult) -> None:
        nonlocal count
        save_step(layout.step_file(root, solver, param, step_number(step, count)), step)
        count += 1

    return write


def run_unit(fn: Callable[..., RunResult], case: Case, solver: str, index: int,
             progress: bool = False,
             on_output: Callable[[StepResult], None] | None = None) -> UnitOutcome:
    """Run one solver on one sweep point; failures are captured, never raised.
    ``on_output`` is passed on to solvers that accept it."""
    t0 = time.perf_counter()
    try:
        if on_output is not None and takes_on_output(fn):
            result = fn(case, progress=progress, on_output=on_output)
        else:
            result = fn(case, progress=progress)
        if not isinstance(result, RunResult) or not result.steps:
            raise RuntimeError(f"returned {type(result).__name__} without output steps")
        _check_finite(result, solver)
    except CaseError as exc:
        return UnitOutcome(index, solver, case.param, None, time.perf_counter() - t0,
                           error=str(exc), kind="case")
    except RuntimeError as exc:
        return UnitOutcome(index, solver, case.param, None, time.perf_counter() - t0,
                           error=str(exc), kind="solver", detail=traceback.format_exc())
    except Exception as exc:  # a bug in a solver: keep going with the other cases
        return UnitOutcome(index, solver, case.param, None, time.perf_counter() - t0,
                           error=f"{type(exc).__name__}: {exc}", kind="internal",
                           detail=traceback.format_exc())
    result.solver, result.param = solver, case.param
    result.case = case.name
    return UnitOutcome(index, solver, case.param, result, time.perf_counter() - t0)


def failure_line(case: str, outcome: UnitOutcome) -> str:
    where = f"{case}" + (f" [{outcome.param}]" if outcome.param else "")
    what = {"case": "rejected the case", "solver": "did not converge",
            "internal": "crashed"}.get(outcome.kind, "failed")
    return f"{where}: solver {outcome.solver} {what}: {outcome.error}"


# ------------------------------------------------------------------ writing


def _jsonable(meta: dict) -> dict:
    """Solver metadata for the manifest: JSON values kept, small arrays as lists, anything
    else (meshes, large arrays) as a short description."""
    out = {}
    for key, value in meta.items():
        if key == "vtu":
            continue
        if isinstance(value, np.ndarray):
            value = value.tolist() if value.size <= 64 else \
                f"array {value.dtype} shape {value.shape}"
        try:
            json.dumps(value)
        except (TypeError, ValueError):
            value = f"{type(value).__name__}: {str(value)[:200]}"
        out[str(key)] = value
    return out


def _vtu_items(meshes: Any, numbers: list[int]) -> list[tuple[str, Any]]:
    """(file stem, mesh) pairs from ``meta["vtu"]``: a mesh, a dict {step or name: mesh},
    a list of meshes (one per output step) or a list of (step, mesh) pairs."""
    import meshio

    def stem(key: Any) -> str:
        if isinstance(key, int | np.integer):
            return f"step_{int(key):04d}"
        return layout.safe_name(str(key))

    if isinstance(meshes, meshio.Mesh):
        return [("mesh", meshes)]
    if isinstance(meshes, dict):
        return [(stem(k), m) for k, m in meshes.items()]
    items = []
    for i, item in enumerate(meshes):
        if isinstance(item, tuple | list) and len(item) == 2:
            items.append((stem(item[0]), item[1]))
        else:
            items.append((stem(numbers[i] if i < len(numbers) else i), item))
    return items


def _write_vtu(root: Path, solver: str, param: str, result: RunResult,
               numbers: list[int]) -> list[str]:
    """Write the meshes of ``meta["vtu"]`` (if any) as .vtu files beside the steps."""
    meshes = result.meta.get("vtu")
    if meshes is None:
        return []
    import meshio

    written = []
    for stem, mesh in _vtu_items(meshes, numbers):
        if not isinstance(mesh, meshio.Mesh):
            raise RuntimeError(f"meta['vtu'] holds a {type(mesh).__name__}, not a meshio.Mesh")
        path = layout.unit_dir(root, solver, param) / f"{stem}.vtu"
        with atomic_path(path) as tmp:
            meshio.write(tmp, mesh, file_format="vtu", binary=True)
        written.append(path.name)
    return written


def write_unit(root: Path, outcome: UnitOutcome) -> list[dict[str, Any]]:
    """Write the fields, tables and meshes of one unit; return its summary rows."""
    result = outcome.result
    assert result is not None
    rows, numbers = [], []
    for k, step in enumerate(result.steps):
        n = step_number(step, k)
        numbers.append(n)
        save_step(layout.step_file(root, outcome.solver, outcome.param, n), step)
        row = {c: step.scalars.get(c, math.nan) for c in SUMMARY_COLUMNS}
        row.update({key: v for key, v in step.scalars.items() if key not in row})
        row.update(case=result.case, solver=outcome.solver, param=outcome.param, step=n)
        if _missing(row.get("wall_s")):
            row["wall_s"] = outcome.wall_s if len(result.steps) == 1 else math.nan
        rows.append(row)
    for name, table in result.tables.items():
        frame = pd.DataFrame({k: pd.Series(np.asarray(v).ravel()) for k, v in table.items()})
        path = layout.unit_dir(root, outcome.solver, outcome.param) / \
            f"{layout.safe_name(name)}.csv"
        with atomic_path(path) as tmp:
            frame.to_csv(tmp, index=False)
    _write_vtu(root, outcome.solver, outcome.param, result, numbers)
    return rows


def _missing(value: Any) -> bool:
    return value is None or (isinstance(value, float) and math.isnan(value))


def summary_frame(rows: list[dict[str, Any]]) -> pd.DataFrame:
    """summary.csv: the contract columns in order, then any extra scalars (sorted)."""
    frame = pd.DataFrame.from_records(rows)
    for c in SUMMARY_COLUMNS:
        if c not in frame.columns:
            frame[c] = math.nan
    extra = sorted(c for c in frame.columns if c not in SUMMARY_COLUMNS)
    return frame[SUMMARY_COLUMNS + extra]


def write_csv(path: Path, frame: pd.DataFrame) -> None:
    """Write a CSV atomically; floats round-trip exactly, NaN is blank."""
    with atomic_path(path) as tmp:
        frame.to_csv(tmp, index=False, na_rep="")


# ------------------------------------------------------------------ staging


def _pid_alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def claim_staging(out: Path, name: str) -> Path:
    """Create a fresh staging directory for ``name``; refuse if a live run owns it."""
    staging = layout.staging_dir(out, name)
    pid_file = staging / ".pid"
    if staging.exists():
        try:
            pid = int(pid_file.read_text())
        except (OSError, ValueError):
            pid = 0
        if pid and pid != os.getpid() and _pid_alive(pid):
            raise UserError(f"another contact-vv run (pid {pid}) is writing {staging}")
        kept = sum(1 for _ in staging.rglob("step_*.npz"))
        print(f"contact-vv: {staging} holds an interrupted run of {name} ({kept} output "
              "step file(s) kept); runs do not resume: discarding it and restarting "
              f"{name} from the beginning", file=sys.stderr)
        shutil.rmtree(staging)
    try:
        staging.mkdir(parents=True)
    except FileExistsError:
        raise UserError(f"another contact-vv run is writing {staging}") from None
    pid_file.write_text(str(os.getpid()))
    return staging


def _remove_dir(path: Path) -> None:
    """Remove a directory by first renaming it away (the removal itself is not atomic)."""
    if path.exists():
        trash = path.with_name(f".{path.name}.old-{os.getpid()}")
        if trash.exists():
            shutil.rmtree(trash)
        os.replace(path, trash)
        shutil.rmtree(trash, ignore_errors=True)


# ------------------------------------------------------------------ a whole case


@dataclass
class CaseRun:
    """What happened to one case: where it went, failures, timings."""

    name: str
    path: Path | None
    failures: list[str] = field(default_factory=list)
    user_error: bool = False
    wall_s: float = 0.0
    unit_wall_s: float = 0.0
    metrics: pd.DataFrame | None = None


Executor = Callable[[CasePlan, list[tuple[int, str]], bool], Iterable[UnitOutcome]]


def serial_executor(plan: CasePlan, units: list[tuple[int, str]],
                    progress: bool) -> Iterator[UnitOutcome]:
    """Run units one after the other in this process; output steps are written into the
    staging directory as they are computed."""
    fns = {s: solvers.resolve(s) for s in {s for _, s in units}}
    for i, s in units:
        case = plan.points[i]
        writer = step_writer(plan.staging, s, case.param) if plan.staging else None
        yield run_unit(fns[s], case, s, i, progress=False, on_output=writer)


def execute(plan: CasePlan, out: Path, *, executor: Executor = serial_executor,
            progress: bool | None = None, extra_manifest: dict[str, Any] | None = None
            ) -> CaseRun:
    """Run every unit of a plan and write the case directory (or leave it absent).

    ``progress=None`` shows bars only on a terminal.  Failures are returned, not raised.
    """
    out = Path(out)
    t0 = time.perf_counter()
    sources = manifest.source_hashes()
    staging = claim_staging(out, plan.dir_name)
    plan.staging = staging
    final = layout.case_dir(out, plan.dir_name)
    if final.exists() and not (final.is_dir() and layout.only_own_files(final)):
        shutil.rmtree(staging)
        raise UserError(f"{final} exists and is not a contact-vv result; refusing to replace "
                        "it (choose another --out)")
    _remove_dir(final)  # an older result must not outlive a newer, failing run

    units = plan.units()
    expected: dict[int, set[str]] = {}
    for i, s in units:
        expected.setdefault(i, set()).add(s)
    pending: dict[int, dict[str, RunResult]] = {}
    rows: dict[tuple[int, int], list[dict[str, Any]]] = {}
    metric_parts: dict[int, pd.DataFrame] = {}
    records: list[dict[str, Any]] = []
    failures: list[UnitOutcome] = []
    order = {s: k for k, s in enumerate(plan.solvers)}

    bar = tqdm(total=len(units), desc=plan.dir_name, unit="run", leave=False,
               disable=None if progress is None else not progress)
    try:
        for outcome in executor(plan, units, bool(progress)):
            bar.update(1)
            bar.set_postfix_str(f"{outcome.solver} {outcome.param}".strip())
            records.append({"solver": outcome.solver, "param": outcome.param,
                            "wall_s": outcome.wall_s, "ok": outcome.result is not None,
                            "error": outcome.error, "kind": outcome.kind,
                            "meta": _jsonable(outcome.result.meta) if outcome.result else {}})
            if outcome.result is None:
                failures.append(outcome)
                break
            try:
                rows[(outcome.index, order[outcome.solver])] = write_unit(staging, outcome)
            except Exception as exc:  # a result that cannot be written is a failed run
                failures.append(dataclasses.replace(
                    outcome, result=None, kind="internal", detail=traceback.format_exc(),
                    error=f"writing its results failed: {type(exc).__name__}: {exc}"))
                break
            bucket = pending.setdefault(outcome.index, {})
            bucket[outcome.solver] = outcome.result
            if set(bucket) == expected[outcome.index]:
                ordered = {s: bucket[s] for s in sorted(bucket, key=order.get)}
                try:
                    metric_parts[outcome.index] = compare_point(plan.points[outcome.index],
                                                                ordered)
                except Exception as exc:  # a result the comparisons cannot digest
                    failures.append(dataclasses.replace(
                        outcome, result=None, kind="internal", detail=traceback.format_exc(),
                        error=f"comparing its results failed: {type(exc).__name__}: {exc}"))
                    break
                del pending[outcome.index]
    finally:
        bar.close()

    unit_wall = float(sum(r["wall_s"] for r in records))
    run = CaseRun(plan.dir_name, None, wall_s=time.perf_counter() - t0, unit_wall_s=unit_wall)
    if failures:
        run.failures = [failure_line(plan.name, f) for f in failures]
        run.user_error = all(f.kind == "case" for f in failures)
        from cases.result import atomic_write_text

        atomic_write_text(staging / layout.FAILED, json.dumps(
            {"case": plan.name, "failures": run.failures,
             "details": [f.detail for f in failures if f.detail]}, indent=1))
        return run

    summary = summary_frame([r for key in sorted(rows) for r in rows[key]])
    write_csv(staging / layout.SUMMARY, summary)
    parts = [metric_parts[i] for i in sorted(metric_parts) if not metric_parts[i].empty]
    metrics = pd.concat(parts, ignore_index=True) if parts else \
        pd.DataFrame(columns=METRICS_COLUMNS)
    write_csv(staging / layout.METRICS, metrics)

    body = {
        "case": plan.name,
        "dir": plan.dir_name,
        "kind": plan.points[0].kind,
        "description": plan.points[0].description,
        "case_file": str(plan.source),
        "case_sha256": manifest.sha256_file(plan.source),
        "quick": plan.quick,
        "overrides": plan.overrides,
        "sweep": plan.sweep,
        "params": [c.param for c in plan.points],
        "points": [dict(dataclasses.asdict(c), hertz_a0=hertz_scales(c)[0],
                        hertz_p0=hertz_scales(c)[1]) for c in plan.points],
        "solvers": plan.solvers,
        "skipped": plan.skipped,
        "units": records,
        "wall_s": time.perf_counter() - t0,
        "unit_wall_s": unit_wall,
        "provenance": manifest.provenance(),
        "sources": sources,
        "sources_changed_during_run": manifest.source_hashes() != sources,
        **(extra_manifest or {}),
    }
    (staging / ".pid").unlink(missing_ok=True)
    manifest.write(staging, body)
    _remove_dir(final)
    os.replace(staging, final)
    run.path, run.metrics = final, metrics
    return run
