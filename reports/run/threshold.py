"""Thresholds as results: ``contact-vv threshold CASE --param KEY --event EVENT``.

The parameter value (a dotted case key such as ``friction.mu``) at which an event of
:mod:`reports.studies.events` changes, found by bisection per solver, per sweep point of the
case (when it sweeps another key) and per grid:

1. the first grid of every (point, solver) evaluates the event at both ends of the bracket
   ``[lo, hi]`` (``--range``, else :data:`DEFAULTS`); the event must differ there, else
   the command fails naming the solver, grid and key before any bisection;
2. each then halves its bracket until it is at most ``--resolution`` wide: the threshold
   is the bracket's midpoint, good to ± half its width (the event is assumed to change
   once in the bracket; bisection finds one change if there are several).

Grids are refinement factors of the solver's discretisation (``SolverRecord.refine``:
``grid.nx, grid.ny`` for grid solvers, ``fem.h`` for the FEM; a closed form is sampled on
the case grid, so it is refined like a grid solver); factor 1 is the case's own and
``grid_shift`` is each grid's threshold minus that one.  The closed form's exact
threshold, where :func:`reports.studies.events.exact_threshold` has one, is a row of solver
``analytic`` with grid ``exact``.  Rows go to ``DIR/thresholds.csv``
(:data:`COLUMNS`), merged with the rows of earlier threshold runs.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from cases.loader import case_path, load_case
from cases.model import Case, CaseError
from cases.schema import read_toml
from reports.registry import solvers
from reports.registry.errors import UserError
from reports.registry.record import grid_cell
from reports.registry.tolerances import check_keys
from reports.run.plan import Limits, check_fits
from reports.run.threshold_request import (  # noqa: F401 (the request's names, here too)
    COLUMNS,
    DEFAULT_GRIDS,
    DEFAULTS,
    Request,
    bracket,
    check_param,
    parse_grids,
)
from reports.run.units import run_unit
from reports.studies import events
from reports.studies.events import (
    EventUndefined,
    Exact,
    Guess,
    NoChange,
    bisect,
    event,
)

# ------------------------------------------------------------------ evaluation


def grid_label(solver: str, case: Case) -> str:
    """``41x41`` for a grid, ``fem.h=0.125`` (a0) for the FEM (its registry record)."""
    return solvers.record(solver).label(case)


@dataclass
class Unit:
    """One bisection: sweep point ``point`` (its label ``point_label``), ``solver``,
    grid refinement ``factor``; it counts its evaluations, time and the step label."""

    request: Request
    point: int
    point_label: str
    solver: str
    factor: float
    evaluations: int = 0
    wall_s: float = 0.0
    at_label: str = ""
    #: runs one evaluation (:func:`reports.run.units.run_unit`'s signature): in this
    #: process, or as a task on a cluster (:meth:`reports.run.cluster.DaskExecutor.evaluate`)
    evaluate: Callable[..., Any] = run_unit

    def case(self, value: float) -> Case:
        """The case at ``param`` = ``value`` on this unit's grid (validated)."""
        r = self.request
        points = load_case(r.case, quick=r.quick, overrides={**r.overrides, r.param: value})
        case = points[self.point]
        if self.factor != 1.0:  # a closed form is sampled on the case grid: refined as one
            refine = solvers.REGISTRY[self.solver].refine or solvers.refine_grid
            case = refine(case, self.factor)
        check_fits(case)
        (r.limits or Limits()).check(case, self.solver)
        return case

    def __call__(self, value: float) -> bool:
        """The event at ``param`` = ``value`` (solves the case)."""
        r = self.request
        case = self.case(value)
        t0 = time.perf_counter()
        outcome = self.evaluate(solvers.resolve(self.solver), case, self.solver, self.point,
                                False, None, (r.limits or Limits()).deadline(case, self.solver))
        if outcome.result is None:
            where = f" [{self.point_label}]" if self.point_label else ""
            text = (f"solver {self.solver}{where} at {r.param} = {value:g} on "
                    f"{grid_label(self.solver, case)}: {outcome.error}")
            # a case the solver rejects (e.g. the contact reaches the grid edge) is the
            # user's error; a solver that fails is a failed row (its row names where)
            raise CaseError(text) if outcome.kind == "case" else RuntimeError(outcome.error)
        step, self.at_label = events.select_step(outcome.result, case, r.options.at)
        verdict = event(r.event).test(step, r.options)
        dt = time.perf_counter() - t0
        self.evaluations, self.wall_s = self.evaluations + 1, self.wall_s + dt
        return verdict

    def row(self, **values: Any) -> dict[str, Any]:
        """A ``thresholds.csv`` row of this unit (``values`` fill the rest)."""
        r = self.request
        case = self.case(r.lo)
        rec = solvers.REGISTRY[self.solver]
        cell = grid_cell(case) if rec.closed_form else rec.cell_size(case)
        row = dict.fromkeys(COLUMNS, math.nan)
        row.update(case=case.name, point=self.point_label, event=r.event, param=r.param,
                   at=self.at_label, quick=r.quick, solver=self.solver,
                   grid=grid_label(self.solver, case), refine=self.factor, cell_size=cell,
                   resolution=r.resolution, range_lo=r.lo, range_hi=r.hi,
                   evaluations=self.evaluations, wall_s=self.wall_s)
        row.update(values)
        return row


