"""Stresses beneath a sphere in full sliding (Hamilton 1983), by point-force quadrature.

Tractions on the body whose stresses are computed (z >= 0 its depth): the Hertz pressure
p = p0 √(1 - r²/a²) and the friction traction q_x = μ p in **+x** (identical materials:
the pressure stays Hertzian).  The trailing edge, where σ_xx is tensile, is then x = -a.
For the body that slides in +x over its counterpart, the traction it feels is -μp: use
``mu -> -mu`` or mirror x (see :mod:`analytic.solver` for the bodies' conventions).

The field is :func:`analytic.quadrature.hertzian_traction_stresses` with
(p0, μ p0): numerical quadrature of the Boussinesq and Cerruti solutions (accuracy < 1e-8 p0 for
z > 1e-4 a with the default rules, < 1e-5 p0 down to z = 1e-6 a; the surface z = 0 is the
exact principal-value limit).

Closed forms used as checks: at the trailing edge (x, y, z) = (-a, 0, 0)

    σ_xx = p0 [(1-2ν)/3 + π(4+ν)μ/8]        (Hamilton 1983, the maximum tensile stress)
    σ_yy = p0 [-(1-2ν)/3 + 3πνμ/8]          (identified from the quadrature, see tests)

and σ_zz = σ_xz = σ_yz = σ_xy = 0 there, so the surface von Mises stress at the edge is
known in closed form (:func:`trailing_edge_von_mises`).  The surface maximum of σ_VM on
y = 0 is a cusp exactly at the trailing edge for every μ > 0 (the tractions vanish there
like a square root on both sides).

The maximum of σ_VM over the xz plane (:func:`vm_max_xz`) lies below the surface for
small μ and jumps to the trailing edge when the edge value overtakes the subsurface
maximum (:func:`surface_jump`; measured μ = 0.3047 for ν = 0.3, Johnson 1985 §7.1 quotes
"about 0.3").  Measured for ν = 0.3 (σ_VM,max/p0 at (x/a, z/a)): μ = 0: 0.6200 (0, 0.481);
0.15: 0.6300 (0.166, 0.467); 0.25: 0.6476 (0.270, 0.444); 0.35: 0.7294 (-1, 0);
0.5: 0.9569 (-1, 0); 0.65: 1.1857 (-1, 0).  A grid sampling of the surface does not
resolve the cusp: on a lattice of cell size h the sampled surface maximum falls short of
the edge value by O(√(h/a)) and may sit at the smooth surface maximum inside the contact
(x ≈ -0.55 a for μ = 0.5).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq, minimize, minimize_scalar

from cases.result import von_mises

from .pointforce import COMPONENTS
from .quadrature import hertzian_traction_stresses


def sliding_sphere_stresses(x, y, z, a: float, p0: float, mu: float, nu: float,
                            **quad) -> dict[str, np.ndarray]:
    """σ_ij under p = p0 √(1 - r²/a²) and q_x = μ p (in +x on this body), z >= 0 depth.

    Returns the dict ``sxx, syy, szz, sxy, sxz, syz`` [units of p0]; ``quad`` passes
    ``n_phi``/``n_r`` to the quadrature.  μ = 0 is the Hertz field (Johnson eq. 3.45 on
    the axis; Hamilton & Goodman 1966 everywhere).
    """
    return hertzian_traction_stresses(x, y, z, a, p0=p0, qx0=mu * p0, nu=nu, **quad)


def trailing_edge_stresses(mu: float, nu: float) -> tuple[float, float]:
    """(σ_xx, σ_yy)/p0 at (x, y, z) = (-a, 0, 0), see the module docstring (Hamilton 1983)."""
    k = (1.0 - 2.0 * nu) / 3.0
    return k + np.pi * (4.0 + nu) * mu / 8.0, -k + 3.0 * np.pi * nu * mu / 8.0


def trailing_edge_von_mises(mu: float, nu: float) -> float:
    """σ_VM/p0 at the trailing edge: plane stress √(σx² + σy² - σx σy) of the closed form."""
    sx, sy = trailing_edge_stresses(mu, nu)
    return float(np.sqrt(sx * sx + sy * sy - sx * sy))


@dataclass(frozen=True)
class VmMax:
    """Maximum of σ_VM/p0 on the plane y = 0 for one μ (coordinates in units of a).

    ``value, x, z`` the global maximum; ``sub_*`` the subsurface local maximum tracked
    from the best interior grid point (``sub_z == 0`` when it has merged with the surface,
    e.g. μ >= 0.4 for ν = 0.3); ``surf_*`` the surface maximum (z = 0).
    """

    mu: float
    value: float
    x: float
    z: float
    sub_value: float
    sub_x: float
    sub_z: float
    surf_value: float
    surf_x: float

    @property
    def at_surface(self) -> bool:
        return self.z == 0.0


def _vm_point(x: float, z: float, mu: float, nu: float) -> float:
    s = sliding_sphere_stresses(np.array([x]), np.zeros(1), np.array([max(z, 0.0)]), 1.0,
                                1.0, mu, nu)
    return float(von_mises(*(s[c] for c in COMPONENTS))[0])


def _unit_fields(x, z, nu: float, n_phi: int, n_r: int):
    X, Z = np.meshgrid(x, z, indexing="ij")
    kw = dict(n_phi=n_phi, n_r=n_r)
    N = hertzian_traction_stresses(X, 0 * X, Z, 1.0, p0=1.0, nu=nu, **kw)
    T = hertzian_traction_stresses(X, 0 * X, Z, 1.0, qx0=1.0, nu=nu, **kw)
    return N, T


def _refine_sub(x0: float, z0: float, mu: float, nu: float) -> tuple[float, float, float]:
    """Local maximum of σ_VM in z > 0 from (x0, z0); Nelder–Mead on (x, z)."""
    res = minimize(lambda v: -_vm_point(v[0], v[1], mu, nu), np.array([x0, z0]),
                   method="Nelder-Mead",
                   options={"xatol": 1e-5, "fatol": 1e-10, "initial_simplex":
                            np.array([[x0, z0], [x0 + 0.03, z0], [x0, z0 + 0.03]])})
    return float(-res.fun), float(res.x[0]), float(max(res.x[1], 0.0))


def vm_max_sweep(mus, nu: float, *, x_range: tuple[float, float] = (-1.5, 1.5),
                 z_max: float = 1.2, nx: int = 49, nz: int = 25) -> list[VmMax]:
    """:func:`vm_max_xz` for several μ, sharing the coarse fields (stresses are linear in μ).

    Coarse search on an nx × nz grid of (x/a, z/a) with a cheap quadrature rule, then the
    subsurface maximum is refined by Nelder–Mead with the default rule, and the surface
    maximum is taken as the larger of the trailing-edge closed form and a bounded 1-D
    refinement of the best surface point away from the edges.
    """
    x = np.linspace(*x_range, nx)
    z = np.linspace(0.0, z_max, nz)
    N, T = _unit_fields(x, z, nu, n_phi=48, n_r=24)
    out = []
    for mu in np.atleast_1d(mus).astype(float):
        vm = von_mises(*(N[c] + mu * T[c] for c in COMPONENTS))
        sub = vm[:, 1:]
        i, k = np.unravel_index(int(np.argmax(sub)), sub.shape)
        sv, sx, sz = _refine_sub(x[i], z[k + 1], mu, nu)
        # surface: the cusp at the trailing edge x = -a (x = +a for mu < 0) ...
        edge_x = -1.0 if mu >= 0.0 else 1.0
        fv, fx = trailing_edge_von_mises(abs(mu), nu), edge_x
        # ... or a smooth maximum inside the contact or outside it
        j = int(np.argmax(np.where(np.abs(np.abs(x) - 1.0) < 1e-12, -np.inf, vm[:, 0])))
        lo, hi = x[max(j - 1, 0)], x[min(j + 1, nx - 1)]
        r = minimize_scalar(lambda t, mu=mu: -_vm_point(t, 0.0, mu, nu), bounds=(lo, hi),
                            method="bounded", options={"xatol": 1e-6})
        if -r.fun > fv and abs(abs(r.x) - 1.0) > 1e-3:  # the edge cusp is the closed form
            fv, fx = float(-r.fun), float(r.x)
        if fv >= sv:
            out.append(VmMax(mu, fv, fx, 0.0, sv, sx, sz, fv, fx))
        else:
            out.append(VmMax(mu, sv, sx, sz, sv, sx, sz, fv, fx))
    return out


def vm_max_xz(mu: float, nu: float, **kw) -> VmMax:
    """Max σ_VM/p0 over the xz plane (y = 0) and its location (x/a, z/a) for friction μ."""
    return vm_max_sweep([mu], nu, **kw)[0]


@dataclass(frozen=True)
class SurfaceJump:
    """The friction coefficient at which max σ_VM jumps to the surface, and the two maxima.

    At μ = ``mu`` the trailing-edge value (closed form) equals ``value``, the subsurface
    local maximum at (``sub_x``, ``sub_z``) in units of a.
    """

    mu: float
    value: float
    sub_x: float
    sub_z: float


def surface_jump(nu: float, bracket: tuple[float, float] = (0.2, 0.45),
                 start: tuple[float, float] | None = None) -> SurfaceJump:
    """Root of σ_VM(trailing edge, closed form) - σ_VM(subsurface local maximum) in μ.

    The subsurface maximum is tracked by Nelder–Mead from ``start`` = (x/a, z/a) (default:
    the location found by :func:`vm_max_xz` at μ = bracket[0]).  For ν = 0.3 the root is
    μ = 0.3047 (σ_VM = 0.661 p0 at x = 0.33 a, z = 0.42 a).
    """
    if start is None:
        first = vm_max_xz(bracket[0], nu)
        start = (first.sub_x, first.sub_z)
    state = [start[0], start[1], np.nan]

    def diff(mu: float) -> float:
        v, x, z = _refine_sub(state[0], state[1], mu, nu)
        state[:] = [x, z, v]
        return trailing_edge_von_mises(mu, nu) - v

    mu = float(brentq(diff, *bracket, xtol=1e-7))
    diff(mu)
    return SurfaceJump(mu=mu, value=state[2], sub_x=state[0], sub_z=state[1])
