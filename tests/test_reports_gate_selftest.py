"""The gate's self-test: results made wrong on purpose must fail the metric that should
see them, for every metric.

The reference B is a closed form (``analytic``) on a case resolved well inside every
resolution floor; the "solver" A is a copy of it with one defect of a known size — a
field scaled, shifted or perturbed in a band, a zone grown, a scalar or a table changed —
and ``compare_point`` must fail the rows that measure that defect.  A metric that leaves
part of a field out, normalises by the wrong norm or looks at the wrong points fails
here (the seeded-defect test applies such defects to the reports code, and this test is
what catches them, ``tests/test_suite_seeded_defects.py``).
"""

from __future__ import annotations

import copy
import math
import tomllib
from collections.abc import Callable

import numpy as np
import pytest

import analytic
from cases.build import build
from cases.model import Case
from cases.result import SLIP, STICK, RunResult, StepResult
from reports.compare.cycles import friction_scale
from reports.compare.point import compare_point


def _case(text: str) -> Case:
    return build(tomllib.loads(text), name="selftest", source="<selftest>", param="")


BODIES = ("[materials.a]\nE = 210000.0\nnu = 0.3\ni1 = 1e-9\n"
          "[materials.b]\nE = 210000.0\nnu = 0.3\ni1 = 1e-9\n[geometry]\nR = 50.0\n")
#: partial slip, a/h = 12.5: tractions, stick zone, planes
SLIP_TEXT = ('kind = "static"\n' + BODIES + "[grid]\nLx = 0.45\nnx = 61\n"
             "[friction]\nmu = 0.3\n[load]\nP = 10.2\nQx = 1.53\n"
             "[stress]\ndepth = 0.3\nnz = 31\n")
SLIP_CASE = _case(SLIP_TEXT)
#: full sliding at mu = 0.5: a surface maximum, its companion below
SLIDING_TEXT = ('kind = "static"\n' + BODIES + "[grid]\nLx = 0.45\nnx = 61\n"
                "[friction]\nmu = 0.5\n[load]\nP = 10.2\nsliding = true\n"
                "[stress]\ndepth = 0.3\nnz = 31\n")
SLIDING_CASE = _case(SLIDING_TEXT)
#: the first fretting cycle in gross slip, a/h = 12: wear, loop, energy
FRETTING_TEXT = ('kind = "fretting"\n' + BODIES + "[grid]\nLx = 1.6\nnx = 61\n"
                 "[friction]\nmu = 0.3\n[load]\napproach = 0.008\n"
                 "[fretting]\namplitude = 0.0043714\nsteps_per_cycle = 8\ncycles = 1\n"
                 "output_cycles = [1]\n[solver]\ntol = 1e-8\n"
                 "[stress]\ndepth = 0.8\nnz = 21\n")
FRETTING_CASE = _case(FRETTING_TEXT)

Perturb = Callable[[Case, RunResult], None]


def _last(result: RunResult) -> StepResult:
    return result.steps[-1]


def _radius(case: Case, step: StepResult) -> np.ndarray:
    X, Y = np.meshgrid(step.x, step.y, indexing="ij")
    return np.hypot(X, Y)


def scale_field(name: str, factor: float) -> Perturb:
    def apply(case: Case, result: RunResult) -> None:
        st = _last(result)
        st.surface[name] = st.surface[name] * factor
    return apply


def ring(name: str, lo: float, hi: float, amount: float, of: str | None = None) -> Perturb:
    """Add ``amount`` × the peak of field ``of`` (default ``name``) on lo·a < r < hi·a (off
    every band)."""
    def apply(case: Case, result: RunResult) -> None:
        st = _last(result)
        a = st.scalars["a_x"]
        r = _radius(case, st)
        band = (r > lo * a) & (r < hi * a)
        peak = np.nanmax(np.abs(st.surface[of or name]))
        st.surface[name] = np.where(band, st.surface[name] + amount * peak,
                                    st.surface[name])
    return apply


def shrink_contact(cells: float) -> Perturb:
    """The contact, its pressure and tractions cut ``cells`` cells inside its edge."""
    def apply(case: Case, result: RunResult) -> None:
        st = _last(result)
        cut = _radius(case, st) > st.scalars["a_x"] - cells * case.grid.dx
        for name in ("p_n", "p_x", "p_y"):
            st.surface[name] = np.where(cut, 0.0, st.surface[name])
        a = st.scalars["a_x"] - cells * case.grid.dx
        st.scalars.update(a_x=a, a_y=a, contact_area=math.pi * a * a)
    return apply


