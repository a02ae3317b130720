"""Determinism (issue 6, item 1): the same case, version and thread count give
bit-identical results.

- ``halfspace.solve`` twice in one process: every summary scalar except the wall time,
  every surface field, stress plane and table is bit-identical (quick Hertz, one quick
  Cattaneo-Mindlin point, a small dissimilar (coupled K != 0) partial-slip case and a
  short pin-on-disk wear run).
- ``contact-vv run hertz --quick --solver ic,analytic`` in this process and again in a
  subprocess with another ``PYTHONHASHSEED`` (so no result may depend on set or dict
  ordering of strings, object addresses or state left in the process): ``summary.csv``
  is byte-identical once its wall-time column ``wall_s`` is removed (the only column
  that varies, see ``reports/run/runner.py``: the manifest's ``date``, ``wall_s`` and
  ``unit_wall_s`` are not in the CSVs), ``metrics.csv`` and the tables are
  byte-identical, and the arrays of every field file are bit-identical (the ``.npz``
  containers themselves carry zip timestamps, and their ``scalars`` the wall time).
- The manifest records the versions and the thread settings the results depend on.
"""

from __future__ import annotations

import csv
import io
import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import halfspace
from cases.loader import load_case
from cases.result import RunResult
from reports.cli import main

ROOT = Path(__file__).resolve().parent.parent
TIME_COLUMNS = frozenset({"wall_s"})  # summary.csv columns that hold wall-clock times


def same_value(a, b) -> bool:
    """Bitwise equality of scalars, with NaN equal to NaN."""
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return type(a) is type(b) and a == b


def assert_same_run(a: RunResult, b: RunResult) -> None:
    """Two runs of one case agree bit for bit, wall times aside."""
    assert len(a.steps) == len(b.steps)
    for k, (sa, sb) in enumerate(zip(a.steps, b.steps, strict=True)):
        keys = set(sa.scalars) - TIME_COLUMNS
        assert keys == set(sb.scalars) - TIME_COLUMNS
        for key in sorted(keys):
            assert same_value(sa.scalars[key], sb.scalars[key]), (k, key, sa.scalars[key],
                                                                  sb.scalars[key])
        assert sa.surface.keys() == sb.surface.keys()
        for key in sa.surface:
            assert np.array_equal(sa.surface[key], sb.surface[key], equal_nan=True), (k, key)
        assert sa.planes.keys() == sb.planes.keys()
        for name in sa.planes:
            pa, pb = sa.planes[name], sb.planes[name]
            assert np.array_equal(pa.s, pb.s) and np.array_equal(pa.z, pb.z)
            assert pa.fields.keys() == pb.fields.keys()
            for comp in pa.fields:
                assert np.array_equal(pa.fields[comp], pb.fields[comp], equal_nan=True), (
                    k, name, comp)
    assert a.tables.keys() == b.tables.keys()
    for name in a.tables:
        for col in a.tables[name]:
            assert np.array_equal(a.tables[name][col], b.tables[name][col], equal_nan=True), (
                name, col)


CASES = {
    "hertz": lambda: load_case("hertz", quick=True)[0],
    "cattaneo_mindlin": lambda: load_case("cattaneo_mindlin", quick=True,
                                          overrides={"load.Qx": 1.53})[0],
    "dissimilar": lambda: load_case("dissimilar", overrides={
        "grid.nx": 21, "grid.ny": 21, "stress.nz": 5})[0],
    "pin_on_disk": lambda: load_case("pin_on_disk", overrides={
        "grid.nx": 21, "grid.ny": 21, "sliding_wear.step": 4.0,
        "sliding_wear.distance": 40.0, "sliding_wear.output_s": [8.0, 20.0, 40.0],
        "stress.nz": 3, "friction.mu": 0.3})[0],
}


@pytest.mark.parametrize("name", CASES)
def test_solve_twice_is_bit_identical(name):
    """halfspace.solve(case) twice: identical scalars (except wall_s), fields, planes and
    tables, bit for bit."""
    case = CASES[name]()
    assert_same_run(halfspace.solve(case), halfspace.solve(case))


# ---------------------------------------------------------------- the CLI


RUN_ARGS = ["run", "hertz", "--quick", "--solver", "ic,analytic", "--no-progress"]


