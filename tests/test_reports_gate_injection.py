"""The gate's self-test by injection, driven by the registry: for every row kind the
comparisons can write (each (quantity, metric) of
:data:`reports.registry.tolerances.QUANTITY_METRICS`), a correct result — the closed form
of a case that gates that row — is perturbed so that the row's metric reads exactly ``k``
times its tolerance, and the verdict must follow: at k = 1.03 and 1.5 the row fails, at
k = 0.5 and 0.97 it passes (the flip sits at the tolerance, so a pass rule with a grace
of a few per cent fails here too), and at every k no other row fails.  Each tolerance
source is covered: the pair's default (the sum of the two solvers' error budgets), a key
of the case file, a pair-specific key of the case file, and a key of its ``[quick]``
table over a looser plain key, and, for the metrics a grid study can set, the combined
uncertainty of a run's grid study (each set to half the default, so that a lookup that
ignored it would pass); and each pair kind of a built-in reference: a closed form,
another solver, an exact metamorphic relation.  Each not-converged rule (a quantity the
case declares, a grid or jump study that does not settle it, a zone under its resolution
floor) shows the row it applies to and gates its companions; the bands' maxima (``kink``,
``edge``, ``surface``) are never gated against a solver.

The perturbations are calibrated from the documented definitions
(``reports/registry/tolerances.py``), not from the comparison code: a field scaled by
1 + ε has a relative L2 error ε; a dip of ε times the reference's peak at one interior
point has a relative max error ε; a scalar scaled by 1 + ε has a relative error ε; a
length moved by ε cells is ε cells off; a loop moved by ε μP at every point is ε off.  A
quantity added to the registry without an injection here fails
:func:`test_every_row_kind_is_injected`.

Some injections necessarily move another row too (a σ_VM plane scaled moves its
maximum, whose tolerance is tighter than the plane's): ``ALSO`` lists them with the
reason; only those may fail beside the injected row.  The location of the σ_VM maximum is
injected where it is a one-parameter change, in a solver's scalars (:func:`move_maximum`);
its defects on the planes are in ``tests/test_reports_gate_selftest.py`` (the maximum moved by a
contact radius, by four cells).
"""

from __future__ import annotations

import copy
import dataclasses
import math
from collections.abc import Callable

import numpy as np
import pandas as pd
import pytest
from test_reports_gate_selftest import (
    FRETTING_CASE,
    FRETTING_TEXT,
    SLIDING_CASE,
    SLIDING_TEXT,
    SLIP_CASE,
    SLIP_TEXT,
    reference,
)

from cases.loader import load_case
from cases.model import Case
from cases.result import RunResult, StepResult
from reports.compare.point import point_rows
from reports.compare.verdict import Uncertainty, decide
from reports.registry import solvers
from reports.registry.tolerances import (
    EXCESS,
    LAW,
    NOT_GATED,
    OWN_ALLOWANCE,
    OWN_RELATIONS,
    PEAK,
    QUANTITY_METRICS,
    tolerance_key,
)
from reports.store.study_tables import CONVERGED, UNSETTLED
from reports.studies import gridstudy, uncertainty
from reports.studies.jumpstudy import JUMP_STUDY
from reports.studies.study import Own, StudyTable

#: every row kind the registry can write
ROW_KINDS = sorted((q, m) for q, ms in QUANTITY_METRICS.items() for m in ms)

Inject = Callable[[Case, RunResult, float, str], None]  # case, result, ε, pair


def _last(result: RunResult) -> StepResult:
    return result.steps[-1]


def _centre(step: StepResult) -> tuple[int, int]:
    return int(np.argmin(np.abs(step.x))), int(np.argmin(np.abs(step.y)))


def scale_field(name: str) -> Inject:
    """``name`` times 1 + ε: relative L2 error ε (the reference normalises itself)."""
    def apply(case: Case, result: RunResult, eps: float, pair: str) -> None:
        st = _last(result)
        st.surface[name] = st.surface[name] * (1.0 + eps)
    return apply


