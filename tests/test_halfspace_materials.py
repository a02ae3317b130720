"""Composite constants of Eq. 6."""

import math

import pytest

from cases.model import Body
from halfspace.materials import Materials


def test_identical_bodies_give_body_constants_and_no_coupling():
    steel = Body(E=210000.0, nu=0.3)
    mat = Materials.from_bodies(steel, steel)
    assert mat.K == 0.0
    assert mat.G == pytest.approx(steel.G, rel=1e-15)
    assert mat.nu == pytest.approx(steel.nu, rel=1e-15)
    assert (mat.nu_a, mat.nu_b) == (0.3, 0.3)


def test_dissimilar_pair_by_hand():
    # G_a = 100, nu_a = 0.25 (E_a = 250); G_b = 50, nu_b = 0.4 (E_b = 140).
    # 1/G = (1/100 + 1/50)/2 = 0.015 -> G = 200/3
    # nu/G = (0.25/100 + 0.4/50)/2 = 0.00525 -> nu = 0.35
    # K = G/4 (0.5/100 - 0.2/50) = (200/3)/4 * 0.001 = 1/60
    a, b = Body(E=250.0, nu=0.25), Body(E=140.0, nu=0.4)
    assert (a.G, b.G) == (100.0, 50.0)
    mat = Materials.from_bodies(a, b)
    assert mat.G == pytest.approx(200.0 / 3.0, rel=1e-14)
    assert mat.nu == pytest.approx(0.35, rel=1e-14)
    assert mat.K == pytest.approx(1.0 / 60.0, rel=1e-12)
    assert (mat.nu_a, mat.nu_b) == (0.25, 0.4)
    # swapping the bodies flips the sign of K only
    swapped = Materials.from_bodies(b, a)
    assert swapped.K == pytest.approx(-mat.K, rel=1e-12)
    assert (swapped.G, swapped.nu) == pytest.approx((mat.G, mat.nu), rel=1e-14)


def test_rigid_limit_of_body_b():
    # a very stiff b: G -> 2 G_a, nu -> nu_a, K -> G/4 (1-2 nu_a)/G_a = (1 - 2 nu_a)/2
    a, b = Body(E=200.0, nu=0.3), Body(E=2e15, nu=0.3)
    mat = Materials.from_bodies(a, b)
    assert mat.G == pytest.approx(2.0 * a.G, rel=1e-10)
    assert mat.nu == pytest.approx(0.3, rel=1e-10)
    assert mat.K == pytest.approx(0.5 * (1.0 - 0.6), rel=1e-10)


def test_without_bodies_per_body_values_raise():
    mat = Materials(G=1.0, nu=0.3, K=0.0)
    with pytest.raises(ValueError, match="without body"):
        _ = mat.nu_a
    with pytest.raises(ValueError, match="'a' or 'b'"):
        mat.body("c")


@pytest.mark.parametrize(
    ("E", "nu", "key"), [(-1.0, 0.3, "E"), (math.nan, 0.3, "E"), (1.0, 0.5, "nu"),
                         (1.0, -1.0, "nu")],
)
def test_invalid_body_is_rejected(E, nu, key):
    good = Body(E=1.0, nu=0.3)
    with pytest.raises(ValueError, match=f"body b: {key}"):
        Materials.from_bodies(good, Body(E=E, nu=nu))
