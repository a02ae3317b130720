"""The solver registry: one record per solver, the only place in ``reports`` that knows
solvers by name.

Every solver is a package exposing the same protocol:

- ``solve(case, *, progress=False, on_output=None) -> RunResult``: ``on_output`` receives
  each output step as soon as it is computed (a runner writes it at once);
- ``supports(case) -> str | None``: None when the solver handles the case, else the
  reason it does not (the runner skips it with that note);
- optionally ``estimate(case) -> cases.result.Cost``: its peak memory and wall time,
  before any work (the planner refuses a case beyond the limits, naming the keys).

The record adds what the reports need to know of a solver: its error budget against the
exact solution (the default tolerance of a pair is the sum of its two budgets, see
:mod:`reports.registry.tolerances`), its plot style, its representative cell size, and whether it
is a closed form (which may leave NaN where it says nothing and has no grid), and how to
refine or coarsen its discretisation for a grid study (``refine(case, factor)``: the
case grid for ``ic``, ``fem.h`` for ``fem``, none for closed forms).  Packages
are imported only when used, so a solver whose package fails to import is reported as
unavailable without breaking the others.  Adding a solver is one record here and one
package, or an installed plugin (:mod:`reports.registry.plugins`).

Error budgets (at the resolutions of the bundled cases, quick grids included), tightened
to the errors measured on the quick chain at main f6ca390 (its default-tolerance
rows, benchmarks/README.md: the worst error of each solver against the closed forms, and
of the pair ic-fem where no closed form exists) and kept above them by a margin for
cases not bundled:

- grid solvers (``ic``: piecewise-constant tractions on cells; the quick grids resolve a0
  with ≈ 4 cells): a peak value is a cell average, ≈ (h/a)²/12 below the point value
  (0.6 % at h/a = 0.27) plus the global discretisation error: 3 % for peak pressure and
  wear (the worn pin's step-like pressure: ic against Argatov's limit 4.6 %, of which
  2.5 % is that limit's own distance from the converged pressure, ``cases/pin_on_disk.toml``;
  wear volume of the fretting case 2.5 %), 1.5 % for σ_VM,max (an integral of the
  tractions, smoother than them; measured ≤ 0.93 %) and 2 % for ``vm_max_below`` (ic-fem
  2.9 % on the worn orthotropic pin, no closed form there).  Field norms include the
  cells next to the contact edge, where p ∝ √(a − r) changes by O(√(h/a)) over one cell:
  5 % in L2 (measured 3.4 %; ic-fem 7.4 % on the worn pin) and 5 % in the max norm, which
  leaves out the one-cell edge band (measured 0.9 % for the pressure, 2.4 % for fretting
  wear); σ_VM planes 2.5 % / 8 % (measured 1.6 % / 4.0 %; ic-fem max 14.0 % at the worn
  pin's edge); tangential tractions 8 % / 10 %, because in partial slip they also have a
  kink at the stick–slip boundary, resolved to a cell (measured 3.4 % / 5.9 %; on the
  1.6 mm / 81² grid of case 1 at Q/μP = 0.25 the slip annulus is 0.7 cell wide and the L2
  error 9.2 %, hence the finer cattaneo_mindlin grid).  Lengths are quantised to cells:
  semi-widths and the equivalent contact radius are good to one cell (measured 0.41 cell
  against the closed forms, but a grid study's three grids place the edge up to 0.9 cell
  apart: the quantisation, not the solver, sets this budget),
  the stick-zone radius to 1.5 cells (it also depends on the slip threshold), the σ_VM
  maximum (a broad maximum sampled on a lattice) to 1.5 cells or 0.3 a0 (one quick-grid
  cell is 0.26 a0; measured 1 cell, 0.26 a0).
- ``fem`` (P2 elements, h ≈ a0/8 in the contact, finite block 20 a0, node-wise
  augmented-Lagrangian contact): the grid budgets, except 1.5 % for p_max (measured
  0.13 % against the closed forms, 0.8 % on the worn pin against Argatov's limit less its
  2.5 %), 7 % for the pressure's max norm (measured 4.7 %: nodal values interpolated
  linearly), 15 % for the tangential max norm (off the stick band, where the √(c − r) kink lies
  between nodes, docs/formulation.md §2.7: measured 5.1 % on Cattaneo–Mindlin at the
  quick a0/10, 6.9 % at a0/12 with an a0/16 surface; the kink itself 0.21–0.23 at
  Q/μP = 0.25) and 5 % for
  wear quantities (the block's compliance acts on the wear increments).  σ_VM,max
  measured 1.04 % (Cattaneo–Mindlin), within the 1.5 %.
- closed forms (``analytic``: closed forms or converged quadrature, sampled on the
  solver's grid): 0.5 % for scalars, 1 % / 2 % for field norms, 0.5 cell for lengths read
  off a grid.

The budgets before this measurement (for the record): grid p_n/wear max 10 %, σ_VM,max
2 %, plane L2 3 %, tangential max 15 %; FEM p_max 3 %, p_n max 10 %.

Model-form terms (``model_form(quantity, metric)``, for the tolerances from grid studies,
:mod:`reports.studies.uncertainty`): what a solver models differently from the half-space
problem.  ``ic`` and the closed forms solve it as stated (0); the FEM's finite block is
measured by enlarging it (:data:`FEM_BLOCK_TERMS`, ``benchmarks/fem_block.py``).

Fretting loops and energy per cycle (``loop_q``: max |ΔQ| / μP over a cycle's loop
points; ``energy``: relative difference of the energy dissipated in the cycle, every
solver's ``energy`` being the trapezoidal rule ∮ Q dδ on its own ``steps_per_cycle``
steps, the analytic's too, so that the time rule — -1.0 | -0.86 % at 20 steps, -6.3 |
-5.6 % at 8, partial | gross slip — is not charged to the solver), measured with the
half-space solver against Mindlin–Deresiewicz on the bundled ``fretting_isotropic``
(tests/test_halfspace_fretting.py; approach 0.008 mm, μ = 0.3, 0.5 | 1.5 δ*):

- grid solvers: loop 0.25 % of μP — the grid error alone (ν = 0, where
  Mindlin–Deresiewicz is exact) is 0.19 | 0.11 % at 31² and 0.021 | 0.019 % at 61²;
  against the closed form with ν = 0.3, 0.10 | 0.14 % at the quick 31² and 8 steps
  (0.22 | 0.13 % with 20) and 0.034 | 0.073 % at 61².  Energy 3 % (the grid budget for scalars): the
  same-rule energy error is 2.5 | 0.005 % at 31² with 20 steps, 1.8 | 0.06 % with the
  quick 8 steps, 0.01 | 0.05 % at 61².
- closed forms: loop 0.1 % of μP — Cattaneo–Mindlin neglects the transverse slip for
  ν ≠ 0, the floor the solver converges to, 0.033 | 0.073 % at 121²; energy 0.5 %
  (the scalar budget; the same-rule difference is 0.24 | 0.04 % at 121²).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable

from cases.model import Case
from cases.result import Cost, RunResult
from reports.registry import plugins, relations
from reports.registry.discretisation import (
    fem_cell,
    fem_label,
    fem_reach,
    no_cell,
    refine_fem,
    refine_grid,
)
from reports.registry.errors import SolverUnavailable
from reports.registry.external import EXTERNAL, external_record, is_external
from reports.registry.record import SolverRecord

SolveFn = Callable[..., RunResult]

#: quantities measured per surface field, per plane and as scalars (see reports.registry.tolerances)
_PLANES = ("vm_xz", "vm_yz")
_TANGENTIAL = ("p_x", "p_y")
_WEAR = ("wear_a", "wear_b", "w_max", "wear_volume")


def grid_budget(quantity: str, metric: str) -> float:
    """Expected error of a solver on a regular grid of cells (module doc)."""
    if quantity in ("loop_q", "q_ends"):
        return 0.0025
    if metric == "rel":
        return {"vm_max": 0.015, "vm_max_below": 0.02}.get(quantity, 0.03)
    if metric in ("l2", "max"):
        if quantity in _PLANES:
            return 0.025 if metric == "l2" else 0.08
        if quantity in _TANGENTIAL:
            return 0.08 if metric == "l2" else 0.10
        return 0.05
    if metric == "cells":
        return 1.5 if quantity in ("stick_area", "vm_max_loc") else 1.0
    return 0.3  # a0: about one cell of the quick grids (h = 0.26 a0)


def fem_budget(quantity: str, metric: str) -> float:
    """Expected error of the P2 FEM with node-wise contact (module doc)."""
    if quantity in _WEAR and metric in ("rel", "l2"):
        return 0.05
    if metric == "max" and quantity in ("p_n", *_TANGENTIAL):
        return 0.07 if quantity == "p_n" else 0.15
    if quantity == "p_max":
        return 0.015
    return grid_budget(quantity, metric)


#: Argatov's worn-pin pressure P/(π a²) is the asymptotic (uniform-pressure) limit,
#: reported from 10 transition distances on (analytic.solver.ASYMPTOTIC_FROM), where it
#: is still 2.5 % below the converged pressure (half-space 81² and 161² agree to 0.4 %):
#: the closed form's model-form error, on every worn pin
ARGATOV_P_MAX = 0.025
#: Argatov's worn-pin depth √(i_w P s / (π R)) is asymptotic too: the converged depth of
#: the frictionless pin (41², 81², 121² agree to 0.03 %) is 1.62 % below it at 10.5
#: transition distances, 1.30 % at 14 and 0.76 % at 28 (benchmarks/README.md)
ARGATOV_W_MAX = 0.017


def closed_form_case_term(case: Case, quantity: str, metric: str) -> float:
    """What a closed form states beyond its sampling budget for a kind of case: the
    asymptotic worn-pin pressure and depth (:data:`ARGATOV_P_MAX`,
    :data:`ARGATOV_W_MAX`)."""
    if case.kind == "sliding_wear" and metric == "rel":
        return {"p_max": ARGATOV_P_MAX, "w_max": ARGATOV_W_MAX}.get(quantity, 0.0)
    return 0.0


def closed_form_budget(quantity: str, metric: str) -> float:
    """Expected error of a closed form sampled on a grid (module doc)."""
    if quantity in ("loop_q", "q_ends"):
        return 0.001
    return {"rel": 0.005, "l2": 0.01, "max": 0.02, "cells": 0.5, "a0": 0.02}[metric]


#: the FEM's finite block (half-width and depth 20 a0) against the half-space: the
#: largest relative change of a scalar when the block is enlarged to 40 a0 (quick
#: meshes, h = a0/8, the mesh regenerated), doubled because an error decaying like a0/L
#: leaves as much again beyond 40 a0.  Measured p_max / σ_VM,max changes: Hertz +0.05 /
#: -0.02 %, sliding sphere μ = 0.5 +0.16 / -0.29 %, Cattaneo–Mindlin Q/μP = 0.5 +0.16 /
#: -0.96 %, dissimilar +0.15 / +0.17 %.  vm_max_below takes the σ_VM,max term (not
#: measured separately); wear and lengths have none (no uncertainty-based tolerance).
FEM_BLOCK_TERMS = {"p_max": 2 * 0.0016, "vm_max": 2 * 0.0096, "vm_max_below": 2 * 0.0096}


def fem_model_form(quantity: str, metric: str) -> float:
    """Model-form term of the FEM (:data:`FEM_BLOCK_TERMS`) for the ``rel`` scalars it
    was measured for; NaN for the others (no uncertainty-based tolerance without it)."""
    return FEM_BLOCK_TERMS.get(quantity, math.nan) if metric == "rel" else math.nan


#: solver name -> record; the order is the order of columns, rows and pairs (the second
#: solver of a pair is its reference).
REGISTRY: dict[str, SolverRecord] = {
    "ic": SolverRecord("ic", "halfspace", budget=grid_budget, refine=refine_grid,
                       style={"color": "C0", "ls": "-", "marker": "o", "ms": 3}),
    "fem": SolverRecord("fem", "fem_reference", budget=fem_budget, cell_size=fem_cell,
                        label=fem_label, step_width=fem_cell, reach=fem_reach,
                        refine=refine_fem, model_form=fem_model_form,
                        style={"color": "C1", "ls": "--", "marker": "s", "ms": 3}),
    "analytic": SolverRecord("analytic", "analytic", budget=closed_form_budget,
                             case_term=closed_form_case_term,
                             cell_size=no_cell, closed_form=True,
                             style={"color": "k", "ls": ":", "marker": None}),
}
REGISTRY.update({
    f"ic+{rel.name}": SolverRecord(
        f"ic+{rel.name}", "halfspace", budget=relations.budget(rel, grid_budget),
        style={"color": "C2", "ls": "-", "marker": None, "lw": 0.8}, relation=rel,
        base="ic") for rel in relations.RELATIONS})
_BUILTIN = frozenset(REGISTRY)
#: the installed plugins (reports.registry.plugins) come first: every pair they are in
#: has a built-in solver as its reference; one line per plugin left out, and why
PLUGINS, PLUGIN_ERRORS = plugins.load(REGISTRY)
REGISTRY = {**PLUGINS, **REGISTRY}


#: what the reference of a pair is (metrics.csv's column ``oracle``)
CLOSED_FORM, OTHER_SOLVER, RELATION = "closed form", "other solver", "metamorphic relation"


def oracle(pair: str) -> str:
    """The kind of reference of pair ``"A-B"``: B a closed form, a metamorphic relation of
    A, or another solver."""
    a, _, b = pair.partition("-")
    rb = record(b)
    if rb.closed_form:
        return CLOSED_FORM
    return RELATION if rb.base == a else OTHER_SOLVER


def exact_pair(pair: str) -> bool:
    """Whether pair ``"A-B"`` is an exact metamorphic relation B of A: one discretisation
    of one problem, where every difference is a defect (nothing is taken out of the gate
    for its resolution or its band)."""
    a, _, b = pair.partition("-")
    rb = record(b)
    return rb.base == a and rb.relation is not None and rb.relation.exact


def _get(name: str) -> SolverRecord:
    """The record of a known solver (registered or external); KeyError otherwise."""
    if name in REGISTRY:
        return REGISTRY[name]
    if is_external(name):
        return external_record(name)
    raise KeyError(name)


def builtin(name: str) -> bool:
    """Whether ``name`` is one of this suite's own solvers (not a plugin, not external
    results): by name, whatever is installed."""
    return name in _BUILTIN


def names() -> list[str]:
    """All registered solver names, in registry order."""
    return list(REGISTRY)


def by_role(names: Iterable[str]) -> list[str]:
    """``names`` with the built-in solvers first, in their roles' order (the solver under
    test, the FEM, the closed forms, the metamorphic relations), then every other
    (plugins, names of another version) by name: an order that does not depend on what
    is installed, for whatever picks a solver of a case's results."""
    builtin = [n for n in REGISTRY if n not in PLUGINS]
    rank = {n: i for i, n in enumerate(builtin)}
    return sorted(dict.fromkeys(names), key=lambda n: (n not in rank, rank.get(n, 0), n))


