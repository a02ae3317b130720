"""Pin wear references: Archard's volume balance, Argatov (2011), Hegadekatte (2008)."""

import math

import numpy as np
import pytest

from analytic import hertz as hz
from analytic import wear

E, NU, R, P = 210000.0, 0.3, 50.0, 10.2
I_W = 1.33e-7
A0 = hz.hertz(P, R, E / (2 * (1 - NU**2))).a
S = np.array([0.0, 1.0, 20.0, 40.0, 80.0, 160.0, 640.0])  # s/a0 = 0, 20/3, ... and the end


def test_orthotropic_wear_coefficient():
    i1, i2 = 1.33e-7, 2.66e-7
    # sliding along +x: θ = -β
    assert wear.sliding_angle(0.0) == 0.0 and wear.sliding_angle(45.0) == -45.0
    assert wear.wear_coefficient(i1, i2, wear.sliding_angle(0.0)) == pytest.approx(i1)
    assert wear.wear_coefficient(i1, i2, wear.sliding_angle(90.0)) == pytest.approx(i2)
    assert wear.wear_coefficient(i1, i2, wear.sliding_angle(45.0)) == pytest.approx(
        math.sqrt((i1**2 + i2**2) / 2), rel=1e-14)
    # even in θ: the sense of sliding does not matter
    assert wear.wear_coefficient(i1, i2, 30.0) == pytest.approx(
        wear.wear_coefficient(i1, i2, -30.0), rel=1e-15)


def test_hegadekatte_depth_satisfies_archard_exactly():
    w = wear.hegadekatte_wear_depth(S, I_W, P, R)
    W = wear.archard_volume(S, I_W, P)
    np.testing.assert_allclose(wear.cap_volume(w, R), W, rtol=1e-10, atol=0)
    assert w[0] == 0.0 and np.all(np.diff(w) > 0)


def test_argatov_depth_is_the_archard_cap():
    # the Archard-consistent reading: the paraboloid cap of height w has the worn volume
    w = wear.argatov_wear_depth(S, A0, I_W, P, R)
    np.testing.assert_allclose(wear.paraboloid_cap_volume(w, R),
                               wear.archard_volume(S, I_W, P), rtol=1e-10, atol=1e-30)
    np.testing.assert_allclose(w, np.sqrt(I_W * P * S / (math.pi * R)), rtol=1e-10)
    assert w[0] == 0.0
    # radius: a0 at s = 0
    assert wear.argatov_radius(0.0, A0, I_W, P, R) == pytest.approx(A0, rel=1e-15)


def test_literal_reading_violates_archard_by_the_elastic_cap():
    # w = a²/(2R) of cases.md: its paraboloid cap holds π a0⁴/(4R) more than Archard's W,
    # i.e. half the elastic approach at s = 0, and differs from the consistent depth by
    # a0⁴/(4 R a²) to leading order
    lit = wear.argatov_wear_depth_literal(S, A0, I_W, P, R)
    extra = wear.paraboloid_cap_volume(lit, R) - wear.archard_volume(S, I_W, P)
    np.testing.assert_allclose(extra, math.pi * A0**4 / (4 * R), rtol=1e-9)
    assert lit[0] == pytest.approx(0.5 * A0**2 / R, rel=1e-14)
    a = wear.argatov_radius(S[-1], A0, I_W, P, R)
    diff = lit[-1] - wear.argatov_wear_depth(S[-1], A0, I_W, P, R)
    assert diff == pytest.approx(A0**4 / (4 * R * a * a), rel=0.01)


def test_argatov_and_hegadekatte_agree_asymptotically():
    # same worn volume, paraboloid vs sphere cap: w_H/w_A - 1 = w/(6R) + O((w/R)²)
    s = np.array([1.0, 40.0, 640.0, 1e5, 1e7])
    wa = wear.argatov_wear_depth(s, A0, I_W, P, R)
    wh = wear.hegadekatte_wear_depth(s, I_W, P, R)
    rel = wh / wa - 1
    np.testing.assert_allclose(rel, wa / (6 * R), rtol=0.05)
    # the 640 mm of case 4: w ≈ 2.35 µm, the two references differ by 8e-6 relative
    assert wa[2] == pytest.approx(2.351e-3, rel=1e-3)
    assert rel[2] < 1e-5


def test_steady_pressure_and_transition():
    p = wear.argatov_p_max(S, A0, I_W, P, R)
    a = wear.argatov_radius(S, A0, I_W, P, R)
    np.testing.assert_allclose(p * math.pi * a**2, P, rtol=1e-14)
    # s_c: wear depth = elastic approach a0²/R; ≈ 23 mm for case 4
    s_c = wear.transition_distance(A0, I_W, P, R)
    assert wear.argatov_wear_depth(s_c, A0, I_W, P, R) == pytest.approx(A0**2 / R, rel=1e-12)
    assert 20.0 < s_c < 26.0


def test_worn_flat_radius():
    w = wear.hegadekatte_wear_depth(640.0, I_W, P, R)
    rho = wear.worn_flat_radius(w, R)
    # the sphere through the flat's rim: (R - w)² + ρ² = R²
    assert (R - w) ** 2 + rho**2 == pytest.approx(R * R, rel=1e-15)
