"""The "analytic" solver: the common result (cases.result) for cases with a closed form.

Covered (:func:`has_solution`):

- ``static``, no tangential load: Hertz (any elastic pair when frictionless; with
  friction only for identical materials, which keep the tangential tractions zero).
- ``static``, ``load.sliding``: full sliding (identical materials, or frictionless).  The
  traction on body a is p · t with the constant vector t = -M² d_e / ‖d‖*_μ of
  formulation Eq. 13 (d the sliding direction of a relative to b): -μ p d for isotropic
  friction, and also exact for orthotropic friction since the direction is uniform.
- ``static``, ``load.Qx/Qy`` or ``load.shift_x/shift_y``: Cattaneo–Mindlin (isotropic
  friction, identical materials), :mod:`analytic.mindlin`; a shift beyond δ* is full
  sliding.
- ``sliding_wear``: Argatov (2011) / Hegadekatte (2008) scalars per output distance
  (:mod:`analytic.wear`); no fields (the reference is asymptotic).

Not covered (:class:`~cases.model.CaseError` from :func:`solve`): fretting, dissimilar
materials with friction, Cattaneo–Mindlin with orthotropic friction.

Conventions (cases/model.py): the surface fields ``p_n, p_x, p_y`` are the tractions on
body a (p_n > 0 compressive), sampled at the cell centres (x[i], y[j]).  Subsurface planes
are reported in ``case.stress.body`` with z >= 0 the depth into it: 'xz' at y = stress.y0
with s = grid.x, 'yz' at x = stress.x0 with s = grid.y, z = stress.z.

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
import time
from collections.abc import Callable

import numpy as np

from cases.model import Case, CaseError
from cases.result import (
    OPEN,
    SLIP,
    STICK,
    Plane,
    RunResult,
    StepResult,
    vm_max_location,
    von_mises,
)

from . import hertz as hz
from . import mindlin, wear
from .pointforce import COMPONENTS
from .quadrature import hertzian_traction_stresses

SOLVER_NAME = "analytic"
#: quadrature rule of the tangential plane fields: error < 1e-7 p0 (measured 2e-8 p0 on a
#: plane through and around the contact, surface included; the analytic budget is 0.5 %)
QUAD = dict(n_phi=48, n_r=24)


# ------------------------------------------------------------------ applicability


def supports(case: Case) -> str | None:
    """None when the case has an analytic solution here, else why not."""
    reason = _no_solution_reason(case)
    return None if reason is None else f"no closed-form solution for this case: {reason}"


def _no_solution_reason(case: Case) -> str | None:
    f = case.friction
    frictional = f.mu1 > 0.0 or f.mu2 > 0.0
    if case.kind == "fretting":
        return "fretting (cyclic wear evolution has no closed form)"
    if not case.identical_materials and frictional:
        return "dissimilar materials with friction (normal-tangential coupling, K != 0)"
    if case.kind == "sliding_wear":
        return None
    if case.kind != "static":
        return f"kind {case.kind!r}"
    mode = case.load.tangential_mode
    if mode in ("load", "shift"):
        if not f.isotropic:
            return "partial slip with orthotropic friction (no Cattaneo-Mindlin closed form)"
        if mode == "load" and math.hypot(case.load.Qx or 0.0, case.load.Qy or 0.0) >= \
                f.mu1 * _normal(case).P:
            return "tangential load >= mu P (no static equilibrium)"
    return None


def has_solution(case: Case) -> bool:
    """Whether :func:`solve` has an analytic reference for ``case``."""
    return supports(case) is None


# ------------------------------------------------------------------ pieces


def _normal(case: Case) -> hz.Hertz:
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


def _delta_star(case: Case, h: hz.Hertz) -> float:
    return mindlin.gross_slip_shift(case.friction.mu1, h.P, h.a, case.a.G, case.a.nu,
                                    case.b.G, case.b.nu)


def _tangential(case: Case, h: hz.Hertz) -> dict:
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
    dstar = _delta_star(case, h)
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


def _surface(case: Case, h: hz.Hertz, tang: dict) -> dict[str, np.ndarray]:
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


def _unit_tangential(x, y, z, radius: float, nu: float, direction: str) -> dict:
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
                unit = _unit_tangential(X, Yk, Z, radius, nu, direction)
                for c in COMPONENTS:
                    sig[c] = sig[c] + amp * unit[c]
    if body == "b":
        sig["sxy"], sig["syz"] = -sig["sxy"], -sig["syz"]
    sig["vm"] = von_mises(*(sig[c] for c in COMPONENTS))
    return sig


def _planes(case: Case, h: hz.Hertz, terms) -> dict[str, Plane]:
    g, st = case.grid, case.stress
    z = st.z
    out = {}
    for name, s, fixed in (("xz", g.x, st.y0), ("yz", g.y, st.x0)):
        S, Z = np.meshgrid(s, z, indexing="ij")
        F = np.full_like(S, fixed)
        X, Y = (S, F) if name == "xz" else (F, S)
        out[name] = Plane(s=np.array(s, float), z=np.array(z, float),
                          fields=plane_stresses(case, h, terms, X, Y, Z))
    return out


def _vm_scalars(case: Case, planes: dict[str, Plane]) -> dict[str, float]:
    vm, x, y, z = vm_max_location(planes, case.stress.x0, case.stress.y0)
    return dict(vm_max=vm, vm_max_x=x, vm_max_y=y, vm_max_z=z)


def _check_grid(case: Case, a: float, what: str) -> None:
    half = 0.5 * min(case.grid.Lx, case.grid.Ly)
    if a >= half:
        raise CaseError(f"{what}: contact radius {a:.4g} mm reaches the edge of the potential "
                        f"contact grid (half-width {half:.4g} mm): enlarge grid.Lx/Ly")


# ------------------------------------------------------------------ steps


def static_step(case: Case) -> StepResult:
    """The one output step of a static case (step 0)."""
    t0 = time.perf_counter()
    h = _normal(case)
    _check_grid(case, h.a, "Hertz")
    tang = _tangential(case, h)
    surface = _surface(case, h, tang)
    planes = _planes(case, h, tang["terms"])
    c = min(tang["c"], h.a)
    stick = math.pi * c * c
    scalars = dict(
        step=0, s=math.nan, cycle=math.nan, P=h.P, Qx=tang["Q"][0], Qy=tang["Q"][1],
        contact_area=h.area, a_x=h.a, a_y=h.a, p_max=h.p0, w_max=0.0, wear_volume=0.0,
        **_vm_scalars(case, planes), stick_area=stick, slip_area=h.area - stick,
        iterations=0, converged=True,
        approach=h.delta, shift_x=tang["shift"][0], shift_y=tang["shift"][1],
        stick_radius=c, p0=h.p0, a0=h.a,
    )
    scalars["wall_s"] = time.perf_counter() - t0
    g = case.grid
    return StepResult(scalars=scalars, x=g.x.copy(), y=g.y.copy(), surface=surface,
                      planes=planes)


# Argatov's radius, pressure and depth are asymptotic in s: reported from this many
# transition distances s_c on (measured with the half-space solver on the article's
# pin: at 10 s_c = 230 mm the gaps are about -1.7% (w_max) and +2.2% (p_max); -13.6%
# and +30% at s = 20 mm < s_c).  Archard's worn volume is exact at every s.
ASYMPTOTIC_FROM = 10.0


def wear_steps(case: Case) -> list[StepResult]:
    """Output steps of a ``sliding_wear`` case: scalars from Argatov / Hegadekatte.

    Step numbers and distances follow the incremental runs: s in output_s plus 0 and the
    total distance, step = round(s / sliding_wear.step).  s = 0 is the exact Hertz state
    (p_max = p0); for s > 0 p_max is Argatov's steady-state P/(π a²), w_max the
    Archard-consistent depth √(a⁴ - a0⁴)/(2R) (see :mod:`analytic.wear`), these
    three only from ``ASYMPTOTIC_FROM`` s_c on (NaN before: no reference), with
    i_w = i_w,a(θ) + i_w,b(θ) (the gap sees both bodies' wear; the disk's is 0 in case 4).
    """
    t0 = time.perf_counter()
    sw = case.sliding_wear
    h = _normal(case)
    f = case.friction
    theta = wear.sliding_angle(f.beta, case.load.slide_angle)
    i_w = sum(wear.wear_coefficient(b.i1, b.i2, theta) for b in (case.a, case.b))
    n_last = int(round(sw.distance / sw.step))
    numbers = sorted({int(round(v / sw.step)) for v in sw.output_s} | {0, n_last})
    t = sliding_traction_vector(case)
    s_c = wear.transition_distance(h.a, i_w, h.P, case.R) if i_w > 0 else math.inf
    g = case.grid
    steps = []
    for n in numbers:
        s = n * sw.step
        a = float(wear.argatov_radius(s, h.a, i_w, h.P, case.R))
        _check_grid(case, a, f"Argatov at s = {s:g} mm")
        p_max = h.p0 if s == 0 else float(wear.argatov_p_max(s, h.a, i_w, h.P, case.R))
        w_max = float(wear.argatov_wear_depth(s, h.a, i_w, h.P, case.R))
        if 0 < s < ASYMPTOTIC_FROM * s_c:
            a = p_max = w_max = math.nan  # Argatov's asymptotic solution not yet valid
        scalars = dict(
            step=n, s=s, cycle=math.nan, P=h.P, Qx=float(h.P * t[0]) if s > 0 else 0.0,
            Qy=float(h.P * t[1]) if s > 0 else 0.0, contact_area=math.pi * a * a, a_x=a, a_y=a,
            p_max=p_max, w_max=w_max,
            wear_volume=float(wear.archard_volume(s, i_w, h.P)),
            vm_max=math.nan, vm_max_x=math.nan, vm_max_y=math.nan, vm_max_z=math.nan,
            stick_area=math.nan, iterations=0, converged=True,
            w_max_hegadekatte=float(wear.hegadekatte_wear_depth(s, i_w, h.P, case.R)),
            w_max_literal=float(wear.argatov_wear_depth_literal(s, h.a, i_w, h.P, case.R)),
            i_w=i_w, s_transition=s_c, wall_s=time.perf_counter() - t0,
        )
        steps.append(StepResult(scalars=scalars, x=g.x.copy(), y=g.y.copy(), surface={}))
    return steps


def solve(case: Case, *, progress: bool = False,
          on_output: Callable[[StepResult], None] | None = None) -> RunResult:
    """The analytic result of ``case``; :class:`CaseError` if it has no analytic solution.
    ``on_output`` receives each output step."""
    reason = _no_solution_reason(case)
    if reason is not None:
        label = f"{case.name} ({case.param})" if case.param else case.name
        raise CaseError(f"no analytic solution for {label}: {reason}")
    steps = wear_steps(case) if case.kind == "sliding_wear" else [static_step(case)]
    for step in steps if on_output is not None else ():
        on_output(step)
    return RunResult(case=case.name, solver=SOLVER_NAME, param=case.param, steps=steps,
                     meta={"references": _references(case)})


def _references(case: Case) -> str:
    if case.kind == "sliding_wear":
        return "Argatov (2011); Hegadekatte et al. (2008); Archard"
    mode = case.load.tangential_mode
    if mode == "sliding":
        return "Hertz; Hamilton (1983) by point-force quadrature"
    if mode in ("load", "shift"):
        return "Hertz; Cattaneo-Mindlin (Johnson 1985 §7.2) by point-force quadrature"
    return "Hertz (Johnson 1985 §3.4, §4.2, eq. 3.45); Hamilton & Goodman (1966)"
