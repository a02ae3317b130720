"""Parameter sweeps from the command line, run on Dask (or serially).

``--param key=start:stop:step`` or ``--param key=v1,v2,...`` sets one dotted case key
(``friction.beta``, ``grid.nx``) per sweep point; several ``--param`` options are zipped
(same number of values), e.g. a grid study ``--param grid.nx=21,41,81 --param
grid.ny=21,41,81``.  The sweep replaces any ``[sweep]`` table of the case file, and its
results go to ``DIR/<case>__sweep_<labels>/`` in the layout of a run.

Every (sweep point, solver) is an independent task, run on a Dask cluster
(:mod:`reports.run.cluster`; a LocalCluster of two workers by default) or serially.
"""

from __future__ import annotations

import json
import math
import tempfile
import time
import tomllib
from pathlib import Path
from typing import Any

from cases.loader import case_path, load_case, read_toml, value_label
from cases.model import Case, CaseError
from reports.registry.errors import RunFailed, UserError
from reports.run.plan import CasePlan, Limits, plan_case
from reports.run.units import serial_executor
from reports.store import layout


def parse_value(text: str) -> Any:
    """A TOML scalar (``45``, ``0.25``, ``true``, ``"cg"``), else the bare string."""
    try:
        return tomllib.loads(f"v = {text.strip()}")["v"]
    except tomllib.TOMLDecodeError:
        return text.strip()


#: the most values a swept key may take
MAX_VALUES = 10_000


def parse_param(spec: str) -> tuple[str, list[Any]]:
    """``key=start:stop:step`` (stop included) or ``key=v1,v2`` -> (key, values)."""
    key, eq, rhs = spec.partition("=")
    key = key.strip()
    if not eq or not key or not rhs.strip():
        raise UserError(f"--param {spec!r}: expected KEY=START:STOP:STEP or KEY=V1,V2,...")
    if ":" in rhs:
        parts = rhs.split(":")
        nums = [parse_value(p) for p in parts]
        if len(parts) != 3 or not all(isinstance(n, int | float) and not isinstance(n, bool)
                                      for n in nums):
            raise UserError(f"--param {spec!r}: a range is START:STOP:STEP with numbers")
        start, stop, step = nums
        if not all(isinstance(n, int) or math.isfinite(n) for n in nums):
            raise UserError(f"--param {spec!r}: START, STOP and STEP must be finite numbers")
        try:
            steps = (stop - start) / step if step else -1.0  # (may overflow to inf)
        except OverflowError:  # integers beyond a float's range
            steps = math.inf
        if steps < 0:
            raise UserError(f"--param {spec!r}: STEP must be non-zero and move towards STOP")
        count = math.floor(steps + 1e-9) + 1 if math.isfinite(steps) else math.inf
        if count > MAX_VALUES:
            raise UserError(f"--param {spec!r}: {count:.6g} values (limit {MAX_VALUES})")
        as_int = all(isinstance(n, int) for n in nums)
        values = [start + k * step if as_int else round(start + k * step, 12)
                  for k in range(count)]
    else:
        values = [parse_value(v) for v in rhs.split(",") if v.strip()]
    if not values:
        raise UserError(f"--param {spec!r}: no values")
    return key, values


def _toml_value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int | float):
        return repr(value)
    if isinstance(value, str):  # a JSON string is a TOML basic string, but for U+007F
        return json.dumps(value, ensure_ascii=False).replace("\x7f", "\\u007f")
    if isinstance(value, list | tuple):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    raise CaseError(f"cannot write {value!r} to TOML")