def cross_traction(case: Case, result: RunResult, eps: float, pair: str) -> None:
    """p_y += ε p_x where p_y is zero: relative L2 error ε of p_y against |p_t| = |p_x|."""
    st = _last(result)
    assert not np.any(st.surface["p_y"])
    st.surface["p_y"] = st.surface["p_y"] + eps * st.surface["p_x"]


def dip_field(name: str, at: str = "centre") -> Inject:
    """One sample of ``name`` lowered by ε × the peak of the reference's norm field (|p_t|
    for a traction component): relative max error ε.  At the centre (inside the contact
    and the stick zone, off every band), or, for p_y, at the peak of |p_x|."""
    def apply(case: Case, result: RunResult, eps: float, pair: str) -> None:
        st = _last(result)
        s = st.surface
        norm = np.hypot(s["p_x"], s["p_y"]) if name in ("p_x", "p_y") else np.abs(s[name])
        i, j = _centre(st)
        field = s[name].copy()
        field[i, j] -= eps * float(norm.max())
        s[name] = field
    return apply


def scale_plane(name: str) -> Inject:
    """σ_VM on one plane times 1 + ε: relative L2 error ε."""
    def apply(case: Case, result: RunResult, eps: float, pair: str) -> None:
        plane = _last(result).planes[name]
        plane.fields["vm"] = plane.fields["vm"] * (1.0 + eps)
    return apply


def dip_plane(name: str) -> Inject:
    """σ_VM lowered by ε × its peak at one point of the plane under the centre, 0.9 a
    deep (inside the contact's neighbourhood, off the edge and stick bands, away from the
    maximum): relative max error ε."""
    def apply(case: Case, result: RunResult, eps: float, pair: str) -> None:
        st = _last(result)
        plane = st.planes[name]
        vm = plane.fields["vm"].copy()
        i = int(np.argmin(np.abs(plane.s)))
        k = int(np.argmin(np.abs(plane.z - 0.9 * st.scalars["a_x"])))
        vm[i, k] -= eps * float(vm.max())
        plane.fields["vm"] = vm
    return apply


def raise_maximum(z_from: Callable[[Case, StepResult], float] | None = None) -> Inject:
    """The σ_VM maximum over both planes (at depths ≥ ``z_from``) times 1 + ε, at its own
    point(s): the maximum's relative error ε, its location unchanged."""
    def apply(case: Case, result: RunResult, eps: float, pair: str) -> None:
        st = _last(result)
        depth = -math.inf if z_from is None else z_from(case, st)
        top = max(float(p.fields["vm"][:, p.z >= depth].max()) for p in st.planes.values())
        for p in st.planes.values():
            vm = p.fields["vm"].copy()
            at = (vm == top) & (p.z >= depth)[None, :]
            vm[at] *= 1.0 + eps
            p.fields["vm"] = vm
    return apply


def move_maximum(metric: str) -> Inject:
    """The σ_VM maximum's location moved along x by ε cells (``cells``) or ε a0 (``a0``),
    as a solver that reports its maximum as scalars (``vm_max_x``, ``vm_max_y``,
    ``vm_max_z``) without σ_VM planes writes it: the pair has no common planes, so the
    location is compared from the scalars (tolerances module doc).  The location on the
    planes, judged by the near-maximum set, has no one-parameter injection (moving a
    maximum moves its set); its defects are in ``tests/test_reports_gate_selftest.py``."""
    def apply(case: Case, result: RunResult, eps: float, pair: str) -> None:
        st = _last(result)
        st.planes = {}
        unit = _cell(case, pair, "x") if metric == "cells" else case.hertz_scales[0]
        st.scalars["vm_max_x"] += eps * unit
    return apply


def below_depth(case: Case, st: StepResult) -> float:
    """The depth of the companion of a near-surface maximum (tolerances module doc: a
    quarter of the contact radius, two cells at least)."""
    hz = float(np.diff(st.planes["xz"].z).max())
    cells = (float(np.diff(st.x).max()), float(np.diff(st.y).max()), hz)
    return max(0.25 * st.scalars["a_x"], 2.0 * max(cells))


def scale_scalar(name: str) -> Inject:
    def apply(case: Case, result: RunResult, eps: float, pair: str) -> None:
        _last(result).scalars[name] *= 1.0 + eps
    return apply