def csv_without(text: str, drop: frozenset[str]) -> list[list[str]]:
    """The rows of a CSV as raw strings (no parsing of numbers), columns ``drop`` removed."""
    rows = list(csv.reader(io.StringIO(text)))
    keep = [i for i, c in enumerate(rows[0]) if c not in drop]
    return [[row[i] for i in keep] for row in rows]


def npz_arrays(path: Path) -> dict[str, np.ndarray]:
    """The arrays of a field file, its JSON scalars with the wall time removed."""
    with np.load(path) as data:
        out = {k: data[k] for k in data.files if k != "scalars"}
        scalars = json.loads(str(data["scalars"]))
    for key in TIME_COLUMNS:
        scalars.pop(key, None)
    out["scalars"] = np.array(json.dumps(scalars, sort_keys=True))
    return out


@pytest.fixture(scope="module")
def two_cli_runs(tmp_path_factory):
    """`contact-vv run hertz --quick --solver ic,analytic` in this process and in a
    subprocess with a different hash seed; returns the two case directories."""
    base = tmp_path_factory.mktemp("determinism")
    assert main([*RUN_ARGS, "--out", str(base / "a")]) == 0
    env = dict(os.environ, PYTHONHASHSEED="12345")
    proc = subprocess.run([sys.executable, "-m", "reports.cli", *RUN_ARGS, "--out",
                           str(base / "b")], cwd=ROOT, env=env, capture_output=True,
                          text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr
    return base / "a" / "hertz", base / "b" / "hertz"


def test_cli_summary_identical_except_wall_time(two_cli_runs):
    """summary.csv: byte-identical fields in every column but wall_s; the columns that
    vary between runs are exactly the wall-time ones."""
    a, b = (d / "summary.csv" for d in two_cli_runs)
    ta, tb = a.read_text(), b.read_text()
    ra, rb = csv_without(ta, TIME_COLUMNS), csv_without(tb, TIME_COLUMNS)
    assert len(ra) == 3  # header, ic, analytic
    assert ra == rb
    full_a, full_b = csv_without(ta, frozenset()), csv_without(tb, frozenset())
    header = full_a[0]
    varying = {header[i] for i in range(len(header))
               if any(x[i] != y[i] for x, y in zip(full_a[1:], full_b[1:], strict=True))}
    assert varying <= TIME_COLUMNS


def test_cli_metrics_and_tables_byte_identical(two_cli_runs):
    """metrics.csv (and any table CSV) has no time column: byte-identical."""
    a, b = two_cli_runs
    assert (a / "metrics.csv").read_bytes() == (b / "metrics.csv").read_bytes()
    assert len(csv_without((a / "metrics.csv").read_text(), frozenset())) > 1
    tables_a = sorted(p.relative_to(a) for p in (a / "fields").rglob("*.csv"))
    tables_b = sorted(p.relative_to(b) for p in (b / "fields").rglob("*.csv"))
    assert tables_a == tables_b
    for rel in tables_a:
        assert (a / rel).read_bytes() == (b / rel).read_bytes(), rel


def test_cli_fields_bit_identical(two_cli_runs):
    """Every field file holds bit-identical arrays (and scalars, wall time aside)."""
    a, b = two_cli_runs
    files_a = sorted(p.relative_to(a) for p in (a / "fields").rglob("*.npz"))
    files_b = sorted(p.relative_to(b) for p in (b / "fields").rglob("*.npz"))
    assert files_a == files_b and len(files_a) == 2  # ic and analytic, one step each
    for rel in files_a:
        xa, xb = npz_arrays(a / rel), npz_arrays(b / rel)
        assert xa.keys() == xb.keys()
        for key in xa:
            assert xa[key].dtype == xb[key].dtype
            assert np.array_equal(xa[key], xb[key], equal_nan=xa[key].dtype.kind == "f"), (
                rel, key)


def test_manifest_records_versions_and_threads(two_cli_runs):
    """Issue 6 item 1: results record the versions and the thread count, the conditions
    under which they are reproducible: the package versions of the solver's numerical
    stack, and a thread count beyond the machine's CPU count (BLAS/OpenMP pools,
    thread variables or FFT workers)."""
    a, _ = two_cli_runs
    prov = json.loads((a / "manifest.json").read_text())["provenance"]
    versions = prov["versions"]
    for pkg in ("python", "contact-vv", "numpy", "scipy"):
        assert versions.get(pkg), pkg
    threads = {k: v for k, v in prov["threads"].items() if k != "cpu_count"}
    assert threads, ("the manifest records no thread count, only the CPU count: "
                     f"{prov['threads']}")
