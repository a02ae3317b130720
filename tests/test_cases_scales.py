"""Hertz scales and expected contact radius carried by the Case, and the a-priori check
that the contact fits in the grid."""

from __future__ import annotations

import math

import pytest

from cases.loader import load_case
from cases.model import Body, CaseError, Friction, SlidingWear
from reports.run.plan import check_fits


def test_hertz_scales_of_the_article_case():
    case = load_case("hertz")[0]
    a0, p0 = case.hertz_scales
    # docs/cases.md: E* = E / (2(1 - ν²)) = 115 385 MPa, a0 ≈ 0.149 mm
    e_star = 210000.0 / (2 * (1 - 0.3**2))
    assert case.E_star == pytest.approx(e_star, rel=1e-12)
    assert a0 == pytest.approx((3 * 10.2 * 50 / (4 * e_star)) ** (1 / 3), rel=1e-12)
    assert a0 == pytest.approx(0.1491, abs=5e-5)
    assert p0 == pytest.approx(3 * 10.2 / (2 * math.pi * a0**2), rel=1e-12)
    assert case.hertz_a0 == a0


def test_displacement_control_gives_the_same_contact():
    load = load_case("hertz")[0]
    a0, p0 = load.hertz_scales
    approach = a0**2 / load.R  # Hertz: δ = a²/R
    disp = load.with_changes(load=load.load.__class__(approach=approach))
    a1, p1 = disp.hertz_scales
    assert a1 == pytest.approx(a0, rel=1e-12)
    assert p1 == pytest.approx(p0, rel=1e-12)  # p0 = 2 E* a / (π R) = 3P/(2π a²)
    assert disp.expected_radius == pytest.approx(a0, rel=1e-12)


def _worn(case, a: Body, b: Body | None = None, beta: float = 0.0, slide: float = 0.0):
    return case.with_changes(kind="sliding_wear", sliding_wear=SlidingWear(distance=640.0),
                             a=a, b=b or case.b,
                             friction=Friction(mu1=0.25, mu2=0.5, beta=beta),
                             load=case.load.__class__(P=case.load.P, sliding=True,
                                                      slide_angle=slide))


def test_expected_radius_of_a_worn_pin():
    case = load_case("hertz")[0]
    a0, _ = case.hertz_scales
    worn = _worn(case, Body(E=case.a.E, nu=case.a.nu, i1=1.33e-7, i2=1.33e-7))
    # Argatov (2011): a⁴ = a0⁴ + 4 i_w P s R / π; with the case-4 numbers a ≈ 0.486 mm
    want = (a0**4 + 4 * 1.33e-7 * 10.2 * 640 * 50 / math.pi) ** 0.25
    assert worn.expected_radius == pytest.approx(want, rel=1e-12)
    assert want == pytest.approx(0.486, abs=1e-3)
    check_fits(worn)  # fits in 1.6 mm x 1.6 mm


@pytest.mark.parametrize("beta, slide", [(0.0, 0.0), (45.0, 0.0), (90.0, 0.0), (30.0, 100.0)])
def test_wear_coefficient_of_the_gap_sums_both_bodies_along_the_slide(beta, slide):
    """i_w(θ) of Eq. 19 with θ = slide − β for each body, summed (the gap sees both)."""
    case = load_case("hertz")[0]
    a = Body(E=case.a.E, nu=case.a.nu, i1=1.33e-7, i2=2.66e-7)
    b = Body(E=case.b.E, nu=case.b.nu, i1=0.5e-7, i2=3.0e-7)
    worn = _worn(case, a, b, beta=beta, slide=slide)
    t = math.radians(slide - beta)
    want = sum(math.sqrt((body.i1 * math.cos(t)) ** 2 + (body.i2 * math.sin(t)) ** 2)
               for body in (a, b))
    assert worn.sliding_wear_coefficient == pytest.approx(want, rel=1e-13)
    a0, _ = case.hertz_scales
    want_a = (a0**4 + 4 * want * 10.2 * 640 * 50 / math.pi) ** 0.25
    assert worn.expected_radius == pytest.approx(want_a, rel=1e-12)


def test_contact_larger_than_the_grid_is_refused():
    case = load_case("hertz", overrides={"grid.Lx": 0.3, "grid.Ly": 0.3, "grid.nx": 31,
                                          "grid.ny": 31})[0]
    # a0 = 0.149 mm against a half-width of 0.15 mm less one 0.0097 mm cell
    with pytest.raises(CaseError, match=r"grid.Lx = 0.3 mm: the expected contact radius "
                                        r"0.1491 mm reaches the edge"):
        check_fits(case)
    check_fits(case.with_changes(grid=case.grid.__class__(Lx=0.34, Ly=0.34, nx=31, ny=31)))