def _ends(unit: Unit, evaluate: bool = True
          ) -> tuple[bool | None, bool | None] | dict[str, Any]:
    """The event at both ends of the bracket (unknown, None, unless ``evaluate``), or the
    row saying why there is none."""
    r = unit.request
    for value in (r.lo, r.hi):
        reason = solvers.unsupported(unit.solver, unit.case(value))
        if reason is not None:
            return unit.row(status=f"unsupported: {reason}")
        reason = None if r.explicit else solvers.not_by_default(unit.solver, unit.case(value))
        if reason is not None:
            return unit.row(status=f"not by default: {reason}")
    if not evaluate:
        return None, None
    try:
        return unit(r.lo), unit(r.hi)
    except EventUndefined as exc:
        return unit.row(status=f"n/a: {exc}")
    except RuntimeError as exc:
        return unit.row(status=f"failed: {exc}")


def _exact_row(unit: Unit) -> dict[str, Any] | None:
    """The exact threshold's row for ``unit``'s point, if the closed form has one."""
    r = unit.request
    case = load_case(r.case, quick=r.quick, overrides={**r.overrides, r.param: r.lo})
    t0 = time.perf_counter()
    try:
        exact = events.exact_threshold(r.event, r.param, case[unit.point], r.options)
    except ValueError as exc:  # the closed form's root is outside its search bracket
        exact = f"the closed form's root was not found ({exc})"
    if not isinstance(exact, Exact):
        return None
    half = exact.resolution / 2
    row = unit.row(threshold=exact.value, uncertainty=half, resolution=exact.resolution,
                   lo=exact.value - half, hi=exact.value + half, evaluations=0,
                   status=f"exact: {exact.reference}", wall_s=time.perf_counter() - t0)
    row.update(grid="exact", refine=math.nan, cell_size=math.nan)
    return row


def make_units(request: Request, evaluate: Callable[..., Any] = run_unit) -> list[Unit]:
    """Every (point, solver, grid) of ``request``, evaluated by ``evaluate``; UserError if
    the event does not apply."""
    for value in (request.hi, request.lo):
        try:
            points = load_case(request.case, quick=request.quick,
                               overrides={**request.overrides, request.param: value})
        except CaseError as exc:
            raise CaseError(f"--param {request.param} = {value:g}: {exc}") from None
    for case in points:  # the keys a run would refuse (a --set typo), refused here too
        check_keys(case, solvers.names())
    reason = event(request.event).applies(points[0])
    if reason is not None:
        raise UserError(reason)
    key = (read_toml(case_path(request.case)).get("sweep") or {}).get("key")
    labels = [c.param if key and key != request.param else "" for c in points]
    order = [s for s in solvers.names()  # a metamorphic relation has no threshold of its own
             if s in request.solvers and not solvers.record(s).base]
    return [Unit(request, i, labels[i], s, f, evaluate=evaluate)
            for i in range(len(points)) for s in order for f in request.grids]


