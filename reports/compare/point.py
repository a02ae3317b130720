"""The metric rows of one sweep point: every pair of solvers (a metamorphic relation with
its base only), every output step both have, each row with the status and tolerance the
comparisons see themselves — the bands' maxima and a near-surface maximum shown, not
gated (:mod:`reports.compare.maxima`), a field in a zone narrower than its resolution
floor shown with the width (:mod:`reports.registry.resolution`) — and the oracle it used.
The verdict on the rows, with a run's studies, is :func:`reports.compare.verdict.decide`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
import pandas as pd

from cases.model import Case
from cases.result import RunResult, StepResult
from reports.compare import maxima
from reports.compare.cycles import compare_tables, friction_scale
from reports.compare.metrics import KINK, KINK_NOTE, compare_steps, scalar
from reports.compare.sampling import spacing
from reports.compare.verdict import EXTRA_COLUMNS, METRICS_COLUMNS, decide
from reports.registry import solvers
from reports.registry import tolerances as tol
from reports.registry.pairs import pairs
from reports.registry.resolution import (
    PROBE_SOLVER,
    PROBED_FLOORS,
    Resolution,
    probed_pair,
    probed_width,
    unresolved,
)

#: metrics written beside a gated one but never gated: -> (the gated metric whose
#: tolerance they are shown against, why they are not gated)
_SHOWN = {KINK: ("max", KINK_NOTE, "stick_band"),
          maxima.EDGE: ("rel", maxima.EDGE_NOTE, "edge_band"),
          maxima.SURFACE: ("rel", maxima.SURFACE_NOTE, "surface")}


def pair_cell(case: Case, a: str, b: str) -> float:
    """The coarser of the cells of solvers ``a`` and ``b`` on ``case`` (0: neither has one)."""
    return _coarser(solvers.record(n).cell_size(case) for n in (a, b))


def pair_reach(case: Case, a: str, b: str) -> float:
    """The longer of the stress reaches of solvers ``a`` and ``b`` on ``case``
    (``SolverRecord.stress_reach``; 0: neither has one)."""
    return _coarser(solvers.record(n).stress_reach(case) for n in (a, b))


def _coarser(lengths) -> float:
    """The largest of the finite ``lengths`` (0: none is)."""
    return max((c for c in lengths if math.isfinite(c)), default=0.0)


def common_steps(ra: RunResult, rb: RunResult) -> list[tuple[int, StepResult, StepResult]]:
    """(step number, step of A, step of B) for every output step both results have."""
    steps_a = {s.number(i): s for i, s in enumerate(ra.steps)}
    steps_b = {s.number(i): s for i, s in enumerate(rb.steps)}
    return [(n, steps_a[n], steps_b[n]) for n in sorted(set(steps_a) & set(steps_b))]


def step_values(case: Case, pair: str, ra: RunResult, rb: RunResult, sa: StepResult,
                sb: StepResult, cell: float, reach: float) -> list[tuple[str, str, float]]:
    """(quantity, metric, value) of one common step of A (``ra``) against reference B
    (``rb``): the fields and scalars (:func:`reports.compare.metrics.compare_steps`) and,
    at an output cycle, the loop and its energy (:func:`reports.compare.cycles.compare_tables`);
    ``cell`` and ``reach`` the pair's (:func:`pair_cell`, :func:`pair_reach`).  The one
    definition of every row's value."""
    a0, p0 = case.hertz_scales
    x0, y0 = case.plane_centre
    rows = compare_steps(sa, sb, a0=a0, p0=p0, x0=x0, y0=y0, cell=cell,
                         reach=reach,
                         z_below=case.stress.z_below, friction=case.friction,
                         vm_rel=tol.tolerance(case, pair, "vm_max", "rel")[0])
    cycle = scalar(sb, "cycle")
    if math.isfinite(cycle):
        rows += compare_tables(ra.tables, rb.tables, cycle, friction_scale(case))
    return rows


