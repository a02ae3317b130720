"""End-to-end: the real solvers through `contact-vv run`, `report` and `gate` on the quick
Hertz case."""

from __future__ import annotations

import pandas as pd
import pytest

from cases.loader import load_case
from reports.cli import main
from reports.render.pages import report_text


@pytest.fixture(scope="module")
def hertz():
    case = load_case("hertz", quick=True)[0]
    return case, *case.hertz_scales


def run_one(tmp_path, solver: str) -> pd.Series:
    out = tmp_path / "res"
    assert main(["run", "hertz", "--quick", "--no-progress", "--solver", solver,
                 "--out", str(out)]) == 0
    summary = pd.read_csv(out / "hertz" / "summary.csv")
    assert list(summary["solver"]) == [solver]
    return summary.iloc[0]


def test_ic_hertz(tmp_path, hertz):
    case, a0, p0 = hertz
    row = run_one(tmp_path, "ic")
    assert row["converged"]
    # 41 cells over 1.6 mm resolve a0 with 3.8 cells: p_max within 3 %, σ_VM,max
    # (0.620 p0 at 0.48 a0, Johnson 1985) within 2 % and one layer (0.01 mm = 0.07 a0)
    assert row["p_max"] / p0 == pytest.approx(1.0, abs=0.03)
    assert row["vm_max"] / p0 == pytest.approx(0.620, rel=0.02)
    assert row["vm_max_z"] / a0 == pytest.approx(0.48, abs=0.07)
    assert row["P"] == pytest.approx(case.load.P, rel=1e-6)


def test_analytic_hertz(tmp_path, hertz):
    _, a0, p0 = hertz
    row = run_one(tmp_path, "analytic")
    assert row["p_max"] == pytest.approx(p0, rel=1e-9)
    assert row["vm_max"] / p0 == pytest.approx(0.620, rel=0.01)


def test_ic_against_analytic_report_and_gate(tmp_path, capsys):
    out = tmp_path / "res"
    args = ["run", "hertz", "--quick", "--no-progress", "--solver", "ic,analytic",
            "--out", str(out)]
    assert main(args) == 0
    assert main(["report", "--out", str(out)]) == 0
    assert 'id="case-hertz"' in report_text(out)
    assert main(["gate", "--out", str(out)]) == 0
    # a deliberately broken tolerance: the gate fails and names it
    assert main([*args, "--set", "tolerances.p_max=1e-9"]) == 0
    capsys.readouterr()
    assert main(["gate", "--out", str(out)]) == 1
    fails = [ln for ln in capsys.readouterr().out.splitlines() if ln.startswith("FAIL")]
    assert fails and all("ic-analytic p_max rel" in f and "(tolerance key p_max" in f
                         for f in fails)


def test_ic_non_convergence_exits_1(tmp_path, capsys):
    out = tmp_path / "res"
    assert main(["run", "hertz", "--quick", "--no-progress", "--solver", "ic",
                 "--set", "solver.max_iter=2", "--out", str(out)]) == 1
    err = capsys.readouterr().err
    assert "hertz: solver ic did not converge" in err and "residual" in err
    assert not (out / "hertz").exists()


def test_ic_is_deterministic(tmp_path):
    for sub in ("a", "b"):
        assert main(["run", "hertz", "--quick", "--no-progress", "--solver", "ic", "--out",
                     str(tmp_path / sub)]) == 0
    a = pd.read_csv(tmp_path / "a" / "hertz" / "summary.csv").drop(columns="wall_s")
    b = pd.read_csv(tmp_path / "b" / "hertz" / "summary.csv").drop(columns="wall_s")
    pd.testing.assert_frame_equal(a, b, check_exact=True)
