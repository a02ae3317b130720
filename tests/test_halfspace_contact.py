"""Contact steps of the half-space solver against Hertz, Cattaneo-Mindlin and Eq. 13/38."""

import numpy as np
import pytest
from vv_testing import assert_converges, hertz_solution

from cases import load_case
from cases.model import Friction
from halfspace.contact import SLIP, STICK, ContactAtEdge, ContactSolver
from halfspace.friction import mu_norm
from halfspace.materials import Materials


def hertz_setup(n=81, **over):
    case = load_case("hertz", overrides={"grid.nx": n, "grid.ny": n, **over})[0]
    X, Y = np.meshgrid(case.grid.x, case.grid.y, indexing="ij")
    h = (X**2 + Y**2) / (2 * case.R)
    return case, h, *case.hertz_scales


def solver_for(case, friction=None, method="cg", tol=1e-10):
    return ContactSolver(case.grid, Materials.from_bodies(case.a, case.b),
                         friction or case.friction, method=method, tol=tol)


def test_hertz_81():
    """Acceptance: force = P to 1e-8, p_max within 1% of p0, radius within one cell."""
    case, h, a0, p0 = hertz_setup()
    sol = solver_for(case).solve(h, P=case.load.P)
    dA = case.grid.dx * case.grid.dy
    assert abs(sol.state.p_n.sum() * dA - case.load.P) < 1e-8 * case.load.P
    assert abs(sol.state.p_n.max() / p0 - 1) < 0.01
    radius = np.sqrt(np.count_nonzero(sol.state.p_n > 0) * dA / np.pi)
    assert abs(radius - a0) < case.grid.dx
    # the approach of the half-space is Hertz's delta0 = a0^2 / R (discretisation ~0.1%)
    assert abs(sol.state.approach / hertz_solution(case).delta - 1) < 0.005
    assert sol.residual_n < 1e-10


def test_displacement_control_reproduces_load_control():
    """Given the approach found under load control, displacement control returns P."""
    case, h, _, _ = hertz_setup(41)
    s = solver_for(case)
    by_load = s.solve(h, P=case.load.P)
    by_disp = s.solve(h, approach=by_load.state.approach)
    assert abs(by_disp.P / case.load.P - 1) < 1e-8
    assert np.abs(by_disp.state.p_n - by_load.state.p_n).max() < 1e-7 * by_load.state.p_n.max()


def test_uzawa_equals_cg_normal():
    case, h, _, _ = hertz_setup(41)
    a = solver_for(case, method="cg").solve(h, P=case.load.P)
    b = solver_for(case, method="uzawa").solve(h, P=case.load.P)
    assert np.abs(a.state.p_n - b.state.p_n).max() < 1e-7 * a.state.p_n.max()
    assert abs(a.state.approach - b.state.approach) < 1e-7 * a.state.approach


def mindlin_traction(r, a, c, mu, p0):
    """Cattaneo-Mindlin q(r) (Johnson 1985 eq. 7.33/7.37), traction magnitude."""
    q = mu * p0 * np.sqrt(np.clip(1 - (r / a) ** 2, 0, None))
    return q - np.where(r < c, c / a * mu * p0 * np.sqrt(np.clip(1 - (r / c) ** 2, 0, None)), 0)


@pytest.mark.parametrize("ratio", [0.25, 0.5, 0.75])
def test_cattaneo_mindlin(ratio):
    """Acceptance: stick radius within 1.5 cells, traction within 3% relative L2."""
    # the bundled case's grid: 0.4 mm square, 81^2 (see cases/cattaneo_mindlin.toml)
    case, h, a0, p0 = hertz_setup(81, **{"friction.mu": 0.3, "grid.Lx": 0.4, "grid.Ly": 0.4})
    mu, P = 0.3, case.load.P
    sol = solver_for(case, tol=1e-9).solve(h, P=P, Q=(ratio * mu * P, 0.0))
    dA = case.grid.dx * case.grid.dy
    assert abs(sol.Qx - ratio * mu * P) < 1e-8 * mu * P
    assert abs(sol.Qy) < 1e-10 * mu * P
    c = a0 * (1 - ratio) ** (1 / 3)
    stick_r = np.sqrt(np.count_nonzero(sol.status == STICK) * dA / np.pi)
    assert abs(stick_r - c) < 1.5 * case.grid.dx, (stick_r, c)
    X, Y = np.meshgrid(case.grid.x, case.grid.y, indexing="ij")
    q_ref = mindlin_traction(np.hypot(X, Y), a0, c, mu, p0)
    # traction on body a resists the shift: its resultant is the applied +Q here
    inside = sol.state.p_n > 0
    err = np.linalg.norm((sol.state.p_x - q_ref)[inside]) / np.linalg.norm(q_ref[inside])
    assert err < 0.03, err


