"""Subsurface stress kernels (Appendix A, C) against Johnson's solutions and quadrature.

Reference physics: Johnson, Contact Mechanics (1985) §3.2, displacement fields of a
half-space z > 0 (z into the body) under a unit surface force at the origin
(Boussinesq, Eq. 3.19; Cerruti, Eq. 3.86), per unit G, with (x, y) = field - load:

- normal force into the body: ``u_x = (xz/rho³ - (1-2nu) x/(rho(rho+z))) / 4pi``,
  ``u_z = (z²/rho³ + 2(1-nu)/rho) / 4pi``;
- tangential force along +x: ``u_x = (1/rho + x²/rho³ + (1-2nu)(1/(rho+z) -
  x²/(rho(rho+z)²))) / 4pi``, ``u_y = (xy/rho³ - (1-2nu) xy/(rho(rho+z)²)) / 4pi``,
  ``u_z = (xz/rho³ + (1-2nu) x/(rho(rho+z))) / 4pi``.

At z = 0 these reduce to the surface formulas tested in test_halfspace_influence.py.  Their
stresses (Hooke's law on finite-difference strains) are the point-kernel reference;
equilibrium, traction-free surface and force resultants are checked independently.
"""

import math

import numpy as np
import pytest
from scipy import integrate

from cases.result import STRESS_COMPONENTS
from halfspace.stress_kernels import LOADS, cell_stress_coefficients, point_stresses

NU = 0.3
IDX = {"sxx": (0, 0), "syy": (1, 1), "szz": (2, 2), "sxy": (0, 1), "sxz": (0, 2),
       "syz": (1, 2)}


def johnson_displacement(x, y, z, nu, load):
    """Johnson's Boussinesq / Cerruti displacement field (G = 1), see module docstring."""
    if load == "y":
        ux, uy, uz = johnson_displacement(y, x, z, nu, "x")
        return uy, ux, uz
    c, m = 1.0 / (4.0 * math.pi), 1.0 - 2.0 * nu
    rho = np.sqrt(x * x + y * y + z * z)
    if load == "n":
        return (c * (x * z / rho**3 - m * x / (rho * (rho + z))),
                c * (y * z / rho**3 - m * y / (rho * (rho + z))),
                c * (z * z / rho**3 + 2.0 * (1.0 - nu) / rho))
    return (c * (1 / rho + x * x / rho**3 + m * (1 / (rho + z) - x * x / (rho * (rho + z) ** 2))),
            c * (x * y / rho**3 - m * x * y / (rho * (rho + z) ** 2)),
            c * (x * z / rho**3 + m * x / (rho * (rho + z))))


def gradient(f, p, h):
    """4th-order central differences: g[i][j] = ∂f_i/∂x_j at the points p (3, n)."""
    g = [[None] * 3 for _ in range(3)]
    for j in range(3):
        e = np.zeros((3, np.size(h)))
        e[j] = h
        fp1, fm1, fp2, fm2 = f(*(p + e)), f(*(p - e)), f(*(p + 2 * e)), f(*(p - 2 * e))
        for i in range(3):
            g[i][j] = (8 * (fp1[i] - fm1[i]) - (fp2[i] - fm2[i])) / (12 * h)
    return g


def johnson_stresses(x, y, z, nu, load):
    """Stresses from Johnson's displacements by Hooke's law (G = 1)."""
    p = np.array([x, y, z], float)
    h = 1e-3 * np.sqrt((p**2).sum(axis=0))
    g = gradient(lambda a, b, c: johnson_displacement(a, b, c, nu, load), p, h)
    lam = 2.0 * nu / (1.0 - 2.0 * nu)
    div = g[0][0] + g[1][1] + g[2][2]
    return {k: lam * div * (i == j) + g[i][j] + g[j][i] for k, (i, j) in IDX.items()}


rng = np.random.default_rng(7)
PTS = np.concatenate([
    rng.uniform([-2, -2, 0.05], [2, 2, 2], size=(30, 3)),
    [[0.0, 0.0, 1.0], [0.0, 0.7, 0.2], [-0.9, 0.0, 0.05], [1e-9, -1e-9, 0.4]],
]).T


