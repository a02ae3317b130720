"""Comparison metrics, sampling and the tolerance naming scheme."""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest
import test_cli_fakes as fakes

from analytic import mindlin
from cases.loader import load_case
from cases.model import CaseError
from cases.result import Plane, RunResult, StepResult
from reports.compare.cycles import compare_tables, friction_scale
from reports.compare.metrics import compare_steps, field_errors
from reports.compare.point import compare_point
from reports.compare.sampling import (
    common_axis,
    contact_edges,
    interior,
    sample,
    stick_band,
)
from reports.registry import tolerances as tol

README = Path(__file__).resolve().parent.parent / "cases" / "README.md"


def test_sample_is_exact_for_bilinear_fields_and_nan_outside():
    x, y = np.linspace(-1, 1, 11), np.linspace(0, 2, 5)
    f = 3 * x[:, None] - 2 * y[None, :] + 0.5 * x[:, None] * y[None, :]
    xs, ys = np.array([-0.95, 0.33, 1.2]), np.array([0.1, 1.7])
    got = sample((x, y), f, (xs, ys))
    want = 3 * xs[:, None] - 2 * ys[None, :] + 0.5 * xs[:, None] * ys[None, :]
    np.testing.assert_allclose(got[:2], want[:2], rtol=1e-13)
    assert np.isnan(got[2]).all()  # x = 1.2 lies outside the grid


def test_sample_on_a_single_line():
    z = np.linspace(0, 1, 6)
    on_axis = sample((np.array([0.0]), z), (2 * z)[None, :], (np.array([-0.1, 0.0]), z))
    assert np.isnan(on_axis[0]).all()
    np.testing.assert_allclose(on_axis[1], 2 * z)


def test_common_axis_takes_the_coarser_grid_inside_the_overlap():
    fine, coarse = np.linspace(-0.5, 0.5, 21), np.linspace(-1, 1, 11)
    np.testing.assert_allclose(common_axis(fine, coarse), [-0.4, -0.2, 0, 0.2, 0.4],
                               atol=1e-15)


def test_field_errors_definitions():
    b = np.array([1.0, 2.0, 2.0, 0.0])
    a = b + np.array([0.1, 0.0, -0.2, 5.0])
    mask = np.array([True, True, True, False])
    err = field_errors(a, b, mask, scale=1.0)
    assert err["l2"] == pytest.approx(math.sqrt(0.05) / 3.0, rel=1e-14)  # ‖(.1,0,-.2)‖/‖(1,2,2)‖
    assert err["max"] == pytest.approx(0.1, rel=1e-14)  # 0.2 / 2
    assert field_errors(np.zeros(3), np.zeros(3), None, 1.0) is None  # nothing to compare
    # a zero reference against a non-zero field is normalised by the scale, and fails
    err = field_errors(np.full(4, 0.5), np.zeros(4), None, scale=1.0)
    assert err == {"l2": pytest.approx(0.5), "max": pytest.approx(0.5)}


def test_traction_components_are_measured_against_the_whole_traction():
    px_b = np.array([1.0, 2.0, 2.0])
    py_b = np.array([0.001, -0.001, 0.0])
    py_a = py_b + np.array([0.002, 0.0, 0.0])
    err = field_errors(py_a, py_b, None, 1.0, ref=np.hypot(px_b, py_b))
    # |Δp_y| = 0.002 against ‖p_t‖ ≈ 3, not against ‖p_y‖ ≈ 0.0014
    assert err["l2"] == pytest.approx(0.002 / np.linalg.norm(np.hypot(px_b, py_b)), rel=1e-12)
    assert err["max"] == pytest.approx(0.002 / np.hypot(2.0, 0.001), rel=1e-12)


def test_interior_drops_the_boundary_ring_of_a_contact():
    x = np.arange(-5, 6, dtype=float)
    disc = np.hypot(x[:, None], x[None, :]) <= 3.5
    inner = interior(disc)
    # a point is interior iff its 3 x 3 neighbourhood lies in the disc
    want = np.array([[disc[max(i - 1, 0):i + 2, max(j - 1, 0):j + 2].all()
                      for j in range(11)] for i in range(11)])
    np.testing.assert_array_equal(inner, want)
    assert inner.sum() == 13 and disc.sum() == 37  # |i|, |j| <= 1, and (±2, 0), (0, ±2)
    np.testing.assert_allclose(contact_edges(x, disc[:, 5].astype(float)), [-3.5, 3.5])


