"""The tables of a case's grid studies for the report: the run's own studies
(``convergence.csv`` of ``run --convergence``) and the study a sweep over cell sizes makes
(observed order and Roache's GCI of p_max and σ_VM,max, :mod:`reports.studies.three_level`), and
its cycle-jump studies (``jump_study.csv`` of ``run --jump-study``)."""

from __future__ import annotations

import math

import pandas as pd

from reports.registry import solvers
from reports.store.results import CaseResults
from reports.studies import gridstudy, probe, three_level
from reports.studies.gridstudy import GRID_STUDY
from reports.studies.jumpstudy import JUMP_STUDY


def scales(case: CaseResults) -> dict[str, tuple[float, float]]:
    """(a0, p0) of every sweep point of a case, from its manifest."""
    return {p.get("param", ""): (float(p.get("hertz_a0", math.nan)),
                                 float(p.get("hertz_p0", math.nan)))
            for p in case.manifest.get("points", [])}


def convergence_frame(case: CaseResults) -> pd.DataFrame:
    """Observed order and GCI of p_max and σ_VM,max from the three finest grids of every
    solver whose cell size varies across the sweep points (last output step)."""
    rows = []
    summary = case.summary
    if summary.empty:
        return pd.DataFrame()
    last = summary.sort_values("step").groupby(["solver", "param"], sort=False).tail(1)
    if "cell_size" not in last.columns:
        return pd.DataFrame()
    for solver, sub in last.groupby("solver", sort=False):
        if solvers.record(solver).closed_form:
            continue
        sub = sub.assign(h=sub["cell_size"]).dropna(subset=["h"]).drop_duplicates("h")
        sub = sub.sort_values("h")
        if len(sub) < 3:
            continue
        three = sub.head(3)
        a0, p0 = scales(case).get(three["param"].iloc[0], (math.nan, math.nan))
        for q in ("p_max", "vm_max"):
            f = tuple(float(v) for v in three[q])
            if not all(math.isfinite(v) for v in f):
                continue
            st = three_level.study(f, tuple(float(v) for v in three["h"]))
            rows.append({
                "solver": solver, "quantity": q,
                "h1/a0": st.h[0] / a0, "h2/a0": st.h[1] / a0, "h3/a0": st.h[2] / a0,
                "f1/p0": st.f[0] / p0, "f2/p0": st.f[1] / p0, "f3/p0": st.f[2] / p0,
                "order p": st.p, "f_ext/p0": st.f_ext / p0, "GCI21 [%]": 100 * st.gci_fine,
                "GCI32 [%]": 100 * st.gci_coarse, "GCI32/(r^p GCI21)": st.asymptotic,
                "converging": st.converging,
            })
    return pd.DataFrame(rows)


def study_frame(case: CaseResults) -> pd.DataFrame:
    """The run's grid studies (``convergence.csv``) for the page: cell sizes in units of
    a0, the three values (finest first) in the quantity's unit, order, GCI, status."""
    conv = case.study(GRID_STUDY.name)
    if conv.empty:
        return pd.DataFrame()
    a0 = conv["param"].map(lambda p: scales(case).get(p, (math.nan,) * 2)[0])
    return pd.DataFrame({
        "solver": conv["solver"], "param": conv["param"], "step": conv["step"],
        "quantity": conv["quantity"],
        "unit": conv["quantity"].map(lambda q: gridstudy.UNITS.get(q, "")),
        "h1/a0": conv["h1"] / a0, "h2/a0": conv["h2"] / a0, "h3/a0": conv["h3"] / a0,
        "f1": conv["f1"], "f2": conv["f2"], "f3": conv["f3"], "order p": conv["order"],
        "f_ext": conv["f_extrapolated"], "GCI21 [%]": 100 * conv["gci_fine"],
        "status": conv["status"], "note": conv["note"]})


def jump_frame(case: CaseResults) -> pd.DataFrame:
    """The run's cycle-jump studies (``jump_study.csv``) for the page: the jumps J/4, J/2,
    J, the three values (finest first), the change when the run's J is halved [%], order,
    extrapolated value, status."""
    js = case.study(JUMP_STUDY.name)
    if js.empty:
        return pd.DataFrame()
    return pd.DataFrame({
        "solver": js["solver"], "param": js["param"], "cycle": js["cycle"],
        "quantity": js["quantity"],
        "unit": js["quantity"].map(lambda q: gridstudy.UNITS.get(q, "")),
        "J/4": js["h1"], "J/2": js["h2"], "J": js["h3"],
        "f(J/4)": js["f1"], "f(J/2)": js["f2"], "f(J)": js["f3"],
        "halving J [%]": 100 * js["change_halved"], "order p": js["order"],
        "f_ext": js["f_extrapolated"], "status": js["status"], "note": js["note"]})


def probe_frame(case: CaseResults) -> pd.DataFrame:
    """The resolution probe (``probe.csv``, :mod:`reports.studies.probe`) for the page: per
    probed row, the quantity's change under the spread wear step, the row's tolerance and
    whether the probe admits it to the gate."""
    table = case.study(probe.PROBE.name)
    if table.empty:
        return pd.DataFrame()
    table = probe.admitted(case.metrics, table)
    return pd.DataFrame({
        "param": table["param"], "pair": table["pair"], "cycle": table["cycle"],
        "quantity": table["quantity"], "metric": table["metric"],
        "sensitivity": table["sensitivity"], "tolerance": table["tolerance"],
        "status": table["admitted"].map({True: "gated", False: "not gated"})})
