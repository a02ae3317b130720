"""CalculiX (the ``ccx`` program) as the contact-vv solver plugin ``calculix``: a second
finite-element reference of another lineage than ``fem_reference`` that checks the
frictional numbers — partial slip, the normal–tangential coupling of dissimilar
materials — through the suite's own comparisons and gates (reports/README.md, "Solver
plugins"; issue 74).

``calculix``: static contact of the case's sphere on its plane, two elastic bodies of
8-node hexahedra on tensor grids graded from the contact (:mod:`calculix_adapter.mesh`),
penalty surface-to-surface contact with isotropic Coulomb friction and the case's load
path (:mod:`calculix_adapter.model`, :mod:`calculix_adapter.deck`), ``ccx`` run on one
thread (:mod:`calculix_adapter.program`), its result files read by the suite's own
reader (:mod:`calculix_adapter.frd`): the tractions from the nodal forces of the
plane's face (:mod:`calculix_adapter.traction`), the stresses from the nodal stresses,
onto the case's grid and planes (:mod:`calculix_adapter.run`,
:mod:`calculix_adapter.fields`).  What it declines and why:
:mod:`calculix_adapter.support`.  Its error budget: :data:`BUDGET`.

It shares no code with ``fem_reference``, ``halfspace`` or ``analytic``
(tests/test_suite_architecture.py): only the case model, the result container and the
registry's record.  It runs only when named (``--solver calculix,fem,ic,analytic``);
without ``ccx`` on the PATH the record is offered but unavailable, saying how to get it.
"""

from __future__ import annotations

from collections.abc import Callable

from cases.model import Case
from cases.result import Cost, RunResult, StepResult
from reports.plugin import SolverRecord

from .support import missing, supports

__all__ = ["record", "solve", "supports", "by_default", "estimate", "budget", "missing"]

#: (quantity, metric) -> the expected error against the exact solution at the element
#: sizes of the bundled cases (a0/4 and a0/5), each above the largest error measured
#: there (benchmarks/README.md, "CalculiX through the gates": a grid study of three
#: element sizes, the penalty's two parameters, Hertz, Cattaneo–Mindlin, Spence, the
#: example cases, and against the other solvers on the dissimilar contact); what it
#: does not list, the grid solvers' budget.  The tractions' and the planes' are those of
#: trilinear elements a0/4 apart read on a grid four times finer: the exact solution
#: held at the nodes and interpolated as the plugin does misses itself by as much.
BUDGET: dict[tuple[str, str], float] = {
    ("P", "rel"): 0.001,
    ("p_max", "rel"): 0.015,
    ("p_n", "l2"): 0.10,
    ("p_n", "max"): 0.10,
    ("p_x", "l2"): 0.25,
    ("p_y", "l2"): 0.25,
    ("p_x", "max"): 0.12,
    ("p_y", "max"): 0.12,
    ("vm_max", "rel"): 0.02,
    ("vm_xz", "l2"): 0.06,
    ("vm_yz", "l2"): 0.06,
    ("vm_xz", "max"): 0.22,
    ("vm_yz", "max"): 0.22,
    ("a_x", "cells"): 1.25,
    ("a_y", "cells"): 1.25,
    ("contact_area", "cells"): 1.25,
}


def budget(quantity: str, metric: str) -> float:
    """The expected error of ``calculix`` against the exact solution (:data:`BUDGET`);
    what it does not list, the grid solvers' budget
    (:func:`reports.registry.solvers.grid_budget`)."""
    if (quantity, metric) in BUDGET:
        return BUDGET[(quantity, metric)]
    from reports.plugin import grid_budget  # not at plugin load

    return grid_budget(quantity, metric)


def cell(case: Case) -> float:
    """The element size at the contact [mm] (:func:`calculix_adapter.model.element_size`)."""
    from .model import element_size

    return element_size(case)


def reach(case: Case) -> float:
    """The stress reach [mm], the planes' edge band: 2.75 h (a sample's stress is
    trilinear in its element, from nodal values that average the elements around each
    node: the reach of the other finite-element solvers).  Chosen, not measured."""
    return 2.75 * cell(case)


def label(case: Case) -> str:
    """The element size at the contact, ``calculix.h=0.25a0``."""
    return f"calculix.h={cell(case) / case.hertz_scales[0]:.4g}a0"


def refine(case: Case, factor: float) -> Case:
    """The same case with elements ``factor`` times smaller: ``fem.h`` scaled
    (:func:`reports.registry.discretisation.refine_fem`; the plugin meshes at
    :data:`calculix_adapter.model.H_FACTOR` times it)."""
    from reports.plugin import refine_fem  # not at plugin load

    return refine_fem(case, factor)


def record() -> SolverRecord:
    """The ``calculix`` solver (unavailable without ``ccx``: :func:`missing`)."""
    return SolverRecord("calculix", __name__, budget=budget, cell_size=cell, label=label,
                        refine=refine, reach=reach, requires=missing,
                        scope="static contact with isotropic Coulomb friction, identical or "
                        "dissimilar materials, load P then (Qx, Qy); declines wear, "
                        "orthotropic friction, a shift or sliding, and the approach held",
                        style={"color": "C8", "ls": ":", "marker": "s", "ms": 3})


def by_default(case: Case) -> str:
    """A peer under verification runs only when named."""
    return "a peer code under verification: name it with --solver"


def estimate(case: Case) -> Cost:
    """Peak memory and wall time of one run from its equations and increments
    (benchmarks/README.md, "CalculiX through the gates")."""
    from .cost import cost

    return cost(case)


def solve(case: Case, *, progress: bool = False,
          on_output: Callable[[StepResult], None] | None = None) -> RunResult:
    """One output step of ``case`` by CalculiX (:mod:`calculix_adapter.run`)."""
    from .run import run

    return run(case, on_output=on_output)
