"""The gate of ``DIR/thresholds.csv`` (``contact-vv threshold``, ``contact-vv article``):
thresholds are results, checked like the metrics.

Each bisected row must be a bracket: ``lo < hi``, the threshold its midpoint, its status
naming two different events at its ends (a bracket whose ends have the same event
locates nothing: ``INVALID``).  A row whose solver failed is a problem (``FAILED``).

Then, for each threshold (case, sweep point, event, key, output step, tier), every
solver's threshold on the case grid (``refine`` 1, else its first grid) is compared with
the closed form's on the case grid where the closed form has one (the exact fields
sampled like the solver's: an event read from sampled fields, such as a σ_VM maximum on
the surface that peaks at the contact edge, converges to its exact root only as the
sampling does, which is not the solver's error), else with every other solver's, in the
solvers' name order:

    |θ_a − θ_b| ≤ u_a + u_b + e_a + e_b

with ``u`` the bisection's half-width and ``e`` the solver's discretisation error as its
own grids measure it: the largest Richardson bound ``s / (r − 1)`` (a coarser grid k,
r = f_1 / f_k) or ``s r / (r − 1)`` (a finer one, r = f_k / f_1) with
``s = |θ_1 − θ_k| + u_1 + u_k`` the largest shift between the grids the two brackets
allow.  For a threshold that converges monotonically at an order p ≥ 1 (the error
c hᵖ) it bounds the case grid's error: ``c hᵖ (rᵖ − 1) / (r − 1) ≥ c hᵖ``.  A solver
with a single grid has no measure of its discretisation: its comparisons are ``NOT
GATED`` notes, not problems.  The exact root (grid ``exact``) is shown, not gated: the
distance of the sampled closed form from it is the sampling's.
"""

from __future__ import annotations

import math
from itertools import combinations
from pathlib import Path

import pandas as pd

from reports.store import layout

#: the columns that name one threshold (its rows differ in solver and grid)
THRESHOLD_KEYS = ["case", "point", "event", "param", "at", "quick"]


def _what(r: pd.Series) -> str:
    point = f" [{r['point']}]" if r["point"] else ""
    at = f" at {r['at']}" if r["at"] else ""
    return f"{r['case']}{point} {r['event']} {r['param']}{at}"


def _ends_differ(status: str) -> bool:
    """Whether a ``bisected: A at lower KEY, B at higher`` status names two events."""
    body = status.partition(":")[2]
    lower, _, higher = body.partition(" at lower ")
    higher = higher.partition(", ")[2].removesuffix(" at higher")
    return bool(lower.strip()) and lower.strip() != higher.strip()


def row_problems(t: pd.DataFrame) -> list[str]:
    """``INVALID`` bracketed rows and ``FAILED`` rows (module doc)."""
    lines = []
    for _, r in t.iterrows():
        status = str(r["status"])
        who = f"{_what(r)}: {r['solver']} {r['grid']}"
        if status.startswith("failed"):
            lines.append(f"FAILED threshold {who}: {status}")
            continue
        if not status.startswith("bisected"):
            continue
        lo, hi, theta = float(r["lo"]), float(r["hi"]), float(r["threshold"])
        if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
            lines.append(f"INVALID threshold {who}: its bracket [{lo:g}, {hi:g}] is not "
                         "an interval")
        elif not _ends_differ(status):
            lines.append(f"INVALID threshold {who}: the event is the same at both ends "
                         f"of [{lo:g}, {hi:g}] ({status}), so nothing changes there")
        elif not math.isclose(theta, 0.5 * (lo + hi), rel_tol=1e-9,
                              abs_tol=1e-12 * (hi - lo)):
            lines.append(f"INVALID threshold {who}: {theta:g} is not the midpoint of its "
                         f"bracket [{lo:g}, {hi:g}]")
    return lines


def _estimate(rows: pd.DataFrame) -> tuple[pd.Series, float] | None:
    """(the case grid's row, e) of one solver's bisected rows of one threshold (module
    doc); None without a second grid."""
    rows = rows.sort_values("refine", kind="stable")
    ones = rows[rows["refine"] == 1.0]
    first = ones.iloc[0] if len(ones) else rows.iloc[0]
    others = rows[rows.index != first.name]
    if others.empty:
        return first, math.nan
    e = 0.0
    for _, o in others.iterrows():
        f1, fk = float(first["refine"]), float(o["refine"])
        r = f1 / fk if fk < f1 else fk / f1
        shift = abs(float(o["threshold"]) - float(first["threshold"])) + float(
            o["uncertainty"]) + float(first["uncertainty"])
        e = max(e, shift / (r - 1.0) if fk < f1 else shift * r / (r - 1.0))
    return first, e


def _closed_form(name: str) -> bool:
    """Whether solver ``name`` is a closed form of this suite's registry."""
    from reports.registry import solvers

    return name in solvers.REGISTRY and bool(solvers.record(name).closed_form)


def comparisons(t: pd.DataFrame) -> tuple[list[str], list[str], int]:
    """(problems, notes, the number gated): each solver's threshold against the closed
    form's or the others' (module doc)."""
    problems, notes, n = [], [], 0
    done = t[t["status"].astype(str).str.startswith("bisected")]
    for _, group in done.groupby(THRESHOLD_KEYS, sort=True, dropna=False):
        own = {s: _estimate(rows) for s, rows in group.groupby("solver", sort=True)}
        closed = [s for s in own if _closed_form(s)]
        pairs = ([(s, closed[0]) for s in own if s != closed[0]] if closed
                 else list(combinations(sorted(own), 2)))
        for a, b in pairs:
            (ra, ea), (rb, eb) = own[a], own[b]
            what = (f"threshold {_what(ra)}: {a} {ra['threshold']:.6g} ± "
                    f"{ra['uncertainty']:.2g} against {b} {rb['threshold']:.6g} ± "
                    f"{rb['uncertainty']:.2g}")
            if math.isnan(ea) or math.isnan(eb):
                one = a if math.isnan(ea) else b
                notes.append(f"NOT GATED {what}: {one} has one grid, no measure of its "
                             "discretisation (run threshold with --grids of two factors)")
                continue
            n += 1
            tol = float(ra["uncertainty"]) + float(rb["uncertainty"]) + ea + eb
            diff = abs(float(ra["threshold"]) - float(rb["threshold"]))
            if not diff <= tol:
                problems.append(f"FAIL {what}: |difference| {diff:.4g} > tolerance "
                                f"{tol:.4g} (half-widths and grid estimates {ea:.2g}, "
                                f"{eb:.2g}; {layout.THRESHOLDS})")
    return problems, notes, n


def threshold_gate(out: Path) -> tuple[list[str], list[str], int]:
    """(problems, notes, the number of gated comparisons) of ``out/thresholds.csv``; none
    if it does not exist (a damaged file is one problem)."""
    from reports.store.readers import DamagedResult, read_result, read_thresholds

    path = Path(out) / layout.THRESHOLDS
    if not (path.exists() or path.is_symlink()):
        return [], [], 0
    try:
        t = read_result(path, read_thresholds)
    except DamagedResult as exc:
        return [f"DAMAGED {layout.THRESHOLDS}: {exc}"], [], 0
    for col in ("point", "at"):
        t[col] = t[col].fillna("").astype(str)
    failed, notes, n = comparisons(t)
    return row_problems(t) + failed, notes, n
