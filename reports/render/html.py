"""The section of one case in the report (its page, :mod:`reports.render.pages`):
tractions, difference maps, σ_VM planes, wear, evolution, fretting loops, sweep, metrics
coloured by pass/fail, grid convergence and provenance (PNG plots inlined as base64; the
pages write them out as files)."""

from __future__ import annotations

import math

import pandas as pd

from reports.registry import solvers as registry
from reports.registry.tolerances import GATED
from reports.render import plots
from reports.render.cross_check import pairs_side_by_side
from reports.render.html_blocks import escape, fig, table_html
from reports.render.html_sections import (
    convergence_section,
    jump_section,
    probe_section,
    provenance_html,
    sweep_check_section,
)
from reports.render.study_frames import scales
from reports.store.event_table import EVENTS_NOTE, events_view
from reports.store.readers import gated, ungated, worst
from reports.store.results import CaseResults, not_converged


def _worst(metrics: pd.DataFrame) -> pd.DataFrame:
    """Per (pair, quantity, metric): the worst value over sweep points and steps
    (:func:`reports.store.readers.worst`)."""
    cols = ["pair", "oracle", "quantity", "metric", "value", "tolerance", "tolerance_kind",
            "budget", "uncertainty", "passed", "param", "step"]
    rows = worst(metrics)
    return rows[[c for c in cols if c in rows.columns]].rename(
        columns={"param": "worst at param", "step": "step"})


def case_section(case: CaseResults) -> str:
    """The HTML section of one case: header, summary, events (if any), fields per sweep
    point, sweep, metrics, grid convergence, Dask check and provenance."""
    mf, name = case.manifest, case.name
    point_scales = scales(case)
    parts = [*_header(case)]
    if not case.summary.empty:
        parts += _summary(case, point_scales)
    events = events_view(case.events)
    if not events.empty:
        parts.append(f'<h3 id="events-{escape(name)}">Events</h3><div class="events"><p>'
                     f"{EVENTS_NOTE}</p>{table_html(events, left=4)}</div>")
    for param in dict.fromkeys(mf.get("params", [""])):
        parts += _fields(case, param, point_scales)
    sweep = plots.sweep_figure(case.summary, point_scales, f"Sweep: {name}") \
        if not case.summary.empty else None
    if sweep is not None:
        parts.append('<h3>Sweep</h3><div class="sweep">' + fig(sweep, "sweep") + "</div>")
    parts += _metrics(case)
    parts += convergence_section(case)
    parts += jump_section(case)
    parts += probe_section(case)
    parts += sweep_check_section(case)
    parts.append(provenance_html(mf))
    parts.append("</section>")
    return "\n".join(p for p in parts if p)


def _header(case: CaseResults) -> list[str]:
    """Title, description, solvers, skipped solvers and non-converged steps."""
    mf, name = case.manifest, case.name
    parts = [f'<section class="case" id="case-{escape(name)}"><h2>{escape(name)}</h2>',
             f"<p>{escape(mf.get('description', ''))} — kind <b>{escape(mf.get('kind'))}</b>, "
             f"solvers {escape(', '.join(mf.get('solvers', [])))}"
             + (" (quick grids)" if mf.get("quick") else "") + "</p>"]
    skipped = mf.get("skipped", {})
    if skipped:  # one line of those asked for, every reason one click away
        reasons = "".join(f"<li><b>{escape(s)}</b>: {escape(r)}</li>"
                          for s, r in skipped.items())
        asked = ", ".join(case.not_run) or "none of the solvers asked for"
        parts.append(f'<details class="not-run"><summary>not run: {escape(asked)} '
                     f'({len(skipped)} declined or unavailable)</summary><ul>{reasons}</ul>'
                     '</details>')
    bad = not_converged(case.summary)
    if not bad.empty:
        parts.append(f'<p class="warn bad">{len(bad)} output step(s) did not converge</p>')
    return parts


def _summary(case: CaseResults, scales: dict[str, tuple[float, float]]) -> list[str]:
    """The last output step of every (solver, sweep point), dimensionless."""
    s = case.summary
    last = s.sort_values("step").groupby(["solver", "param"], sort=False).tail(1)
    a0 = last["param"].map(lambda p: scales.get(p, (math.nan,) * 2)[0])
    p0 = last["param"].map(lambda p: scales.get(p, (math.nan,) * 2)[1])
    view = pd.DataFrame({
        "solver": last["solver"], "param": last["param"], "step": last["step"],
        "P [N]": last["P"], "p_max/p0": last["p_max"] / p0, "a_x/a0": last["a_x"] / a0,
        "a_y/a0": last["a_y"] / a0, "w_max [µm]": 1e3 * last["w_max"],
        "σ_VM,max/p0": last["vm_max"] / p0, "z(σ_VM,max)/a0": last["vm_max_z"] / a0,
        "iterations": last["iterations"], "converged": last["converged"],
        "wall [s]": last["wall_s"]})
    return ['<h3 id="summary-' + escape(case.name) + '">Summary (last output step)</h3>',
            table_html(view, left=2)]


