"""The runs of the resolution probe (:mod:`reports.studies.probe`): planned with the case
(:func:`reports.run.plan.plan_case`), one run of the half-space solver per worn point the
FEM runs, run through the run's executor after the case's own units, and turned into
``probe.csv``."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import pandas as pd

from cases.result import RunResult
from reports.compare.metrics import scalar
from reports.compare.point import common_steps, pair_cell, pair_reach, step_values
from reports.registry.pairs import pairs
from reports.run.plan import CasePlan
from reports.run.study_runs import run_levels
from reports.run.units import Executor
from reports.store.study_tables import PROBE_COLUMNS
from reports.studies import probe


def kept(plan: CasePlan) -> set[tuple[int, str]]:
    """The (point, solver) units whose results the probe compares with its runs."""
    return {(g.point, g.solver) for g in plan.probes}


@dataclass
class Probed:
    """What the probe runs left: ``probe.csv``, their manifest records, and why the probe
    of a point (by its param) failed."""

    table: pd.DataFrame
    records: list[dict[str, Any]] = field(default_factory=list)
    failed: dict[str, str] = field(default_factory=dict)


def run_probes(plan: CasePlan, executor: Executor, progress: bool | None,
               own: dict[tuple[int, str], RunResult]) -> Probed:
    """Run the probes of ``plan`` (fields not written) and compare each with the point's
    own run ``own[(point, solver)]`` by every probed pair's metrics."""
    study = run_levels(plan, plan.probes, executor, progress, "probe",
                       lambda g: {"study": "probe", "width": g.width,
                                  "wear_spread": g.case.solver.wear_spread},
                       keep_results=True)
    rows: list[dict[str, Any]] = []
    failed = {}
    for g in plan.probes:
        key = (g.point, g.solver, g.level)
        result = study.results.get(key)
        if result is None:
            failed[g.case.param] = study.errors.get(key, "not run")
            continue
        rows += table_rows(plan, g, own[(g.point, g.solver)], result)
    frame = pd.DataFrame.from_records(rows, columns=PROBE_COLUMNS)
    return Probed(frame.astype({"step": "int64"}) if not frame.empty else frame,
                  study.records, failed)


def table_rows(plan: CasePlan, g: probe.ProbeRun, own: RunResult, spread: RunResult
               ) -> list[dict[str, Any]]:
    """The rows of ``probe.csv`` for probe ``g``: for every probed pair of the point and
    every output step, each quantity's change from ``own`` to ``spread`` by the pair's
    metric (:func:`reports.compare.point.step_values`)."""
    case = plan.points[g.point]
    names = [f"{a}-{b}" for a, b in pairs(plan.applicable(case))]
    out = []
    for pair in probe.probed_pairs(names):
        cell = pair_cell(case, *pair.split("-", 1))
        reach = pair_reach(case, *pair.split("-", 1))
        for n, sa, sb in common_steps(spread, own):
            for quantity, metric, value in step_values(case, pair, spread, own, sa, sb, cell,
                                                       reach):
                out.append({"param": case.param, "pair": pair, "step": n,
                            "cycle": scalar(sb, "cycle"), "quantity": quantity,
                            "metric": metric, "sensitivity": value, "width": g.width,
                            "spread": g.case.solver.wear_spread})
    return out
