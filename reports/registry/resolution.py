"""The resolution from which the numerical solvers' error budgets hold.

The budgets of :mod:`reports.registry.solvers` are errors at a resolution: a field that
lives in a zone a few cells wide is not a number a grid of that size gives to its budget.
Two lengths of a step set the resolution, counted in the coarser of the pair's cells
(the sample spacing, or the FEM's element): the contact radius a and the width of the
slip zone, a − c (c the stick radius; the whole radius in full sliding and gross slip).
Both are the reference's (:func:`reports.compare.point.step_resolution`): a closed form's
own, which it states (Cattaneo–Mindlin's c, Spence's (SP1) bound, none in full sliding),
else the union of the two solvers' zones (the larger contact radius, the smaller stick
radius) — never the solver's under test alone, so a solver that reports no slip zone
where there is one is judged on its tractions, not exempted by its own zone.
A quantity whose zone spans fewer cells than its floor is compared and shown, not gated,
with the reason; its companions stay gated — the stick radius (``stick_area``), the
contact radius and area, the pressure, the stresses — so a solver cannot hide a defect
by narrowing a zone (docs/formulation.md §2.7).

Floors, measured with the half-space solver against the closed forms on generated cases
(``tests/test_suite_false_alarms.py``; ``benchmarks/README.md``, "False alarms"):

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
- the fretting loop (``loop_q``, and ``q_ends`` at its extremes): a slip zone of 1.5
  cells and a contact radius of 8 cells (the loop's tangential compliance converges at
  order 2–3: 0.19 % of μP at 10 cells per radius, 0.4 % at 6.3, about 1 % at 5, against
  a budget of 0.25 %);
- the energy dissipated in a cycle (``energy``): as the wear, a slip zone of 5 cells
  (it is dissipated in the slip zone: 5.3 % at 2.1 cells, against 3 %), and a contact
  radius of 8 cells;
- where the resolution probe runs (a worn point, the half-space solver beside a solver
  with a step width, :mod:`reports.studies.probe`), the floors of the wear quantities
  (:data:`PROBED_FLOORS`) count the probing solver's own cells in the rows of the pairs
  it judges: what the coarser element does to the narrow worn annulus is what the probe
  measures (it predicts the FEM's distance in the wear, ``benchmarks/README.md``, "The
  resolution probe"), and the floor is left to judge the probing solver's own grid;
- the pressure's maximum (``p_max``, ``p_n`` max) where friction couples dissimilar
  materials (Dundurs' β ≠ 0) and the stick disc is narrower than 0.9 of the contact
  (:data:`reports.compare.point.PEAK_DISC`): a stick radius of 5 cells — the pressure
  peaks in the stick disc, at a cusp of the self-similar solution, and becomes singular
  at the centre as the disc shrinks to nothing in full slip (docs/formulation.md §2.9),
  so a grid holds the peak only where the disc spans cells (``benchmarks/README.md``,
  "Spence's compression, exact"); a disc that fills the contact leaves a peak as broad
  as Hertz's; the pressure's L2 norm, the load and the contact radius stay gated;
- the σ_VM planes (``vm_xz``, ``vm_yz``): the plane one cell inside the contact edge,
  a − |y0| for the xz plane through y0 (a − |x0| for the yz plane) — a plane off the
  centre within a cell of the edge crosses the contact where its discretised edge
  shapes the whole plane (``benchmarks/README.md``, "Stress planes off the centre").
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from cases.model import Case
from reports.registry import solvers


@dataclass(frozen=True)
class Resolution:
    """How many cells span the contact radius, the slip zone, and the distances from the
    xz and yz stress planes to the contact edge of a step."""

    contact: float
    slip: float
    inset_xz: float = math.inf
    inset_yz: float = math.inf
    #: the stick radius where the pressure peaks in the stick disc: friction between
    #: dissimilar materials (module doc); inf elsewhere
    stick: float = math.inf


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
    "q_ends": (("slip", 1.5), ("contact", 8.0)),
    "energy": (("slip", 5.0), ("contact", 8.0)),
    "vm_xz": (("inset_xz", 1.0),),
    "vm_yz": (("inset_yz", 1.0),),
    "p_max": (("stick", 5.0),),
    "p_n_max": (("stick", 5.0),),
}
_NAMES = {"slip": "slip zone", "contact": "contact radius", "stick": "stick radius",
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


#: the solver that probes: its wear increments can be spread (``solver.wear_spread``)
PROBE_SOLVER = "ic"
#: the quantities whose floors count the probing solver's cells where the probe judges
#: (module doc)
PROBED_FLOORS = ("wear_a", "wear_b", "w_max", "wear_volume")


def wears(case: Case) -> bool:
    """Whether ``case`` wears: a sliding-wear or fretting case with a wear coefficient."""
    if case.kind not in ("sliding_wear", "fretting"):
        return False
    return any(v > 0 for v in (case.a.i1, case.a.i2, case.b.i1, case.b.i2))


def probed_width(case: Case, solver_names: list[str]) -> float | None:
    """The widest step width [mm] (:attr:`reports.registry.record.SolverRecord.step_width`)
    among ``solver_names`` on a worn ``case`` run beside :data:`PROBE_SOLVER`: what the
    resolution probe spreads the wear over (None: nothing to probe)."""
    if not wears(case) or PROBE_SOLVER not in solver_names:
        return None
    widths = [float(w(case)) for s in solver_names
              if (w := solvers.record(s).step_width) is not None]
    return max(widths) if widths else None


def probed_pair(pair: str) -> bool:
    """Whether the probe judges the rows of ``pair``: it holds a solver with a step width."""
    return any(solvers.record(s).step_width is not None for s in pair.split("-", 1))
