"""Kratos Multiphysics' mortar contact (its ContactStructuralMechanicsApplication) as the
contact-vv solver plugin ``kratos``: a second finite-element reference of another lineage
than ``fem_reference``, verified through the suite's own comparisons and gates
(reports/README.md, "Solver plugins"; issue 60).

``kratos``: frictionless normal contact of the case's sphere on its plane, both bodies
meshed by gmsh as quarter models of linear tetrahedra (:mod:`kratos_adapter.mesh`),
solved by Kratos' augmented-Lagrangian mortar contact under the case's normal load
(:mod:`kratos_adapter.model`, :mod:`kratos_adapter.run`); the pressure on the case grid
and the stresses on its planes interpolated in the elements and mirrored to the full
grid (:mod:`kratos_adapter.fields`).  What it declines and why:
:mod:`kratos_adapter.support`.  Its error budget is measured by a grid study of its own
mesh (:func:`budget`).

It shares no code with ``fem_reference`` or ``halfspace`` (tests/test_suite_architecture.py):
only the case model, the result container and gmsh.  It runs only when named
(``--solver kratos,fem,ic,analytic``); without Kratos installed the record is not offered
(nothing changes).  Kratos runs on one thread.
"""

from __future__ import annotations

import importlib.util
import math
from collections.abc import Callable
from importlib import metadata

from cases.model import Case
from cases.result import Cost, RunResult, StepResult
from reports.registry.record import SolverRecord

from .support import supports

__all__ = ["record", "solve", "supports", "by_default", "estimate", "budget"]

#: the distributions of the ``[kratos]`` extra (in ``[peers]``) that make the plugin,
#: looked up without importing Kratos (its import prints a banner)
DISTRIBUTIONS = ("kratosmultiphysics", "kratosstructuralmechanicsapplication",
                 "kratoscontactstructuralmechanicsapplication",
                 "kratoslinearsolversapplication")

#: (quantity, metric) -> the expected error against the exact solution at the element
#: size of the bundled cases (a0/6 at the default fem.h), measured by the grid study of
#: benchmarks/README.md, "Kratos through the gates" (the worst of a0/6, a0/8 and a0/10,
#: with a margin); the lengths in cells and a0 as for the grid solvers
BUDGET = {
    ("P", "rel"): 0.005,
    ("p_max", "rel"): 0.06,
    ("p_n", "l2"): 0.06,
    ("p_n", "max"): 0.15,
    ("vm_max", "rel"): 0.03,
    ("vm_xz", "l2"): 0.04,
    ("vm_yz", "l2"): 0.04,
    ("vm_xz", "max"): 0.12,
    ("vm_yz", "max"): 0.12,
}


def budget(quantity: str, metric: str) -> float:
    """The expected error of ``kratos`` against the exact solution (:data:`BUDGET`);
    what it does not list, the grid solvers' budget
    (:func:`reports.registry.solvers.grid_budget`)."""
    if (quantity, metric) in BUDGET:
        return BUDGET[(quantity, metric)]
    from reports.registry.solvers import grid_budget  # not at plugin load

    return grid_budget(quantity, metric)


def cell(case: Case) -> float:
    """The element size at the contact [mm] (:func:`kratos_adapter.run.element_size`)."""
    from .run import element_size

    return element_size(case)


def reach(case: Case) -> float:
    """The stress reach [mm]: the diameter bound of gmsh's elements at size h (2.75 h, as
    for the FEM reference's mesher, the same sizing) — a sample's stress is interpolated
    from its element's nodes."""
    return 2.75 * cell(case)


def label(case: Case) -> str:
    """The element size at the contact, ``kratos.h=0.1667a0``."""
    return f"kratos.h={cell(case) / case.hertz_scales[0]:.4g}a0"


def refine(case: Case, factor: float) -> Case:
    """The same case with elements ``factor`` times smaller: ``fem.h`` scaled
    (:func:`reports.registry.discretisation.refine_fem`; the plugin meshes at
    :data:`kratos_adapter.run.H_FACTOR` times it)."""
    from reports.registry.discretisation import refine_fem  # not at plugin load

    return refine_fem(case, factor)


def record() -> SolverRecord | None:
    """The ``kratos`` solver; None without Kratos installed (the ``[peers]`` extra)."""
    if importlib.util.find_spec("KratosMultiphysics") is None:
        return None
    for dist in DISTRIBUTIONS:
        try:
            metadata.version(dist)
        except metadata.PackageNotFoundError:
            return None
    return SolverRecord("kratos", __name__, budget=budget, cell_size=cell, label=label,
                        refine=refine, reach=reach,
                        style={"color": "C9", "ls": "--", "marker": "D", "ms": 3})


def by_default(case: Case) -> str:
    """A peer under verification runs only when named."""
    return "a peer code under verification: name it with --solver"


def estimate(case: Case) -> Cost:
    """Peak memory and wall time of one run: the nodes of the two quarter meshes grow as
    (FINE_RADIUS a0 / h)³ near the contact; measured 0.31 GB and 15-35 s at a0/6 on the
    bundled Hertz case (benchmarks/README.md, "Kratos through the gates")."""
    from .mesh import FINE_RADIUS

    try:
        ratio = case.hertz_scales[0] / cell(case)
    except Exception:  # the approach held: declined by supports anyway
        ratio = 6.0
    nodes = 6000.0 * (ratio / 6.0) ** 3 * (FINE_RADIUS / 2.5) ** 3
    return Cost(memory=0.25e9 + 1.2e4 * nodes, seconds=5.0 + 5e-3 * nodes * math.log(nodes),
                memory_keys=("fem.h",), time_keys=("fem.h",))


def solve(case: Case, *, progress: bool = False,
          on_output: Callable[[StepResult], None] | None = None) -> RunResult:
    """One output step of ``case`` by Kratos (:mod:`kratos_adapter.run`)."""
    from .run import run

    return run(case, on_output=on_output)
