"""Surface influence kernels (Eq. 5, 41) against Johnson's one-body solutions and quadrature.

Reference physics, Johnson, Contact Mechanics (1985) §3.2, one half-space z > 0 (z into
the body), unit force at the surface origin, surface displacement at (x, y) = field -
load, s = sqrt(x² + y²):

- Boussinesq (normal force P into the body): ``u_z = (1-nu) P / (2 pi G s)``,
  ``u_r = -(1-2nu) P / (4 pi G s)`` (towards the load).
- Cerruti (tangential force Q along +x): ``u_x = Q/(2 pi G) ((1-nu)/s + nu x²/s³)``,
  ``u_y = Q/(2 pi G) nu x y / s³``, and, by Betti's reciprocity with the Boussinesq
  ``u_r``, ``u_z = +(1-2nu) Q x / (4 pi G s²)``.

Two bodies: a occupies z > 0 and carries +p; b occupies z < 0 and carries -p.  In b's own
frame (reflection R = diag(1, 1, -1), which maps b onto a half-space z > 0 and is a
symmetry of isotropic elasticity) its load is R(-p) and its displacement R u^(b), so
``u^(a) - u^(b) = (M_a + R M_b R) p`` with M the one-body matrix above.
"""

import math

import numpy as np
import pytest
from scipy import integrate

from cases.model import Body
from halfspace.influence import BLOCKS, point_kernel, surface_coefficients
from halfspace.materials import Materials

STEEL = Body(E=210000.0, nu=0.3)
ALU = Body(E=70000.0, nu=0.33)
PMMA = Body(E=3000.0, nu=0.4)
IDENTICAL = Materials.from_bodies(STEEL, STEEL)
DISSIMILAR = Materials.from_bodies(STEEL, PMMA)  # |K| / G ~ 0.1
IJ = {"x": 0, "y": 1, "z": 2}


def one_body_entry(i: int, j: int, x: float, y: float, body: Body) -> float:
    """Johnson's one-body surface displacement u_i due to a unit force F_j (scalar)."""
    G, nu = body.G, body.nu
    s = math.hypot(x, y)
    d = (x, y)
    if i == 2 and j == 2:
        return (1 - nu) / (2.0 * math.pi * G * s)  # Boussinesq u_z
    if j == 2:
        return -(1 - 2 * nu) / (4.0 * math.pi * G * s) * d[i] / s  # Boussinesq u_r
    if i == 2:
        # Betti: u_z at x due to Q_j at 0 equals u_j at 0 due to P at x, i.e. u_r(-x)
        return (1 - 2 * nu) / (4.0 * math.pi * G * s) * d[j] / s
    return ((1 - nu) / s * (i == j) + nu * d[i] * d[j] / s**3) / (2.0 * math.pi * G)  # Cerruti


def one_body(x: float, y: float, body: Body) -> np.ndarray:
    """The matrix M[i, j] of :func:`one_body_entry`."""
    return np.array([[one_body_entry(i, j, x, y, body) for j in range(3)] for i in range(3)])


def two_body(x: float, y: float, a: Body, b: Body) -> np.ndarray:
    """Relative displacement u^(a) - u^(b) per unit traction p on a (and -p on b)."""
    R = np.diag([1.0, 1.0, -1.0])
    return one_body(x, y, a) + R @ one_body(x, y, b) @ R


def two_body_entry(i: int, j: int, x: float, y: float, a: Body, b: Body) -> float:
    """Entry [i, j] of :func:`two_body` (R M R flips the entries with one z index)."""
    sign = -1.0 if (i == 2) != (j == 2) else 1.0
    return one_body_entry(i, j, x, y, a) + sign * one_body_entry(i, j, x, y, b)


# ------------------------------------------------------------------ point kernels

POINTS = [(0.3, 0.0), (0.0, -0.2), (0.1, 0.25), (-0.4, 0.07), (-0.05, -0.3), (1.7, -2.2)]


