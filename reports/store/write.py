"""Writing the results of a unit into a case's staging directory: output steps as
``.npz``, solver tables as CSV, meshes as ``.vtu``, the summary rows; CSV files written
atomically (floats round-trip exactly, NaN blank)."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from cases.model import Case
from cases.result import SUMMARY_COLUMNS, RunResult, atomic_path, save_step, write_vtu
from reports.store import layout, vtk


def jsonable(meta: dict) -> dict:
    """Solver metadata for the manifest: JSON values kept, small arrays as lists, anything
    else (meshes, large arrays) as a short description."""
    out = {}
    for key, value in meta.items():
        if key == "vtu":
            continue
        if isinstance(value, np.ndarray):
            value = value.tolist() if value.size <= 64 else \
                f"array {value.dtype} shape {value.shape}"
        try:
            json.dumps(value)
        except (TypeError, ValueError):
            value = f"{type(value).__name__}: {str(value)[:200]}"
        out[str(key)] = value
    return out


def _vtu_items(meshes: Any, numbers: list[int]) -> list[tuple[str, Any]]:
    """(file stem, mesh) pairs from ``meta["vtu"]``: a mesh, a dict {step or name: mesh},
    a list of meshes (one per output step) or a list of (step, mesh) pairs."""
    import meshio

    def stem(key: Any) -> str:
        if isinstance(key, int | np.integer):
            return f"step_{int(key):04d}"
        return layout.safe_name(str(key))

    if isinstance(meshes, meshio.Mesh):
        return [("mesh", meshes)]
    if isinstance(meshes, dict):
        return [(stem(k), m) for k, m in meshes.items()]
    items = []
    for i, item in enumerate(meshes):
        if isinstance(item, tuple | list) and len(item) == 2:
            items.append((stem(item[0]), item[1]))
        else:
            items.append((stem(numbers[i] if i < len(numbers) else i), item))
    return items


def _write_vtu(root: Path, solver: str, param: str, result: RunResult,
               numbers: list[int]) -> list[str]:
    """Write the meshes of ``meta["vtu"]`` (if any) as .vtu files beside the steps."""
    meshes = result.meta.get("vtu")
    if meshes is None:
        return []
    import meshio

    written = []
    for stem, mesh in _vtu_items(meshes, numbers):
        if not isinstance(mesh, meshio.Mesh):
            raise RuntimeError(f"meta['vtu'] holds a {type(mesh).__name__}, not a meshio.Mesh")
        path = write_vtu(layout.unit_dir(root, solver, param) / f"{stem}.vtu", mesh)
        written.append(path.name)
    return written


def write_unit(root: Path, result: RunResult, *, solver: str, param: str, cell_size: float,
               wall_s: float, written: int = 0, case: Case | None = None
               ) -> list[dict[str, Any]]:
    """Write the fields, tables and meshes of one unit (``solver`` at sweep point
    ``param``); return its summary rows.  The first ``written`` output steps were saved as
    they were computed and are not written again.

    Steps with surface fields on a regular grid are also written for ParaView
    (:mod:`reports.store.vtk`); their planes cross at the steps' ``x0, y0`` scalars, else at
    ``case.plane_centre`` (0, 0 without ``case``)."""
    rows = result.summary_rows()
    numbers = [row["step"] for row in rows]
    x0, y0 = case.plane_centre if case is not None else (0.0, 0.0)
    folder = layout.unit_dir(root, solver, param)
    for k, (n, step) in enumerate(zip(numbers, result.steps, strict=True)):
        if k >= written:
            save_step(layout.step_file(root, solver, param, n), step)
        vtk.write_step(folder, n, step, x0, y0)
    for row in rows:
        row["cell_size"] = cell_size
        if _missing(row.get("wall_s")):
            row["wall_s"] = wall_s if len(result.steps) == 1 else math.nan
    for name, table in result.tables.items():
        frame = pd.DataFrame({k: pd.Series(np.asarray(v).ravel()) for k, v in table.items()})
        path = folder / f"{layout.safe_name(name)}.csv"
        with atomic_path(path) as tmp:
            frame.to_csv(tmp, index=False)
    _write_vtu(root, solver, param, result, numbers)
    return rows


def _missing(value: Any) -> bool:
    return value is None or (isinstance(value, float) and math.isnan(value))


def summary_frame(rows: list[dict[str, Any]]) -> pd.DataFrame:
    """summary.csv: the contract columns in order, then any extra scalars (sorted)."""
    frame = pd.DataFrame.from_records(rows)
    for c in SUMMARY_COLUMNS:
        if c not in frame.columns:
            frame[c] = math.nan
    extra = sorted(c for c in frame.columns if c not in SUMMARY_COLUMNS)
    return frame[SUMMARY_COLUMNS + extra]


def write_csv(path: Path, frame: pd.DataFrame) -> None:
    """Write a CSV atomically; floats round-trip exactly, NaN is blank."""
    with atomic_path(path) as tmp:
        frame.to_csv(tmp, index=False, na_rep="")
