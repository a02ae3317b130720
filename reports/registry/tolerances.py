"""Compared quantities, their metrics, the tolerance naming scheme and the defaults.

Naming scheme (documented in ``cases/README.md``):

================  ==================  ===================================================
quantity          metrics             meaning
================  ==================  ===================================================
p_n, p_x, p_y     l2, max             surface tractions over the contact (where both
wear_a, wear_b                        solvers have p_n > 0) and wear depths of body a / b
vm_xz, vm_yz      l2, max             σ_VM on the xz / yz plane through the load centre,
                                      over the contact's neighbourhood
P, p_max, w_max,  rel                 scalars of ``summary.csv`` (P the normal load: a
wear_volume,                          result where the approach is held); ``vm_max``
                                      the σ_VM
                                      maximum over the planes off the edge band, and
vm_max,                               ``vm_max_below`` the one at depth z ≥ z_below, its
vm_max_below                          companion where ``vm_max`` lies near the surface
                                      (:mod:`reports.compare.maxima`)
a_x, a_y          cells               contact semi-widths (half the contact's extent)
contact_area,     cells               equivalent radius √(A/π) of the contact / stick zone
stick_area
vm_max_loc        cells, a0           distance from each σ_VM maximum to the other
                                      solver's near-maximum set
loop_q            max                 fretting loop Q(δ) of an output cycle (table
                                      ``loops``), max |Q_A − Q_B| / μP over its points
q_ends            max                 the same at the loop's extremes δ = ±A only
energy            rel                 energy dissipated in that cycle (table ``cycles``)
friction_law      excess              max(‖p_t‖_μ − p_n) / max p_n of each solver's own
                                      fields, the larger of the two (the friction
                                      ellipse, Eq. 9: an exact law, tolerance
                                      ``OWN_ALLOWANCE`` for every pair,
                                      :mod:`reports.compare.laws`)
pressure_peak     excess              (max p_n − p_max) / p_max of each solver's own
                                      field and scalar, the larger of the two (no
                                      sample of a pressure exceeds its peak: exact,
                                      ``OWN_ALLOWANCE``, :mod:`reports.compare.laws`)
================  ==================  ===================================================

Metrics, with A the first and B the second (reference) solver of the pair:
``l2`` = ‖A − B‖₂ / ‖B‖₂ and ``max`` = max|A − B| / max|B| on common sample points (for
``p_x`` and ``p_y`` the denominators are the norms of B's whole tangential traction
|p_t| = √(p_x² + p_y²), so a component that is nearly zero in both is not inflated, and
where B carries no tangential traction at all they are μ p0 (the largest traction the
contact can carry, :func:`reports.compare.metrics.tangential_scale`; p0 without
friction), so that a traction that should not be there, or one that is missing from B,
is measured on its own size and not on p0 (at μ = 0.04 the whole traction is 4 % of p0);
for
``wear_a`` or ``wear_b`` where B wears only the other body, those of B's whole wear);
max norms leave out the *edge band*, the sample points within one cell of either
solver's contact boundary (on the planes: within one cell, the coarser sample spacing,
of the boundary's surface points, by the distance in space), where a cell average and a
point value of a traction that drops to zero inside the cell differ by a fraction of the
traction itself — O(1) for the step-like pressure edge of a worn contact at any grid
size (:mod:`reports.compare.metrics`); the L2 norms of
the tractions, the semi-widths and the contact area still measure the edge; the plane
norms leave the band out and are taken over the points within one contact half-chord of
the contact (its neighbourhood: the norms do not depend on how far a case's planes
extend); the max norms of ``p_x`` and ``p_y`` and both norms of ``vm_xz`` and ``vm_yz``
also leave out the *stick band*, the points within one cell (the coarser solver's own
cell) of either solver's stick–slip boundary, where the traction has a √(c − r) kink
that no field held at points h apart follows (docs/formulation.md §2.7): the max over
that band is written as the metric ``kink`` beside the max's tolerance, with status
"not gated", and is never gated (it has no tolerance key);
``rel`` = |A − B| / |B|; for ``loop_q`` ``max`` = max over the cycle's loop points of
|Q_A − Q_B| (the tangential load vector on body a) / μP, μ the friction coefficient along
the path direction and P the case's Hertz load (:func:`reports.compare.metrics.friction_scale`),
the points of the two loops matched by their imposed displacements (loops of different
paths are not compared); ``cells`` = a length difference in units of the coarser of the
two solvers' cell sizes (the larger of the sample spacing and each solver's own cell,
``SolverRecord.cell_size``: the FEM's element size); ``a0`` = a length difference in
units of the Hertz radius.

Tolerance keys: the quantity name for a single-metric quantity (``p_max``, ``a_x``), else
``<quantity>_<metric>`` (``p_n_l2``, ``vm_xz_max``, ``vm_max_loc_cells``); prefixed with a
pair and a dot (``"ic-fem.p_max"``, a quoted TOML key) it applies to that pair only.
Lookup order: pair-specific key in the case, plain key in the case, default of the pair.

Not gated.  A quantity that is not a converged number is compared and shown but not
gated: its metric rows carry ``status`` "not gated", a ``reason`` code and a ``note``
saying why.  The
code decides it from the run, with a converged companion gated in its place: the
maxima over the stick band (``kink``) and over the edge band (``vm_max`` ``edge``), a
σ_VM maximum near the surface (``vm_max`` ``surface``, companion ``vm_max_below``,
:mod:`reports.compare.maxima`), a field that lives in a zone narrower than its
resolution floor (:mod:`reports.registry.resolution`; companions the stick and contact
radii), and a grid or jump study of the run whose status for the quantity is neither
converged nor exact for either solver of the pair (:func:`reports.studies.gridstudy.flags`).
A case file may still declare a quantity in its ``[not_converged]`` table (quantity ->
the reason, with the measured values), for what is model form; it may not both declare a
quantity not converged and set a tolerance for it.

Defaults.  Each solver has an *error budget* per metric: the error it is expected to make
against the exact solution at the resolution the bundled cases use (quick grids
included), held in its registry record (:mod:`reports.registry.solvers`, where the reasoning is);
the default tolerance of a pair is the sum of its two budgets, because by the triangle
inequality |A − B| ≤ |A − exact| + |B − exact|.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from cases.model import Case, CaseError
from reports.registry import solvers
from reports.registry.pairs import pair_names

SURFACE_FIELDS = ("p_n", "p_x", "p_y", "wear_a", "wear_b")
PLANE_FIELDS = {"vm_xz": "xz", "vm_yz": "yz"}
REL_SCALARS = ("P", "p_max", "w_max", "wear_volume", "vm_max", "vm_max_below")
LENGTH_SCALARS = ("a_x", "a_y")
AREA_SCALARS = ("contact_area", "stick_area")
#: quantities computed from the solvers' tables per cycle (fretting): table, metric
TABLE_QUANTITIES = {"loop_q": ("loops", "max"), "q_ends": ("loops", "max"),
                    "energy": ("cycles", "rel")}

#: the exact relations checked on each solver's own results (:mod:`reports.compare.laws`):
#: the friction law, and the pressure field bounded by the peak pressure the solver reports
LAW, PEAK, EXCESS = "friction_law", "pressure_peak", "excess"
OWN_RELATIONS = (LAW, PEAK)
#: their tolerance, a fraction of the peak pressure, the same for every pair: above the
#: round-off and the contact iterations' residuals (relative 1e-6 and below) and a results
#: file written to four significant digits (5e-5 on each component); a friction
#: coefficient, a traction or a pressure field 0.5 % high exceeds it five times
OWN_ALLOWANCE = 1e-3

#: quantity -> its metrics, in the order rows are written.
QUANTITY_METRICS: dict[str, tuple[str, ...]] = {
    **{q: ("l2", "max") for q in SURFACE_FIELDS},
    **{q: ("l2", "max") for q in PLANE_FIELDS},
    **{q: ("rel",) for q in REL_SCALARS},
    **{q: ("cells",) for q in LENGTH_SCALARS + AREA_SCALARS},
    "vm_max_loc": ("cells", "a0"),
    **{q: (m,) for q, (_, m) in TABLE_QUANTITIES.items()},
    LAW: (EXCESS,),
    PEAK: (EXCESS,),
}

def tolerance_key(quantity: str, metric: str) -> str:
    """The tolerance key of a (quantity, metric): bare for single-metric quantities."""
    return quantity if len(QUANTITY_METRICS[quantity]) == 1 else f"{quantity}_{metric}"


#: every valid (pair-less) tolerance key -> (quantity, metric)
KEYS: dict[str, tuple[str, str]] = {
    tolerance_key(q, m): (q, m) for q, ms in QUANTITY_METRICS.items() for m in ms
}


def budget(solver: str, quantity: str, metric: str) -> float:
    """Expected error of one solver against the exact solution (its registry record)."""
    return solvers.record(solver).budget(quantity, metric)


def default_tolerance(pair: str, quantity: str, metric: str) -> float:
    """Default tolerance of a pair ``"A-B"``: the sum of the two solvers' budgets; for a
    metamorphic relation B of A, B's allowance alone (:mod:`reports.registry.relations`)."""
    a, _, b = pair.partition("-")
    if quantity in OWN_RELATIONS:  # exact on each solver's own results: no budget
        return OWN_ALLOWANCE
    if solvers.record(b).base == a:
        return budget(b, quantity, metric)
    return budget(a, quantity, metric) + budget(b, quantity, metric)