@pytest.mark.parametrize("load", LOADS)
def test_point_stresses_are_johnsons(load):
    got = point_stresses(*PTS, NU, load)
    want = johnson_stresses(*PTS, NU, load)
    rho = np.sqrt((PTS**2).sum(axis=0))
    for c in STRESS_COMPONENTS:
        # FD error ~ (1e-3)^4 + 1e-16/1e-3 relative to the local scale 1/rho²
        np.testing.assert_allclose(got[c] * rho**2, want[c] * rho**2, rtol=0, atol=1e-8,
                                   err_msg=c)
    assert all(np.all(np.isfinite(v)) for v in got.values())


@pytest.mark.parametrize("load", LOADS)
def test_point_stresses_equilibrium_and_free_surface(load):
    # div sigma = 0 away from the load (finite differences of the kernel itself)
    h = 1e-3 * np.sqrt((PTS**2).sum(axis=0))

    def sig_rows(a, b, c):
        s = point_stresses(a, b, c, NU, load)
        return [[s[k] for k in ("sxx", "sxy", "sxz")], [s[k] for k in ("sxy", "syy", "syz")],
                [s[k] for k in ("sxz", "syz", "szz")]]

    for row in range(3):
        g = gradient(lambda a, b, c, r=row: sig_rows(a, b, c)[r], PTS, h)
        div = g[0][0] + g[1][1] + g[2][2]
        rho = np.sqrt((PTS**2).sum(axis=0))
        np.testing.assert_allclose(div * rho**3, 0.0, atol=1e-8)
    # traction-free surface away from the load
    xs, ys = rng.uniform(-2, 2, size=(2, 20))
    s = point_stresses(xs, ys, 0.0, NU, load)
    for c in ("szz", "sxz", "syz"):
        np.testing.assert_array_equal(s[c], 0.0)


@pytest.mark.parametrize(("load", "comp", "force"),
                         [("n", "szz", -1.0), ("n", "sxz", 0.0), ("x", "sxz", -1.0),
                          ("x", "szz", 0.0), ("x", "syz", 0.0), ("y", "syz", -1.0)])
def test_point_force_resultant_on_a_plane(load, comp, force):
    """The slab above z = c is in equilibrium: ∫∫ sigma_iz dA = -F_i (polar quadrature)."""
    c = 0.3

    def f(p):
        r, th = p[:, 0], p[:, 1]
        return r * point_stresses(r * np.cos(th), r * np.sin(th), c, NU, load)[comp]

    res = integrate.cubature(f, [0.0, 0.0], [np.inf, 2 * np.pi], rtol=1e-10, atol=1e-12)
    assert res.status == "converged"
    val = float(res.estimate)
    assert val == pytest.approx(force, abs=1e-8)


def test_trailing_edge_of_tangential_force_is_tensile():
    # erratum 9: sigma_xx(x < 0, 0, 0+) = +(1 + nu) Q / (pi x²) for Q along +x
    x = np.array([-0.5, -2.0, 0.5])
    s = point_stresses(x, 0.0, 0.0, NU, "x")
    np.testing.assert_allclose(s["sxx"], np.sign(-x) * (1 + NU) / (math.pi * x**2), rtol=1e-14)
    s = point_stresses(0.0, x, 0.0, NU, "y")
    np.testing.assert_allclose(s["syy"], np.sign(-x) * (1 + NU) / (math.pi * x**2), rtol=1e-14)
    # Boussinesq at the surface: radial tension (1-2nu)/(2 pi r²), hoop the opposite
    s = point_stresses(x, 0.0, 0.0, NU, "n")
    np.testing.assert_allclose(s["sxx"], (1 - 2 * NU) / (2 * math.pi * x**2), rtol=1e-14)
    np.testing.assert_allclose(s["syy"], -(1 - 2 * NU) / (2 * math.pi * x**2), rtol=1e-14)


def test_point_stresses_on_the_load_axis_are_finite():
    z = np.array([0.1, 1.0])
    s = point_stresses(0.0, 0.0, z, NU, "n")
    # Johnson (3.20) on the axis: (1 - z/rho)/r² -> 1/(2 z²), so
    # sigma_r = sigma_theta = (1 - 2nu)/(4 pi z²) and sigma_z = -3/(2 pi z²)
    np.testing.assert_allclose(s["sxx"], (1 - 2 * NU) / (4 * math.pi * z**2), rtol=1e-14)
    np.testing.assert_allclose(s["szz"], -3 / (2 * math.pi * z**2), rtol=1e-14)


# ---------------------------------------------------------------- cell coefficients

