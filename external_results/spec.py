"""The ``[external.NAME]`` table of a case: which files hold another code's results and
how their fields map to the suite's (``docs/external-results.md`` documents every key).

Every error is a :class:`cases.model.CaseError` that names the key (``external.NAME.key``)
or the file.
"""

from __future__ import annotations

import glob
import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from cases.model import Case, CaseError
from cases.steps import output_steps

#: the suite's surface fields a file may hold (cases.result, module doc)
SURFACE = ("p_n", "p_x", "p_y", "wear_a", "wear_b", "gap", "state")
#: the stress components of the reported body (reported frame: x, y, depth z) and σ_VM
STRESS = ("sxx", "syy", "szz", "sxy", "sxz", "syz", "vm")
#: the scalars a file may state itself (cases.result.SUMMARY_COLUMNS); the others are
#: derived from the fields (external_results.step)
SCALARS = ("P", "Qx", "Qy", "contact_area", "stick_area", "a_x", "a_y", "p_max", "w_max",
           "wear_volume", "s", "cycle")
#: mm per file length unit, MPa per file stress unit
LENGTH_UNITS = {"mm": 1.0, "m": 1e3, "cm": 10.0, "um": 1e-3}
STRESS_UNITS = {"MPa": 1.0, "Pa": 1e-6, "kPa": 1e-3, "GPa": 1e3, "N/mm2": 1.0}
AXES = ("x", "y", "z")
#: the budgets of the length metrics unless stated: one element (``cell``) and 0.3 a0,
#: a grid solver's (reports.registry.solvers.grid_budget); ``default`` is a relative error
LENGTH_BUDGETS = {"cells": 1.0, "a0": 0.3}
KEYS = ("files", "format", "steps", "fields", "scalars", "scalars_file", "length_unit",
        "stress_unit", "axes", "origin", "mirror", "budget", "cell", "description")


@dataclass(frozen=True)
class Source:
    """Where a suite quantity is in a file: the file's field ``name`` (its ``component``
    for a vector or tensor field, None for a scalar one), times ``sign``."""

    name: str
    component: int | None = None
    sign: float = 1.0


@dataclass(frozen=True)
class Spec:
    """One external result set (module doc): the files of the output steps in order,
    their step numbers, the field and scalar sources, the units (mm and MPa per file
    unit), the axes (file axis index and sign of the suite's x, y and depth), the file
    point that is the suite's origin, the mirror planes of a partial model, the stated
    error budget (quantity, quantity_metric or ``default`` -> relative error) and the
    representative element size at the surface [mm]."""

    name: str
    files: tuple[Path, ...]
    steps: tuple[int, ...]
    fields: Mapping[str, Source]
    scalars: Mapping[str, Source]
    length: float
    stress: float
    axes: tuple[tuple[int, float], ...]
    origin: tuple[float, float, float]
    mirror: tuple[str, ...]
    budget: Mapping[str, float]
    cell: float | None
    format: str | None = None
    #: a CSV table of the scalars, one row per output step (column ``step``); None: the
    #: scalars are the files' field data
    scalars_file: Path | None = None

    def budget_of(self, quantity: str, metric: str) -> float:
        """The stated budget of (quantity, metric): ``quantity_metric``, else
        ``quantity``, else the metric's (``rel``, ``l2``, ``max``, ``cells``, ``a0``), else
        ``default`` for the relative metrics and :data:`LENGTH_BUDGETS` for the lengths."""
        for key in (f"{quantity}_{metric}", quantity, metric):
            if key in self.budget:
                return self.budget[key]
        return LENGTH_BUDGETS.get(metric, self.budget["default"])


def _source(text: Any, key: str) -> Source:
    if not isinstance(text, str) or not text.strip("-").strip():
        raise CaseError(f"{key} = {text!r}: expected a field name, e.g. \"CPRESS\", "
                        "\"-S13\" (sign reversed) or \"stress:2\" (component 2)")
    sign = -1.0 if text.startswith("-") else 1.0
    name, colon, comp = text.lstrip("-").rpartition(":")
    if not colon:
        return Source(comp, None, sign)
    if not comp.isdigit():
        raise CaseError(f"{key} = {text!r}: the component after ':' must be an integer")
    return Source(name, int(comp), sign)


