"""Run a case through the half-space solver and return the common result ("ic")."""

from __future__ import annotations

import time
from collections.abc import Callable

import numpy as np

from cases.model import Case
from cases.result import RunResult, StepResult

from .contact import SLIP, STICK, ContactSolver, ContactState, StepSolution
from .materials import Materials
from .operator import WORKERS
from .stresses import StressEvaluator

SOLVER_NAME = "ic"
SLIDE_FACTOR = 1e6  # rigid slip of a gross-sliding step, in units of the grid size


def profile(case: Case) -> np.ndarray:
    """Geometric gap h(x, y) = (x^2 + y^2) / (2R) of the paraboloid on the cell centres."""
    X, Y = np.meshgrid(case.grid.x, case.grid.y, indexing="ij")
    return (X**2 + Y**2) / (2.0 * case.R)


def slide_direction(angle_deg: float) -> np.ndarray:
    t = np.radians(angle_deg)
    return np.array([np.cos(t), np.sin(t)])


def contact_solver(case: Case) -> ContactSolver:
    mat = Materials.from_bodies(case.a, case.b)
    s = case.solver
    return ContactSolver(case.grid, mat, case.friction, method=s.method, tol=s.tol,
                         max_iter=s.max_iter)


def stress_evaluator(case: Case) -> StressEvaluator:
    body = case.stress.body
    nu = case.a.nu if body == "a" else case.b.nu
    return StressEvaluator(case.grid, case.stress.z, nu, body)


def semi_widths(case: Case, p_n: np.ndarray) -> tuple[float, float]:
    """Contact semi-widths along x and y through the cells nearest the planes' centre."""
    g = case.grid
    i0 = int(np.argmin(np.abs(g.x - case.stress.x0)))
    j0 = int(np.argmin(np.abs(g.y - case.stress.y0)))

    def half_extent(coord, mask, d):
        if not mask.any():
            return 0.0
        c = coord[mask]
        return 0.5 * (c.max() - c.min() + d)

    return half_extent(g.x, p_n[:, j0] > 0, g.dx), half_extent(g.y, p_n[i0, :] > 0, g.dy)


def step_result(case: Case, sol: StepSolution, stresses: StressEvaluator, *, step: int,
                wear_a: np.ndarray, wear_b: np.ndarray, wall_s: float,
                s: float = np.nan, cycle: float = np.nan) -> StepResult:
    """Collect the summary scalars, surface fields and stress planes of one step."""
    g = case.grid
    dA = g.dx * g.dy
    st = sol.state
    planes = stresses.planes(st.p_x, st.p_y, st.p_n, case.stress.x0, case.stress.y0)
    best = max(planes.items(), key=lambda kv: kv[1].vm_max()[0])
    vm, s_at, z_at = best[1].vm_max()
    if best[0] == "xz":
        vx, vy = s_at, float(g.y[np.argmin(np.abs(g.y - case.stress.y0))])
    else:
        vx, vy = float(g.x[np.argmin(np.abs(g.x - case.stress.x0))]), s_at
    a_x, a_y = semi_widths(case, st.p_n)
    wear = wear_a + wear_b
    scalars = dict(
        step=step, s=s, cycle=cycle, P=sol.P, Qx=sol.Qx, Qy=sol.Qy,
        contact_area=float(np.count_nonzero(st.p_n > 0) * dA), a_x=a_x, a_y=a_y,
        p_max=float(st.p_n.max()), w_max=float(wear.max()),
        wear_volume=float(wear.sum() * dA), vm_max=vm, vm_max_x=vx, vm_max_y=vy,
        vm_max_z=z_at, stick_area=float(np.count_nonzero(sol.status == STICK) * dA),
        slip_area=float(np.count_nonzero(sol.status == SLIP) * dA),
        iterations=sol.iterations, converged=True, wall_s=wall_s,
        approach=st.approach, shift_x=st.shift_x, shift_y=st.shift_y,
        residual_n=sol.residual_n, residual_t=sol.residual_t,
    )
    surface = dict(p_n=st.p_n, p_x=st.p_x, p_y=st.p_y, gap=sol.gap, slip_x=sol.slip_x,
                   slip_y=sol.slip_y, wear_a=wear_a, wear_b=wear_b,
                   state=sol.status.astype(np.int8))
    return StepResult(scalars=scalars, x=g.x.copy(), y=g.y.copy(), surface=surface,
                      planes=planes)


