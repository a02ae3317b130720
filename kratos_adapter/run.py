"""One frictionless static case by Kratos: mesh, the secant search for the normal load,
the fields on the case's grid and planes, the scalars of the other solvers.

The load: Kratos drives the approach δ of the far faces; the quarter's load P/4 is the
reaction of the plane's far face.  Starting from :data:`APPROACH` times Hertz's
δ = a0²/R, each step moves δ by the secant of log P against log δ (the first by Hertz's
P ∝ δ^(3/2)), from the last converged state, until P is within :data:`LOAD_TOL` of the
case's load (at most :data:`MAX_STEPS` steps).  The finite bodies (side and height
:data:`SIDE` a0) are stiffer than half-spaces: the approach that carries P is about 2 %
below Hertz's.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable

import numpy as np

from cases.model import Case
from cases.result import OPEN, SLIP, RunResult, StepResult, semi_widths, vm_max_location

from . import fields
from .mesh import hex_bodies
from .model import Material, Model

#: the bodies' side and height, in a0 (the FEM reference's block is 20 a0 too, but the
#: two share no code: this is the same choice of domain, measured separately)
SIDE = 20.0
#: the first approach, over Hertz's a0²/R: the finite bodies' (measured 0.977–0.98 on
#: the bundled Hertz case at h = a0/4 to a0/6)
APPROACH = 0.9795
#: relative tolerance of the normal load, and the most load steps to reach it
LOAD_TOL = 2e-3
MAX_STEPS = 8
#: the element size near the contact over the FEM's ``fem.h`` (a0/6 at its default a0/8):
#: trilinear hexahedra, h from the case so that a grid study refines both FEMs alike
H_FACTOR = 4.0 / 3.0


class KratosNotConverged(RuntimeError):
    """Kratos' Newton solve or the load search did not converge."""


def element_size(case: Case) -> float:
    """The element size [mm] at the contact: :data:`H_FACTOR` times the FEM's."""
    fem = case.fem
    h = fem.h_surface if fem.h_surface is not None else fem.h
    return H_FACTOR * h * case.hertz_scales[0]


def young(body) -> float:
    """The Young's modulus Kratos is given for a body [MPa] (one place, for the seeded
    defect of tests/test_kratos_adapter.py)."""
    return body.E


def load_search(model: Model, target: float, delta: float) -> tuple[float, float, int]:
    """(δ, quarter load, Newton iterations) with the load within :data:`LOAD_TOL` of
    ``target`` (module doc)."""
    history: list[tuple[float, float]] = []
    iterations = 0
    for _ in range(MAX_STEPS):
        if not model.solve(delta):
            raise KratosNotConverged(f"Kratos' Newton solve did not converge at the approach "
                                     f"{delta:.6g} mm")
        iterations += model.iterations()
        load = abs(model.load())
        history.append((delta, load))
        if abs(load / target - 1.0) <= LOAD_TOL:
            return delta, load, iterations
        if load <= 0.0:
            delta *= 2.0
            continue
        if len(history) >= 2 and history[-2][1] > 0 and history[-2][0] != delta:
            (d1, p1), (d2, p2) = history[-2], history[-1]
            slope = math.log(p2 / p1) / math.log(d2 / d1)
            slope = min(max(slope, 1.0), 3.0)
        else:
            slope = 1.5
        delta *= (target / load) ** (1.0 / slope)
    raise KratosNotConverged(f"the load search did not reach P within {LOAD_TOL:g} in "
                             f"{MAX_STEPS} steps (last {4 * history[-1][1]:.6g} N)")


def run(case: Case, on_output: Callable[[StepResult], None] | None = None) -> RunResult:
    """One output step of ``case`` by Kratos (module doc)."""
    t0 = time.perf_counter()
    a0 = case.hertz_scales[0]
    h = element_size(case)
    body_a, body_b = hex_bodies(a0, case.R, h, SIDE * a0, SIDE * a0)
    model = Model(body_a, body_b, Material(young(case.a), case.a.nu),
                  Material(young(case.b), case.b.nu))
    delta, quarter, iterations = load_search(model, case.load.P / 4.0,
                                             APPROACH * a0**2 / case.R)
    g, st = case.grid, case.stress
    face = np.unique(body_a.contact)
    p_nodes = model.pressure()
    p_n = fields.surface(body_a.nodes, body_a.contact, p_nodes, g.x, g.y)
    p_n = np.where(p_n > 0.0, p_n, 0.0)
    body = body_a if st.body == "a" else body_b
    stress = model.stresses(st.body)
    x0, y0 = case.plane_centre
    planes = fields.planes(body.nodes, body.cells, stress, x=g.x, y=g.y, z=st.z, x0=x0,
                           y0=y0, sign_z=1.0 if st.body == "a" else -1.0)
    vm, vx, vy, vz = vm_max_location(planes, x0, y0)
    dA = g.dx * g.dy
    a_x, a_y = semi_widths(g.x, g.y, p_n)
    zero = np.zeros_like(p_n)
    scalars = {
        "step": 0, "P": 4.0 * quarter, "Qx": 0.0, "Qy": 0.0,
        "contact_area": float(np.count_nonzero(p_n > 0) * dA), "a_x": a_x, "a_y": a_y,
        "p_max": float(max(p_nodes[face].max(), p_n.max())), "vm_max": vm, "vm_max_x": vx,
        "vm_max_y": vy, "vm_max_z": vz, "x0": x0, "y0": y0, "approach": delta,
        "iterations": iterations, "converged": True, "h": h,
        "nodes": body_a.nodes.shape[0] + body_b.nodes.shape[0],
        "elements": body_a.cells.shape[0] + body_b.cells.shape[0],
        "wall_s": time.perf_counter() - t0,
    }
    state = np.where(p_n > 0.0, SLIP, OPEN).astype(np.int8)
    step = StepResult(scalars=scalars, x=g.x.copy(), y=g.y.copy(),
                      surface={"p_n": p_n, "p_x": zero, "p_y": zero.copy(), "state": state},
                      planes=planes)
    if on_output is not None:
        on_output(step)
    return RunResult(case=case.name, solver="kratos", param=case.param, steps=[step],
                     meta={"kratos": version()})


def version() -> str:
    from importlib.metadata import version as v

    return v("KratosMultiphysics")
