"""Tamaas (Frérot, Anciaux, Rey, Pham-Ba and Molinari; the peer code of the ``[peers]``
extra) as contact-vv solver plugins, verified through the suite's own comparisons and
gates (reports/README.md, "Solver plugins"; the verdict: benchmarks/README.md).

Two solvers, registered in ``pyproject.toml`` under ``contact_vv.solvers``:

- ``tamaas``: normal contact by Tamaas's PolonskyKeerRey with its non-periodic DC-FFT
  operator; partial slip under a tangential load by its PolonskyKeerTan (periodic
  only); the subsurface stresses by its volume operators on a domain padded to twice the
  case grid (:mod:`tamaas_adapter.volume`);
- ``tamaas_periodic``: normal contact with Tamaas's default periodic operator, the
  stresses of the same periodic problem.

Which cases each models, and why not the others: :mod:`tamaas_adapter.support`.  Both
run only when named (``--solver tamaas,ic,analytic``): a peer under verification, not a
reference.  Without Tamaas installed the records are not offered (nothing changes).
"""

from __future__ import annotations

import importlib.util
from collections.abc import Callable

from cases.model import Case
from cases.result import Cost, RunResult, StepResult
from reports.plugin import SolverRecord

from .support import supports, supports_periodic

__all__ = ["record", "record_periodic", "solve", "solve_periodic", "supports",
           "supports_periodic", "by_default", "estimate", "estimate_periodic"]


def grid_budget(quantity: str, metric: str) -> float:
    """Tamaas discretises the tractions on the case's cells as the half-space solver
    does: the grid solvers' budget (:func:`reports.registry.solvers.grid_budget`)."""
    from reports.plugin import grid_budget as budget  # not at plugin load

    return budget(quantity, metric)


def refine_grid(case: Case, factor: float) -> Case:
    """The case grid refined by ``factor``, as for the half-space solver's grid studies
    (:func:`reports.registry.discretisation.refine_grid`)."""
    from reports.plugin import refine_grid as refine  # not at plugin load

    return refine(case, factor)


def missing() -> str | None:
    """Why the plugins cannot run here (Tamaas not installed), None if they can."""
    if importlib.util.find_spec("tamaas") is None:
        return "Tamaas is not installed: pip install 'contact-vv[peers]'"
    return None


#: what the plugins model (tamaas_adapter/support.py says why not, case by case)
SCOPE = ("static normal contact and partial slip under a tangential load, isotropic "
         "friction; declines wear, orthotropic friction, dissimilar materials with "
         "friction, and the approach or a shift held")


def _record(name: str, suffix: str, style: dict) -> SolverRecord:
    return SolverRecord(name, __name__, budget=grid_budget, refine=refine_grid,
                        solve_attr="solve" + suffix, supports_attr="supports" + suffix,
                        estimate_attr="estimate" + suffix, requires=missing, scope=SCOPE,
                        style=style)


def record() -> SolverRecord:
    """The ``tamaas`` solver (DC-FFT normal contact, PolonskyKeerTan partial slip)."""
    return _record("tamaas", "", {"color": "C5", "ls": "-", "marker": "v", "ms": 3})


def record_periodic() -> SolverRecord:
    """The ``tamaas_periodic`` solver (the periodic operator on the case grid)."""
    return _record("tamaas_periodic", "_periodic",
                   {"color": "C6", "ls": "-.", "marker": "x", "ms": 3})


def by_default(case: Case) -> str:
    """A peer under verification runs only when named."""
    return "a peer code under verification: name it with --solver"


def estimate(case: Case) -> Cost:
    """Peak memory and wall time of ``tamaas`` on ``case`` (:mod:`tamaas_adapter.cost`)."""
    from .cost import estimate as _estimate

    return _estimate(case, periodic=False)


def estimate_periodic(case: Case) -> Cost:
    """Peak memory and wall time of ``tamaas_periodic`` on ``case``."""
    from .cost import estimate as _estimate

    return _estimate(case, periodic=True)


def solve(case: Case, *, progress: bool = False,
          on_output: Callable[[StepResult], None] | None = None) -> RunResult:
    """One output step of ``case`` by Tamaas (non-periodic normal contact)."""
    from .contact import run

    return run(case, periodic=False, on_output=on_output)


def solve_periodic(case: Case, *, progress: bool = False,
                   on_output: Callable[[StepResult], None] | None = None) -> RunResult:
    """One output step of ``case`` by Tamaas on the periodic case grid."""
    from .contact import run

    return run(case, periodic=True, on_output=on_output)
