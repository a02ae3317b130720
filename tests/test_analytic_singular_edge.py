"""The log-singular edge stress of docs/formulation.md §2.6, Eq. (S1): the closed form
against quadrature of the Flamant kernel, and its growth rate as the depth halves (the
reason the surface σ_VM maximum of a worn frictional contact is declared not converged)."""

import math

import numpy as np
import pytest
from scipy.integrate import quad


def flamant_sxx(x: float, z: float, Q: float = 1.0) -> float:
    """σ_xx at (x, z) of a tangential line force Q at the origin of a half-plane."""
    r2 = x * x + z * z
    return -2.0 * Q / math.pi * x**3 / r2**2


def edge_sxx(q: float, c: float, z: float) -> float:
    """Eq. (S1): σ_xx below the edge x = c of a uniform traction q on |x'| < c."""
    return -q / math.pi * (math.log((4 * c * c + z * z) / (z * z))
                           + z * z / (4 * c * c + z * z) - 1.0)


@pytest.mark.parametrize("z", [1e-3, 0.05, 0.3, 2.0])
def test_closed_form_equals_quadrature(z):
    q, c = 1.7, 0.6
    # the kernel's peak sits at x - s ~ z: split there so quad resolves it
    pts = [c - z] if 0 < c - z < 2 * c else None
    value, err = quad(lambda s: q * flamant_sxx(c - s, z), -c, c, points=pts, limit=400,
                      epsabs=0, epsrel=1e-12)
    assert edge_sxx(q, c, z) == pytest.approx(value, rel=1e-9)


def test_grows_by_2q_ln2_over_pi_per_halving():
    """The stress has no limit at the surface: each halving of z adds (2q/π) ln 2."""
    q, c = 1.0, 1.0
    z = np.array([1e-2, 5e-3, 2.5e-3, 1.25e-3])
    s = np.array([edge_sxx(q, c, zz) for zz in z])
    growth = -np.diff(s)
    assert growth == pytest.approx(2 * q / math.pi * math.log(2), rel=1e-4)
    # while a fixed depth gives a finite number (the companion quantity)
    assert math.isfinite(edge_sxx(q, c, 0.1))