@pytest.mark.parametrize(("a", "b"), [(STEEL, STEEL), (STEEL, PMMA), (PMMA, ALU), (ALU, STEEL)])
def test_point_kernel_is_the_two_body_johnson_sum(a, b):
    mat = Materials.from_bodies(a, b)
    x, y = np.array(POINTS).T
    got = point_kernel(x, y, mat)
    for n, (px, py) in enumerate(POINTS):
        ref = two_body(px, py, a, b)
        for key in BLOCKS:
            want = ref[IJ[key[0]], IJ[key[1]]]
            scale = abs(ref).max()
            assert got[key][n] == pytest.approx(want, rel=1e-12, abs=1e-14 * scale), key


def test_coupling_sign_physically():
    # With a rigid lower body, u = u^(a): a compressive load on a pulls a's surface
    # towards the load (Boussinesq u_r < 0), so A_xz < 0 ahead of the load (xo > 0) and,
    # by reciprocity, A_zx > 0 there; K = (1 - 2 nu_a)/2 > 0 in this limit.
    a, b = Body(E=100.0, nu=0.0), Body(E=1e12, nu=0.0)  # b rigid: u = u^a
    mat = Materials.from_bodies(a, b)
    assert mat.K > 0
    k = point_kernel(np.array([0.5]), np.array([0.0]), mat)
    ref_ux = -(1 - 2 * a.nu) / (4 * math.pi * a.G * 0.5)  # Boussinesq u_r of body a
    assert k["xz"][0] == pytest.approx(ref_ux, rel=1e-9)
    assert k["xz"][0] < 0 < k["zx"][0]


def test_identical_bodies_are_twice_one_body_and_uncoupled():
    x, y = np.array(POINTS).T
    got = point_kernel(x, y, IDENTICAL)
    for n, (px, py) in enumerate(POINTS):
        m = one_body(px, py, STEEL)
        for key in ("xx", "yy", "zz", "xy", "yx"):
            assert got[key][n] == pytest.approx(2 * m[IJ[key[0]], IJ[key[1]]], rel=1e-12)
    for key in ("xz", "zx", "yz", "zy"):
        assert np.all(got[key] == 0.0)


def test_two_body_entry_is_the_matrix_sum():
    for px, py in POINTS:
        m = two_body(px, py, STEEL, PMMA)
        for i in range(3):
            for j in range(3):
                assert two_body_entry(i, j, px, py, STEEL, PMMA) == pytest.approx(m[i, j])


def test_point_kernel_reciprocity():
    # Betti for the pair: A_ij(d) = A_ji(-d)
    x, y = np.array(POINTS).T
    fwd, back = point_kernel(x, y, DISSIMILAR), point_kernel(-x, -y, DISSIMILAR)
    for key in BLOCKS:
        np.testing.assert_allclose(fwd[key], back[key[::-1]], rtol=1e-14, atol=0)


# ------------------------------------------------------------------ quadrature

# (field - cell centre) in units of (dx, dy): self, adjacent, on an edge, above a
# corner, near, far.
OFFSETS = [
    (0, 0), (1, 0), (0, 1), (-1, 0), (0, -1), (1, 1), (-1, 1), (0.5, 0.5), (-0.5, -0.5),
    (0.5, 0), (0, -0.5), (0.5, 0.2), (-0.3, 0.5), (0.2, 0.1), (2.3, -1.7), (3, 0),
    (-4, 5), (12, -7), (40, 25), (-60, 3),
]
CELLS = [(0.02, 0.02), (0.06, 0.02)]  # square, aspect ratio dx/dy = 3