def _cell(case: Case, pair: str, axis: str) -> float:
    """The unit of ``cells``: the coarser of the sample spacing and each solver's own
    cell (tolerances module doc)."""
    g = case.grid
    h = {"x": g.dx, "y": g.dy, "xy": max(g.dx, g.dy)}[axis]
    return max([h] + [solvers.record(s).cell_size(case) for s in pair.split("-")])


def move_length(name: str, axis: str) -> Inject:
    """A semi-width ε cells longer."""
    def apply(case: Case, result: RunResult, eps: float, pair: str) -> None:
        _last(result).scalars[name] += eps * _cell(case, pair, axis)
    return apply


def grow_area(name: str) -> Inject:
    """An area whose equivalent radius √(A/π) is ε cells longer."""
    def apply(case: Case, result: RunResult, eps: float, pair: str) -> None:
        sc = _last(result).scalars
        r = math.sqrt(sc[name] / math.pi) + eps * _cell(case, pair, "xy")
        sc[name] = math.pi * r * r
    return apply


def move_loop(case: Case, result: RunResult, eps: float, pair: str) -> None:
    """The loop's Qx moved by ε μP at every point, μP computed here from the case: μ of
    the isotropic friction and Hertz's load 2π a0² p0 / 3."""
    a0, p0 = case.hertz_scales
    mu_P = case.friction.mu1 * 2.0 * math.pi * a0 * a0 * p0 / 3.0
    loops = result.tables["loops"]
    loops["Qx"] = np.asarray(loops["Qx"], float) + eps * mu_P


def scale_tractions(case: Case, result: RunResult, eps: float, pair: str) -> None:
    """p_x and p_y times 1 + ε in full sliding, where ‖p_t‖_μ = p_n at every contact
    point: the friction law's excess reads ε at the peak pressure."""
    s = _last(result).surface
    for name in ("p_x", "p_y"):
        s[name] = s[name] * (1.0 + eps)


def scale_pressure(case: Case, result: RunResult, eps: float, pair: str) -> None:
    """p_n times 1 + ε and its peak ``p_max`` not, the closed form sampled at its
    centre (the slip case's odd grid): the peak's excess reads ε."""
    s = _last(result).surface
    s["p_n"] = s["p_n"] * (1.0 + eps)


def scale_energy(case: Case, result: RunResult, eps: float, pair: str) -> None:
    cycles = result.tables["cycles"]
    cycles["energy"] = np.asarray(cycles["energy"], float) * (1.0 + eps)


#: row kind -> (the case whose closed form gates it, the injection)
INJECT: dict[tuple[str, str], tuple[Case, Inject]] = {
    ("p_n", "l2"): (SLIP_CASE, scale_field("p_n")),
    ("p_n", "max"): (SLIP_CASE, dip_field("p_n")),
    ("p_x", "l2"): (SLIP_CASE, scale_field("p_x")),
    ("p_x", "max"): (SLIP_CASE, dip_field("p_x")),
    ("p_y", "l2"): (SLIP_CASE, cross_traction),
    ("wear_a", "l2"): (FRETTING_CASE, scale_field("wear_a")),
    ("wear_a", "max"): (FRETTING_CASE, dip_field("wear_a")),
    ("wear_b", "l2"): (FRETTING_CASE, scale_field("wear_b")),
    ("wear_b", "max"): (FRETTING_CASE, dip_field("wear_b")),
    ("vm_xz", "l2"): (SLIP_CASE, scale_plane("xz")),
    ("vm_xz", "max"): (SLIP_CASE, dip_plane("xz")),
    ("vm_yz", "l2"): (SLIP_CASE, scale_plane("yz")),
    ("vm_yz", "max"): (SLIP_CASE, dip_plane("yz")),
    ("P", "rel"): (FRETTING_CASE, scale_scalar("P")),
    ("p_max", "rel"): (SLIP_CASE, scale_scalar("p_max")),
    ("w_max", "rel"): (FRETTING_CASE, scale_scalar("w_max")),
    ("wear_volume", "rel"): (FRETTING_CASE, scale_scalar("wear_volume")),
    ("vm_max", "rel"): (SLIP_CASE, raise_maximum()),
    ("vm_max_below", "rel"): (SLIDING_CASE, raise_maximum(below_depth)),
    ("vm_max_loc", "cells"): (SLIP_CASE, move_maximum("cells")),
    ("vm_max_loc", "a0"): (SLIP_CASE, move_maximum("a0")),
    ("a_x", "cells"): (SLIP_CASE, move_length("a_x", "x")),
    ("a_y", "cells"): (SLIP_CASE, move_length("a_y", "y")),
    ("contact_area", "cells"): (SLIP_CASE, grow_area("contact_area")),
    ("stick_area", "cells"): (SLIP_CASE, grow_area("stick_area")),
    ("loop_q", "max"): (FRETTING_CASE, move_loop),
    ("q_ends", "max"): (FRETTING_CASE, move_loop),
    ("energy", "rel"): (FRETTING_CASE, scale_energy),
    (LAW, EXCESS): (SLIDING_CASE, scale_tractions),
    (PEAK, EXCESS): (SLIP_CASE, scale_pressure),
}
#: p_y's max: p_y is zero in every closed form here, so its dip is the same injection as
#: p_x's at the peak of |p_t|, written into p_y
INJECT[("p_y", "max")] = (SLIP_CASE, dip_field("p_y"))

