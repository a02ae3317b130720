"""The resolution from which the numerical solvers' error budgets hold.

The budgets of :mod:`reports.registry.solvers` are errors at a resolution: a field that
lives in a zone a few cells wide is not a number a grid of that size gives to its budget.
Two lengths of a step set the resolution, counted in the coarser of the pair's cells
(the sample spacing, or the FEM's element): the contact radius a and the width of the
slip zone, a − c (c the stick radius; the whole radius in full sliding and gross slip).
A quantity whose zone spans fewer cells than its floor is compared and shown, not gated,
with the reason; its companions stay gated — the stick radius (``stick_area``), the
contact radius and area, the pressure, the stresses — so a solver cannot hide a defect
by narrowing a zone (docs/formulation.md §2.7).

Floors, measured with the half-space solver against the closed forms on generated cases
(``tests/test_false_alarms.py``; ``benchmarks/README.md``, "False alarms"):

- the pressure's L2 norm (``p_n_l2``): a contact radius of 4 cells (its error sits in the edge
  cells, the partly covered ones, and depends on where the edge falls in them: Hertz
  L2 1.4–4.5 % from 4 to 8 cells per radius, up to 7 % at 3.5, against a budget of 5 %);

- the tangential tractions ``p_x``, ``p_y``: a slip zone of 1.5 cells (Cattaneo–Mindlin
  with an annulus under one cell misses Mindlin's traction by 9–15 % in L2, against a
  budget of 8 %);
- the wear fields, their maximum and the worn volume (``wear_a``, ``wear_b``, ``w_max``,
  ``wear_volume``): a slip zone of 5 cells (the first fretting cycle's wear in partial
  slip concentrates in the annulus as (r − c)^3/2, and in gross slip the wear depth
  follows the pressure's √ edge);
- the fretting loop (``loop_q``): a slip zone of 1.5 cells and a contact radius of 8
  cells (the loop's tangential compliance converges at order 2–3: 0.19 % of μP at 10
  cells per radius, 0.4 % at 6.3, about 1 % at 5, against a budget of 0.25 %);
- the energy dissipated in a cycle (``energy``): as the wear, a slip zone of 5 cells
  (it is dissipated in the slip zone: 5.3 % at 2.1 cells, against 3 %), and a contact
  radius of 8 cells;
- the σ_VM planes (``vm_xz``, ``vm_yz``): the plane one cell inside the contact edge,
  a − |y0| for the xz plane through y0 (a − |x0| for the yz plane) — a plane off the
  centre within a cell of the edge crosses the contact where its discretised edge
  shapes the whole plane (``benchmarks/README.md``, "Stress planes off the centre").
"""

from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class Resolution:
    """How many cells span the contact radius, the slip zone, and the distances from the
    xz and yz stress planes to the contact edge of a step."""

    contact: float
    slip: float
    inset_xz: float = math.inf
    inset_yz: float = math.inf


#: quantity (all its metrics) or ``<quantity>_<metric>`` -> the lengths and the cells each
#: must span for the budgets to hold
FLOORS: dict[str, tuple[tuple[str, float], ...]] = {
    "p_n_l2": (("contact", 4.0),),
    "p_x": (("slip", 1.5),),
    "p_y": (("slip", 1.5),),
    "wear_a": (("slip", 5.0),),
    "wear_b": (("slip", 5.0),),
    "w_max": (("slip", 5.0),),
    "wear_volume": (("slip", 5.0),),
    "loop_q": (("slip", 1.5), ("contact", 8.0)),
    "energy": (("slip", 5.0), ("contact", 8.0)),
    "vm_xz": (("inset_xz", 1.0),),
    "vm_yz": (("inset_yz", 1.0),),
}
_NAMES = {"slip": "slip zone", "contact": "contact radius",
          "inset_xz": "distance from the xz plane to the contact edge",
          "inset_yz": "distance from the yz plane to the contact edge"}


def unresolved(quantity: str, metric: str, resolution: Resolution | None) -> str:
    """Why ``quantity`` (its ``metric``) is not a number at ``resolution`` ('' when it is)."""
    if resolution is None:
        return ""
    floors = FLOORS.get(f"{quantity}_{metric}", ()) + FLOORS.get(quantity, ())
    for length, cells in floors:
        have = getattr(resolution, length)
        if math.isfinite(have) and have < cells:
            return (f"not resolved: the {_NAMES[length]} spans {have:.2g} cells, the budget "
                    f"of {quantity} holds from {cells:g} (reports.registry.resolution)")
    return ""
