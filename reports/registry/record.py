"""The record of a solver: what the reports know of it (:mod:`reports.registry.solvers`
holds the built-in records and the budgets; :mod:`reports.registry.plugins` the installed
ones), and the defaults of a solver on the case's grid."""

from __future__ import annotations

import functools
import importlib
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

from cases.model import Case
from reports.registry import relations
from reports.registry.errors import SolverUnavailable


def grid_cell(case: Case) -> float:
    """The larger cell side of the case's grid [mm]."""
    return max(case.grid.dx, case.grid.dy)


def grid_label(case: Case) -> str:
    """The case's grid, ``41x41``."""
    return f"{case.grid.nx}x{case.grid.ny}"


def no_case_term(case: Case, quantity: str, metric: str) -> float:
    """A solver whose budget does not depend on the kind of case."""
    return 0.0


def no_model_form(quantity: str, metric: str) -> float:
    """The solver models the half-space problem itself: no model-form term."""
    return 0.0


@dataclass(frozen=True)
class SolverRecord:
    """What the reports know of one solver (:mod:`reports.registry.solvers`, module doc)."""

    name: str
    package: str  # importable module exposing solve() and supports()
    #: expected error against the exact solution (quantity, metric) -> relative error
    budget: Callable[[str, str], float]
    style: Mapping[str, Any] = field(default_factory=lambda: {"ls": "-."})
    cell_size: Callable[[Case], float] = grid_cell
    #: how the discretisation of a case is named in tables (``41x41``, ``fem.h=0.125``)
    label: Callable[[Case], str] = grid_label
    #: the same case with cells ``factor`` times smaller (coarser below 1), for grid
    #: studies (``run --convergence``); None: the solver has no grid to refine
    refine: Callable[[Case, float], Case] | None = None
    #: what the budget adds for a kind of case (case, quantity, metric) -> term, e.g. a
    #: closed form that is an asymptotic limit there
    case_term: Callable[[Case, str, str], float] = no_case_term
    #: relative error of what the solver models differently from the half-space problem
    #: (quantity, metric) -> term, for uncertainty-based tolerances (reports.studies.uncertainty)
    model_form: Callable[[str, str], float] = no_model_form
    #: the width [mm] over which the solver resolves a step of the worn surface (an
    #: element: its surface is polynomial within one), for the resolution probe
    #: (reports.studies.probe); None: it holds a step sharp, or has no surface
    step_width: Callable[[Case], float] | None = None
    #: the distance [mm] over which the field around a point decides the solver's
    #: subsurface stresses there: the width of the planes' edge band
    #: (reports.compare.metrics); None: its cell
    reach: Callable[[Case], float] | None = None
    closed_form: bool = False
    solve_attr: str = "solve"
    supports_attr: str = "supports"
    estimate_attr: str = "estimate"  # optional: Cost of a case before any work
    #: optional: why a run that names no solvers leaves this one out on a case (None: it
    #: runs); the solver still runs when requested with --solver
    default_attr: str = "by_default"
    #: a metamorphic relation of the solver ``base`` (reports.registry.relations): it runs
    #: the base on the transformed case, wherever the base runs, and pairs with it only
    relation: relations.Relation | None = None
    base: str = ""
    #: keyword arguments every entry point of the package is called with (an external
    #: result set's ``name``)
    options: Mapping[str, Any] = field(default_factory=dict)
    #: why the solver cannot run on this machine (a program it drives is missing, and
    #: how to get it), None when it can; checked before any entry point is used
    requires: Callable[[], str | None] | None = None
    #: what the solver models and declines, one line for ``contact-vv list`` (its
    #: ``supports`` says why on each case)
    scope: str = ""

    def stress_reach(self, case: Case) -> float:
        """:attr:`reach` of ``case``, else its cell (NaN: a closed form's, none)."""
        return (self.reach or self.cell_size)(case)

    def entry(self, attr: str) -> Callable:
        """The callable ``attr`` of the package; SolverUnavailable if it cannot load."""
        reason = self.requires() if self.requires is not None else None
        if reason:
            raise SolverUnavailable(f"solver {self.name!r} is not available: {reason}")
        try:
            module = importlib.import_module(self.package)
        except Exception as exc:  # an import error, or any error a plugin raises
            raise SolverUnavailable(f"solver {self.name!r} is not available: cannot import "
                                    f"{self.package} ({exc})") from None
        fn = getattr(module, attr, None)
        if not callable(fn):
            raise SolverUnavailable(f"solver {self.name!r} is not available: {self.package} "
                                    f"has no entry point {attr}()")
        return functools.partial(fn, **self.options) if self.options else fn