def second_solvers(ran: Iterable[str], declined: Iterable[str]) -> list[str]:
    """The built-in solvers (relations left out) that a case's results lack: neither run
    (``ran``) nor declined by the case (``declined``), by role — what a hint that names
    a solver set that would compare a lonely solver draws from."""
    out = set(ran) | set(declined)
    return [s for s in by_role(n for n in REGISTRY if n not in PLUGINS)
            if s not in out and not record(s).base]


def record(name: str) -> SolverRecord:
    """The record of solver ``name``; a name not registered (results written by another
    version) gets a grid solver's defaults."""
    if is_external(name):
        return external_record(name)
    return REGISTRY.get(name) or SolverRecord(name, package="", budget=grid_budget)


def resolve(name: str) -> SolveFn:
    """The ``solve`` entry point of solver ``name``; SolverUnavailable if it cannot load."""
    if name not in REGISTRY and not is_external(name):
        raise SolverUnavailable(f"unknown solver {name!r} (known: {', '.join(REGISTRY)}, "
                                f"{EXTERNAL}NAME)")
    rec = _get(name)
    fn = rec.entry(rec.solve_attr)
    return relations.wrap(rec.relation, fn) if rec.relation is not None else fn


def available(name: str) -> tuple[bool, str]:
    """(True, '') if solver ``name`` loads, else (False, reason)."""
    try:
        resolve(name)
        rec = _get(name)
        rec.entry(rec.supports_attr)
    except SolverUnavailable as exc:
        return False, str(exc)
    return True, ""