def cell_quad(f, t0: float, t1: float, u0: float, u1: float, eps: float) -> float:
    """∫∫ f(t, u) over [t0, t1] x [u0, u1]; split at the singular point t = u = 0.

    Sub-rectangles with the singular point at a corner are integrated in polar
    coordinates about it (f r is bounded there), the rest with plain dblquad.
    """
    ts = [t0, 0.0, t1] if t0 < 0.0 < t1 else [t0, t1]
    us = [u0, 0.0, u1] if u0 < 0.0 < u1 else [u0, u1]
    total = 0.0
    for ta, tb in zip(ts[:-1], ts[1:], strict=True):
        for ua, ub in zip(us[:-1], us[1:], strict=True):
            if 0.0 in (ta, tb) and 0.0 in (ua, ub):
                total += polar_quad(f, ta + tb, ua + ub, eps)
            else:
                total += integrate.dblquad(
                    lambda u, t: f(t, u), ta, tb, ua, ub, epsabs=eps, epsrel=1e-11
                )[0]
    return total


def polar_quad(f, A: float, B: float, eps: float) -> float:
    """∫∫ f over the rectangle with corners (0, 0) and (A, B), in polar coordinates."""
    sa, sb, A, B = math.copysign(1.0, A), math.copysign(1.0, B), abs(A), abs(B)
    theta_c = math.atan2(B, A)

    def g(r, th):
        return f(sa * r * math.cos(th), sb * r * math.sin(th)) * r

    lo = integrate.dblquad(g, 0.0, theta_c, 0.0, lambda th: A / math.cos(th),
                           epsabs=eps, epsrel=1e-11)[0]
    hi = integrate.dblquad(g, theta_c, 0.5 * math.pi, 0.0, lambda th: B / math.sin(th),
                           epsabs=eps, epsrel=1e-11)[0]
    return lo + hi


def quad_coefficient(key: str, xo: float, yo: float, dx: float, dy: float, mat: Materials):
    """The cell coefficient by quadrature of the Johnson two-body point kernel."""
    i, j = IJ[key[0]], IJ[key[1]]

    def f(t, u):
        return two_body_entry(i, j, t, u, mat.a, mat.b)

    eps = 1e-13 * max(dx, dy) / mat.G
    return cell_quad(f, xo - dx / 2, xo + dx / 2, yo - dy / 2, yo + dy / 2, eps)


@pytest.mark.parametrize("key", BLOCKS)
def test_cell_coefficients_match_quadrature(key):
    """Every block vs quadrature, 40 (cell, field) pairs, dissimilar pair (K != 0).

    Quadrature is run to ~1e-11 relative, so 1e-6 relative is a safe test bound that
    still catches any wrong term (each term contributes O(1) relative).  Values that
    vanish by symmetry (e.g. xy on the axes) are compared with an absolute floor of
    1e-9 times the largest |value| of the block.
    """
    xs, ys, dxs, dys, want = [], [], [], [], []
    for dx, dy in CELLS:
        for ox, oy in OFFSETS:
            xs.append(ox * dx), ys.append(oy * dy), dxs.append(dx), dys.append(dy)
            want.append(quad_coefficient(key, ox * dx, oy * dy, dx, dy, DISSIMILAR))
    want = np.array(want)
    got = np.array([
        surface_coefficients(np.array(x), np.array(y), dx, dy, DISSIMILAR)[key]
        for x, y, dx, dy in zip(xs, ys, dxs, dys, strict=True)
    ])
    floor = 1e-9 * np.abs(want).max()
    np.testing.assert_allclose(got, want, rtol=1e-6, atol=floor)
    assert np.all(np.isfinite(got))


def test_vectorised_and_broadcast():
    dx, dy = 0.06, 0.02
    ox, oy = np.array(OFFSETS).T
    xo, yo = ox * dx, oy * dy
    grid = surface_coefficients(xo[:, None], yo[None, :], dx, dy, DISSIMILAR)
    for key in BLOCKS:
        assert grid[key].shape == (len(xo), len(yo))
        scalar = [surface_coefficients(xo[3], yo[k], dx, dy, DISSIMILAR)[key]
                  for k in range(len(yo))]
        np.testing.assert_array_equal(grid[key][3], np.array(scalar))


