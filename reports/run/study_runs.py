"""The extra runs of a run's studies (:class:`reports.studies.study.Study`), run through the
run's executor after the case's own units, without fields, and turned into the study's
evidence: its table and why its runs failed."""

from __future__ import annotations

from dataclasses import replace
from typing import Any

from tqdm.auto import tqdm

from reports.run.plan import CasePlan
from reports.run.units import Executor
from reports.store.write import jsonable
from reports.studies.gridstudy import changes
from reports.studies.study import Levels, Own, Planned, StudyTable


def run_levels(plan: CasePlan, planned: Planned, executor: Executor, progress: bool | None
               ) -> Levels:
    """Run the runs of ``planned`` through ``executor`` without fields: their summary rows
    (or why there are none) keyed (point, solver, level), the results themselves where the
    study keeps them, and their manifest records, with the study's keys, in the planned
    order."""
    study, runs = planned.study, list(planned.runs)
    sub = replace(plan, points=[g.case for g in runs], staging=None, studies=())
    units = [(k, g.solver) for k, g in enumerate(runs)]
    levels = Levels()
    order = {s: k for k, s in enumerate(plan.solvers)}
    keyed: list[tuple[tuple[int, int, int], dict[str, Any]]] = []
    bar = tqdm(total=len(units), desc=f"{plan.dir_name} {study.label}", unit="run",
               leave=False, disable=None if progress is None else not progress)
    try:
        for outcome in executor(sub, units, bool(progress)):
            bar.update(1)
            g = runs[outcome.index]
            key = (g.point, g.solver, g.level)
            if outcome.result is not None:  # keep the scalars only, not the fields
                levels.rows[key] = outcome.result.summary_rows()
                if study.keeps_results:
                    levels.results[key] = outcome.result
            else:
                levels.errors[key] = f"{outcome.kind or 'failed'}: {outcome.error}"
            keyed.append(((g.point, order.get(g.solver, len(order)), g.level), {
                "solver": outcome.solver, "param": outcome.param, "wall_s": outcome.wall_s,
                "ok": outcome.result is not None, "error": outcome.error,
                "kind": outcome.kind, **study.describe(g),
                "changes": jsonable(changes(plan.points[g.point], g.case)),
                "meta": jsonable(outcome.result.meta) if outcome.result else {}}))
    finally:
        bar.close()
    levels.records = [r for _, r in sorted(keyed, key=lambda kr: kr[0])]  # as planned
    return levels


def run_study(plan: CasePlan, planned: Planned, executor: Executor, progress: bool | None,
              own: Own) -> tuple[StudyTable, list[dict[str, Any]]]:
    """Run the study ``planned`` of ``plan`` and build its evidence against the run's own
    units ``own``: (evidence, the runs' manifest records)."""
    levels = run_levels(plan, planned, executor, progress)
    return planned.study.table(own, list(planned.runs), levels), levels.records