def point_rows(case: Case, results: Mapping[str, RunResult], probed: bool = False
               ) -> pd.DataFrame:
    """The metric rows of one sweep point, before the verdict: every pair, every common
    output step, with the status and tolerance the comparisons see themselves.
    ``probed``: the run probes this point (:mod:`reports.studies.probe`), so the wear
    floors of the pairs it judges count the probing solver's cells
    (:mod:`reports.registry.resolution`)."""
    x0, y0 = case.plane_centre
    coupled = case.dundurs_beta != 0 and max(case.friction.mu1, case.friction.mu2) > 0
    probed = probed and probed_width(case, list(results)) is not None
    own = solvers.record(PROBE_SOLVER).cell_size(case) if probed else math.nan
    records = []
    for sa_name, sb_name in pairs(list(results)):
        pair = f"{sa_name}-{sb_name}"
        ra, rb = results[sa_name], results[sb_name]
        cell = pair_cell(case, sa_name, sb_name)
        reach = pair_reach(case, sa_name, sb_name)
        for n, sa, sb in common_steps(ra, rb):
            rows = step_values(case, pair, ra, rb, sa, sb, cell, reach)
            exact = solvers.exact_pair(pair)
            closed = solvers.oracle(pair) == solvers.CLOSED_FORM
            resolution = None if exact else step_resolution(sa, sb, cell, x0, y0, closed,
                                                            coupled)
            # the probe measures what the coarser element does to the worn annulus
            # (reports.registry.resolution): its wear floors count the probing solver's cells
            wear_resolution = step_resolution(sa, sb, own, x0, y0, closed, coupled) \
                if probed and not exact and probed_pair(pair) else resolution
            for quantity, metric, value in rows:
                shown = None if exact else _SHOWN.get(metric)  # a band's max, never gated
                limit, key = tol.tolerance(
                    case, pair, quantity, _SHOWN[metric][0] if metric in _SHOWN else metric)
                status, note, reason = tol.status(case, quantity)
                coarse = unresolved(quantity, metric, wear_resolution
                                    if quantity in PROBED_FLOORS else resolution)
                if status == tol.GATED and (shown or coarse):
                    status = tol.NOT_GATED
                    note, reason = (coarse, "floor") if coarse else shown[1:]
                records.append({
                    "status": status, "note": note, "reason": reason,
                    "quantity": quantity, "pair": pair, "metric": metric, "value": value,
                    "tolerance": limit, "case": case.name, "param": case.param, "step": n,
                    "s": scalar(sb, "s"), "cycle": scalar(sb, "cycle"),
                    "tolerance_key": key, "oracle": solvers.oracle(pair),
                })
    frame = pd.DataFrame.from_records(records, columns=METRICS_COLUMNS + EXTRA_COLUMNS)
    return frame


#: a stick disc narrower than this fraction of the contact radius sets the resolution of
#: the pressure's peak in a coupled frictional contact; a wider one leaves a peak of
#: Hertz's breadth (reports.registry.resolution)
PEAK_DISC = 0.9


def step_resolution(sa: StepResult, sb: StepResult, cell: float, x0: float = 0.0,
                    y0: float = 0.0, closed: bool = False, coupled: bool = False
                    ) -> Resolution | None:
    """The cells (the coarser of the sample spacings and ``cell``) across the contact
    radius a, the slip zone c < r < a and the distances a − |y0|, a − |x0| from the planes
    through (x0, y0) to the contact edge (:mod:`reports.registry.resolution`); None
    without a contact area.

    The zones are the reference's, never the solver's under test alone: a closed form
    ``sb`` (``closed``) states them (:func:`zones`); where it states none, and between two
    solvers, they are the union of both solvers' — the larger contact radius, the smaller
    stick radius — so a solver that reports a narrower slip zone than the other (or none)
    cannot take its own rows out of the gate.  ``coupled``: friction between dissimilar
    materials, where the stick radius also sets the pressure peak's floor
    (:mod:`reports.registry.resolution`)."""
    h = max(spacing(sa.x), spacing(sa.y), spacing(sb.x), spacing(sb.y), cell)
    (a_a, c_a), (a_b, c_b) = zones(sa), zones(sb)
    a = a_b if closed and math.isfinite(a_b) else max(
        (v for v in (a_a, a_b) if math.isfinite(v)), default=math.nan)
    if not (math.isfinite(a) and h > 0):
        return None
    c = c_b if closed and math.isfinite(c_b) else min(
        (v for v in (c_a, c_b) if math.isfinite(v)), default=0.0)
    # the stick disc's own floor (the pressure's peak) takes the larger of the two, so
    # that a solver reporting a smaller disc does not take its peak out of the gate either
    c_peak = c_b if closed and math.isfinite(c_b) else max(
        (v for v in (c_a, c_b) if math.isfinite(v)), default=0.0)
    # a reference with no tangential traction at all has no slip zone to resolve: a
    # traction of the other solver is an error of its own size (reports.compare.metrics)
    slip = max(a - c, 0.0) / h if carries_traction(sb) else math.inf
    return Resolution(contact=a / h, slip=slip,
                      inset_xz=(a - abs(y0)) / h, inset_yz=(a - abs(x0)) / h,
                      stick=c_peak / h if coupled and c_peak < PEAK_DISC * a else math.inf)


def carries_traction(step: StepResult) -> bool:
    """Whether ``step`` has a tangential traction anywhere (True where it states no
    tangential field: nothing is known to be zero)."""
    fields = [step.surface[k] for k in ("p_x", "p_y") if k in step.surface]
    return not fields or any(np.any(np.nan_to_num(f) != 0) for f in fields)


def zones(step: StepResult) -> tuple[float, float]:
    """(contact radius, stick radius) a step states: √(A/π) of its ``contact_area`` (NaN
    without a contact) and of its ``stick_area``, else its ``stick_radius`` (a closed form
    that bounds the stick zone without stating its area, :mod:`analytic.spence`); NaN
    where it states none."""
    area = scalar(step, "contact_area")
    a = math.sqrt(area / math.pi) if math.isfinite(area) and area > 0 else math.nan
    stick = scalar(step, "stick_area")
    c = math.sqrt(max(stick, 0.0) / math.pi) if math.isfinite(stick) else \
        scalar(step, "stick_radius")
    return a, c


def compare_point(case: Case, results: Mapping[str, RunResult]) -> pd.DataFrame:
    """metrics.csv rows of one sweep point alone: :func:`point_rows` with the verdict of
    :func:`reports.compare.verdict.decide` (a run decides its rows once, with its studies)."""
    return decide(point_rows(case, results))
