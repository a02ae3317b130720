"""How each solver's discretisation is measured and refined, for the records of
:mod:`reports.registry.solvers`: its cell size (the unit of lengths and resolution
floors), its stress reach (the planes' edge band, :mod:`reports.compare.metrics`), its
label in tables, and the same case on finer or coarser cells for grid studies."""

from __future__ import annotations

import math
from dataclasses import replace

from cases.model import Case, CaseError


def fem_cell(case: Case) -> float:
    """The FEM's element size at the contact surface [mm]: ``fem.h_surface`` (else
    ``fem.h``) in units of a0."""
    return case.fem.h_contact * case.hertz_scales[0]


#: the longest edge of an element touching the FEM's contact surface where its size is h
#: (``h_surface`` with a surface layer), over h: a bound of the mesher's elements (held by
#: tests/test_fem_mesh.py; measured: benchmarks/README.md, "False alarms")
FEM_ELEMENT_DIAMETER = 2.75


def fem_reach(case: Case) -> float:
    """The FEM's stress reach [mm]: the largest diameter of its contact-zone elements.  Its
    stress at a point is the linear field of the element containing it (P2 displacements),
    so an element that reaches the contact edge, where the traction's √ profile is not
    polynomial, carries that edge's error to every point of it."""
    return FEM_ELEMENT_DIAMETER * fem_cell(case)


def fem_label(case: Case) -> str:
    """The FEM's element sizes, ``fem.h=0.125`` (a0), with ``h_surface`` if set."""
    hs = case.fem.h_surface
    return f"fem.h={case.fem.h:.4g}" + ("" if hs is None else f",h_surface={hs:.4g}")


def no_cell(case: Case) -> float:
    """A closed form has no cell size."""
    return math.nan


def _cells(n: int, factor: float, key: str) -> int:
    """``n`` cells refined by ``factor`` (coarsened when it is below 1): the nearest count
    of the same parity (an odd count keeps a cell centred on the axis, an even one a cell
    face there) that changes the cell size by at least ``factor``."""
    m = math.ceil(n * factor - 1e-9) if factor > 1 else math.floor(n * factor + 1e-9)
    if (m - n) % 2:
        m += 1 if factor > 1 else -1
    if m < 4:
        raise CaseError(f"{key} = {n}: a grid {1 / factor:g} times coarser has {m} cells "
                        "(at least 4 needed); refine the grid for a grid-convergence study")
    return m


def refine_grid(case: Case, factor: float) -> Case:
    """``case`` on a grid whose cells are ``factor`` times smaller (larger when ``factor``
    < 1): ``grid.nx``, ``grid.ny`` scaled, the extents and everything else unchanged."""
    g = case.grid
    grid = replace(g, nx=_cells(g.nx, factor, "grid.nx"), ny=_cells(g.ny, factor, "grid.ny"))
    return case.with_changes(grid=grid)


def refine_fem(case: Case, factor: float) -> Case:
    """``case`` with the FEM's element sizes ``fem.h`` and ``fem.h_surface`` divided by
    ``factor`` (the block, the penalty in units of E*/h and the output grid unchanged)."""
    return case.with_changes(fem=case.fem.refined(factor))