def tolerance(case: Case, pair: str, quantity: str, metric: str) -> tuple[float, str]:
    """(tolerance, the key it came from) for one metric of one pair of a case."""
    key = tolerance_key(quantity, metric)
    for candidate in (f"{pair}.{key}", key):
        if candidate in case.tolerances:
            return case.tolerances[candidate], candidate
    if quantity in OWN_RELATIONS:
        return default_tolerance(pair, quantity, metric), f"default:{key}"
    terms = sum(solvers.record(s).case_term(case, quantity, metric) for s in pair.split("-"))
    return default_tolerance(pair, quantity, metric) + terms, f"default:{key}"


def check_keys(case: Case, solver_names: list[str]) -> None:
    """Refuse tolerance keys that name no quantity, metric or pair (typos would be ignored)."""
    for raw in case.tolerances:
        pair, dot, key = raw.rpartition(".")
        if key not in KEYS:
            known = ", ".join(sorted(KEYS))
            raise CaseError(f"tolerances.{raw}: unknown tolerance key {key!r} (known: {known})")
        if dot and pair not in (known := pair_names(solver_names)):
            raise CaseError(f"tolerances.{raw}: {pair!r} is not a compared pair (the pairs, "
                            f"in the order compared: {', '.join(known)})")
        if not math.isfinite(case.tolerances[raw]):
            raise CaseError(f"tolerances.{raw}: must be finite")
        if KEYS[key][0] in case.not_converged:
            raise CaseError(f"tolerances.{raw}: {KEYS[key][0]!r} is declared not converged "
                            "([not_converged]); it is not gated, so a tolerance for it is "
                            "meaningless (remove one of the two)")
    for quantity in case.not_converged:
        if quantity not in QUANTITY_METRICS:
            raise CaseError(f"not_converged.{quantity}: unknown quantity (known: "
                            f"{', '.join(sorted(QUANTITY_METRICS))})")
    if {"vm_max", "vm_max_below"} <= set(case.not_converged):
        raise CaseError("not_converged: vm_max and vm_max_below both declared: no σ_VM "
                        "maximum would be gated at all (vm_max_below, the maximum below the "
                        "surface layer, is the one kept where vm_max does not converge)")


