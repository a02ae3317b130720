"""Boussinesq and Cerruti point-force stresses (Johnson 1985 §3.2).

Each kernel is checked as an elastic field independently of the textbook formulas:
equilibrium div σ = 0 and Beltrami–Michell compatibility by finite differences, a
traction-free surface away from the load, and the resultant force on a plane below it.
"""

import numpy as np
import pytest

from analytic.pointforce import (
    boussinesq,
    cerruti,
    cerruti_y,
    combined,
    surface_limit_coefficients,
)

NU = 0.3
KERNELS = (boussinesq, cerruti, cerruti_y)
POINTS = [np.array([0.3, -0.2, 0.5]), np.array([-0.7, 0.4, 0.15]), np.array([0.05, 0.9, 1.3])]


def tensor(fn, p, nu=NU):
    s = fn(p[0], p[1], p[2], nu)
    return np.array([[s[0], s[3], s[4]], [s[3], s[1], s[5]], [s[4], s[5], s[2]]], float)


def divergence(fn, p, h):
    div = np.zeros(3)
    for j in range(3):
        e = np.zeros(3)
        e[j] = h
        div += (tensor(fn, p + e) - tensor(fn, p - e))[:, j] / (2 * h)
    return div


def beltrami_michell(fn, p, h, nu=NU):
    """(1+ν) ∇²σ_ij + ∂_i∂_j σ_kk by central differences."""
    lap = np.zeros((3, 3))
    hess = np.zeros((3, 3))

    def tr(q):
        return np.trace(tensor(fn, q))

    for i in range(3):
        ei = np.zeros(3)
        ei[i] = h
        lap += (tensor(fn, p + ei) - 2 * tensor(fn, p) + tensor(fn, p - ei)) / h**2
        for j in range(3):
            ej = np.zeros(3)
            ej[j] = h
            hess[i, j] = (tr(p + ei + ej) - tr(p + ei - ej) - tr(p - ei + ej)
                          + tr(p - ei - ej)) / (4 * h * h)
    return (1 + nu) * lap + hess


@pytest.mark.parametrize("fn", KERNELS)
@pytest.mark.parametrize("p", POINTS)
def test_equilibrium(fn, p):
    # central differences: error O(h²) ~ 1e-8 of |∇σ| ~ 1 at h = 1e-4
    scale = np.abs(tensor(fn, p)).max() / np.linalg.norm(p)
    assert np.abs(divergence(fn, p, 1e-4)).max() < 1e-6 * scale


@pytest.mark.parametrize("fn", KERNELS)
@pytest.mark.parametrize("p", POINTS)
def test_compatibility(fn, p):
    # Richardson extrapolation of the O(h²) difference error; a wrong ν (0.25) leaves a
    # residual of ~0.4 |σ|/|x|², 1e4 times the tolerance.
    r1, r2 = beltrami_michell(fn, p, 2e-3), beltrami_michell(fn, p, 1e-3)
    resid = np.abs((4 * r2 - r1) / 3).max()
    scale = np.abs(tensor(fn, p)).max() / np.dot(p, p)
    assert resid < 1e-5 * scale
    wrong = np.abs(beltrami_michell(fn, p, 1e-3, nu=0.25)).max()
    assert wrong > 1e-2 * scale


@pytest.mark.parametrize("fn", KERNELS)
def test_surface_is_traction_free_off_the_load(fn):
    x, y = np.array([0.4, -0.3, 1.2]), np.array([0.3, 0.8, -0.1])
    s = fn(x, y, np.zeros(3), NU)
    for comp in (s[2], s[4], s[5]):  # szz, sxz, syz
        assert np.all(comp == 0.0)


def _plane_resultant(fn, z):
    """∫∫ (σ_zz, σ_xz, σ_yz) dA over the plane at depth z (trapezoid in φ and in ln r)."""
    t = np.linspace(0, 2 * np.pi, 33)[:-1]
    r = np.geomspace(1e-6 * z, 1e5 * z, 4001)
    R, T = np.meshgrid(r, t, indexing="ij")
    s = fn(R * np.cos(T), R * np.sin(T), z, NU)
    return [np.trapezoid((c * R * R).mean(axis=1) * 2 * np.pi, np.log(r))
            for c in (s[2], s[4], s[5])]


@pytest.mark.parametrize("fn,expected", [(boussinesq, (-1, 0, 0)), (cerruti, (0, -1, 0)),
                                         (cerruti_y, (0, 0, -1))])
def test_resultant_on_a_plane_balances_the_force(fn, expected):
    # the slab above depth z is in equilibrium: the traction σ·(-e_z) on its lower face
    # balances the unit force; the tail beyond 1e5 z is < 1e-5 of the resultant
    got = _plane_resultant(fn, 0.3)
    np.testing.assert_allclose(got, expected, atol=2e-5)


def test_cerruti_tension_behind_the_force():
    # erratum 9: σ_xx(x<0, 0, 0) = +(1+ν) Q/(π x²) behind a force Q in +x, compressive ahead
    x = np.array([-0.5, -2.0, 0.5])
    sxx = cerruti(x, 0 * x, 0 * x, NU)[0]
    np.testing.assert_allclose(sxx, np.sign(-x) * (1 + NU) / (np.pi * x**2), rtol=1e-14)


def test_boussinesq_surface_radial_stress():
    # Boussinesq at z = 0: σ_r = -σ_θ = (1-2ν)/(2π r²)
    r = np.array([0.3, 1.0, 3.0])
    s = boussinesq(r, 0 * r, 0 * r, NU)
    np.testing.assert_allclose(s[0], (1 - 2 * NU) / (2 * np.pi * r**2), rtol=1e-14)
    np.testing.assert_allclose(s[1], -(1 - 2 * NU) / (2 * np.pi * r**2), rtol=1e-14)


def test_fused_kernel_equals_the_sum_of_the_textbook_kernels():
    rng = np.random.default_rng(0)
    x, y, z = rng.normal(size=(3, 500))
    z = np.abs(z)
    z[:50] = 0.0
    got = combined(x, y, z, NU, 0.7, -0.4, 0.25)
    parts = [f(x, y, z, NU) for f in KERNELS]
    for k in range(6):
        want = 0.7 * parts[0][k] - 0.4 * parts[1][k] + 0.25 * parts[2][k]
        assert np.abs(got[k] - want).max() <= 1e-13 * np.abs(want).max()


def test_local_coefficients_are_the_disc_integrals_at_small_depth():
    # c = lim_{z->0} ∫∫_disc T dA (the principal value over a centred disc is zero)
    z = 1e-4
    t = np.linspace(0, 2 * np.pi, 33)[:-1]
    r = np.geomspace(1e-6 * z, 1.0, 4001)
    R, T = np.meshgrid(r, t, indexing="ij")
    coef = surface_limit_coefficients(NU)
    for fn, key in ((boussinesq, "normal"), (cerruti, "x"), (cerruti_y, "y")):
        s = fn(R * np.cos(T), R * np.sin(T), z, NU)
        got = [np.trapezoid((c * R * R).mean(axis=1) * 2 * np.pi, np.log(r)) for c in s]
        # the disc of radius 1 misses the part beyond it: O(z) = 1e-4
        np.testing.assert_allclose(got, coef[key], atol=5e-4)