def _flat_punch_step(radius: float, x: np.ndarray, vm_edge: float) -> StepResult:
    """Uniform pressure 1 on a disc, and a σ_VM plane that is 1 except ``vm_edge`` at
    the surface samples within one cell of the contact boundary (the midpoint between
    the last sample in contact, s = ±radius, and the first outside)."""
    p_n = np.where(np.hypot(x[:, None], x[None, :]) <= radius, 1.0, 0.0)
    z = np.linspace(0.0, 1.0, 6)
    vm = np.ones((x.size, z.size))
    h = x[1] - x[0]
    vm[np.abs(np.abs(x) - (radius + 0.5 * h)) < h, 0] = vm_edge
    plane = Plane(s=x, z=z, fields={"vm": vm})
    return StepResult(scalars={}, x=x, y=x, surface={"p_n": p_n},
                      planes={"xz": plane, "yz": plane})


def test_the_norms_leave_out_the_edge_band():
    """Two uniform-pressure contacts whose boundaries cut different cells (a worn,
    step-edged pressure sampled on grids half a cell apart): the norms see no difference
    off the one-cell edge band; a difference one cell farther inside, and a contact one
    solver lacks beyond the band, they do see."""
    x = np.linspace(-1.0, 1.0, 41)  # h = 0.05
    r = np.hypot(x[:, None], x[None, :])
    sa = _flat_punch_step(0.5, x, vm_edge=1.0)
    sb = _flat_punch_step(0.5, x, vm_edge=1.6)
    sa.surface["p_n"][np.abs(r - 0.5) < 0.03] = 0.6
    rows = {(q, m): v for q, m, v in compare_steps(sa, sb, a0=0.5, p0=1.0)}
    for key in [("p_n", "max"), ("p_n", "l2"), ("vm_xz", "max"), ("vm_xz", "l2")]:
        assert rows[key] == pytest.approx(0.0, abs=1e-15), key
    # a difference one cell farther inside is measured
    sb.surface["p_n"][np.abs(r - 0.4) < 0.03] = 0.7
    rows = {(q, m): v for q, m, v in compare_steps(sa, sb, a0=0.5, p0=1.0)}
    assert rows[("p_n", "max")] == pytest.approx(0.3, rel=1e-12)
    assert rows[("p_n", "l2")] > 0.05
    # a contact three cells smaller: the ring it lacks counts in L2 beyond the bands
    sc = _flat_punch_step(0.35, x, vm_edge=1.0)
    rows = {(q, m): v for q, m, v in compare_steps(sc, _flat_punch_step(0.5, x, vm_edge=1.0),
                                                    a0=0.5, p0=1.0)}
    assert rows[("p_n", "l2")] > 0.3


def test_the_planes_band_is_the_stress_reach_of_the_pair():
    """An element's outlier (a point value 1.6 cells deep below the contact edge) is left
    out of the planes' norms where the pair's stress reach covers it and measured where it
    does not; a difference just beyond the reach is still measured; the FEM's reach is
    FEM_ELEMENT_DIAMETER of its cells, a grid solver's its cell."""
    from cases.loader import load_case
    from reports.compare.point import pair_reach
    from reports.registry.discretisation import FEM_ELEMENT_DIAMETER, fem_cell
    from reports.registry.record import grid_cell

    x = np.linspace(-1.0, 1.0, 41)  # h = 0.05, the boundary's midpoint at s = ±0.525
    sa = _flat_punch_step(0.5, x, vm_edge=1.0)
    sb = _flat_punch_step(0.5, x, vm_edge=1.0)
    z = sa.planes["xz"].z  # 0.2 apart
    sb.planes["xz"].fields["vm"] = sb.planes["xz"].fields["vm"].copy()
    i = int(np.argmin(np.abs(x - 0.45)))  # 0.075 from the boundary point, z = 0.2
    sb.planes["xz"].fields["vm"][i, 1] = 1.3
    d = float(np.hypot(x[i] - 0.525, z[1]))
    for reach, left_out in ((0.0, False), (d - 0.01, False), (d + 0.01, True)):
        rows = {(q, m): v for q, m, v in compare_steps(sa, sb, a0=0.5, p0=1.0, reach=reach)}
        assert (rows[("vm_xz", "max")] == 0.0) == left_out, reach
        assert rows[("vm_xz", "max")] in (0.0, pytest.approx(0.3 / 1.3, rel=1e-12))
    case = load_case("hertz", quick=True)[0]
    assert pair_reach(case, "ic", "fem") == FEM_ELEMENT_DIAMETER * fem_cell(case)
    assert pair_reach(case, "ic", "analytic") == grid_cell(case)
    assert pair_reach(case, "fem", "analytic") == FEM_ELEMENT_DIAMETER * fem_cell(case)


