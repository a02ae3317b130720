"""Kratos Multiphysics' mortar contact (its ContactStructuralMechanicsApplication) as the
contact-vv solver plugin ``kratos``: a second finite-element reference of another lineage
than ``fem_reference``, verified through the suite's own comparisons and gates
(reports/README.md, "Solver plugins"; issue 60).

``kratos``: frictionless normal contact of the case's sphere on its plane, both bodies
quarter models of structured trilinear hexahedra (:mod:`kratos_adapter.mesh`), solved
by Kratos' augmented-Lagrangian mortar contact under the case's normal load
(:mod:`kratos_adapter.model`, :mod:`kratos_adapter.run`); the pressure on the case grid
and the stresses on its planes interpolated in the elements and mirrored to the full
grid (:mod:`kratos_adapter.fields`).  What it declines and why:
:mod:`kratos_adapter.support`.  Its error budget is measured by a grid study of its own
mesh (:func:`budget`).

It shares no code with ``fem_reference`` or ``halfspace`` (tests/test_suite_architecture.py):
only the case model, the result container and the registry's record.  It runs only when named
(``--solver kratos,fem,ic,analytic``); without Kratos installed the record is not offered
(nothing changes).  Kratos runs on one thread.
"""

from __future__ import annotations

import importlib.util
from collections.abc import Callable
from importlib import metadata

from cases.model import Case
from cases.result import Cost, RunResult, StepResult
from reports.plugin import SolverRecord

from .support import supports

__all__ = ["record", "solve", "supports", "by_default", "estimate", "budget"]

#: the distributions of the ``[kratos]`` extra (in ``[peers]``) that make the plugin,
#: looked up without importing Kratos (its import prints a banner)
DISTRIBUTIONS = ("kratosmultiphysics", "kratosstructuralmechanicsapplication",
                 "kratoscontactstructuralmechanicsapplication",
                 "kratoslinearsolversapplication")

#: (quantity, metric) -> the expected error against the exact solution at the element
#: size of the bundled cases (a0/6 at the default fem.h), each above the largest error
#: measured against the closed form (benchmarks/README.md, "Kratos through the gates"):
#: the grid study of its own mesh on the bundled Hertz case (a0/4, a0/5, a0/6), a
#: frictionless steel-on-aluminium contact, and four generated normal contacts
#: (tests/case_generator.py, ν from -0.26 to 0.07):
#:
#: - p_max 0.23 / 0.15 / 0.006 % (the structured mesh's nodal pressure; the case's own
#:   p_max tolerance, 1 %, applies on Hertz); P: the load search's tolerance
#:   (:data:`kratos_adapter.run.LOAD_TOL`, 0.2 %);
#: - p_n 1.3 / 1.4 / 0.8 % in L2, 1.5 / 1.6 / 0.9 % in the max norm; 2.5 % and 4.8 % on
#:   the steel-on-aluminium contact, whose grid (a0/13 cells) samples the pressure,
#:   linear between nodes a0/6 apart, closer to the edge;
#: - σ_VM planes 3.7 / 3.7 / 2.8 % in L2 (3.7 % steel on aluminium, 4.0 % on a
#:   generated draw) and 19 / 14.5 / 11.5 % in the max norm (12.7 %), the largest at the
#:   surface under the contact, where σ_VM has its steep minimum and the first element
#:   layer is h/2 thick (it shrinks with h, order about 1.3); σ_VM,max 0.33 / 0.56 /
#:   0.40 % (0.62 %; 1.22 % on a generated draw with ν = 0);
#: - lengths: a_x up to 1.07 cells (the pressure linear from the last active node to the
#:   first inactive one, h further out), the contact's equivalent radius 0.67 cells.
BUDGET = {
    ("P", "rel"): 0.003,
    ("p_max", "rel"): 0.005,
    ("p_n", "l2"): 0.03,
    ("p_n", "max"): 0.05,
    ("vm_max", "rel"): 0.015,
    ("vm_xz", "l2"): 0.05,
    ("vm_yz", "l2"): 0.05,
    ("vm_xz", "max"): 0.13,
    ("vm_yz", "max"): 0.13,
    ("a_x", "cells"): 1.25,
    ("a_y", "cells"): 1.25,
    ("contact_area", "cells"): 1.25,
}


