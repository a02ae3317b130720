"""Spence's frictional compression (analytic/spence.py, docs/formulation.md §2.8): the
slip annulus's traction opposes the relative slip that Hertz's pressure makes (Johnson
1985 eq. 3.41a), and the stick radius of (SP1) behaves as a stick radius must."""

from __future__ import annotations

import math

import numpy as np
import pytest

from analytic.solver import solve
from analytic.spence import dundurs_beta, stick_ratio
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
    assert np.isnan(step.surface["p_x"][x.size // 2, j])  # the stick disc: no statement


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
