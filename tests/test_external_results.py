"""Results of another code as a solver (issue 49): the FEM's own files, read back as
``external:NAME``, give the FEM's metrics; the same files perturbed (pressure 5 % high,
the x and y axes swapped, the sign of the shear traction flipped) fail the gate on the
rows that see the defect; XDMF, Exodus II and CSV read like VTU; bad files get an
error naming the file and the field, and the results directory keeps what it had.

The reference of the round trip is the FEM's own metric rows (the same pairs, steps,
sample points and metric code).  The surface fields are the nodal tractions
interpolated as the FEM interpolates them (linear on each facet's sub-triangles), so
they agree to round-off; the scalars a file states are copied.  The stresses differ: a
file holds node-averaged stresses, the FEM samples its exact element stresses; that
difference is bounded here by half of the FEM's own plane budgets (the figures: the
dated table in benchmarks/README.md, "External results").
"""

from __future__ import annotations

import shutil
from pathlib import Path

import meshio
import numpy as np
import pandas as pd
import pytest

from cases.loader import case_path
from reports.cli import main
from reports.registry import solvers, tolerances

pytestmark = pytest.mark.fem

FIELDS = {"p_n": "p_n", "p_x": "p_x", "p_y": "p_y", "sxx": "sxx", "syy": "syy",
          "szz": "szz", "sxy": "sxy", "sxz": "-sxz", "syz": "-syz"}
#: what the FEM's summary states that the fields do not define the same way
STATED = ("P", "Qx", "Qy", "a_x", "a_y", "contact_area")
SURFACE_ROWS = ("p_n", "p_x", "p_y")
PLANE_ROWS = ("vm_xz", "vm_yz", "vm_max", "vm_max_loc")


def fem_budget_table() -> str:
    """The FEM's budgets (reports.registry.solvers.fem_budget) as a stated budget table:
    what a user states whose code is as good as the FEM."""
    lines = ["default = 0.03"]
    for q, metrics in tolerances.QUANTITY_METRICS.items():
        for m in metrics:
            lines.append(f"{q}_{m} = {solvers.fem_budget(q, m)!r}")
    return "\n".join(lines)


def external_case(path: Path, bundled: str, name: str, files: str, *, mirror: str,
                  scalars: str | None = "scalars.csv", fmt: str | None = None,
                  fields: dict[str, str] | None = None) -> Path:
    """A copy of the bundled case ``bundled`` with an ``[external.NAME]`` table."""
    text = case_path(bundled).read_text()
    table = [f"\n[external.{name}]", f'files = "{files}"', f"mirror = {mirror}"]
    if fmt:
        table.append(f'format = "{fmt}"')
    if scalars:
        table.append(f'scalars_file = "{scalars}"')
        table.append("scalars = { " + ", ".join(f'{q} = "{q}"' for q in STATED) + " }")
    table += [f"[external.{name}.fields]"]
    table += [f'{k} = "{v}"' for k, v in (fields or FIELDS).items()]
    table += [f"[external.{name}.budget]", fem_budget_table()]
    path.write_text(text + "\n".join(table) + "\n")
    return path


@pytest.fixture(scope="module")
def fem_results(tmp_path_factory) -> Path:
    """The quick Hertz (quarter model) and sliding sphere (half model, μ = 0.15, 0.5)
    with the FEM, the half-space solver and the closed forms."""
    out = tmp_path_factory.mktemp("ext") / "runs"
    assert main(["run", "hertz", "sliding_friction", "--quick", "--no-progress",
                 "--solver", "ic,fem,analytic", "--out", str(out)]) == 0
    return out


def export(fem_results: Path, case: str, where: Path) -> Path:
    """The FEM's files of ``case`` as another code would hand them over: its meshes and a
    table of its scalars (one row per output step)."""
    src = fem_results / case / "fields" / "fem"
    dst = where / case
    for vtu in src.rglob("step_????.vtu"):
        target = dst / vtu.relative_to(src)
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(vtu, target)
    summary = pd.read_csv(fem_results / case / "summary.csv")
    params = summary.param.astype(object).fillna("")
    for param, rows in summary[summary.solver == "fem"].groupby(params):
        folder = dst / (param or "base")
        rows[["step", *STATED]].to_csv(folder / "scalars.csv", index=False)
    return dst


def ext_run(case: Path, name: str, out: Path) -> int:
    return main(["run", str(case), "--quick", "--no-progress", "--solver",
                 f"external:{name},ic,analytic", "--out", str(out)])


