"""Planning a run: a case file and its sweep points validated, the solvers that apply to
each point chosen (:mod:`reports.registry.solvers`), hopeless grids refused before any work."""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from cases.loader import case_path, load_case
from cases.model import Case, CaseError
from reports.registry import solvers
from reports.registry.errors import SolverUnavailable, UserError
from reports.registry.pairs import pairs
from reports.registry.tolerances import check_keys
from reports.run import deadline
from reports.store import layout
from reports.studies import registry as studies
from reports.studies.study import Own, Planned, Study, StudyRun


def check_fits(case: Case) -> None:
    """Refuse a case whose contact cannot fit in the potential contact grid.

    The solvers detect a contact touching the grid edge during the run; this catches
    the hopeless cases before any work: the expected radius must leave at least one
    cell free on each side.
    """
    a = case.expected_radius
    g = case.grid
    for key, half, cell in (("grid.Lx", g.Lx / 2, g.dx), ("grid.Ly", g.Ly / 2, g.dy)):
        if a >= half - cell:
            where = f" [{case.param}]" if case.param else ""
            raise CaseError(
                f"{key} = {2 * half:g} mm{where}: the expected contact radius {a:.4g} mm "
                f"reaches the edge of the potential contact grid (half-width {half:g} mm, "
                f"cell {cell:.3g} mm); enlarge grid.Lx/grid.Ly")


def grid_warning(case: Case) -> str | None:
    """A fretting case whose worn contact may outgrow the grid
    (:attr:`cases.model.Case.worn_radius_estimate`), said before any work: the run is not
    refused (the estimate is too large where a stick zone stays) but stops at the grid
    edge if the contact reaches it."""
    a = case.worn_radius_estimate
    g = case.grid
    if a is None or a < min(g.Lx / 2 - g.dx, g.Ly / 2 - g.dy):
        return None
    where = f" [{case.param}]" if case.param else ""
    need = 2.0 * a + 4.0 * max(g.dx, g.dy)
    return (f"{case.name}{where}: grid.Lx x grid.Ly = {g.Lx:g} x {g.Ly:g} mm: by Archard's "
            f"law with gross slip in every cycle the worn contact may reach r = {a:.3g} mm "
            f"by cycle {case.fretting.cycles:g} (less where a stick zone stays); if it "
            f"reaches the grid edge the run stops there; grid.Lx = grid.Ly = {need:.3g} mm "
            "keeps it inside")