#: rows an injection necessarily moves besides its own, and why
ALSO: dict[tuple[str, str], set[tuple[str, str]]] = {
    # a field scaled by 1 + ε: its max error is ε as well
    **{(q, "l2"): {(q, "max")} for q in ("wear_a", "wear_b")},
    # the pressure scaled: its max too, and it exceeds the peak the solver reports
    ("p_n", "l2"): {("p_n", "max"), (PEAK, EXCESS)},
    ("p_y", "l2"): {("p_y", "max"), (LAW, EXCESS)},
    # a traction raised in a slip zone leaves the friction ellipse there
    ("p_x", "l2"): {("p_x", "max"), (LAW, EXCESS)},
    # a plane scaled: its max error, and the maximum it holds
    **{(q, "l2"): {(q, "max"), ("vm_max", "rel"), ("vm_max_below", "rel")}
       for q in ("vm_xz", "vm_yz")},
    # one distance in two units: the row with the tighter tolerance fails first
    ("vm_max_loc", "cells"): {("vm_max_loc", "a0")},
    ("vm_max_loc", "a0"): {("vm_max_loc", "cells")},
    # the loop moved at every point: its extremes too, and the other way round
    ("loop_q", "max"): {("q_ends", "max")},
    ("q_ends", "max"): {("loop_q", "max")},
}

#: what an exact metamorphic relation adds: it gates every row at one allowance, the
#: stick and edge bands included (registry.solvers.exact_pair), so the rows an injection
#: moves by the same ε — the band's own row, the plane holding the maximum — fail with it
RELATION_ALSO: dict[tuple[str, str], set[tuple[str, str]]] = {
    ("p_x", "l2"): {("p_x", "kink")},
    ("p_y", "l2"): {("p_y", "kink")},
    ("vm_max", "rel"): {("vm_max", "edge"), ("vm_xz", "max"), ("vm_yz", "max")},
    # the tractions scaled: their own rows (the law's tolerance is above the allowance)
    (LAW, EXCESS): {("p_x", "l2"), ("p_x", "max"), ("p_x", "kink")},
    # the pressure scaled: its own rows
    (PEAK, EXCESS): {("p_n", "l2"), ("p_n", "max")},
    ("vm_max_below", "rel"): {("vm_xz", "max"), ("vm_yz", "max")},
    **{(q, "l2"): {("vm_max", "edge")} for q in ("vm_xz", "vm_yz")},
}

#: the pair under test, by kind of reference: the closed form's result is also relabelled
#: as another solver's and as the half-space solver's exact mirror relation's
PAIR_KINDS = {"closed form": "ic-analytic", "other solver": "ic-fem",
              "metamorphic relation": "ic-ic+mirror"}
SOURCES = ("default", "case key", "pair key", "quick key", "uncertainty")
#: the case files of the cases above (the quick key is read by the loader)
TEXTS = {id(SLIP_CASE): SLIP_TEXT, id(SLIDING_CASE): SLIDING_TEXT,
         id(FRETTING_CASE): FRETTING_TEXT}


