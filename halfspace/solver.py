"""Run a case through the half-space solver and return the common result ("ic")."""

from __future__ import annotations

import time
from collections.abc import Callable

import numpy as np

from cases.model import Case
from cases.result import RunResult, StepResult
from cases.steps import normal_fractions

from .contact import ContactSolver, ContactState, StepSolution
from .operator import WORKERS
from .output import SOLVER_NAME, step_result
from .problem import contact_solver, profile, slide_direction, stress_evaluator
from .wear import solve_evolution

SLIDE_FACTOR = 1e6  # rigid slip of a gross-sliding step, in units of the grid size
TANGENTIAL_INCREMENTS = 5  # tangential loading steps after the normal load


def static_step(case: Case, solver: ContactSolver, h: np.ndarray,
                prev: ContactState | None = None) -> StepSolution:
    """Solve a static case along its load path: the normal load (or approach) first,
    the tangential load (or shift) after it (cases.md, case 2).  With friction the result
    depends on the path when the materials couple normal and tangential (K != 0) or the
    tangential load is not monotonic in direction, so the normal load is applied in the
    increments of :func:`cases.steps.normal_fractions` when coupled and a tangential load
    or shift in ``TANGENTIAL_INCREMENTS`` steps, each with the slip history of the
    previous one (the same path as the FEM reference).  Gross sliding is one step after
    the normal load."""
    ld = case.load
    mode = ld.tangential_mode
    frictional = case.friction.mu1 > 0
    normal = ({"P": ld.P} if ld.load_controlled else {"approach": ld.approach})
    fractions = normal_fractions(case) if frictional and solver.op.coupled else (1.0,)
    base = np.zeros(2) if prev is None else np.array([prev.shift_x, prev.shift_y])
    sol = None
    for f in fractions:
        sol = solver.solve(h, prev=prev, shift=base, **{k: v * f for k, v in normal.items()})
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
