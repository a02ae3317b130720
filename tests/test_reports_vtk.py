"""Grid solvers' steps as .vtu for ParaView (reports/store/vtk.py): values round-trip exactly
and sit where they belong in the FEM's frame (Z = -depth); `contact-vv run` writes them."""

from __future__ import annotations

import math

import meshio
import numpy as np
import pytest
from skfem import MeshTet

from cases.loader import load_case
from cases.result import STRESS_COMPONENTS, Plane, StepResult, load_step, von_mises
from fem_reference.fields.vtu import fields_mesh
from fem_reference.model.elasticity import P2Space
from reports.cli import main
from reports.store import vtk


def fem_stress_names() -> list[str]:
    """The stress names of the FEM's .vtu point data (all but the displacement)."""
    m = MeshTet.init_tensor(*(np.linspace(0.0, 1.0, 2),) * 3)
    space = P2Space(m)
    mesh = fields_mesh(space, np.zeros(space.nodes.size), 0.3, 1000.0)
    return [k for k in mesh.point_data if k != "displacement"]


def toy_step(x0: float = 0.0, y0: float = 0.0, scalars: dict | None = None) -> StepResult:
    """A step on a 5 x 4 grid (different spacings) with distinct values everywhere."""
    rng = np.random.default_rng(7)
    x = (np.arange(5) + 0.5) * 0.1 - 0.25
    y = (np.arange(4) + 0.5) * 0.2 - 0.4
    surface = {k: rng.normal(size=(5, 4)) for k in
               ("p_n", "p_x", "p_y", "gap", "slip_x", "slip_y", "wear_a", "wear_b")}
    surface["state"] = rng.integers(0, 3, size=(5, 4)).astype(np.int8)
    z = np.linspace(0.0, 0.3, 7)
    planes = {}
    for name, s in (("xz", x), ("yz", y)):
        f = {c: rng.normal(size=(s.size, z.size)) for c in STRESS_COMPONENTS}
        f["vm"] = von_mises(*(f[c] for c in STRESS_COMPONENTS))
        planes[name] = Plane(s=s.copy(), z=z, fields=f)
    return StepResult(scalars=dict(scalars or {}, step=3), x=x, y=y, surface=surface,
                      planes=planes)


def read(path) -> meshio.Mesh:
    return meshio.read(path, file_format="vtu")


def test_surface_cells_carry_the_fields_at_their_centres(tmp_path):
    step = toy_step()
    assert vtk.write_step(tmp_path, 3, step) == ["step_0003_surface.vtu",
                                                  "step_0003_planes.vtu"]
    mesh = read(tmp_path / "step_0003_surface.vtu")
    assert [c.type for c in mesh.cells] == ["quad"]
    corners = mesh.points[mesh.cells[0].data]  # (ncells, 4, 3)
    assert np.all(corners[:, :, 2] == 0.0)  # the contact surface Z = 0
    centres = corners.mean(axis=1)
    nx, ny = step.surface["p_n"].shape
    assert len(centres) == nx * ny
    for name, arr in step.surface.items():
        back = mesh.cell_data[name][0]
        assert back.dtype == arr.dtype, name
        for c in range(nx * ny):
            i = int(np.argmin(np.abs(step.x - centres[c, 0])))
            j = int(np.argmin(np.abs(step.y - centres[c, 1])))
            assert centres[c, :2] == pytest.approx([step.x[i], step.y[j]], abs=1e-12)
            assert back[c] == arr[i, j], (name, c)  # exact
    # the quads tile the grid: cell sizes dx x dy
    assert np.ptp(corners[0, :, 0]) == pytest.approx(0.1)
    assert np.ptp(corners[0, :, 1]) == pytest.approx(0.2)
    traction = mesh.cell_data["traction"][0]
    assert traction.shape == (nx * ny, 3)
    assert np.array_equal(traction, np.stack(
        [step.surface[k].ravel() for k in ("p_x", "p_y", "p_n")], axis=1))


@pytest.mark.parametrize("how", ["case", "scalars"])
def test_planes_sit_at_their_crossing_with_the_fem_names(tmp_path, how):
    x0, y0 = 0.05, -0.1  # anywhere: the planes are placed, not sampled, there
    if how == "case":
        step = toy_step()
        vtk.write_step(tmp_path, 3, step, x0, y0)
    else:  # the step's own x0, y0 win over the case's
        step = toy_step(scalars={"x0": x0, "y0": y0})
        vtk.write_step(tmp_path, 3, step, 9.0, 9.0)
    mesh = read(tmp_path / "step_0003_planes.vtu")
    fem_names = fem_stress_names()
    assert fem_names == [*STRESS_COMPONENTS, "von_mises"]
    assert list(mesh.point_data) == fem_names
    assert {c.type for c in mesh.cells} == {"quad"}
    pts = mesh.points
    for name, plane in step.planes.items():
        for i, s in enumerate(plane.s):
            for k, z in enumerate(plane.z):
                where = (s, y0, -z) if name == "xz" else (x0, s, -z)
                hit = np.flatnonzero(np.all(pts == np.array(where), axis=1))
                # on the crossing line both planes have a point; pick this plane's
                hit = [h for h in hit if
                       mesh.point_data["von_mises"][h] == plane.fields["vm"][i, k]]
                assert len(hit) == 1, (name, i, k)
                for c in STRESS_COMPONENTS:
                    assert mesh.point_data[c][hit[0]] == plane.fields[c][i, k]
    assert np.all(pts[:, 2] <= 0.0) and pts[:, 2].min() == -0.3  # Z = -depth
    n_quads = sum(len(c.data) for c in mesh.cells)
    assert n_quads == 4 * 6 + 3 * 6  # xz (5 x 7 samples) + yz (4 x 7)