# (xo/dx, yo/dy, z/dx): shallow interior, above corners and edges, adjacent, deep, far
FIELD = [
    (0, 0, 0.05), (0.3, -0.2, 0.05), (0.45, 0.1, 0.05), (0.5, 0.5, 0.05), (0.5, -0.5, 0.3),
    (-0.5, 0.5, 1.0), (0.5, 0, 0.05), (0, -0.5, 0.2), (1, 0, 0.05), (0, 1, 0.1),
    (1, 1, 0.5), (-1.3, 0.7, 0.25), (0, 0, 0.5), (0.2, 0.1, 1.0), (2, -1, 0.4),
    (0, 0, 5.0), (1, 2, 10.0), (-3, 4, 3.0), (15, -10, 2.0), (-30, 5, 1.0),
]
CELLS = [(0.02, 0.02), (0.06, 0.02)]  # square, aspect ratio 3


def quad_cell(load, xo, yo, z, dx, dy, nu=NU):
    """∫∫ of the point kernel over the cell, all six components (vectorised cubature).

    (t, u) = field - load runs over [xo - dx/2, xo + dx/2] x [yo - dy/2, yo + dy/2];
    the region is split at the field point's projection t = u = 0 (the kernel's peak).
    """
    a = np.array([xo - dx / 2, yo - dy / 2])
    b = np.array([xo + dx / 2, yo + dy / 2])

    def f(tu):
        s = point_stresses(tu[:, 0], tu[:, 1], z, nu, load)
        return np.stack([s[c] for c in STRESS_COMPONENTS], axis=-1)

    inside = [np.zeros(2)] if np.all((a < 0) & (b > 0)) else None
    scale = min(1.0, dx * dy / (2 * math.pi * (z * z + xo * xo + yo * yo)))
    res = integrate.cubature(f, a, b, rtol=1e-11, atol=1e-13 * scale, points=inside)
    assert res.status == "converged"
    return dict(zip(STRESS_COMPONENTS, res.estimate, strict=True))


@pytest.mark.parametrize("load", LOADS)
def test_cell_coefficients_match_quadrature(load):
    """All six components of one load, 40 (cell, field) pairs.

    Quadrature is converged to ~1e-11; 1e-6 relative catches any wrong term.  A
    component that vanishes by symmetry is compared with an absolute floor of 1e-9 times
    the largest component at that field point.
    """
    for dx, dy in CELLS:
        for fx, fy, fz in FIELD:
            xo, yo, z = fx * dx, fy * dy, fz * dx
            want = quad_cell(load, xo, yo, z, dx, dy)
            got = cell_stress_coefficients(xo, yo, z, dx, dy, NU)[load]
            floor = 1e-9 * max(abs(v) for v in want.values())
            for c in STRESS_COMPONENTS:
                assert float(got[c]) == pytest.approx(want[c], rel=1e-6, abs=floor), (
                    load, c, (dx, dy), (fx, fy, fz))


def test_other_nu_and_vectorised():
    """nu enters as the body's own ratio; a (x, y, z) array call equals pointwise calls."""
    nu, dx, dy = 0.45, 0.06, 0.02
    pts = np.array([(0.3, -0.2, 0.05), (0.5, 0.5, 0.3), (2, -1, 0.4)]) * [dx, dy, dx]
    B = cell_stress_coefficients(pts[:, 0], pts[:, 1], pts[:, 2], dx, dy, nu)
    for k, (xo, yo, z) in enumerate(pts):
        for load in LOADS:
            want = quad_cell(load, xo, yo, z, dx, dy, nu)
            floor = 1e-9 * max(abs(v) for v in want.values())
            for c in STRESS_COMPONENTS:
                assert B[load][c][k] == pytest.approx(want[c], rel=1e-6, abs=floor)


