"""The analytic solver's first fretting cycle (analytic/fretting_case.py, ``fretting_steps``) on
the bundled ``fretting_isotropic`` case: applicability, the fields it has closed forms
for, the loop and energy tables against analytic/fretting.py."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

import halfspace.wear as hw
from analytic import fretting as fr
from analytic import fretting_case
from analytic import hertz as hz
from analytic.fretting_case import fretting_reference
from analytic.solver import solve, supports
from cases.loader import load_case
from cases.model import Body, Friction
from cases.result import OPEN, SLIP, STICK


@pytest.fixture(scope="module")
def cases():
    return load_case("fretting_isotropic", quick=True)


@pytest.fixture(scope="module")
def runs(cases):
    return [solve(c) for c in cases]


def test_the_bundled_sweep_is_one_partial_and_one_gross_slip_amplitude(cases):
    ref = fretting_reference(cases[0])
    # δ* = μ(2-ν)δ_n / (2(1-ν)) for identical bodies at a held approach
    assert ref.delta_star == pytest.approx(0.3 * 1.7 * 0.008 / 1.4, rel=1e-12)
    ratios = [c.fretting.amplitude / ref.delta_star for c in cases]
    assert ratios == pytest.approx([0.5, 1.5], rel=1e-4)


def test_supports_says_why_not(cases):
    case = cases[0]
    assert supports(case) is None
    ortho = case.with_changes(friction=Friction(mu1=0.3, mu2=0.5))
    assert "orthotropic friction" in supports(ortho)
    soft = case.with_changes(b=Body(E=70000.0, nu=0.33, i1=1e-9, i2=1e-9))
    assert "K != 0" in supports(soft)
    jump = case.with_changes(fretting=replace(case.fretting, cycles=10, jump=5.0,
                                              output_cycles=[5, 10]))
    assert "jump" in supports(jump)
    later = case.with_changes(fretting=replace(case.fretting, cycles=3,
                                               output_cycles=[2, 3]))
    assert "first cycle is not an output" in supports(later)
    assert supports(case.with_changes(fretting=replace(case.fretting, cycles=3,
                                                       output_cycles=[1, 3]))) is None
    # the bundled orthotropic fretting case has no closed form
    assert "orthotropic" in supports(load_case("fretting_orthotropic", quick=True)[0])


def test_the_imposed_path_is_the_solvers(cases):
    for steps in (8, 20, 22):
        np.testing.assert_array_equal(fretting_case.imposed_cycle(1.0, steps),
                                      hw.cycle_path(1.0, steps))


@pytest.mark.parametrize("k", [0, 1])
def test_first_cycle_step(cases, runs, k):
    case, run = cases[k], runs[k]
    ref = fretting_reference(case)
    A, mu = case.fretting.amplitude, case.friction.mu1
    assert len(run.steps) == 1
    step = run.steps[0]
    s = step.scalars
    assert (step.number(0), s["cycle"]) == (1, 1.0)  # halfspace numbers cycle 1 as step 1
    h = hz.hertz_from_approach(case.load.approach, case.R, case.E_star)
    assert (s["P"], s["p_max"]) == pytest.approx((h.P, h.p0), rel=1e-12)
    # every surface field has a closed form here: finite everywhere
    for name in ("p_n", "p_x", "p_y", "wear_a", "wear_b", "gap"):
        assert np.isfinite(step.surface[name]).all(), name
    assert np.isfinite(step.planes["xz"].fields["vm"]).all()
    for key in ("P", "Qx", "p_max", "w_max", "wear_volume", "vm_max", "stick_area"):
        assert math.isfinite(s[key]), key
    # Q at the end of the cycle: the virgin F(A), on body a against the shift
    assert s["Qx"] == pytest.approx(-fr.load_amplitude(A, mu, ref.P, ref.delta_star))
    assert s["Qy"] == 0.0
    # wear of both bodies: equal coefficients share the gap's first-cycle wear equally
    X, Y = np.meshgrid(step.x, step.y, indexing="ij")
    i_w = 2e-9
    w = fr.cycle_wear(X, Y, A, ref.a, ref.p0, ref.delta_star, i_w, ref.lam)
    np.testing.assert_allclose(step.surface["wear_a"], 0.5 * w, rtol=1e-14)
    np.testing.assert_allclose(step.surface["wear_b"], 0.5 * w, rtol=1e-14)
    assert s["w_max"] >= w.max() and s["w_max"] < 1.05 * w.max()
    assert s["wear_volume"] == pytest.approx(
        i_w * fr.cycle_energy(A, mu, ref.P, ref.delta_star) / mu, rel=1e-12)
    # stick zone r < c = a√(1 - A/δ*), none in gross slip
    c = fr.stick_radius_at(A, ref.a, ref.delta_star)
    r = np.hypot(X, Y)
    state = step.surface["state"]
    assert (state[r < c] == STICK).all() and (state[(r > c) & (r < ref.a)] == SLIP).all()
    assert (state[r > ref.a] == OPEN).all()
    assert s["stick_area"] == pytest.approx(math.pi * c * c)


@pytest.mark.parametrize("k", [0, 1])
def test_loop_and_energy_tables(cases, runs, k):
    case, run = cases[k], runs[k]
    ref = fretting_reference(case)
    A, mu, n = case.fretting.amplitude, case.friction.mu1, case.fretting.steps_per_cycle
    loops, cycles = run.tables["loops"], run.tables["cycles"]
    np.testing.assert_array_equal(loops["displacement"], hw.cycle_path(A, n))
    assert (loops["cycle"] == 1).all()
    hist = np.concatenate([A * np.arange(0, n // 4 + 1) / (n // 4), hw.cycle_path(A, n)])
    Q = fr.md_path(hist, mu, ref.P, ref.delta_star)
    np.testing.assert_allclose(-loops["Qx"], Q[n // 4 + 1:], rtol=1e-14)
    np.testing.assert_array_equal(loops["Qy"], 0.0)
    # the closed form and the trapezoid on the same steps
    assert cycles["energy_exact"][0] == fr.cycle_energy(A, mu, ref.P, ref.delta_star)
    assert cycles["energy"][0] == pytest.approx(fr.loop_area(hist[n // 4:], Q[n // 4:]),
                                                rel=1e-14)
    rule = cycles["energy"][0] / cycles["energy_exact"][0] - 1
    assert rule == pytest.approx(-0.0628 if k == 0 else -0.0562, abs=5e-4)  # 8 steps
    assert cycles["gross_slip"][0] == float(k == 1)


def test_a_path_along_y_rotates_the_solution(cases, runs):
    case = cases[0]
    along_y = solve(case.with_changes(load=replace(case.load, slide_angle=90.0)))
    sx, sy = runs[0].steps[0], along_y.steps[0]
    assert sy.scalars["Qy"] == pytest.approx(sx.scalars["Qx"], rel=1e-12)
    assert sy.scalars["Qx"] == pytest.approx(0.0, abs=1e-9 * abs(sx.scalars["Qx"]))
    # the grid is square and symmetric: the fields are transposed
    np.testing.assert_allclose(sy.surface["wear_a"], sx.surface["wear_a"].T, rtol=1e-9,
                               atol=1e-12 * sx.surface["wear_a"].max())
    np.testing.assert_allclose(along_y.tables["loops"]["Qy"], runs[0].tables["loops"]["Qx"],
                               rtol=1e-12)
