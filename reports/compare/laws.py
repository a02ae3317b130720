"""The friction law as an exact relation of each solver's own fields.

Coulomb's law bounds the tangential traction by the friction ellipse, ‖p_t‖_μ ≤ p_n
(Eqs. 9, 17), at every point of every solver: the half-space solver projects each cell's
traction onto it, the FEM each node's (its grid values interpolate them linearly, a
convex combination that stays inside the ellipse), the closed forms hold it exactly.
The metric ``excess`` of the quantity ``friction_law`` is the largest ‖p_t‖_μ − p_n over
the grid, over the solver's largest pressure; a pair's row is the larger of its two
solvers' (a solver that breaks the law fails every pair it is in, whatever the order),
gated at :data:`reports.registry.tolerances.LAW_ALLOWANCE`.  It sees what the pairwise
norms cannot at their tolerances: μ or the tangential tractions a few per cent high
(``benchmarks/README.md``, "Escapes").  Frictionless cases (μ₁ or μ₂ zero) and steps
without tractions have no row.
"""

from __future__ import annotations

import math

import numpy as np

from cases.model import Friction
from cases.result import StepResult
from reports.registry.tolerances import EXCESS, LAW


def excess(step: StepResult, friction: Friction) -> float | None:
    """max(‖p_t‖_μ − p_n) / max p_n over the step's grid (module doc); None without
    friction in both directions, without the three tractions or without a pressure."""
    s = step.surface
    if friction.mu1 <= 0 or friction.mu2 <= 0 or not s \
            or any(k not in s for k in ("p_n", "p_x", "p_y")):
        return None
    p_n, p_x, p_y = (np.asarray(s[k], float) for k in ("p_n", "p_x", "p_y"))
    p_max = float(np.nanmax(p_n, initial=0.0))
    if not p_max > 0:
        return None
    b = math.radians(friction.beta)
    p_1 = math.cos(b) * p_x + math.sin(b) * p_y  # in the friction axes e1, e2 (Eq. 9)
    p_2 = -math.sin(b) * p_x + math.cos(b) * p_y
    over = np.hypot(p_1 / friction.mu1, p_2 / friction.mu2) - p_n
    if not np.isfinite(over).any():
        return None
    return max(float(np.nanmax(over)), 0.0) / p_max


def rows(sa: StepResult, sb: StepResult, friction: Friction
         ) -> list[tuple[str, str, float]]:
    """The ``friction_law`` row of a pair: the larger excess of its two solvers."""
    values = [v for v in (excess(sa, friction), excess(sb, friction)) if v is not None]
    return [(LAW, EXCESS, max(values))] if values else []