def test_surface_limit_at_own_cell_centre():
    """z = 0 at the loaded cell's centre: the traction boundary values and symmetry.

    Trace of the Boussinesq kernel -(1 + nu) z/(pi rho³) integrates to -2(1 + nu) p as
    z -> 0+ under the load, so sigma_xx + sigma_yy = -(1 + 2 nu) p; on a square
    each is -(1 + 2 nu)/2 by symmetry.  Under the x traction everything except
    sigma_xz = -1 is odd about the centre.
    """
    for dx, dy in CELLS:
        B = cell_stress_coefficients(0.0, 0.0, 0.0, dx, dy, NU)
        n, x, y = B["n"], B["x"], B["y"]
        assert float(n["szz"]) == pytest.approx(-1.0, abs=1e-15)
        assert float(n["sxx"] + n["syy"]) == pytest.approx(-(1 + 2 * NU), rel=1e-13)
        if dx == dy:
            assert float(n["sxx"]) == pytest.approx(-(1 + 2 * NU) / 2, rel=1e-13)
        assert float(x["sxz"]) == pytest.approx(-1.0, abs=1e-15)
        assert float(y["syz"]) == pytest.approx(-1.0, abs=1e-15)
        for c in ("sxz", "syz", "sxy"):
            assert abs(float(n[c])) < 1e-15
        for c in ("sxx", "syy", "szz", "sxy", "syz"):
            assert abs(float(x[c])) < 1e-15, c


def test_surface_limit_is_the_limit_of_quadrature():
    """Own centre: quadrature at z = 1e-3 dx is within O(z/dx) of the z = 0 values,
    and the closed form is continuous at z -> 0+."""
    dx, dy = 0.06, 0.02
    B0 = cell_stress_coefficients(0.0, 0.0, 0.0, dx, dy, NU)
    Bs = cell_stress_coefficients(0.0, 0.0, 1e-9 * dx, dx, dy, NU)
    for load in LOADS:
        want = quad_cell(load, 0.0, 0.0, 1e-3 * dx, dx, dy)
        for c in STRESS_COMPONENTS:
            # stresses vary by O(z/min(dx, dy)) = 3e-3 near the surface
            assert float(B0[load][c]) == pytest.approx(want[c], abs=1e-2), (load, c)
            assert float(Bs[load][c]) == pytest.approx(float(B0[load][c]), abs=1e-7)


def test_surface_values_at_other_cell_centres_match_quadrature():
    """z = 0 at other cells' centres: the kernel is regular over the loaded cell there."""
    for dx, dy in CELLS:
        for fx, fy in [(1, 0), (-1, 0), (0, 1), (1, -1), (2, 3), (-5, 1), (20, -9)]:
            xo, yo = fx * dx, fy * dy
            B = cell_stress_coefficients(xo, yo, 0.0, dx, dy, NU)
            for load in LOADS:
                want = quad_cell(load, xo, yo, 0.0, dx, dy)
                floor = 1e-9 * max(abs(v) for v in want.values())
                for c in STRESS_COMPONENTS:
                    assert float(B[load][c]) == pytest.approx(want[c], rel=1e-6, abs=floor)
                assert float(B[load]["szz"]) == 0.0 == float(B[load]["sxz"])
    # the trailing neighbour of an x-traction is in tension, the leading one compressed
    B = cell_stress_coefficients(np.array([-0.02, 0.02]), 0.0, 0.0, 0.02, 0.02, NU)
    assert B["x"]["sxx"][0] > 0 > B["x"]["sxx"][1]


@pytest.mark.parametrize(("load", "comp"), [("n", "szz"), ("x", "sxz"), ("y", "syz")])
def test_cell_resultant_on_a_plane(load, comp):
    """Equilibrium: ∫∫ B dxo dyo over the plane z = c is -(cell area).

    Integrated over the square |xo|, |yo| <= L = 100 c; the part of the plane outside
    it carries the point force's share ``-1 - ∫∫_square T`` (at least 50 cells away the
    cell acts as a point force, up to a relative O((dx/L)²/24) ~ 1e-5 of that share,
    itself <= 0.014), so ``∫∫_square B = area ∫∫_square T`` to ~1e-7; the point
    kernel's full-plane resultant -1 is checked in test_point_force_resultant_on_a_plane.
    """
    dx, dy, z = 0.06, 0.02, 0.05
    L = 100 * z

    def cell(p):
        return cell_stress_coefficients(p[:, 0], p[:, 1], z, dx, dy, NU)[load][comp]

    def point(p):
        return point_stresses(p[:, 0], p[:, 1], z, NU, load)[comp]

    total = integrate.cubature(cell, [-L, -L], [L, L], rtol=1e-9, atol=1e-11 * dx * dy)
    share = integrate.cubature(point, [-L, -L], [L, L], rtol=1e-11, atol=1e-13,
                               points=[np.zeros(2)])
    assert total.status == share.status == "converged"
    assert -1.0 < share.estimate < -0.98  # the square carries most of the load
    assert total.estimate == pytest.approx(share.estimate * dx * dy, rel=1e-6)


