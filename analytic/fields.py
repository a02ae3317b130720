"""The closed-form fields of a case on its grid: the Hertz pressure, the tangential
tractions of full sliding and Cattaneo–Mindlin, the surface fields and the σ_VM planes of
the analytic solver (:mod:`analytic.solver`).

Conventions (cases/model.py): the surface fields ``p_n, p_x, p_y`` are the tractions on
body a (p_n > 0 compressive), sampled at the cell centres (x[i], y[j]).  Subsurface planes
are reported in ``case.stress.body`` with z >= 0 the depth into it: 'xz' at y = y0
with s = grid.x, 'yz' at x = x0 with s = grid.y, z = stress.z, (x0, y0) the planes'
centre ``case.plane_centre``.

- Body a: global z points into it, so its frame (x, y, z) is the half-space frame of the
  point-force kernels; it carries (p_x, p_y, p_n).
- Body b: depth ζ = -z.  The right-handed frame (x, -y, ζ) (a rotation by π about x)
  is a kernel frame; in it b carries the pressure p_n into b and the tangential traction
  -(p_x, p_y), which reads (-p_x, +p_y).  So b's stresses are the kernel field at
  (x, -y, ζ) with tractions (-p_x, +p_y, p_n), and on the way back to the axes (x, y, ζ)
  σ_xy and σ_yζ change sign (σ_xζ, the normal stresses and σ_VM do not).  The sign of
  ``sxz`` and ``syz`` is therefore that of the components on the depth axis.
  E.g. a sliding in +x over b: the traction on b is +μp along x and b's σ_xx is tensile
  at its trailing edge x = -a.

The normal part of the planes is the Hamilton–Goodman closed form
(:func:`analytic.hertz.full_field`), the tangential part the point-force quadrature
(:mod:`analytic.quadrature`); both are tested against each other.
"""

from __future__ import annotations

import math

import numpy as np

from cases.model import Case, CaseError
from cases.result import OPEN, SLIP, STICK, Plane, vm_max_location, von_mises

from . import hertz as hz
from . import mindlin
from .pointforce import COMPONENTS
from .quadrature import hertzian_traction_stresses

#: quadrature rule of the tangential plane fields: error < 1e-7 p0 (measured 2e-8 p0 on a
#: plane through and around the contact, surface included; the analytic budget is 0.5 %)
QUAD = dict(n_phi=48, n_r=24)


def normal(case: Case) -> hz.Hertz:
    if case.load.P is not None:
        return hz.hertz(case.load.P, case.R, case.E_star)
    return hz.hertz_from_approach(case.load.approach, case.R, case.E_star)


def sliding_traction_vector(case: Case) -> np.ndarray:
    """(t_x, t_y): traction on body a per unit pressure in full sliding (Eq. 13, Eq. 11).

    d = (cos α, sin α) the sliding direction of a relative to b; in the tribological axes
    d_e = R(β) d, t_e = -M² d_e / ‖d‖*_μ with ‖d‖*_μ = √((μ1 d_e1)² + (μ2 d_e2)²); back to
    x, y by R(β)ᵀ.  Isotropic μ: t = -μ d.
    """
    f = case.friction
    alpha, beta = math.radians(case.load.slide_angle), math.radians(f.beta)
    d = np.array([math.cos(alpha), math.sin(alpha)])
    rot = np.array([[math.cos(beta), math.sin(beta)], [-math.sin(beta), math.cos(beta)]])
    de = rot @ d
    norm = math.hypot(f.mu1 * de[0], f.mu2 * de[1])
    if norm == 0.0:
        return np.zeros(2)
    te = -np.array([f.mu1**2 * de[0], f.mu2**2 * de[1]]) / norm
    return rot.T @ te


def delta_star(case: Case, h: hz.Hertz) -> float:
    return mindlin.gross_slip_shift(case.friction.mu1, h.P, h.a, case.a.G, case.a.nu,
                                    case.b.G, case.b.nu)


def tangential(case: Case, h: hz.Hertz) -> dict:
    """The tangential solution: Hertz-shaped terms [(radius, (qx0, qy0))] on body a, etc."""
    ld, f = case.load, case.friction
    mode = ld.tangential_mode
    empty = dict(terms=[], Q=(0.0, 0.0), c=h.a if f.mu1 > 0 else 0.0, shift=(0.0, 0.0))
    if mode == "none":
        return empty
    if mode == "sliding":
        t = sliding_traction_vector(case)
        return dict(terms=[(h.a, tuple(h.p0 * t))], Q=tuple(float(v) for v in h.P * t), c=0.0,
                    shift=(math.nan,) * 2)
    mu = f.mu1
    dstar = delta_star(case, h)
    if mode == "load":
        Q = np.array([ld.Qx or 0.0, ld.Qy or 0.0])
        Qm = float(np.hypot(*Q))
        if Qm == 0.0:
            return empty
        e = Q / Qm  # traction on a parallel to Q (Q is the resultant on a, Eq. 37)
        shift = -e * mindlin.shift_from_load(Qm, mu, h.P, dstar)
    else:
        s = np.array([ld.shift_x or 0.0, ld.shift_y or 0.0])
        sm = float(np.hypot(*s))
        if sm == 0.0:
            return empty
        e = -s / sm  # b resists: the traction on a opposes a's shift
        Qm = mindlin.load_from_shift(sm, mu, h.P, dstar)
        shift = s
    c = mindlin.stick_radius(h.a, Qm, mu, h.P)
    q0 = mu * h.p0
    terms = [(h.a, tuple(q0 * e))]
    if c > 0.0:
        terms.append((c, tuple(-(c / h.a) * q0 * e)))
    return dict(terms=terms, Q=tuple(float(v) for v in Qm * e), c=c,
                shift=tuple(float(v) for v in shift))


