"""The interpolation of external results (external_results.interpolate) against exact
references: a quadratic field on ten-node tetrahedra and a linear one on triangles are
reproduced to round-off, a point outside the mesh is found outside, and the surface
integral of a linear field is exact."""

from __future__ import annotations

import numpy as np
from scipy.spatial import Delaunay

from external_results.interpolate import TET10_EDGES, TRI6_SUB, Surface, Volume


def tet10_mesh(rng):
    """Ten-node tetrahedra on random points of the box [-1, 1]² x [0, 1] (depth), with
    midside nodes shared between elements."""
    corners = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (0, 1)], float)
    pts = np.vstack([corners, rng.uniform([-1, -1, 0], [1, 1, 1], size=(40, 3))])
    tets = Delaunay(pts).simplices
    edges = {}
    nodes = [*pts]
    conn = []
    for t in tets:
        row = list(t)
        for i, j in TET10_EDGES:
            key = tuple(sorted((t[i], t[j])))
            if key not in edges:
                edges[key] = len(nodes)
                nodes.append(0.5 * (pts[t[i]] + pts[t[j]]))
            row.append(edges[key])
        conn.append(row)
    return np.array(nodes), np.array(conn)


def quadratic(p):
    x, y, z = p.T
    return 1.0 + 2 * x - y + 0.5 * z + 3 * x * y - x * z + 2 * z * z - y * y


def test_ten_node_tetrahedra_reproduce_a_quadratic_field():
    rng = np.random.default_rng(3)
    nodes, conn = tet10_mesh(rng)
    vol = Volume.of(nodes, {"tetra10": conn})
    q = rng.uniform([-0.99, -0.99, 0.01], [0.99, 0.99, 0.99], size=(500, 3))
    inside, idx, w = vol.weights(q)
    assert inside.all()
    got = (quadratic(nodes)[idx] * w).sum(axis=1)
    assert np.abs(got - quadratic(q)).max() < 1e-11
    out, _, _ = vol.weights(np.array([[0.0, 0.0, 1.5], [2.0, 0.0, 0.5]]))
    assert not out.any()


def test_surface_sub_triangles_reproduce_a_linear_field_and_its_integral():
    rng = np.random.default_rng(4)
    nodes, conn = tet10_mesh(rng)
    surf = Surface.of(nodes, {"tetra10": conn}, 1e-12)
    lin = 0.3 + 1.5 * nodes[:, 0] - 0.7 * nodes[:, 1]
    q = rng.uniform(-0.99, 0.99, size=(400, 2))
    inside, idx, w = surf.weights(q)
    assert inside.all()
    assert np.abs((lin[idx] * w).sum(axis=1) - (0.3 + 1.5 * q[:, 0] - 0.7 * q[:, 1])
                  ).max() < 1e-12
    # ∫ over the square [-1, 1]² of the linear field: 4 × its value at the centre
    assert abs(surf.integral(lin) - 4 * 0.3) < 1e-12
    assert len(surf.simplices.index) % 4 == 0  # each six-node face in four


def test_six_node_triangle_splits_into_four_of_quarter_area():
    v = np.array([[0, 0], [2, 0], [0, 2], [1, 0], [1, 1], [0, 1]], float)
    tri = v[TRI6_SUB]
    a, b = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    area = 0.5 * np.abs(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0])
    assert np.allclose(area, 0.5)


def test_stresses_on_surface_points_only_are_refused_with_the_file_named(tmp_path):
    """A CSV table whose stresses lie on the surface alone gives no tetrahedra: the error
    names the file, not a Qhull traceback."""
    import pandas as pd
    import pytest

    from cases import load_point
    from cases.model import CaseError
    from external_results import solve

    x, y = np.meshgrid(np.linspace(-1, 1, 9), np.linspace(-1, 1, 9), indexing="ij")
    pd.DataFrame({"x": x.ravel(), "y": y.ravel(), "z": 0.0, "p": 1.0, "s": 2.0}).to_csv(
        tmp_path / "flat.csv", index=False)
    case = load_point("hertz", quick=True)
    case = case.with_changes(source=str(tmp_path / "case.toml"), external={"flat": {
        "files": "flat.csv", "fields": {"p_n": "p", "vm": "s"}, "budget": {"default": 0.1}}})
    with pytest.raises(CaseError, match=r"flat\.csv: the stresses mapped in "
                       r"external\.flat\.fields need points that fill"):
        solve(case, name="flat")