def test_uzawa_equals_cg_tangential():
    case, h, _, _ = hertz_setup(41, **{"friction.mu": 0.3})
    Q = (0.5 * 0.3 * case.load.P, 0.0)
    a = solver_for(case, method="cg", tol=1e-9).solve(h, P=case.load.P, Q=Q)
    b = solver_for(case, method="uzawa", tol=1e-9).solve(h, P=case.load.P, Q=Q)
    scale = 0.3 * a.state.p_n.max()
    assert np.abs(a.state.p_x - b.state.p_x).max() < 1e-5 * scale
    assert np.array_equal(a.status, b.status)


ORTHO = Friction(mu1=0.25, mu2=0.5, beta=45.0)


def sliding(case, h, friction, angle_deg, method="cg"):
    d = np.array([np.cos(np.radians(angle_deg)), np.sin(np.radians(angle_deg))])
    return solver_for(case, friction, method=method).solve(h, P=case.load.P, shift=1e3 * d)


def test_orthotropic_full_sliding_eq38():
    """Acceptance: every slipping cell carries the traction of Eq. 13/38 for slip along
    +x and lies on the friction ellipse to 1e-6."""
    case, h, _, _ = hertz_setup(81)
    sol = sliding(case, h, ORTHO, 0.0)
    p_n, p_x, p_y = sol.state.p_n, sol.state.p_x, sol.state.p_y
    contact = p_n > 0
    assert np.all(sol.status[contact] == SLIP)
    # Eq. 38 for d = e_x, beta = 45: d_e = (cos45, -sin45), ||d||* = sqrt(mu1^2 + mu2^2)/sqrt2
    mu1, mu2 = 0.25, 0.5
    dual = np.sqrt((mu1**2 + mu2**2) / 2)
    ex = -(mu1**2 + mu2**2) / 2 / dual
    ey = -(mu1**2 - mu2**2) / 2 / dual
    assert np.abs(p_x - ex * p_n)[contact].max() < 1e-6 * p_n.max()
    assert np.abs(p_y - ey * p_n)[contact].max() < 1e-6 * p_n.max()
    assert ey > 0  # the traction has a component across the slip
    on_ellipse = mu_norm(p_x, p_y, ORTHO)[contact] / p_n[contact]
    assert np.abs(on_ellipse - 1).max() < 1e-6


def test_rotating_axes_and_sliding_rotates_solution():
    """(beta, slide direction) -> (beta + 90, slide direction + 90) rotates the fields."""
    case, h, _, _ = hertz_setup(41)
    a = sliding(case, h, ORTHO, 0.0)
    b = sliding(case, h, Friction(0.25, 0.5, 135.0), 90.0)
    rot = np.rot90  # field at (x, y) -> (-y, x) on the square, symmetric grid
    scale = a.state.p_n.max()
    assert np.abs(b.state.p_n - rot(a.state.p_n)).max() < 1e-9 * scale
    assert np.abs(b.state.p_x - rot(-a.state.p_y)).max() < 1e-7 * scale
    assert np.abs(b.state.p_y - rot(a.state.p_x)).max() < 1e-7 * scale


def test_contact_reaching_the_edge_fails_loudly():
    case, h, _, _ = hertz_setup(21, **{"grid.Lx": 0.3, "grid.Ly": 0.3})
    with pytest.raises(ContactAtEdge, match="edge"):
        solver_for(case).solve(h, P=case.load.P)


def test_refinement_order_of_pressure():
    """p_max error against Hertz decreases over three grids at an order > 1 per doubling
    of the cell count (21, 41, 81 cells: odd counts keep a cell on the axis).  The order
    is per nominal halving of h (relative h 1, 1/2, 1/4), as the bound was set: the true
    cell-size ratios 41/21 and 81/41 would give orders 3.6 % and 1.8 % higher."""
    errs = []
    for n in (21, 41, 81):
        case, h, _, p0 = hertz_setup(n)
        errs.append(abs(solver_for(case).solve(h, P=case.load.P).state.p_n.max() / p0 - 1))
    print(assert_converges((1.0, 0.5, 0.25), errs, min_order=1.0, what="|p_max/p0 - 1|"))


def test_worn_through_contact_under_displacement_control_carries_no_load():
    """Wear down to the held approach leaves the bodies touching without load: the step
    returns zero pressure with zero residual (found in the 1e5-cycle fretting run, where
    round-off penetration used to leave a residual of 1 behind)."""
    case, h, _, _ = hertz_setup(41)
    approach = 0.002
    worn = h + np.maximum(approach - h, 0.0)
    sol = solver_for(case).solve(worn, approach=approach)
    assert sol.P == 0.0 and sol.residual_n == 0.0
