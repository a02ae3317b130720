"""Hertz scales and the a-priori check that the contact fits in the grid."""

from __future__ import annotations

import math

import pytest

from cases.loader import load_case
from cases.model import CaseError
from reports.runner import check_fits, expected_radius
from reports.scales import hertz_scales


def test_hertz_scales_of_the_article_case():
    case = load_case("hertz")[0]
    a0, p0 = hertz_scales(case)
    # paper/cases.md: E* = E / (2(1 - ν²)) = 115 385 MPa, a0 ≈ 0.149 mm
    e_star = 210000.0 / (2 * (1 - 0.3**2))
    assert case.E_star == pytest.approx(e_star, rel=1e-12)
    assert a0 == pytest.approx((3 * 10.2 * 50 / (4 * e_star)) ** (1 / 3), rel=1e-12)
    assert a0 == pytest.approx(0.1491, abs=5e-5)
    assert p0 == pytest.approx(3 * 10.2 / (2 * math.pi * a0**2), rel=1e-12)


def test_displacement_control_gives_the_same_contact():
    load = load_case("hertz")[0]
    a0, p0 = hertz_scales(load)
    approach = a0**2 / load.R  # Hertz: δ = a²/R
    disp = load.with_changes(load=load.load.__class__(approach=approach))
    a1, p1 = hertz_scales(disp)
    assert a1 == pytest.approx(a0, rel=1e-12)
    assert p1 == pytest.approx(p0, rel=1e-12)  # p0 = 2 E* a / (π R) = 3P/(2π a²)


def test_expected_radius_of_a_worn_pin():
    case = load_case("hertz")[0]
    a0, _ = hertz_scales(case)
    from cases.model import SlidingWear

    worn = case.with_changes(kind="sliding_wear", sliding_wear=SlidingWear(distance=640.0),
                             a=case.a.__class__(E=case.a.E, nu=case.a.nu, i1=1.33e-7,
                                                i2=1.33e-7))
    # Argatov (2011): a⁴ = a0⁴ + 4 i_w P s R / π; with the case-4 numbers a ≈ 0.486 mm
    want = (a0**4 + 4 * 1.33e-7 * 10.2 * 640 * 50 / math.pi) ** 0.25
    assert expected_radius(worn) == pytest.approx(want, rel=1e-12)
    assert want == pytest.approx(0.486, abs=1e-3)
    check_fits(worn)  # fits in 1.6 mm x 1.6 mm


def test_contact_larger_than_the_grid_is_refused():
    case = load_case("hertz", overrides={"grid.Lx": 0.3, "grid.Ly": 0.3, "grid.nx": 31,
                                          "grid.ny": 31})[0]
    # a0 = 0.149 mm against a half-width of 0.15 mm less one 0.0097 mm cell
    with pytest.raises(CaseError, match=r"grid.Lx = 0.3 mm: the expected contact radius "
                                        r"0.1491 mm reaches the edge"):
        check_fits(case)
    check_fits(case.with_changes(grid=case.grid.__class__(Lx=0.34, Ly=0.34, nx=31, ny=31)))