#: the ``status`` of a metric row: gated, or shown and not gated (why: its ``reason``)
GATED, NOT_GATED = "gated", "not gated"
#: the ``status`` earlier releases wrote for a row not gated, read as :data:`NOT_GATED`
OLD_STATUS = {"not converged": NOT_GATED}

#: why a metric row is shown and not gated: the closed set of metrics.csv's ``reason``
#: codes (set where the decision is made, never read back from the note), each with the
#: words the gate's case line, the report and the baselines name it by
REASONS = {
    "declared": "declared",  # the case file's [not_converged] (status below)
    "floor": "below a resolution floor",  # reports.registry.resolution
    "stick_band": "stick band",  # reports.compare.metrics (KINK_NOTE)
    "edge_band": "edge band",  # reports.compare.maxima (EDGE_NOTE)
    "surface": "maximum on the surface",  # reports.compare.maxima (SURFACE_NOTE)
    "grid_study": "grid study",  # reports.studies.gridstudy
    "jump_study": "jump study",  # reports.studies.jumpstudy
    "probe": "resolution probe",  # reports.studies.probe
    "study": "a study",  # a study that names no code of its own (reports.studies.study)
}
#: the reason of a row metrics.csv holds without one (written before the column)
UNRECORDED = "unrecorded"


def reason_words(code: str) -> str:
    """The words of a ``reason`` code (:data:`REASONS`)."""
    return REASONS.get(code, "reason not recorded" if code in ("", UNRECORDED) else code)


def status(case: Case, quantity: str) -> tuple[str, str, str]:
    """(status, note, reason) of a quantity's metric rows from the case file."""
    if quantity in case.not_converged:
        return (NOT_GATED,
                "declared: " + " ".join(case.not_converged[quantity].split()), "declared")
    return GATED, "", ""


#: ``tolerance_kind`` of a metric row: the pair's default (the sum of its two budgets), a
#: key of the case file, or the combined uncertainty of grid studies
#: (:mod:`reports.studies.uncertainty`)
BUDGET, CASE, UNCERTAINTY = "budget", "case", "uncertainty"
KINDS = (BUDGET, CASE, UNCERTAINTY)
#: the columns metrics.csv holds about a row's tolerance, after those of the comparison
TOLERANCE_COLUMNS = ["tolerance_kind", "budget", "uncertainty"]


def kind_of(tolerance_key: str) -> str:
    """The kind of a tolerance found by :func:`tolerance`."""
    return BUDGET if tolerance_key.startswith("default:") else CASE


def with_tolerance_columns(metrics: pd.DataFrame) -> pd.DataFrame:
    """``metrics`` with :data:`TOLERANCE_COLUMNS` present: from the tolerance key and the
    tolerance where they are missing (a fresh comparison, or a file an older run wrote)."""
    out = metrics.copy()
    if "tolerance_kind" not in out.columns:
        keys = out["tolerance_key"].fillna("") if "tolerance_key" in out.columns else \
            pd.Series("default:", index=out.index)
        out["tolerance_kind"] = [kind_of(str(k)) for k in keys]
    if "budget" not in out.columns:
        out["budget"] = out["tolerance"].astype(float)
    if "uncertainty" not in out.columns:
        out["uncertainty"] = math.nan
    return out


def passes(value, tolerance) -> np.ndarray:
    """The pass rule, the only place ``passed`` is computed: a metric passes iff value and
    tolerance are finite numbers and value <= tolerance (elementwise)."""
    v, t = np.asarray(value, float), np.asarray(tolerance, float)
    with np.errstate(invalid="ignore"):
        return np.isfinite(v) & np.isfinite(t) & (v <= t)
