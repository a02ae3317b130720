"""Cycle-jump studies of fretting runs: ``contact-vv run CASE --jump-study``.

A fretting run simulates one cycle in J (``fretting.jump``): simulated cycle n stands for
the real cycles (n − 1) J + 1 … n J and wears J times its own wear (docs/formulation.md
§3.4, §4.3).  J discretises the wear history as the grid discretises the surface, and a
number at 10⁵ cycles is only as good as its convergence in J.  For every sweep point and
numerical solver of a fretting case with J > 1 the case runs again at J/2 and J/4 — the
same grid, steps per cycle and output cycles (an output cycle on the grid of J is on
those of J/2 and J/4) — and ``jump_study.csv`` holds, for every output cycle of the run
and every studied quantity (:data:`reports.gridstudy.GATED`):

- ``h1, h2, h3`` the jumps J/4, J/2, J (finest first, as in ``convergence.csv``) and
  ``f1, f2, f3`` the values at the same real cycle;
- ``change_halved``: (f(J/2) − f(J)) / |f(J)|, what halving the run's own jump changes;
- order, Richardson extrapolation, GCIs and status of the three levels
  (:func:`reports.convergence.classify`, refinement ratio 2);
- ``cell_size`` of the run's grid, for budgets in cells.

The run's own results stay those of J.  ``summary.csv`` gets a last column
:data:`FLAG_COLUMN` naming the studied quantities of a row whose study is neither
``converged`` nor ``exact``; their metric rows are marked "not converged" and not gated
when the three values spread by more than the solver's budget
(:func:`reports.gridstudy.flag_metrics`), and ``gate`` prints ``NOT CONVERGED (jump)``
notes.  The extra runs cost 2 + 4 = 6 runs of the case (the simulated cycles double at
each level); ``--max-hours`` and ``--max-memory`` are checked on them before any work.
A solver without a cycle jump (a closed form, J = 1 exactly) is not studied.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path
from typing import Any

import pandas as pd

from cases.model import Case, CaseError

from . import solvers
from .gridstudy import (
    GATED,
    Executor,
    GridRun,
    Kind,
    Study,
    flag_metrics,
    flag_summary,
    note_lines,
    read_study,
    study_row,
    value_of,
)
from .plan import CasePlan, Limits

#: the jump is halved from one level to the next
RATIO = 2.0
#: the summary.csv column naming the quantities of a row that did not converge in J
FLAG_COLUMN = "jump_not_converged"
COLUMNS = ["solver", "param", "cycle", "step", "quantity", "h1", "h2", "h3", "f1", "f2",
           "f3", "change_halved", "order", "f_extrapolated", "gci_fine", "status",
           "gci_coarse", "asymptotic", "note", "cell_size"]
#: how its rows read in notes: sizes are jumps J in cycles; budgets in cells use the grid
JUMP = Kind(label="jump", symbol="J", unit=" cycles", cell="cell_size")

__all__ = ["COLUMNS", "FLAG_COLUMN", "JUMP", "RATIO", "add_jumps", "flag_metrics_jump",
           "flag_summary_jump", "manifest_entry", "not_studied", "note_lines_jump",
           "read_jump_study", "run", "table"]


def not_studied(solver: str, case: Case) -> str | None:
    """Why (``solver``, ``case``) gets no jump study, None if it does."""
    if case.kind != "fretting" or case.fretting is None:
        return f"a {case.kind} case has no cycle jump"
    if solvers.record(solver).closed_form:
        return "a closed form has no cycle jump"
    if case.fretting.jump <= 1.0:
        return f"fretting.jump = {case.fretting.jump:g}: every cycle is simulated"
    return None


def finer_cases(case: Case) -> list[Case]:
    """``case`` at J/2 and J/4 (levels 2 and 3 of the study; 1 is the run's J)."""
    fr = case.fretting
    assert fr is not None
    return [case.with_changes(fretting=dataclasses.replace(fr, jump=fr.jump / k))
            for k in (RATIO, RATIO * RATIO)]


def add_jumps(plan: CasePlan, limits: Limits | None = None) -> CasePlan:
    """``plan`` with the runs of its jump studies, checked against ``limits`` and the
    solvers' support before any work (``CaseError`` naming the level)."""
    plan.jump_study = True
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
    plan.jumps = runs
    return plan


def studied(plan: CasePlan) -> list[tuple[int, str]]:
    return list(dict.fromkeys((g.point, g.solver) for g in plan.jumps))


def manifest_entry(plan: CasePlan) -> dict[str, Any]:
    """The ratio, the quantities and, per (point, solver), the jumps studied or why not."""
    units = []
    for i, s in plan.units():
        case = plan.points[i]
        why = not_studied(s, case)
        entry: dict[str, Any] = {"solver": s, "param": case.param}
        if why is None:
            entry["jumps"] = [case.fretting.jump / RATIO ** k for k in range(3)]
        else:
            entry["not_studied"] = why
        units.append(entry)
    return {"ratio": RATIO, "quantities": list(GATED), "units": units}


def run(plan: CasePlan, executor: Executor, progress: bool | None,
        fine_rows: dict[tuple[int, str], list[dict[str, Any]]]) -> Study:
    """Run J/2 and J/4 of every studied unit (fields not written) and build the table
    against ``fine_rows`` ((point, solver) -> summary rows of the run's own J)."""
    from .gridstudy import run_levels

    study = run_levels(plan, plan.jumps, executor, progress, "jumps", lambda g: {
        "study": "jump", "level": g.level, "jump": g.case.fretting.jump})
    study.table = table(plan, fine_rows, study)
    return study


def _by_cycle(rows: list[dict[str, Any]]) -> dict[float, dict[str, Any]]:
    return {float(r["cycle"]): r for r in rows
            if r.get("cycle") is not None and math.isfinite(float(r["cycle"]))}


def table(plan: CasePlan, fine_rows: dict[tuple[int, str], list[dict[str, Any]]],
          study: Study) -> pd.DataFrame:
    """``jump_study.csv``: one row per (solver, sweep point, output cycle, quantity)."""
    rows = []
    for i, s in studied(plan):
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
                failed.append(f"J/{RATIO ** (level - 1):g} failed "
                              f"({study.errors.get(key, 'not run')})")
        h = (J / RATIO ** 2, J / RATIO, J)
        cell = solvers.record(s).cell_size(case)
        for cycle in sorted(fine):
            own = fine[cycle]
            for q in GATED:
                f = (value_of(levels[1].get(cycle), q), value_of(levels[0].get(cycle), q),
                     value_of(own, q))
                if q not in own or all(math.isnan(v) for v in f):
                    continue  # the solver does not report it
                row = study_row(s, case.param, int(own["step"]), q, h, f, failed)
                change = (f[1] - f[2]) / abs(f[2]) if f[2] != 0 else \
                    (0.0 if f[1] == 0 else math.inf)
                rows.append({**row, "cycle": cycle, "change_halved": change,
                             "cell_size": cell})
    frame = pd.DataFrame.from_records(rows, columns=COLUMNS)
    return frame.astype({"step": "int64"}) if not frame.empty else frame


def flag_summary_jump(summary: pd.DataFrame, frame: pd.DataFrame) -> pd.DataFrame:
    """``summary`` with :data:`FLAG_COLUMN` (:func:`reports.gridstudy.flag_summary`)."""
    return flag_summary(summary, frame, FLAG_COLUMN)


def flag_metrics_jump(metrics: pd.DataFrame, frame: pd.DataFrame) -> pd.DataFrame:
    """``metrics`` with the rows of quantities not converged in J not gated
    (:func:`reports.gridstudy.flag_metrics`; budgets in cells use the run's grid)."""
    return flag_metrics(metrics, frame, JUMP)


def note_lines_jump(case: str, frame: pd.DataFrame) -> list[str]:
    """``NOT CONVERGED (jump) …`` lines for the gate."""
    return note_lines(case, frame, JUMP)


def read_jump_study(path: Path) -> pd.DataFrame:
    """``jump_study.csv`` as a run writes it (a parser for
    :func:`reports.readers.read_result`); ``Malformed`` otherwise."""
    return read_study(path, COLUMNS, COLUMNS)
