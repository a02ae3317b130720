"""Regression baselines: explicit update, drift detection, missing rows."""

from __future__ import annotations

import pandas as pd
import test_cli_fakes as fakes
from test_cli_run import write_case

from reports.cli import main


def test_baseline_update_and_drift(tmp_path, monkeypatch, capsys):
    fakes.use(monkeypatch, ic="solve_ic", analytic="solve_exact")
    case, out, base = write_case(tmp_path), tmp_path / "res", tmp_path / "baselines"
    run = ["run", "--no-progress", str(case), "--out", str(out)]
    assert main(run) == 0
    assert main(["gate", "--out", str(out), "--baseline", str(base)]) == 2  # none yet
    assert "--update-baseline" in capsys.readouterr().err
    assert main(["gate", "--out", str(out), "--update-baseline", str(base)]) == 0
    stored = pd.read_csv(base / "small.csv")
    assert list(stored.columns[:4]) == ["case", "solver", "param", "step"]
    assert list(stored["solver"]) == ["analytic", "ic"]  # sorted rows
    capsys.readouterr()
    assert main(["gate", "--out", str(out), "--baseline", str(base)]) == 0

    # the "ic" solver drifts by 1e-5 relative: caught at the default 1e-6, not at 1e-4
    monkeypatch.setattr(fakes, "ERROR", fakes.ERROR + 1.02e-5)
    assert main(run) == 0
    capsys.readouterr()
    assert main(["gate", "--out", str(out), "--baseline", str(base)]) == 1
    lines = [ln for ln in capsys.readouterr().out.splitlines() if ln.startswith("DRIFT")]
    assert any(ln.startswith("DRIFT small ic [] step 0 p_max:") and "relative 1e-05" in ln
               for ln in lines), lines
    assert all(" ic " in ln for ln in lines)  # the analytic rows did not move
    assert main(["gate", "--out", str(out), "--baseline", str(base), "--drift", "1e-4"]) == 0

    # a result row that disappeared is a failure too
    fakes.use(monkeypatch, ic="solve_ic")
    assert main([*run, "--solver", "ic"]) == 0
    capsys.readouterr()
    assert main(["gate", "--out", str(out), "--baseline", str(base), "--drift", "1e-4"]) == 1
    assert "DRIFT small analytic [] step 0: baseline row missing from the results" in \
        capsys.readouterr().out
