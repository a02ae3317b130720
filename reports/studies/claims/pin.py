"""Claims 2, 3 and 6–9 of the source article: the worn pin, isotropic (Figs. 6–9) and
orthotropic (Figs. 10–13, 20), judged from the ``pin`` and ``pin_ortho`` sources of
:mod:`reports.studies.claims.sources`."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from reports.store.readers import gated
from reports.studies.claims.finding import (
    FAILS,
    HOLDS,
    UNDECIDED,
    Article,
    Finding,
    Panel,
    closed_form,
    fmt,
    measure,
    undecided,
)

#: what "differ markedly" is taken to mean in claim 7: a spread over β above 10 %
MARKED = 0.10
WORN = ("w_max", "wear_volume", "p_max", "a_x", "contact_area")


def _theta(point: dict) -> float:
    """θ of formulation Eq. 19: the sliding direction's angle from e1."""
    return float(point["load"]["slide_angle"]) - float(point["friction"]["beta"])


def _closed(art: Article, source: str, param: str, s: np.ndarray) -> dict:
    point = art.case(source).point(param)
    a0, _ = art.scale(source, param)
    return closed_form("worn_pin")(s, a0, point["a"]["i1"], point["a"]["i2"], _theta(point),
                                   point["load"]["P"], point["R"])


def worn_pin(art: Article) -> Finding:
    """Claim 2: w_max(s), a(s) and p_max(s) of the frictionless worn pin follow Argatov's
    asymptotic solution and Hegadekatte's cap model; judged by the gate's ic-analytic
    rows of those quantities (tolerance: the two error budgets, Argatov's asymptotic
    term included) and the ic wear depth against Hegadekatte's."""
    src = "pin"
    r = art.rows(src, "ic")
    r = r[r["value"] == 0.0]
    if r.empty:
        return undecided("no frictionless worn pin (μ = 0) in the pin results")
    param = r["param"].iloc[0]
    a0, p0 = art.scale(src, param)
    s = r["s"].to_numpy()
    sd = np.linspace(0.0, s.max(), 200)
    cf = _closed(art, src, param, sd)
    at = _closed(art, src, param, s)
    m = art.case(src).metrics
    m = m[(m["pair"] == "ic-analytic") & (m["param"] == param) & m["quantity"].isin(WORN)
          & gated(m)]
    worn = m[m["step"] > 0]
    panels = (
        Panel("maximum wear depth", "s / a0", "w_max [µm]",
              {"ic": (s / a0, 1e3 * r["w_max"].to_numpy()),
               "Argatov": (sd / a0, 1e3 * cf["w"]),
               "Hegadekatte": (sd / a0, 1e3 * cf["w_cap"])}),
        Panel("contact semi-width", "s / a0", "a / a0",
              {"ic": (s / a0, r["a_x"].to_numpy() / a0),
               "Argatov": (sd / a0, cf["a"] / a0)}),
        Panel("maximum pressure", "s / a0", "p_max / p0",
              {"ic": (s / a0, r["p_max"].to_numpy() / p0),
               "Argatov (uniform)": (sd / a0, cf["p_max"] / p0)}))
    if worn.empty:
        return undecided("no gated ic-analytic row of the worn pin (run the analytic "
                         "solver with ic)", panels)
    failed = worn[~worn["passed"].astype(bool)]
    depth_rows = worn[worn["quantity"] == "w_max"]  # where Argatov's depth is stated
    compared = np.isin(s, depth_rows["s"].to_numpy()) & (at["w_cap"] > 0)
    cap = np.abs(r["w_max"].to_numpy()[compared] - at["w_cap"][compared]) / at["w_cap"][compared]
    worst = worn.assign(margin=worn["value"] / worn["tolerance"]).sort_values("margin").iloc[-1]
    measured = (f"{len(worn)} gated ic-analytic rows of the worn pin, worst "
                f"{worst['quantity']} {worst['metric']} {fmt(worst['value'])} against "
                f"{fmt(worst['tolerance'])} at s = {fmt(worst['s'])} mm; ic w_max from "
                f"Hegadekatte's cap depth at most {fmt(100 * cap.max(), 2)} %")
    verdict = FAILS if len(failed) else HOLDS
    why = ("every row within the combined error budget, Argatov's asymptotic term "
           "included" if verdict == HOLDS else
           f"{len(failed)} rows exceed the combined budget: "
           + ", ".join(sorted(set(failed["quantity"]))))
    return Finding(measured, "the pair's tolerance: both error budgets", verdict, why, panels,
                   {"worst_margin": float(worst["value"] / worst["tolerance"])})