def estimate(name: str, case: Case) -> Cost | None:
    """The solver's own estimate of what ``case`` will cost it (None if it makes none)."""
    rec = _get(name)
    try:
        fn = rec.entry(rec.estimate_attr)
    except SolverUnavailable:
        return None
    case = case if rec.relation is None else rec.relation.transform(case)
    if name not in PLUGINS:
        return fn(case)
    try:
        cost = fn(case)
    except Exception:  # a plugin's estimate is advice: without it, the run has no deadline
        return None
    return cost if isinstance(cost, Cost) else None


def not_by_default(name: str, case: Case) -> str | None:
    """Why a run that names no solvers leaves solver ``name`` out on ``case`` (its
    optional ``by_default``), None if it runs."""
    rec = _get(name)
    try:
        fn = rec.entry(rec.default_attr)
    except SolverUnavailable:
        return None
    reason = _ask(name, fn, case)
    return None if reason is None else str(reason)


def unsupported(name: str, case: Case) -> str | None:
    """Why solver ``name`` does not handle ``case`` (its ``supports``), None if it does."""
    rec = _get(name)
    if rec.relation is not None:
        if (why := relations.applies(case)) is not None:
            return why
        case = rec.relation.transform(case)
    reason = _ask(name, rec.entry(rec.supports_attr), case)
    return None if reason is None else str(reason)


def _ask(name: str, fn: Callable[[Case], object], case: Case) -> object:
    """``fn(case)``; for a plugin, what it raises becomes the reason it is left out of
    the case (the other solvers run on)."""
    if name not in PLUGINS:
        return fn(case)
    try:
        return fn(case)
    except Exception as exc:  # anything a foreign package raises
        return f"solver plugin {name!r}: {fn.__name__}() raised {type(exc).__name__}: {exc}"
