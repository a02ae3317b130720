"""Cattaneo–Mindlin: traction, stick zone, tangential compliance, fretting regime and loop."""

import math

import numpy as np
import pytest

from analytic import hertz as hz
from analytic import mindlin as md

E, NU = 210000.0, 0.3
G = E / (2 * (1 + NU))
E_STAR = E / (2 * (1 - NU**2))
R, P, MU = 50.0, 10.2, 0.3


def one_body_ux(X, Y, terms, nu=NU, G=G, n_phi=64, n_r=64):
    """u_x at surface points of one half-space under Hertz-shaped x-tractions.

    Quadrature of the Cerruti surface displacement u_x = [(1-ν)/s + ν (Δx)²/s³]/(2πG)
    (Cerruti, Johnson §3.2, at z = 0), in polar coordinates centred on the field point (the 1/s
    cancels with s ds); terms = [(radius, q0)] for q0 √(1 - r²/radius²).  Points inside
    every circle.
    """
    phi = 2 * np.pi * np.arange(n_phi) / n_phi
    v, wv = np.polynomial.legendre.leggauss(n_r)
    v, wv = 0.5 * (v + 1), 0.5 * wv
    out = []
    for x0, y0 in zip(X, Y, strict=True):
        total = 0.0
        for rad, q0 in terms:
            b = x0 * np.cos(phi) + y0 * np.sin(phi)
            root = np.sqrt(b * b + rad * rad - x0 * x0 - y0 * y0)
            r2, r1 = -b + root, -b - root
            # r = r2 (1 - v²): √(r2 - r) = √r2 v, dr = 2 r2 v dv
            r = r2[:, None] * (1 - v**2)
            shape = np.sqrt(r2[:, None]) * v * np.sqrt(r - r1[:, None]) / rad
            ang = (1 - nu) + nu * np.cos(phi) ** 2
            ray = (shape * 2 * r2[:, None] * v * wv).sum(axis=1)
            total += q0 * (ang * ray).sum() * (2 * np.pi / n_phi) / (2 * np.pi * G)
        out.append(total)
    return np.array(out)


def test_single_term_displacement_matches_johnson_section_72():
    # u_x = π q0 [4(2-ν)a² - (4-3ν)x² - (4-ν)y²]/(32 G a) inside the contact
    a, q0 = 0.15, 100.0
    X, Y = np.array([0.0, 0.05, 0.0, 0.06]), np.array([0.0, 0.0, 0.07, -0.04])
    want = math.pi * q0 * (4 * (2 - NU) * a * a - (4 - 3 * NU) * X**2 - (4 - NU) * Y**2) / (
        32 * G * a)
    np.testing.assert_allclose(one_body_ux(X, Y, [(a, q0)]), want, rtol=1e-9)


@pytest.mark.parametrize("ratio", [0.25, 0.5, 0.75])
def test_stick_zone_moves_rigidly_by_the_mindlin_shift(ratio):
    h = hz.hertz(P, R, E_STAR)
    c = md.stick_radius(h.a, ratio * MU * P, MU, P)
    assert c == pytest.approx(h.a * (1 - ratio) ** (1 / 3), rel=1e-14)
    terms = [(h.a, MU * h.p0), (c, -(c / h.a) * MU * h.p0)]
    rr = np.array([0.0, 0.3, 0.6, 0.9]) * c
    ang = np.array([0.0, 1.0, 2.2, 4.0])
    u = one_body_ux(rr * np.cos(ang), rr * np.sin(ang), terms)
    # uniform over the stick zone (quadrature error ~1e-10 relative)
    assert np.ptp(u) < 1e-8 * abs(u[0])
    # one body on a rigid plane: 3μP(2-ν)/(16Ga)[1 - (1-Q/μP)^(2/3)]; two identical
    # bodies move apart by twice that: the δ_t of shift_from_load
    one = 3 * MU * P * (2 - NU) / (16 * G * h.a) * (1 - (1 - ratio) ** (2 / 3))
    assert u[0] == pytest.approx(one, rel=1e-9)
    dstar = md.gross_slip_shift(MU, P, h.a, G, NU, G, NU)
    assert md.shift_from_load(ratio * MU * P, MU, P, dstar) == pytest.approx(2 * u[0],
                                                                            rel=1e-9)


