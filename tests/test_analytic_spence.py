"""Spence's frictional compression (analytic/spence.py, docs/formulation.md §2.8–2.9): the
slip annulus's traction opposes the relative slip that Hertz's pressure makes (Johnson
1985 eq. 3.41a), the stick radius of (SP1) behaves as a stick radius must, and the coupled
self-similar solution on rings (analytic/axisymmetric.py) reproduces what is known of it:
Hertz without coupling, the ring influence functions by 2D quadrature of the point-load
kernel, CONTACT's published stick radius, the friction law and the direction of slip, a
stick disc inside (SP1)'s, and convergence in the number of rings."""

from __future__ import annotations

import math

import numpy as np
import pytest

from analytic import axisymmetric
from analytic.solver import solve
from analytic.spence import compression, dundurs_beta, stick_ratio
from cases.loader import load_case


def radial_displacement(r: np.ndarray, a: float, p0: float, E: float, nu: float
                        ) -> np.ndarray:
    """The surface's radial displacement under Hertz's pressure, inside the contact
    (Johnson 1985 eq. 3.41a): −(1 − 2ν)(1 + ν)/(3E) a²/r [1 − (1 − r²/a²)^3/2] p0."""
    return -(1 - 2 * nu) * (1 + nu) / (3 * E) * a**2 / r * (1 - (1 - (r / a) ** 2) ** 1.5) * p0


@pytest.mark.parametrize("swap", [False, True], ids=["steel on titanium", "titanium on steel"])
def test_the_annulus_traction_opposes_the_relative_slip(swap):
    case = load_case("spence", quick=True)[0]
    if swap:
        case = case.with_changes(a=case.b, b=case.a)
    beta = dundurs_beta(case)
    step = solve(case).steps[0]
    a, p0 = step.scalars["a_x"], step.scalars["p_max"]
    x, y = step.x, step.y
    j = int(np.argmin(np.abs(y)))
    ring = (x > 0.9 * a) & (x < 0.98 * a)  # inside the annulus on the +x axis
    slip = (radial_displacement(x[ring], a, p0, case.a.E, case.a.nu)
            - radial_displacement(x[ring], a, p0, case.b.E, case.b.nu))
    q = step.surface["p_x"][ring, j]
    assert np.all(np.sign(q) == -np.sign(slip))  # friction on a opposes a's slip over b
    assert np.sign(q[0]) == np.sign(beta)
    np.testing.assert_allclose(np.abs(q), case.friction.mu1 * step.surface["p_n"][ring, j],
                               rtol=1e-12)
    centre = x.size // 2
    assert abs(step.surface["p_x"][centre, j]) <= 1e-12 * p0  # no radial shear at r = 0
    r = np.abs(x)
    stick = r < 0.9 * step.scalars["stick_radius"]
    assert np.all(np.abs(step.surface["p_x"][stick, j])
                  < case.friction.mu1 * step.surface["p_n"][stick, j])


def test_the_stick_radius_of_sp1():
    """c/a falls from 1 (no coupling) to 0 as |β|/μ grows; the coupling's sign does not
    change it, and (SP1) holds at the root found."""
    from scipy.special import ellipk

    values = [stick_ratio(b, 1.0) for b in (0.0, 0.3, 0.75, 1.0, 1.5, 2.0, 3.0, 5.0)]
    assert values[0] == 1.0 and all(np.diff(values) < 0) and values[-1] < 0.03
    assert stick_ratio(-1.2, 0.8) == stick_ratio(1.2, 0.8)
    for target in (0.75, 1.0, 1.5, 2.5):
        k = stick_ratio(target, 1.0)
        assert k * ellipk(1 - k * k) / math.atanh(k) == pytest.approx(target, rel=1e-10)


#: Hertz's dimensionless pressure at the centre, p0 R / (G a) = 2 / (π (1 − ν))
def _hertz_centre(nu: float) -> float:
    return 2.0 / (np.pi * (1.0 - nu))


