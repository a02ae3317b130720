"""``contact-vv report``: one self-contained ``DIR/index.html`` (PNG plots inlined as
base64) with a section per case: tractions, difference maps, σ_VM planes, wear, evolution,
fretting loops, sweep, metrics coloured by pass/fail, grid convergence and provenance."""

from __future__ import annotations

import base64
import html
import json
import math
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pandas as pd

from cases.result import atomic_write_text
from reports.registry.tolerances import GATED
from reports.render import plots
from reports.render.gate import metrics_table, problems
from reports.render.study_frames import convergence_frame, jump_frame, scales, study_frame
from reports.store import layout
from reports.store.event_table import EVENTS_NOTE, events_view
from reports.store.readers import gated, ungated
from reports.store.results import CaseResults, Scan, not_converged, scan
from reports.studies import gridstudy

CSS = """
body{font-family:system-ui,sans-serif;margin:1.5em;max-width:1400px;color:#222}
h1{margin-bottom:0}h2{border-bottom:2px solid #446;padding-bottom:.2em;margin-top:2em}
table{border-collapse:collapse;font-size:.85em;margin:.5em 0}
td,th{border:1px solid #bbb;padding:.15em .5em;text-align:right}
th{background:#eef}td.l,th.l{text-align:left}
tr.pass td{background:#e5f5e5}tr.fail td{background:#fbdcdc;font-weight:600}
tr.ng td{background:#fff3cd}
.warn{background:#fff3cd;border:1px solid #e0c060;padding:.5em 1em}
.bad{color:#a00;font-weight:600}.ok{color:#070;font-weight:600}
figure{margin:.5em 0}img{max-width:100%}
.provenance{background:#f6f6f9;border:1px solid #ccd;padding:.5em 1em;font-size:.85em}
.scroll{max-height:30em;overflow:auto}
"""


def _e(text: Any) -> str:
    return html.escape(str(text))


def _img(png: bytes, alt: str) -> str:
    data = base64.b64encode(png).decode("ascii")
    return f'<figure><img alt="{_e(alt)}" src="data:image/png;base64,{data}"></figure>'


def _fig(fig, alt: str) -> str:
    return _img(plots.png(fig), alt) if fig is not None else ""


def _fmt(v: Any) -> str:
    if isinstance(v, float):
        return "" if math.isnan(v) else f"{v:.4g}"
    return _e(v)


def table_html(frame: pd.DataFrame, *, status: str | None = None, left: int = 0,
               row_class: Callable[[pd.Series], str] | None = None) -> str:
    """An HTML table; rows coloured by a boolean column ``status`` (pass / fail), or given
    the class ``row_class(row)`` (none if it returns '')."""
    head = "".join(f'<th class="{"l" if i < left else ""}">{_e(c)}</th>'
                   for i, c in enumerate(frame.columns))
    body = []
    for _, row in frame.iterrows():
        cls = ""
        if status is not None:
            ok = str(row[status]).lower() in ("true", "1")
            cls = ' class="pass"' if ok else ' class="fail"'
        elif row_class is not None and row_class(row):
            cls = f' class="{_e(row_class(row))}"'
        cells = "".join(f'<td class="{"l" if i < left else ""}">{_fmt(v)}</td>'
                        for i, v in enumerate(row.tolist()))
        body.append(f"<tr{cls}>{cells}</tr>")
    return f"<table><tr>{head}</tr>{''.join(body)}</table>"


def _worst(metrics: pd.DataFrame) -> pd.DataFrame:
    """Per (pair, quantity, metric): the worst value over sweep points and steps."""
    m = metrics.assign(margin=metrics["value"].fillna(math.inf) / metrics["tolerance"])
    idx = m.groupby(["pair", "quantity", "metric"], sort=False)["margin"].idxmax()
    cols = ["pair", "oracle", "quantity", "metric", "value", "tolerance", "tolerance_kind",
            "budget", "uncertainty", "passed", "param", "step"]
    worst = m.loc[idx, [c for c in cols if c in m.columns]]
    return worst.rename(columns={"param": "worst at param", "step": "step"})


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
        parts.append(f'<h3 id="events-{_e(name)}">Events</h3><div class="events"><p>'
                     f"{EVENTS_NOTE}</p>{table_html(events, left=4)}</div>")
    for param in dict.fromkeys(mf.get("params", [""])):
        parts += _fields(case, param, point_scales)
    sweep = plots.sweep_figure(case.summary, point_scales, f"Sweep: {name}") \
        if not case.summary.empty else None
    if sweep is not None:
        parts.append('<h3>Sweep</h3><div class="sweep">' + _fig(sweep, "sweep") + "</div>")
    parts += _metrics(case)
    parts += _convergence(case)
    parts += _jump_study(case)
    parts += _sweep_check(case)
    parts.append(provenance_html(mf))
    parts.append("</section>")
    return "\n".join(p for p in parts if p)


