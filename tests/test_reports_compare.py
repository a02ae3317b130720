"""Comparison metrics, sampling and the tolerance naming scheme."""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest
import test_cli_fakes as fakes

from cases.loader import load_case
from cases.model import CaseError
from cases.result import Plane, StepResult
from reports import tolerances as tol
from reports.compare import (
    common_axis,
    compare_point,
    compare_steps,
    contact_edges,
    field_errors,
    interior,
    sample,
)

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


def test_max_norms_leave_out_the_edge_band():
    """Two uniform-pressure contacts whose boundaries cut different cells (a worn,
    step-edged pressure sampled on grids half a cell apart): the max norms see no
    difference off the one-cell edge band, the L2 norms still see the edge cells."""
    x = np.linspace(-1.0, 1.0, 41)  # h = 0.05
    sa = _flat_punch_step(0.5, x, vm_edge=1.0)
    sb = _flat_punch_step(0.5, x, vm_edge=1.6)
    sa.surface["p_n"][np.abs(np.hypot(x[:, None], x[None, :]) - 0.5) < 0.03] = 0.6
    rows = {(q, m): v for q, m, v in compare_steps(sa, sb, a0=0.5, p0=1.0)}
    assert rows[("p_n", "max")] == pytest.approx(0.0, abs=1e-15)
    assert rows[("p_n", "l2")] > 0.05
    assert rows[("vm_xz", "max")] == pytest.approx(0.0, abs=1e-15)
    assert rows[("vm_xz", "l2")] > 0.02
    # a difference one cell farther inside is measured by the max norm
    sb.surface["p_n"][np.abs(np.hypot(x[:, None], x[None, :]) - 0.4) < 0.03] = 0.7
    rows = {(q, m): v for q, m, v in compare_steps(sa, sb, a0=0.5, p0=1.0)}
    assert rows[("p_n", "max")] == pytest.approx(0.3, rel=1e-12)


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
    ("ic-fm.p_max", "'ic-fm' is not a solver pair"),
    ("ic-ic.p_max", "'ic-ic' is not a solver pair"),
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
