"""The cost of one CalculiX run before it starts, for the planner and the deadline:
from the equations of its model (3 per node) and its Newton iterations.

``ccx`` solves each Newton iteration with SPOOLES (the only direct solver of Debian's
build; unsymmetric with friction): the time per iteration grows like the equations to
the power :data:`EXPONENT`.  Calibrated on the runs of benchmarks/README.md, "CalculiX
through the gates" (the constants below are those measurements' fit).
"""

from __future__ import annotations

from cases.model import Case
from cases.result import Cost

#: seconds per Newton iteration at :data:`REF_EQUATIONS` equations, with and without
#: friction (SPOOLES unsymmetric or symmetric), and the power of the equations it grows
#: with
REF_EQUATIONS = 2.0e4
SECONDS_FRICTION = 2.1
SECONDS_FRICTIONLESS = 0.6
EXPONENT = 1.76
#: Newton iterations per increment, and the tangential step's increments
ITERATIONS = 6
TANGENTIAL_INCREMENTS = 4
#: memory: the process's base and bytes per equation (SPOOLES' factor)
BASE_BYTES = 0.1e9
BYTES_PER_EQUATION = 1.2e4
#: measured wall times lie within this factor of the estimate
TIME_FACTOR = 4.0


def cost(case: Case) -> Cost:
    """The estimate (module doc)."""
    from .deck import approach_path
    from .mesh import node_count
    from .model import SIDE, element_size, radius_ratio
    from .support import symmetry

    a0 = case.hertz_scales[0]
    h = element_size(case)
    equations = 3 * node_count(a0, h, SIDE * a0, SIDE * a0, symmetry(case))
    first = min(1.0, 2.0 * h / a0)
    normal = approach_path(radius_ratio(case), first)[0].size  # and the force step
    tangential = TANGENTIAL_INCREMENTS if case.load.tangential_mode == "load" else 0
    per = SECONDS_FRICTION if case.friction.mu1 > 0 else SECONDS_FRICTIONLESS
    seconds = 2.0 + per * (equations / REF_EQUATIONS) ** EXPONENT * ITERATIONS * (
        normal + tangential)
    return Cost(memory=BASE_BYTES + BYTES_PER_EQUATION * equations, seconds=seconds,
                memory_keys=("fem.h",), time_keys=("fem.h",), time_factor=TIME_FACTOR)