def dump_toml(data: dict[str, Any]) -> str:
    """A minimal TOML writer for case files (scalars, arrays, nested tables)."""
    lines: list[str] = []

    def table(prefix: str, node: dict[str, Any]) -> None:
        scalars = {k: v for k, v in node.items() if not isinstance(v, dict)}
        tables = {k: v for k, v in node.items() if isinstance(v, dict)}
        if prefix and scalars:
            lines.append(f"[{prefix}]")
        for k, v in scalars.items():
            lines.append(f"{_toml_value(k) if not k.isidentifier() else k} = {_toml_value(v)}")
        for k, v in tables.items():
            name = k if k.replace("_", "a").isalnum() else _toml_value(k)
            table(f"{prefix}.{name}" if prefix else name, v)

    table("", data)
    return "\n".join(lines) + "\n"


def sweep_points(ref: str | Path, params: list[tuple[str, list[Any]]], *,
                 quick: bool = False, overrides: dict[str, Any] | None = None
                 ) -> tuple[list[Case], dict[str, Any]]:
    """The validated cases of a command-line sweep and its description for the manifest."""
    lengths = {len(v) for _, v in params}
    if len(lengths) != 1:
        raise UserError("zipped --param options need the same number of values")
    source = case_path(ref)
    raw = read_toml(source)
    raw.pop("sweep", None)
    if "quick" in raw:
        raw["quick"] = {k: v for k, v in raw["quick"].items() if not k.startswith("sweep.")}
    raw.setdefault("name", source.stem)
    labels = [key.split(".")[-1] for key, _ in params]
    cases = []
    with tempfile.TemporaryDirectory(prefix="contact-vv-sweep-") as tmp:
        path = Path(tmp) / source.name
        path.write_text(dump_toml(raw))
        for k in range(lengths.pop()):
            point = dict(overrides or {})
            point.update({key: values[k] for key, values in params})
            (case,) = load_case(path, quick=quick, overrides=point)
            label = ",".join(f"{lab}={value_label(values[k])}"
                             for lab, (_, values) in zip(labels, params, strict=True))
            if any(c.param == label for c in cases):
                raise UserError(f"--param: repeated sweep point {label}")
            cases.append(case.with_changes(param=label, source=str(source)))
    return cases, {"keys": [key for key, _ in params], "labels": labels,
                   "values": [values for _, values in params]}


def plan_sweep(ref: str | Path, params: list[tuple[str, list[Any]]], solver_names: list[str],
               *, quick: bool = False, overrides: dict[str, Any] | None = None,
               skipped: dict[str, str] | None = None, limits: Limits | None = None,
               explicit: bool = True) -> CasePlan:
    cases, sweep = sweep_points(ref, params, quick=quick, overrides=overrides)
    return plan_case(ref, solver_names, quick=quick, overrides=overrides, skipped=skipped,
                     points=cases, sweep=sweep,
                     dir_name=layout.sweep_dir_name(cases[0].name, [k for k, _ in params]),
                     limits=limits, explicit=explicit)


def check_serial(plan: CasePlan, path: Path, wall: float) -> dict[str, Any]:
    """Re-run a sweep serially into a scratch directory: its wall time against the
    sweep's ``wall``, and whether its summary (but the wall times) and metrics are the
    sweep's; written as ``sweep_check.json`` beside the sweep's results."""
    import json

    import pandas as pd

    from cases.result import atomic_write_text
    from reports.run.runner import execute
    from reports.store import layout

    with tempfile.TemporaryDirectory(prefix="contact-vv-serial-") as tmp:
        t0 = time.perf_counter()
        ref = execute(plan, Path(tmp), executor=serial_executor, progress=False)
        serial = time.perf_counter() - t0
        if ref.failures:
            raise RunFailed(ref.failures)
        a = pd.read_csv(path / layout.SUMMARY).drop(columns="wall_s")
        b = pd.read_csv(ref.path / layout.SUMMARY).drop(columns="wall_s")
        same = a.equals(b) and \
            (path / layout.METRICS).read_bytes() == (ref.path / layout.METRICS).read_bytes()
    check = {"parallel_wall_s": wall, "serial_wall_s": serial, "speedup": serial / wall,
             "identical": bool(same)}
    atomic_write_text(path / layout.SWEEP_CHECK, json.dumps(check, indent=1))
    return check
