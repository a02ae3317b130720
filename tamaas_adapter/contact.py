"""The Tamaas solves of one case on its own grid (cell centres, piecewise-constant
tractions), in the common result container.

- Normal contact: PolonskyKeerRey on a ``basic_2d`` model (E* of the pair: E = E*(1 −
  ν²) with the reported body's ν), the non-periodic DC-FFT operator or Tamaas's default
  periodic one, stopped at a relative error of ``solver.tol`` (at most
  ``solver.max_iter`` iterations).
- Full sliding (``load.sliding``): the sliding law on Tamaas's pressure,
  p_t = −μ p_n along ``load.slide_angle`` (the traction on body a opposes its motion).
- Partial slip (``load.Qx/Qy``): PolonskyKeerTan on a periodic ``surface_2d`` model,
  ν = 0.5 and E = 0.75 E* (:mod:`tamaas_adapter.support`), the mean tractions
  (Qx, Qy, P) over the cell, for :data:`PKT_ITERATIONS` iterations: its error measure
  levels off above zero in partial slip, so its tolerance cannot stop it
  (``benchmarks/peers_bench.py``).  Tamaas's surface models are periodic only: for
  ``tamaas`` the cell is the case grid widened to about twice its size (the images two
  grid widths away), for ``tamaas_periodic`` the case grid itself.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable

import numpy as np

from cases.model import Case
from cases.result import RunResult, StepResult, semi_widths, vm_max_location
from reports.plugin import silenced

from . import volume

PKT_ITERATIONS = 1000
PKT_NU = 0.5


def _profile(case: Case, pad: tuple[int, int] = (0, 0)) -> np.ndarray:
    """The sphere's profile at the cell centres of the case grid widened by ``pad``
    cells on each side."""
    g = case.grid
    x = (np.arange(-pad[0], g.nx + pad[0]) + 0.5) * g.dx - 0.5 * g.Lx
    y = (np.arange(-pad[1], g.ny + pad[1]) + 0.5) * g.dy - 0.5 * g.Ly
    return -(x[:, None] ** 2 + y[None, :] ** 2) / (2.0 * case.R)


def normal(case: Case, periodic: bool) -> np.ndarray:
    """The pressure [MPa] on the case's cells under ``load.P``."""
    import tamaas as tm

    g = case.grid
    nu = (case.a if case.stress.body == "a" else case.b).nu
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [g.Lx, g.Ly], [g.nx, g.ny])
    model.E, model.nu = case.E_star * (1.0 - nu**2), nu
    solver = tm.PolonskyKeerRey(model, _profile(case), case.solver.tol)
    if not periodic:
        tm.ModelFactory.registerNonPeriodic(model, "dcfft")
        solver.setIntegralOperator("dcfft")
    solver.max_iter = case.solver.max_iter
    with silenced():
        solver.solve(case.load.P / (g.Lx * g.Ly))
    return np.array(model.traction, dtype=float).reshape(g.nx, g.ny)


def partial_slip(case: Case, periodic: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(p_x, p_y, p_n) [MPa] under ``load.Qx/Qy`` and ``load.P`` (module doc); not
    ``periodic``: on a periodic cell of about twice the case grid, the profile continued,
    read back on the case's cells."""
    import tamaas as tm

    g, ld = case.grid, case.load
    pad = (0, 0) if periodic else ((g.nx + 1) // 2, (g.ny + 1) // 2)
    n = (g.nx + 2 * pad[0], g.ny + 2 * pad[1])
    side = (n[0] * g.dx, n[1] * g.dy)
    model = tm.ModelFactory.createModel(tm.model_type.surface_2d, list(side), list(n))
    model.E, model.nu = case.E_star * (1.0 - PKT_NU**2), PKT_NU
    solver = tm.PolonskyKeerTan(model, _profile(case, pad), 0.0, case.friction.mu1)
    solver.max_iter = PKT_ITERATIONS
    area = side[0] * side[1]
    with silenced():
        solver.solve([(ld.Qx or 0.0) / area, (ld.Qy or 0.0) / area, ld.P / area])
    t = np.array(model.traction, dtype=float).reshape(*n, 3)
    t = t[pad[0]:pad[0] + g.nx, pad[1]:pad[1] + g.ny]
    return t[..., 0], t[..., 1], t[..., 2]


def tractions(case: Case, periodic: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(p_x, p_y, p_n) on body a [MPa] (module doc)."""
    mode = case.load.tangential_mode
    if mode == "load":
        return partial_slip(case, periodic)
    p_n = normal(case, periodic)
    if mode == "sliding":
        theta = math.radians(case.load.slide_angle)
        mu = case.friction.mu1
        return -mu * p_n * math.cos(theta), -mu * p_n * math.sin(theta), p_n
    return np.zeros_like(p_n), np.zeros_like(p_n), p_n


def run(case: Case, *, periodic: bool,
        on_output: Callable[[StepResult], None] | None = None) -> RunResult:
    """One output step of ``case`` by Tamaas (module doc)."""
    t0 = time.perf_counter()
    g = case.grid
    p_x, p_y, p_n = tractions(case, periodic)
    planes = volume.planes(case, volume.stress_block(case, p_x, p_y, p_n, periodic))
    i0, j0 = g.nearest_cell(case.stress.x0, case.stress.y0)
    x0, y0 = float(g.x[i0]), float(g.y[j0])
    vm, vx, vy, vz = vm_max_location(planes, x0, y0)
    dA = g.dx * g.dy
    a_x, a_y = semi_widths(g.x, g.y, p_n)
    scalars = {
        "step": 0, "P": float(p_n.sum() * dA), "Qx": float(p_x.sum() * dA),
        "Qy": float(p_y.sum() * dA), "contact_area": float(np.count_nonzero(p_n > 0) * dA),
        "a_x": a_x, "a_y": a_y,
        "p_max": float(p_n.max()), "vm_max": vm, "vm_max_x": vx, "vm_max_y": vy,
        "vm_max_z": vz, "x0": x0, "y0": y0, "wall_s": time.perf_counter() - t0,
    }
    step = StepResult(scalars=scalars, x=g.x.copy(), y=g.y.copy(),
                      surface={"p_n": p_n, "p_x": p_x, "p_y": p_y}, planes=planes)
    if on_output is not None:
        on_output(step)
    name = "tamaas_periodic" if periodic else "tamaas"
    return RunResult(case=case.name, solver=name, param=case.param, steps=[step])