def grow_stick(cells: float) -> Perturb:
    """The stick zone grown by ``cells`` cells (state and area)."""
    def apply(case: Case, result: RunResult) -> None:
        st = _last(result)
        c = math.sqrt(st.scalars["stick_area"] / math.pi) + cells * case.grid.dx
        r = _radius(case, st)
        state = st.surface["state"].copy()
        state[(state == SLIP) & (r < c)] = STICK
        st.surface["state"] = state
        st.scalars["stick_area"] = math.pi * c * c
    return apply


def scale_planes(factor: float, z_from: float = 0.0) -> Perturb:
    """σ_VM on both planes times ``factor`` at depths z >= ``z_from`` (in a0)."""
    def apply(case: Case, result: RunResult) -> None:
        st = _last(result)
        deep = None
        for plane in st.planes.values():
            deep = plane.z >= z_from * case.hertz_scales[0]
            plane.fields["vm"] = np.where(deep[None, :], plane.fields["vm"] * factor,
                                          plane.fields["vm"])
    return apply


def moved_maximum(case: Case, result: RunResult) -> None:
    """A second σ_VM peak, 10 % above the maximum, a contact radius off the first."""
    st = _last(result)
    a0 = case.hertz_scales[0]
    plane = st.planes["xz"]
    S, Z = np.meshgrid(plane.s, plane.z, indexing="ij")
    vm = plane.fields["vm"]
    bump = np.exp(-((S - 1.2 * a0) ** 2 + (Z - 0.8 * a0) ** 2) / (0.1 * a0) ** 2)
    plane.fields["vm"] = np.maximum(vm, 1.10 * vm.max() * bump)


def nearby_maximum(case: Case, result: RunResult) -> None:
    """A second σ_VM peak, 5 % above the maximum, four cells beside it."""
    st = _last(result)
    plane = st.planes["xz"]
    vm = plane.fields["vm"]
    i, k = np.unravel_index(np.argmax(vm), vm.shape)
    S, Z = np.meshgrid(plane.s, plane.z, indexing="ij")
    s0 = plane.s[min(i + 4, plane.s.size - 1)]
    bump = np.exp(-((S - s0) ** 2 + (Z - plane.z[k]) ** 2) / (0.5 * case.grid.dx) ** 2)
    plane.fields["vm"] = np.maximum(vm, 1.05 * vm.max() * bump)


def spike(name: str, amount: float) -> Perturb:
    """One sample of field ``name``, halfway out on the x axis, raised by ``amount`` × its
    peak."""
    def apply(case: Case, result: RunResult) -> None:
        st = _last(result)
        i = int(np.argmin(np.abs(st.x - 0.5 * st.scalars["a_x"])))
        j = int(np.argmin(np.abs(st.y)))
        field = st.surface[name].copy()
        field[i, j] += amount * np.nanmax(np.abs(field))
        st.surface[name] = field
    return apply


def scale_scalar(name: str, factor: float) -> Perturb:
    def apply(case: Case, result: RunResult) -> None:
        _last(result).scalars[name] *= factor
    return apply


def scale_wear(factor: float) -> Perturb:
    """Both bodies' wear, its maximum and volume times ``factor``."""
    def apply(case: Case, result: RunResult) -> None:
        st = _last(result)
        for name in ("wear_a", "wear_b"):
            st.surface[name] = st.surface[name] * factor
        st.scalars["w_max"] *= factor
        st.scalars["wear_volume"] *= factor
    return apply


def loop_offset(fraction: float) -> Perturb:
    """The fretting loop's Q moved by ``fraction`` of μP at every point."""
    def apply(case: Case, result: RunResult) -> None:
        loops = result.tables["loops"]
        loops["Qx"] = np.asarray(loops["Qx"]) + fraction * friction_scale(case)
    return apply


def energy_scale(factor: float) -> Perturb:
    def apply(case: Case, result: RunResult) -> None:
        cycles = result.tables["cycles"]
        cycles["energy"] = np.asarray(cycles["energy"]) * factor
    return apply


