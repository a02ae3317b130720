"""The worn partial-slip contact of the quick sweep (``fretting_orthotropic``, β = 90°,
approach held, J = 500, 2000 cycles) on the half-space solver: its wear and stick zone
converge in space.

The worn profile steps at the stick edge (the slip annulus wears, the stick disc does
not).  The half-space solver holds the step at a cell boundary on every grid, so the
wear it carries and the stick zone it leaves converge in space, while the pressure
maximum at the step grows with every refinement (docs/fem-notes.md, part 5).  This is
what the FEM is compared against at β = 90°; the FEM resolves the step only across an
element, and that is where the two solvers part.
"""

from __future__ import annotations

import functools
import math

import halfspace
from cases.loader import load_case
from reports.registry.solvers import grid_budget


@functools.cache
def worn(n: int) -> dict[str, float]:
    """The scalars at 2000 cycles of the β = 90° quick point on an n² grid."""
    case = next(c for c in load_case("fretting_orthotropic", quick=True,
                                     overrides={"grid.nx": n, "grid.ny": n})
                if c.friction.beta == 90.0)
    step = halfspace.solve(case).steps[-1]
    assert step.scalars["cycle"] == 2000
    return {**step.scalars, "cell": case.grid.dx}


def test_the_worn_stick_zone_and_wear_converge_in_space():
    """31² against 63² (cells halved): w_max and the wear volume within the solver's
    budget for them (3 %), the stick zone's equivalent radius within its budget in the
    coarse grid's cells (1.5).  The stick zone is still there: partial slip."""
    coarse, fine = worn(31), worn(63)
    for q in ("w_max", "wear_volume"):
        change = fine[q] / coarse[q] - 1
        print(f"{q}: {coarse[q]:.5g} -> {fine[q]:.5g} ({change:+.2%})")
        assert abs(coarse[q] - fine[q]) / fine[q] < grid_budget(q, "rel")
    radius = [math.sqrt(s["stick_area"] / math.pi) for s in (coarse, fine)]
    cells = abs(radius[0] - radius[1]) / coarse["cell"]
    print(f"stick radius {radius[0]:.4f} -> {radius[1]:.4f} mm ({cells:.2f} cells)")
    assert fine["stick_area"] > 0
    assert cells < grid_budget("stick_area", "cells")