def budget(quantity: str, metric: str) -> float:
    """The expected error of ``kratos`` against the exact solution (:data:`BUDGET`);
    what it does not list, the grid solvers' budget
    (:func:`reports.registry.solvers.grid_budget`)."""
    if (quantity, metric) in BUDGET:
        return BUDGET[(quantity, metric)]
    from reports.plugin import grid_budget  # not at plugin load

    return grid_budget(quantity, metric)


def cell(case: Case) -> float:
    """The element size at the contact [mm] (:func:`kratos_adapter.run.element_size`)."""
    from .run import element_size

    return element_size(case)


def reach(case: Case) -> float:
    """The stress reach [mm], the planes' edge band: 2.75 h, the bound the FEM reference
    takes for its elements (this mesh's element diagonal is √3 h; a sample's stress is
    interpolated from its element's nodes, each an average over the elements around
    it).  Chosen, not measured: the budget's plane errors were measured with it."""
    return 2.75 * cell(case)


def label(case: Case) -> str:
    """The element size at the contact, ``kratos.h=0.1667a0``."""
    return f"kratos.h={cell(case) / case.hertz_scales[0]:.4g}a0"


def refine(case: Case, factor: float) -> Case:
    """The same case with elements ``factor`` times smaller: ``fem.h`` scaled
    (:func:`reports.registry.discretisation.refine_fem`; the plugin meshes at
    :data:`kratos_adapter.run.H_FACTOR` times it)."""
    from reports.plugin import refine_fem  # not at plugin load

    return refine_fem(case, factor)


#: how to get the Kratos distributions the plugin drives
HOW_TO_GET = "pip install 'contact-vv[kratos]' (or [peers])"


def missing() -> str | None:
    """Why the plugin cannot run here (a Kratos distribution not installed), None if it
    can."""
    gone = [d for d in DISTRIBUTIONS if not _installed(d)]
    if not gone and importlib.util.find_spec("KratosMultiphysics") is None:
        gone = ["KratosMultiphysics"]
    return f"Kratos is not installed ({gone[0]}…): {HOW_TO_GET}" if gone else None


def _installed(dist: str) -> bool:
    try:
        metadata.version(dist)
    except metadata.PackageNotFoundError:
        return False
    return True


def record() -> SolverRecord:
    """The ``kratos`` solver, offered always and available where Kratos is installed
    (:func:`missing`)."""
    return SolverRecord("kratos", __name__, budget=budget, cell_size=cell, label=label,
                        refine=refine, reach=reach, requires=missing,
                        scope="static frictionless normal contact, identical or dissimilar "
                        "materials, load P; declines friction, wear and the approach held",
                        style={"color": "C9", "ls": "--", "marker": "D", "ms": 3})


def by_default(case: Case) -> str:
    """A peer under verification runs only when named."""
    return "a peer code under verification: name it with --solver"


def estimate(case: Case) -> Cost:
    """Peak memory and wall time of one run, from the nodes of its two quarter meshes
    (:func:`kratos_adapter.mesh.node_count`): measured on the bundled Hertz case at a0/4,
    a0/5 and a0/6 (7200, 9826 and 14440 nodes): 327, 368 and 437 MB; 2.5 to 12 s per
    Newton iteration of Kratos (AMGCL), 2 to 7 iterations (benchmarks/README.md,
    "Kratos through the gates").  An order of magnitude, not calibrated for a deadline."""
    from .mesh import node_count
    from .run import SIDE

    try:
        a0 = case.hertz_scales[0]
        nodes = node_count(a0, cell(case), SIDE * a0)
    except Exception:  # the approach held: declined by supports anyway
        nodes = 15000
    return Cost(memory=0.22e9 + 1.6e4 * nodes, seconds=5.0 + 6 * 6e-4 * nodes,
                memory_keys=("fem.h",), time_keys=("fem.h",))


def solve(case: Case, *, progress: bool = False,
          on_output: Callable[[StepResult], None] | None = None) -> RunResult:
    """One output step of ``case`` by Kratos (:mod:`kratos_adapter.run`)."""
    from .run import run

    return run(case, on_output=on_output)
