"""Orthotropic friction and wear norms, the associated sliding rule and its projection.

Vectors are given by their x and y components (arrays of any common shape); the
tribological axes e1, e2 are rotated by beta (degrees, counter-clockwise) from x, y.
"""

from __future__ import annotations

import numpy as np

from cases.model import Friction


def to_axes(vx, vy, beta: float):
    """Components along (e1, e2) of a vector given along (x, y) (Eq. 11-12)."""
    c, s = np.cos(np.radians(beta)), np.sin(np.radians(beta))
    return c * vx + s * vy, -s * vx + c * vy


def from_axes(v1, v2, beta: float):
    """Inverse of :func:`to_axes`."""
    c, s = np.cos(np.radians(beta)), np.sin(np.radians(beta))
    return c * v1 - s * v2, s * v1 + c * v2


def mu_norm(px, py, fr: Friction):
    """Elliptic norm ||p_t||_mu = sqrt((p_e1/mu1)^2 + (p_e2/mu2)^2) (Eq. 9)."""
    p1, p2 = to_axes(px, py, fr.beta)
    return np.hypot(p1 / fr.mu1, p2 / fr.mu2)


def mu_dual_norm(gx, gy, fr: Friction):
    """Dual norm ||g||*_mu = sqrt((mu1 g_e1)^2 + (mu2 g_e2)^2) (Eq. 10)."""
    g1, g2 = to_axes(gx, gy, fr.beta)
    return np.hypot(fr.mu1 * g1, fr.mu2 * g2)


def wear_norm(gx, gy, i1: float, i2: float, beta: float):
    """||g||_i = sqrt((i1 g_e1)^2 + (i2 g_e2)^2) (Eq. 21) = i_w(theta) ||g|| (Eq. 19-20)."""
    g1, g2 = to_axes(gx, gy, beta)
    return np.hypot(i1 * g1, i2 * g2)


def wear_coefficient(theta_deg, i1: float, i2: float):
    """i_w(theta) = sqrt((i1 cos theta)^2 + (i2 sin theta)^2) (Eq. 19)."""
    t = np.radians(theta_deg)
    return np.hypot(i1 * np.cos(t), i2 * np.sin(t))


def mu_squared(gx, gy, fr: Friction):
    """The product M^2 g of Eq. 13-16, with M = diag(mu1, mu2) in the tribological axes."""
    g1, g2 = to_axes(gx, gy, fr.beta)
    return from_axes(fr.mu1**2 * g1, fr.mu2**2 * g2, fr.beta)


def project(px, py, rho, fr: Friction):
    """P_E_rho of Eq. 17: radial scaling onto the friction ellipse ||p||_mu <= rho."""
    norm = mu_norm(px, py, fr)
    outside = norm > rho  # then norm > 0; elsewhere no division (a tiny norm overflowed)
    scale = np.where(outside, rho / np.where(outside, norm, 1.0), 1.0)
    return px * scale, py * scale


def slip_traction(gx, gy, p_n, fr: Friction):
    """Traction of a slipping point, p_t = -p_n M^2 g / ||g||*_mu (Eq. 13), g != 0."""
    mx, my = mu_squared(gx, gy, fr)
    d = mu_dual_norm(gx, gy, fr)
    return -p_n * mx / d, -p_n * my / d