def _header(case: CaseResults) -> list[str]:
    """Title, description, solvers, skipped solvers and non-converged steps."""
    mf, name = case.manifest, case.name
    parts = [f'<section class="case" id="case-{_e(name)}"><h2>{_e(name)}</h2>',
             f"<p>{_e(mf.get('description', ''))} — kind <b>{_e(mf.get('kind'))}</b>, "
             f"solvers {_e(', '.join(mf.get('solvers', [])))}"
             + (" (quick grids)" if mf.get("quick") else "") + "</p>"]
    for solver, reason in mf.get("skipped", {}).items():
        parts.append(f'<p class="warn">{_e(solver)} not run: {_e(reason)}</p>')
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
    return ['<h3 id="summary-' + _e(case.name) + '">Summary (last output step)</h3>',
            table_html(view, left=2)]


def _fields(case: CaseResults, param: str, scales: dict[str, tuple[float, float]]
            ) -> list[str]:
    """The plots of one sweep point: tractions, differences, σ_VM planes, wear, evolution,
    fretting loops (at the last output step all solvers have)."""
    name, s = case.name, case.summary
    a0, p0 = scales.get(param, (math.nan, math.nan))
    if not (math.isfinite(a0) and math.isfinite(p0)):
        return []
    solvers = list(case.manifest.get("solvers", []))
    history = {sv: case.steps(sv, param) for sv in solvers}
    history = {sv: h for sv, h in history.items() if h}
    if not history:
        return []
    label = f" — {param}" if param else ""
    common = set.intersection(*(set(h) for h in history.values()))
    n = max(common) if common else max(max(h) for h in history.values())
    at = {sv: h[n] for sv, h in history.items() if n in h}
    where = f"{name}{label}, output step {n}"
    parts = [f"<h3>Fields{_e(label)}</h3>"]
    parts.append('<div class="profiles">' + _fig(
        plots.traction_profiles(at, a0, p0, f"Tractions through the centre: {where}"),
        "traction profiles") + "</div>")
    parts.append('<div class="differences">' + _fig(
        plots.difference_maps(at, a0, p0, "p_n", f"Pressure differences: {where}"),
        "difference maps") + _fig(
        plots.plane_difference_maps(at, a0, p0, "xz", f"σ_VM differences: {where}"),
        "stress difference maps") + "</div>")
    parts.append('<div class="vm-planes">' + _fig(
        plots.vm_planes(at, a0, p0, f"σ_VM planes: {where}"), "von Mises planes")
        + "</div>")
    sub = s[s["param"] == param] if not s.empty else s
    labels = {}
    if not sub.empty:
        t, tl = plots.progress_axis(sub, a0)
        short = plots.SHORT.get(tl, tl)
        labels = {int(k): f"{short}={v:.3g}" for k, v in zip(sub["step"], t, strict=True)}
    parts.append('<div class="wear">' + _fig(
        plots.wear_profiles(history, a0, labels, f"Wear profiles: {name}{label}"),
        "wear profiles") + "</div>")
    parts.append('<div class="evolution">' + _fig(
        plots.histories(sub, a0, p0, f"Evolution: {name}{label}"), "evolution")
        + "</div>")
    tables = {sv: case.tables(sv, param) for sv in solvers}
    parts.append('<div class="loops">' + _fig(
        plots.loops(tables, f"Fretting loops: {name}{label}"), "fretting loops")
        + "</div>")
    return parts