def surface(case: Case, h: hz.Hertz, tang: dict) -> dict[str, np.ndarray]:
    g = case.grid
    X, Y = np.meshgrid(g.x, g.y, indexing="ij")
    r = np.hypot(X, Y)
    p_n = hz.pressure(r, h.a, h.p0)
    p_x, p_y = np.zeros_like(p_n), np.zeros_like(p_n)
    for radius, (qx0, qy0) in tang["terms"]:
        shape = np.sqrt(np.clip(1.0 - (r / radius) ** 2, 0.0, None))
        p_x += qx0 * shape
        p_y += qy0 * shape
    # stick inside the stick radius c (c = a: friction but no tangential load; c = 0:
    # frictionless or sliding, where every contact cell slips as in the IC solver)
    state = np.where(r < h.a, np.where(r < tang["c"], STICK, SLIP), OPEN)
    zero = np.zeros_like(p_n)
    return dict(p_n=p_n, p_x=p_x, p_y=p_y, gap=hz.gap(r, h.a, h.R), wear_a=zero,
                wear_b=zero.copy(), state=state.astype(np.int8))


_UNIT_CACHE: dict[tuple, dict[str, np.ndarray]] = {}


def _unittangential(x, y, z, radius: float, nu: float, direction: str) -> dict:
    """Stresses of the unit Hertz-shaped tangential traction (cached: sweeps reuse them)."""
    key = (x.tobytes(), y.tobytes(), z.tobytes(), radius, nu, direction)
    if key not in _UNIT_CACHE:
        if len(_UNIT_CACHE) > 16:
            _UNIT_CACHE.clear()
        q = {"x": (1.0, 0.0), "y": (0.0, 1.0)}[direction]
        _UNIT_CACHE[key] = hertzian_traction_stresses(x, y, z, radius, qx0=q[0], qy0=q[1],
                                                      nu=nu, **QUAD)
    return _UNIT_CACHE[key]


def plane_stresses(case: Case, h: hz.Hertz, terms, X, Y, Z) -> dict[str, np.ndarray]:
    """Stresses in body ``case.stress.body`` at global (X, Y) and depth Z (see module doc)."""
    body = case.stress.body
    nu = case.a.nu if body == "a" else case.b.nu
    ysign, tsign = (1.0, 1.0) if body == "a" else (-1.0, -1.0)
    Yk = ysign * Y
    sig = hz.full_field(X, Yk, Z, h.a, h.p0, nu)
    for radius, (qx0, qy0) in terms:
        # body b: traction (-p_x, +p_y) in the frame (x, -y, zeta)
        for amp, direction in ((tsign * qx0, "x"), (qy0, "y")):
            if amp != 0.0:
                unit = _unittangential(X, Yk, Z, radius, nu, direction)
                for c in COMPONENTS:
                    sig[c] = sig[c] + amp * unit[c]
    if body == "b":
        sig["sxy"], sig["syz"] = -sig["sxy"], -sig["syz"]
    sig["vm"] = von_mises(*(sig[c] for c in COMPONENTS))
    return sig


def planes(case: Case, h: hz.Hertz, terms) -> dict[str, Plane]:
    g, st = case.grid, case.stress
    z = st.z
    x0, y0 = case.plane_centre
    out = {}
    for name, s, fixed in (("xz", g.x, y0), ("yz", g.y, x0)):
        S, Z = np.meshgrid(s, z, indexing="ij")
        F = np.full_like(S, fixed)
        X, Y = (S, F) if name == "xz" else (F, S)
        out[name] = Plane(s=np.array(s, float), z=np.array(z, float),
                          fields=plane_stresses(case, h, terms, X, Y, Z))
    return out


def vm_scalars(case: Case, planes: dict[str, Plane]) -> dict[str, float]:
    vm, x, y, z = vm_max_location(planes, *case.plane_centre)
    return dict(vm_max=vm, vm_max_x=x, vm_max_y=y, vm_max_z=z)


def check_grid(case: Case, a: float, what: str) -> None:
    half = 0.5 * min(case.grid.Lx, case.grid.Ly)
    if a >= half:
        raise CaseError(f"{what}: contact radius {a:.4g} mm reaches the edge of the potential "
                        f"contact grid (half-width {half:.4g} mm): enlarge grid.Lx/Ly")


# ------------------------------------------------------------------ steps