def joined(metrics: pd.DataFrame, name: str) -> pd.DataFrame:
    """external:NAME's rows beside the FEM's against the same reference."""
    m = metrics.assign(param=metrics.param.astype(object).fillna(""))
    a = m[m.pair.str.startswith(f"external:{name}-")]
    b = m[m.pair.str.startswith("fem-")]
    a = a.assign(ref=a.pair.str.split("-").str[1])
    b = b.assign(ref=b.pair.str.split("-").str[1])
    return a.merge(b, on=["param", "step", "ref", "quantity", "metric"],
                   suffixes=("_ext", "_fem"))


@pytest.fixture(scope="module")
def round_trip(fem_results, tmp_path_factory) -> pd.DataFrame:
    """The Hertz files read back, run beside the half-space solver and closed forms, with
    the FEM's rows of the same pairs."""
    where = tmp_path_factory.mktemp("rt")
    export(fem_results, "hertz", where)
    case = external_case(where / "hertz" / "base" / "case.toml", "hertz", "fe",
                         "step_0000.vtu", mirror='["x", "y"]')
    out = where / "out"
    assert ext_run(case, "fe", out) == 0
    metrics = pd.read_csv(out / "case" / "metrics.csv")
    fem = pd.read_csv(fem_results / "hertz" / "metrics.csv")
    both = joined(pd.concat([metrics, fem]), "fe")
    assert main(["gate", str(out)]) == 0
    return both


def test_round_trip_gives_the_fems_metrics(round_trip):
    both = round_trip
    assert set(both.ref) == {"analytic"}  # the pairs both have (ic-fem has ic first)
    exact = both[both.quantity.isin(SURFACE_ROWS + ("P", "p_max", "a_x", "a_y",
                                                    "contact_area"))]
    assert len(exact) >= 6
    assert np.abs(exact.value_ext - exact.value_fem).max() < 1e-9
    planes = both[both.quantity.isin(PLANE_ROWS)]
    assert len(planes) >= 6
    for row in planes.itertuples():
        half = 0.5 * solvers.fem_budget(row.quantity, row.metric)
        assert abs(row.value_ext - row.value_fem) <= half, row


@pytest.mark.parametrize("fmt", ["xdmf", "exodus"])
def test_xdmf_and_exodus_read_as_the_vtu(fem_results, tmp_path, fmt):
    from cases import load_case
    from external_results import solve

    where = export(fem_results, "hertz", tmp_path) / "base"
    mesh = meshio.read(where / "step_0000.vtu")
    name = "step_0000." + ("xdmf" if fmt == "xdmf" else "exo")
    meshio.write(where / name, mesh, file_format=fmt,
                 **({"data_format": "XML"} if fmt == "xdmf" else {}))
    results = {}
    for f in ("step_0000.vtu", name):
        case = external_case(where / f"{f}.toml", "hertz", "fe", f, mirror='["x", "y"]')
        results[f] = solve(load_case(case, quick=True)[0], name="fe").steps[0]
    a, b = results.values()
    for key in a.surface:
        assert np.array_equal(a.surface[key], b.surface[key])
    for plane in a.planes:
        assert np.array_equal(a.planes[plane].fields["vm"], b.planes[plane].fields["vm"])
    assert a.scalars.keys() == b.scalars.keys()


def test_a_csv_surface_table_reads_the_fems_surface(fem_results, tmp_path):
    """The FEM's surface points as a CSV table (no cells: the reader triangulates them):
    the pressure agrees with the VTU's to the difference between two triangulations of
    the same nodes, far inside the budget."""
    from cases import load_case
    from external_results import solve

    where = export(fem_results, "hertz", tmp_path) / "base"
    mesh = meshio.read(where / "step_0000.vtu")
    top = np.abs(mesh.points[:, 2]) < 1e-12
    table = pd.DataFrame({"x": mesh.points[top, 0], "y": mesh.points[top, 1],
                          "z": mesh.points[top, 2], "CPRESS": mesh.point_data["p_n"][top]})
    table.to_csv(where / "surface.csv", index=False)
    steps = {}
    for f, fields in (("step_0000.vtu", {"p_n": "p_n"}), ("surface.csv", {"p_n": "CPRESS"})):
        case = external_case(where / f"{f}.toml", "hertz", "fe", f, mirror='["x", "y"]',
                             fields=fields, scalars=None)
        steps[f] = solve(load_case(case, quick=True)[0], name="fe").steps[0]
    a, b = steps["step_0000.vtu"].surface["p_n"], steps["surface.csv"].surface["p_n"]
    assert not steps["surface.csv"].planes
    err = np.linalg.norm(a - b) / np.linalg.norm(a)
    assert err < 0.1 * solvers.fem_budget("p_n", "l2"), err
    assert steps["surface.csv"].scalars["p_max"] == steps["step_0000.vtu"].scalars["p_max"]


