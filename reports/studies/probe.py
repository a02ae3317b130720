"""The resolution probe: which compared quantities of a worn contact a solver's surface
resolution can give (issue 51; :data:`PROBE`, a :class:`reports.studies.study.Study`, run
wherever it plans runs).

Wear leaves a step in the worn profile where slip meets stick. The half-space solver holds
it sharp at a cell face; a solver whose surface is polynomial within an element
(the FEM, :attr:`reports.registry.record.SolverRecord.step_width`) resolves it only
across about an element, and quantities that depend on the step's sharpness part the
two solvers by more than either's discretisation error would suggest
(docs/fem-notes.md, part 5).  The probe measures that dependence, point by point: the
half-space solver runs the point once more with every committed wear increment spread by
a tent of half-width r = :data:`SPREAD` × the element width
(:mod:`halfspace.wear_spread`), and each quantity's change is computed by the same
metric, on the same samples, as the pair's row (:func:`reports.compare.point.step_values`).

A row of a pair with such a solver whose quantity moves by more than :data:`FRACTION` of
the row's tolerance is not a number that element gives: it is shown, not gated, with the
measured sensitivity and the element width that would bring it under the limit were the
sensitivity to fall in proportion to the width (a first-order guess, not a promise).
Elsewhere the row is gated as before.  Points without wear (static cases, wear
coefficients zero) have no step and are not probed.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
import pandas as pd

from cases.model import Case, CaseError
from cases.result import RunResult
from reports.compare.metrics import scalar
from reports.compare.point import common_steps, pair_cell, pair_reach, step_values
from reports.compare.verdict import Evidence, Flags
from reports.registry import solvers
from reports.registry.pairs import pairs
from reports.registry.resolution import PROBE_SOLVER, probed_pair, probed_width
from reports.store.study_tables import PROBE_COLUMNS
from reports.studies.study import Check, Levels, Own, Study, StudyRun, StudyTable

#: the spread's half-width in element widths.  Measured (docs/fem-notes.md, part 5, "Why";
#: the quick grid in ``benchmarks/README.md``, "The resolution probe"): a tent of 0.5–0.8
#: element widths moves the half-space solver onto the FEM's stick area, wear and energy;
#: the lower end, since on a grid whose cell is near the element the spread acts more
SPREAD = 0.5
#: how the notes of the rows the probe does not gate start
NOTE = "resolution probe"
#: a row is gated only where the probe moves its quantity by at most this part of its
#: tolerance
FRACTION = 0.5


@dataclass(frozen=True)
class ProbeRun(StudyRun):
    """The probe of sweep point ``point``: ``solver`` on ``case``, its wear spread over
    ``width`` × :data:`SPREAD` (``level`` 0: one run, not a refinement level)."""

    width: float = math.nan


def probe_case(case: Case, width: float) -> Case:
    """``case`` with its wear increments spread over :data:`SPREAD` × ``width``."""
    return case.with_changes(solver=dataclasses.replace(case.solver,
                                                         wear_spread=SPREAD * width))


def probed_pairs(pair_names: list[str]) -> list[str]:
    """The pairs whose rows the probe judges: those with a solver that has a step width."""
    return [p for p in pair_names if probed_pair(p)]


def _key(frame: pd.DataFrame) -> pd.Series:
    return (frame["param"].astype(str) + "|" + frame["pair"].astype(str) + "|"
            + frame["step"].astype(int).astype(str) + "|" + frame["quantity"].astype(str)
            + "|" + frame["metric"].astype(str))


def flags(metrics: pd.DataFrame, table: pd.DataFrame,
          failed: Mapping[str, str] | None = None) -> Flags | None:
    """The probe's findings on ``metrics`` (rows by position) of the points it probed (the
    params of ``table`` and of ``failed``, param -> why its probe run failed): a row of a
    probed pair whose quantity moves under the probe by more than :data:`FRACTION` of its
    tolerance is dropped, with the measured sensitivity (module doc); so is one the probe
    did not measure, or measured as NaN, or whose probe run failed."""
    failed = dict(failed or {})
    if metrics.empty or (table.empty and not failed):
        return None
    sens = dict(zip(_key(table), table.itertuples(index=False), strict=True))
    params = set(table["param"].astype(str)) | set(failed)
    dropped: dict[int, list[str]] = {}
    for k, key in enumerate(_key(metrics)):
        param, pair = str(metrics["param"].iat[k]), str(metrics["pair"].iat[k])
        if param not in params or not probed_pair(pair):
            continue
        limit = float(metrics["tolerance"].iat[k])
        if param in failed:
            dropped[k] = [f"{NOTE} failed ({failed[param]})"]
        elif (found := sens.get(key)) is None:
            dropped[k] = [f"{NOTE}: not measured (the probing solver does not give this "
                          "quantity)"]
        elif math.isfinite(limit) and not float(found.sensitivity) <= FRACTION * limit:
            dropped[k] = [note(float(found.sensitivity), limit, float(found.width),
                               float(found.spread))]
    return Flags(dropped=dropped, reason="probe")


def note(sensitivity: float, limit: float, width: float, spread: float) -> str:
    """Why the probe does not gate a row: the measured sensitivity, and the element width
    that would bring it under the limit at first order."""
    need = width * FRACTION * limit / sensitivity if sensitivity > 0 else math.nan
    return (f"{NOTE}: the half-space solver with its wear spread over "
            f"{spread:.3g} mm ({SPREAD:g} of the {width:.3g} mm element) moves it by "
            f"{sensitivity:.3g}, more than {FRACTION:g} of the tolerance {limit:.3g}; "
            f"an element of about {need:.2g} mm would resolve it, were the sensitivity to "
            "fall in proportion")


def admitted(metrics: pd.DataFrame, table: pd.DataFrame) -> pd.DataFrame:
    """``table`` with the row's ``tolerance`` and whether the probe admits it
    (``admitted``), for the report's table."""
    if table.empty:
        return table.assign(tolerance=[], admitted=[])
    limits = dict(zip(_key(metrics), metrics["tolerance"].astype(float), strict=False))
    tolerance = np.array([limits.get(k, math.nan) for k in _key(table)])
    ok = np.isfinite(tolerance) & (table["sensitivity"].to_numpy(float)
                                   <= FRACTION * tolerance)
    return table.assign(tolerance=tolerance, admitted=ok)