def _no_change(request: Request, stuck: list[tuple[Unit, bool]]) -> UserError:
    ev = event(request.event)
    which = "; ".join(f"{u.solver} {grid_label(u.solver, u.case(request.lo))}"
                      + (f" [{u.point_label}]" if u.point_label else "")
                      + f": {ev.true_means if v else ev.false_means} at both ends"
                      for u, v in stuck)
    return UserError(f"--param {request.param}: event {request.event} does not change over "
                     f"[{request.lo:g}, {request.hi:g}] ({which}); widen --range")


def _bisect_unit(unit: Unit, ends: tuple[bool | None, bool | None],
                 guesses: dict[tuple, Guess]) -> dict[str, Any]:
    """The row of ``unit``'s bisection, searched from the guess of its (case, point,
    solver) if an earlier one left it there; its own result left as the next guess."""
    r, ev = unit.request, event(unit.request.event)
    key = guess_key(unit)
    try:
        b = bisect(unit, r.lo, r.hi, r.resolution, at_lo=ends[0], at_hi=ends[1],
                   guess=guesses.get(key))
    except NoChange as exc:
        raise _no_change(r, [(unit, exc.value)]) from None
    except RuntimeError as exc:
        return unit.row(status=f"failed: {exc}")
    except EventUndefined as exc:
        return unit.row(status=f"n/a: {exc}")
    guesses[key] = Guess(b.value, b.at_lo)
    below, above = (ev.true_means, ev.false_means) if b.at_lo else \
        (ev.false_means, ev.true_means)
    return unit.row(threshold=b.value, uncertainty=b.uncertainty, lo=b.lo, hi=b.hi,
                    status=f"bisected: {below} at lower {r.param}, {above} at higher")


#: the statuses of a unit that says nothing of the threshold (a run of only these is
#: refused, as ``run`` refuses a case none of its solvers runs)
NOTHING = ("unsupported", "not by default", "n/a")


def guess_key(unit: Unit) -> tuple:
    """What a bisection's guess is kept under: the case, event, key, sweep point and
    solver (its grids and output cycles share it)."""
    r = unit.request
    return (r.case, r.event, r.param, unit.point, unit.solver)


def run(request: Request, log: Callable[[str], None] | None = None,
        guesses: dict[tuple, Guess] | None = None, cluster: Any = None
        ) -> list[dict[str, Any]]:
    """The threshold rows of ``request`` (module doc): UserError if the event does not
    change over the bracket for some unit, or if no solver can say anything of it; a unit
    whose solver fails has a ``failed`` row.

    A unit whose (case, point, solver) has already been bisected (another grid of this
    request, or of an earlier request sharing ``guesses``: another output cycle) searches
    from that threshold (:func:`reports.studies.events.bisect`): the same interval where
    the event changes once in the bracket, in 2 evaluations when it has not moved.  Its
    ends are evaluated only if the search reaches them; the first unit of each has them
    evaluated before any bisection, so that a bracket without a change fails early.

    The units of one (point, solver) run one after the other; with a ``cluster``
    (:class:`reports.run.cluster.DaskExecutor`) those of different ones at once, each
    evaluation a task: the same evaluations, so the same rows."""
    guesses = {} if guesses is None else guesses
    groups: dict[tuple, list[Unit]] = {}
    for u in make_units(request, run_unit if cluster is None else cluster.evaluate):
        groups.setdefault(guess_key(u), []).append(u)
    mapped = (lambda f, xs: [f(x) for x in xs]) if cluster is None else cluster.map
    ahead = set(guesses)  # the groups whose units will all have a guess
    ends = [e for g in mapped(lambda g: _group_ends(g, ahead), list(groups.values()))
            for e in g]
    said = [e for _, e in ends if isinstance(e, dict)]
    if ends and len(said) == len(ends) and all(e["status"].startswith(NOTHING) for e in said):
        why = "; ".join(dict.fromkeys(f"{e['solver']}: {e['status']}" for e in said))
        raise UserError(f"{request.case}: none of the solvers {', '.join(request.solvers)} "
                        f"can locate {request.event} on this case ({why}); name another "
                        "solver with --solver")
    stuck = [(u, e[0]) for u, e in ends
             if isinstance(e, tuple) and e[0] is not None and e[0] == e[1]]
    if stuck:
        raise _no_change(request, stuck)
    by_group: dict[tuple, list] = {}
    for u, e in ends:
        by_group.setdefault(guess_key(u), []).append((u, e))
    rows = [r for g in mapped(lambda g: _group_rows(g, guesses, log), list(by_group.values()))
            for r in g]
    return add_grid_shift(rows)