def test_symmetry_of_cell_coefficients():
    """B^N_yy(xo, yo; dx, dy) = B^N_xx(yo, xo; dy, dx) (independent formulas), and the
    y-load is the x-load in swapped axes."""
    dx, dy = 0.06, 0.02
    f = np.array(FIELD)
    xo, yo, z = f[:, 0] * dx, f[:, 1] * dy, f[:, 2] * dx
    B = cell_stress_coefficients(xo, yo, z, dx, dy, NU)
    S = cell_stress_coefficients(yo, xo, z, dy, dx, NU)
    swap = {"sxx": "syy", "syy": "sxx", "szz": "szz", "sxy": "sxy", "sxz": "syz",
            "syz": "sxz"}
    for c in STRESS_COMPONENTS:
        scale = np.abs(B["n"]["szz"]).max()
        np.testing.assert_allclose(B["n"][c], S["n"][swap[c]], rtol=1e-11, atol=1e-14 * scale)
        np.testing.assert_allclose(B["y"][c], S["x"][swap[c]], rtol=1e-11, atol=1e-14 * scale)


def test_finite_everywhere_and_z0_edges_rejected():
    dx, dy = 0.06, 0.02
    k = np.arange(-6, 7) * 0.25
    xo, yo, z = np.meshgrid(k * dx, k * dy, np.array([1e-6, 0.05, 1.0]) * dx, indexing="ij")
    B = cell_stress_coefficients(xo, yo, z, dx, dy, NU)
    for load in LOADS:
        for c in STRESS_COMPONENTS:
            assert np.all(np.isfinite(B[load][c])), (load, c)
    centres = np.arange(-40, 41)
    B = cell_stress_coefficients(centres[:, None] * dx, centres[None, :] * dy, 0.0, dx, dy, NU)
    assert all(np.all(np.isfinite(B[ld][c])) for ld in LOADS for c in STRESS_COMPONENTS)
    with pytest.raises(ValueError, match="edge"):
        cell_stress_coefficients(0.5 * dx, 0.0, 0.0, dx, dy, NU)
    with pytest.raises(ValueError, match="z must be"):
        cell_stress_coefficients(0.0, 0.0, -1.0, dx, dy, NU)


@pytest.mark.parametrize(("kx", "ky"), [((-5, 7), (-3, 4)), ((2, 6), (-6, -1)),
                                        ((-4, 0), (0, 3)), ((-7, -7), (3, 3)),
                                        ((-6, -2), (-2, 5))])
@pytest.mark.parametrize("z", [0.0, 0.004, 0.05])
def test_symmetric_table_equals_the_full_table(kx, ky, z):
    """One quadrant mirrored by the parity of each coefficient (odd ones change sign)
    equals the table evaluated over the whole range, for ranges on either side of zero,
    straddling it, or a single offset; a wrong parity sign fails by O(1)."""
    from halfspace.stress_kernels import coefficient_table, parity, symmetric_table

    dx, dy, nu = 0.02, 0.03, 0.28
    full = coefficient_table(kx, ky, z, dx, dy, nu)
    sym = symmetric_table(kx, ky, z, dx, dy, nu)
    scale = max(np.abs(arr).max() for comps in full.values() for arr in comps.values())
    for load, comps in full.items():
        for c, arr in comps.items():
            assert sym[load][c].shape == arr.shape
            assert np.abs(sym[load][c] - arr).max() < 1e-12 * scale, (load, c)
    # the parities themselves: even/odd in xo and yo, checked on the closed form
    B = cell_stress_coefficients(np.array([0.7, -0.7, 0.7]) * dx * 3,
                                 np.array([0.4, 0.4, -0.4]) * dy * 3, 0.01, dx, dy, nu)
    odd_seen = 0
    for load in LOADS:
        for c in STRESS_COMPONENTS:
            px, py = parity(load, c)
            v = B[load][c]
            assert v[1] == pytest.approx(px * v[0], rel=1e-9, abs=1e-15), (load, c)
            assert v[2] == pytest.approx(py * v[0], rel=1e-9, abs=1e-15), (load, c)
            odd_seen += (px < 0) + (py < 0)
    assert odd_seen == 16  # n: 2 + 2, x and y: 4 + 2 of the (component, axis) pairs