def test_the_planes_stick_band_is_the_stress_reach_too():
    """A point value 0.2 deep below a stick edge, farther than one cell from it: left out
    of both plane norms (and kept in the ``kink`` row) where the pair's stress reach
    covers it, measured where it does not; the contact edge's band is far from it.  The
    false alarm that showed it: a worn fretting point whose two meshes of one element
    size differ there by 0.09 of the max norm (benchmarks/README.md, "False alarms")."""
    x = np.linspace(-1.0, 1.0, 41)  # h = 0.05
    r = np.hypot(x[:, None], x[None, :])
    sa, sb = (_flat_punch_step(0.5, x, vm_edge=1.0) for _ in range(2))
    for st in (sa, sb):  # stick within r = 0.25: the stick edge's midpoint at s = ±0.275
        st.surface["state"] = np.where(r <= 0.5, np.where(r < 0.26, 1, 2), 0)
    z = sa.planes["xz"].z  # 0.2 apart
    sb.planes["xz"] = Plane(s=x, z=z, fields={"vm": sb.planes["xz"].fields["vm"].copy()})
    i = int(np.argmin(np.abs(x - 0.2)))
    sb.planes["xz"].fields["vm"][i, 1] = 1.3
    d = float(np.hypot(0.275 - x[i], z[1]))  # 0.214: beyond one cell, within 4.3 cells
    for reach, left_out in ((0.0, False), (d - 0.01, False), (d + 0.01, True)):
        rows = {(q, m): v for q, m, v in compare_steps(sa, sb, a0=0.5, p0=1.0, cell=0.05,
                                                       reach=reach)}
        assert (rows[("vm_xz", "max")] == 0.0) == left_out, reach
        assert (rows[("vm_xz", "l2")] == 0.0) == left_out, reach
        assert rows[("vm_xz", "max")] in (0.0, pytest.approx(0.3 / 1.3, rel=1e-12))
        if left_out:
            assert rows[("vm_xz", "kink")] == pytest.approx(0.3 / 1.3, rel=1e-12)
    assert rows[("vm_yz", "max")] == 0.0  # the other plane is the same in both


def _mindlin_step(x: np.ndarray, c: float, h: float | None = None) -> StepResult:
    """Cattaneo–Mindlin surface fields (a = 1, p0 = 1, μ = 0.3, stick radius c) on the
    grid x²; with ``h``, every field is held at nodes h apart (offset from the grid) and
    interpolated bilinearly, as a solver's nodal fields are."""
    def fields(X, Y):
        r = np.hypot(X, Y)
        state = np.where(r < 1, np.where(r < c, 1, 2), 0)
        return (np.sqrt(np.clip(1 - r**2, 0, None)), mindlin.traction(r, 1.0, c, 0.3, 1.0),
                (state == 1).astype(float), (state == 2).astype(float))
    if h is None:
        p, q, stick, slip = fields(*np.meshgrid(x, x, indexing="ij"))
    else:
        nodes = np.arange(-1.4 - 0.37 * h, 1.4 + h, h)
        p, q, stick, slip = (sample((nodes, nodes), f, (x, x))
                             for f in fields(*np.meshgrid(nodes, nodes, indexing="ij")))
    state = np.where(stick > 0.5, 1, np.where(slip > 0.5, 2, 0))
    return StepResult(scalars={}, x=x, y=x, planes={},
                      surface={"p_n": p, "p_x": q, "p_y": 0 * q, "state": state})


