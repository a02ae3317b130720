"""What the gate covers: for each regime × quantity × kind of reference, whether at least
one metric row of the results is gated, and if none is, why (issue 63, point 1).

A row's regime is that of its case and step: a static contact ``normal`` (no tangential
load), in ``partial slip`` (a tangential load or shift) or in ``full sliding``;
``sliding wear`` (pin-on-disk); a first fretting cycle in ``fretting gross slip`` or
``fretting partial slip`` (a stick zone in the half-space solver's step, else the
reference's); ``worn fretting`` from the second cycle on.  The kind of reference is the
row's ``oracle`` (closed form, other solver, metamorphic relation).  A cell with rows
and none gated says why: its rows counted by ``reason`` (a resolution floor, a band, a
study; the codes of metrics.csv, in words), the most frequent first, and the most
frequent note.  Summarised by regime in the report's index, whole on its own page of
the report and in ``benchmarks/README.md``; the quick
chain's table is held by ``tests/test_suite_quick_gates.py``.
"""

from __future__ import annotations

import math
import re
from collections import Counter

import pandas as pd

from reports.registry import tolerances as tol
from reports.store import layout
from reports.store.results import CaseResults, Scan

REGIMES = ("normal", "partial slip", "full sliding", "sliding wear",
           "fretting gross slip", "fretting partial slip", "worn fretting")
COLUMNS = ["regime", "quantity", "oracle", "rows", "gated", "why"]
_REF = re.compile(r" \((reports|cases|analytic|halfspace|fem_reference)\.[^)]*\)$")


def _stick(summary: pd.DataFrame, param: str, step: int) -> bool:
    """Whether the step has a stick zone: the half-space solver's, else any solver's."""
    rows = summary[(summary["param"] == param) & (summary["step"] == step)]
    ic = rows[rows["solver"] == "ic"]
    area = (ic if not ic.empty else rows).get("stick_area", pd.Series(dtype=float))
    return bool((pd.to_numeric(area, errors="coerce") > 0).any())


def regime(point: dict, summary: pd.DataFrame, param: str, step: int, cycle: float) -> str:
    """The regime of one step of a sweep point (module doc); ``point`` the recorded case
    parameters (:meth:`reports.store.results.CaseResults.point`)."""
    kind, load = point.get("kind"), point.get("load") or {}
    if kind == "sliding_wear":
        return "sliding wear"
    if kind == "fretting":
        if math.isfinite(cycle) and cycle > 1:
            return "worn fretting"
        return "fretting partial slip" if _stick(summary, param, step) else \
            "fretting gross slip"
    if load.get("sliding"):
        return "full sliding"
    tangential = ("Qx", "Qy", "shift_x", "shift_y")
    return "partial slip" if any(load.get(k) is not None for k in tangential) else "normal"


def _case_rows(case: CaseResults) -> pd.DataFrame:
    m = case.metrics
    if m.empty:
        return pd.DataFrame(columns=[*COLUMNS[:3], "status", "reason", "note"])
    summary = case.summary.assign(param=case.summary["param"].astype(object).fillna(""))
    params = m["param"].astype(object).fillna("")
    regimes = [regime(case.point(p), summary, p, int(s), float(c))
               for p, s, c in zip(params, m["step"], m["cycle"], strict=True)]
    return pd.DataFrame({"regime": regimes, "quantity": m["quantity"],
                         "oracle": m["oracle"], "status": m["status"],
                         "reason": m["reason"], "note": m["note"].astype(object).fillna("")})


def _why(rows: pd.DataFrame) -> str:
    """Why none of ``rows`` is gated: their counts by reason, and the most frequent note."""
    counts = Counter(rows["reason"]).most_common()
    note = next(iter(Counter(_REF.sub("", n) for n in rows["note"] if n).most_common(1)),
                ("", 0))[0]
    return ", ".join(f"{tol.reason_words(r)} {n}" for r, n in counts) + \
        (f": {note}" if note else "")


