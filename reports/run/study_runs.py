"""The extra runs of a run's studies: the coarse grids of ``run --convergence``
(:mod:`reports.studies.gridstudy`) and the smaller cycle jumps of ``run --jump-study``
(:mod:`reports.studies.jumpstudy`), planned before any work, run through the run's
executor without fields, and turned into ``convergence.csv`` and ``jump_study.csv``."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

import pandas as pd
from tqdm.auto import tqdm

from cases.model import Case, CaseError
from reports.registry import solvers
from reports.run.plan import CasePlan, Limits, check_fits
from reports.run.units import Executor
from reports.store.study_tables import CONVERGENCE_COLUMNS, JUMP_COLUMNS
from reports.store.write import jsonable
from reports.studies.gridstudy import RATIO, STUDIED, changes, coarse_cases, study_row, value_of
from reports.studies.jumpstudy import RATIO as JUMP_RATIO
from reports.studies.jumpstudy import finer_cases, not_studied


@dataclass(frozen=True)
class GridRun:
    """One extra run of a study: sweep point ``point``, ``solver``, ``level`` 2 or 3
    (1 is the run's own), on ``case`` (a coarser grid here, a smaller cycle jump in
    :mod:`reports.studies.jumpstudy`)."""

    point: int
    solver: str
    level: int
    case: Case


def grid_studied(plan: CasePlan) -> list[tuple[int, str]]:
    """The (point, solver) units of ``plan`` that get a grid study: numerical solvers
    whose record knows how to refine."""
    return [(i, s) for i, s in plan.units()
            if solvers.record(s).refine is not None and not solvers.record(s).closed_form]


def add_grids(plan: CasePlan, limits: Limits | None = None) -> CasePlan:
    """``plan`` with the grid studies of ``run --convergence``: :func:`plan_grids`."""
    return replace(plan, convergence=True, grids=plan_grids(plan, limits))


def add_grid_studies(plans: list[CasePlan], limits: Limits | None) -> list[CasePlan]:
    """``plans`` with their grid studies (:func:`add_grids`); UserError if no run has a
    grid to refine (closed forms only: the flag would do nothing)."""
    from reports.registry.errors import UserError

    plans = [add_grids(p, limits) for p in plans]
    if not any(p.grids for p in plans):
        names = sorted({s for p in plans for _, s in p.units()})
        raise UserError(f"--convergence: no run has a grid to refine (solver(s) "
                        f"{', '.join(names)}: closed forms have none); add a numerical "
                        "solver, e.g. --solver ic")
    return plans


def plan_grids(plan: CasePlan, limits: Limits | None = None) -> list[GridRun]:
    """The coarse runs of the grid studies of ``plan``, validated like the case itself
    (contact within the grid, solver support, limits): ``CaseError`` naming the grid."""
    runs = []
    for i, s in grid_studied(plan):
        case = plan.points[i]
        where = case.name + (f" [{case.param}]" if case.param else "")
        try:
            coarse = coarse_cases(s, case)
            for level, c in zip((2, 3), coarse, strict=True):
                check_fits(c)
                reason = solvers.unsupported(s, c)
                if reason is not None:
                    raise CaseError(f"solver {s} does not support grid {level}: {reason}")
                if limits is not None:
                    limits.check(c, s)
                runs.append(GridRun(i, s, level, c))
        except CaseError as exc:
            raise CaseError(f"--convergence: {where}: {exc}") from None
    return runs


def grid_manifest_entry(plan: CasePlan) -> dict[str, Any]:
    """What the manifest records of the studies: the ratio and, per coarse run, its keys."""
    return {"ratio": RATIO, "quantities": list(STUDIED),
            "grids": [{"solver": g.solver, "param": g.case.param, "grid": g.level,
                       "cell_size": solvers.record(g.solver).cell_size(g.case),
                       "changes": jsonable(changes(plan.points[g.point], g.case))}
                      for g in plan.grids]}


@dataclass
class Study:
    """What the coarse runs left: summary rows (or why there are none) per (point,
    solver, grid), their manifest records, and the table built from them."""

    rows: dict[tuple[int, str, int], list[dict[str, Any]]] = field(default_factory=dict)
    results: dict[tuple[int, str, int], Any] = field(default_factory=dict)  # keep_results
    errors: dict[tuple[int, str, int], str] = field(default_factory=dict)
    records: list[dict[str, Any]] = field(default_factory=list)
    table: pd.DataFrame | None = None


def run_grids(plan: CasePlan, executor: Executor, progress: bool | None,
              fine_rows: dict[tuple[int, str], list[dict[str, Any]]]) -> Study:
    """Run the coarse grids of ``plan`` through ``executor`` (fields not written) and
    build the convergence table against ``fine_rows`` ((point, solver) -> summary rows of
    the run's own grid)."""
    study = run_levels(plan, plan.grids, executor, progress, "grids", lambda g: {
        "grid": g.level, "cell_size": solvers.record(g.solver).cell_size(g.case)})
    study.table = grid_table(plan, fine_rows, study)
    return study


def run_levels(plan: CasePlan, runs: list[Any], executor: Executor, progress: bool | None,
               label: str, describe: Callable[[Any], dict[str, Any]],
               keep_results: bool = False) -> Study:
    """Run the extra levels ``runs`` of a study (items with ``point, solver, level,
    case``) through ``executor`` without fields: their summary rows (or why there are
    none) keyed (point, solver, level), the results themselves if ``keep_results``, and
    their manifest records, with ``describe``'s keys, in the planned order."""
    sub = replace(plan, points=[g.case for g in runs], staging=None,
                  grids=[], jumps=[], probes=[])
    units = [(k, g.solver) for k, g in enumerate(runs)]
    study = Study()
    order = {s: k for k, s in enumerate(plan.solvers)}
    keyed: list[tuple[tuple[int, int, int], dict[str, Any]]] = []
    bar = tqdm(total=len(units), desc=f"{plan.dir_name} {label}", unit="run", leave=False,
               disable=None if progress is None else not progress)
    try:
        for outcome in executor(sub, units, bool(progress)):
            bar.update(1)
            g = runs[outcome.index]
            key = (g.point, g.solver, g.level)
            if outcome.result is not None:  # keep the scalars only, not the fields
                study.rows[key] = outcome.result.summary_rows()
                if keep_results:
                    study.results[key] = outcome.result
            else:
                study.errors[key] = f"{outcome.kind or 'failed'}: {outcome.error}"
            keyed.append(((g.point, order.get(g.solver, len(order)), g.level), {
                "solver": outcome.solver, "param": outcome.param, "wall_s": outcome.wall_s,
                "ok": outcome.result is not None, "error": outcome.error,
                "kind": outcome.kind, **describe(g),
                "changes": jsonable(changes(plan.points[g.point], g.case)),
                "meta": jsonable(outcome.result.meta) if outcome.result else {}}))
    finally:
        bar.close()
    study.records = [r for _, r in sorted(keyed, key=lambda kr: kr[0])]  # as planned
    return study


def _by_step(rows: list[dict[str, Any]]) -> dict[int, dict[str, Any]]:
    return {int(r["step"]): r for r in rows}


def grid_table(plan: CasePlan, fine_rows: dict[tuple[int, str], list[dict[str, Any]]],
          study: Study) -> pd.DataFrame:
    """``convergence.csv``: one row per (solver, sweep point, step, gated quantity)."""
    rows = []
    for i, s in grid_studied(plan):
        case = plan.points[i]
        rec = solvers.record(s)
        fine = _by_step(fine_rows.get((i, s), []))
        coarse, h, failed = [], [rec.cell_size(case)], []
        for level in (2, 3):
            key = (i, s, level)
            g = next(g for g in plan.grids if (g.point, g.solver, g.level) == key)
            h.append(rec.cell_size(g.case))
            if key in study.rows:
                coarse.append(_by_step(study.rows[key]))
            else:
                coarse.append({})
                failed.append(f"grid {level} failed ({study.errors.get(key, 'not run')})")
        for step in sorted(fine):
            for q in STUDIED:
                f = (value_of(fine[step], q), value_of(coarse[0].get(step), q),
                     value_of(coarse[1].get(step), q))
                if q not in fine[step] or all(math.isnan(v) for v in f):
                    continue  # the solver does not report it
                rows.append(study_row(s, case.param, step, q, tuple(h), f, failed))
    frame = pd.DataFrame.from_records(rows, columns=CONVERGENCE_COLUMNS)
    return frame.astype({"step": "int64"}) if not frame.empty else frame


def add_jumps(plan: CasePlan, limits: Limits | None = None) -> CasePlan:
    """``plan`` with the runs of its jump studies, checked against ``limits`` and the
    solvers' support before any work (``CaseError`` naming the level)."""
    runs = []
    for i, s in plan.units():
        case = plan.points[i]
        if not_studied(s, case) is not None:
            continue
        where = case.name + (f" [{case.param}]" if case.param else "")
        for level, c in zip((2, 3), finer_cases(case), strict=True):
            try:
                reason = solvers.unsupported(s, c)
                if reason is not None:
                    raise CaseError(f"solver {s} does not support J = {c.fretting.jump:g}: "
                                    f"{reason}")
                if limits is not None:
                    limits.check(c, s)
            except CaseError as exc:
                raise CaseError(f"--jump-study: {where}: {exc}") from None
            runs.append(GridRun(i, s, level, c))
    return replace(plan, jump_study=True, jumps=runs)


def jump_studied(plan: CasePlan) -> list[tuple[int, str]]:
    return list(dict.fromkeys((g.point, g.solver) for g in plan.jumps))


def jump_manifest_entry(plan: CasePlan) -> dict[str, Any]:
    """The ratio, the quantities and, per (point, solver), the jumps studied or why not."""
    units = []
    for i, s in plan.units():
        case = plan.points[i]
        why = not_studied(s, case)
        entry: dict[str, Any] = {"solver": s, "param": case.param}
        if why is None:
            entry["jumps"] = [case.fretting.jump / JUMP_RATIO ** k for k in range(3)]
        else:
            entry["not_studied"] = why
        units.append(entry)
    return {"ratio": JUMP_RATIO, "quantities": list(STUDIED), "units": units}


def run_jumps(plan: CasePlan, executor: Executor, progress: bool | None,
              fine_rows: dict[tuple[int, str], list[dict[str, Any]]]) -> Study:
    """Run J/2 and J/4 of every studied unit (fields not written) and build the table
    against ``fine_rows`` ((point, solver) -> summary rows of the run's own J)."""
    study = run_levels(plan, plan.jumps, executor, progress, "jumps", lambda g: {
        "study": "jump", "level": g.level, "jump": g.case.fretting.jump})
    study.table = jump_table(plan, fine_rows, study)
    return study


def _by_cycle(rows: list[dict[str, Any]]) -> dict[float, dict[str, Any]]:
    return {float(r["cycle"]): r for r in rows
            if r.get("cycle") is not None and math.isfinite(float(r["cycle"]))}


def jump_table(plan: CasePlan, fine_rows: dict[tuple[int, str], list[dict[str, Any]]],
          study: Study) -> pd.DataFrame:
    """``jump_study.csv``: one row per (solver, sweep point, output cycle, quantity)."""
    rows = []
    for i, s in jump_studied(plan):
        case = plan.points[i]
        J = case.fretting.jump
        fine = _by_cycle(fine_rows.get((i, s), []))
        levels, failed = [], []
        for level in (2, 3):
            key = (i, s, level)
            if key in study.rows:
                levels.append(_by_cycle(study.rows[key]))
            else:
                levels.append({})
                failed.append(f"J/{JUMP_RATIO ** (level - 1):g} failed "
                              f"({study.errors.get(key, 'not run')})")
        h = (J / JUMP_RATIO ** 2, J / JUMP_RATIO, J)
        cell = solvers.record(s).cell_size(case)
        for cycle in sorted(fine):
            own = fine[cycle]
            for q in STUDIED:
                f = (value_of(levels[1].get(cycle), q), value_of(levels[0].get(cycle), q),
                     value_of(own, q))
                if q not in own or all(math.isnan(v) for v in f):
                    continue  # the solver does not report it
                row = study_row(s, case.param, int(own["step"]), q, h, f, failed)
                change = (f[1] - f[2]) / abs(f[2]) if f[2] != 0 else \
                    (0.0 if f[1] == 0 else math.inf)
                rows.append({**row, "cycle": cycle, "change_halved": change,
                             "cell_size": cell})
    frame = pd.DataFrame.from_records(rows, columns=JUMP_COLUMNS)
    return frame.astype({"step": "int64"}) if not frame.empty else frame


def add_jump_studies(plans: list[CasePlan], limits: Limits | None
                     ) -> tuple[list[CasePlan], list[str]]:
    """``plans`` with their cycle-jump studies (:func:`add_jumps`) and a note per fretting
    case without a jump to halve; UserError if no plan has one."""
    from reports.registry.errors import UserError

    plans = [add_jumps(p, limits) for p in plans]
    if not any(p.jumps for p in plans):
        why = sorted({f"{p.points[i].name}: {not_studied(s, p.points[i])}"
                      for p in plans for i, s in p.units()})
        raise UserError("--jump-study: no run has a cycle jump to halve (" + "; ".join(why)
                        + ")")
    notes = [f"{p.name}: no cycle jump to halve (fretting.jump = "
             f"{p.points[0].fretting.jump:g})" for p in plans
             if not p.jumps and any(c.kind == "fretting" for c in p.points)]
    return plans, notes
