"""The far-field compliance the finite block lacks: the approach of a block against the
approach of a half-space.

The half-space's approach δ is measured against points at infinity; the block's
against its fixed bottom at depth H.  Under a load P the block's surface near the
contact moves less than the half-space's by a nearly rigid offset c₁ P / E (the
displacement the half-space has beyond the block, felt through it), so a held
half-space approach δ is the FE approach δ_FE = δ − c P with c = c₁(ν_a)/E_a +
c₁(ν_b)/E_b (:class:`fem_reference.contact.control.Control`, ``compliance``).

The same holds tangentially, with the opposite sign: the block, free at its sides,
also rocks about its bottom and is the more compliant (c₁ₜ < 0).  An imposed
half-space shift g_t,o is the FE shift D + c_t Q with Q the resultant on body a (it
opposes D), c_t = −(c₁ₜ(ν_a)/E_a + c₁ₜ(ν_b)/E_b), c₁ₜ measured like c₁ under a unit
tangential point force at the origin against Cerruti's surface displacement (Johnson
1985, Eq. 2.19 at z = 0), fitted by c₁ₜ + k r² + k' r² cos 2θ (the correction is not
axisymmetric):

    u_x(x, y) = (1 + ν)/(2π r) [2(1 − ν) + 2ν x²/r²].

c₁(ν) is measured once per mesh and ν from the block itself: a unit load with the
Hertz distribution of radius a (p = p₀ √(1 − r²/a²), p₀ = 3/(2πa²)) is applied through
the contact points' weights, and outside the loaded circle the block's vertical surface
displacement is compared with the half-space's (E = 1; Johnson 1985, Eq. 3.42b):

    u_z(r) = (1 − ν²) p₀/(2a) [(2a² − r²) sin⁻¹(a/r) + r a √(1 − a²/r²)],   r ≥ a,

which tends to the Boussinesq point load (1 − ν²)/(π r).  The difference is fitted by
c₁ + k r² on the top-surface nodes at 2a ≤ r ≤ 8a (the offset and the leading term of
its slow variation over the block size); c₁ is the value on the axis.
"""

from __future__ import annotations

import numpy as np

FIT_RADII = (2.0, 8.0)  # fit range in units of the load radius a


def hertz_outer_uz(r: np.ndarray, a: float, nu: float) -> np.ndarray:
    """Vertical surface displacement of a half-space (E = 1) at r ≥ a under a unit load
    with the Hertz distribution of radius a (module doc)."""
    p0 = 3.0 / (2.0 * np.pi * a * a)
    r = np.maximum(r, a)
    return (1.0 - nu**2) * p0 / (2.0 * a) * (
        (2.0 * a * a - r * r) * np.arcsin(a / r) + r * a * np.sqrt(1.0 - (a / r) ** 2))


def cerruti_ux(x: np.ndarray, y: np.ndarray, nu: float) -> np.ndarray:
    """u_x at the surface of a half-space (E = 1) under a unit point force along x at
    the origin (module doc)."""
    r = np.hypot(x, y)
    return (1.0 + nu) / (2.0 * np.pi * r) * (2.0 * (1.0 - nu) + 2.0 * nu * (x / r) ** 2)


def _solve(factor, free: np.ndarray, F: np.ndarray) -> np.ndarray:
    u = np.zeros_like(F)
    u[free] = factor.solve(F[free])
    return u


def _fit_ring(nodes: np.ndarray, a: float) -> np.ndarray:
    """Top-surface nodes at FIT_RADII (in units of a) from the axis."""
    r = np.hypot(nodes[0], nodes[1])
    ring = (r >= FIT_RADII[0] * a) & (r <= FIT_RADII[1] * a)
    return np.flatnonzero((np.abs(nodes[2]) <= 1e-9 * a) & ring)


def _axis_value(columns: list[np.ndarray], diff: np.ndarray) -> tuple[float, float]:
    """(constant term, largest residual) of the least-squares fit of ``diff``."""
    A = np.column_stack(columns)
    coef, *_ = np.linalg.lstsq(A, diff, rcond=None)
    return float(coef[0]), float(np.abs(A @ coef - diff).max())


def block_offset(factor, free: np.ndarray, surface_dofs: np.ndarray, f_unit: np.ndarray,
                 nodes: np.ndarray, a: float, nu: float) -> tuple[float, float]:
    """(c₁, spread): the normal offset of the block (E = 1, factorised free stiffness
    ``factor``) under the nodal forces ``f_unit`` at ``surface_dofs`` (a unit load pushing
    into the block, Hertz distribution of radius ``a``), and the largest residual of the
    fit.  ``nodes``: (3, nnodes) coordinates of the P2 nodes."""
    F = np.zeros(3 * nodes.shape[1])
    F[surface_dofs] = f_unit
    u = _solve(factor, free, F)
    idx = _fit_ring(nodes, a)
    r = np.hypot(nodes[0, idx], nodes[1, idx])
    diff = hertz_outer_uz(r, a, nu) - np.abs(u[3 * idx + 2])
    return _axis_value([np.ones(idx.size), (r / a) ** 2], diff)


def block_offset_t(factor, free: np.ndarray, nodes: np.ndarray, a: float, nu: float,
                   sym: float) -> tuple[float, float]:
    """(c₁ₜ, spread): the tangential offset of the block (E = 1) under a unit force along
    x at the surface node on the axis (1/``sym`` of it in a symmetric model), and the
    largest residual of the fit."""
    origin = int(np.argmin((nodes**2).sum(axis=0)))
    F = np.zeros(3 * nodes.shape[1])
    F[3 * origin] = 1.0 / sym
    u = _solve(factor, free, F)
    idx = _fit_ring(nodes, a)
    x, y = nodes[0, idx], nodes[1, idx]
    r2 = (x * x + y * y) / a**2
    diff = cerruti_ux(x, y, nu) - u[3 * idx]
    return _axis_value([np.ones(idx.size), r2, r2 * (x * x - y * y) / (x * x + y * y)], diff)