def _metrics(case: CaseResults) -> list[str]:
    """The worst value of every (pair, quantity, metric) and, folded, every metric."""
    parts = [f'<h3 id="metrics-{_e(case.name)}">Metrics</h3><div class="metrics">']
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
                f'<p class="bad">Not converged, so not gated ({len(m) - n_on} rows): the '
                "largest value of each, and why (a band's maximum, a maximum near the "
                "surface, a zone narrower than the resolution floor, a grid or jump study "
                "with its three values, or declared in the case file).</p>")
            off = ungated(m)[["pair", "quantity", "metric", "value", "rows", "param", "step",
                              "note"]].rename(columns={"param": "worst at param",
                                                       "note": "why"})
            parts.append(table_html(off, left=3, row_class=lambda _: "ng"))
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


def _study_row_class(row: pd.Series) -> str:
    return "" if row["status"] in gridstudy.SETTLED else "bad"


def _convergence(case: CaseResults) -> list[str]:
    """Observed orders and GCIs of the run's grid studies (``run --convergence``) and of a
    grid-study sweep, or how to make one."""
    name = case.name
    parts = [f'<h3 id="convergence-{_e(name)}">Grid convergence</h3>'
             '<div class="convergence">']
    study = study_frame(case)
    if not study.empty:
        bad = study[study["status"].map(lambda v: v not in gridstudy.SETTLED)]
        entry = case.manifest.get("convergence")
        ratio = entry.get("ratio", gridstudy.RATIO) if isinstance(entry, dict) else \
            gridstudy.RATIO
        parts.append(
            "<p>Grid studies of this run (<code>--convergence</code>): every numerical "
            f"solver on its own grid (1, the run's results) and two grids coarser by at "
            f"least {_e(ratio)} each (2, 3); observed order p, Richardson-extrapolated "
            "value f_ext and Roache's GCI of the finest grid (F<sub>s</sub> = 1.25), cell "
            "sizes h in units of a0.</p>")
        cls = "ok" if bad.empty else "bad"
        parts.append(f'<p class="{cls}">{len(study) - len(bad)} / {len(study)} quantities '
                     "converged or exact" + (f"; {len(bad)} not converged (flagged, their "
                                             "metrics not gated): " + _e(", ".join(dict.fromkeys(
                                                 bad["quantity"]))) if len(bad) else "")
                     + "</p>")
        table = table_html(study, left=5, row_class=_study_row_class)
        parts.append(f"<div class='scroll'>{table}</div>" if len(study) > 40 else table)
    conv = convergence_frame(case)
    if not conv.empty:
        parts.append("<p>Observed order p and Roache's GCI (F<sub>s</sub> = 1.25) from the "
                     "three finest grids of the sweep; cell sizes h in units of a0.</p>")
        parts.append(table_html(conv, status="converging", left=2))
    if study.empty and conv.empty:
        ref = _e(case.manifest.get("case", name))
        parts.append("<p>No grid study in these results. Run <code>contact-vv run "
                     f"{ref} --convergence</code>, or a sweep of three grids, e.g. "
                     f"<code>contact-vv sweep {ref} --param grid.nx=21,41,81 --param "
                     "grid.ny=21,41,81</code>.</p>")
    parts.append("</div>")
    return parts


def _jump_study(case: CaseResults) -> list[str]:
    """The cycle-jump studies of a fretting run (``run --jump-study``), or how to make
    one; nothing for other kinds."""
    if case.manifest.get("kind") != "fretting":
        return []
    name = case.name
    parts = [f'<h3 id="jump-{_e(name)}">Cycle-jump convergence</h3><div class="convergence">']
    study = jump_frame(case)
    if study.empty:
        ref = _e(case.manifest.get("case", name))
        parts.append("<p>No cycle-jump study in these results. Run <code>contact-vv run "
                     f"{ref} --jump-study</code>: every numerical solver again at half and "
                     "a quarter of <code>fretting.jump</code>.</p></div>")
        return parts
    bad = study[study["status"].map(lambda v: v not in gridstudy.SETTLED)]
    parts.append(
        "<p>Cycle-jump studies of this run (<code>--jump-study</code>): every numerical "
        "solver at its jump J (the run's results), J/2 and J/4, on the same grid, values at "
        "the same real cycle; <i>halving J</i> is (f(J/2) − f(J)) / |f(J)|, observed order "
        "p and Richardson-extrapolated value f_ext from the three.</p>")
    cls = "ok" if bad.empty else "bad"
    parts.append(f'<p class="{cls}">{len(study) - len(bad)} / {len(study)} quantities '
                 "converged or exact" + (f"; {len(bad)} not converged (flagged, their "
                                         "metrics not gated beyond their budget): "
                                         + _e(", ".join(dict.fromkeys(bad["quantity"])))
                                         if len(bad) else "") + "</p>")
    table = table_html(study, left=4, row_class=_study_row_class)
    parts.append(f"<div class='scroll'>{table}</div>" if len(study) > 40 else table)
    parts.append("</div>")
    return parts