def _unit(value: Any, table: Mapping[str, float], key: str) -> float:
    if isinstance(value, str) and value in table:
        return table[value]
    if isinstance(value, int | float) and not isinstance(value, bool) and value > 0 \
            and math.isfinite(value):
        return float(value)
    raise CaseError(f"{key} = {value!r}: one of {', '.join(table)} or a positive factor")


def _axes(value: Any, key: str) -> tuple[tuple[int, float], ...]:
    ok = isinstance(value, list) and len(value) == 3 and all(
        isinstance(v, str) and v.lstrip("-") in AXES for v in value)
    if ok and len({v.lstrip("-") for v in value}) == 3:
        return tuple((AXES.index(v.lstrip("-")), -1.0 if v.startswith("-") else 1.0)
                     for v in value)
    raise CaseError(f"{key} = {value!r}: three distinct file axes, each \"x\", \"y\" or "
                    "\"z\" with an optional \"-\": the suite's x, y and depth (into the body)")


def _files(value: Any, case: Case, key: str) -> tuple[Path, ...]:
    base = Path(case.source).parent if case.source else Path.cwd()
    items = [value] if isinstance(value, str) else value
    if not (isinstance(items, list) and items and all(isinstance(v, str) for v in items)):
        raise CaseError(f"{key} = {value!r}: a file name, a glob pattern or a list of file "
                        "names (one per output step, in order)")
    paths: list[Path] = []
    for item in items:
        pattern = str(base / item.replace("{param}", case.param))
        found = sorted(glob.glob(pattern)) if glob.has_magic(pattern) else [pattern]
        if not found or not Path(found[0]).exists():
            raise CaseError(f"{key}: no file {pattern}")
        if folders := [p for p in found if Path(p).is_dir()]:
            raise CaseError(f"{key}: {folders[0]} is a directory, not a result file")
        paths += [Path(p) for p in found]
    return tuple(paths)


def _budget(value: Any, key: str) -> dict[str, float]:
    if not isinstance(value, dict) or "default" not in value:
        raise CaseError(f"{key}: state the error budget of these results, at least "
                        "{ default = ... } (a relative error; in cells for the cells "
                        "metrics), optionally per quantity or quantity_metric")
    out = {}
    for k, v in value.items():
        if isinstance(v, bool) or not isinstance(v, int | float) or not (
                math.isfinite(v) and v >= 0):
            raise CaseError(f"{key}.{k} = {v!r}: must be a number >= 0")
        out[k] = float(v)
    return out


def _table(value: Any, allowed: tuple[str, ...], key: str) -> dict[str, Source]:
    if not isinstance(value, dict):
        raise CaseError(f"{key} must be a table")
    for k in value:
        if k not in allowed:
            raise CaseError(f"unknown key {key}.{k} (allowed: {', '.join(allowed)})")
    return {k: _source(v, f"{key}.{k}") for k, v in value.items()}


@dataclass(frozen=True)
class Stated:
    """What a result set states of itself, read without its files (the gate needs it
    after the run): the error budget and the element size at the surface [mm]."""

    budget: Mapping[str, float]
    cell: float | None

    budget_of = Spec.budget_of


def _table_of(case: Case, name: str) -> dict:
    if name not in case.external:
        raise CaseError(f"solver external:{name}: the case has no [external.{name}] table "
                        "naming the result files (docs/external-results.md)")
    d = case.external[name]
    for k in d:
        if k not in KEYS:
            raise CaseError(f"unknown key external.{name}.{k} (allowed: {', '.join(KEYS)})")
    return d


def _cell(d: dict, where: str) -> float | None:
    cell = d.get("cell")
    if cell is not None and (isinstance(cell, bool) or not isinstance(cell, int | float)
                             or not cell > 0):
        raise CaseError(f"{where}.cell = {cell!r}: the element size at the surface, > 0 mm")
    return None if cell is None else float(cell)


