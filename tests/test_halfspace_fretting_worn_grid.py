"""Worn fretting contacts on the half-space solver: where its grid resolves the slip zone
(the wear's floor of :mod:`reports.registry.resolution`), the wear and the stick zone
after 2000 cycles converge in space — the bundled β = 90° quick point (partial slip,
approach held, J = 500) and cases the suite has not seen.

The worn profile steps at the stick edge (the slip annulus wears, the stick disc does
not).  The half-space solver holds the step at a cell boundary on every grid, so the
wear it carries and the stick zone it leaves converge in space, while the pressure
maximum at the step grows with every refinement (docs/fem-notes.md, part 5).  This is
what the FEM is compared against at β = 90°; the FEM resolves the step only across an
element, and that is where the two solvers part.
"""

from __future__ import annotations

import dataclasses
import functools
import math

from hypothesis import assume, given, settings
from hypothesis import strategies as st

import halfspace
from cases.loader import load_case
from cases.result import StepResult
from reports.compare.point import step_resolution
from reports.registry.resolution import unresolved
from reports.registry.solvers import grid_budget

WEAR = ("w_max", "wear_volume")


@functools.cache
def worn(n: int, beta: float = 90.0, **keys: float) -> StepResult:
    """The last output (2000 cycles) of ``fretting_orthotropic`` (quick) at ``beta`` on
    an n² grid, with the dotted case ``keys`` changed."""
    case = load_case("fretting_orthotropic", quick=True,
                     overrides={"grid.nx": n, "grid.ny": n, **keys})[0]
    case = case.with_changes(friction=dataclasses.replace(case.friction, beta=beta))
    step = halfspace.solve(case).steps[-1]
    assert step.scalars["cycle"] == 2000
    return step


def radius(area: float) -> float:
    return math.sqrt(max(area, 0.0) / math.pi)


def why_unresolved(step: StepResult) -> str:
    """The comparisons' reason the wear of ``step`` is not a number on its grid ('' when
    it is): the slip zone a − c in cells against the wear's floor."""
    return unresolved("wear_volume", "rel", step_resolution(step, step, 0.0))


def assert_converged(coarse: StepResult, fine: StepResult) -> None:
    """Cells halved: w_max and the wear volume within the solver's budget for them, the
    stick zone's equivalent radius within its budget in the coarse grid's cells."""
    c, f = coarse.scalars, fine.scalars
    for q in WEAR:
        print(f"{q}: {c[q]:.5g} -> {f[q]:.5g} ({f[q] / c[q] - 1:+.2%})")
        assert abs(c[q] - f[q]) / f[q] < grid_budget(q, "rel")
    r = [radius(s["stick_area"]) for s in (c, f)]
    cells = abs(r[0] - r[1]) / (coarse.x[1] - coarse.x[0])
    print(f"stick radius {r[0]:.4f} -> {r[1]:.4f} mm ({cells:.2f} cells)")
    assert cells < grid_budget("stick_area", "cells")


def test_the_bundled_worn_stick_zone_and_wear_converge_in_space():
    """β = 90° of the quick sweep, 31² against 63²: resolved, in partial slip, converged."""
    coarse, fine = worn(31), worn(63)
    assert why_unresolved(coarse) == ""
    assert fine.scalars["stick_area"] > 0
    assert_converged(coarse, fine)


@settings(max_examples=4, deadline=None, derandomize=True)
@given(mu1=st.floats(0.15, 0.35), ratio=st.floats(1.5, 6.0), beta=st.floats(45.0, 90.0),
       amplitude=st.floats(2e-3, 5e-3), R=st.floats(25.0, 60.0))
def test_generated_worn_contacts_converge_where_resolved(mu1, ratio, beta, amplitude, R):
    """Any orthotropic friction ellipse, angle, amplitude and radius, worn for 2000 cycles
    and still in partial slip (the worn step in place): where the 31² grid resolves the
    slip zone for the wear, 63² confirms its wear and stick zone to within the budgets.
    A case in gross slip, or one the floor calls unresolved (not a claim of the solver's),
    is set aside."""
    keys = {"friction.mu1": mu1, "friction.mu2": mu1 * ratio,
            "fretting.amplitude": amplitude, "geometry.R": R}
    coarse = worn(31, beta, **keys)
    assume(coarse.scalars["stick_area"] > 0 and why_unresolved(coarse) == "")
    print(f"\nmu = ({mu1:.3f}, {mu1 * ratio:.3f}), beta = {beta:.1f}, amplitude "
          f"{amplitude:.4f} mm, R = {R:.1f} mm")
    assert_converged(coarse, worn(63, beta, **keys))