def test_steps_without_grid_fields_are_skipped_and_nan_is_written(tmp_path):
    step = toy_step()
    bare = StepResult(scalars={"P": 1.0}, x=step.x, y=step.y, surface={})
    assert not vtk.on_grid(bare)
    assert vtk.write_step(tmp_path, 0, bare) == []
    uneven = StepResult(scalars={}, x=step.x ** 3, y=step.y, surface=step.surface)
    assert vtk.write_step(tmp_path, 0, uneven) == []
    assert not list(tmp_path.iterdir())
    # a closed form's NaN fields, and no planes
    nan = StepResult(scalars={"x0": math.nan}, x=step.x, y=step.y,
                     surface={"p_n": np.full((5, 4), np.nan)})
    assert vtk.write_step(tmp_path, 1, nan) == ["step_0001_surface.vtu"]
    assert np.isnan(read(tmp_path / "step_0001_surface.vtu").cell_data["p_n"][0]).all()


def test_halfspace_step_roundtrips(tmp_path):
    import halfspace

    case = load_case("hertz", quick=True)[0]
    step = halfspace.solve(case).steps[0]
    vtk.write_step(tmp_path, 0, step, case.stress.x0, case.stress.y0)
    surface = read(tmp_path / "step_0000_surface.vtu")
    centres = surface.points[surface.cells[0].data].mean(axis=1)
    i, j = np.unravel_index(int(np.argmax(step.surface["p_n"])), step.surface["p_n"].shape)
    c = int(np.argmax(surface.cell_data["p_n"][0]))
    assert surface.cell_data["p_n"][0][c] == step.surface["p_n"][i, j]
    assert centres[c, :2] == pytest.approx([step.x[i], step.y[j]], abs=1e-12)
    planes = read(tmp_path / "step_0000_planes.vtu")
    vm = planes.point_data["von_mises"]
    at = int(np.argmax(vm))
    assert vm[at] == step.scalars["vm_max"]
    assert planes.points[at] == pytest.approx(
        [step.scalars["vm_max_x"], step.scalars["vm_max_y"], -step.scalars["vm_max_z"]],
        abs=1e-12)


def test_off_grid_planes_are_drawn_where_the_halfspace_sampled_them(tmp_path):
    """stress.x0, y0 between cell centres: the half-space solver samples its planes
    through the nearest centres and reports them (x0, y0 scalars); the .vtu planes stand
    there, not at the requested point half a cell away."""
    import halfspace

    case = load_case("hertz", quick=True, overrides={"stress.x0": 0.013,
                                                      "stress.y0": -0.011})[0]
    step = halfspace.solve(case).steps[0]
    i, j = case.grid.nearest_cell(0.013, -0.011)
    assert (step.scalars["x0"], step.scalars["y0"]) == (case.grid.x[i], case.grid.y[j])
    assert abs(step.scalars["x0"] - 0.013) > 1e-3  # really off the requested point
    vtk.write_step(tmp_path, 0, step, case.stress.x0, case.stress.y0)
    planes = read(tmp_path / "step_0000_planes.vtu")
    xz = planes.points[:, 1] == step.scalars["y0"]
    yz = planes.points[:, 0] == step.scalars["x0"]
    assert xz.sum() + yz.sum() == planes.points.shape[0] + (yz & xz).sum()
    assert xz.any() and yz.any()


def test_cli_run_writes_them_beside_the_steps(tmp_path):
    out = tmp_path / "res"
    assert main(["run", "hertz", "--quick", "--solver", "ic", "--no-progress",
                 "--out", str(out)]) == 0
    unit = out / "hertz" / "fields" / "ic" / "base"
    names = sorted(p.name for p in unit.iterdir())
    assert names == ["step_0000.npz", "step_0000_planes.vtu", "step_0000_surface.vtu"]
    step = load_step(unit / "step_0000.npz")
    back = read(unit / "step_0000_surface.vtu")
    assert np.array_equal(back.cell_data["p_n"][0], step.surface["p_n"].ravel())
    planes = read(unit / "step_0000_planes.vtu")
    assert np.array_equal(planes.point_data["von_mises"], np.concatenate(
        [step.planes[k].fields["vm"].ravel() for k in ("xz", "yz")]))
