"""Claims 10–13 of the source article: orthotropic fretting, gross and partial slip
(Figs. 15–18), judged from the ``fretting`` source of
:mod:`reports.studies.claims.sources` and the β thresholds of ``thresholds.csv``."""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import pandas as pd
from scipy import ndimage

from reports.studies.claims.finding import (
    FAILS,
    HOLDS,
    UNDECIDED,
    Article,
    Finding,
    MissingSource,
    Panel,
    fmt,
    measure,
    study_evidence,
    undecided,
)
from reports.studies.claims.sources import SOURCES
from reports.studies.gridstudy import GRID_STUDY

SRC = "fretting"
#: the two normal controls the article leaves open, as sources (the transverse motion
#: held; at β = 0 and 90° held and free are the same problem)
CONTROLS = {"approach held": "fretting", "load held": "fretting_load"}
#: the four readings of the set-up: both normal controls, the transverse motion held or
#: free (Qy = 0)
READINGS = {**CONTROLS, "approach held, transverse free": "fretting_free",
            "load held, transverse free": "fretting_load_free"}
#: the reading of a threshold's case (``thresholds.csv``'s case column)
READING_OF = {SOURCES[src].name: label for label, src in READINGS.items()}
#: the article's regime-change angle (claim 13) and its printed resolution
ARTICLE_BETA = 67.0
#: the crown of claim 10: the wear at the centre of the stick zone below this share of
#: the largest wear depth
CROWN = 0.25
STICK, SLIP = 1, 2


#: a stick cell carries load above this share of the peak pressure (the worn annulus
#: touches at pressures of 1e-9 p0: in contact, not sliding, and carrying nothing)
CARRYING = 1e-6


def carrying_stick(step) -> np.ndarray:
    """The stick cells that carry load (:data:`CARRYING`)."""
    p = step.surface["p_n"]
    return (step.surface["state"] == STICK) & (p > CARRYING * p.max())


def _point(art: Article, beta: float, src: str = SRC, solver: str = "ic"
           ) -> tuple[str, pd.DataFrame] | None:
    r = art.rows(src, solver)
    r = r[r["value"] == beta]
    return (r["param"].iloc[0], r) if not r.empty else None


def _cycles(art: Article, src: str, solver: str, param: str) -> pd.DataFrame:
    return art.case(src).tables(solver, param).get("cycles", pd.DataFrame())


def _last_step(art: Article, src: str, solver: str, param: str):
    steps = art.case(src).steps(solver, param)
    return steps[max(steps)] if steps else None


def regimes(art: Article, src: str = SRC) -> Finding:
    """Claim 10: at β = 0 gross slip and the wear widens the contact; at β = 90 partial
    slip, with a crown of wear around an unworn stick zone."""
    g, p = _point(art, 0.0, src), _point(art, 90.0, src)
    if g is None or p is None:
        return undecided("needs the fretting sweep at β = 0 and 90°")
    out, bad, panels = [], [], []
    (pg, rg), (pp, _) = g, p
    a0, _ = art.scale(src, pg)
    cg, cp = _cycles(art, src, "ic", pg), _cycles(art, src, "ic", pp)
    gross = bool(len(cg)) and bool((cg["min_stick_area"] == 0).all())
    area0 = math.pi * a0**2
    area = rg["contact_area"].to_numpy()
    u = measure(art, src, "ic", pg, int(rg["step"].iloc[-1]), "contact_area", area[-1]).u
    widens = area[-1] - u > area0 and bool(np.all(np.diff(area) > -u))
    out.append(f"β = 0: least stick area over every cycle {fmt(cg['min_stick_area'].max())} "
               f"mm²; contact area {fmt(area0)} (unworn) → {', '.join(fmt(a) for a in area)} "
               f"± {fmt(u, 2)} mm²")
    bad += [] if gross else ["β = 0 is not in gross slip"]
    bad += [] if widens else ["the wear does not widen the β = 0 contact"]
    partial = bool(len(cp)) and bool((cp["min_stick_area"] > 0).all())
    bad += [] if partial else ["β = 90 is not in partial slip"]
    st = _last_step(art, src, "ic", pp)
    w = 1e3 * (st.surface["wear_a"] + st.surface["wear_b"])
    stick = carrying_stick(st)
    i0, j0 = int(np.argmin(np.abs(st.x))), int(np.argmin(np.abs(st.y)))
    centre = float(w[i0, j0] / w.max()) if w.max() > 0 else math.nan
    inside = float(w[stick].max() / w.max()) if stick.any() else math.nan
    crown = stick[i0, j0] and centre < CROWN
    bad += [] if crown else [f"no crown: the centre's wear is {fmt(centre)} of the largest"]
    out.append(f"β = 90: least stick area {fmt(cp['min_stick_area'].min())} mm² over every "
               f"cycle; at the last output the centre's wear {fmt(centre, 2)} of the largest, "
               f"the stick zone's largest {fmt(inside, 2)}")
    for beta, param in ((0.0, pg), (90.0, pp)):
        s = _last_step(art, src, "ic", param)
        wt = 1e3 * (s.surface["wear_a"] + s.surface["wear_b"])
        panels.append(Panel(f"wear depth along x, β = {beta:g}° (last output)", "x / a0",
                            "w_a + w_b [µm]", {"ic": (s.x / a0, wt[:, j0])}))
    return Finding("; ".join(out), "areas ± their uncertainty; the crown from the cells "
                   f"(centre below {CROWN:g} of the largest wear)", FAILS if bad else HOLDS,
                   "; ".join(bad) or "gross slip with a widening contact at β = 0; partial "
                   "slip at β = 90 with the stick zone unworn and the wear around it",
                   tuple(panels), {"centre_wear": centre})