def test_tangential_max_norms_leave_out_the_stick_band():
    """Exact Mindlin at Q/μP = 0.25 (c = 0.909 a) held at nodes a/12 apart: the
    √(c − r) kink between the nodes misses the exact traction by a quarter of it, and
    only within a cell of the stick radius.  The gated max leaves that band out, the
    ``kink`` row keeps it, the L2 norm still sees it; without the states there is no
    band."""
    x = np.linspace(-1.3, 1.3, 61)
    exact, nodal = _mindlin_step(x, 0.909), _mindlin_step(x, 0.909, h=1 / 12)
    rows = {(q, m): v for q, m, v in compare_steps(nodal, exact, a0=1.0, p0=1.0,
                                                   cell=1 / 12)}
    assert rows[("p_x", "kink")] > 0.25
    assert rows[("p_x", "max")] < 0.1  # the rest: the contact edge between nodes
    assert rows[("p_x", "l2")] > 0.1
    assert ("p_n", "kink") not in rows  # the pressure has no stick band
    for st in (exact, nodal):
        del st.surface["state"]
    rows = {(q, m): v for q, m, v in compare_steps(nodal, exact, a0=1.0, p0=1.0,
                                                   cell=1 / 12)}
    assert rows[("p_x", "max")] > 0.25 and ("p_x", "kink") not in rows


def test_the_stick_band_still_catches_a_wrong_stick_radius():
    """A solver whose stick radius is 0.05 a (0.6 cell) too small, at Q/μP = 0.5: the
    max norm off the band exceeds the default fem-analytic tolerance (0.17)."""
    x = np.linspace(-1.3, 1.3, 61)
    rows = {(q, m): v for q, m, v in compare_steps(
        _mindlin_step(x, 0.744), _mindlin_step(x, 0.794), a0=1.0, p0=1.0, cell=1 / 12)}
    assert rows[("p_x", "max")] > tol.default_tolerance("fem-analytic", "p_x", "max")
    assert rows[("p_x", "l2")] > tol.default_tolerance("fem-analytic", "p_x", "l2")


def test_stick_band_is_the_points_within_a_width_of_the_other_state():
    x = np.linspace(-1.0, 1.0, 21)  # spacing 0.1
    state = np.zeros((21, 21), dtype=int)
    state[:, :] = 2
    state[:10, :] = 1  # stick for x < 0, slip for x >= 0: the boundary is x = -0.05
    step = StepResult(scalars={}, x=x, y=x, planes={}, surface={"state": state})
    band = stick_band([step], x, x, 0.2)
    np.testing.assert_array_equal(band[:, 0], np.abs(x + 0.05) <= 0.2)
    assert band.all(axis=1).sum() == 4  # x = -0.2, -0.1, 0, 0.1
    state[:] = 1  # all stick: no boundary, no band
    assert not stick_band([step], x, x, 0.2).any()


def test_pair_metrics_on_different_grids():
    """ic on a 27-cell grid vs the exact solution on 81 cells: metrics on the coarse
    points, where the fine field is interpolated."""
    fine = load_case("hertz")[0]
    coarse = load_case("hertz", overrides={"grid.nx": 27, "grid.ny": 27})[0]
    res = {"ic": fakes.solve_ic(coarse), "analytic": fakes.solve_exact(fine)}
    m = compare_point(fine, res).set_index(["quantity", "metric"])
    assert set(m["pair"]) == {"ic-analytic"}
    # every 27-cell centre is an 81-cell centre (the 3j+1-th): interpolation is exact
    assert m.loc[("p_max", "rel"), "value"] == pytest.approx(fakes.ERROR, rel=1e-9)
    assert m.loc[("p_n", "l2"), "value"] == pytest.approx(fakes.ERROR, rel=1e-9)
    a0, _ = fine.hertz_scales
    # a_x of the two grids differ by less than one coarse cell
    assert 0 <= m.loc[("a_x", "cells"), "value"] <= 1.0
    assert m.loc[("vm_max_loc", "a0"), "value"] == pytest.approx(0.0, abs=1e-12)
    keys = m["tolerance_key"]
    assert keys[("p_max", "rel")] == "p_max"  # hertz.toml sets p_max and vm_max
    assert keys[("p_n", "l2")] == "default:p_n_l2"


