"""Fretting with the transverse motion free (``fretting.transverse = "free"``): the rigid
shift across the imposed motion is found in every step so that the resultant across it
vanishes (mixed control, :func:`halfspace.tangential_load.shift_for_resultant` with a
basis).  Checked against the exact facts it must meet: Qy = 0, the friction ellipse's
capacity along the motion, and the symmetry that makes it the held reading at β = 0 and
90°."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from cases.loader import CASES_DIR, load_case
from halfspace import solve
from halfspace.friction import mu_norm

ONE_CYCLE = {"fretting.cycles": 1000, "fretting.jump": 500.0,
             "fretting.output_cycles": [1000]}
HELD_LOAD = str(CASES_DIR / "examples" / "fretting_orthotropic_load.toml")
HELD_LOAD_FREE = str(CASES_DIR / "examples" / "fretting_orthotropic_load_free.toml")


def _run(beta: float, transverse: str, name: str = "fretting_orthotropic"):
    case = load_case(name, quick=True, overrides={
        **ONE_CYCLE, "fretting.transverse": transverse})[0]
    case = case.with_changes(friction=replace(case.friction, beta=beta))
    return case, solve(case)


@pytest.mark.parametrize("beta", [0.0, 90.0])
def test_free_is_held_where_the_axes_lie_along_the_motion(beta):
    """At β = 0 and 90° the problem is symmetric in y -> -y: the held reading carries no
    Qy, so leaving the motion free changes nothing (to the solver's tolerance)."""
    _, held = _run(beta, "held")
    _, free = _run(beta, "free")
    a, b = held.steps[-1], free.steps[-1]
    assert abs(a.scalars["Qy"]) <= 1e-9 * a.scalars["P"]
    assert abs(b.scalars["shift_y"]) <= 1e-9 * b.scalars["shift_x"]
    for key in ("p_n", "p_x", "wear_a", "wear_b"):
        scale = np.abs(a.surface[key]).max()
        assert np.abs(a.surface[key] - b.surface[key]).max() <= 1e-6 * scale, key
    assert b.scalars["stick_area"] == a.scalars["stick_area"]


@pytest.mark.parametrize(("beta", "name"), [(60.0, "fretting_orthotropic"),
                                            (30.0, HELD_LOAD)])
def test_oblique_free_motion_carries_no_transverse_load(beta, name):
    """At an oblique β the held reading carries a large Qy, the free one none at any
    step; in gross slip the free reading's Qx is at most what the friction ellipse
    carries along x, P / ||e_x||_mu, which the held reading's exceeds (its traction is
    oblique)."""
    case, free = _run(beta, "free", name)
    _, held = _run(beta, "held", name)
    for run in (free, held):
        assert (np.asarray(run.tables["cycles"]["min_stick_area"]) == 0).all()  # gross
    P = free.steps[-1].scalars["P"]
    assert np.abs(np.asarray(free.tables["loops"]["Qy"])).max() <= 1e-6 * P
    assert np.abs(np.asarray(held.tables["loops"]["Qy"])).max() > 0.05 * P
    along_x = float(mu_norm(np.array(1.0), np.array(0.0), case.friction))
    assert abs(free.steps[-1].scalars["Qx"]) <= P / along_x * (1 + 1e-6)
    held_last = held.steps[-1].scalars
    assert abs(held_last["Qx"]) > held_last["P"] / along_x
    assert free.steps[-1].scalars["shift_y"] != 0.0


def test_the_fem_declines_only_the_oblique_free_reading():
    """The FEM runs the free reading where it is the held one (the half block, β = 0 and
    90°) and declines an oblique one with the key named (docs/fem-notes.md, part 5)."""
    import fem_reference

    case = load_case("fretting_orthotropic", quick=True,
                     overrides={"fretting.transverse": "free"})[0]
    for beta, declined in ((0.0, False), (90.0, False), (60.0, True)):
        why = fem_reference.supports(case.with_changes(
            friction=replace(case.friction, beta=beta)))
        assert (why is not None) == declined and (not declined or "transverse" in why)


@pytest.mark.parametrize("approach", [1e-12, 1e-6])
def test_a_nearly_unloaded_contact_slides_with_no_transverse_load(approach):
    """A contact worn almost away (one cell, P of nN to mN) in gross slip: the search
    across the motion must still reach Qy = 0 (the shift it needs is set by the slip's
    direction, on the scale of the motion, not by the contact's tiny gross-slip shift),
    and the one slipping cell carries exactly P / ||e_x||_mu along x."""
    from halfspace.problem import contact_solver, profile

    case = load_case("fretting_orthotropic", quick=True)[0]
    case = case.with_changes(friction=replace(case.friction, beta=45.0))
    solver, h = contact_solver(case), profile(case)
    start = solver.solve(h, approach=approach)
    sol = solver.solve(h, approach=approach, shift=(1e-3, 0.0), free=(0.0, 1.0),
                       prev=start.state)
    along_x = float(mu_norm(np.array(1.0), np.array(0.0), case.friction))
    assert abs(sol.Qy) <= 1e-6 * sol.P
    assert sol.Qx == pytest.approx(-sol.P / along_x, rel=1e-6)


@settings(max_examples=8, deadline=None, derandomize=True)
@given(mu1=st.floats(0.05, 0.6), ratio=st.floats(1.0, 6.0), beta=st.floats(0.0, 90.0),
       amplitude=st.floats(5e-4, 6e-3))
def test_free_motion_under_a_held_load_on_generated_cases(mu1, ratio, beta, amplitude):
    """Any friction ellipse, angle and amplitude, the load held (P fixed, so the
    ellipse's capacity along x is fixed): no transverse load at any step, and the load
    along x never above P / ||e_x||_mu."""
    case = load_case(HELD_LOAD_FREE, quick=True, overrides={
        **ONE_CYCLE, "fretting.amplitude": amplitude})[0]
    case = case.with_changes(friction=replace(case.friction, mu1=mu1,
                                              mu2=min(mu1 * ratio, 1.0), beta=beta))
    run = solve(case)
    P = case.load.P
    loops = run.tables["loops"]
    along_x = float(mu_norm(np.array(1.0), np.array(0.0), case.friction))
    assert np.abs(np.asarray(loops["Qy"])).max() <= 1e-6 * P
    assert np.abs(np.asarray(loops["Qx"])).max() <= P / along_x * (1 + 1e-6)