def _axis_max(art: Article, source: str, solver: str, param: str, step: int) -> float:
    """The largest σ_VM on the axis x = y = 0 over the stress planes of a step that
    contain it (NaN without one)."""
    found = art.case(source).steps(solver, param).get(step)
    stress = art.case(source).point(param).get("stress", {})
    through = {"xz": float(stress.get("y0", 0.0)), "yz": float(stress.get("x0", 0.0))}
    best = math.nan
    for name, plane in (found.planes.items() if found is not None else ()):
        if through.get(name, math.nan) != 0.0:
            continue  # a plane off the axis
        i = int(np.argmin(np.abs(plane.s)))
        if abs(plane.s[i]) <= 1e-12 * max(1.0, float(np.abs(plane.s).max())):
            best = float(np.nanmax([best, np.nanmax(plane.fields["vm"][i])]))
    return best


def frictionless_depth(art: Article) -> Finding:
    """Claim 3: the frictionless worn pin's σ_VM,max falls with s and moves deeper than
    z/a0 = 0.48, staying on the axis: a maximum sampled off the axis (beyond two half
    cells) leaves it only where σ_VM on the axis is lower by more than the maximum's
    uncertainty — on a flat plateau the axis is as much the maximum's place as the
    sample that happens to be largest (the near-maximum set of
    :mod:`reports.compare.maxima`)."""
    src, out, series, bad = "pin", [], {"vm": {}, "z": {}}, []
    for solver in art.base_solvers(src):
        r = art.rows(src, solver)
        r = r[(r["value"] == 0.0) & r["vm_max"].notna()]
        if len(r) < 2:
            continue
        param = r["param"].iloc[0]
        a0, p0 = art.scale(src, param)
        dz, dx = art.half_cell(src, param)
        s, vm, z = r["s"].to_numpy(), r["vm_max"].to_numpy(), r["vm_max_z"].to_numpy()
        off = np.hypot(r["vm_max_x"].to_numpy(), r["vm_max_y"].to_numpy())
        u = np.array([measure(art, src, solver, param, int(k), "vm_max", v).u
                      for k, v in zip(r["step"], vm, strict=True)])
        series["vm"][solver] = (s / a0, vm / p0)
        series["z"][solver] = (s / a0, z / a0)
        if np.any(np.diff(vm) > u[1:] + u[:-1]):
            bad.append(f"{solver}: σ_VM,max grows at some s")
        if np.any(np.diff(z) < -2 * dz) or z[-1] <= z[0]:
            bad.append(f"{solver}: the maximum does not move deeper")
        axis = np.array([_axis_max(art, src, solver, param, int(k)) for k in r["step"]])
        left = (off > 2 * dx) & ~(vm - axis <= u)
        if np.any(left):
            bad.append(f"{solver}: the maximum leaves the axis ({fmt(off[left].max() / a0)} "
                       f"a0, σ_VM on the axis {fmt(np.max((vm - axis)[left] / vm[left]), 2)} "
                       "lower)")
        out.append(f"{solver}: σ_VM,max/p0 {fmt(vm[0] / p0)} → {fmt(vm[-1] / p0)}, z/a0 "
                   f"{fmt(z[0] / a0)} → {fmt(z[-1] / a0)} (s {s[0]:g} → {s[-1]:g} mm), at "
                   f"most {fmt(off.max() / a0)} a0 off the axis, where σ_VM is within "
                   f"{fmt(np.max((vm - axis) / vm), 2)} of it")
    if not out:
        return undecided("no σ_VM of the frictionless worn pin (μ = 0) over s")
    panels = (Panel("σ_VM,max of the frictionless pin", "s / a0", "σ_VM,max / p0",
                    series["vm"], markers=True),
              Panel("its depth", "s / a0", "z / a0", series["z"], markers=True))
    return Finding("; ".join(out), "σ_VM ± its uncertainty; locations ± half a cell",
                   FAILS if bad else HOLDS,
                   "; ".join(bad) or "the maximum falls and deepens step by step, on the axis",
                   panels)


def _ortho_last(art: Article, solver: str = "ic") -> pd.DataFrame:
    r = art.rows("pin_ortho", solver)
    return r[r["step"] == r["step"].max()]


