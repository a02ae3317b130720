"""Stresses of a point force on the surface of an elastic half-space (Johnson 1985, §3.2).

Conventions (``docs/formulation.md``, erratum 9): z >= 0 is the depth into the
body, the force acts at the surface origin, the arguments are the field point *relative
to the load point* (x_field - x_load), tensile stress is positive.

- :func:`boussinesq` — unit normal force pressing on the surface (in +z, into the body),
  Johnson 1985 §3.2, written in cylindrical components and rotated to x, y.
- :func:`cerruti` — unit tangential force in +x on the surface, Johnson 1985 §3.2 (formulation
  Appendix A, eq. 40).
- :func:`cerruti_y` — unit tangential force in +y (x and y exchanged).

Each returns ``(sxx, syy, szz, sxy, sxz, syz)`` per unit force [1/length²].  At z = 0 the
normal stresses are singular at the origin only; every expression is written without a
1/r² that cancels (``(1 - z/ρ)/r² = 1/(ρ(ρ+z))``), so r → 0 at z > 0 is regular.
"""

from __future__ import annotations

import numpy as np

Stress6 = tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]
COMPONENTS = ("sxx", "syy", "szz", "sxy", "sxz", "syz")


def boussinesq(x, y, z, nu: float) -> Stress6:
    """Unit normal (compressive) point force (Boussinesq; Johnson 1985 §3.2).

    σ_r = [(1-2ν)/(ρ(ρ+z)) - 3 z r²/ρ⁵] / 2π,   σ_θ = -(1-2ν)[1/(ρ(ρ+z)) - z/ρ³] / 2π,
    σ_z = -3 z³/(2π ρ⁵),   τ_rz = -3 r z²/(2π ρ⁵);  r² = x² + y², ρ² = r² + z².
    """
    x, y, z = np.asarray(x, float), np.asarray(y, float), np.asarray(z, float)
    r2 = x * x + y * y
    rho = np.sqrt(r2 + z * z)
    rho5 = rho**5
    g = 1.0 / (rho * (rho + z))  # (1 - z/ρ)/r², regular as r -> 0
    c = (1.0 - 2.0 * nu) / (2.0 * np.pi)
    k = 3.0 * z / (2.0 * np.pi * rho5)
    s_theta = -c * (g - z / rho**3)
    # σ_xx = σ_θ + (σ_r - σ_θ) x²/r², with (σ_r - σ_θ)/r² = c (2g - z/ρ³)/r² - k and
    # 2g - z/ρ³ = (2ρ + z)(ρ - z)/(ρ³(ρ + z)) = r² (2ρ + z)/(ρ³ (ρ + z)²): no 1/r² left
    d = c * (2.0 * rho + z) / (rho**3 * (rho + z) ** 2) - k
    sxx = s_theta + d * x * x
    syy = s_theta + d * y * y
    sxy = d * x * y
    szz = -3.0 * z**3 / (2.0 * np.pi * rho5)
    t = -3.0 * z * z / (2.0 * np.pi * rho5)  # τ_rz / r
    return sxx, syy, szz, sxy, t * x, t * y


def cerruti(x, y, z, nu: float) -> Stress6:
    """Unit tangential point force in +x (Cerruti; Johnson 1985 §3.2).

    σ_x = -[3x³/ρ⁵ - (1-2ν)(x/ρ³ - 3x/(ρ(ρ+z)²) + x³/(ρ³(ρ+z)²) + 2x³/(ρ²(ρ+z)³))] / 2π
    σ_y = -[3xy²/ρ⁵ - (1-2ν)(x/ρ³ - x/(ρ(ρ+z)²) + xy²/(ρ³(ρ+z)²) + 2xy²/(ρ²(ρ+z)³))] / 2π
    τ_xy = -[3x²y/ρ⁵ - (1-2ν)(-y/(ρ(ρ+z)²) + x²y/(ρ³(ρ+z)²) + 2x²y/(ρ²(ρ+z)³))] / 2π
    σ_z = -3xz²/(2πρ⁵),  τ_xz = -3x²z/(2πρ⁵),  τ_yz = -3xyz/(2πρ⁵).
    At z = 0, y = 0, x < 0 (behind the force): σ_x = +(1+ν)/(π x²), tensile (erratum 9).
    """
    x, y, z = np.asarray(x, float), np.asarray(y, float), np.asarray(z, float)
    rho = np.sqrt(x * x + y * y + z * z)
    rz = rho + z
    i2pi = 1.0 / (2.0 * np.pi)
    m = 1.0 - 2.0 * nu
    rho3, rho5 = rho**3, rho**5
    e1 = 1.0 / (rho3 * rz * rz) + 2.0 / (rho * rho * rz**3)  # multiplies x^3, xy^2, x^2 y
    sxx = -i2pi * (3.0 * x**3 / rho5 - m * (x / rho3 - 3.0 * x / (rho * rz * rz) + x**3 * e1))
    syy = -i2pi * (3.0 * x * y * y / rho5 - m * (x / rho3 - x / (rho * rz * rz) + x * y * y * e1))
    sxy = -i2pi * (3.0 * x * x * y / rho5 - m * (-y / (rho * rz * rz) + x * x * y * e1))
    k = -3.0 * i2pi / rho5
    return sxx, syy, k * x * z * z, sxy, k * x * x * z, k * x * y * z


