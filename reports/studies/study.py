"""A study of a run, as one base class with defaults (:class:`Study`): extra runs of a
case's units, a table built from them, and the evidence that table gives the verdict.

A study plans its runs before any work (:meth:`Study.plan`); the runner runs them through
the run's executor after the case's own units, without fields
(:func:`reports.run.study_runs.run_study`); the study turns them into its table
(:meth:`Study.table`, written as :func:`reports.store.layout.study_file` of its name),
a column of ``summary.csv`` (:meth:`Study.summary`), evidence on the metric rows
(:meth:`Study.evidence`, folded by :func:`reports.compare.verdict.decide`), the
manifest's entry (:meth:`Study.manifest`) and the gate's notes (:meth:`Study.notes`).
The studies a run knows are listed once, in :data:`reports.studies.registry.STUDIES`;
adding one is a module and a line there.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

import pandas as pd

from cases.model import Case
from cases.result import RunResult
from reports.compare.verdict import Evidence


@dataclass(frozen=True)
class StudyRun:
    """One extra run of a study: sweep point ``point``, ``solver``, ``level`` (2 or 3 of a
    three-level study, whose level 1 is the run's own; 0 for a single run) on ``case``."""

    point: int
    solver: str
    level: int
    case: Case


@dataclass
class Levels:
    """What the extra runs of a study left, keyed (point, solver, level): summary rows,
    the results themselves where the study keeps them (:attr:`Study.keeps_results`),
    why a run left none, and the runs' manifest records in the planned order."""

    rows: dict[tuple[int, str, int], list[dict[str, Any]]] = field(default_factory=dict)
    results: dict[tuple[int, str, int], RunResult] = field(default_factory=dict)
    errors: dict[tuple[int, str, int], str] = field(default_factory=dict)
    records: list[dict[str, Any]] = field(default_factory=list)


@dataclass(frozen=True)
class Own:
    """The run's own units, which a study compares its runs with: the sweep points, the
    (point, solver) units, the solvers in registry order, the applicable solvers of each
    point, the summary rows of each unit and the results kept for the studies."""

    points: list[Case]
    units: list[tuple[int, str]]
    applicable: Callable[[Case], list[str]]
    rows: Mapping[tuple[int, str], list[dict[str, Any]]] = field(default_factory=dict)
    results: Mapping[tuple[int, str], RunResult] = field(default_factory=dict)


@dataclass(frozen=True)
class StudyTable:
    """A study's table and why the runs of a point failed (param -> cause)."""

    table: pd.DataFrame
    failed: Mapping[str, str] = field(default_factory=dict)


#: checks a unit of a study before any work (``CaseError``): the case's contact within its
#: grid, the run's limits (:meth:`reports.run.plan.Limits.check`)
Check = Callable[[Case, str], None]


class Study(ABC):
    """One study of a run (module doc), as a base with defaults: a study implements
    :meth:`plan`, :meth:`table`, :meth:`evidence` and :meth:`nothing_planned`, and
    overrides the others only where it adds something.  ``name`` is its key in the
    manifest and in :meth:`reports.store.results.CaseResults.study`, and names its
    table; ``option`` is the flag of ``run`` that asks for it (None: it runs wherever it
    plans runs); ``label`` names its progress bar."""

    name: str
    label: str
    option: str | None = None
    keeps_results: bool = False  # it compares whole results of the run's units
    table_without_runs: bool = False  # asked for, it writes its (empty) table anyway

    @abstractmethod
    def plan(self, own: Own, check: Check) -> list[StudyRun]:
        """Its runs for the run's units, checked before any work (``CaseError``)."""

    def describe(self, run: StudyRun) -> dict[str, Any]:
        """What the manifest's record of ``run`` says beyond the unit's own keys."""
        return {}

    @abstractmethod
    def table(self, own: Own, runs: list[StudyRun], levels: Levels) -> StudyTable:
        """Its table from the run's own units and its runs."""

    def summary(self, summary: pd.DataFrame, table: pd.DataFrame) -> pd.DataFrame:
        """``summary.csv`` with the study's column, if it adds one (default: as it is)."""
        return summary

    @abstractmethod
    def evidence(self, rows: pd.DataFrame, evidence: StudyTable, own: Own) -> list[Evidence]:
        """Its evidence on the metric rows, for :func:`reports.compare.verdict.decide`."""

    def manifest(self, own: Own, runs: list[StudyRun]) -> dict[str, Any] | None:
        """The manifest's entry under :attr:`name` (default None: none)."""
        return None

    def notes(self, case: str, table: pd.DataFrame) -> list[str]:
        """The gate's notes on the case from its table (default: none)."""
        return []

    @abstractmethod
    def nothing_planned(self, owns: list[Own]) -> str:
        """Why no run of ``owns`` gets this study, for a user who asked for it."""

    def idle_note(self, own: Own) -> str | None:
        """A note on a case that gets no run of this study, where it deserves one
        (default None)."""
        return None


@dataclass(frozen=True)
class Planned:
    """A study a run holds, with its runs planned before any work."""

    study: Study
    runs: tuple[StudyRun, ...] = ()