def _sweep_check(case: CaseResults) -> list[str]:
    """The Dask-against-serial check of a sweep, if one was made."""
    check = case.path / layout.SWEEP_CHECK
    if not check.is_file():
        return []
    c = json.loads(check.read_text())
    return [f'<p class="{"ok" if c.get("identical") else "bad"}">Sweep on Dask: '
            f'{c["parallel_wall_s"]:.1f} s wall against {c["serial_wall_s"]:.1f} s serial '
            f'(speed-up {c["speedup"]:.2f}x); numbers '
            f'{"identical to" if c.get("identical") else "DIFFERENT from"} the serial run.</p>']


def provenance_html(mf: dict[str, Any]) -> str:
    prov = mf.get("provenance", {})
    git = prov.get("git", {})
    versions = ", ".join(f"{k} {v}" for k, v in prov.get("versions", {}).items())
    threads = prov.get("threads", {})
    units = pd.DataFrame(mf.get("units", []))
    walls = ""
    if not units.empty:
        cols = ["solver", "param", "wall_s"]
        if "grid" in units.columns:  # run --convergence: the coarse grids' runs too
            grid = pd.to_numeric(units["grid"], errors="coerce").fillna(1)
            units = units.assign(grid=grid.astype(int))
            cols.insert(2, "grid")
        if "jump" in units.columns:  # run --jump-study: the runs at J/2 and J/4
            cols.insert(2, "jump")
        walls = table_html(units[cols].rename(columns={"wall_s": "wall [s]"}), left=2)
    overrides = mf.get("overrides") or {}
    rows = [
        ("case file", mf.get("case_file")), ("case file SHA-256", mf.get("case_sha256")),
        ("quick", mf.get("quick")), ("overrides", overrides or "none"),
        ("sweep", mf.get("sweep") or "from the case file" if len(mf.get("params", [])) > 1
         else mf.get("sweep") or "none"),
        ("git commit", f"{git.get('commit')}" + (" (uncommitted changes)"
                                                  if git.get("dirty") else "")),
        ("date (UTC)", prov.get("date")), ("versions", versions),
        ("source SHA-256", ", ".join(f"{k} {v[:12]}" for k, v in
                                     (mf.get("sources") or {}).items())
         + (" — CHANGED DURING THE RUN" if mf.get("sources_changed_during_run") else "")),
        ("threads", ", ".join(f"{k}={v}" for k, v in threads.items()
                              if k != "threadpools")),
        ("executor", mf.get("executor", "serial")),
        ("wall time", f"{mf.get('wall_s', math.nan):.2f} s (solver time "
                      f"{mf.get('unit_wall_s', math.nan):.2f} s)"),
        ("command", " ".join(prov.get("command", []))),
    ]
    body = "".join(f'<tr><th class="l">{_e(k)}</th><td class="l">{_e(v)}</td></tr>'
                   for k, v in rows)
    return (f'<div class="provenance"><h3>Provenance</h3><table>{body}</table>'
            f"{walls}</div>")


def thresholds_html(out: Path) -> str:
    """The Thresholds table from ``DIR/thresholds.csv`` (``contact-vv threshold``), if any."""
    from reports.store.layout import THRESHOLDS
    from reports.store.readers import DamagedResult, read_result, read_thresholds

    if not (Path(out) / THRESHOLDS).exists():
        return ""
    try:
        t = read_result(Path(out) / THRESHOLDS, read_thresholds)
    except DamagedResult as exc:
        return f'<h2 id="thresholds">Thresholds</h2><p class="warn bad">{_e(exc)}</p>'
    cols = ["case", "point", "event", "param", "at", "solver", "grid", "cell_size",
            "threshold", "uncertainty", "resolution", "evaluations", "grid_shift", "status"]
    return ('<h2 id="thresholds">Thresholds</h2><div class="thresholds"><p>Parameter values '
            "at which an event changes (<code>contact-vv threshold</code>): bisected per "
            "solver and grid to ± uncertainty; grid_shift is the change from the case grid; "
            "cell_size in mm; grid <i>exact</i>: the closed form's value.</p>"
            + table_html(t[[c for c in cols if c in t.columns]], left=7) + "</div>")


