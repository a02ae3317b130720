"""Grid-convergence studies as part of a run: ``contact-vv run CASE --convergence``.

For every sweep point and every numerical solver that can refine its discretisation
(``SolverRecord.refine`` in :mod:`reports.solvers`: the case grid ``grid.nx, grid.ny``
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
output step (matched by step number) and every gated scalar (:data:`GATED`) the table
holds the three cell sizes and values (finest first), the observed order, the
Richardson-extrapolated value, Roache's GCI of the finest grid (Fs = 1.25, a relative
uncertainty of f1) and of the coarser pair, the asymptotic-range ratio and a status
(:func:`reports.convergence.classify`: ``converged``, ``oscillating``, ``not converged``
or ``exact``) with its reason in ``note``.  ``summary.csv`` gets a last column
:data:`FLAG_COLUMN` naming the gated quantities of each row whose study is neither
``converged`` nor ``exact`` (blank: none, or no study for that solver); ``gate`` prints
them as ``NOT CONVERGED (grid) …`` notes and the report flags them; their metric rows
(for either solver of a pair) are marked "not converged" and not gated
(:func:`flag_metrics`): a number without a converged value is shown, not compared.

Only the spatial discretisation changes: the time or sliding step, the stress-output
layers (``stress.nz``) and, for the FEM, the block and the surface grid it is sampled
on stay as in the case.  A coarse run that fails (did not converge, contact reaching the
grid edge) does not fail the case: its quantities are ``not converged`` with the cause
in ``note``.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
from tqdm.auto import tqdm

from cases.model import Case, CaseError

from . import convergence, solvers
from .plan import CasePlan, Limits, check_fits
from .tolerances import NOT_CONVERGED, budget
from .units import UnitOutcome
from .write import jsonable

#: the smallest refinement ratio between consecutive grids
RATIO = 1.5
#: the scalars studied: those the comparisons gate, plus the load
GATED = ("P", "contact_area", "a_x", "a_y", "p_max", "stick_area", "w_max", "wear_volume",
         "vm_max", "vm_max_below")
#: units of the studied quantities (as in summary.csv)
UNITS = {"P": "N", "contact_area": "mm²", "a_x": "mm", "a_y": "mm", "p_max": "MPa",
         "stick_area": "mm²", "w_max": "mm", "wear_volume": "mm³", "vm_max": "MPa",
         "vm_max_below": "MPa"}
#: the summary.csv column naming the quantities of a row that did not converge
FLAG_COLUMN = "grid_not_converged"
COLUMNS = convergence.TABLE_COLUMNS
#: statuses that are fine: everything else is named
SETTLED = (convergence.CONVERGED, convergence.EXACT)


@dataclass(frozen=True)
class Kind:
    """How the rows of a study are named: the label of its notes (``grid``), the symbol
    and unit of its sizes, and the column holding the cell size a ``cells`` budget is
    measured in (:func:`spread`)."""

    label: str = "grid"
    symbol: str = "h"
    unit: str = " mm"
    cell: str = "h1"


GRID = Kind()


@dataclass(frozen=True)
class GridRun:
    """One extra run of a study: sweep point ``point``, ``solver``, ``level`` 2 or 3
    (1 is the run's own), on ``case`` (a coarser grid here, a smaller cycle jump in
    :mod:`reports.jumpstudy`)."""

    point: int
    solver: str
    level: int
    case: Case


def studied(plan: CasePlan) -> list[tuple[int, str]]:
    """The (point, solver) units of ``plan`` that get a grid study: numerical solvers
    whose record knows how to refine."""
    return [(i, s) for i, s in plan.units()
            if solvers.record(s).refine is not None and not solvers.record(s).closed_form]


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


def add_grids(plan: CasePlan, limits: Limits | None = None) -> CasePlan:
    """``plan`` with the grid studies of ``run --convergence``: :func:`plan_grids`."""
    plan.convergence = True
    plan.grids = plan_grids(plan, limits)
    return plan


def plan_grids(plan: CasePlan, limits: Limits | None = None) -> list[GridRun]:
    """The coarse runs of the grid studies of ``plan``, validated like the case itself
    (contact within the grid, solver support, limits): ``CaseError`` naming the grid."""
    runs = []
    for i, s in studied(plan):
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


def manifest_entry(plan: CasePlan) -> dict[str, Any]:
    """What the manifest records of the studies: the ratio and, per coarse run, its keys."""
    return {"ratio": RATIO, "quantities": list(GATED),
            "grids": [{"solver": g.solver, "param": g.case.param, "grid": g.level,
                       "cell_size": solvers.record(g.solver).cell_size(g.case),
                       "changes": jsonable(changes(plan.points[g.point], g.case))}
                      for g in plan.grids]}


@dataclass
class Study:
    """What the coarse runs left: summary rows (or why there are none) per (point,
    solver, grid), their manifest records, and the table built from them."""

    rows: dict[tuple[int, str, int], list[dict[str, Any]]] = field(default_factory=dict)
    errors: dict[tuple[int, str, int], str] = field(default_factory=dict)
    records: list[dict[str, Any]] = field(default_factory=list)
    table: pd.DataFrame | None = None


Executor = Callable[[CasePlan, list[tuple[int, str]], bool], Iterable[UnitOutcome]]


def run(plan: CasePlan, executor: Executor, progress: bool | None,
        fine_rows: dict[tuple[int, str], list[dict[str, Any]]]) -> Study:
    """Run the coarse grids of ``plan`` through ``executor`` (fields not written) and
    build the convergence table against ``fine_rows`` ((point, solver) -> summary rows of
    the run's own grid)."""
    study = run_levels(plan, plan.grids, executor, progress, "grids", lambda g: {
        "grid": g.level, "cell_size": solvers.record(g.solver).cell_size(g.case)})
    study.table = table(plan, fine_rows, study)
    return study


def run_levels(plan: CasePlan, runs: list[Any], executor: Executor, progress: bool | None,
               label: str, describe: Callable[[Any], dict[str, Any]]) -> Study:
    """Run the extra levels ``runs`` of a study (items with ``point, solver, level,
    case``) through ``executor`` without fields: their summary rows (or why there are
    none) keyed (point, solver, level), and their manifest records, with ``describe``'s
    keys, in the planned order."""
    sub = dataclasses.replace(plan, points=[g.case for g in runs], staging=None,
                              grids=[], jumps=[])
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


def value_of(row: dict[str, Any] | None, q: str) -> float:
    """Quantity ``q`` of a summary row as a float (NaN: no row, no value)."""
    if row is None:
        return math.nan
    v = row.get(q)
    try:
        return float(v)
    except (TypeError, ValueError):
        return math.nan


def table(plan: CasePlan, fine_rows: dict[tuple[int, str], list[dict[str, Any]]],
          study: Study) -> pd.DataFrame:
    """``convergence.csv``: one row per (solver, sweep point, step, gated quantity)."""
    rows = []
    for i, s in studied(plan):
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
            for q in GATED:
                f = (value_of(fine[step], q), value_of(coarse[0].get(step), q),
                     value_of(coarse[1].get(step), q))
                if q not in fine[step] or all(math.isnan(v) for v in f):
                    continue  # the solver does not report it
                rows.append(study_row(s, case.param, step, q, tuple(h), f, failed))
    frame = pd.DataFrame.from_records(rows, columns=COLUMNS)
    return frame.astype({"step": "int64"}) if not frame.empty else frame


def study_row(solver: str, param: str, step: int, q: str, h: tuple[float, float, float],
              f: tuple[float, float, float], failed: list[str]) -> dict[str, Any]:
    """One row of a three-level study (values ``f`` on sizes ``h``, finest first):
    order, extrapolation, GCIs and status (:func:`reports.convergence.classify`);
    ``failed`` names levels that did not run."""
    st = convergence.study(f, h)
    status, note = convergence.classify(st)
    if failed:
        note = "; ".join(failed)
    order, f_ext, gci_fine, gci_coarse = st.p, st.f_ext, st.gci_fine, st.gci_coarse
    asymptotic = st.asymptotic
    if status == convergence.EXACT:
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
        return pd.DataFrame(columns=COLUMNS)
    return frame[~frame["status"].isin(SETTLED)]


def flag_summary(summary: pd.DataFrame, frame: pd.DataFrame,
                 column: str = FLAG_COLUMN) -> pd.DataFrame:
    """``summary`` with the last column ``column``: the space-separated studied
    quantities of each (solver, param, step) that are not converged ('' if none)."""
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


def flag_metrics(metrics: pd.DataFrame, frame: pd.DataFrame,
                 kind: Kind = GRID) -> pd.DataFrame:
    """``metrics`` with the rows of a studied quantity that is not converged set to
    ``status`` "not converged", the ``note`` naming the solver, status and three values:
    a number that the grids do not settle is shown, not gated (:mod:`reports.tolerances`).

    Not converged means: the study of either solver of the pair (at that sweep point and
    step) is neither converged nor exact, *and* its three values spread by more than that
    solver's budget for the metric (:func:`spread`).  A quantity that oscillates within
    its budget is settled to that budget and stays gated (its note says so), and so does
    one whose study lacks a value (a failed coarse run is no evidence about the fine
    one): the gate keeps every number it has no measured reason to drop."""
    bad = {(str(r.solver), "" if pd.isna(r.param) else str(r.param), int(r.step),
            str(r.quantity)): r for r in unsettled(frame).itertuples(index=False)}
    if not bad or metrics.empty:
        return metrics
    out = metrics.copy()
    param = out["param"].fillna("").astype(str)
    for k in range(len(out)):
        q, metric = str(out["quantity"].iat[k]), str(out["metric"].iat[k])
        dropped, kept = [], []
        for solver in str(out["pair"].iat[k]).split("-"):
            r = bad.get((solver, param.iat[k], int(out["step"].iat[k]), q))
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
            (dropped if width > limit else kept).append(text)
        if not (dropped or kept):
            continue
        old = str(out["note"].iat[k]) if out["status"].iat[k] == NOT_CONVERGED else ""
        if dropped:
            out.iloc[k, out.columns.get_loc("status")] = NOT_CONVERGED
        out.iloc[k, out.columns.get_loc("note")] = "; ".join(
            [n for n in [old] if n] + dropped + [t + " (gated)" for t in kept])
    return out


def read_convergence(path: Path) -> pd.DataFrame:
    """``convergence.csv`` as a run writes it (a parser for
    :func:`reports.readers.read_result`): the required columns, numbers where a run
    writes numbers, a known ``status``; ``Malformed`` otherwise."""
    return read_study(path, COLUMNS, COLUMNS[:14])


def read_study(path: Path, columns: list[str], required: list[str]) -> pd.DataFrame:
    """A study table with ``columns`` (``required`` among them): text and numbers as a
    run writes them, a known ``status``; ``Malformed`` otherwise."""
    from .readers import Malformed, read_csv

    text = ("solver", "param", "quantity", "status", "note")
    frame = read_csv(path, required=required, text=text,
                     numeric=[c for c in columns if c not in (*text, "step")],
                     integer=["step"])
    bad = ~frame["status"].isin(convergence.STATUSES)
    if bad.any():
        i = int(bad.to_numpy().nonzero()[0][0])
        raise Malformed(f"column 'status' holds {frame['status'].iloc[i][:40]!r} (data row "
                        f"{i + 1}), not one of {', '.join(convergence.STATUSES)}")
    return frame


def note_lines(case: str, frame: pd.DataFrame, kind: Kind = GRID) -> list[str]:
    """One ``NOT CONVERGED (grid) <case> [param] step N <solver> <quantity>: …`` line per
    quantity of a study table that is neither converged nor exact, with its three
    values (finest first), sizes and observed order: information for the gate, not a
    failure (the quantity's metric rows are not gated, :func:`flag_metrics`)."""
    lines = []
    for r in unsettled(frame).itertuples(index=False):
        param = "" if pd.isna(r.param) else str(r.param)
        where = case + (f" [{param}]" if param else "") + f" step {int(r.step)}"
        order = f"order {r.order:.3g}" if math.isfinite(r.order) else "no order"
        lines.append(
            f"NOT CONVERGED ({kind.label}) {where} {r.solver} {r.quantity}: {r.status}; "
            f"f = {r.f1:.6g}, {r.f2:.6g}, {r.f3:.6g} on {kind.symbol} = {r.h1:.4g}, "
            f"{r.h2:.4g}, {r.h3:.4g}{kind.unit}; {order}" + (f" ({r.note})" if r.note else ""))
    return lines