#: (id, case, perturbation, the (quantity, metric) rows it must fail)
DEFECTS = [
    ("pressure scaled", SLIP_CASE, scale_field("p_n", 1.10),
     {("p_n", "l2"), ("p_n", "max")}),
    ("pressure ring", SLIP_CASE, ring("p_n", 0.2, 0.45, 0.12), {("p_n", "max")}),
    ("pressure spike", SLIP_CASE, spike("p_n", 0.12), {("p_n", "max")}),
    ("peak pressure", SLIP_CASE, scale_scalar("p_max", 1.05), {("p_max", "rel")}),
    ("contact cut", SLIP_CASE, shrink_contact(2.5),
     {("a_x", "cells"), ("a_y", "cells"), ("contact_area", "cells")}),
    ("traction scaled", SLIP_CASE, scale_field("p_x", 1.15), {("p_x", "l2"), ("p_x", "max")}),
    ("traction ring", SLIP_CASE, ring("p_x", 0.2, 0.4, 0.2), {("p_x", "max")}),
    ("cross traction", SLIP_CASE, ring("p_y", 0.1, 0.6, 0.15, of="p_x"),
     {("p_y", "l2"), ("p_y", "max")}),
    ("stick zone grown", SLIP_CASE, grow_stick(3.0), {("stick_area", "cells")}),
    ("stresses scaled", SLIP_CASE, scale_planes(1.06),
     {("vm_xz", "l2"), ("vm_yz", "l2"), ("vm_max", "rel")}),
    ("deep stresses scaled", SLIP_CASE, scale_planes(1.06, z_from=0.3),
     {("vm_xz", "l2"), ("vm_yz", "l2")}),
    ("stresses scaled more", SLIP_CASE, scale_planes(1.15), {("vm_xz", "max"), ("vm_yz", "max")}),
    ("maximum moved", SLIP_CASE, moved_maximum,
     {("vm_max", "rel"), ("vm_max_loc", "cells"), ("vm_max_loc", "a0")}),
    ("maximum moved four cells", SLIP_CASE, nearby_maximum, {("vm_max_loc", "cells")}),
    ("stresses below scaled", SLIDING_CASE, scale_planes(1.05, z_from=0.1),
     {("vm_max_below", "rel")}),
    ("wear scaled", FRETTING_CASE, scale_wear(1.12),
     {("wear_a", "l2"), ("wear_a", "max"), ("wear_b", "l2"), ("w_max", "rel"),
      ("wear_volume", "rel")}),
    ("loop offset", FRETTING_CASE, loop_offset(0.01), {("loop_q", "max")}),
    ("energy scaled", FRETTING_CASE, energy_scale(1.06), {("energy", "rel")}),
]

_REFERENCES: dict[int, RunResult] = {}


def reference(case: Case) -> RunResult:
    """The closed form of ``case`` (cached: the perturbations work on deep copies)."""
    key = id(case)
    if key not in _REFERENCES:
        _REFERENCES[key] = analytic.solve(case)
    return _REFERENCES[key]


@pytest.mark.parametrize(("name", "case", "perturb", "fails"), DEFECTS,
                         ids=[d[0] for d in DEFECTS])
def test_a_wrong_result_fails_the_metric_that_should_see_it(name, case, perturb, fails):
    good = reference(case)
    wrong = copy.deepcopy(good)
    perturb(case, wrong)
    metrics = compare_point(case, {"ic": wrong, "analytic": good})
    rows = {(q, m): (v, t, s, p) for q, m, v, t, s, p in zip(
        metrics["quantity"], metrics["metric"], metrics["value"], metrics["tolerance"],
        metrics["status"], metrics["passed"], strict=True)}
    for key in sorted(fails):
        assert key in rows, f"{name}: no {key} row"
        value, tolerance, status, passed = rows[key]
        assert status == "gated", f"{name}: {key} not gated"
        assert value > tolerance, f"{name}: {key} = {value:.4g} within {tolerance:g}"
        assert not passed, f"{name}: {key} = {value:.4g} > {tolerance:g} passed"


@pytest.mark.parametrize("case", [SLIP_CASE, SLIDING_CASE, FRETTING_CASE],
                         ids=["partial slip", "sliding", "fretting"])
def test_the_reference_against_itself_passes_and_gates_every_metric(case):
    """Without a defect every row is 0 and passes; the rows the defects above must fail
    are all present and gated (a row that vanished would pass every defect)."""
    good = reference(case)
    metrics = compare_point(case, {"ic": copy.deepcopy(good), "analytic": good})
    assert metrics["passed"].all()
    assert np.allclose(metrics["value"].to_numpy(float), 0.0)
    gated = set(zip(metrics.loc[metrics["status"] == "gated", "quantity"],
                    metrics.loc[metrics["status"] == "gated", "metric"], strict=True))
    wanted = set().union(*(d[3] for d in DEFECTS if d[1] is case))
    assert wanted - {("p_y", "l2"), ("p_y", "max")} <= gated  # p_y: zero in both here
