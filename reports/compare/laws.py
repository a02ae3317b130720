"""Exact relations of each solver's own results: the friction law and the peak pressure.

Coulomb's law bounds the tangential traction by the friction ellipse, ‖p_t‖_μ ≤ p_n
(Eqs. 9, 17), at every point of every solver: the half-space solver projects each cell's
traction onto it, the FEM each node's (its grid values interpolate them linearly, a
convex combination that stays inside the ellipse), the closed forms hold it exactly.
The metric ``excess`` of the quantity ``friction_law`` is the largest ‖p_t‖_μ − p_n over
the grid, over the solver's largest pressure; a pair's row is the larger of its two
solvers' (a solver that breaks the law fails every pair it is in, whatever the order),
gated at :data:`reports.registry.tolerances.OWN_ALLOWANCE`.  It sees what the pairwise
norms cannot at their tolerances: μ or the tangential tractions a few per cent high
(``benchmarks/README.md``, "Escapes").  Frictionless cases (μ₁ or μ₂ zero) and steps
without tractions have no row.

The peak pressure ``p_max`` a solver reports is the maximum of its pressure distribution
(``summary.csv``), so no sample of its ``p_n`` field exceeds it: the half-space solver's
field is its cells' values, the FEM's interpolates its nodes' linearly (a convex
combination), a closed form is sampled below its peak, a results file's grid
interpolates its nodes.  The metric ``excess`` of the quantity ``pressure_peak`` is
(max p_n − p_max) / p_max, the larger of the pair's two solvers, at the same allowance.
A field whose scalars were computed before it was scaled, or from another step, fails
it, where the pairwise norms allow a legitimate solver's discretisation error at the
quick grids (a pressure field 3 % high passes p_n's ``max`` and ``l2`` budgets).  A
solver without ``p_max`` or without a pressure has no row.
"""

from __future__ import annotations

import math

import numpy as np

from cases.model import Friction
from cases.result import StepResult
from reports.registry.tolerances import EXCESS, LAW, PEAK


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


def peak_excess(step: StepResult) -> float | None:
    """(max p_n − p_max) / p_max, at least 0 (module doc); None without a pressure field
    or a positive, finite ``p_max``."""
    s = step.surface
    try:
        p_max = float(step.scalars.get("p_max"))
    except (TypeError, ValueError):
        return None
    if not s or "p_n" not in s or not (math.isfinite(p_max) and p_max > 0):
        return None
    p_n = np.asarray(s["p_n"], float)
    if not np.isfinite(p_n).any():
        return None
    return max(float(np.nanmax(p_n)) - p_max, 0.0) / p_max


def rows(sa: StepResult, sb: StepResult, friction: Friction | None
         ) -> list[tuple[str, str, float]]:
    """The ``friction_law`` (with a friction) and ``pressure_peak`` rows of a pair: the
    larger excess of its two solvers."""
    out = []
    for quantity, of in ((LAW, lambda st: excess(st, friction) if friction else None),
                         (PEAK, peak_excess)):
        values = [v for v in (of(sa), of(sb)) if v is not None]
        if values:
            out.append((quantity, EXCESS, max(values)))
    return out
