"""The "analytic" solver: the common result (cases.result) for cases with a closed form.

Covered (:func:`has_solution`):

- ``static``, no tangential load: Hertz (any elastic pair when frictionless; with
  friction only for identical materials, which keep the tangential tractions zero).
- ``static``, dissimilar materials with friction and no tangential load: Spence's
  frictional compression (:func:`analytic.spence.compression`), the coupling solved
  whole on rings (numerically exact): the pressure, the radial shear of the stick disc
  and the slip annulus, the stick and contact radii; no stresses.
- ``static``, ``load.sliding``: full sliding (identical materials, or frictionless).  The
  traction on body a is p · t with the constant vector t = -M² d_e / ‖d‖*_μ of
  formulation Eq. 13 (d the sliding direction of a relative to b): -μ p d for isotropic
  friction, and also exact for orthotropic friction since the direction is uniform.
- ``static``, ``load.Qx/Qy`` or ``load.shift_x/shift_y``: Cattaneo–Mindlin (isotropic
  friction, identical materials), :mod:`analytic.mindlin`; a shift beyond δ* is full
  sliding.
- ``sliding_wear``: Argatov (2011) / Hegadekatte (2008) scalars per output distance
  (:mod:`analytic.wear`); no fields (the reference is asymptotic).
- ``fretting``, the first cycle only (:mod:`analytic.fretting_case`): isotropic
  friction, a pair without normal-tangential coupling (K = 0), the first cycle an
  output (jump = 1):
  Mindlin–Deresiewicz loop and energy, Archard's first-cycle wear of both bodies, the
  Hertz pressure and the Cattaneo traction at the cycle's end (:mod:`analytic.fretting`).

Not covered (:class:`~cases.model.CaseError` from :func:`solve`): fretting beyond the
first cycle or with orthotropic friction, dissimilar materials with friction under a
tangential load,
Cattaneo–Mindlin with orthotropic friction.

Conventions and the fields on the grid: :mod:`analytic.fields`.
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Callable

import numpy as np

from cases.model import Case, CaseError
from cases.result import (
    OPEN,
    SLIP,
    STICK,
    RunResult,
    StepResult,
)
from cases.steps import sliding_outputs

from . import fields, fretting_case, spence, wear
from .fields import sliding_traction_vector

SOLVER_NAME = "analytic"
# ------------------------------------------------------------------ applicability


def supports(case: Case) -> str | None:
    """None when the case has an analytic solution here, else why not."""
    reason = _no_solution_reason(case)
    return None if reason is None else f"no closed-form solution for this case: {reason}"


def _no_solution_reason(case: Case) -> str | None:
    f = case.friction
    frictional = f.mu1 > 0.0 or f.mu2 > 0.0
    if case.solver.wear_spread > 0 and case.kind in ("sliding_wear", "fretting"):
        return (f"solver.wear_spread = {case.solver.wear_spread:g} mm (the half-space "
                "solver's resolution probe: its wear increments spread over a length)")
    if case.kind == "fretting":
        return fretting_case.no_solution_reason(case)
    if not case.identical_materials and frictional:
        if case.kind == "static" and case.load.tangential_mode == "none" and f.isotropic:
            return None  # Spence's frictional compression (analytic.spence)
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
                f.mu1 * fields.normal(case).P:
            return "tangential load >= mu P (no static equilibrium)"
    return None


def has_solution(case: Case) -> bool:
    """Whether :func:`solve` has an analytic reference for ``case``."""
    return supports(case) is None


# ------------------------------------------------------------------ pieces


def static_step(case: Case) -> StepResult:
    """The one output step of a static case (step 0)."""
    if not case.identical_materials and case.friction.mu1 > 0:
        return compression_step(case)
    t0 = time.perf_counter()
    h = fields.normal(case)
    fields.check_grid(case, h.a, "Hertz")
    tang = fields.tangential(case, h)
    surface = fields.surface(case, h, tang)
    planes = fields.planes(case, h, tang["terms"])
    c = min(tang["c"], h.a)
    stick = math.pi * c * c
    scalars = dict(
        step=0, s=math.nan, cycle=math.nan, P=h.P, Qx=tang["Q"][0], Qy=tang["Q"][1],
        contact_area=h.area, a_x=h.a, a_y=h.a, p_max=h.p0, w_max=0.0, wear_volume=0.0,
        **fields.vm_scalars(case, planes), stick_area=stick, slip_area=h.area - stick,
        iterations=0, converged=True,
        approach=h.delta, shift_x=tang["shift"][0], shift_y=tang["shift"][1],
        stick_radius=c, p0=h.p0, a0=h.a,
    )
    scalars["wall_s"] = time.perf_counter() - t0
    g = case.grid
    return StepResult(scalars=scalars, x=g.x.copy(), y=g.y.copy(), surface=surface,
                      planes=planes)


def compression_step(case: Case) -> StepResult:
    """Normal loading of a dissimilar pair with friction (:mod:`analytic.spence`): Spence's
    self-similar compression with the coupling solved whole (:func:`analytic.spence.
    compression`, docs/formulation.md §2.9) — the pressure, the radial shear in the stick
    disc and the slip annulus, the stick radius, the contact radius and the approach of
    the load (or the load of the approach); no stresses."""
    t0 = time.perf_counter()
    G, nu, K = spence.pair_constants(case)
    mu = case.friction.mu1
    sol = spence.compression(nu, K, mu)
    R = case.R
    if case.load.P is not None:
        P = case.load.P
        a = (P * R / (G * sol.load)) ** (1.0 / 3.0)
    else:
        a = math.sqrt(case.load.approach * R / sol.delta)
        P = G * a ** 3 * sol.load / R
    fields.check_grid(case, a, "Spence's compression")
    hertz_a0, hertz_p0 = case.hertz_scales  # p0 and a0 are Hertz's in every step
    c, unit = sol.k * a, G * a / R
    g = case.grid
    X, Y = np.meshgrid(g.x, g.y, indexing="ij")
    r = np.hypot(X, Y)
    inside = r < a
    p_n = np.where(inside, unit * np.interp(r / a, sol.rho, sol.p), 0.0)
    q = np.where(inside, unit * np.interp(r / a, sol.rho, sol.q), 0.0)
    with np.errstate(invalid="ignore", divide="ignore"):
        p_x, p_y = (np.where(r > 0, q * v / r, 0.0) for v in (X, Y))
    state = np.where(inside, np.where(r <= c, STICK, SLIP), OPEN).astype(np.int8)
    zero = np.zeros_like(p_n)
    delta = sol.delta * a * a / R
    surface = dict(p_n=p_n, p_x=p_x, p_y=p_y, gap=sol.gap(r / a) * a * a / R,
                   wear_a=zero, wear_b=zero.copy(), state=state)
    nan = math.nan
    area, stick = math.pi * a * a, math.pi * c * c
    scalars = dict(
        step=0, s=nan, cycle=nan, P=P, Qx=0.0, Qy=0.0, contact_area=area, a_x=a, a_y=a,
        p_max=unit * float(sol.p.max()), w_max=0.0, wear_volume=0.0, vm_max=nan,
        vm_max_x=nan, vm_max_y=nan, vm_max_z=nan, stick_area=stick, slip_area=area - stick,
        iterations=0, converged=True, approach=delta,
        dundurs_beta=case.dundurs_beta, stick_radius=c,
        stick_radius_uncoupled=spence.stick_ratio(case.dundurs_beta, mu) * a,
        p0=hertz_p0, a0=hertz_a0, wall_s=time.perf_counter() - t0)
    return StepResult(scalars=scalars, x=g.x.copy(), y=g.y.copy(), surface=surface)


# Argatov's radius, pressure and depth are asymptotic in s: reported from this many
# transition distances s_c on (measured with the half-space solver on the article's
# pin: at 10 s_c = 230 mm the gaps are about -1.7% (w_max) and +2.2% (p_max); -13.6%
# and +30% at s = 20 mm < s_c).  Archard's worn volume is exact at every s.
ASYMPTOTIC_FROM = 10.0


def wear_steps(case: Case) -> list[StepResult]:
    """Output steps of a ``sliding_wear`` case: scalars from Argatov / Hegadekatte.

    Step numbers and distances follow the incremental runs: s in output_s plus 0 and the
    total distance, step = round(s / sliding_wear.step).  s = 0 is the sliding sphere
    before any wear (:func:`sliding_start`, fields and stresses); for s > 0 p_max is
    Argatov's steady-state P/(π a²), w_max the Archard-consistent depth √(a⁴ - a0⁴)/(2R)
    (see :mod:`analytic.wear`), these three only from ``ASYMPTOTIC_FROM`` s_c on (NaN
    before: no reference), with
    i_w = i_w,a(θ) + i_w,b(θ) (the gap sees both bodies' wear; the disk's is 0 in case 4).
    """
    t0 = time.perf_counter()
    sw = case.sliding_wear
    h = fields.normal(case)
    f = case.friction
    theta = wear.sliding_angle(f.beta, case.load.slide_angle)
    i_w = sum(wear.wear_coefficient(b.i1, b.i2, theta) for b in (case.a, case.b))
    numbers = sliding_outputs(sw)
    t = sliding_traction_vector(case)
    s_c = wear.transition_distance(h.a, i_w, h.P, case.R) if i_w > 0 else math.inf
    g = case.grid
    steps = []
    for n in numbers:
        s = n * sw.step
        if n == 0:  # before any wear: the sphere sliding on the plane, fields and all
            start = sliding_start(case)
            start.scalars.update(i_w=i_w, s_transition=s_c)
            steps.append(start)
            continue
        a = float(wear.argatov_radius(s, h.a, i_w, h.P, case.R))
        fields.check_grid(case, a, f"Argatov at s = {s:g} mm")
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


def sliding_start(case: Case) -> StepResult:
    """Step 0 of a ``sliding_wear`` case, s = 0: the unworn sphere sliding on the plane
    along ``load.slide_angle`` — Hertz's pressure and Hamilton's field of the full-sliding
    traction (orthotropic friction: the one direction of Eq. 13), exact at any μ, β."""
    sliding = case.with_changes(
        kind="static", sliding_wear=None,
        load=dataclasses.replace(case.load, sliding=True))
    step = static_step(sliding)
    step.scalars.update(step=0, s=0.0, w_max=0.0, wear_volume=0.0, w_max_hegadekatte=0.0,
                        w_max_literal=0.0)
    return step


def solve(case: Case, *, progress: bool = False,
          on_output: Callable[[StepResult], None] | None = None) -> RunResult:
    """The analytic result of ``case``; :class:`CaseError` if it has no analytic solution.
    ``on_output`` receives each output step."""
    reason = _no_solution_reason(case)
    if reason is not None:
        label = f"{case.name} ({case.param})" if case.param else case.name
        raise CaseError(f"no analytic solution for {label}: {reason}")
    if case.kind == "sliding_wear":
        steps = wear_steps(case)
    elif case.kind == "fretting":
        steps, tables = fretting_case.fretting_steps(case)
    else:
        steps = [static_step(case)]
    for step in steps if on_output is not None else ():
        on_output(step)
    return RunResult(case=case.name, solver=SOLVER_NAME, param=case.param, steps=steps,
                     meta={"references": _references(case)},
                     tables=tables if case.kind == "fretting" else {})


def _references(case: Case) -> str:
    if case.kind == "sliding_wear":
        return "Argatov (2011); Hegadekatte et al. (2008); Archard"
    if case.kind == "fretting":
        return ("Hertz; Mindlin & Deresiewicz (1953), Johnson 1985 §7.2-7.4; Archard; "
                "Hamilton (1983) by point-force quadrature")
    mode = case.load.tangential_mode
    if mode == "sliding":
        return "Hertz; Hamilton (1983) by point-force quadrature"
    if mode in ("load", "shift"):
        return "Hertz; Cattaneo-Mindlin (Johnson 1985 §7.2) by point-force quadrature"
    return "Hertz (Johnson 1985 §3.4, §4.2, eq. 3.45); Hamilton & Goodman (1966)"
