"""One output step of the half-space solver in the common result format
(:class:`cases.result.StepResult`): summary scalars, surface fields, stress planes."""

from __future__ import annotations

import numpy as np

from cases.model import Case
from cases.result import SLIP, STICK, StepResult, semi_widths, vm_max_location

from .contact import StepSolution
from .stresses import StressEvaluator

SOLVER_NAME = "ic"


def step_result(case: Case, sol: StepSolution, stresses: StressEvaluator, *, step: int,
                wear_a: np.ndarray, wear_b: np.ndarray, wall_s: float,
                s: float = np.nan, cycle: float = np.nan) -> StepResult:
    """Collect the summary scalars, surface fields and stress planes of one step."""
    g = case.grid
    dA = g.dx * g.dy
    st = sol.state
    planes = stresses.planes(st.p_x, st.p_y, st.p_n, case.stress.x0, case.stress.y0)
    x_plane, y_plane = stresses.plane_centre(case.stress.x0, case.stress.y0)
    vm, vx, vy, z_at = vm_max_location(planes, x_plane, y_plane)
    a_x, a_y = semi_widths(g.x, g.y, st.p_n)
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
        x0=x_plane, y0=y_plane,  # where the planes were sampled (the nearest cell centres)
        residual_n=sol.residual_n, residual_t=sol.residual_t,
    )
    surface = dict(p_n=st.p_n, p_x=st.p_x, p_y=st.p_y, gap=sol.gap, slip_x=sol.slip_x,
                   slip_y=sol.slip_y, wear_a=wear_a, wear_b=wear_b,
                   state=sol.status.astype(np.int8))
    return StepResult(scalars=scalars, x=g.x.copy(), y=g.y.copy(), surface=surface,
                      planes=planes)