def wear_with_beta(art: Article) -> Finding:
    """Claim 6: the orthotropic pin's wear grows with β, but W(90°) − W(0°) is not twice
    W(45°) − W(0°)."""
    last = _ortho_last(art).set_index("value")
    if not {0.0, 45.0, 90.0} <= set(last.index):
        return undecided("needs the orthotropic pin at β = 0, 45 and 90°")
    W = {b: float(last.loc[b, "wear_volume"]) for b in (0.0, 45.0, 90.0)}
    us = {b: measure(art, "pin_ortho", "ic", last.loc[b, "param"], int(last.loc[b, "step"]),
                     "wear_volume", W[b]).u for b in W}
    ratio = (W[90.0] - W[0.0]) / (W[45.0] - W[0.0])
    lo = (W[90.0] - us[90.0] - W[0.0] - us[0.0]) / (W[45.0] + us[45.0] - W[0.0] + us[0.0])
    hi = (W[90.0] + us[90.0] - W[0.0] + us[0.0]) / (W[45.0] - us[45.0] - W[0.0] - us[0.0])
    s = float(last["s"].iloc[0])
    exact = {b: float(_closed(art, "pin_ortho", last.loc[b, "param"], np.array([s]))["volume"][0])
             for b in W}
    r_exact = (exact[90.0] - exact[0.0]) / (exact[45.0] - exact[0.0])
    grows = W[0.0] < W[45.0] < W[90.0]
    verdict = HOLDS if grows and not lo <= 2.0 <= hi else FAILS
    measured = (f"ic at s = {s:g} mm: W = {fmt(W[0.0], 4)}, {fmt(W[45.0], 4)}, "
                f"{fmt(W[90.0], 4)} mm³ (β = 0, 45, 90°); (W90 − W0)/(W45 − W0) = "
                f"{ratio:.3f} [{lo:.3f}, {hi:.3f}]; Archard with i_w(θ) (Eq. 19): {r_exact:.3f}")
    why = ("the ratio follows from i_w(θ) = √((i1 cos θ)² + (i2 sin θ)²), which is not "
           "linear in sin²θ" if verdict == HOLDS else "the wear does not grow with β, or "
           "the ratio's interval contains 2")
    betas = np.array(sorted(W))
    panel = Panel("worn volume at the last output", "β [°]", "W [mm³]",
                  {"ic": (betas, np.array([W[b] for b in betas])),
                   "Archard, i_w(θ)": (betas, np.array([exact[b] for b in betas]))},
                  markers=True)
    return Finding(measured, "each W ± its uncertainty, propagated to the ratio's interval",
                   verdict, why, (panel,), {"ratio": ratio, "ratio_exact": r_exact})


def pressure_and_area(art: Article) -> Finding:
    """Claim 7: p_max and the contact area differ markedly for β = 0, 45 and 90°
    (taken as a spread over β above :data:`MARKED` and beyond the uncertainty)."""
    last = _ortho_last(art).set_index("value")
    if len(last) < 3:
        return undecided("needs the orthotropic pin at β = 0, 45 and 90°")
    out, ok, series = [], True, {}
    for q in ("p_max", "contact_area"):
        v = last[q].astype(float)
        u = max(measure(art, "pin_ortho", "ic", last.loc[b, "param"], int(last.loc[b, "step"]),
                        q, float(v[b])).u / float(v[b]) for b in v.index)
        spread_ = float((v.max() - v.min()) / v.max())
        ok &= spread_ > max(MARKED, 2 * u)
        out.append(f"{q}: {', '.join(fmt(x, 4) for x in v)} (spread {100 * spread_:.0f} %, "
                   f"uncertainty {100 * u:.1f} %)")
        series[q] = (v.index.to_numpy(), (v / v.iloc[0]).to_numpy())
    panel = Panel("at the last output, relative to β = 0", "β [°]", "value / value(β = 0)",
                  series, markers=True)
    return Finding("ic at the last output: " + "; ".join(out), "each value's relative "
                   "uncertainty", HOLDS if ok else FAILS,
                   f"both spread by more than {100 * MARKED:.0f} % and twice their "
                   "uncertainty" if ok else "a spread is within the threshold", (panel,))