def test_traction_resultant_is_Q():
    # ∫ q dA = μP - (c/a)³ μP = Q, by 1-D quadrature in r (independent of the formulas)
    from scipy.integrate import quad

    h = hz.hertz(P, R, E_STAR)
    for ratio in (0.2, 0.6, 0.95):
        c = md.stick_radius(h.a, ratio * MU * P, MU, P)
        f = lambda r, c=c: float(md.traction(r, h.a, c, MU, h.p0)) * 2 * math.pi * r  # noqa: E731
        Q = quad(f, 0, c, epsabs=0, epsrel=1e-12)[0] + quad(f, c, h.a, epsabs=0,
                                                            epsrel=1e-12)[0]
        assert Q == pytest.approx(ratio * MU * P, rel=1e-9)
        # on the slip limit μp in the annulus, below it in the stick zone
        r_slip = np.linspace(c, h.a, 7)[1:-1]
        np.testing.assert_allclose(md.traction(r_slip, h.a, c, MU, h.p0),
                                   MU * hz.pressure(r_slip, h.a, h.p0), rtol=1e-12)
        r_stick = np.linspace(0, c, 7)[:-1]
        assert np.all(md.traction(r_stick, h.a, c, MU, h.p0)
                      < MU * hz.pressure(r_stick, h.a, h.p0))


def test_load_and_shift_are_inverse_and_saturate():
    d = 0.002
    for Q in (-2.0, 0.3, 1.7, 3.0):
        assert md.load_from_shift(md.shift_from_load(Q, MU, P, d), MU, P, d) == pytest.approx(
            Q, rel=1e-12)
    assert md.load_from_shift(1.5 * d, MU, P, d) == pytest.approx(MU * P, rel=1e-15)
    # initial stiffness dQ/dδ = (3/2) μP/δ* (the slope of the virgin curve at 0)
    eps = 1e-9 * d
    assert md.load_from_shift(eps, MU, P, d) / eps == pytest.approx(1.5 * MU * P / d, rel=1e-6)


def test_gross_slip_shift_under_a_held_approach():
    # case 6: δ_n = 0.008 mm; δ* = μ(2-ν)δ_n/(2(1-ν)) for two identical bodies, the same as
    # 3μP(2-ν)/(8Ga) with P, a of the Hertz state of that approach
    dn = 0.008
    h = hz.hertz_from_approach(dn, R, E_STAR)
    for mu in (0.1, 0.65):
        a = md.gross_slip_shift_from_approach(dn, mu, E_STAR, G, NU, G, NU)
        b = md.gross_slip_shift(mu, h.P, h.a, G, NU, G, NU)
        assert a == pytest.approx(b, rel=1e-13)
        assert a == pytest.approx(mu * (2 - NU) * dn / (2 * (1 - NU)), rel=1e-13)
        assert a == pytest.approx(3 * mu * h.P * (2 - NU) / (8 * G * h.a), rel=1e-13)
    # amplitude 0.004 mm: gross slip along μ = 0.1, partial slip along μ = 0.65; the
    # threshold is μ = 2(1-ν) A / ((2-ν) δ_n) = 0.4118
    amp = 0.004
    assert md.fretting_regime(amp, md.gross_slip_shift_from_approach(
        dn, 0.1, E_STAR, G, NU, G, NU)) == "gross"
    assert md.fretting_regime(amp, md.gross_slip_shift_from_approach(
        dn, 0.65, E_STAR, G, NU, G, NU)) == "partial"
    mu_t = 2 * (1 - NU) * amp / ((2 - NU) * dn)
    assert md.gross_slip_shift_from_approach(dn, mu_t, E_STAR, G, NU, G, NU) == pytest.approx(
        amp, rel=1e-13)


@pytest.mark.parametrize("amp_ratio", [0.05, 0.4, 0.8, 1.0])
def test_loop_area_is_the_dissipated_energy(amp_ratio):
    # Johnson §7.4 (with δ*) against the trapezoid area of the Masing loop;
    # the trapezoid error ~ (δ/n)² |Q''| is < 1e-6 relative with n = 4001
    d = 0.002
    amp = amp_ratio * d
    x, q = md.loop_partial_slip(amp, MU, P, d, n=4001)
    area = np.trapezoid(q, x)  # counter-clockwise: positive work per cycle
    Qa = md.load_from_shift(amp, MU, P, d)
    assert area == pytest.approx(md.dissipated_energy(Qa, MU, P, d), rel=1e-5)
    # small amplitudes: ΔW ≈ (4/27) μP δ* (Q/μP)³
    if amp_ratio < 0.1:
        t = Qa / (MU * P)
        assert md.dissipated_energy(Qa, MU, P, d) == pytest.approx(
            4 / 27 * MU * P * d * t**3, rel=0.1)
