"""Run a case (every sweep point) through the chosen solvers and write ``DIR/<case>/``.

The output layout is described in :mod:`reports.store.layout`.  Everything is written into a
staging directory ``DIR/.<case>.partial``; the manifest is written last and the staging
directory is then renamed onto ``DIR/<case>``, so a case directory is either complete or
absent, and files of two runs are never mixed.  A run that fails (a solver that does not
converge, raises, or returns non-finite fields) leaves only the staging directory, with
``failed.json`` naming the cause; ``report`` and ``gate`` flag it.  Every solver hands
over each output step as soon as it is computed (``on_output``, :mod:`reports.registry.solvers`)
and the serial executor writes it into the staging directory at once, so an interrupted
long run keeps the steps it finished there (``fields/<solver>/<param>/``).
Runs do not resume: re-running says so, discards the staging directory and restarts the
case cleanly.  The runs of the plan's studies (:mod:`reports.studies.study`: the grid
studies of ``run --convergence``, the resolution probe, …) run after the case's own units,
through the same executor, and each study's table is written into the staging directory
with the rest (:mod:`reports.run.study_runs`).

The stages live in their own modules: planning (:mod:`reports.run.plan`), one unit
(:mod:`reports.run.units`), writing (:mod:`reports.store.write`), the staging directory
(:mod:`reports.store.staging`); this module runs them for a whole case.
"""

from __future__ import annotations

import dataclasses
import json
import os
import time
import traceback
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import pandas as pd
from tqdm.auto import tqdm

from cases.result import RunResult, atomic_write_text
from reports.compare import verdict
from reports.compare.point import point_rows
from reports.registry.errors import UserError
from reports.registry.tolerances import TOLERANCE_COLUMNS
from reports.run import study_runs
from reports.run.plan import CasePlan
from reports.run.units import (
    Executor,
    UnitOutcome,
    disk_error,
    disk_full,
    failure_line,
    serial_executor,
)
from reports.store import layout, manifest
from reports.store.event_table import events_frame
from reports.store.staging import case_lock, claim_staging, remove_dir
from reports.store.write import jsonable, summary_frame, write_csv, write_unit
from reports.studies.probe import PROBE
from reports.studies.registry import STUDIES
from reports.studies.study import Own, Study, StudyTable


def _study_files() -> frozenset[str]:
    """The tables the studies write into a case directory."""
    return frozenset(layout.study_file(s.name) for s in STUDIES)


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
    staging_left: bool = True  # a failed run's staging directory is on disk


@dataclass
class _Collected:
    """What the units of a case produced so far: summary rows per (point, solver),
    event rows per (point, solver) of the solvers that watch for events, metrics per
    complete point, manifest records, failures."""

    rows: dict[tuple[int, int], list[dict[str, Any]]] = field(default_factory=dict)
    events: dict[tuple[int, int], list[dict[str, Any]]] = field(default_factory=dict)
    metrics: dict[int, pd.DataFrame] = field(default_factory=dict)
    kept: dict[tuple[int, str], RunResult] = field(default_factory=dict)  # for the studies
    records: list[dict[str, Any]] = field(default_factory=list)
    failures: list[UnitOutcome] = field(default_factory=list)


def _failed(outcome: UnitOutcome, what: str, exc: Exception) -> UnitOutcome:
    """``outcome`` turned into an internal failure: ``what`` failed with ``exc`` (a full
    disk's failure where it is one)."""
    if disk_full(exc):
        return replace(outcome, result=None, kind="disk", error=disk_error(exc))
    return replace(outcome, result=None, kind="internal",
                               detail=traceback.format_exc(),
                               error=f"{what} failed: {type(exc).__name__}: {exc}")


