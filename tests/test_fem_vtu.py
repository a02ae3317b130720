"""FE fields as .vtu: meshio reads back what was written; nodal stresses are right."""

from __future__ import annotations

import numpy as np
import pytest
from skfem import MeshTet

from cases.loader import load_case
from cases.model import FemSettings
from fem_reference import read_vtu, solve, write_vtu
from fem_reference.fields.vtu import fields_mesh
from fem_reference.model.elasticity import P2Space, stress_from_gradient

pytestmark = pytest.mark.fem


def _roundtrip(mesh, path):
    write_vtu(path, mesh)
    back = read_vtu(path)
    assert np.array_equal(back.points, mesh.points)
    assert len(back.cells) == 1 and back.cells[0].type == "tetra10"
    assert np.array_equal(back.cells[0].data, mesh.cells[0].data)
    assert set(back.point_data) == set(mesh.point_data)
    for key, value in mesh.point_data.items():
        assert np.array_equal(back.point_data[key], value), key
    return back


def test_vtu_roundtrip_linear_field(tmp_path):
    m = MeshTet.init_tensor(np.linspace(0, 1, 3), np.linspace(0, 1, 3), np.linspace(-1, 0, 3))
    space = P2Space(m)
    A = np.array([[1e-3, 2e-4, 0.0], [0.0, -5e-4, 1e-4], [3e-4, 0.0, 2e-3]])
    u = (A @ space.nodes).T.ravel()
    mesh = fields_mesh(space, u, 0.3, 1000.0)
    back = _roundtrip(mesh, tmp_path / "linear.vtu")
    # uniform strain: every nodal stress equals the exact one
    sig = stress_from_gradient(A, 0.3, 1000.0)
    assert np.allclose(back.point_data["sxx"], sig[0, 0]) and np.allclose(
        back.point_data["syz"], sig[1, 2])
    assert np.allclose(back.point_data["displacement"], u.reshape(-1, 3))
    with pytest.raises(ValueError, match=".vtu"):
        write_vtu(tmp_path / "x.vtk", mesh)


def test_solve_returns_step_meshes(tmp_path):
    case = load_case("hertz", quick=True)[0]
    case = case.with_changes(fem=FemSettings(block=10.0, depth=10.0, h=0.5))
    res = solve(case)
    meshes = res.meta["vtu"]
    assert [step for step, _ in meshes] == [0]
    mesh = meshes[0][1]
    back = _roundtrip(mesh, tmp_path / "step_0000.vtu")
    # the body is pressed down under the contact; σ_zz < 0 there
    top = np.isclose(back.points[:, 2], 0.0)
    centre = np.argmin(np.where(top, np.hypot(back.points[:, 0], back.points[:, 1]), np.inf))
    assert back.point_data["displacement"][centre, 2] < 0
    assert back.point_data["szz"][centre] < 0
    assert back.point_data["von_mises"].max() > 0
