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
from reports.registry.resolution import Resolution, unresolved

#: metrics written beside a gated one but never gated: -> (the gated metric whose
#: tolerance they are shown against, why they are not gated)
_SHOWN = {KINK: ("max", KINK_NOTE), maxima.EDGE: ("rel", maxima.EDGE_NOTE),
          maxima.SURFACE: ("rel", maxima.SURFACE_NOTE)}


def point_rows(case: Case, results: Mapping[str, RunResult]) -> pd.DataFrame:
    """The metric rows of one sweep point, before the verdict: every pair, every common
    output step, with the status and tolerance the comparisons see themselves."""
    a0, p0 = case.hertz_scales
    mu_P = friction_scale(case)
    x0, y0 = case.plane_centre
    own = {n: solvers.record(n).cell_size(case) for n in results}
    records = []
    for sa_name, sb_name in pairs(list(results)):
        pair = f"{sa_name}-{sb_name}"
        cell = max((c for c in (own[sa_name], own[sb_name]) if math.isfinite(c)),
                   default=0.0)
        steps_a = {s.number(i): s for i, s in enumerate(results[sa_name].steps)}
        steps_b = {s.number(i): s for i, s in enumerate(results[sb_name].steps)}
        for n in sorted(set(steps_a) & set(steps_b)):
            sa, sb = steps_a[n], steps_b[n]
            rows = compare_steps(sa, sb, a0=a0, p0=p0, x0=x0, y0=y0,
                                 cell=cell, z_below=case.stress.z_below,
                                 vm_rel=tol.tolerance(case, pair, "vm_max", "rel")[0])
            cycle = scalar(sb, "cycle")
            if math.isfinite(cycle):
                rows += compare_tables(results[sa_name].tables, results[sb_name].tables,
                                       cycle, mu_P)
            exact = solvers.exact_pair(pair)
            resolution = None if exact else step_resolution(sa, sb, cell, x0, y0)
            for quantity, metric, value in rows:
                shown = None if exact else _SHOWN.get(metric)  # a band's max, never gated
                limit, key = tol.tolerance(
                    case, pair, quantity, _SHOWN[metric][0] if metric in _SHOWN else metric)
                status, note = tol.status(case, quantity)
                coarse = unresolved(quantity, metric, resolution)
                if status == tol.GATED and (shown or coarse):
                    status, note = tol.NOT_CONVERGED, coarse or shown[1]
                records.append({
                    "status": status, "note": note,
                    "quantity": quantity, "pair": pair, "metric": metric, "value": value,
                    "tolerance": limit, "case": case.name, "param": case.param, "step": n,
                    "s": scalar(sb, "s"), "cycle": scalar(sb, "cycle"),
                    "tolerance_key": key, "oracle": solvers.oracle(pair),
                })
    frame = pd.DataFrame.from_records(records, columns=METRICS_COLUMNS + EXTRA_COLUMNS)
    return frame


def step_resolution(sa: StepResult, sb: StepResult, cell: float, x0: float = 0.0,
                    y0: float = 0.0) -> Resolution | None:
    """The cells (the coarser of the sample spacings and ``cell``) across the contact
    radius a, the slip zone of reference ``sb`` (else ``sa``) and the distances a − |y0|,
    a − |x0| from the planes through (x0, y0) to the contact edge
    (:mod:`reports.registry.resolution`); None without a contact area."""
    h = max(spacing(sa.x), spacing(sa.y), spacing(sb.x), spacing(sb.y), cell)
    area = next((v for v in (scalar(sb, "contact_area"), scalar(sa, "contact_area"))
                 if math.isfinite(v) and v > 0), math.nan)
    if not (math.isfinite(area) and h > 0):
        return None
    stick = next((v for v in (scalar(sb, "stick_area"), scalar(sa, "stick_area"))
                  if math.isfinite(v)), 0.0)
    a, c = math.sqrt(area / math.pi), math.sqrt(max(stick, 0.0) / math.pi)
    return Resolution(contact=a / h, slip=max(a - c, 0.0) / h,
                      inset_xz=(a - abs(y0)) / h, inset_yz=(a - abs(x0)) / h)


def compare_point(case: Case, results: Mapping[str, RunResult]) -> pd.DataFrame:
    """metrics.csv rows of one sweep point alone: :func:`point_rows` with the verdict of
    :func:`reports.compare.verdict.decide` (a run decides its rows once, with its studies)."""
    return decide(point_rows(case, results))
