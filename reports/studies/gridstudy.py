"""Grid-convergence studies as part of a run: ``contact-vv run CASE --convergence``
(:data:`GRID_STUDY`, a :class:`reports.studies.study.Study`; the runs themselves:
:mod:`reports.run.study_runs`).

For every sweep point and every numerical solver that can refine its discretisation
(``SolverRecord.refine`` in :mod:`reports.registry.solvers`: the case grid ``grid.nx, grid.ny``
for ``ic``, the element size ``fem.h`` for ``fem``; closed forms have none) the case
runs on three grids of refinement ratio r ≥ :data:`RATIO` and the same physics:

- grid 1, the finest, is the case's own discretisation: its results are the run's
  ordinary results (``summary.csv``, ``metrics.csv``, ``fields/`` as without the flag);
- grids 2 and 3 are coarsened by r and r² from it (``refine(case, 1/r)`` applied twice).
  A grid solver keeps the parity of the cell counts (an odd count keeps a cell centred on
  the axis) and rounds down, so each ratio is at least r (41 → 27 → 17 cells: 1.52,
  1.59); the FEM's ``fem.h`` is multiplied by r exactly (0.125 → 0.1875 → 0.281 a0).
  Making the case grid the finest keeps the cost of a study below 1 + 1/r² + 1/r⁴ ≈ 1.64
  runs for a surface grid (for the 3-D FEM the coarse meshes are cheaper still), leaves
  the run's own numbers unchanged by the flag, and makes the GCI of the finest grid the
  uncertainty of exactly the values the run reports.

The coarse runs write no fields; they feed ``convergence.csv`` only (their wall times
and changed keys are in the manifest's ``units``, with ``grid`` 2 or 3).  For every
output step (matched by step number) and every studied scalar (:data:`STUDIED`) the table
holds the three cell sizes and values (finest first), the observed order, the
Richardson-extrapolated value, Roache's GCI of the finest grid (Fs = 1.25, a relative
uncertainty of f1) and of the coarser pair, the asymptotic-range ratio and a status
(:func:`reports.studies.three_level.classify`: ``converged``, ``oscillating``, ``unsettled``
or ``exact``) with its reason in ``note``.  ``summary.csv`` gets a last column
:data:`FLAG_COLUMN` naming the gated quantities of each row whose study is neither
``converged`` nor ``exact`` (blank: none, or no study for that solver); ``gate`` prints
them as ``UNSETTLED (grid) …`` notes and the report flags them; their metric rows
(for either solver of a pair) are marked "not gated" with the reason ``grid_study``
(:func:`flags`): a number without a converged value is shown, not compared.

Only the spatial discretisation changes: the time or sliding step, the stress-output
layers (``stress.nz``) and, for the FEM, the block and the surface grid it is sampled
on stay as in the case.  A coarse run that fails (did not converge, contact reaching the
grid edge) does not fail the case: its quantities are ``unsettled`` with the cause in
``note``.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import pandas as pd

from cases.model import Case, CaseError
from reports.compare.verdict import Evidence, Flags, Uncertainty
from reports.registry import solvers
from reports.registry.tolerances import budget
from reports.store.study_tables import CONVERGED, CONVERGENCE_COLUMNS, EXACT
from reports.store.write import jsonable
from reports.studies import three_level, uncertainty
from reports.studies.study import Check, Levels, Own, Study, StudyRun, StudyTable

#: the smallest refinement ratio between consecutive grids
RATIO = 1.5
#: the scalars studied: those the comparisons gate, plus the load
STUDIED = ("P", "contact_area", "a_x", "a_y", "p_max", "stick_area", "w_max", "wear_volume",
         "vm_max", "vm_max_below")
#: units of the studied quantities (as in summary.csv)
UNITS = {"P": "N", "contact_area": "mm²", "a_x": "mm", "a_y": "mm", "p_max": "MPa",
         "stick_area": "mm²", "w_max": "mm", "wear_volume": "mm³", "vm_max": "MPa",
         "vm_max_below": "MPa"}
#: the summary.csv column naming the quantities of a row that did not converge
FLAG_COLUMN = "grid_not_converged"
#: statuses that are fine: everything else is named
SETTLED = (CONVERGED, EXACT)


@dataclass(frozen=True)
class Kind:
    """How the rows of a study are named: the label of its notes (``grid``), the symbol
    and unit of its sizes, and the column holding the cell size a ``cells`` budget is
    measured in (:func:`spread`)."""

    label: str = "grid"
    symbol: str = "h"
    unit: str = " mm"
    cell: str = "h1"
    reason: str = "grid_study"  # the reason of a row it drops (tolerances.REASONS)


GRID = Kind()


def coarse_cases(solver: str, case: Case, ratio: float = RATIO) -> list[Case]:
    """Grids 2 and 3 of ``solver`` for ``case`` (``CaseError`` if they cannot be made)."""
    rec = solvers.record(solver)
    assert rec.refine is not None
    out, prev = [], case
    for level in (2, 3):
        nxt = rec.refine(prev, 1.0 / ratio)
        h0, h1 = rec.cell_size(prev), rec.cell_size(nxt)
        if not (math.isfinite(h0) and math.isfinite(h1) and h1 >= ratio * h0 * (1 - 1e-9)):
            raise CaseError(f"solver {solver}: grid {level} of the study has cell size "
                            f"{h1:.4g} mm against {h0:.4g} mm (a refinement ratio of at "
                            f"least {ratio:g} is needed)")
        out.append(nxt)
        prev = nxt
    return out


def changes(fine: Case, coarse: Case) -> dict[str, Any]:
    """The dotted keys whose values differ between two cases (``grid.nx``: 27, …)."""
    def flat(obj: Any, prefix: str = "") -> dict[str, Any]:
        if dataclasses.is_dataclass(obj):
            out: dict[str, Any] = {}
            for f in dataclasses.fields(obj):
                out.update(flat(getattr(obj, f.name), f"{prefix}{f.name}."))
            return out
        return {prefix[:-1]: obj}

    a, b = flat(fine), flat(coarse)
    return {k: b[k] for k in b if a.get(k) != b[k]}


def value_of(row: dict[str, Any] | None, q: str) -> float:
    """Quantity ``q`` of a summary row as a float (NaN: no row, no value)."""
    if row is None:
        return math.nan
    v = row.get(q)
    try:
        return float(v)
    except (TypeError, ValueError):
        return math.nan


def study_row(solver: str, param: str, step: int, q: str, h: tuple[float, float, float],
              f: tuple[float, float, float], failed: list[str]) -> dict[str, Any]:
    """One row of a three-level study (values ``f`` on sizes ``h``, finest first):
    order, extrapolation, GCIs and status (:func:`reports.studies.three_level.classify`);
    ``failed`` names levels that did not run."""
    st = three_level.study(f, h)
    status, note = three_level.classify(st)
    if failed:
        note = "; ".join(failed)
    order, f_ext, gci_fine, gci_coarse = st.p, st.f_ext, st.gci_fine, st.gci_coarse
    asymptotic = st.asymptotic
    if status == three_level.EXACT:
        order, f_ext, gci_fine, gci_coarse = math.nan, f[0], 0.0, 0.0
        asymptotic = math.nan
    elif not st.converging and not st.oscillatory and math.isfinite(order):
        # growing differences: the order is negative (Celik's |ln| hides the sign), and
        # there is nothing to extrapolate to
        order, f_ext, gci_fine, gci_coarse = -abs(order), math.nan, math.nan, math.nan
    return {"solver": solver, "param": param, "step": int(step), "quantity": q,
            "h1": h[0], "h2": h[1], "h3": h[2], "f1": f[0], "f2": f[1], "f3": f[2],
            "order": order, "f_extrapolated": f_ext, "gci_fine": gci_fine,
            "status": status, "gci_coarse": gci_coarse, "asymptotic": asymptotic,
            "note": note}


def unsettled(frame: pd.DataFrame) -> pd.DataFrame:
    """The rows of a convergence table whose status is neither converged nor exact."""
    if frame is None or frame.empty:
        return pd.DataFrame(columns=CONVERGENCE_COLUMNS)
    return frame[~frame["status"].isin(SETTLED)]


def flag_summary(summary: pd.DataFrame, frame: pd.DataFrame,
                 column: str = FLAG_COLUMN) -> pd.DataFrame:
    """``summary`` with the last column ``column``: the space-separated studied
    quantities of each (solver, param, step) that are unsettled ('' if none)."""
    bad: dict[tuple[str, str, int], list[str]] = {}
    for r in unsettled(frame).itertuples(index=False):
        bad.setdefault((str(r.solver), str(r.param), int(r.step)), []).append(str(r.quantity))
    param = summary["param"].fillna("").astype(str)
    flags = [" ".join(bad.get((str(s), p, int(k)), []))
             for s, p, k in zip(summary["solver"], param, summary["step"], strict=True)]
    return summary.assign(**{column: flags})


def spread(row: Any, metric: str, cell: float | None = None) -> float:
    """How far apart the three values of a study row are, in the units of ``metric``:
    (max − min) / |f1| for ``rel``; for ``cells`` the spread of the length (a semi-width,
    or the equivalent radius √(A/π) of an area) over the cell size ``cell`` (default the
    finest cell size h1 of a grid study).  NaN when a value is missing."""
    f = np.array([row.f1, row.f2, row.f3], dtype=float)
    if not np.isfinite(f).all():
        return math.nan
    if metric == "rel":
        return float((f.max() - f.min()) / abs(f[0])) if f[0] != 0 else math.inf
    if row.quantity in ("contact_area", "stick_area"):
        f = np.sqrt(np.clip(f, 0.0, None) / math.pi)
    return float((f.max() - f.min()) / (row.h1 if cell is None else cell))


def flags(metrics: pd.DataFrame, frame: pd.DataFrame, kind: Kind = GRID) -> Flags | None:
    """The study ``frame``'s findings on the rows of ``metrics`` (by position), for
    :func:`reports.compare.verdict.decide`: a number that the grids do not settle is shown,
    not gated (:mod:`reports.registry.tolerances`).

    A row is dropped when the study of either solver of the pair (at that sweep point and
    step) is neither converged nor exact, *and* its three values spread by more than that
    solver's budget for the metric (:func:`spread`).  A quantity that oscillates within
    its budget is settled to that budget and stays gated (its note says so), and so does
    one whose study lacks a value (a failed coarse run is no evidence about the fine
    one): the gate keeps every number it has no measured reason to drop."""
    bad = {(str(r.solver), "" if pd.isna(r.param) else str(r.param), int(r.step),
            str(r.quantity)): r for r in unsettled(frame).itertuples(index=False)}
    if not bad or metrics.empty:
        return None
    param = metrics["param"].fillna("").astype(str)
    dropped: dict[int, list[str]] = {}
    kept: dict[int, list[str]] = {}
    for k in range(len(metrics)):
        q, metric = str(metrics["quantity"].iat[k]), str(metrics["metric"].iat[k])
        for solver in str(metrics["pair"].iat[k]).split("-"):
            r = bad.get((solver, param.iat[k], int(metrics["step"].iat[k]), q))
            if r is None:
                continue
            width = spread(r, metric, float(getattr(r, kind.cell)))
            limit = budget(solver, q, metric)
            order = f"order {r.order:.3g}" if math.isfinite(r.order) else "no order"
            versus = "unknown" if math.isnan(width) else \
                f"{width:.3g} {'>' if width > limit else '<='} budget {limit:g}"
            text = (f"{kind.label} study: {solver} {r.status}, f = {r.f1:.6g}, {r.f2:.6g}, "
                    f"{r.f3:.6g} on {kind.symbol} = {r.h1:.4g}, {r.h2:.4g}, "
                    f"{r.h3:.4g}{kind.unit}, {order}, spread {versus}")
            (dropped if width > limit else kept).setdefault(k, []).append(text)
    return Flags(dropped, kept, reason=kind.reason)


def note_lines(case: str, frame: pd.DataFrame, kind: Kind = GRID) -> list[str]:
    """One ``UNSETTLED (grid) <case> [param] step N <solver> <quantity>: …`` line per
    quantity of a study table that is neither converged nor exact, with its three
    values (finest first), sizes and observed order: information for the gate, not a
    failure (the quantity's metric rows are not gated, :func:`flags`)."""
    lines = []
    for r in unsettled(frame).itertuples(index=False):
        param = "" if pd.isna(r.param) else str(r.param)
        where = case + (f" [{param}]" if param else "") + f" step {int(r.step)}"
        order = f"order {r.order:.3g}" if math.isfinite(r.order) else "no order"
        lines.append(
            f"UNSETTLED ({kind.label}) {where} {r.solver} {r.quantity}: {r.status}; "
            f"f = {r.f1:.6g}, {r.f2:.6g}, {r.f3:.6g} on {kind.symbol} = {r.h1:.4g}, "
            f"{r.h2:.4g}, {r.h3:.4g}{kind.unit}; {order}" + (f" ({r.note})" if r.note else ""))
    return lines


def by_step(rows: list[dict[str, Any]]) -> dict[int, dict[str, Any]]:
    """Summary rows by step number."""
    return {int(r["step"]): r for r in rows}


class GridStudy(Study):
    """The grid studies of ``run --convergence`` (module doc) as a
    :class:`reports.studies.study.Study`."""

    name, option, label = "convergence", "--convergence", "grids"
    table_without_runs = True

    @staticmethod
    def studied(own: Own) -> list[tuple[int, str]]:
        """The (point, solver) units with a grid study: numerical solvers whose record
        knows how to refine."""
        return [(i, s) for i, s in own.units
                if solvers.record(s).refine is not None and not solvers.record(s).closed_form]

    def plan(self, own: Own, check: Check) -> list[StudyRun]:
        """Grids 2 and 3 of every studied unit, checked like the case (``CaseError`` naming
        the grid)."""
        runs = []
        for i, s in self.studied(own):
            case = own.points[i]
            where = case.name + (f" [{case.param}]" if case.param else "")
            try:
                for level, c in zip((2, 3), coarse_cases(s, case), strict=True):
                    reason = solvers.unsupported(s, c)
                    if reason is not None:
                        raise CaseError(f"solver {s} does not support grid {level}: {reason}")
                    check(c, s)
                    runs.append(StudyRun(i, s, level, c))
            except CaseError as exc:
                raise CaseError(f"{self.option}: {where}: {exc}") from None
        return runs

    def describe(self, run: StudyRun) -> dict[str, Any]:
        return {"grid": run.level, "cell_size": solvers.record(run.solver).cell_size(run.case)}

    def table(self, own: Own, runs: list[StudyRun], levels: Levels) -> StudyTable:
        """``convergence.csv``: one row per (solver, sweep point, step, studied quantity)."""
        rows = []
        for i, s in self.studied(own):
            case = own.points[i]
            rec = solvers.record(s)
            fine = by_step(own.rows.get((i, s), []))
            coarse, h, failed = [], [rec.cell_size(case)], []
            for level in (2, 3):
                key = (i, s, level)
                g = next(g for g in runs if (g.point, g.solver, g.level) == key)
                h.append(rec.cell_size(g.case))
                if key in levels.rows:
                    coarse.append(by_step(levels.rows[key]))
                else:
                    coarse.append({})
                    failed.append(f"grid {level} failed ({levels.errors.get(key, 'not run')})")
            for step in sorted(fine):
                for q in STUDIED:
                    f = (value_of(fine[step], q), value_of(coarse[0].get(step), q),
                         value_of(coarse[1].get(step), q))
                    if q not in fine[step] or all(math.isnan(v) for v in f):
                        continue  # the solver does not report it
                    rows.append(study_row(s, case.param, step, q, tuple(h), f, failed))
        frame = pd.DataFrame.from_records(rows, columns=CONVERGENCE_COLUMNS)
        return StudyTable(frame.astype({"step": "int64"}) if not frame.empty else frame)

    def summary(self, summary: pd.DataFrame, table: pd.DataFrame) -> pd.DataFrame:
        return flag_summary(summary, table, FLAG_COLUMN)

    def evidence(self, rows: pd.DataFrame, evidence: StudyTable, own: Own) -> list[Evidence]:
        """The grids' flags (:func:`flags`) and the uncertainty U of every row
        (:func:`reports.studies.uncertainty.values`)."""
        found: list[Evidence] = []
        if (f := flags(rows, evidence.table)) is not None:
            found.append(f)
        u = uncertainty.values(rows, evidence.table, {c.param: c for c in own.points})
        if u is not None:
            found.append(Uncertainty(u))
        return found

    def manifest(self, own: Own, runs: list[StudyRun]) -> dict[str, Any]:
        """The ratio, the quantities and, per coarse run, its keys."""
        return {"ratio": RATIO, "quantities": list(STUDIED),
                "grids": [{"solver": g.solver, "param": g.case.param, "grid": g.level,
                           "cell_size": solvers.record(g.solver).cell_size(g.case),
                           "changes": jsonable(changes(own.points[g.point], g.case))}
                          for g in runs]}

    def notes(self, case: str, table: pd.DataFrame) -> list[str]:
        return note_lines(case, table, GRID)

    def nothing_planned(self, owns: list[Own]) -> str:
        names = sorted({s for own in owns for _, s in own.units})
        return (f"no run has a grid to refine (solver(s) {', '.join(names)}: closed forms "
                "have none); add a numerical solver, e.g. --solver ic")


GRID_STUDY = GridStudy()