def test_every_row_kind_is_injected():
    """The registry's row kinds are exactly those injected here: a quantity added later
    without an injection fails."""
    assert sorted(INJECT) == ROW_KINDS


def _expected_tolerance(case: Case, pair: str, quantity: str, metric: str) -> float:
    """The pair's default (tolerances module doc): the sum of the two solvers' budgets
    and their terms for the kind of case; for a metamorphic relation B of A, B's
    allowance alone; the exact relations' allowance for every pair (the friction law, the
    peak pressure)."""
    if quantity in OWN_RELATIONS:
        return OWN_ALLOWANCE
    a, _, b = pair.partition("-")
    both = [b] if solvers.record(b).base == a else [a, b]
    return sum(solvers.record(s).budget(quantity, metric)
               + solvers.record(s).case_term(case, quantity, metric) for s in both)


def _with_tolerance(case: Case, source: str, pair: str, key: str, tol: float,
                    tmp_path) -> Case:
    """``case`` whose tolerance for ``key`` is ``tol`` by ``source``: a key of the case,
    a pair-specific key, or a ``[quick]`` key over a looser plain one, read by the
    loader with ``quick=True``."""
    if source == "case key":
        return case.with_changes(tolerances={key: tol})
    if source == "pair key":
        return case.with_changes(tolerances={f"{pair}.{key}": tol})
    path = tmp_path / "selftest.toml"
    path.write_text(TEXTS[id(case)] + f'[tolerances]\n{key} = {2 * tol!r}\n'
                    f'[quick]\n"tolerances.{key}" = {tol!r}\n')
    return load_case(path, quick=True)[0]


def _study(case: Case, pair: str, kind: tuple[str, str], u_pair: float, step: int,
           status: str = CONVERGED, f: tuple[float, float, float] = (1.0, 1.0, 1.0),
           ) -> pd.DataFrame:
    """A grid-study table as ``run --convergence`` writes it, with one row: the tested
    solver's study of ``kind``'s quantity.  ``converged``, its GCI chosen so that the
    pair's combined uncertainty (Eq. U1, computed here from the documented terms: a
    closed form's budget and case term, each solver's model-form term) is ``u_pair``."""
    tested, _, ref = pair.partition("-")
    quantity, metric = kind
    r_ref, r_tested = solvers.record(ref), solvers.record(tested)
    others = [r_ref.budget(quantity, metric) + r_ref.case_term(case, quantity, metric),
              r_ref.model_form(quantity, metric), r_tested.model_form(quantity, metric)]
    gci = math.sqrt(u_pair**2 - sum(t * t for t in others))
    h = (0.01, 0.015, 0.0225)
    row = {"solver": tested, "param": case.param, "step": step, "quantity": quantity,
           "h1": h[0], "h2": h[1], "h3": h[2], "cell_size": h[0], "f1": f[0], "f2": f[1],
           "f3": f[2], "order": 2.0, "f_extrapolated": f[0], "gci_fine": gci,
           "status": status, "gci_coarse": gci, "asymptotic": 1.0, "note": ""}
    return pd.DataFrame([row])


def _step(result: RunResult) -> int:
    return _last(result).number(len(result.steps) - 1)


def _rows(case: Case, pair: str, tested: RunResult, good: RunResult,
          study: pd.DataFrame | None = None, rule: str = "") -> dict:
    """The tested pair's rows of one point, with the verdict of a run whose grid study
    (``rule`` "grid"; or its jump study, "jump"; or, by default, the combined uncertainty
    it gives) is ``study``."""
    a, _, b = pair.partition("-")
    rows = point_rows(case, {a: tested, b: good})
    if study is None:
        metrics = decide(rows)
    elif rule == "grid":
        metrics = decide(rows, [gridstudy.flags(rows, study)])
    elif rule == "jump":
        metrics = decide(rows, JUMP_STUDY.evidence(rows, StudyTable(study), Own([case], [],
                                                                               lambda c: [])))
    else:
        metrics = decide(rows, [Uncertainty(uncertainty.values(rows, study,
                                                               {case.param: case}))])
    metrics = metrics[metrics["pair"] == pair]
    return {(q, m): (float(v), float(t), s, bool(p), str(n)) for q, m, v, t, s, p, n in zip(
        metrics["quantity"], metrics["metric"], metrics["value"], metrics["tolerance"],
        metrics["status"], metrics["passed"], metrics["note"], strict=True)}