def test_ring_influence_functions_against_quadrature_of_the_point_load_kernel():
    """The ring operators of a traction linear between nodes against 2D quadrature of the
    kernel of Eq. (5) over the disc, in polar coordinates about the field point (which
    absorbs its 1/s): Boussinesq's u_z of p = √(1 − ρ²) and Cerruti's u_r of q = ρ √(1 −
    ρ²) (its ν term integrates to zero over each ring, module doc), to 1e-4."""
    from scipy.integrate import dblquad

    ops = axisymmetric.ring_operators(200)
    rho = ops.nodes
    shape = np.sqrt(np.clip(1.0 - rho**2, 0.0, None))
    uz, ur = ops.Z @ shape, ops.R @ (rho * shape)
    for r in (0.0, 0.3, 0.7, 0.95):
        for radial, value in ((False, uz), (True, ur)):
            exact = dblquad(_disc_integrand, 0.0, 2 * np.pi, lambda psi: 0.0,
                            lambda psi, r=r: -r * np.cos(psi)
                            + np.sqrt(1.0 - (r * np.sin(psi)) ** 2),
                            args=(r, radial), epsabs=1e-11)[0]
            assert np.interp(r, rho, value) == pytest.approx(exact, rel=1e-4, abs=1e-6)


def _disc_integrand(ray: float, psi: float, r: float, radial: bool) -> float:
    """The integrand over the disc about the field point (r, 0), in polar coordinates
    (ray, psi) there: the kernel's 1/s times the area element s ds dψ leaves the traction
    alone, √(1 − ρ²) for u_z, its radial shear's x component ρ √(1 − ρ²) X/ρ for u_r."""
    X, Y = r + ray * np.cos(psi), ray * np.sin(psi)
    p = np.sqrt(max(1.0 - X * X - Y * Y, 0.0))
    return p * X if radial else p


def test_without_coupling_the_compression_is_hertz():
    """K → 0: the pressure is Hertz's to 1e-3 of its peak, the approach a²/R, the stick
    disc the whole contact but the last ring, whose edge node carries the only shear, μ p
    there (the stick–slip boundary's traction), which vanishes with the ring spacing."""
    nu = 0.3
    sol = compression(nu, 1e-9, 0.3)
    hertz = _hertz_centre(nu) * np.sqrt(1.0 - sol.rho**2)
    assert np.max(np.abs(sol.p - hertz)) < 1e-3 * hertz[0]
    assert sol.delta == pytest.approx(1.0, rel=1e-4)
    assert sol.load == pytest.approx(2 * np.pi * _hertz_centre(nu) / 3, rel=1e-4)
    assert sol.k == sol.rho[-2]
    assert np.max(np.abs(sol.q)) == pytest.approx(0.3 * sol.p[-2], rel=1e-6)
    assert np.max(np.abs(sol.q[:-2])) < abs(sol.q[-2])  # its stick zone response


def test_the_stick_radius_of_a_peer_codes_published_example():
    """Vollebregt's CONTACT, example spence35: c/a = 1/2 at β = 1/2, μ = 0.2986 (the stick
    radius to the ring spacing there, 0.003 a), against (SP1)'s 0.623."""
    nu = 0.3
    sol = compression(nu, 0.5 * (1 - nu), 0.2986)
    assert sol.k == pytest.approx(0.5, abs=0.004)
    assert stick_ratio(0.5, 0.2986) > sol.k + 0.1


@pytest.mark.parametrize(("beta", "mu", "nu"), [(-0.0575, 0.04, 0.33), (0.5, 0.3, 0.0),
                                                (-0.2, 0.3, 0.25), (0.2, 0.05, 0.3),
                                                (0.45, 1.0, -0.5), (-0.3, 0.5, 0.45)])
def test_the_coupled_compression_obeys_friction_and_converges(beta, mu, nu):
    """The friction law (|q| ≤ μ p, = μ p in the slip annulus, the traction against the
    slip rate there), a stick disc no larger than (SP1)'s, and convergence in the number
    of rings: p_max and a move by < 5e-4 of Hertz's from 400 to 800 rings (the ring
    count's error, N_RINGS), c/a by < 4e-3 (the ring spacing)."""
    K = beta * (1 - nu)
    sol, fine = compression(nu, K, mu), compression(nu, K, mu, 800)
    hertz = _hertz_centre(nu)
    m = int(np.searchsorted(sol.rho, sol.k))
    assert np.all(np.abs(sol.q) <= mu * sol.p + 1e-9 * hertz)
    np.testing.assert_allclose(sol.q[m:], np.sign(beta) * mu * sol.p[m:], atol=1e-12)
    assert sol.slip_rate_min >= 0.0
    assert sol.k <= stick_ratio(beta, mu) + 4e-3
    for v in (sol, fine):
        assert v.p.max() > hertz  # the coupling raises the peak
    assert abs(sol.p.max() - fine.p.max()) < 5e-4 * hertz
    assert abs(sol.load - fine.load) < 5e-4 * sol.load
    assert abs(sol.k - fine.k) < 4e-3
