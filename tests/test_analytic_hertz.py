"""Hertz closed forms against each other and against point-force quadrature."""

import math

import numpy as np
import pytest

from analytic import hertz as hz
from analytic.quadrature import hertzian_traction_stresses
from cases import load_case

NU = 0.3


def test_article_numbers():
    # cases.md case 1: a0 ≈ 0.149 mm for R = 50 mm, P = 10.2 N, two steels
    case = load_case("hertz", quick=True)[0]
    h = hz.hertz(case.load.P, case.R, case.E_star)
    E_star = 210000.0 / (2 * (1 - 0.3**2))
    assert case.E_star == pytest.approx(E_star, rel=1e-14)
    assert h.a == pytest.approx((3 * 10.2 * 50 / (4 * E_star)) ** (1 / 3), rel=1e-14)
    assert round(h.a, 3) == 0.149
    assert h.a == pytest.approx(case.hertz_a0, rel=1e-14)
    # p0 = 3P/(2πa²) and P = ∫ p dA (the mean pressure is 2/3 p0)
    assert h.p0 * (2.0 / 3.0) * math.pi * h.a**2 == pytest.approx(10.2, rel=1e-14)
    assert h.delta == pytest.approx(h.a**2 / 50.0, rel=1e-14)


def test_approach_control_inverts_load_control():
    h = hz.hertz(10.2, 50.0, 115384.6)
    g = hz.hertz_from_approach(h.delta, 50.0, 115384.6)
    assert (g.P, g.a, g.p0) == pytest.approx((h.P, h.a, h.p0), rel=1e-13)


def test_axis_closed_form_against_quadrature():
    # Johnson eq. 3.45 vs quadrature of the Boussinesq kernel over the Hertz pressure;
    # the quadrature converges to ~1e-7 p0 on the axis with the default rule
    z = np.array([0.0, 1e-3, 0.1, 0.3, 0.48, 0.8, 1.5, 4.0])
    sr, sz = hz.axis_stresses(z, 1.0, 1.0, NU)
    q = hertzian_traction_stresses(0 * z, 0 * z, z, 1.0, p0=1.0, nu=NU)
    assert np.abs(q["sxx"] - sr).max() < 1e-5
    assert np.abs(q["syy"] - sr).max() < 1e-5
    assert np.abs(q["szz"] - sz).max() < 1e-5


def test_axis_von_mises_maximum():
    # textbook (Johnson §3.7): τ1 = 0.31 p0 at z = 0.48a, i.e. σ_VM = 0.62 p0 for ν = 0.3
    vm, z = hz.axis_vm_max(NU)
    assert vm == pytest.approx(0.62, abs=0.005)
    assert z == pytest.approx(0.48, abs=0.005)
    # a maximum: the closed form is lower on both sides
    assert hz.axis_von_mises(z * (1 + 1e-3), 1, 1, NU) < vm
    assert hz.axis_von_mises(z * (1 - 1e-3), 1, 1, NU) < vm
    # and the stationarity condition d(σ_z - σ_r)/dz = 0 holds (central difference)
    d = 1e-6
    assert abs(hz.axis_von_mises(z + d, 1, 1, NU) - hz.axis_von_mises(z - d, 1, 1, NU)) < 1e-10


def test_full_field_against_quadrature():
    # Hamilton & Goodman (1966) closed form vs Boussinesq quadrature, in and around the
    # contact, surface included; both converge to < 1e-8 p0 (measured 5e-9 with 128 x 64)
    x = np.linspace(-2.0, 2.0, 17)
    y = np.array([0.0, 0.37, 1.1])
    z = np.array([0.0, 1e-3, 0.1, 0.48, 1.0, 2.0])
    X, Y, Z = np.meshgrid(x, y, z, indexing="ij")
    a, p0 = 0.15, 1000.0
    q = hertzian_traction_stresses(a * X, a * Y, a * Z, a, p0=p0, nu=NU)
    h = hz.full_field(a * X, a * Y, a * Z, a, p0, NU)
    for c in q:
        assert np.abs(q[c] - h[c]).max() < 2e-5 * p0, c


def test_full_field_surface_equals_johnson_341():
    # two closed forms: Hamilton-Goodman at z = 0 vs Johnson §3.4 (σ_r on y = 0)
    r = np.array([0.1, 0.5, 0.9, 0.999, 1.0, 1.2, 3.0])
    f = hz.full_field(r, 0 * r, 0 * r, 1.0, 1.0, NU)
    sr, st = hz.surface_stresses(r, 1.0, 1.0, NU)
    np.testing.assert_allclose(f["sxx"], sr, atol=1e-12)
    np.testing.assert_allclose(f["syy"], st, atol=1e-12)
    np.testing.assert_allclose(f["szz"], -hz.pressure(r, 1.0, 1.0), atol=1e-12)
    # at the edge σ_r = (1-2ν)p0/3, the maximum tensile stress of the Hertz contact
    assert sr[4] == pytest.approx((1 - 2 * NU) / 3, rel=1e-14)


def test_full_field_axis_limit_is_continuous():
    # just outside the axis patch (r = 1e-4 a) the general formula, which loses
    # ~1e-16 a²/r² to cancellation, meets eq. 3.45 to within the O(r²) = 1e-8 variation
    z = np.array([0.2, 0.48, 1.0])
    sr, sz = hz.axis_stresses(z, 1.0, 1.0, NU)
    for r in (1.01e-4, 3e-4):
        near = hz.full_field(r + 0 * z, 0 * z, z, 1.0, 1.0, NU)
        np.testing.assert_allclose(near["sxx"], sr, atol=2 * r**2)
        np.testing.assert_allclose(near["syy"], sr, atol=2 * r**2)
        np.testing.assert_allclose(near["szz"], sz, atol=2 * r**2)


def test_gap():
    a, R = 0.149, 50.0
    r = np.array([0.0, 0.5 * a, 0.999 * a])
    assert np.all(hz.gap(r, a, R) == 0.0)
    # continuous at the edge: g ~ (r - a)^(3/2) just outside
    assert hz.gap(a * (1 + 1e-8), a, R) < 1e-12 * a
    # far field: the surfaces separate like r²/2R - δ + P/(π E* r) (point force on two
    # half-spaces), P/(πE*) = 4a³/(3πR); the next term is O(a⁵/(R r³))
    rf = np.array([20.0, 50.0]) * a
    far = rf**2 / (2 * R) - a**2 / R + 4 * a**3 / (3 * math.pi * R * rf)
    np.testing.assert_allclose(hz.gap(rf, a, R), far, rtol=1e-6)
    assert np.all(np.diff(hz.gap(np.linspace(a, 3 * a, 50), a, R)) > 0)