INJECTED = [k for k in ROW_KINDS if k in INJECT]
#: metrics a never-gated row carries: the stick and edge bands' maxima, a surface maximum
SHOWN_METRICS = ("kink", "edge", "surface")


#: every tolerance source against the closed form (the uncertainty of grid studies only
#: for the metrics a study can set); every pair kind under its default
PLANS = ([(k, "closed form", s) for k in INJECTED for s in SOURCES
          if s != "uncertainty" or k[1] in uncertainty.STUDIED_METRICS]
         + [(k, p, "default") for k in INJECTED for p in sorted(PAIR_KINDS)
            if p != "closed form"])


@pytest.mark.parametrize(("kind", "pair_kind", "source"), PLANS,
                         ids=[f"{q}.{m}-{p}, {s}" for (q, m), p, s in PLANS])
def test_the_verdict_flips_at_the_tolerance(kind, pair_kind, source, tmp_path):
    pair = PAIR_KINDS[pair_kind]
    quantity, metric = kind
    case, inject = INJECT[kind]
    good = reference(case)
    tol = _expected_tolerance(case, pair, quantity, metric)
    study = None
    if source == "uncertainty":
        tol *= 0.5
        study = _study(case, pair, kind, tol, _step(good))
    elif source != "default":
        tol *= 0.5
        case = _with_tolerance(case, source, pair, tolerance_key(quantity, metric), tol,
                               tmp_path)
    for k in (0.5, 0.97, 1.03, 1.5):
        tested = copy.deepcopy(good)
        inject(case, tested, k * tol, pair)
        rows = _rows(case, pair, tested, good, study)
        assert kind in rows, f"{kind}: no row for {pair}"
        value, row_tol, status, passed, _ = rows[kind]
        assert status == "gated", f"{kind}: {status}"
        assert row_tol == pytest.approx(tol, rel=1e-9), f"{kind}: tolerance {row_tol}"
        assert value == pytest.approx(k * tol, rel=1e-6), f"{kind}: value {value} at k = {k}"
        assert passed == (k < 1), f"{kind} at k = {k}: passed = {passed}"
        failed = {key for key, (_, _, st, ok, _) in rows.items() if st == "gated" and not ok}
        moved = ALSO.get(kind, set()) | (RELATION_ALSO.get(kind, set())
                                          if pair_kind == "metamorphic relation" else set())
        others = failed - {kind} - moved
        assert others == set(), f"{kind} at k = {k} also fails {sorted(others)}"
        if pair_kind != "metamorphic relation":  # an exact relation gates the bands too
            shown = {key: st for key, (_, _, st, _, _) in rows.items()
                     if key[1] in SHOWN_METRICS}
            assert set(shown.values()) <= {NOT_GATED}, f"a band's max gated: {shown}"


#: a partial slip whose slip zone (Q = 0.1 μP: a − c = 0.035 a, under half a cell) is
#: narrower than the tractions' resolution floor (reports.registry.resolution)
NARROW_SLIP_CASE = SLIP_CASE.with_changes(
    load=dataclasses.replace(SLIP_CASE.load, Qx=0.1 * 0.3 * SLIP_CASE.load.P))

#: Spence's compression of a rigid-on-soft pair (β = −0.375) at μ = 0.05: a stick disc
#: under a cell, so the pressure's peak is under its floor (issue 73)
COUPLED_CASE = SLIP_CASE.with_changes(
    b=dataclasses.replace(SLIP_CASE.b, E=2100.0, nu=0.2),
    friction=dataclasses.replace(SLIP_CASE.friction, mu1=0.05, mu2=0.05),
    load=dataclasses.replace(SLIP_CASE.load, Qx=None),
    grid=dataclasses.replace(SLIP_CASE.grid, Lx=2.4, Ly=2.4, nx=41, ny=41))