def _fields(case: CaseResults, param: str, scales: dict[str, tuple[float, float]]
            ) -> list[str]:
    """The plots of one sweep point: tractions, differences, σ_VM planes, wear, evolution,
    fretting loops (at the last output step all solvers have)."""
    name, s = case.name, case.summary
    a0, p0 = scales.get(param, (math.nan, math.nan))
    if not (math.isfinite(a0) and math.isfinite(p0)):
        return []
    solvers = registry.by_role(case.manifest.get("solvers", []))
    history = {sv: case.steps(sv, param) for sv in solvers}
    history = {sv: h for sv, h in history.items() if h}
    if not history:
        return []
    label = f" — {param}" if param else ""
    common = set.intersection(*(set(h) for h in history.values()))
    n = max(common) if common else max(max(h) for h in history.values())
    at = {sv: h[n] for sv, h in history.items() if n in h}
    where = f"{name}{label}, output step {n}"
    parts = [f"<h3>Fields{escape(label)}</h3>"]
    parts.append('<div class="profiles">' + fig(
        plots.traction_profiles(at, a0, p0, f"Tractions through the centre: {where}"),
        "traction profiles") + "</div>")
    parts.append('<div class="differences">' + fig(
        plots.difference_maps(at, a0, p0, "p_n", f"Pressure differences: {where}"),
        "difference maps") + fig(
        plots.plane_difference_maps(at, a0, p0, "xz", f"σ_VM differences: {where}"),
        "stress difference maps") + "</div>")
    parts.append('<div class="vm-planes">' + fig(
        plots.vm_planes(at, a0, p0, f"σ_VM planes: {where}"), "von Mises planes")
        + "</div>")
    sub = s[s["param"] == param] if not s.empty else s
    labels = {}
    if not sub.empty:
        t, tl = plots.progress_axis(sub, a0)
        short = plots.SHORT.get(tl, tl)
        labels = {int(k): f"{short}={v:.3g}" for k, v in zip(sub["step"], t, strict=True)}
    parts.append('<div class="wear">' + fig(
        plots.wear_profiles(history, a0, labels, f"Wear profiles: {name}{label}"),
        "wear profiles") + "</div>")
    parts.append('<div class="evolution">' + fig(
        plots.histories(sub, a0, p0, f"Evolution: {name}{label}"), "evolution")
        + "</div>")
    tables = {sv: case.tables(sv, param) for sv in solvers}
    parts.append('<div class="loops">' + fig(
        plots.loops(tables, f"Fretting loops: {name}{label}"), "fretting loops")
        + "</div>")
    return parts


def _metrics(case: CaseResults) -> list[str]:
    """The worst value of every (pair, quantity, metric) and, folded, every metric."""
    parts = [f'<h3 id="metrics-{escape(case.name)}">Metrics</h3><div class="metrics">']
    m = case.metrics
    if m.empty:
        parts.append("<p>No pair of solvers to compare.</p>")
    else:
        on = gated(m)
        n_ok, n_on = _n_passed(m), int(on.sum())
        cls = "ok" if n_ok == n_on else "bad"
        parts.append(f'<p class="{cls}">{n_ok} / {n_on} gated metrics within tolerance</p>')
        if n_on:
            parts.append("<p>Oracles: the pair's reference is a <i>closed form</i>, an "
                         "<i>other solver</i> or a <i>metamorphic relation</i> (the same "
                         "solver on a transformed case, mapped back). Tolerance kinds: "
                         "<i>budget</i> (the sum of the pair's error budgets; a relation's "
                         "own allowance), <i>case</i> (a key of the case file), "
                         "<i>uncertainty</i> (the combined numerical uncertainty of the grid "
                         "studies, shown beside the budget it replaced).</p>")
            parts.append(table_html(_worst(m[on]), status="passed", left=4))
        if n_on < len(m):
            parts.append(
                f'<p class="bad">Shown and not gated ({len(m) - n_on} rows): the '
                "largest value of each, and why (a band's maximum, a maximum near the "
                "surface, a zone narrower than the resolution floor, a grid or jump study "
                "with its three values, or declared in the case file).</p>")
            off = ungated(m)[["pair", "quantity", "metric", "value", "rows", "param", "step",
                              "note"]].rename(columns={"param": "worst at param",
                                                       "note": "why"})
            parts.append(table_html(off, left=3, row_class=lambda _: "ng"))
        side = pairs_side_by_side(m)
        if not side.empty:
            parts.append("<h4>Pairs side by side</h4><p>The worst value of each pair of "
                         "solvers, one column each (another solver, then a closed form): "
                         "whether two references agree with each other where they differ "
                         "from a third. ✗ failed, (ng) not gated.</p>"
                         + table_html(side, left=2))
        cols = ["param", "step", "pair", "oracle", "quantity", "metric", "value", "tolerance",
                "passed", "status", "note", "tolerance_key", "tolerance_kind", "budget",
                "uncertainty"]
        parts.append("<details><summary>All metrics</summary><div class='scroll'>"
                     + table_html(m[[c for c in cols if c in m.columns]], left=6,
                                  row_class=_metric_row_class) + "</div></details>")
    parts.append("</div>")
    return parts


def _n_passed(m: pd.DataFrame) -> int:
    """How many gated metric rows passed."""
    if m.empty:
        return 0
    return int((m["passed"].astype(bool) & gated(m)).sum())


def _metric_row_class(row: pd.Series) -> str:
    if row.get("status", GATED) != GATED:
        return "ng"
    return "pass" if bool(row["passed"]) else "fail"
