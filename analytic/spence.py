"""Frictional compression of a dissimilar pair (Spence 1975; Johnson 1985 §5.5): the
normal–tangential coupling's closed-form reference.

Pressed together, the two surfaces move radially inward by amounts ∝ (1 − 2ν)/G: the one
with the larger (1 − 2ν)/G slides inward over the other.  With friction μ the contact
grows self-similarly (a stick disc r < c and a slip annulus c < r < a, c/a fixed), and in
the annulus the traction on each body is μ p, radial, opposing its slip: with Dundurs'

    β = ½ [(1 − 2ν_a)/G_a − (1 − 2ν_b)/G_b] / [(1 − ν_a)/G_a + (1 − ν_b)/G_b],

body a (the upper one) moves inward relative to b for β > 0, so the traction on a points
outward, q_a = sign(β) μ p r̂; for β < 0 inward (Spence 1975; Vollebregt's CONTACT, user
guide, example spence35: c/a = 1/2 at β = 1/2, μ = 0.2986, traction on body 1 outward).

**(SP1)** (not in the source article; docs/formulation.md §2.8) The stick radius of the
uncoupled problem (the pressure kept Hertzian, the shear driven by the pressure's radial
displacements; a self-similar, monotonic loading with a traction bounded at r = c)
solves

    |β| / μ = k K(√(1 − k²)) / artanh k,   k = c / a,

K the complete elliptic integral of the first kind.  With the coupling the stick disc is
smaller (1/2 against 0.623 at β = 1/2; within 0.01 a for |β| ≤ 0.2): on r > c of (SP1)
the pair slips, and there the traction is the exact μ p r̂ above.  This is what the
reference states; inside c it says nothing (NaN), and the pressure is Hertz's, which the
coupling changes by O(β μ) only.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq
from scipy.special import ellipk

from cases.model import Case


def dundurs_beta(case: Case) -> float:
    """Dundurs' β of the pair (module doc); 0 for identical materials."""
    a, b = case.a, case.b
    ga, gb = a.E / (2 * (1 + a.nu)), b.E / (2 * (1 + b.nu))
    return 0.5 * ((1 - 2 * a.nu) / ga - (1 - 2 * b.nu) / gb) / ((1 - a.nu) / ga
                                                                 + (1 - b.nu) / gb)


def stick_ratio(beta: float, mu: float) -> float:
    """c / a of (SP1) (module doc); 1 without coupling."""
    target = abs(beta) / mu
    if target == 0.0:
        return 1.0

    def excess(y: float) -> float:  # k = tanh y resolves k -> 1
        k = math.tanh(y)
        return k * ellipk(1.0 / math.cosh(y) ** 2) / y - target

    if excess(40.0) >= 0.0:  # |β|/μ below π/80: c/a = tanh 40, 1 to double precision
        return 1.0
    return math.tanh(brentq(excess, 1e-12, 40.0, xtol=1e-14))


def slip_traction(X: np.ndarray, Y: np.ndarray, p_n: np.ndarray, a: float, c: float,
                  beta: float, mu: float) -> tuple[np.ndarray, np.ndarray]:
    """(p_x, p_y) on body a: sign(β) μ p r̂ in the slip annulus c < r < a, NaN in the
    stick disc, 0 outside the contact."""
    r = np.hypot(X, Y)
    with np.errstate(invalid="ignore", divide="ignore"):
        scale = np.where(r > 0, math.copysign(mu, beta) * p_n / r, 0.0)
    p_x, p_y = scale * X, scale * Y
    stick = r <= c
    p_x[stick], p_y[stick] = np.nan, np.nan
    outside = r >= a
    p_x[outside], p_y[outside] = 0.0, 0.0
    return p_x, p_y