NORMAL_INCREMENTS_COUPLED = 5  # normal loading steps when K != 0 and friction (history)
TANGENTIAL_INCREMENTS = 5  # tangential loading steps after the normal load


def static_step(case: Case, solver: ContactSolver, h: np.ndarray,
                prev: ContactState | None = None) -> StepSolution:
    """Solve a static case along its load path: the normal load (or approach) first,
    the tangential load (or shift) after it (cases.md, case 2).  With friction the result
    depends on the path when the materials couple normal and tangential (K != 0) or the
    tangential load is not monotonic in direction, so the normal load is applied in
    ``NORMAL_INCREMENTS_COUPLED`` steps when coupled and a tangential load or shift in
    ``TANGENTIAL_INCREMENTS`` steps, each with the slip history of the previous one (the
    same path as the FEM reference).  Gross sliding is one step after the normal load."""
    ld = case.load
    mode = ld.tangential_mode
    frictional = case.friction.mu1 > 0
    normal = ({"P": ld.P} if ld.load_controlled else {"approach": ld.approach})
    n_normal = NORMAL_INCREMENTS_COUPLED if frictional and solver.op.coupled else 1
    base = np.zeros(2) if prev is None else np.array([prev.shift_x, prev.shift_y])
    sol = None
    for i in range(1, n_normal + 1):
        frac = {k: v * i / n_normal for k, v in normal.items()}
        sol = solver.solve(h, prev=prev, shift=base, **frac)
        prev = sol.state
    if mode == "load" and frictional:
        Q = np.array([ld.Qx or 0.0, ld.Qy or 0.0])
        for i in range(1, TANGENTIAL_INCREMENTS + 1):
            sol = solver.solve(h, prev=prev, Q=Q * i / TANGENTIAL_INCREMENTS, **normal)
            prev = sol.state
    elif mode == "shift":
        target = np.array([ld.shift_x or 0.0, ld.shift_y or 0.0])
        for i in range(1, TANGENTIAL_INCREMENTS + 1):
            shift = base + (target - base) * i / TANGENTIAL_INCREMENTS
            sol = solver.solve(h, prev=prev, shift=shift, **normal)
            prev = sol.state
    elif mode == "sliding":
        shift = base + SLIDE_FACTOR * max(case.grid.Lx, case.grid.Ly) * slide_direction(
            ld.slide_angle)
        sol = solver.solve(h, prev=prev, shift=shift, **normal)
    return sol


def solve(case: Case, progress: bool = False,
          on_output: Callable[[StepResult], None] | None = None) -> RunResult:
    """Solve a case: static cases in one step; wear cases through ``halfspace.wear``.
    ``on_output`` receives each output step as soon as it is computed."""
    if case.kind != "static":
        from .wear import solve_evolution

        return solve_evolution(case, progress=progress, on_output=on_output)
    t0 = time.perf_counter()
    solver = contact_solver(case)
    sol = static_step(case, solver, profile(case))
    zero = np.zeros((case.grid.nx, case.grid.ny))
    result = step_result(case, sol, stress_evaluator(case), step=0, wear_a=zero,
                         wear_b=zero.copy(), wall_s=time.perf_counter() - t0)
    if on_output is not None:
        on_output(result)
    return RunResult(case=case.name, solver=SOLVER_NAME, param=case.param, steps=[result],
                     meta={"method": case.solver.method, "fft_workers": WORKERS})
