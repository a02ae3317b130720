"""Read what runs left in a results directory: complete cases, incomplete ones and damaged
ones.

Every result file is read through :func:`reports.store.readers.read_result`, where a file that
cannot be decoded, or that does not hold what a run writes, becomes a
:class:`~reports.store.readers.DamagedResult` naming the file and the cause.  :func:`scan` reads and
checks every file of a case once, so a case is either fully readable (``complete``) or
listed, with the reason, as ``incomplete`` (no manifest, a failed or interrupted run,
files changed after the run) or ``damaged`` (a file that cannot be read).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from cases.result import StepResult
from reports.registry.errors import IncompleteRun, UserError
from reports.store import layout, manifest
from reports.store.event_table import COLUMNS, read_events
from reports.store.readers import (
    DamagedResult,
    Malformed,
    describe,
    read_json_object,
    read_metrics,
    read_result,
    read_step,
    read_summary,
    read_sweep_check,
    read_table,
)
from reports.store.study_tables import TABLES, read_study_table

# --------------------------------------------------------------------- results


def _step_number(path: Path) -> int:
    _, _, digits = path.stem.partition("_")
    if not digits.isdigit():
        raise DamagedResult(path, "not named step_NNNN.npz")
    return int(digits)


@dataclass
class CaseResults:
    """One complete case directory."""

    path: Path
    manifest: dict[str, Any]
    summary: pd.DataFrame
    metrics: pd.DataFrame
    _studies: dict[str, pd.DataFrame] = field(default_factory=dict, repr=False)

    @property
    def name(self) -> str:
        return str(self.manifest.get("dir") or self.manifest.get("case") or self.path.name)

    @property
    def not_run(self) -> dict[str, str]:
        """The solvers the run was asked for (or runs by default) that did not run, with
        why (:meth:`reports.run.plan.CasePlan.not_run`; a manifest written before it:
        every solver skipped)."""
        return dict(self.manifest.get("not_run", self.manifest.get("skipped", {})))

    def _step_files(self, solver: str, param: str) -> dict[int, Path]:
        folder = layout.unit_dir(self.path, solver, param)
        return {_step_number(f): f for f in sorted(folder.glob("step_*.npz"))}

    def steps(self, solver: str, param: str) -> dict[int, StepResult]:
        """Output steps of one solver at one sweep point, by step number."""
        return {n: read_result(f, read_step) for n, f in self._step_files(solver, param).items()}

    def tables(self, solver: str, param: str) -> dict[str, pd.DataFrame]:
        folder = layout.unit_dir(self.path, solver, param)
        return {f.stem: read_result(f, read_table) for f in sorted(folder.glob("*.csv"))}

    def study(self, name: str) -> pd.DataFrame:
        """The table of the run's study ``name`` (:mod:`reports.studies.study`;
        :func:`reports.store.study_tables.read_study_table`): an empty table where it did not
        run."""
        if name not in self._studies:
            self._studies[name] = read_study_table(self.path, name)
        return self._studies[name]

    @property
    def events(self) -> pd.DataFrame:
        """The regime events of the runs (``events.csv``, :mod:`reports.store.event_table`; an
        empty table when the case has none)."""
        path = self.path / layout.EVENTS
        if not path.exists():
            return pd.DataFrame(columns=COLUMNS)
        return read_result(path, read_events)

    def point(self, param: str) -> dict[str, Any]:
        """The case parameters (as recorded) of one sweep point."""
        for p in self.manifest.get("points", []):
            if p.get("param", "") == param:
                return p
        return {}

    def check_files(self) -> None:
        """Read every output step, solver table, the sweep check, the grid and jump studies
        and the events once (:class:`DamagedResult` on the first that cannot be read)."""
        for solver in self.manifest.get("solvers", []):
            for param in dict.fromkeys(self.manifest.get("params", [""])):
                for f in self._step_files(solver, param).values():
                    read_result(f, read_step)  # one at a time: a long run has many
                self.tables(solver, param)
        if (self.path / layout.SWEEP_CHECK).exists():
            read_result(self.path / layout.SWEEP_CHECK, read_sweep_check)
        for name in TABLES:
            self.study(name)
        _ = self.events


@dataclass
class Scan:
    """All cases in a results directory."""

    complete: list[CaseResults] = field(default_factory=list)
    incomplete: dict[str, str] = field(default_factory=dict)  # case -> reason
    damaged: dict[str, str] = field(default_factory=dict)  # case -> file and cause

    @property
    def empty(self) -> bool:
        return not (self.complete or self.incomplete or self.damaged)


def _read_failure(path: Path) -> list[str]:
    failures = read_json_object(path).get("failures")
    if not isinstance(failures, list) or not all(isinstance(f, str) for f in failures):
        raise Malformed("failures is not a list of strings")
    return failures


def _failure_reason(staging: Path) -> str:
    failed = staging / layout.FAILED
    if failed.exists():
        try:
            return "run failed: " + "; ".join(read_result(failed, _read_failure))
        except DamagedResult as exc:
            return f"run failed (its failure record {exc})"
    return "run interrupted or still in progress (no manifest)"


def read_case(path: Path, *, verify: bool = True) -> CaseResults:
    """One case directory, every file read (with ``verify``, also the output steps and
    tables); :class:`~reports.registry.errors.IncompleteRun` or :class:`DamagedResult` otherwise."""
    mf = manifest.read(path, verify=verify)
    case = CaseResults(path=path, manifest=mf,
                       summary=read_result(path / layout.SUMMARY, read_summary),
                       metrics=read_result(path / layout.METRICS, read_metrics))
    _check_units(case)
    if verify:
        case.check_files()
    return case


def _check_units(case: CaseResults) -> None:
    """IncompleteRun if the manifest lists no unit, or a unit that ran without a row in
    the summary (a run, or a hand edit, that dropped a solver's results)."""
    units = case.manifest.get("units")
    if units is None:  # a manifest from before units were recorded
        return
    if not units:
        raise IncompleteRun(f"{case.path}: the manifest lists no solver run")
    have = set(zip(case.summary["solver"].astype(str),
                   case.summary["param"].fillna("").astype(str), strict=True))
    for u in units:
        key = (str(u.get("solver")), str(u.get("param") or ""))
        if u.get("ok", True) and key not in have:
            raise IncompleteRun(f"{case.path}: solver {key[0]}"
                                + (f" [{key[1]}]" if key[1] else "")
                                + f" ran but has no row in {layout.SUMMARY}")


def scan(out: Path, *, verify: bool = True) -> Scan:
    """Every case directory under ``out``; :class:`UserError` if ``out`` is not one."""
    out = Path(out)
    if not out.is_dir():
        raise UserError(f"results directory {out} does not exist (run `contact-vv run` first)")
    if (out / layout.MANIFEST).exists():
        raise UserError(f"{out} is a case directory, not a results directory "
                        f"(use --out {out.parent})")
    result = Scan()
    for path in sorted(out.iterdir()):
        if not path.is_dir():
            continue
        partial = layout.partial_case_name(path)
        if partial is not None:
            result.incomplete[partial] = _failure_reason(path)
            continue
        if path.name.startswith(".") or not layout.looks_like_result(path):
            continue  # not something a run wrote
        try:
            result.complete.append(read_case(path, verify=verify))
        except DamagedResult as exc:
            result.damaged[path.name] = str(exc)
        except IncompleteRun as exc:
            result.incomplete[path.name] = str(exc)
        except OSError as exc:  # e.g. a file listed in the manifest that cannot be opened
            result.damaged[path.name] = f"{exc.filename or path}: {describe(exc)}"
    return result


def not_converged(summary: pd.DataFrame) -> pd.DataFrame:
    """Rows of a summary whose ``converged`` is false (blank means not applicable)."""
    if summary.empty or "converged" not in summary.columns:
        return summary.iloc[0:0]
    col = summary["converged"]
    text = col.astype(str).str.strip().str.lower()
    bad = text.isin(["false", "0", "0.0", "no"]) & col.notna()
    return summary[np.asarray(bad)]