def available_memory() -> float:
    """Memory the machine has available now [bytes] (MemAvailable of /proc/meminfo, else
    the free physical pages)."""
    try:
        with open("/proc/meminfo") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    return float(line.split()[1]) * 1024
    except OSError:
        pass
    return float(os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_AVPHYS_PAGES"))


@dataclass(frozen=True)
class Limits:
    """What one unit of a run may take: memory [bytes] (default: 90 % of what the
    machine has available) and wall time [h] by the solvers' own estimates."""

    memory: float | None = None
    hours: float = 48.0
    slowdown: float = 1.0  # --time-factor: the machine against the estimates' own

    @classmethod
    def from_flags(cls, max_memory: float | None, max_hours: float,
                   time_factor: float = 1.0) -> Limits:
        """From ``--max-memory`` [GiB], ``--max-hours`` and ``--time-factor``; UserError
        unless positive."""
        for flag, value in (("--max-memory", max_memory), ("--max-hours", max_hours),
                            ("--time-factor", time_factor)):
            if value is not None and not (math.isfinite(value) and value > 0):
                raise UserError(f"{flag} must be a positive number")
        return cls(memory=None if max_memory is None else max_memory * 2**30,
                   hours=max_hours, slowdown=time_factor)

    def deadline(self, case: Case, solver: str) -> float:
        """How long ``solver`` may run on ``case`` (:mod:`reports.run.deadline`)."""
        cost = solvers.estimate(solver, case)
        return math.inf if cost is None else \
            deadline.seconds(cost.seconds, cost.time_factor, self.slowdown)

    def check(self, case: Case, solver: str) -> None:
        """CaseError naming the keys to change when ``solver``'s estimate for ``case``
        exceeds a limit."""
        cost = solvers.estimate(solver, case)
        if cost is None:
            return
        where = f"{case.name}" + (f" [{case.param}]" if case.param else "")
        memory, source = self.memory, "--max-memory"
        if memory is None:
            memory, source = 0.9 * available_memory(), "90 % of the available memory"
        if cost.memory > memory:
            raise CaseError(
                f"{where}: solver {solver} would need about {cost.memory / 2**30:.3g} GiB "
                f"(limit {memory / 2**30:.3g} GiB, {source}); reduce "
                f"{', '.join(cost.memory_keys)} (or set --max-memory)")
        if self.slowdown * cost.seconds > 3600.0 * self.hours:
            raise CaseError(
                f"{where}: solver {solver} would run for about "
                f"{self.slowdown * cost.seconds / 3600:.3g} h "
                f"(limit {self.hours:g} h); reduce {', '.join(cost.time_keys)} (or set "
                "--max-hours)")


@dataclass(frozen=True)
class CasePlan:
    """What to run for one case: its sweep points and the solvers that apply.  Built once
    (:func:`plan_case`); a changed plan is a new one (``dataclasses.replace``)."""

    name: str
    source: Path
    points: list[Case]
    solvers: list[str]
    skipped: dict[str, str] = field(default_factory=dict)
    quick: bool = False
    overrides: dict[str, Any] = field(default_factory=dict)
    sweep: dict[str, Any] | None = None
    dir_name: str = ""
    staging: Path | None = None  # where output steps are streamed (the runner's copy)
    #: the run's studies with their runs (reports.studies.study), in the registry's order
    studies: tuple[Planned, ...] = ()
    warnings: list[str] = field(default_factory=list)  # said before any work (grid_warning)
    limits: Limits = field(default_factory=Limits)  # memory, time, deadlines

    def units(self) -> list[tuple[int, str]]:
        """(point index, solver) pairs to run, point-major, solvers in registry order."""
        return [(i, s) for i, case in enumerate(self.points) for s in self.solvers
                if s in self.applicable(case)]

    def applicable(self, case: Case) -> list[str]:
        return [s for s in self.solvers if solvers.unsupported(s, case) is None]

    def not_run(self) -> dict[str, str]:
        """The skipped solvers a user would miss, with why: those chosen for the run
        (named, or run by default) that declined the case, and the built-in solvers that
        run by default and could not; not the plugins nobody named, nor the metamorphic
        relations that do not apply to the case (:attr:`skipped` holds every one)."""
        return {s: why for s, why in self.skipped.items()
                if not solvers.record(s).base
                and (s in self.solvers or s not in solvers.PLUGINS)}

    def own(self) -> Own:
        """The run's own units as its studies see them (before any work)."""
        return Own(self.points, self.units(), self.applicable)

    def study_runs(self) -> list[StudyRun]:
        """The runs of every study of the plan, in order."""
        return [r for planned in self.studies for r in planned.runs]

    def check(self, case: Case, solver: str) -> None:
        """A study's unit checked like the case's own (``CaseError``)."""
        check_fits(case)
        self.limits.check(case, solver)

    def planned(self, study: Study) -> Planned:
        """The plan's ``study`` with its runs (none, if the plan does not hold it)."""
        return next((p for p in self.studies if p.study is study), Planned(study))

    def with_study(self, study: Study) -> CasePlan:
        """The plan with ``study`` and its runs (:meth:`Study.plan`), in the registry's
        order (``CaseError`` from the study's checks)."""
        held = [p for p in self.studies if p.study is not study]
        held.append(Planned(study, tuple(study.plan(self.own(), self.check))))
        return replace(self, studies=tuple(sorted(held, key=lambda p: studies.rank(p.study))))


#: the metamorphic relation a default run adds where no other solver compares with one
PARTNER = "mirror"


def _add_partner(plan: CasePlan) -> CasePlan:
    """``plan``, where a point of a run has no pair to compare (one numerical solver, no
    closed form, the FEM not run by default or not named), with that solver's exact
    :data:`PARTNER` relation, where it applies: a case the gate verifies nothing of fails
    it."""
    lonely = [c for c in plan.points if not pairs(plan.applicable(c))]
    for base in dict.fromkeys(s for c in lonely for s in plan.applicable(c)):
        partner = f"{base}+{PARTNER}"
        if partner in plan.solvers or partner not in solvers.names() or \
                any(solvers.unsupported(partner, c) is not None for c in lonely):
            continue
        plan = replace(
            plan, solvers=[s for s in solvers.names() if s in plan.solvers or s == partner],
            warnings=[*plan.warnings, f"{plan.name}: no other solver compares with {base} on "
                      f"this case; its exact relation {partner} runs too (one more run of "
                      f"{base}), so that the gate verifies something"])
    return plan


def select_solvers(requested: list[str] | None, *, relations: bool = True
                   ) -> tuple[list[str], dict[str, str]]:
    """(usable solvers, {skipped solver: reason}).

    Without an explicit request every registered solver is tried and unavailable ones
    are skipped; an explicitly requested solver that cannot load is an error.  The
    metamorphic relations of a chosen base solver come with it when ``relations`` (the
    quick tier: at full size each costs another run of its base) or when named.
    """
    known = solvers.names()

    def wanted(s: str, chosen: list[str]) -> bool:
        base = solvers.record(s).base
        return s in chosen or bool(base) and relations and base in chosen

    if requested:
        unknown = [s for s in requested if s not in known and not solvers.is_external(s)]
        if unknown:
            raise UserError(f"unknown solver(s) {', '.join(unknown)} (known: {', '.join(known)}"
                            f", {solvers.EXTERNAL}NAME for the case's [external.NAME] files)")
        for s in requested:
            solvers.resolve(s)  # raises SolverUnavailable with the reason
        # result files of another code come first, like a plugin: the built-in solvers
        # are their references; by name, so that no pair depends on the order named
        external = sorted({s for s in requested if solvers.is_external(s)})
        return external + [s for s in known if wanted(s, requested)], {}
    usable, skipped = [], {}
    for s in known:
        ok, reason = solvers.available(s)
        if ok:
            usable.append(s)
        else:
            skipped[s] = reason
    if not usable:
        raise SolverUnavailable("no solver is available: " + "; ".join(skipped.values()))
    bases = [s for s in usable if not solvers.record(s).base]
    return [s for s in usable if wanted(s, bases)], skipped


def _check_point_dirs(points: list[Case]) -> None:
    """Every sweep point must have a field directory of its own
    (:func:`reports.store.layout.param_dir`), of a length a file system takes."""
    seen: dict[str, str] = {}
    for case in points:
        folder = layout.param_dir(case.param)
        if folder in seen:
            raise CaseError(f"sweep.values: the points {seen[folder]!r} and {case.param!r} "
                            f"would share the field directory {folder}/ (characters other "
                            "than letters, digits and . _ = + - become _); make the values "
                            "differ in the characters kept")
        if len(folder.encode()) > 200:
            raise CaseError(f"sweep.values: the point {case.param[:60]!r}... is too long to "
                            "name a directory (at most 200 characters)")
        seen[folder] = case.param


def plan_case(ref: str | Path, solver_names: list[str], *, quick: bool = False,
              overrides: dict[str, Any] | None = None, skipped: dict[str, str] | None = None,
              points: list[Case] | None = None, sweep: dict[str, Any] | None = None,
              dir_name: str | None = None, limits: Limits | None = None,
              explicit: bool = True) -> CasePlan:
    """Load and validate a case (``CaseError`` on bad input, or a unit beyond the
    ``limits``) and plan its runs (the studies a flag asks for are added by
    :func:`request_study`).  ``explicit``: the solvers were named by the
    user; otherwise a solver that runs on a case only on request
    (:func:`reports.registry.solvers.not_by_default`) is left out with its reason."""
    source = case_path(ref)
    if points is None:
        points = load_case(source, quick=quick, overrides=overrides)
    warnings = []
    for case in points:
        check_keys(case, solvers.names())
        check_fits(case)
        if (w := grid_warning(case)) is not None:
            warnings.append(w)
    _check_point_dirs(points)
    name = points[0].name
    chosen, skipped = list(solver_names), dict(skipped or {})
    for s in chosen:
        reasons = [solvers.unsupported(s, c) for c in points]
        if all(r is not None for r in reasons):
            skipped[s] = reasons[0]
    if not explicit:
        for s in [s for s in chosen if s not in skipped]:
            reason = next((r for c in points if (r := solvers.not_by_default(s, c))), None)
            if reason is not None:
                skipped[s] = reason
                chosen.remove(s)
    plan = _add_partner(CasePlan(  # named solvers that compare nothing get the exact relation
        name=name, source=source, points=points, solvers=chosen, skipped=skipped,
        quick=quick, overrides=dict(overrides or {}), sweep=sweep, dir_name=dir_name or name,
        warnings=warnings, limits=limits or Limits()))
    if not plan.units():  # a run of nothing would write an empty case that gates nothing
        why = "; ".join(f"{s}: {r}" for s, r in plan.skipped.items() if s in solver_names)
        raise CaseError(f"{source}: none of the solvers {', '.join(solver_names)} runs this "
                        f"case ({why or 'no solver chosen'})")
    for i, s in plan.units():
        plan.limits.check(points[i], s)
    return _add_automatic(plan)


def _add_automatic(plan: CasePlan) -> CasePlan:
    """``plan`` with every study no flag asks for (``option`` None) that plans runs for it,
    e.g. the resolution probe of worn points (:mod:`reports.studies.probe`)."""
    for study in studies.STUDIES:
        if study.option is None:
            held = plan.with_study(study)
            plan = held if held.planned(study).runs else plan
    return plan


def request_study(plans: list[CasePlan], name: str) -> tuple[list[CasePlan], list[str]]:
    """``plans`` with the study ``name`` that a flag asked for (``Study.option``), and a note
    on each case it has nothing to study in; UserError when no plan gets a run of it."""
    study = studies.by_name(name)
    plans = [p.with_study(study) for p in plans]
    if not any(p.planned(study).runs for p in plans):
        raise UserError(f"{study.option}: {study.nothing_planned([p.own() for p in plans])}")
    notes = [n for p in plans if not p.planned(study).runs
             if (n := study.idle_note(p.own())) is not None]
    return plans, notes
