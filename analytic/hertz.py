"""Hertz contact of a sphere (paraboloid h = r²/2R) on a half-space (Johnson 1985, §4.2, §3.7).

Two bodies of moduli (E_a, ν_a), (E_b, ν_b) enter through 1/E* = (1-ν_a²)/E_a + (1-ν_b²)/E_b
(for two equal steels E* = E / (2(1-ν²))); the subsurface stresses of one body depend on
the pressure and that body's ν only.  Sign convention: tensile stress positive, the
pressure p > 0 compressive, z >= 0 the depth into the body.

- :func:`hertz` — a0 = (3PR/4E*)^(1/3), p0 = 3P/(2πa²), approach δ = a²/R (§4.2);
  :func:`hertz_from_approach` for displacement control, P = (4/3) E* R^(1/2) δ^(3/2).
- :func:`pressure`, :func:`gap` — p(r) = p0 √(1 - r²/a²) (§3.4), the surface gap
  outside the contact (from the surface displacement of §3.4).
- :func:`axis_stresses`, :func:`axis_von_mises`, :func:`axis_vm_max` — σ_r = σ_θ and σ_z on
  r = 0 (eq. 3.45) and the maximum of σ_VM = |σ_z - σ_r| along the axis.
- :func:`surface_stresses` — σ_r, σ_θ at z = 0 (§3.4).
- :func:`full_field` — every component at any (x, y, z >= 0), the explicit equations of
  Hamilton & Goodman (1966) in the form of Hamilton (1983), normal-load part.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize_scalar


@dataclass(frozen=True)
class Hertz:
    """The Hertz solution of one normal load: P [N], R [mm], E* [MPa] -> a, p0, δ."""

    P: float
    R: float
    E_star: float
    a: float
    p0: float
    delta: float

    @property
    def area(self) -> float:
        return math.pi * self.a**2


def hertz(P: float, R: float, E_star: float) -> Hertz:
    """Load control: a = (3PR/4E*)^(1/3), p0 = 3P/(2πa²), δ = a²/R (Johnson 1985 §4.2)."""
    a = (3.0 * P * R / (4.0 * E_star)) ** (1.0 / 3.0)
    return Hertz(P=P, R=R, E_star=E_star, a=a, p0=3.0 * P / (2.0 * math.pi * a * a),
                 delta=a * a / R)


def hertz_from_approach(delta: float, R: float, E_star: float) -> Hertz:
    """Displacement control: a = √(Rδ), P = (4/3) E* √R δ^(3/2) (Johnson 1985 §4.2)."""
    P = 4.0 / 3.0 * E_star * math.sqrt(R) * delta**1.5
    a = math.sqrt(R * delta)
    return Hertz(P=P, R=R, E_star=E_star, a=a, p0=3.0 * P / (2.0 * math.pi * a * a),
                 delta=delta)


def pressure(r, a: float, p0: float) -> np.ndarray:
    """p(r) = p0 √(1 - r²/a²) for r < a, 0 outside (Johnson 1985 §3.4)."""
    r = np.asarray(r, float)
    return p0 * np.sqrt(np.clip(1.0 - (r / a) ** 2, 0.0, None))


def gap(r, a: float, R: float) -> np.ndarray:
    """Normal gap between the deformed surfaces, 0 inside the contact (Johnson 1985 §3.4).

    g(r) = r²/2R - δ + ū(r) with δ = a²/R and the combined surface displacement outside
    the contact ū = [(2a² - r²) asin(a/r) + a √(r² - a²)] / (πR), for r >= a.
    """
    r = np.abs(np.asarray(r, float))
    ro = np.maximum(r, a)
    u = ((2 * a * a - ro * ro) * np.arcsin(a / ro) + a * np.sqrt(ro * ro - a * a)) / (math.pi * R)
    return np.where(r > a, ro * ro / (2 * R) - a * a / R + u, 0.0)


def axis_stresses(z, a: float, p0: float, nu: float) -> tuple[np.ndarray, np.ndarray]:
    """(σ_r = σ_θ, σ_z) on the axis r = 0 at depth z (Johnson 1985 eq. 3.45).

    σ_r/p0 = -(1+ν)[1 - (z/a) atan(a/z)] + 1/(2(1 + z²/a²)),  σ_z/p0 = -1/(1 + z²/a²).
    """
    zeta = np.asarray(z, float) / a
    sr = -(1.0 + nu) * (1.0 - zeta * np.arctan2(1.0, zeta)) + 0.5 / (1.0 + zeta**2)
    sz = -1.0 / (1.0 + zeta**2)
    return p0 * sr, p0 * sz


def axis_von_mises(z, a: float, p0: float, nu: float) -> np.ndarray:
    """σ_VM on the axis: with σ_r = σ_θ and no shear, σ_VM = |σ_z - σ_r| = 2 τ1."""
    sr, sz = axis_stresses(z, a, p0, nu)
    return np.abs(sz - sr)


def axis_vm_max(nu: float) -> tuple[float, float]:
    """(max σ_VM / p0, its depth z/a) on the axis, maximising eq. 3.45 numerically.

    For ν = 0.3: 0.6200 p0 at z = 0.4804 a (Johnson: τ1 = 0.31 p0 at z = 0.48 a).
    """
    res = minimize_scalar(lambda t: -axis_von_mises(t, 1.0, 1.0, nu), bounds=(0.0, 3.0),
                          method="bounded", options={"xatol": 1e-10})
    return float(-res.fun), float(res.x)


def surface_stresses(r, a: float, p0: float, nu: float) -> tuple[np.ndarray, np.ndarray]:
    """(σ_r, σ_θ) at z = 0 (Johnson 1985 §3.4); σ_z = -p(r).

    Inside: σ_r/p0 = (1-2ν)/3 (a²/r²)[1 - (1 - r²/a²)^(3/2)] - √(1 - r²/a²),
            σ_θ/p0 = -(1-2ν)/3 (a²/r²)[1 - (1 - r²/a²)^(3/2)] - 2ν √(1 - r²/a²);
    outside: σ_r = -σ_θ = (1-2ν) a² p0 / (3 r²).  At the edge σ_r = (1-2ν) p0 / 3.
    """
    r = np.abs(np.asarray(r, float))
    rho2 = (r / a) ** 2
    s = np.sqrt(np.clip(1.0 - rho2, 0.0, None))
    with np.errstate(divide="ignore", invalid="ignore"):
        # (1 - s^3) / rho2, with its limit 3/2 at r = 0
        g = np.where(rho2 > 1e-8, (1.0 - s**3) / np.where(rho2 > 0, rho2, 1.0), 1.5 - 0.375 * rho2)
    k = (1.0 - 2.0 * nu) / 3.0
    return p0 * (k * g - s), p0 * (-k * g - 2.0 * nu * s)


def full_field(x, y, z, a: float, p0: float, nu: float) -> dict[str, np.ndarray]:
    """All six stress components under the Hertz pressure, closed form.

    Hamilton & Goodman (1966); explicit form of Hamilton (1983), normal-load part, with
    A = r² + z² - a², S = √(A² + 4a²z²), M = √((S+A)/2), N = √((S-A)/2), φ = atan(a/M),
    G = M² - N² + zM - aN, H = 2MN + aM + zN (lengths in units of a below):

    σ_x = (1+ν)zφ + [ (y²-x²)/r² ((1-ν)Nz² - (1-2ν)(NS + 2AN + 1)/3 - νMz)
                      - N(x² + 2νy²) - M x² z / S ] / r²
    σ_z = -N + zM/S
    τ_xy = xy(1-2ν)/r⁴ (-Nr² + 2N(S + 2A)/3 - z(zN + M) + 2/3) + xyz/r⁴ (-Mr²/S - zN + M)
    τ_xz = -z (xN/S - xzH/(G² + H²)),   σ_y, τ_yz by exchanging x and y; all times p0.
    Within r < 1e-4 a of the axis eq. 3.45 is used (error O(r²/a²) <= 1e-8 p0).  Verified
    against quadrature of the Boussinesq kernel in the tests.
    """
    X, Y, Z = np.broadcast_arrays(*(np.asarray(v, float) / a for v in (x, y, z)))
    r2 = X * X + Y * Y
    A = r2 + Z * Z - 1.0
    S = np.sqrt(A * A + 4.0 * Z * Z)
    M = np.sqrt(np.clip((S + A) / 2.0, 0.0, None))
    N = np.sqrt(np.clip((S - A) / 2.0, 0.0, None))
    with np.errstate(divide="ignore", invalid="ignore"):
        phi = np.arctan2(1.0, M)
        G = M * M - N * N + Z * M - N
        H = 2.0 * M * N + M + Z * N
        iS = np.where(S > 0.0, 1.0 / S, 0.0)  # S = 0 only on the edge circle at z = 0
        ir2 = np.where(r2 > 0.0, 1.0 / r2, 0.0)
        GH = G * G + H * H
        iGH = np.where(GH > 0.0, 1.0 / GH, 0.0)
        br = (1.0 - nu) * N * Z * Z - (1.0 - 2.0 * nu) * (N * S + 2.0 * A * N + 1.0) / 3.0 \
            - nu * M * Z
        sxx = (1.0 + nu) * Z * phi + ir2 * ((Y * Y - X * X) * ir2 * br
                                            - N * (X * X + 2.0 * nu * Y * Y) - M * X * X * Z * iS)
        syy = (1.0 + nu) * Z * phi + ir2 * ((X * X - Y * Y) * ir2 * br
                                            - N * (Y * Y + 2.0 * nu * X * X) - M * Y * Y * Z * iS)
        szz = -N + Z * M * iS
        bxy = -N * r2 + 2.0 * N * (S + 2.0 * A) / 3.0 - Z * (Z * N + M) + 2.0 / 3.0
        sxy = X * Y * ir2 * ir2 * ((1.0 - 2.0 * nu) * bxy + Z * (-M * r2 * iS - Z * N + M))
        t = -Z * (N * iS - Z * H * iGH)
    sxz, syz = t * X, t * Y
    axis = r2 < 1e-8  # r < 1e-4 a: the 1/r² cancellation would cost ~1e-16 a²/r²
    if np.any(axis):
        sr, sz = axis_stresses(Z[axis], 1.0, 1.0, nu)
        sxx, syy, szz = (np.where(axis, 0.0, s) for s in (sxx, syy, szz))
        sxx[axis], syy[axis], szz[axis] = sr, sr, sz
        sxy, sxz, syz = (np.where(axis, 0.0, s) for s in (sxy, sxz, syz))
    return {k: p0 * np.asarray(v) for k, v in
            zip(("sxx", "syy", "szz", "sxy", "sxz", "syz"), (sxx, syy, szz, sxy, sxz, syz),
                strict=True)}