#: not-converged rule -> (the case, the row it exempts, words of its note, the
#: companions that stay gated)
RULES = {
    "declared": (SLIP_CASE, ("p_max", "rel"), "declared: measured elsewhere",
                 {("p_n", "l2"), ("a_x", "cells")}),
    "grid": (SLIP_CASE, ("p_max", "rel"), "grid study: ic unsettled",
             {("p_n", "max"), ("a_x", "cells")}),
    "jump": (FRETTING_CASE, ("wear_volume", "rel"), "jump study: ic unsettled",
             {("p_n", "l2"), ("loop_q", "max")}),
    "resolution": (NARROW_SLIP_CASE, ("p_x", "l2"), "slip zone",
                   {("stick_area", "cells"), ("p_n", "l2"), ("a_x", "cells")}),
    "stick disc": (COUPLED_CASE, ("p_max", "rel"), "stick radius",
                   {("p_n", "l2"), ("P", "rel"), ("contact_area", "cells"),
                    ("stick_area", "cells")}),
}


@pytest.mark.parametrize("rule", sorted(RULES))
def test_each_not_converged_rule_shows_its_row_and_gates_the_companions(rule):
    """A row a not-converged rule applies to is shown, not gated, with the rule's reason:
    injected at 1.5 times its tolerance it fails nothing — while the same injection
    without the rule fails it — and its companions stay gated."""
    case, kind, words, companions = RULES[rule]
    pair = "ic-analytic"
    good = reference(case)
    tol = _expected_tolerance(case, pair, *kind)
    tested = copy.deepcopy(good)
    INJECT[kind][1](case, tested, 1.5 * tol, pair)
    study = None
    if rule == "declared":
        ruled = case.with_changes(not_converged={kind[0]: "measured elsewhere"})
    else:
        ruled = case
    if rule in ("grid", "jump"):  # three values 20 % apart: beyond every budget
        study = _study(case, pair, kind, tol, _step(good), status=UNSETTLED,
                       f=(1.0, 1.2, 1.4))
    rows = _rows(ruled, pair, tested, good, study, rule)
    value, _, status, _, note = rows[kind]
    assert value == pytest.approx(1.5 * tol, rel=1e-6)
    assert status == NOT_GATED and words in note, (status, note)
    failed = {key for key, (_, _, st, ok, _) in rows.items() if st == "gated" and not ok}
    # the friction law is exact at any resolution: the traction scaled in the narrow
    # slip zone leaves the ellipse, and it fails there, where the field's norm cannot
    law = {(LAW, EXCESS)} if rule == "resolution" else set()
    assert failed == law, f"{rule}: fails {sorted(failed)}"
    assert all(rows[c][2] == "gated" for c in companions), {c: rows[c][2] for c in companions}
    if rule not in ("resolution", "stick disc"):  # without the rule it fails the row
        assert not _rows(case, pair, tested, good)[kind][3]


def test_a_traction_the_reference_lacks_is_measured_on_mu_p0():
    """Issue 73, point 2: against a reference without tangential traction (Hertz with
    friction and no tangential load, μ = 0.04), a uniform traction ε μ p0 over the contact
    reads ε in both norms, and the verdict flips at the tolerance: at μ = 0.04 a traction
    as large as friction allows fails, where on p0 it read 0.04."""
    case = SLIP_CASE.with_changes(
        friction=dataclasses.replace(SLIP_CASE.friction, mu1=0.04, mu2=0.04),
        load=dataclasses.replace(SLIP_CASE.load, Qx=None))
    good = reference(case)
    assert not np.any(_last(good).surface["p_x"])
    _, p0 = case.hertz_scales
    pair = "ic-analytic"
    for metric in ("l2", "max"):
        tol = _expected_tolerance(case, pair, "p_x", metric)
        for k in (0.97, 1.03):
            tested = copy.deepcopy(good)
            s = _last(tested).surface
            s["p_x"] = np.where(s["p_n"] > 0, k * tol * 0.04 * p0, 0.0)
            value, _, status, ok, _ = _rows(case, pair, tested, good)[("p_x", metric)]
            assert value == pytest.approx(k * tol, rel=1e-9) and status == "gated"
            assert ok == (k < 1), (metric, k, value, tol)