def perturbed(fem_results: Path, where: Path, change) -> Path:
    """The sliding sphere's points (μ = 0.15, 0.5) unfolded to the whole model (the half
    model's mirror image, the y-odd components' signs flipped) and changed by
    ``change(mesh)``; its case, which reads each point's files by ``{param}``."""
    top = export(fem_results, "sliding_friction", where)
    for folder in top.iterdir():
        mesh = meshio.read(folder / "step_0000.vtu")
        pts = mesh.points
        odd = {"p_y", "sxy", "syz"}
        data = {k: np.concatenate([v, -v if k in odd else v])
                for k, v in mesh.point_data.items() if np.ndim(v) == 1}
        cells = [(c.type, np.vstack([c.data, c.data + len(pts)])) for c in mesh.cells]
        full = meshio.Mesh(np.vstack([pts, pts * [1.0, -1.0, 1.0]]), cells, point_data=data)
        change(full)
        meshio.write(folder / "changed.vtu", full)
    return external_case(top / "case.toml", "sliding_friction", "fe", "{param}/changed.vtu",
                         mirror="[]", scalars="{param}/scalars.csv")


def failed(out: Path) -> set[str]:
    m = pd.read_csv(next(out.glob("*/metrics.csv")))
    mine = m[m.pair.str.startswith("external:fe-") & (m.tolerance_kind.notna())]
    return set(mine.quantity[mine.passed.astype(str) == "False"])


def _scale_pressure(mesh):
    mesh.point_data["p_n"] *= 1.05


def _swap_axes(mesh):
    mesh.points[:, [0, 1]] = mesh.points[:, [1, 0]]


def _flip_shear(mesh):
    mesh.point_data["p_x"] *= -1.0


@pytest.mark.parametrize("change, rows", [
    (None, set()),
    (_scale_pressure, {"p_max"}),
    (_swap_axes, {"vm_xz", "vm_yz"}),
    (_flip_shear, {"p_x"}),
], ids=["unchanged", "pressure+5%", "x<->y", "-p_x"])
def test_perturbed_files_fail_the_gate_where_they_should(fem_results, tmp_path, change, rows):
    case = perturbed(fem_results, tmp_path, change or (lambda mesh: None))
    out = tmp_path / "out"
    assert ext_run(case, "fe", out) == 0
    fails = failed(out)
    assert rows <= fails and (rows or not fails), fails
    assert main(["gate", str(out)]) == (1 if rows else 0)


def files_of(out: Path, case: str) -> dict[Path, bytes]:
    return {p.relative_to(out): p.read_bytes() for p in (out / case).rglob("*") if p.is_file()}


def test_bad_files_are_named_and_the_results_kept(fem_results, tmp_path):
    """A file that does not exist, or lacks a mapped field, is refused while the run is
    planned, with the key, the file and the field named: nothing is replaced, no other
    case is touched."""
    where = export(fem_results, "hertz", tmp_path) / "base"
    good = external_case(where / "case.toml", "hertz", "fe", "step_0000.vtu",
                         mirror='["x", "y"]', scalars=None, fields={"p_n": "p_n"})
    out = tmp_path / "out"
    assert main(["run", "hertz", "--quick", "--no-progress", "--solver", "ic,analytic",
                 "--out", str(out)]) == 0
    assert ext_run(good, "fe", out) == 0
    other, kept = files_of(out, "hertz"), files_of(out, "case")

    missing = good.read_text().replace('files = "step_0000.vtu"', 'files = "gone.vtu"')
    good.write_text(missing)
    assert ext_run(good, "fe", out) == 2  # refused while planning: nothing replaced
    assert files_of(out, "case") == kept and files_of(out, "hertz") == other

    bad = missing.replace('files = "gone.vtu"', 'files = "step_0000.vtu"').replace(
        'p_n = "p_n"', 'p_n = "CPRESS"')
    good.write_text(bad)
    assert ext_run(good, "fe", out) == 2
    assert files_of(out, "case") == kept and files_of(out, "hertz") == other

    from cases import load_case
    from cases.model import CaseError
    from external_results import solve

    with pytest.raises(CaseError, match=r"step_0000\.vtu.*fields\.p_n.*no field 'CPRESS'"):
        solve(load_case(good, quick=True)[0], name="fe")
    good.write_text(missing)
    with pytest.raises(CaseError, match=r"external\.fe\.files: no file .*gone\.vtu"):
        solve(load_case(good, quick=True)[0], name="fe")