def render(results: Scan, out: Path) -> str:
    """The whole report page.  A case whose files turn out to be damaged while its
    section is drawn is moved from ``results.complete`` to ``results.damaged``."""
    from reports.store.manifest import provenance
    from reports.store.readers import DamagedResult

    when = provenance()["date"]
    toc, sections = [], []
    for case in list(results.complete):
        try:
            section = case_section(case)
        except DamagedResult as exc:
            results.complete.remove(case)
            results.damaged[case.path.name] = str(exc)
            continue
        sections.append(section)
        m = case.metrics
        n_ok, n_on = _n_passed(m), int(gated(m).sum())
        bad = len(not_converged(case.summary))
        grid = len(gridstudy.unsettled(case.convergence))
        jump = len(gridstudy.unsettled(case.jump_study))
        status = "ok" if n_ok == n_on and not bad else "bad"
        toc.append(f'<li><a href="#case-{_e(case.name)}">{_e(case.name)}</a> '
                   f'<span class="{status}">{n_ok}/{n_on} metrics passed'
                   + (f", {len(m) - n_on} not gated" if n_on < len(m) else "")
                   + (f", {bad} not converged" if bad else "") + "</span>"
                   + (f' <span class="bad">{grid} quantities not grid-converged</span>'
                      if grid else "")
                   + (f' <span class="bad">{jump} quantities not converged in the cycle '
                      'jump</span>' if jump else "") + "</li>")
    warn = ""
    if results.incomplete or results.damaged:
        items = "".join(f"<li><b>{_e(k)}</b>: {_e(v)}</li>"
                        for k, v in results.incomplete.items())
        items += "".join(f"<li><b>{_e(k)}</b>: damaged: {_e(v)}</li>"
                         for k, v in results.damaged.items())
        warn = (f'<div class="warn" id="incomplete"><b>Incomplete or damaged runs (not '
                f"reported):</b><ul>{items}</ul></div>")
    found = problems(results)
    table = metrics_table(results)
    n_on = int(gated(table).sum())
    off = f", {len(table) - n_on} not converged and not gated" if n_on < len(table) else ""
    verdict = (f'<p class="ok" id="verdict">Gate: pass ({n_on} gated metrics{off})</p>'
               if not found else
               f'<p class="bad" id="verdict">Gate: {len(found)} problem(s)</p><ul>'
               + "".join(f"<li>{_e(x)}</li>" for x in found[:50]) + "</ul>")
    return (f"<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'>"
            f"<title>contact-vv report</title><style>{CSS}</style></head><body>"
            f"<h1>contact-vv verification report</h1><p>Results in <code>{_e(out)}</code>, "
            f"report generated {_e(when)}.</p>{warn}{verdict}"
            f"<nav><h2>Cases</h2><ul>{''.join(toc)}</ul></nav>{thresholds_html(out)}"
            f"{''.join(sections)}"
            "</body></html>")


def write_report(out: Path) -> Path:
    """Write ``out/index.html`` atomically from whatever complete results ``out`` holds.

    Incomplete or damaged cases are listed in the page, and then raised as
    :class:`RunFailed` (one line each, the page written: the CLI exits 1).
    """
    from reports.registry.errors import RunFailed, UserError
    from reports.render.gate import case_problems

    out = Path(out)
    results = scan(out)
    if results.empty and not (out / layout.THRESHOLDS).exists():
        raise UserError(f"no results in {out} (run `contact-vv run` first)")
    path = out / layout.REPORT
    atomic_write_text(path, render(results, out))
    lines = case_problems(results)
    if lines:
        raise RunFailed([*lines, f"report {path} written without the {len(lines)} "
                         "incomplete or damaged case(s) above"])
    return path
