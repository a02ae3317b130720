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


def test_a_row_that_leaves_the_gate_fails_the_baseline(tmp_path, monkeypatch, capsys):
    """Issue 73, point 4: the baselines hold which metric rows are gated; a change that
    takes a gated row out of the gate (here a declaration in the case file, as any rule
    that ungates rows would) fails ``gate --baseline``, naming the row and its reason, with
    every key number unmoved; a row gated anew does not."""
    from test_cli_run import HERTZ

    fakes.use(monkeypatch, ic="solve_ic", analytic="solve_exact")
    case, out, base = write_case(tmp_path), tmp_path / "res", tmp_path / "baselines"
    run = ["run", "--no-progress", str(case), "--out", str(out)]
    assert main(run) == 0
    assert main(["gate", "--out", str(out), "--update-baseline", str(base)]) == 0
    rows = pd.read_csv(base / "gated" / "small.csv", keep_default_na=False)
    assert list(rows.columns) == ["param", "step", "pair", "quantity", "metric", "gated",
                                  "reason"]
    metrics = pd.read_csv(out / "small" / "metrics.csv")
    assert len(rows) == len(metrics) and rows["gated"].sum() == (metrics["status"] ==
                                                                 "gated").sum()
    capsys.readouterr()
    assert main(["gate", "--out", str(out), "--baseline", str(base)]) == 0

    write_case(tmp_path, HERTZ + '\n[not_converged]\np_max = "seeded: ungated"\n')
    assert main(run) == 0
    capsys.readouterr()
    assert main(["gate", "--out", str(out)]) == 0  # the plain gate cannot see it
    capsys.readouterr()
    assert main(["gate", "--out", str(out), "--baseline", str(base)]) == 1
    lines = [ln for ln in capsys.readouterr().out.splitlines() if ln.startswith("DRIFT")]
    assert lines and all(" p_max rel: gated in the baseline " in ln for ln in lines), lines
    assert all(ln.endswith("not gated now (declared)") for ln in lines), lines
    assert any(" ic-analytic p_max " in ln for ln in lines)

    # the baseline written now holds the row as not gated: the row gated anew passes
    assert main(["gate", "--out", str(out), "--update-baseline", str(base)]) == 0
    write_case(tmp_path)
    assert main(run) == 0
    capsys.readouterr()
    assert main(["gate", "--out", str(out), "--baseline", str(base)]) == 0


def test_a_baseline_without_its_gated_rows_fails(tmp_path, monkeypatch, capsys):
    """A baseline directory written before the gated rows were held (no ``gated/``) fails
    ``gate --baseline`` with how to write them, rather than passing unseen."""
    import shutil

    fakes.use(monkeypatch, ic="solve_ic", analytic="solve_exact")
    case, out, base = write_case(tmp_path), tmp_path / "res", tmp_path / "baselines"
    assert main(["run", "--no-progress", str(case), "--out", str(out)]) == 0
    assert main(["gate", "--out", str(out), "--update-baseline", str(base)]) == 0
    shutil.rmtree(base / "gated")
    capsys.readouterr()
    assert main(["gate", "--out", str(out), "--baseline", str(base)]) == 1
    assert "DRIFT small: no baseline of its gated rows" in capsys.readouterr().out