def table(results: Scan) -> pd.DataFrame:
    """The coverage of every complete case of ``results`` (module doc), one row per
    regime × quantity × oracle that has metric rows, in the order of :data:`REGIMES`
    and of the quantities' registry."""
    frames = [_case_rows(c) for c in results.complete]
    rows = pd.concat(frames, ignore_index=True) if frames else pd.DataFrame()
    out = []
    if rows.empty:
        return pd.DataFrame(columns=COLUMNS)
    order = {q: i for i, q in enumerate(tol.QUANTITY_METRICS)}
    for (reg, q, oracle), g in rows.groupby(["regime", "quantity", "oracle"]):
        on = g["status"] == tol.GATED
        why = "" if on.any() else _why(g)
        out.append({"regime": reg, "quantity": q, "oracle": oracle, "rows": len(g),
                    "gated": int(on.sum()), "why": why})
    df = pd.DataFrame(out, columns=COLUMNS)
    key = df["regime"].map(REGIMES.index) * 1000 + df["quantity"].map(order).fillna(999)
    return df.assign(_k=key).sort_values(["_k", "oracle"], kind="stable") \
        .drop(columns="_k").reset_index(drop=True)


def holes(cov: pd.DataFrame) -> pd.DataFrame:
    """The cells with rows and no gated row."""
    return cov[cov["gated"] == 0]


def pivot(cov: pd.DataFrame) -> pd.DataFrame:
    """Per regime and quantity, one column per kind of reference: ``gated / rows``, and
    why none is gated where none is; empty where the kind compares nothing."""
    cells = cov.assign(cell=[f"{g} / {n}" + (f" ({w})" if not g and w else "")
                             for g, n, w in zip(cov["gated"], cov["rows"], cov["why"],
                                                strict=True)])
    out = cells.pivot(index=["regime", "quantity"], columns="oracle", values="cell")
    order = list(dict.fromkeys(zip(cov["regime"], cov["quantity"], strict=True)))
    return out.reindex(order).fillna("").reset_index()


def markdown(cov: pd.DataFrame) -> str:
    """:func:`pivot` as a Markdown table."""
    t = pivot(cov)
    lines = ["| " + " | ".join(t.columns) + " |", "|" + "---|" * len(t.columns)]
    lines += ["| " + " | ".join(str(v) for v in row) + " |" for row in t.itertuples(index=False)]
    return "\n".join(lines)


#: the page of the full table, beside the case pages (no case's name starts with "_")
PAGE = "_coverage.html"


def by_regime(cov: pd.DataFrame) -> pd.DataFrame:
    """Per regime of :func:`table`: its cells (quantity × kind of reference with rows), the
    cells with none of their rows gated, the rows and the gated rows; in the order of
    :data:`REGIMES`."""
    g = cov.assign(hole=cov["gated"] == 0).groupby("regime", sort=False)
    out = pd.DataFrame({"cells": g.size(), "none gated": g["hole"].sum(),
                        "rows": g["rows"].sum(), "gated rows": g["gated"].sum()})
    out = out.reindex([r for r in REGIMES if r in out.index])
    return out.astype(int).reset_index()


def html(results: Scan) -> tuple[str, str]:
    """The Coverage section of the report's index (:func:`by_regime`, linking the full
    table) and the section of its own page (:func:`pivot`); empty without metric rows."""
    from reports.render.html_blocks import table_html

    cov = table(results)
    if cov.empty:
        return "", ""
    n = len(holes(cov))
    index = ('<h2 id="coverage">Coverage</h2><div class="coverage"><p>Per regime: its cells '
             "(quantity × kind of reference with compared rows), those with none gated, "
             f"and the rows ({n} cell(s) with none gated; "
             f'<a href="{layout.REPORT_PAGES}/{PAGE}">the full table</a>, '
             "<code>reports/render/coverage.py</code>).</p>"
             + table_html(by_regime(cov), left=1) + "</div>")
    page = ('<h2 id="coverage">Coverage</h2><div class="coverage"><p>Per regime, quantity '
            "and kind of reference: gated rows / compared rows, and why none is gated "
            f"where none is ({n} such cell(s)).</p>" + table_html(pivot(cov), left=2)
            + "</div>")
    return index, page