def stress_with_beta(art: Article) -> Finding:
    """Claim 8: at fixed s the orthotropic pin's σ_VM,max grows with β and moves towards
    the surface."""
    r = art.rows("pin_ortho", "ic")
    r = r[r["s"] > 0]
    if r.empty or r["value"].nunique() < 3:
        return undecided("needs the worn orthotropic pin at three β")
    a0, p0 = art.scale("pin_ortho", r["param"].iloc[0])
    dz, _ = art.half_cell("pin_ortho", r["param"].iloc[0])
    falls, within, out, series = [], [], [], {}
    for s, g in r.groupby("s"):
        g = g.sort_values("value")
        vm, z = g["vm_max"].to_numpy(), g["vm_max_z"].to_numpy()
        u = np.array([measure(art, "pin_ortho", "ic", p, int(k), "vm_max", v).u
                      for p, k, v in zip(g["param"], g["step"], vm, strict=True)])
        d, tol = np.diff(vm), u[1:] + u[:-1]
        if np.any(d < -tol) or np.any(np.diff(z) > 2 * dz):
            falls.append(f"s = {s:g}")
        elif np.any(np.abs(d) <= tol):
            within.append(f"s = {s:g} mm ({fmt(100 * float(np.min(d / vm[:-1])), 2)} %)")
        out.append(f"s = {s:g}: σ_VM,max/p0 {', '.join(fmt(v / p0) for v in vm)}, z/a0 "
                   f"{', '.join(fmt(x / a0) for x in z)}")
        series[f"s/a0 = {s / a0:.0f}"] = (g["value"].to_numpy(), vm / p0)
    verdict = FAILS if falls else UNDECIDED if within else HOLDS
    why = {FAILS: "σ_VM,max falls or deepens with β at " + ", ".join(falls),
           UNDECIDED: "the smallest increase is within the uncertainty at " + ", ".join(within),
           HOLDS: "at every output s the maximum grows with β beyond its uncertainty and "
                  "does not deepen"}[verdict]
    panel = Panel("σ_VM,max at fixed s", "β [°]", "σ_VM,max / p0", series, markers=True)
    return Finding("ic (β = 0, 45, 90°): " + "; ".join(out), "σ_VM ± its uncertainty, "
                   "depth ± half a step", verdict, why, (panel,))


def oblique_traction(art: Article) -> Finding:
    """Claim 9: at β = 45° the tangential traction is not parallel to the slip, and the
    yz-plane stresses lose their symmetry. The traction's angle to the slip is exact from
    the associated rule (Eq. 13): tan(φ + θ) = (μ2/μ1)² tan θ in the tribological axes."""
    case = art.case("pin_ortho")
    params = {p: float(p.partition("=")[2]) for p in case.manifest.get("params", [])}
    p45 = next((p for p, b in params.items() if b == 45.0), None)
    p0_ = next((p for p, b in params.items() if b == 0.0), None)
    if p45 is None or p0_ is None or "ic" not in art.solvers("pin_ortho"):
        return undecided("needs the ic fields of the orthotropic pin at β = 0 and 45°")
    point = case.point(p45)
    mu1, mu2 = float(point["friction"]["mu1"]), float(point["friction"]["mu2"])
    theta = math.radians(_theta(point))
    exact = math.degrees(math.atan2(mu2**2 * math.sin(theta), mu1**2 * math.cos(theta))
                         - theta)
    a0, p0 = art.scale("pin_ortho", p45)
    asym, phi, series = {}, math.nan, {}
    for p in (p0_, p45):
        steps = case.steps("ic", p)
        st = steps[max(steps)]
        yz = st.planes.get("yz")
        vm = yz.fields["vm"]
        asym[p] = float(np.max(np.abs(vm - vm[::-1])) / np.max(vm))
        k = int(np.argmax(vm.max(axis=0)))
        series[f"σ_VM/p0 on yz at its max's depth, {p}"] = (yz.s / a0, vm[:, k] / p0)
        if p == p45:
            sf = st.surface
            slip = np.hypot(sf["slip_x"], sf["slip_y"])
            sel = (sf["state"] == 2) & (sf["p_n"] > 0) & (slip > 0)
            ang = np.degrees(np.arctan2(sf["p_y"][sel], sf["p_x"][sel])
                             - np.arctan2(-sf["slip_y"][sel], -sf["slip_x"][sel]))
            ang = (ang + 180.0) % 360.0 - 180.0
            phi = float(np.average(ang, weights=sf["p_n"][sel])) if sel.any() else math.nan
    ok = math.isfinite(phi) and abs(abs(phi) - abs(exact)) <= 1.0 and \
        asym[p45] > 100 * max(asym[p0_], 1e-12) and asym[p45] > 0.01
    measured = (f"ic at β = 45°: traction at {phi:.2f}° to the slip (associated rule: "
                f"{exact:.2f}°); yz σ_VM asymmetry max|f(y) − f(−y)|/max f = "
                f"{asym[p45]:.3g} at β = 45° against {asym[p0_]:.2g} at β = 0")
    return Finding(measured, "the β = 0 asymmetry is the numerical floor; the angle within "
                   "1° of the rule's", HOLDS if ok else FAILS,
                   "the traction turns by the rule's angle and the yz plane is asymmetric "
                   "far above the symmetric case's floor" if ok else
                   "the angle or the asymmetry is not what the claim says",
                   (Panel("yz plane at the depth of the maximum", "y / a0", "σ_VM / p0",
                          series),), {"angle": phi, "angle_exact": exact})
