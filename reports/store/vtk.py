"""Grid solvers' output steps as VTK unstructured grids (``.vtu``) for ParaView.

The meshes are in the frame of the FEM's ``.vtu`` files (:mod:`fem_reference.fields.vtu`):
x and y the global axes, Z = −depth, the reported body below its contact surface Z = 0.

- ``step_NNNN_surface.vtu``: the grid cells as ``quad`` cells at Z = 0; cell data the
  cell-centred surface fields under their names in ``StepResult.surface`` (``p_n``,
  ``gap``, ``state``, …) and the traction ``traction`` = (p_x, p_y, p_n) as a 3-vector.
- ``step_NNNN_planes.vtu``: the xz plane (at y = y0) and the yz plane (at x = x0) as
  ``quad`` cells through their samples; point data the stress components ``sxx, syy,
  szz, sxy, sxz, syz`` and ``von_mises`` (the names of the FEM's point data; the
  planes' ``vm``), further plane fields under their own names.  The two planes share
  no points: on their crossing line each keeps its own values.

A step is written when its surface fields lie on a regular grid (``step.x``, ``step.y``
evenly spaced, fields of shape (nx, ny)); steps without one (closed forms that give
only scalars) are skipped.  NaN fields (what a closed form does not cover) are written
as NaN.  Values are written as they are (float64 stays float64), so they read back
exactly.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path

import meshio
import numpy as np

from cases.result import STRESS_COMPONENTS, Plane, StepResult, write_vtu

#: plane field names in the ``.vtu`` point data (as in the FEM's); others keep theirs
PLANE_NAMES = {**{c: c for c in STRESS_COMPONENTS}, "vm": "von_mises"}
#: the suffixes of the files written per output step
SURFACE, PLANES = "surface", "planes"


def _regular(c: np.ndarray) -> bool:
    """Whether ``c`` is a 1-D, finite, increasing, evenly spaced coordinate."""
    if c.ndim != 1 or c.size == 0 or not np.all(np.isfinite(c)):
        return False
    if c.size == 1:
        return True
    d = np.diff(c)
    return bool(d[0] > 0 and np.allclose(d, d[0], rtol=1e-6, atol=0.0))


def _grid_fields(step: StepResult) -> dict[str, np.ndarray]:
    """The surface fields of ``step`` of shape (nx, ny) or (nx, ny, k), real or integer."""
    shape = (np.size(step.x), np.size(step.y))
    out = {}
    for name, arr in step.surface.items():
        arr = np.asarray(arr)
        if arr.shape[:2] == shape and arr.ndim in (2, 3) and arr.dtype.kind in "biuf":
            out[name] = arr
    return out


def on_grid(step: StepResult) -> bool:
    """Whether ``step`` has surface fields on a regular grid (what :func:`surface_mesh`
    needs)."""
    x, y = np.asarray(step.x, dtype=float), np.asarray(step.y, dtype=float)
    if not (_regular(x) and _regular(y)) or (x.size == 1 and y.size == 1):
        return False
    return bool(_grid_fields(step))


def _edges(c: np.ndarray, fallback: float) -> np.ndarray:
    """Cell edges of the cell-centred coordinate ``c`` (one more than ``c``)."""
    h = float(c[1] - c[0]) if c.size > 1 else fallback
    return np.concatenate([[c[0] - 0.5 * h], 0.5 * (c[:-1] + c[1:]), [c[-1] + 0.5 * h]])


def _quads(n: int, m: int) -> np.ndarray:
    """Quads of an (n + 1) x (m + 1) lattice of points numbered i * (m + 1) + j; quad
    (i, j) is row i * m + j (the C order of an (n, m) array)."""
    i, j = np.meshgrid(np.arange(n), np.arange(m), indexing="ij")
    p = (i * (m + 1) + j).ravel()
    return np.stack([p, p + m + 1, p + m + 2, p + 1], axis=1).astype(np.int64)


def _cell_array(arr: np.ndarray) -> np.ndarray:
    if arr.dtype.kind == "b":
        arr = arr.astype(np.uint8)
    return arr.reshape(arr.shape[0] * arr.shape[1], *arr.shape[2:]).copy()


def surface_mesh(step: StepResult) -> meshio.Mesh:
    """The grid cells of ``step`` as ``quad`` cells at Z = 0 with the surface fields
    as cell data (cell (i, j) is row i * ny + j) and the traction 3-vector."""
    if not on_grid(step):
        raise ValueError("the step has no surface fields on a regular grid")
    x, y = np.asarray(step.x, dtype=float), np.asarray(step.y, dtype=float)
    hx = float(x[1] - x[0]) if x.size > 1 else float(y[1] - y[0])
    hy = float(y[1] - y[0]) if y.size > 1 else hx
    ex, ey = _edges(x, hx), _edges(y, hy)
    X, Y = np.meshgrid(ex, ey, indexing="ij")
    points = np.column_stack([X.ravel(), Y.ravel(), np.zeros(X.size)])
    fields = _grid_fields(step)
    cell_data = {name: [_cell_array(arr)] for name, arr in fields.items()}
    if {"p_x", "p_y", "p_n"} <= fields.keys() and all(
            fields[k].ndim == 2 and fields[k].dtype.kind == "f" for k in ("p_x", "p_y", "p_n")):
        cell_data["traction"] = [np.stack(
            [fields[k].ravel() for k in ("p_x", "p_y", "p_n")], axis=1)]
    return meshio.Mesh(points=points, cells=[("quad", _quads(x.size, y.size))],
                       cell_data=cell_data)


def _plane_points(name: str, plane: Plane, x0: float, y0: float) -> np.ndarray:
    """Points (x, y, Z) of the samples of ``plane``, row k * nz + l for (s[k], z[l])."""
    s = np.asarray(plane.s, dtype=float).ravel()
    z = np.asarray(plane.z, dtype=float).ravel()
    S, Z = np.meshgrid(s, 0.0 - z, indexing="ij")  # 0.0 - z: no -0.0 at the surface
    fixed = np.full(S.size, y0 if name == "xz" else x0)
    if name == "xz":
        return np.column_stack([S.ravel(), fixed, Z.ravel()])
    return np.column_stack([fixed, S.ravel(), Z.ravel()])


def planes_mesh(planes: Mapping[str, Plane], x0: float, y0: float) -> meshio.Mesh | None:
    """The ``xz`` plane at y = ``y0`` and the ``yz`` plane at x = ``x0`` as ``quad``
    cells through their samples (point data: the plane fields, ``vm`` as ``von_mises``),
    xz first; None without such a plane."""
    blocks = []
    for name in ("xz", "yz"):
        plane = planes.get(name)
        if plane is None:
            continue
        ns, nz = np.size(plane.s), np.size(plane.z)
        fields = {k: np.asarray(v) for k, v in plane.fields.items()
                  if np.shape(v) == (ns, nz) and np.asarray(v).dtype.kind in "biuf"}
        if ns == 0 or nz == 0:
            continue
        blocks.append((name, plane, fields, ns, nz))
    if not blocks:
        return None
    # point data must cover every point: a field one plane lacks is NaN on the other
    names: list[str] = []
    for block in blocks:
        names += [k for k in block[2] if k not in names]
    points, cells, data = [], [], {PLANE_NAMES.get(k, k): [] for k in names}
    offset = 0
    for name, plane, fields, ns, nz in blocks:
        points.append(_plane_points(name, plane, x0, y0))
        if ns > 1 and nz > 1:
            cells.append(("quad", _quads(ns - 1, nz - 1) + offset))
        else:  # a single line or point of samples
            cells.append(("vertex", np.arange(offset, offset + ns * nz,
                                              dtype=np.int64)[:, None]))
        for k in names:
            arr = fields.get(k)
            data[PLANE_NAMES.get(k, k)].append(
                np.full(ns * nz, math.nan) if arr is None else arr.ravel())
        offset += ns * nz
    point_data = {k: np.concatenate(v) for k, v in data.items()}
    return meshio.Mesh(points=np.concatenate(points), cells=cells, point_data=point_data)


def crossing(step: StepResult, x0: float = 0.0, y0: float = 0.0) -> tuple[float, float]:
    """Where the planes of ``step`` cross: its ``x0``, ``y0`` scalars when it has them
    (finite), else the given (the case's ``stress.x0, stress.y0``)."""
    def pick(key: str, default: float) -> float:
        value = step.scalars.get(key)
        try:
            value = float(value)  # type: ignore[arg-type]
        except (TypeError, ValueError):
            return float(default)
        return value if math.isfinite(value) else float(default)

    return pick("x0", x0), pick("y0", y0)


def step_paths(folder: Path, number: int) -> dict[str, Path]:
    """The files of output step ``number`` in a unit's field directory."""
    return {kind: Path(folder) / f"step_{int(number):04d}_{kind}.vtu"
            for kind in (SURFACE, PLANES)}


def write_step(folder: Path, number: int, step: StepResult, x0: float = 0.0,
               y0: float = 0.0) -> list[str]:
    """Write output step ``number`` (surface, and planes if it has any) into ``folder``
    if it has surface fields on a regular grid; return the names written.  The planes
    cross at :func:`crossing` (``x0, y0``: the case's ``stress.x0, stress.y0``)."""
    if not on_grid(step):
        return []
    paths = step_paths(folder, number)
    write_vtu(paths[SURFACE], surface_mesh(step))
    written = [paths[SURFACE].name]
    mesh = planes_mesh(step.planes, *crossing(step, x0, y0))
    if mesh is not None:
        write_vtu(paths[PLANES], mesh)
        written.append(paths[PLANES].name)
    return written