def _collect(plan: CasePlan, staging: Path, executor: Executor, progress: bool | None
             ) -> _Collected:
    """Run the units of ``plan``, writing each into ``staging`` and comparing each sweep
    point as soon as all its solvers are done; stop at the first failure."""
    units = plan.units()
    expected: dict[int, set[str]] = {}
    for i, s in units:
        expected.setdefault(i, set()).add(s)
    order = {s: k for k, s in enumerate(plan.solvers)}
    pending: dict[int, dict[str, RunResult]] = {}
    got = _Collected()
    keep = {(r.point, r.solver) for p in plan.studies if p.study.keeps_results
            for r in p.runs}
    # the comparisons count the probing solver's cells where the probe runs (point_rows)
    probed = {r.point for p in plan.studies if p.study is PROBE for r in p.runs}
    bar = tqdm(total=len(units), desc=plan.dir_name, unit="run", leave=False,
               disable=None if progress is None else not progress)

    def running(k: int) -> None:  # the label names the unit that runs now, in plan order
        if k < len(units):
            i, s = units[k]
            bar.set_postfix_str(f"now {s} {plan.points[i].param}".strip())

    try:
        running(0)
        for outcome in executor(plan, units, bool(progress)):
            bar.update(1)
            running(bar.n)
            got.records.append({
                "solver": outcome.solver, "param": outcome.param, "wall_s": outcome.wall_s,
                "ok": outcome.result is not None, "error": outcome.error,
                "kind": outcome.kind,
                "meta": jsonable(outcome.result.meta) if outcome.result else {}})
            if outcome.result is None:
                got.failures.append(outcome)
                break
            try:
                got.rows[(outcome.index, order[outcome.solver])] = write_unit(
                    staging, outcome.result, solver=outcome.solver, param=outcome.param,
                    cell_size=outcome.cell_size, wall_s=outcome.wall_s,
                    written=outcome.steps_written, case=plan.points[outcome.index])
                if outcome.result.events is not None:
                    got.events[(outcome.index, order[outcome.solver])] = \
                        outcome.result.event_rows()
            except Exception as exc:  # a result that cannot be written is a failed run
                got.failures.append(_failed(outcome, "writing its results", exc))
                break
            if (outcome.index, outcome.solver) in keep:
                got.kept[(outcome.index, outcome.solver)] = outcome.result
            bucket = pending.setdefault(outcome.index, {})
            bucket[outcome.solver] = outcome.result
            if set(bucket) != expected[outcome.index]:
                continue
            ordered = {s: bucket[s] for s in sorted(bucket, key=order.get)}
            try:
                got.metrics[outcome.index] = point_rows(
                    plan.points[outcome.index], ordered,
                    probed=outcome.index in probed)
            except Exception as exc:  # a result the comparisons cannot digest
                got.failures.append(_failed(outcome, "comparing its results", exc))
                break
            del pending[outcome.index]
    finally:
        bar.close()
    return got


def _discard(staging: Path, run: CaseRun) -> None:
    """Remove the staging directory of a run the disk could not take (where the disk
    allows removing it); ``run.staging_left`` says whether it is still there."""
    try:
        remove_dir(staging)
    except OSError:
        pass
    run.staging_left = staging.exists()


def _manifest_body(plan: CasePlan, got: _Collected, t0: float, unit_wall: float,
                   sources: dict[str, str]) -> dict[str, Any]:
    """The manifest of a complete case: what ran, on what, from which sources."""
    return {
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
        "points": [dict(dataclasses.asdict(c), hertz_a0=c.hertz_scales[0],
                        hertz_p0=c.hertz_scales[1]) for c in plan.points],
        "solvers": plan.solvers,
        "skipped": plan.skipped,
        "not_run": plan.not_run(),
        "units": got.records,
        "wall_s": time.perf_counter() - t0,
        "unit_wall_s": unit_wall,
        "provenance": manifest.provenance(),
        "sources": sources,
        "sources_changed_during_run": manifest.source_hashes() != sources,
    }


def execute(plan: CasePlan, out: Path, *, executor: Executor = serial_executor,
            progress: bool | None = None, extra_manifest: dict[str, Any] | None = None
            ) -> CaseRun:
    """Run every unit of a plan and write the case directory (or leave it absent), holding
    the case's lock throughout (:func:`reports.store.staging.case_lock`).

    ``progress=None`` shows bars only on a terminal.  Failures are returned, not raised.
    """
    out = Path(out)
    with case_lock(out, plan.dir_name):
        return _execute(plan, out, executor, progress, extra_manifest or {})