def test_tolerance_lookup_order_and_defaults():
    case = load_case("hertz")[0].with_changes(tolerances={"p_max": 0.01, "ic-fem.p_max": 0.2})
    assert tol.tolerance(case, "ic-fem", "p_max", "rel") == (0.2, "ic-fem.p_max")
    assert tol.tolerance(case, "ic-analytic", "p_max", "rel") == (0.01, "p_max")
    value, key = tol.tolerance(case, "ic-analytic", "p_n", "l2")
    assert key == "default:p_n_l2"
    assert value == pytest.approx(tol.budget("ic", "p_n", "l2") + tol.budget("analytic",
                                                                            "p_n", "l2"))
    assert tol.tolerance_key("vm_max_loc", "cells") == "vm_max_loc_cells"
    assert tol.tolerance_key("a_x", "cells") == "a_x"


@pytest.mark.parametrize(("key", "needle"), [
    ("p_mx", "unknown tolerance key 'p_mx'"),
    ("ic-fm.p_max", "'ic-fm' is not a compared pair"),
    ("ic-ic.p_max", "'ic-ic' is not a compared pair"),
    ("p_n", "unknown tolerance key 'p_n'"),  # p_n has two metrics: p_n_l2 / p_n_max
])
def test_bad_tolerance_keys_are_named(key, needle):
    case = load_case("hertz")[0].with_changes(tolerances={key: 0.1})
    with pytest.raises(CaseError, match=re.escape(needle)):
        tol.check_keys(case, ["ic", "fem", "analytic"])


def test_readme_documents_every_key_and_default():
    text = README.read_text()
    pairs = ["ic-fem", "ic-analytic", "fem-analytic"]
    for key, (q, m) in tol.KEYS.items():
        values = " | ".join(f"{tol.default_tolerance(p, q, m):g}" for p in pairs)
        assert f"| `{key}` | {q} | {m} | {values} |" in text, key


def test_readme_documents_every_case_key():
    from cases.schema import SCHEMA as _SCHEMA

    text = README.read_text()
    for table, sub in _SCHEMA.items():
        if isinstance(sub, dict):
            for key, inner in sub.items():
                names = inner if isinstance(inner, dict) else [key]
                for name in names:
                    assert f"`{name}`" in text, f"{table}.{name}"
        else:
            assert f"`{table}`" in text or f"[{table}]" in text, table


# ------------------------------------------------------------------ fretting tables


def _fretting_run(solver: str, cycles: list[float], dQ: float = 0.0, energy_factor=1.0
                  ) -> RunResult:
    """A fretting result: one output step per cycle (step n = cycle n), loops through
    +1 -> -1 -> +1 with Qx = 10 δ (+ ``dQ`` at the third point), energy 2 per cycle
    (× ``energy_factor``)."""
    x = np.linspace(-1.0, 1.0, 5)
    path = np.array([0.5, 0.0, -0.5, -1.0, -0.5, 0.0, 0.5, 1.0])
    loops = {k: [] for k in ("cycle", "displacement", "Qx", "Qy")}
    for c in cycles:
        Qx = 10.0 * path
        Qx[2] += dQ
        loops["cycle"] += [c] * path.size
        loops["displacement"] += list(path)
        loops["Qx"] += list(Qx)
        loops["Qy"] += [0.0] * path.size
    tables = {"loops": {k: np.array(v, float) for k, v in loops.items()},
              "cycles": {"cycle": np.array(cycles, float),
                         "energy": 2.0 * energy_factor * np.ones(len(cycles))}}
    steps = [StepResult(scalars={"step": int(c), "cycle": float(c)}, x=x, y=x, surface={})
             for c in cycles]
    return RunResult(case="f", solver=solver, param="", steps=steps, tables=tables)