def gross_slip_pressure(art: Article, src: str = SRC) -> Finding:
    """Claim 11: in gross slip (β = 30°) the pressure falls while the contact grows."""
    found = _point(art, 30.0, src)
    if found is None:
        return undecided("needs the fretting sweep at β = 30°")
    param, r = found
    a0, p0 = art.scale(src, param)
    cyc = np.concatenate([[0.0], r["cycle"].to_numpy()])
    p = np.concatenate([[p0], r["p_max"].to_numpy()])
    a = np.concatenate([[math.pi * a0**2], r["contact_area"].to_numpy()])
    up = [0.0] + [measure(art, src, "ic", param, int(k), "p_max", v).u
                  for k, v in zip(r["step"], r["p_max"], strict=True)]
    ua = [0.0] + [measure(art, src, "ic", param, int(k), "contact_area", v).u
                  for k, v in zip(r["step"], r["contact_area"], strict=True)]
    up, ua = np.array(up), np.array(ua)
    falls = bool(np.all(np.diff(p) < up[1:] + up[:-1]))
    grows = bool(np.all(np.diff(a) > -(ua[1:] + ua[:-1])))
    lost = _load_lost(art, src, param)
    ok = (falls and grows and p[-1] + up[-1] < p[0] and a[-1] - ua[-1] > a[0]
          and lost > cyc[-1])
    measured = (f"ic, β = 30°, from the unworn contact (Hertz at the held approach or load) over "
                f"cycles {', '.join(f'{c:g}' for c in cyc)}: p_max/p0 "
                f"{', '.join(fmt(v / p0) for v in p)}, contact area/πa0² "
                f"{', '.join(fmt(v / a[0]) for v in a)}"
                + (f"; the load lost at cycle {lost:g}" if math.isfinite(lost) else ""))
    panel = Panel("β = 30°: pressure and contact area", "N (cycles)", "relative to cycle 0",
                  {"p_max / p0": (cyc, p / p0), "area / πa0²": (cyc, a / a[0])}, markers=True)
    why = ("the pressure falls and the contact grows at every output" if ok else
           f"the contact is worn away: the load is lost (the run's load_lost event) by cycle "
           f"{lost:g}, before the last output" if lost <= cyc[-1] else
           "the pressure does not fall or the contact does not grow throughout")
    return Finding(measured, "each value ± its uncertainty", HOLDS if ok else FAILS, why,
                   (panel,))


def _load_lost(art: Article, src: str, param: str) -> float:
    """The cycle of the ic run's ``load_lost`` event (a held approach: P below 1 % of the
    initial load, reports/README.md, events); infinity if none."""
    e = art.case(src).events
    e = e[(e["solver"] == "ic") & (e["param"] == param) & (e["event"] == "load_lost")]
    return float(e["cycle"].min()) if len(e) else math.inf