def cerruti_y(x, y, z, nu: float) -> Stress6:
    """Unit tangential point force in +y: :func:`cerruti` with x and y exchanged."""
    sxx, syy, szz, sxy, sxz, syz = cerruti(y, x, z, nu)
    return syy, sxx, szz, sxy, syz, sxz


def combined(x, y, z, nu: float, p: float, qx: float, qy: float) -> Stress6:
    """``p·boussinesq + qx·cerruti + qy·cerruti_y``, fused for speed (same formulas).

    With L = qx x + qy y, F = 3/ρ⁵ - (1-2ν)(1/(ρ³(ρ+z)²) + 2/(ρ²(ρ+z)³)), B = 1/(ρ(ρ+z)²),
    the tangential part of :func:`cerruti` is
    σ_x = -[x² F L - (1-2ν) L/ρ³ + (1-2ν) B (3 qx x + qy y)] / 2π,
    σ_y = -[y² F L - (1-2ν) L/ρ³ + (1-2ν) B (qx x + 3 qy y)] / 2π,
    τ_xy = -[x y F L + (1-2ν) B (qx y + qy x)] / 2π,  (σ_z, τ_xz, τ_yz) = -3 z L (z, x, y)/(2πρ⁵).
    """
    x, y, z = np.asarray(x, float), np.asarray(y, float), np.asarray(z, float)
    m = 1.0 - 2.0 * nu
    rho = np.sqrt(x * x + y * y + z * z)
    irho = 1.0 / rho
    irz = 1.0 / (rho + z)
    irho2 = irho * irho
    irho3 = irho2 * irho
    irho5 = irho3 * irho2
    irz2 = irz * irz
    k = (-1.5 / np.pi) * irho5
    kz = k * z
    sxx = np.zeros_like(rho)
    syy = np.zeros_like(rho)
    sxy = np.zeros_like(rho)
    szz = np.zeros_like(rho)
    sxz = np.zeros_like(rho)
    syz = np.zeros_like(rho)
    if p != 0.0:
        c = p * m / (2.0 * np.pi)
        g = irho * irz
        s_theta = -c * (g - z * irho3)
        d = c * (2.0 * rho + z) * irho3 * irz2 + p * kz
        sxx += s_theta + d * x * x
        syy += s_theta + d * y * y
        sxy += d * x * y
        t = p * kz * z
        szz += t * z
        sxz += t * x
        syz += t * y
    if qx != 0.0 or qy != 0.0:
        i2pi = -1.0 / (2.0 * np.pi)
        L = qx * x + qy * y
        B = m * irho * irz2
        FL = (3.0 * irho5 - m * irz2 * (irho3 + 2.0 * irho2 * irz)) * L
        mL = m * irho3 * L
        sxx += i2pi * (x * x * FL - mL + B * (3.0 * qx * x + qy * y))
        syy += i2pi * (y * y * FL - mL + B * (qx * x + 3.0 * qy * y))
        sxy += i2pi * (x * y * FL + B * (qx * y + qy * x))
        t = kz * L
        szz += t * z
        sxz += t * x
        syz += t * y
    return sxx, syy, szz, sxy, sxz, syz


def surface_limit_coefficients(nu: float) -> dict[str, np.ndarray]:
    """Local (delta-like) parts of the kernels as z → 0+, per unit traction at the point.

    For a traction t smooth at the field point, ``lim_{z→0+} ∫∫ T(x-x', z) t(x') dA'``
    equals the principal value of the z = 0 kernel plus ``c · t(x)``, with ``c`` the
    limit of the kernel integrated over a disc centred on the field point.  Rows: normal,
    x-, y-force; columns: :data:`COMPONENTS`.  Normal force: σ_zz gets -1 (σ_zz = -p at
    the surface), σ_xx = σ_yy get -1 (from -3zx²/2πρ⁵) + (1-2ν)/2 (from the (1-2ν)zy²/r²ρ³
    term), i.e. -(1+2ν)/2, which is the Hertz surface stress at the centre (Johnson
    §3.4).  Tangential force: τ_xz (τ_yz) gets -1 (τ_xz = -q_x at the surface); the odd
    kernels have no local part.
    """
    c = np.zeros((3, 6))
    c[0, 0] = c[0, 1] = -(1.0 + 2.0 * nu) / 2.0
    c[0, 2] = -1.0
    c[1, 4] = -1.0
    c[2, 5] = -1.0
    return {"normal": c[0], "x": c[1], "y": c[2]}