def test_result_sets_come_first_by_name_whatever_the_order_named():
    from reports.run.plan import select_solvers

    for order in (["external:b", "ic", "external:a"], ["external:a", "external:b", "ic"]):
        chosen, _ = select_solvers(order, relations=False)
        assert chosen == ["external:a", "external:b", "ic"]


def _scaled_copy(src: Path, dst: Path, factor: float) -> None:
    mesh = meshio.read(src)
    for k in mesh.point_data:
        mesh.point_data[k] = mesh.point_data[k] * factor
    meshio.write(dst, mesh)


@pytest.mark.parametrize("files, steps, words", [
    ('"wrong.vtu"', "[1]", "the case has no output step [1] (its output steps: [0])"),
    ('["step_0000.vtu", "more_1.vtu", "more_2.vtu"]', None,
     "3 files for the case's 1 output step(s) [0]"),
    ('["step_0000.vtu", "more_1.vtu"]', "[0, 0]", "a step named twice"),
], ids=["a-step-the-case-lacks", "files-beyond-its-steps", "a-step-twice"])
def test_files_no_comparison_would_read_are_refused_while_planning(
        fem_results, tmp_path, capsys, files, steps, words):
    """Issue 59: a file mapped to a step that no other solver has (here 20 % and 5 % too
    high) used to be stored and compared nowhere, and the gate passed: the steps are
    checked against the case's output steps (:func:`cases.steps.output_steps`) while the
    run is planned — exit 2, the key named, nothing written."""
    where = export(fem_results, "hertz", tmp_path) / "base"
    base = where / "step_0000.vtu"
    _scaled_copy(base, where / "wrong.vtu", 1.2)
    _scaled_copy(base, where / "more_1.vtu", 1.05)
    _scaled_copy(base, where / "more_2.vtu", 1.2)
    case = external_case(where / "case.toml", "hertz", "fe", "step_0000.vtu",
                         mirror='["x", "y"]', scalars=None, fields={"p_n": "p_n"})
    table = f"files = {files}" + (f"\nsteps = {steps}" if steps else "")
    case.write_text(case.read_text().replace('files = "step_0000.vtu"', table))
    out = tmp_path / "out"
    capsys.readouterr()
    assert ext_run(case, "fe", out) == 2
    err = capsys.readouterr().err
    assert "external.fe.steps" in err and words in err, err
    assert not out.exists() or not any(out.iterdir())


def _surface_only(where: Path) -> str:
    """The top surface's points alone, as a point cloud, with the stresses still there."""
    m = meshio.read(where / "step_0000.vtu")
    idx = np.flatnonzero(m.points[:, 2] > -1e-12)
    meshio.write(where / "surface.vtu", meshio.Mesh(
        m.points[idx], [("vertex", np.arange(idx.size)[:, None])],
        point_data={k: v[idx] for k, v in m.point_data.items()}))
    return 'files = "surface.vtu"'


def _header_only(where: Path) -> str:
    (where / "empty.csv").write_text("x,y,z,p_n\n")
    return 'files = "empty.csv"'


def _wrong_axes(where: Path) -> str:
    return 'files = "step_0000.vtu"\naxes = ["x", "z", "-y"]'


@pytest.mark.parametrize("make, needles", [
    (_surface_only, ("surface.vtu", "external.fe.fields", "fill the body")),
    (_header_only, ("empty.csv", "0 point(s)")),
    (_wrong_axes, ("step_0000.vtu", "external.fe.axes", "outside its mesh")),
], ids=["surface-only-with-stresses", "header-only-csv", "wrong-axes"])
def test_unusable_files_are_refused_while_planning(fem_results, tmp_path, capsys, make,
                                                    needles):
    """Issue 59: a file without a usable surface or body for what is mapped used to fail
    in the solve (Qhull's 40-line dump, or "did not converge: QH6154", the file and the
    key unnamed, the case's earlier results deleted and a .partial folder left); it is
    refused while the run is planned, naming the file, the key and the likely cause,
    with Qhull's first line only, and the earlier results kept."""
    where = export(fem_results, "hertz", tmp_path) / "base"
    case = external_case(where / "case.toml", "hertz", "fe", "step_0000.vtu",
                         mirror='["x", "y"]', scalars=None)
    out = tmp_path / "out"
    assert ext_run(case, "fe", out) == 0
    kept = files_of(out, "case")
    capsys.readouterr()
    case.write_text(case.read_text().replace('files = "step_0000.vtu"', make(where)))
    assert ext_run(case, "fe", out) == 2
    err = capsys.readouterr().err
    assert all(n in err for n in needles), err
    assert "Traceback" not in err and len(err.splitlines()) <= 3, err
    assert files_of(out, "case") == kept
    assert not list(out.glob(".*partial*"))
