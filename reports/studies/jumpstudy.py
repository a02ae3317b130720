"""Cycle-jump studies of fretting runs: ``contact-vv run CASE --jump-study``
(:data:`JUMP_STUDY`, a :class:`reports.studies.study.Study`; the runs themselves:
:mod:`reports.run.study_runs`).

A fretting run simulates one cycle in J (``fretting.jump``): simulated cycle n stands for
the real cycles (n − 1) J + 1 … n J and wears J times its own wear (docs/formulation.md
§3.4, §4.3).  J discretises the wear history as the grid discretises the surface, and a
number at 10⁵ cycles is only as good as its convergence in J.  For every sweep point and
numerical solver of a fretting case with J > 1 the case runs again at J/2 and J/4 — the
same grid, steps per cycle and output cycles (an output cycle on the grid of J is on
those of J/2 and J/4) — and ``jump_study.csv`` holds, for every output cycle of the run
and every studied quantity (:data:`reports.studies.gridstudy.STUDIED`):

- ``h1, h2, h3`` the jumps J/4, J/2, J (finest first, as in ``convergence.csv``) and
  ``f1, f2, f3`` the values at the same real cycle;
- ``change_halved``: (f(J/2) − f(J)) / |f(J)|, what halving the run's own jump changes;
- order, Richardson extrapolation, GCIs and status of the three levels
  (:func:`reports.studies.three_level.classify`, refinement ratio 2);
- ``cell_size`` of the run's grid, for budgets in cells.

The run's own results stay those of J.  ``summary.csv`` gets a last column
:data:`FLAG_COLUMN` naming the studied quantities of a row whose study is neither
``converged`` nor ``exact``; their metric rows are marked "not gated" (``jump_study``)
when the three values spread by more than the solver's budget
(:func:`reports.studies.gridstudy.flags`), and ``gate`` prints ``UNSETTLED (jump)``
notes.  The extra runs cost 2 + 4 = 6 runs of the case (the simulated cycles double at
each level); ``--max-hours`` and ``--max-memory`` are checked on them before any work.
A solver without a cycle jump (a closed form, J = 1 exactly) is not studied.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import pandas as pd

from cases.model import Case, CaseError
from reports.compare.verdict import Evidence, Flags
from reports.registry import solvers
from reports.store.study_tables import JUMP_COLUMNS
from reports.studies.gridstudy import (
    STUDIED,
    Kind,
    flag_summary,
    flags,
    note_lines,
    study_row,
    value_of,
)
from reports.studies.study import Check, Levels, Own, Study, StudyRun, StudyTable

#: the jump is halved from one level to the next
RATIO = 2.0
#: the summary.csv column naming the quantities of a row that did not converge in J
FLAG_COLUMN = "jump_not_converged"
#: how its rows read in notes: sizes are jumps J in cycles; budgets in cells use the grid
JUMP = Kind(label="jump", symbol="J", unit=" cycles", cell="cell_size", reason="jump_study")


def not_studied(solver: str, case: Case) -> str | None:
    """Why (``solver``, ``case``) gets no jump study, None if it does."""
    if case.kind != "fretting" or case.fretting is None:
        return f"a {case.kind} case has no cycle jump"
    if solvers.record(solver).closed_form:
        return "a closed form has no cycle jump"
    if solvers.record(solver).base:
        return "a metamorphic relation is compared with its base, not studied"
    if case.fretting.jump <= 1.0:
        return f"fretting.jump = {case.fretting.jump:g}: every cycle is simulated"
    return None


def finer_cases(case: Case) -> list[Case]:
    """``case`` at J/2 and J/4 (levels 2 and 3 of the study; 1 is the run's J)."""
    fr = case.fretting
    assert fr is not None
    return [case.with_changes(fretting=dataclasses.replace(fr, jump=fr.jump / k))
            for k in (RATIO, RATIO * RATIO)]


def by_cycle(rows: list[dict[str, Any]]) -> dict[float, dict[str, Any]]:
    """Summary rows by cycle (rows without one left out)."""
    return {float(r["cycle"]): r for r in rows
            if r.get("cycle") is not None and math.isfinite(float(r["cycle"]))}


class JumpStudy(Study):
    """The cycle-jump studies of ``run --jump-study`` (module doc) as a
    :class:`reports.studies.study.Study`."""

    name, option, label = "jump_study", "--jump-study", "jumps"

    def plan(self, own: Own, check: Check) -> list[StudyRun]:
        """J/2 and J/4 of every studied unit, checked before any work (``CaseError``
        naming the level)."""
        runs = []
        for i, s in own.units:
            case = own.points[i]
            if not_studied(s, case) is not None:
                continue
            where = case.name + (f" [{case.param}]" if case.param else "")
            for level, c in zip((2, 3), finer_cases(case), strict=True):
                try:
                    reason = solvers.unsupported(s, c)
                    if reason is not None:
                        raise CaseError(f"solver {s} does not support J = "
                                        f"{c.fretting.jump:g}: {reason}")
                    check(c, s)
                except CaseError as exc:
                    raise CaseError(f"{self.option}: {where}: {exc}") from None
                runs.append(StudyRun(i, s, level, c))
        return runs

    def describe(self, run: StudyRun) -> dict[str, Any]:
        return {"study": "jump", "level": run.level, "jump": run.case.fretting.jump}

    def table(self, own: Own, runs: list[StudyRun], levels: Levels) -> StudyTable:
        """``jump_study.csv``: one row per (solver, sweep point, output cycle, quantity)."""
        rows = []
        for i, s in dict.fromkeys((g.point, g.solver) for g in runs):
            case = own.points[i]
            J = case.fretting.jump
            fine = by_cycle(own.rows.get((i, s), []))
            at, failed = [], []
            for level in (2, 3):
                key = (i, s, level)
                if key in levels.rows:
                    at.append(by_cycle(levels.rows[key]))
                else:
                    at.append({})
                    failed.append(f"J/{RATIO ** (level - 1):g} failed "
                                  f"({levels.errors.get(key, 'not run')})")
            h = (J / RATIO ** 2, J / RATIO, J)
            cell = solvers.record(s).cell_size(case)
            for cycle in sorted(fine):
                f_own = fine[cycle]
                for q in STUDIED:
                    f = (value_of(at[1].get(cycle), q), value_of(at[0].get(cycle), q),
                         value_of(f_own, q))
                    if q not in f_own or all(math.isnan(v) for v in f):
                        continue  # the solver does not report it
                    row = study_row(s, case.param, int(f_own["step"]), q, h, f, failed)
                    change = (f[1] - f[2]) / abs(f[2]) if f[2] != 0 else \
                        (0.0 if f[1] == 0 else math.inf)
                    rows.append({**row, "cycle": cycle, "change_halved": change,
                                 "cell_size": cell})
        frame = pd.DataFrame.from_records(rows, columns=JUMP_COLUMNS)
        return StudyTable(frame.astype({"step": "int64"}) if not frame.empty else frame)

    def summary(self, summary: pd.DataFrame, table: pd.DataFrame) -> pd.DataFrame:
        return flag_summary(summary, table, FLAG_COLUMN)

    def evidence(self, rows: pd.DataFrame, evidence: StudyTable, own: Own) -> list[Evidence]:
        """The jumps' flags (:func:`reports.studies.gridstudy.flags`; budgets in cells use
        the run's grid), after the uncertainty."""
        found = flags(rows, evidence.table, JUMP)
        return [] if found is None else [Flags(found.dropped, found.kept, late=True,
                                                   reason=JUMP.reason)]

    def manifest(self, own: Own, runs: list[StudyRun]) -> dict[str, Any]:
        """The ratio, the quantities and, per (point, solver), the jumps studied or why
        not."""
        units = []
        for i, s in own.units:
            case = own.points[i]
            why = not_studied(s, case)
            entry: dict[str, Any] = {"solver": s, "param": case.param}
            if why is None:
                entry["jumps"] = [case.fretting.jump / RATIO ** k for k in range(3)]
            else:
                entry["not_studied"] = why
            units.append(entry)
        return {"ratio": RATIO, "quantities": list(STUDIED), "units": units}

    def notes(self, case: str, table: pd.DataFrame) -> list[str]:
        """``UNSETTLED (jump) …`` lines for the gate."""
        return note_lines(case, table, JUMP)

    def nothing_planned(self, owns: list[Own]) -> str:
        why = sorted({f"{own.points[i].name}: {not_studied(s, own.points[i])}"
                      for own in owns for i, s in own.units})
        return "no run has a cycle jump to halve (" + "; ".join(why) + ")"

    def idle_note(self, own: Own) -> str | None:
        if not any(c.kind == "fretting" for c in own.points):
            return None
        return (f"{own.points[0].name}: no cycle jump to halve (fretting.jump = "
                f"{own.points[0].fretting.jump:g})")


JUMP_STUDY = JumpStudy()
