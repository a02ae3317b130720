"""The report's sections of a case's studies and provenance: its grid-convergence and
cycle-jump tables, the Dask check of a sweep, where the run came from, and the thresholds
table beside the cases."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import pandas as pd

from reports.render.html_blocks import escape, table_html
from reports.render.study_frames import convergence_frame, jump_frame, probe_frame, study_frame
from reports.store import layout
from reports.store.results import CaseResults
from reports.studies import gridstudy, probe
from reports.studies.probe import PROBE


def _study_row_class(row: pd.Series) -> str:
    return "" if row["status"] in gridstudy.SETTLED else "bad"


def convergence_section(case: CaseResults) -> list[str]:
    """Observed orders and GCIs of the run's grid studies (``run --convergence``) and of a
    grid-study sweep, or how to make one."""
    name = case.name
    parts = [f'<h3 id="convergence-{escape(name)}">Grid convergence</h3>'
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
            f"least {escape(ratio)} each (2, 3); observed order p, Richardson-extrapolated "
            "value f_ext and Roache's GCI of the finest grid (F<sub>s</sub> = 1.25), cell "
            "sizes h in units of a0.</p>")
        cls = "ok" if bad.empty else "bad"
        names = escape(", ".join(dict.fromkeys(bad["quantity"])))
        parts.append(f'<p class="{cls}">{len(study) - len(bad)} / {len(study)} quantities '
                     "converged or exact" + (f"; {len(bad)} unsettled (flagged, their "
                                             "metrics not gated): " + names if len(bad)
                                             else "") + "</p>")
        table = table_html(study, left=5, row_class=_study_row_class)
        parts.append(f"<div class='scroll'>{table}</div>" if len(study) > 40 else table)
    conv = convergence_frame(case)
    if not conv.empty:
        parts.append("<p>Observed order p and Roache's GCI (F<sub>s</sub> = 1.25) from the "
                     "three finest grids of the sweep; cell sizes h in units of a0.</p>")
        parts.append(table_html(conv, status="converging", left=2))
    if study.empty and conv.empty:
        ref = escape(case.manifest.get("case", name))
        parts.append("<p>No grid study in these results. Run <code>contact-vv run "
                     f"{ref} --convergence</code>, or a sweep of three grids, e.g. "
                     f"<code>contact-vv sweep {ref} --param grid.nx=21,41,81 --param "
                     "grid.ny=21,41,81</code>.</p>")
    parts.append("</div>")
    return parts


def jump_section(case: CaseResults) -> list[str]:
    """The cycle-jump studies of a fretting run (``run --jump-study``), or how to make
    one; nothing for other kinds."""
    if case.manifest.get("kind") != "fretting":
        return []
    name = case.name
    parts = [f'<h3 id="jump-{escape(name)}">Cycle-jump convergence</h3><div class="convergence">']
    study = jump_frame(case)
    if study.empty:
        ref = escape(case.manifest.get("case", name))
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
                 "converged or exact" + (f"; {len(bad)} unsettled (flagged, their "
                                         "metrics not gated beyond their budget): "
                                         + escape(", ".join(dict.fromkeys(bad["quantity"])))
                                         if len(bad) else "") + "</p>")
    table = table_html(study, left=4, row_class=_study_row_class)
    parts.append(f"<div class='scroll'>{table}</div>" if len(study) > 40 else table)
    parts.append("</div>")
    return parts


def probe_section(case: CaseResults) -> list[str]:
    """The resolution probe of worn points (:mod:`reports.studies.probe`); nothing where
    none ran."""
    study = probe_frame(case)
    if study.empty:
        return []
    table = case.study(PROBE.name)
    width, spread = table["width"].max(), table["spread"].max()
    out = study[study["status"] != "gated"]
    parts = [f'<h3 id="probe-{escape(case.name)}">Resolution probe</h3><div class="convergence">',
             "<p>The half-space solver again with every committed wear increment spread "
             f"over {escape(f'{spread:.3g}')} mm ({probe.SPREAD:g} of the "
             f"{escape(f'{width:.3g}')} mm element of the FEM's surface): a row whose "
             f"quantity moves by more than {probe.FRACTION:g} of its tolerance is a number "
             "that element cannot give, and is shown, not gated "
             "(<code>reports/README.md</code>, \"The resolution probe\").</p>",
             f'<p class="{"ok" if out.empty else "bad"}">{len(study) - len(out)} / '
             f"{len(study)} probed rows admitted to the gate"
             + (": not gated " + escape(", ".join(dict.fromkeys(out["quantity"])))
                if len(out) else "") + "</p>"]
    table = table_html(study, left=5, row_class=lambda r: "" if r["status"] == "gated"
                       else "bad")
    parts.append(f"<div class='scroll'>{table}</div>" if len(study) > 40 else table)
    parts.append("</div>")
    return parts


def sweep_check_section(case: CaseResults) -> list[str]:
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
    body = "".join(f'<tr><th class="l">{escape(k)}</th><td class="l">{escape(v)}</td></tr>'
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
        return f'<h2 id="thresholds">Thresholds</h2><p class="warn bad">{escape(exc)}</p>'
    cols = ["case", "point", "event", "param", "at", "solver", "grid", "cell_size",
            "threshold", "uncertainty", "resolution", "evaluations", "grid_shift", "status"]
    return ('<h2 id="thresholds">Thresholds</h2><div class="thresholds"><p>Parameter values '
            "at which an event changes (<code>contact-vv threshold</code>): bisected per "
            "solver and grid to ± uncertainty; grid_shift is the change from the case grid; "
            "cell_size in mm; grid <i>exact</i>: the closed form's value.</p>"
            + table_html(t[[c for c in cols if c in t.columns]], left=7) + "</div>")