def _group_ends(units: list[Unit], ahead: set[tuple]) -> list[tuple[Unit, Any]]:
    """The ends (:func:`_ends`) of the units of one (point, solver), in order: the first
    evaluates them unless the group has a guess; after a unit that cannot say, the
    others are left out (one row, not one a grid)."""
    out: list[tuple[Unit, Any]] = []
    known = bool(units) and guess_key(units[0]) in ahead
    for u in units:
        out.append((u, _ends(u, evaluate=not known)))
        if not isinstance(out[-1][1], dict):
            known = True  # evaluated (or searched from a guess): the next units search
        elif not out[-1][1]["status"].startswith("fail"):
            break
    return out


def _group_rows(ends: list[tuple[Unit, Any]], guesses: dict[tuple, Guess],
                log: Callable[[str], None] | None) -> list[dict]:
    """The rows of the units of one (point, solver), bisected in order (each from the
    last one's threshold), the closed form's exact row first; each logged when done."""
    rows = []
    for u, e in ends:
        if solvers.record(u.solver).closed_form and u.factor == u.request.grids[0]:
            exact = _exact_row(u)
            if exact is not None:
                rows.append(exact)
        rows.append(e if isinstance(e, dict) else _bisect_unit(u, e, guesses))
        if log is not None:
            log(row_line(rows[-1]))
    return rows


def row_line(row: dict[str, Any]) -> str:
    """One line of a finished bisection (or why it has none): its progress line."""
    where = f" [{row['point']}]" if row["point"] else ""
    at = f" at {row['at']}" if row["at"] else ""
    if isinstance(row["threshold"], float) and math.isfinite(row["threshold"]):
        what = f"{row['param']} = {row['threshold']:.6g} ± {row['uncertainty']:.2g}"
    else:
        what = str(row["status"])
    return (f"{row['solver']} {row['grid']}{where}{at}: {what} ({row['evaluations']} "
            f"evaluations, {row['wall_s']:.1f} s)")


def add_grid_shift(rows: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """``grid_shift``: each row's threshold minus that of the same (point, solver) on the
    case grid (factor 1, else the first grid listed); the exact row gets the step label."""
    ref: dict[tuple[str, str], float] = {}
    for row in (r for r in rows if r["grid"] != "exact"):
        if (row["point"], row["solver"]) not in ref or row["refine"] == 1.0:
            ref[(row["point"], row["solver"])] = row["threshold"]
    for row in rows:
        if row["grid"] != "exact":
            row["grid_shift"] = row["threshold"] - ref[(row["point"], row["solver"])]
        elif not row["at"]:
            row["at"] = next((o["at"] for o in rows if o["at"]), "")
    return rows