def table_rows(own: Own, g: ProbeRun, unit: RunResult, spread: RunResult
               ) -> list[dict[str, Any]]:
    """The rows of ``probe.csv`` for probe ``g``: for every probed pair of the point and
    every output step, each quantity's change from the unit's own result ``unit`` to
    ``spread`` by the pair's metric (:func:`reports.compare.point.step_values`)."""
    case = own.points[g.point]
    names = [f"{a}-{b}" for a, b in pairs(own.applicable(case))]
    out = []
    for pair in probed_pairs(names):
        cell = pair_cell(case, *pair.split("-", 1))
        reach = pair_reach(case, *pair.split("-", 1))
        for n, sa, sb in common_steps(spread, unit):
            for quantity, metric, value in step_values(case, pair, spread, unit, sa, sb, cell,
                                                       reach):
                out.append({"param": case.param, "pair": pair, "step": n,
                            "cycle": scalar(sb, "cycle"), "quantity": quantity,
                            "metric": metric, "sensitivity": value, "width": g.width,
                            "spread": g.case.solver.wear_spread})
    return out


class ResolutionProbe(Study):
    """The resolution probe (module doc) as a :class:`reports.studies.study.Study`: it
    runs wherever a worn point has a solver with a step width beside
    :data:`reports.registry.resolution.PROBE_SOLVER`; its rows carry their own notes
    (:func:`note`), so it has no gate notes of its own."""

    name, label = "probe", "probe"
    keeps_results = True

    def plan(self, own: Own, check: Check) -> list[StudyRun]:
        """One run of every probed point, checked like the units (``CaseError`` naming
        the point)."""
        runs: list[StudyRun] = []
        for i, case in enumerate(own.points):
            width = probed_width(case, own.applicable(case))
            if width is None:
                continue
            c = probe_case(case, width)
            reason = solvers.unsupported(PROBE_SOLVER, c)
            if reason is not None:
                where = case.name + (f" [{case.param}]" if case.param else "")
                raise CaseError(f"resolution probe: {where}: {reason}")
            check(c, PROBE_SOLVER)
            runs.append(ProbeRun(point=i, solver=PROBE_SOLVER, level=0, case=c, width=width))
        return runs

    def describe(self, run: StudyRun) -> dict[str, Any]:
        assert isinstance(run, ProbeRun)
        return {"study": "probe", "width": run.width, "wear_spread": run.case.solver.wear_spread}

    def table(self, own: Own, runs: list[StudyRun], levels: Levels) -> StudyTable:
        """``probe.csv``, each probe compared with the point's own run by every probed
        pair's metrics, and why a point's probe failed."""
        rows: list[dict[str, Any]] = []
        failed = {}
        for g in runs:
            assert isinstance(g, ProbeRun)
            key = (g.point, g.solver, g.level)
            result = levels.results.get(key)
            if result is None:
                failed[g.case.param] = levels.errors.get(key, "not run")
                continue
            rows += table_rows(own, g, own.results[(g.point, g.solver)], result)
        frame = pd.DataFrame.from_records(rows, columns=PROBE_COLUMNS)
        return StudyTable(frame.astype({"step": "int64"}) if not frame.empty else frame, failed)

    def evidence(self, rows: pd.DataFrame, evidence: StudyTable, own: Own) -> list[Evidence]:
        found = flags(rows, evidence.table, evidence.failed)
        return [] if found is None else [found]

    def nothing_planned(self, owns: list[Own]) -> str:
        return "no worn point has a solver with a step width beside " + PROBE_SOLVER


PROBE = ResolutionProbe()
