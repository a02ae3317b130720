"""The one module a solver plugin imports from the suite (``reports/README.md``, "Solver
plugins"): the record it declares, the budgets and refinements it may reuse, the errors it
may raise, the silencer of a chatty library, and the case and result types it reads and
returns.  These names are the plugins' stable face; the modules behind them may change.
The bundled adapters import nothing else of ``reports`` (``tests/test_suite_plugin_face.py``).

- :class:`SolverRecord`: what a plugin declares (its package, budget, cell size, …);
- :func:`grid_budget`: the grid solvers' error budget (quantity, metric) -> tolerance;
- :func:`refine_grid`, :func:`refine_fem`: a case refined for a grid study, as the
  half-space solver's grid or as the FEM's elements;
- :func:`silenced`: a context that silences a library writing to file descriptors 1/2;
- :class:`SolverUnavailable`, :class:`UserError`: a solver that cannot run here, a bad
  request;
- :class:`Case`, :class:`CaseError`, :class:`Cost`, :class:`RunResult`,
  :class:`StepResult`, :class:`Plane`: the case a plugin is given, its errors, its
  estimate, and the result it returns (package ``cases``).

The names are imported when first used: a plugin's record can be built while the
registry that loads it is still being built.
"""

from __future__ import annotations

from importlib import import_module
from typing import Any

#: public name -> the module that defines it
HOMES = {
    "SolverRecord": "reports.registry.record",
    "grid_budget": "reports.registry.solvers",
    "refine_grid": "reports.registry.discretisation",
    "refine_fem": "reports.registry.discretisation",
    "silenced": "reports.registry.plugins",
    "SolverUnavailable": "reports.registry.errors",
    "UserError": "reports.registry.errors",
    "Case": "cases.model",
    "CaseError": "cases.model",
    "Cost": "cases.result",
    "RunResult": "cases.result",
    "StepResult": "cases.result",
    "Plane": "cases.result",
}

__all__ = sorted(HOMES)


def __getattr__(name: str) -> Any:
    if name not in HOMES:
        raise AttributeError(f"module 'reports.plugin' has no attribute {name!r}")
    value = getattr(import_module(HOMES[name]), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