def test_loop_and_energy_metrics_give_a_known_difference_exactly():
    a = _fretting_run("ic", [1.0], dQ=0.3, energy_factor=1.05)
    b = _fretting_run("analytic", [1.0])
    rows = {(q, m): v for q, m, v in compare_tables(a.tables, b.tables, 1.0, mu_P=6.0)}
    assert rows == {("loop_q", "max"): pytest.approx(0.3 / 6.0, rel=1e-14),
                    ("q_ends", "max"): 0.0,  # the third point is not an extreme
                    ("energy", "rel"): pytest.approx(0.05, rel=1e-12)}
    # Qy counts too: |ΔQ| is the norm of the vector difference
    a.tables["loops"]["Qy"][2] = 0.4  # at the point of ΔQx = 0.3
    rows = {(q, m): v for q, m, v in compare_tables(a.tables, b.tables, 1.0, mu_P=6.0)}
    assert rows[("loop_q", "max")] == pytest.approx(0.5 / 6.0, rel=1e-14)
    # the extremes δ = ±1 (the fourth and the last point) are q_ends' points
    for k, dq in ((3, 0.2), (7, -0.1)):
        a.tables["loops"]["Qx"][k] += dq
    rows = {(q, m): v for q, m, v in compare_tables(a.tables, b.tables, 1.0, mu_P=6.0)}
    assert rows[("q_ends", "max")] == pytest.approx(0.2 / 6.0, rel=1e-12)
    assert rows[("loop_q", "max")] == pytest.approx(0.5 / 6.0, rel=1e-14)
    # loops through other displacements (other steps) are not compared point by point
    a.tables["loops"]["displacement"] = a.tables["loops"]["displacement"] * 0.9
    rows = {(q, m) for q, m, _ in compare_tables(a.tables, b.tables, 1.0, mu_P=6.0)}
    assert rows == {("energy", "rel")}


def test_a_cycle_only_one_solver_has_is_skipped():
    a = _fretting_run("ic", [1.0, 2.0], dQ=0.3)
    b = _fretting_run("analytic", [1.0])
    assert compare_tables(a.tables, b.tables, 2.0, mu_P=6.0) == []
    assert compare_tables(b.tables, a.tables, 2.0, mu_P=6.0) == []
    assert compare_tables({}, b.tables, 1.0, mu_P=6.0) == []


def test_compare_point_adds_the_cycle_metrics_at_common_output_cycles():
    case = load_case("fretting_isotropic", quick=True)[0]
    mu_P = friction_scale(case)
    a0, p0 = case.hertz_scales
    assert mu_P == pytest.approx(0.3 * 2 * math.pi * a0**2 * p0 / 3, rel=1e-14)
    assert mu_P == pytest.approx(0.3 * 778.4068, rel=1e-6)  # Hertz at approach 0.008
    a = _fretting_run("ic", [1.0, 2.0], dQ=0.3, energy_factor=0.99)
    b = _fretting_run("analytic", [1.0])
    m = compare_point(case, {"ic": a, "analytic": b})
    got = m[m["quantity"].isin(["loop_q", "q_ends", "energy"])].set_index(
        ["quantity", "metric"])
    assert list(got["step"]) == [1, 1, 1] and list(got["cycle"]) == [1.0, 1.0, 1.0]
    assert got.loc[("loop_q", "max"), "value"] == pytest.approx(0.3 / mu_P, rel=1e-12)
    assert got.loc[("energy", "rel"), "value"] == pytest.approx(0.01, rel=1e-9)
    assert got.loc[("loop_q", "max"), "tolerance_key"] == "default:loop_q"
    assert got.loc[("energy", "rel"), "tolerance"] == pytest.approx(
        tol.budget("ic", "energy", "rel") + tol.budget("analytic", "energy", "rel"))