def partial_slip_pressure(art: Article, src: str = SRC) -> Finding:
    """Claim 12: in partial slip (β = 90°) the pressure turns towards a nearly uniform
    distribution over the stick zone, with a maximum more than twice the first cycles'
    (the unworn contact's p0 at the held approach).

    Uniformity is judged inside the stick zone less its edge cells (the worn profile
    steps at the stick edge, and the pressure peaks there): the coefficient of variation
    of p_n there against Hertz's over the same cells, and the share of the load the stick
    zone carries, output by output. A maximum on the stick edge is the step's peak: it is
    a number only where a grid study shows how it moves.  What the run's studies say of
    the point is added (:func:`reports.studies.claims.finding.study_evidence`): which
    quantities the grid study
    settles, and which the resolution probe admits — a maximum at the step that grows
    under refinement and that the probe moves is the model's singularity (a step in the
    worn profile, like a flat punch's edge), not a number to compare."""
    found = _point(art, 90.0, src)
    if found is None:
        return undecided("needs the fretting sweep at β = 90°")
    param, r = found
    a0, p0 = art.scale(src, param)
    cycles, cv, cv_h, share = [], [], [], []
    steps = art.case(src).steps("ic", param)
    for k in sorted(steps):
        st = steps[k]
        stick = carrying_stick(st)
        inner = ndimage.binary_erosion(stick)
        if not inner.any():
            continue
        p = st.surface["p_n"]
        X, Y = np.meshgrid(st.x, st.y, indexing="ij")
        hertz = p0 * np.sqrt(np.clip(1.0 - (X**2 + Y**2) / a0**2, 0.0, None))
        cycles.append(float(st.scalars.get("cycle", math.nan)))
        cv.append(float(np.std(p[inner]) / np.mean(p[inner])))
        cv_h.append(float(np.std(hertz[inner]) / np.mean(hertz[inner])))
        share.append(float(p[stick].sum() / p.sum()))
    if not cycles:
        return undecided("no stick zone wider than its edge cells at β = 90°")
    last = r.iloc[-1]
    m = measure(art, src, "ic", param, int(last["step"]), "p_max", float(last["p_max"]))
    st = steps[max(steps)]
    p, stick = st.surface["p_n"], carrying_stick(st)
    edge = stick & ~ndimage.binary_erosion(stick) | ndimage.binary_dilation(stick) & ~stick
    on_edge = bool(edge.flat[int(np.argmax(p))])
    ratio, u = m.value / p0, m.u / p0
    flatter = cv[-1] < cv_h[-1] and share[-1] >= share[0]
    lower_bound = on_edge and _grows(art, src, param, int(last["step"]))
    if not flatter:
        verdict, why = FAILS, "the pressure inside the stick zone is not flatter than Hertz's"
    elif ratio + u < 2.0 and not on_edge:
        verdict, why = FAILS, "the maximum is below twice the first cycles'"
    elif ratio - u > 2.0 and (m.settled and not on_edge or lower_bound):
        verdict = HOLDS
        why = ("nearly uniform inside the stick zone, which carries more and more of the "
               "load, and p_max above 2 p0" + ("; p_max sits on the stick edge, where the worn "
               "profile steps, and grows under refinement (no limit): the ratio is a lower "
               "bound" if on_edge else ""))
    else:
        verdict = UNDECIDED
        why = ("nearly uniform inside the stick zone, but p_max sits on the stick edge, where "
               "the worn profile steps: not a converged number without a grid study showing "
               "it grow" if on_edge else "the ratio is within its uncertainty of 2")
    panels = _pressure_panels(st, a0, p0, {"CV of p_n": cv, "CV of Hertz's p": cv_h,
                                           "load share": share}, cycles)
    measured = (f"ic at cycles {', '.join(f'{c:g}' for c in cycles)}: coefficient of "
                f"variation of p_n inside the stick zone {', '.join(f'{v:.3f}' for v in cv)} "
                f"(Hertz's over the same cells {', '.join(f'{v:.3f}' for v in cv_h)}), share "
                f"of the load {', '.join(f'{v:.2f}' for v in share)}; p_max/p0 = {ratio:.3f} "
                f"± {fmt(u, 2)} ({m.basis})" + (", on the stick edge" if on_edge else "")
                + study_evidence(art.case(src), param, int(last["step"]), CLAIM_12))
    if on_edge:
        why += ("; the maximum at the step is the model's singularity (the worn profile "
                "steps there), not a number to compare between solvers")
    return Finding(measured, "p_max ± " + m.basis, verdict, why, panels,
                   {"ratio": ratio, "cv": cv[-1], "cv_hertz": cv_h[-1]})


