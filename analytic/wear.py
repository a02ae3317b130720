"""Wear of a spherical pin under constant load (pin-on-disk, cases 4 and 5 of cases.md).

Archard's law integrated over the contact gives the worn volume exactly,
W = i_w P s (every contact point slides the distance s; formulation Eq. 18), whatever
the pressure distribution.  Two references translate W into a wear depth:

- **Argatov (2011)**, asymptotic (quasi-steady, uniform pressure) solution:
  contact radius a(s) = (a0⁴ + 4 i_w P s R / π)^(1/4), steady-state pressure
  p_max = P / (π a²).  cases.md gives the maximum wear depth as "w = a²/(2R)".
  Read literally that is the height of the paraboloid cap cut at the *contact* radius a,
  which includes the elastic flattening: at s = 0 it gives a0²/(2R) = δ0/2 although nothing
  has worn, and its cap volume π a⁴/(4R) = π a0⁴/(4R) + i_w P s violates Archard's
  balance by the constant π a0⁴/(4R).  The a0⁴ term of a(s) is the elastic part; the worn
  cap is the part that Archard's volume pays for: a paraboloid cap of height w has volume
  π R w² (= π a_w⁴ / 4R with a_w² = 2Rw), so

      w(s) = √(a⁴ - a0⁴) / (2R) = √(i_w P s / (π R))      (:func:`argatov_wear_depth`),

  which is 0 at s = 0, satisfies W = i_w P s exactly, and differs from the literal
  a²/(2R) (:func:`argatov_wear_depth_literal`) by a0⁴/(4 R a²) + O(a0⁸/a⁶): the two agree
  only asymptotically (s ≫ s_c, :func:`transition_distance`).
- **Hegadekatte et al. (2008)**: the worn spherical cap of height w, volume
  W = π (3R - w) w² / 3 = i_w P s, solved for w by Brent's method
  (:func:`hegadekatte_wear_depth`); the worn flat has radius √(2Rw - w²).  It is the exact
  sphere version of the paraboloid cap above: w_H / w_A - 1 = w/(6R) + O((w/R)²).

Orthotropic wear (formulation Eq. 19): i_w(θ) = √((i1 cos θ)² + (i2 sin θ)²), θ the
angle of the sliding direction from the tribological axis e1; for sliding along +x with
e1 at β from x, θ = -β.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq


def wear_coefficient(i1: float, i2: float, theta_deg: float) -> float:
    """i_w(θ) = √((i1 cos θ)² + (i2 sin θ)²) (formulation Eq. 19), θ in degrees."""
    t = math.radians(theta_deg)
    return math.hypot(i1 * math.cos(t), i2 * math.sin(t))


def sliding_angle(beta_deg: float, slide_angle_deg: float = 0.0) -> float:
    """θ of Eq. 19: the sliding direction's angle from e1, slide_angle - β (θ = -β along +x)."""
    return slide_angle_deg - beta_deg


def archard_volume(s, i_w: float, P: float) -> np.ndarray:
    """W = i_w P s [mm³]: Archard's law summed over the contact (formulation Eq. 18)."""
    return i_w * P * np.asarray(s, float)


def argatov_radius(s, a0: float, i_w: float, P: float, R: float) -> np.ndarray:
    """a(s) = (a0⁴ + 4 i_w P s R / π)^(1/4) (Argatov 2011)."""
    return (a0**4 + 4.0 * i_w * P * np.asarray(s, float) * R / math.pi) ** 0.25


def argatov_wear_depth(s, a0: float, i_w: float, P: float, R: float) -> np.ndarray:
    """Archard-consistent maximum wear depth √(a⁴ - a0⁴)/(2R) = √(i_w P s/(πR)), see module."""
    a = argatov_radius(s, a0, i_w, P, R)
    return np.sqrt(np.clip(a**4 - a0**4, 0.0, None)) / (2.0 * R)


def argatov_wear_depth_literal(s, a0: float, i_w: float, P: float, R: float) -> np.ndarray:
    """cases.md read literally: w = a(s)²/(2R) (includes the elastic a0 part; not 0 at s=0)."""
    return argatov_radius(s, a0, i_w, P, R) ** 2 / (2.0 * R)


def argatov_p_max(s, a0: float, i_w: float, P: float, R: float) -> np.ndarray:
    """Steady-state (uniform) pressure P / (π a(s)²) (Argatov 2011)."""
    return P / (math.pi * argatov_radius(s, a0, i_w, P, R) ** 2)


def paraboloid_cap_volume(w, R: float) -> np.ndarray:
    """Volume of the cap of height w of the paraboloid r²/(2R): π R w²."""
    return math.pi * R * np.asarray(w, float) ** 2


def cap_volume(w, R: float) -> np.ndarray:
    """Volume of the spherical cap of height w: π (3R - w) w² / 3 (Hegadekatte et al. 2008)."""
    w = np.asarray(w, float)
    return math.pi * (3.0 * R - w) * w * w / 3.0


def hegadekatte_wear_depth(s, i_w: float, P: float, R: float) -> np.ndarray:
    """w solving π (3R - w) w² / 3 = i_w P s on [0, 2R] (Brent; Hegadekatte et al. 2008)."""
    s = np.asarray(s, float)
    out = np.empty(s.shape)
    for k, W in np.ndenumerate(archard_volume(s, i_w, P)):
        if W <= 0.0:
            out[k] = 0.0
            continue
        if W > cap_volume(2.0 * R, R):
            raise ValueError(f"worn volume {W} exceeds the whole sphere")
        guess = math.sqrt(W / (math.pi * R))  # paraboloid cap, a lower bound
        hi = min(2.0 * R, 2.0 * guess + 1e-300)
        out[k] = brentq(lambda w, W=W: float(cap_volume(w, R)) - W, 0.0, hi,
                        xtol=1e-300, rtol=4.0 * np.finfo(float).eps, maxiter=200)
    return out


def worn_flat_radius(w, R: float) -> np.ndarray:
    """Radius of the worn flat of a sphere cut at depth w: √(2Rw - w²)."""
    w = np.asarray(w, float)
    return np.sqrt(np.clip(2.0 * R * w - w * w, 0.0, None))


def transition_distance(a0: float, i_w: float, P: float, R: float) -> float:
    """s_c at which the wear depth √(i_w P s/(πR)) equals the elastic approach δ0 = a0²/R.

    Below a few s_c the pressure is still closer to Hertz than to uniform, and the
    asymptotic (Argatov) radius and pressure are not yet accurate.
    """
    delta0 = a0 * a0 / R
    return math.pi * R * delta0 * delta0 / (i_w * P)