def test_a_traction_against_a_zero_reference_is_measured_on_mu_p0():
    """Issue 73, point 2: where the reference carries no tangential traction (a solver
    that drops the coupling, or a frictionless reference), a traction of the other solver
    is measured on the largest traction the contact can carry, μ p0 — not on p0, where at
    μ = 0.04 the whole traction reads 4 %: Mindlin's traction at μ = 0.04 against zero
    reads its rms over μ p0, more than twice the ic-fem tolerance (on p0: 1.5 %)."""
    from cases.model import Friction

    x = np.linspace(-1.3, 1.3, 61)
    mindlin_step, none = _mindlin_step(x, 0.794), _mindlin_step(x, 0.794)
    none.surface["p_x"] = 0 * none.surface["p_x"]
    mu = 0.04
    mindlin_step.surface["p_x"] = mindlin_step.surface["p_x"] * (mu / 0.3)
    q = mindlin_step.surface["p_x"]
    inside = (mindlin_step.surface["p_n"] > 0)
    rows = {(qq, m): v for qq, m, v in compare_steps(
        mindlin_step, none, a0=1.0, p0=1.0, friction=Friction(mu1=mu, mu2=mu))}
    assert rows[("p_x", "max")] > 0.5  # the peak of μ p0's size, on μ p0
    rms = float(np.sqrt(np.mean(q[inside] ** 2)))
    assert rows[("p_x", "l2")] == pytest.approx(rms / mu, rel=0.25)
    assert rows[("p_x", "l2")] > 2 * tol.default_tolerance("ic-fem", "p_x", "l2")
    # without the case's friction (a frictionless reference): on p0, where any is wrong
    rows = {(qq, m): v for qq, m, v in compare_steps(mindlin_step, none, a0=1.0, p0=1.0)}
    assert rows[("p_x", "l2")] == pytest.approx(rms, rel=0.25)
    assert rows[("p_x", "l2")] < tol.default_tolerance("ic-fem", "p_x", "l2") / 5


def test_the_slip_zone_of_a_resolution_floor_is_the_references():
    """Issue 73, point 1: the floors count the closed form's zones where it states them,
    else the union of both solvers' (the larger contact, the smaller stick radius): a
    solver that reports no slip zone does not take its own traction rows out of the gate,
    whichever side of the pair it is on."""
    from reports.compare.point import step_resolution

    x = np.linspace(-1.3, 1.3, 61)
    h = x[1] - x[0]

    def step(a: float, c: float | None, **extra) -> StepResult:
        scalars = {"contact_area": math.pi * a * a, **extra}
        if c is not None:
            scalars["stick_area"] = math.pi * c * c
        return StepResult(scalars=scalars, x=x, y=x, planes={}, surface={})

    right, stuck = step(1.0, 0.8), step(1.0, 1.0)  # stuck: no slip zone at all
    for sa, sb in ((stuck, right), (right, stuck)):
        assert step_resolution(sa, sb, 0.0).slip == pytest.approx(0.2 / h)
    # a closed form states its own zones, whatever the solver under test reports
    closed = step(1.0, 0.7)
    assert step_resolution(stuck, closed, 0.0, closed=True).slip == pytest.approx(0.3 / h)
    assert step_resolution(step(1.0, 0.1), closed, 0.0, closed=True).slip == \
        pytest.approx(0.3 / h)
    # a closed form that bounds its stick zone by a radius (Spence's (SP1))
    spence = step(1.0, None, stick_radius=0.75)
    assert step_resolution(stuck, spence, 0.0, closed=True).slip == pytest.approx(0.25 / h)
    # the contact radius too: the larger of the two between solvers
    assert step_resolution(step(0.5, 0.5), right, 0.0).contact == pytest.approx(1.0 / h)
    # a reference without any tangential traction has no slip zone to resolve
    none = step(1.0, 1.0)
    none.surface.update(p_x=np.zeros((x.size, x.size)), p_y=np.zeros((x.size, x.size)))
    assert step_resolution(right, none, 0.0).slip == math.inf
    # the pressure peak's stick floor (coupled contacts) takes the larger stick disc
    assert step_resolution(step(1.0, 0.1), right, 0.0, coupled=True).stick == \
        pytest.approx(0.8 / h)
    assert step_resolution(right, right, 0.0).stick == math.inf
    full = step(1.0, 0.95)  # a disc that fills the contact: a peak of Hertz's breadth
    assert step_resolution(full, full, 0.0, coupled=True).stick == math.inf