def _pressure_panels(st, a0: float, p0: float, series: dict[str, list[float]],
                     cycles: list[float]) -> tuple[Panel, Panel]:
    """Claim 12's panels: the pressure along x at the last output against the unworn
    contact's, and ``series`` inside the stick zone against the cycles."""
    j0 = int(np.argmin(np.abs(st.y)))
    X, Y = np.meshgrid(st.x, st.y, indexing="ij")
    hertz = p0 * np.sqrt(np.clip(1.0 - (X**2 + Y**2) / a0**2, 0.0, None))
    return (Panel("β = 90°: pressure along x at the last output", "x / a0", "p_n / p0",
                  {"ic": (st.x / a0, st.surface["p_n"][:, j0] / p0),
                   "unworn (Hertz)": (st.x / a0, hertz[:, j0] / p0)}),
            Panel("inside the stick zone", "N (cycles)", "",
                  {k: (np.array(cycles), np.array(v)) for k, v in series.items()},
                  markers=True))


#: the quantities of claim 12 whose standing the studies are asked about
CLAIM_12 = ("P", "p_max", "stick_area", "w_max", "wear_volume")


def _grows(art: Article, src: str, param: str, step: int) -> bool:
    """Whether the grid study of p_max shows it growing with every refinement."""
    study = art.case(src).study(GRID_STUDY.name)
    row = study[(study["solver"] == "ic") & (study["param"] == param)
                & (study["step"] == step) & (study["quantity"] == "p_max")]
    if row.empty:
        return False
    r = row.iloc[0]
    return bool(r["f1"] > r["f2"] > r["f3"])


#: why claims at β = 0 and 90° need only the two normal controls
AXES_NOTE = ("the transverse motion held or free is the same problem at β = 0 and 90° (the "
             "friction and wear axes lie along the motion)")


def under_readings(judge: Callable[[Article, str], Finding],
                   readings: dict[str, str] = CONTROLS, note: str = ""
                   ) -> Callable[[Article], Finding]:
    """A claim judged under each reading of the set-up the article leaves open (the held
    approach and the held load; with ``READINGS`` also the transverse motion free): it
    holds if it holds under one, and says under which; it does not hold if it holds under
    none."""
    def both(art: Article) -> Finding:
        found = {}
        for control, src in readings.items():
            try:
                found[control] = judge(art, src)
            except MissingSource as exc:
                found[control] = undecided(str(exc))
        verdicts = [f.verdict for f in found.values()]
        holds = [c for c, f in found.items() if f.verdict == HOLDS]
        verdict = HOLDS if holds else FAILS if all(v == FAILS for v in verdicts) else UNDECIDED
        why = "; ".join(f"{c}: {f.verdict} ({f.why})" for c, f in found.items())
        if note:
            why += "; " + note
        if holds:
            which = ("every reading" if len(holds) == len(found) > 1 else
                     "the " + "; the ".join(holds))
            why = f"reproduced with {which}; " + why
        panels = tuple(Panel(f"{c}: {p.title}", p.xlabel, p.ylabel, p.series, p.markers)
                       for c, f in found.items() for p in f.panels)
        return Finding("; ".join(f"{c}: {f.measured}" for c, f in found.items()),
                       "; ".join(f"{c}: {f.uncertainty}" for c, f in found.items()), verdict,
                       why, panels, {f"{c}: {k}": v for c, f in found.items()
                                     for k, v in f.values.items()})
    both.__doc__ = judge.__doc__
    return both


def _cycle_of(at: str) -> float:
    """The cycle of a threshold's ``at`` label (``cycle=1000``); NaN if none."""
    try:
        return float(at.partition("=")[2])
    except ValueError:
        return math.nan


