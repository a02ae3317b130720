"""One result file read into the suite's frame and units: points (x, y, depth) [mm], the
cells, the mapped fields at the points [MPa, mm] and the scalars the file states.

Meshes are read with meshio (VTU, XDMF, Exodus II and every other format it reads);
a field held as cell data is averaged onto the points of its cells.  A CSV table has a
header row, the columns ``x, y, z`` (file coordinates) and one column per mapped field,
one row per point, and no cells (the samplers triangulate its points).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from cases.model import CaseError

from .spec import Source, Spec

#: how a quantity scales: by the stress unit, the length unit or not at all
LENGTHS = ("wear_a", "wear_b", "gap", "a_x", "a_y", "w_max", "s")
AREAS = ("contact_area", "stick_area")
FORCES = ("P", "Qx", "Qy")
PLAIN = ("state", "cycle")


@dataclass(frozen=True)
class Frame:
    """A file in the suite's frame (module doc)."""

    path: Path
    xyz: np.ndarray  # (n, 3): x, y, depth [mm]
    cells: dict[str, np.ndarray]  # cell type (meshio's names) -> (m, nodes) indices
    values: dict[str, np.ndarray]  # suite quantity -> (n,) values at the points
    scalars: dict[str, float]


def factor(quantity: str, spec: Spec) -> float:
    """What turns a file value of ``quantity`` into mm, MPa and N."""
    if quantity in PLAIN:
        return 1.0
    if quantity in LENGTHS:
        return spec.length
    if quantity in AREAS:
        return spec.length**2
    if quantity == "wear_volume":
        return spec.length**3
    if quantity in FORCES:
        return spec.stress * spec.length**2
    return spec.stress


def _component(data: np.ndarray, src: Source, where: str) -> np.ndarray:
    data = np.asarray(data, dtype=float)
    if src.component is None:
        if data.ndim > 1 and data.shape[1] != 1:
            raise CaseError(f"{where}: field {src.name!r} has {data.shape[1]} components; "
                            f"name one, e.g. \"{src.name}:0\"")
        return data.reshape(-1)
    if data.ndim != 2 or src.component >= data.shape[1]:
        raise CaseError(f"{where}: field {src.name!r} has no component {src.component}")
    return data[:, src.component]


def _cell_to_points(mesh, name: str, npoints: int) -> np.ndarray | None:
    """Cell data ``name`` averaged onto the points of its cells (None: not cell data)."""
    if name not in mesh.cell_data:
        return None
    first = np.asarray(mesh.cell_data[name][0], dtype=float)
    total = np.zeros((npoints, *first.shape[1:]))
    count = np.zeros(npoints)
    for block, data in zip(mesh.cells, mesh.cell_data[name], strict=True):
        data = np.asarray(data, dtype=float)
        for k in range(block.data.shape[1]):
            np.add.at(total, block.data[:, k], data)
            np.add.at(count, block.data[:, k], 1.0)
    return total / np.maximum(count, 1.0).reshape(-1, *([1] * (total.ndim - 1)))


def _read_mesh(path: Path, spec: Spec):
    import meshio

    try:
        return meshio.read(path, file_format=spec.format)
    except (Exception, SystemExit) as exc:  # meshio raises many kinds (and exits)
        raise CaseError(f"{path}: cannot read it as a mesh ({type(exc).__name__}: {exc})"
                        ) from None


def _read_csv(path: Path, needed: tuple[str, ...] = ("x", "y", "z")
              ) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    import pandas as pd

    try:
        table = pd.read_csv(path)
    except Exception as exc:
        raise CaseError(f"{path}: cannot read it as a CSV table ({exc})") from None
    missing = [c for c in needed if c not in table.columns]
    if missing:
        raise CaseError(f"{path}: no column {', '.join(missing)} (needed: "
                        f"{', '.join(needed)})")
    cols = {}
    for c in table.columns:
        try:
            cols[c] = table[c].to_numpy(dtype=float)
        except (TypeError, ValueError):
            if c in needed:
                raise CaseError(f"{path}: column {c} is not numeric") from None
    return np.column_stack([cols[c] for c in needed]), cols


def scalar_rows(spec: Spec) -> dict[int, dict[str, float]] | None:
    """The rows of ``spec.scalars_file`` by step number (None without one)."""
    if spec.scalars_file is None:
        return None
    _, cols = _read_csv(spec.scalars_file, ("step",))
    steps = cols["step"]
    if not np.all(steps == np.rint(steps)):
        raise CaseError(f"{spec.scalars_file}: column step must hold integers")
    return {int(s): {k: v[i] for k, v in cols.items()} for i, s in enumerate(steps)}


def read(path: Path, spec: Spec, number: int = 0,
         rows: dict[int, dict[str, float]] | None = None) -> Frame:
    """The file ``path`` of output step ``number`` in the suite's frame and units (module
    doc), its scalars from ``rows`` (:func:`scalar_rows`) if given, else from its field
    data; CaseError naming the file and the missing or malformed field."""
    csv = (spec.format or path.suffix.lstrip(".")).lower() == "csv"
    if csv:
        points, columns = _read_csv(path)
        cells: dict[str, np.ndarray] = {}
        field_data = {k: v[:1] for k, v in columns.items()}
    else:
        mesh = _read_mesh(path, spec)
        points = np.asarray(mesh.points, dtype=float)
        cells = {}
        for block in mesh.cells:
            data = np.asarray(block.data, dtype=np.int64)
            cells[block.type] = (np.vstack([cells[block.type], data])
                                 if block.type in cells else data)
        field_data = mesh.field_data
    if points.ndim != 2 or points.shape[1] < 3 or not np.isfinite(points).all():
        raise CaseError(f"{path}: the points must have three finite coordinates")
    if points.shape[0] < 3:
        raise CaseError(f"{path}: {points.shape[0]} point(s): a result file needs the "
                        "points of a contact surface (a table with a header and no rows?)")
    xyz = np.column_stack([
        sign * (points[:, axis] - spec.origin[axis]) * spec.length
        for axis, sign in spec.axes])
    values = {}
    for q, src in spec.fields.items():
        where = f"{path} (external.{spec.name}.fields.{q})"
        if csv:
            data = columns.get(src.name)
        else:
            data = mesh.point_data.get(src.name)
            if data is None:
                data = _cell_to_points(mesh, src.name, len(points))
        if data is None:
            raise CaseError(f"{where}: no field {src.name!r}")
        v = src.sign * factor(q, spec) * _component(data, src, where)
        if v.shape != (len(points),) or not np.isfinite(v).all():
            raise CaseError(f"{where}: field {src.name!r} must hold one finite value per "
                            "point")
        values[q] = v
    if rows is not None:
        if number not in rows:
            raise CaseError(f"{spec.scalars_file}: no row of step {number}")
        field_data = {k: np.array([v]) for k, v in rows[number].items()}
    scalars = {}
    for q, src in spec.scalars.items():
        where = f"{path} (external.{spec.name}.scalars.{q})"
        if src.name not in field_data:
            origin = spec.scalars_file or "the file's field data"
            raise CaseError(f"{where}: no scalar {src.name!r} in {origin}")
        raw = np.asarray(field_data[src.name], dtype=float).reshape(-1)
        k = src.component or 0
        if raw.size <= k or not np.isfinite(raw[k]):
            raise CaseError(f"{where}: scalar {src.name!r} has no finite value {k}")
        scalars[q] = float(src.sign * factor(q, spec) * raw[k])
    return Frame(path=path, xyz=xyz, cells=cells, values=values, scalars=scalars)