def test_uncoupled_blocks_vanish_exactly_for_identical_bodies():
    dx, dy = 0.06, 0.02
    ox, oy = np.array(OFFSETS).T
    c = surface_coefficients(ox * dx, oy * dy, dx, dy, IDENTICAL)
    for key in ("xz", "zx", "yz", "zy"):
        assert np.all(c[key] == 0.0), key
    assert np.all(c["zz"] > 0)


def test_symmetries_of_cell_coefficients():
    """Reciprocity C_ij(d) = C_ji(-d) and the x <-> y swap for a cell rotated by 90°."""
    dx, dy = 0.06, 0.02
    ox, oy = np.array(OFFSETS).T
    xo, yo = ox * dx, oy * dy
    fwd = surface_coefficients(xo, yo, dx, dy, DISSIMILAR)
    back = surface_coefficients(-xo, -yo, dx, dy, DISSIMILAR)
    swap = surface_coefficients(yo, xo, dy, dx, DISSIMILAR)
    for key in BLOCKS:
        np.testing.assert_allclose(fwd[key], back[key[::-1]], rtol=1e-12, atol=0)
        sk = key.translate(str.maketrans("xy", "yx"))
        # atol: round-off of the corner sums, ~1e-16 of their terms
        np.testing.assert_allclose(fwd[key], swap[sk], rtol=1e-12,
                                   atol=1e-13 * np.abs(fwd[key]).max())


def test_far_field_tends_to_point_kernel_times_area():
    dx, dy = 0.02, 0.06
    xo, yo = np.array([3.0, -2.0, 0.0]), np.array([4.0, 1.0, -5.0])
    c = surface_coefficients(xo, yo, dx, dy, DISSIMILAR)
    p = point_kernel(xo, yo, DISSIMILAR)
    for key in BLOCKS:
        # error O((cell / distance)^2) ~ 1e-4
        np.testing.assert_allclose(c[key], p[key] * dx * dy, rtol=1e-3,
                                   atol=1e-3 * np.abs(p["zz"] * dx * dy).max())


def test_self_influence_closed_form():
    # square cell of side 2h centred on the field point: ∫∫ 1/s = 8 h asinh(1)
    h = 0.01
    c = surface_coefficients(0.0, 0.0, 2 * h, 2 * h, IDENTICAL)
    G, nu = IDENTICAL.G, IDENTICAL.nu
    assert float(c["zz"]) == pytest.approx((1 - nu) * 8 * h * math.asinh(1) / (math.pi * G),
                                          rel=1e-14)
    # ∫∫ x²/s³ = ∫∫ 1/s / 2 by symmetry
    assert float(c["xx"]) == pytest.approx(
        (1 - nu / 2) * 8 * h * math.asinh(1) / (math.pi * G), rel=1e-14)


def test_continuous_across_cell_edges_and_corners():
    """Field points a hair off an edge or corner give the edge/corner value (no blow-up)."""
    dx, dy = 0.06, 0.02
    for ox, oy in [(0.5, 0.0), (0.5, 0.5), (-0.5, 0.3), (1.5, -0.5)]:
        exact = surface_coefficients(ox * dx, oy * dy, dx, dy, DISSIMILAR)
        for eps in (1e-300, 1e-17, -1e-15, 1e-12):
            near = surface_coefficients(ox * dx + eps, oy * dy - eps, dx, dy, DISSIMILAR)
            for key in BLOCKS:
                scale = abs(float(exact["zz"]))
                assert np.isfinite(near[key])
                # ∂C/∂xo has a log singularity at the edge: a few terms of size
                # ln(dx/|eps|)/(pi G) each, so |ΔC| <~ 4 |eps| (1 + ln(dx/|eps|)) / (pi G)
                slope = 4 * (1 + math.log(dx / abs(eps))) / (math.pi * DISSIMILAR.G)
                bound = 1e-13 * scale + slope * abs(eps)
                assert abs(near[key] - exact[key]) <= bound, (ox, oy, eps, key)