def _execute(plan: CasePlan, out: Path, executor: Executor, progress: bool | None,
             extra_manifest: dict[str, Any]) -> CaseRun:
    t0 = time.perf_counter()
    sources = manifest.source_hashes()
    final = layout.case_dir(out, plan.dir_name)
    if final.exists() or final.is_symlink():
        mine = final.is_dir() and not final.is_symlink()
        other = layout.foreign(final, _study_files()) if mine else final
        if other is not None:
            raise UserError(f"{final} exists and is not a contact-vv result ({other} is not "
                            "a file a run writes); refusing to replace it (choose another "
                            "--out)")
    staging = claim_staging(out, plan.dir_name, _study_files())
    plan = replace(plan, staging=staging)
    remove_dir(final)  # an older result must not outlive a newer, failing run

    got = _collect(plan, staging, executor, progress)
    own = Own(plan.points, plan.units(), plan.applicable,
              {(i, plan.solvers[k]): rows for (i, k), rows in got.rows.items()}, got.kept)
    evidence: list[tuple[Study, StudyTable]] = []
    for planned in plan.studies:  # each study's runs, in the registry's order
        if got.failures or not (planned.runs or planned.study.table_without_runs):
            continue
        found, records = study_runs.run_study(plan, planned, executor, progress, own)
        evidence.append((planned.study, found))
        got.records += records
    unit_wall = float(sum(r["wall_s"] for r in got.records))
    run = CaseRun(plan.dir_name, None, wall_s=time.perf_counter() - t0, unit_wall_s=unit_wall)
    if got.failures:
        run.failures = [failure_line(plan.name, f) for f in got.failures]
        run.user_error = all(f.kind == "case" for f in got.failures)
        if any(f.kind == "disk" for f in got.failures):  # nothing more fits: remove it
            _discard(staging, run)
            return run
        try:
            atomic_write_text(staging / layout.FAILED, json.dumps(
                {"case": plan.name, "failures": run.failures,
                 "details": [f.detail for f in got.failures if f.detail]}, indent=1))
        except OSError as exc:
            if not disk_full(exc):
                raise
            _discard(staging, run)
        return run

    try:  # the case's tables and manifest
        summary = summary_frame([r for key in sorted(got.rows) for r in got.rows[key]])
        for study, found in evidence:
            write_csv(staging / layout.study_file(study.name), found.table)
            summary = study.summary(summary, found.table)
        write_csv(staging / layout.SUMMARY, summary)
        if got.events:  # some solver watched for regime events (reports.store.event_table)
            write_csv(staging / layout.EVENTS,
                      events_frame([r for key in sorted(got.events) for r in got.events[key]]))
        parts = [got.metrics[i] for i in sorted(got.metrics) if not got.metrics[i].empty]
        if parts:  # the verdict, once, with the studies' evidence
            rows = pd.concat(parts, ignore_index=True)
            metrics = verdict.decide(rows, [f for study, found in evidence
                                             for f in study.evidence(rows, found, own)])
        else:  # a single solver: the header only
            metrics = pd.DataFrame(columns=verdict.METRICS_COLUMNS + (
                TOLERANCE_COLUMNS if evidence else []))
        write_csv(staging / layout.METRICS, metrics)
        body = _manifest_body(plan, got, t0, unit_wall, sources)
        for planned in plan.studies:
            entry = planned.study.manifest(plan.own(), list(planned.runs))
            if entry is not None:
                body[planned.study.name] = entry
        manifest.write(staging, {**body, **extra_manifest})
    except OSError as exc:
        if not disk_full(exc):
            raise
        run.failures = [f"{plan.name}: the disk is full: the case's tables could not be "
                        f"written ({disk_error(exc)})"]
        _discard(staging, run)
        return run
    remove_dir(final)
    os.replace(staging, final)
    run.path, run.metrics = final, metrics
    return run


def run_case(case: str | Path, solvers: list[str] | None = None, *,
             out: str | Path = "results", quick: bool = False,
             overrides: dict[str, Any] | None = None) -> CaseRun:
    """``contact-vv run CASE`` from Python: plan the case (a bundled name or a TOML path;
    ``solvers`` as ``--solver``, default the built-in ones; ``overrides`` as ``--set``)
    and run it serially into ``out``; the :class:`CaseRun` says where it went or why
    it failed (``CaseError`` on bad input)."""
    from reports.run.plan import plan_case, select_solvers

    chosen, skipped = select_solvers(list(solvers or []), relations=quick)
    plan = plan_case(case, chosen, quick=quick, overrides=overrides, skipped=skipped,
                     explicit=bool(solvers))
    return execute(plan, Path(out), progress=False)
