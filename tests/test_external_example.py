"""The worked example of docs/external-results.md runs in one command, and its
conversions (SI units, the file's Y as the depth, a quarter model, Abaqus-style names)
give back the FEM's own rows: the same pressure rows against the closed forms as the FEM
run on the same case, to round-off."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pandas as pd
import pytest

from reports.cli import main

pytestmark = pytest.mark.fem
EXAMPLE = Path(__file__).resolve().parents[1] / "docs/examples/external_results/run_example.py"


def test_the_example_runs_and_reads_the_fem_back(tmp_path):
    spec = importlib.util.spec_from_file_location("run_example", EXAMPLE)
    example = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(example)
    assert example.main([str(tmp_path)]) == 0
    case = tmp_path / "hertz_other_code.toml"
    assert main(["run", str(case), "--quick", "--no-progress", "--solver", "fem,analytic",
                 "--out", str(tmp_path / "fem")]) == 0
    rows = pd.concat([pd.read_csv(tmp_path / d / "hertz_other_code" / "metrics.csv")
                      for d in ("results", "fem")])
    key = ["quantity", "metric"]
    ext = rows[rows.pair == "external:my_fe-analytic"].set_index(key).value
    fem = rows[rows.pair == "fem-analytic"].set_index(key).value
    for q in [("p_n", "l2"), ("p_n", "max"), ("p_max", "rel")]:
        assert abs(ext[q] - fem[q]) < 1e-9, q
    assert len(ext) >= 12