def _thresholds(t: pd.DataFrame) -> list[dict]:
    """Per (case, output) of one solver: the finest grid's threshold, its uncertainty
    (half the bracket plus the largest shift to a coarser grid) and every grid's value."""
    out = []
    for (case, at), g in t.groupby(["case", "at"], sort=False):
        g = g.sort_values("cell_size")
        fine = g.iloc[0]
        shift = float(np.nanmax(np.abs(g["threshold"] - fine["threshold"])))
        out.append({"control": READING_OF.get(str(case), str(case)),
                    "case": case, "at": str(at), "cycle": _cycle_of(str(at)),
                    "beta": float(fine["threshold"]), "u": float(fine["uncertainty"]) + shift,
                    "grids": ", ".join(f"{r.grid} {r.threshold:.1f}" for r in g.itertuples())})
    return sorted(out, key=lambda r: (r["control"], r["cycle"]))


def regime_change(art: Article) -> Finding:
    """Claim 13: the regime turns from gross to partial slip at β ≈ 67°, where σ_VM,max
    after 10⁵ cycles is largest.  A FEM threshold in ``thresholds.csv`` (``contact-vv
    threshold fretting_orthotropic --param friction.beta --event gross_to_partial_slip
    --solver fem ...``) checks the half-space solver's at the same output."""
    t = art.thresholds
    t = t[(t["event"] == "gross_to_partial_slip") & (t["param"] == "friction.beta")
          & t["threshold"].notna()]
    ic = _thresholds(t[t["solver"] == "ic"])
    if not ic:
        return undecided("no ic threshold of gross_to_partial_slip in friction.beta in "
                         "thresholds.csv")
    near = [abs(r["beta"] - ARTICLE_BETA) <= 1.0 + r["u"] for r in ic]
    parts = [f"{r['control']}, {r['at']}: {r['beta']:.1f}° ± {fmt(r['u'], 2)} ({r['grids']})"
             for r in ic]
    checks = []
    for f in _thresholds(t[t["solver"] == "fem"]):
        mate = next((r for r in ic if (r["case"], r["at"]) == (f["case"], f["at"])), None)
        agree = mate is not None and abs(mate["beta"] - f["beta"]) <= mate["u"] + f["u"]
        checks.append(f"FEM {f['control']}, {f['at']}: {f['beta']:.1f}° ± {fmt(f['u'], 2)}"
                      + ("" if mate is None else " (agrees with ic)" if agree else
                         " (differs from ic)"))
    peak = {}
    for solver in art.base_solvers(SRC):
        r = art.rows(SRC, solver)
        last = r[r["step"] == r["step"].max()]
        if len(last) > 1:
            peak[solver] = (float(last["value"].iloc[int(last["vm_max"].to_numpy().argmax())]),
                            float(last["cycle"].iloc[0]))
    verdict = HOLDS if all(near) else FAILS if not any(near) else UNDECIDED
    betas = ", ".join(f"{r['beta']:.1f}°" for r in ic)
    why = {FAILS: f"the half-space solver puts the change at {betas}, none near "
                  f"{ARTICLE_BETA:g}°, under every reading of the set-up, output and grid",
           UNDECIDED: f"the thresholds ({betas}) straddle the article's {ARTICLE_BETA:g}°",
           HOLDS: f"every threshold is within 1° and its uncertainty of {ARTICLE_BETA:g}°"}[
               verdict]
    closest = min(ic, key=lambda r: abs(r["beta"] - ARTICLE_BETA))
    why += f"; closest: {closest['control']}, {closest['at']}: {closest['beta']:.1f}°"
    if "ic" in peak:
        why += (f"; σ_VM,max at cycle {peak['ic'][1]:g} is largest at β = {peak['ic'][0]:g}° "
                "of the sweep")
    why += "; " + ("; ".join(checks) if checks else "no FEM threshold at an oblique β here")
    series: dict[str, tuple[np.ndarray, np.ndarray]] = {}
    for control in dict.fromkeys(r["control"] for r in ic):
        mine = [r for r in ic if r["control"] == control]
        series[f"ic, {control}"] = (np.array([r["cycle"] for r in mine]),
                                    np.array([r["beta"] for r in mine]))
    panel = Panel("β at the gross-to-partial-slip change", "N (cycles)", "β [°]", series,
                  markers=True)
    return Finding("; ".join(parts + checks), "± half the bisection bracket plus the "
                   "largest grid shift", verdict, why, (panel,),
                   {"beta_peak": peak.get("ic", (math.nan,))[0],
                    **{f"beta_first: {r['control']}": r["beta"] for r in ic
                       if r["cycle"] == 1}})