def stated(case: Case, name: str) -> Stated:
    """The budget and element size ``[external.NAME]`` states (CaseError naming the key)."""
    d = _table_of(case, name)
    where = f"external.{name}"
    return Stated(_budget(d.get("budget"), f"{where}.budget"), _cell(d, where))


def spec(case: Case, name: str) -> Spec:
    """The spec of ``external:NAME`` on ``case`` (CaseError naming the key)."""
    where = f"external.{name}"
    d = _table_of(case, name)
    given = stated(case, name)
    if "files" not in d:
        raise CaseError(f"{where}.files is required")
    files = _files(d["files"], case, f"{where}.files")
    steps = _steps(d.get("steps"), files, case, f"{where}.steps")
    fields = _table(d.get("fields", {}), SURFACE + STRESS, f"{where}.fields")
    if "p_n" not in fields:
        raise CaseError(f"{where}.fields.p_n is required: the file's contact pressure")
    mirror = d.get("mirror", [])
    if not (isinstance(mirror, list) and set(mirror) <= {"x", "y"}):
        raise CaseError(f"{where}.mirror = {mirror!r}: a list of \"x\" and/or \"y\" (the "
                        "file holds the part x >= 0 / y >= 0 of a symmetric model)")
    origin = d.get("origin", [0.0, 0.0, 0.0])
    if not (isinstance(origin, list) and len(origin) == 3 and all(
            isinstance(v, int | float) and not isinstance(v, bool) for v in origin)):
        raise CaseError(f"{where}.origin = {origin!r}: three numbers (file units)")
    fmt = d.get("format")
    if fmt is not None and not isinstance(fmt, str):
        raise CaseError(f"{where}.format = {fmt!r}: \"csv\" or a meshio format name")
    return Spec(
        name=name, files=files, steps=tuple(steps), fields=fields,
        scalars=_table(d.get("scalars", {}), SCALARS, f"{where}.scalars"),
        length=_unit(d.get("length_unit", "mm"), LENGTH_UNITS, f"{where}.length_unit"),
        stress=_unit(d.get("stress_unit", "MPa"), STRESS_UNITS, f"{where}.stress_unit"),
        axes=_axes(d.get("axes", ["x", "y", "-z"]), f"{where}.axes"),
        origin=tuple(float(v) for v in origin), mirror=tuple(dict.fromkeys(mirror)),
        budget=given.budget, cell=given.cell, format=fmt,
        scalars_file=_scalars_file(d.get("scalars_file"), case, f"{where}.scalars_file"))


def _steps(value: Any, files: tuple[Path, ...], case: Case, key: str) -> list[int]:
    """The step number of each file: ``value``, else the case's output steps in order
    (:func:`cases.steps.output_steps`); CaseError for a number the case does not have or
    more files than its output steps (a file no comparison would read)."""
    known = output_steps(case)
    if value is None:
        if len(files) > len(known):
            raise CaseError(f"{key}: {len(files)} files for the case's {len(known)} output "
                            f"step(s) {known}: name the step of each file")
        return known[:len(files)]
    if not (isinstance(value, list) and len(value) == len(files)
            and all(isinstance(s, int) and not isinstance(s, bool) for s in value)):
        raise CaseError(f"{key} = {value!r}: one integer step number per file "
                        f"({len(files)} files)")
    unknown = [s for s in value if s not in known]
    if unknown:
        raise CaseError(f"{key} = {value!r}: the case has no output step {unknown} (its "
                        f"output steps: {known}); no solver's result would meet the file")
    if len(set(value)) < len(value):
        raise CaseError(f"{key} = {value!r}: a step named twice")
    return value


def _scalars_file(value: Any, case: Case, key: str) -> Path | None:
    if value is None:
        return None
    if not isinstance(value, str):
        raise CaseError(f"{key} = {value!r}: the name of a CSV file")
    return _files(value, case, key)[0]
