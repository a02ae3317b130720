"""Cycle-jump studies of fretting runs: ``contact-vv run CASE --jump-study`` (the runs
themselves: :mod:`reports.run.study_runs`).

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
  (:func:`reports.studies.convergence.classify`, refinement ratio 2);
- ``cell_size`` of the run's grid, for budgets in cells.

The run's own results stay those of J.  ``summary.csv`` gets a last column
:data:`FLAG_COLUMN` naming the studied quantities of a row whose study is neither
``converged`` nor ``exact``; their metric rows are marked "not converged" and not gated
when the three values spread by more than the solver's budget
(:func:`reports.studies.gridstudy.flags`), and ``gate`` prints ``NOT CONVERGED (jump)``
notes.  The extra runs cost 2 + 4 = 6 runs of the case (the simulated cycles double at
each level); ``--max-hours`` and ``--max-memory`` are checked on them before any work.
A solver without a cycle jump (a closed form, J = 1 exactly) is not studied.
"""

from __future__ import annotations

import dataclasses

import pandas as pd

from cases.model import Case
from reports.compare.verdict import Flags
from reports.registry import solvers
from reports.studies.gridstudy import Kind, flag_summary, flags, note_lines

#: the jump is halved from one level to the next
RATIO = 2.0
#: the summary.csv column naming the quantities of a row that did not converge in J
FLAG_COLUMN = "jump_not_converged"
#: how its rows read in notes: sizes are jumps J in cycles; budgets in cells use the grid
JUMP = Kind(label="jump", symbol="J", unit=" cycles", cell="cell_size")


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


def flag_summary_jump(summary: pd.DataFrame, frame: pd.DataFrame) -> pd.DataFrame:
    """``summary`` with :data:`FLAG_COLUMN` (:func:`reports.studies.gridstudy.flag_summary`)."""
    return flag_summary(summary, frame, FLAG_COLUMN)


def flags_jump(metrics: pd.DataFrame, frame: pd.DataFrame) -> Flags | None:
    """The findings of a cycle-jump study on ``metrics`` (:func:`reports.studies.gridstudy.flags`;
    budgets in cells use the run's grid)."""
    return flags(metrics, frame, JUMP)


def note_lines_jump(case: str, frame: pd.DataFrame) -> list[str]:
    """``NOT CONVERGED (jump) …`` lines for the gate."""
    return note_lines(case, frame, JUMP)
