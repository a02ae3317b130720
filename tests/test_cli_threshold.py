"""``contact-vv threshold``: the table it prints, DIR/thresholds.csv (merged between runs),
the report's Thresholds table, the fretting β threshold, and bad input (exit 2, the key
or cause named)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
import test_cli_fakes as fakes

from reports.cli import main
from reports.render.pages import report_text
from reports.store.readers import read_result, read_thresholds

SLIDING = ["threshold", "sliding_friction", "--param", "friction.mu", "--event",
           "vm_max_on_surface", "--quick", "--no-progress"]


def test_sliding_threshold_table_csv_and_report(tmp_path, capsys):
    out = tmp_path / "res"
    argv = [*SLIDING, "--solver", "ic,analytic", "--range", "0.25", "0.45",
            "--resolution", "0.025", "--out", str(out)]
    assert main(argv) == 0
    text = capsys.readouterr().out
    assert "threshold of vm_max_on_surface in friction.mu for sliding_friction (quick)" in text
    for needle in ("ic        -          41x41", "ic        -          27x27",
                   "analytic  -          exact", "grid dependence ic: "):
        assert needle in text
    table = read_result(out / "thresholds.csv", read_thresholds)
    assert list(table["solver"]) == ["ic", "ic", "analytic", "analytic", "analytic"]
    assert list(table["grid"]) == ["41x41", "27x27", "exact", "41x41", "27x27"]
    bisected = table[table["status"].str.startswith("bisected")]
    assert (bisected["hi"] - bisected["lo"] <= 0.025 + 1e-12).all()
    # 0.2 wide: 3 halvings to <= 0.025 and both ends on the case grid; the coarser grid's
    # search starts in that interval, where its threshold is too: its two ends
    assert list(bisected["evaluations"]) == [2 + 3, 2, 2 + 3, 2]
    assert (bisected.groupby("solver")["threshold"].nunique() == 1).all()
    assert (table["at"] == "step=0").all()
    exact = table[table["grid"] == "exact"].iloc[0]
    assert exact["threshold"] == pytest.approx(0.3047, abs=1e-4)
    ic = table[table["solver"] == "ic"]
    assert ic["grid_shift"].tolist()[0] == 0.0

    # a second run replaces its own rows and keeps the others
    assert main([*SLIDING, "--solver", "ic", "--range", "0.25", "0.45", "--resolution",
                 "0.05", "--grids", "1", "--out", str(out)]) == 0
    again = read_result(out / "thresholds.csv", read_thresholds)
    assert len(again) == 5
    assert again[again["solver"] == "ic"]["resolution"].tolist() == [0.025, 0.05]

    assert main(["report", "--out", str(out)]) == 0
    html = report_text(out)
    assert '<h2 id="thresholds">Thresholds</h2><div class="thresholds">' in html
    assert "Hamilton (1983)" in html


def test_fretting_beta_threshold_with_the_halfspace_solver(tmp_path, capsys):
    """Quick fretting_orthotropic after 1000 cycles (two simulated cycles of the jump
    500): gross slip at β = 60°, partial slip at 90° (μ2 = 0.65 along x, docs/cases.md,
    case 6); 3 solver runs."""
    out = tmp_path / "res"
    assert main(["threshold", "fretting_orthotropic", "--param", "friction.beta",
                 "--event", "gross_to_partial_slip", "--quick", "--no-progress",
                 "--solver", "ic,analytic",
                 "--range", "60", "90", "--resolution", "20", "--grids", "1",
                 "--set", "fretting.cycles=1000", "--set", "fretting.output_cycles=[1000]",
                 "--at", "1000", "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "at cycle=1000" in text
    table = read_result(out / "thresholds.csv", read_thresholds).set_index("solver")
    ic = table.loc["ic"]
    assert ic["status"] == ("bisected: gross slip (no stick) at lower friction.beta, "
                            "partial slip (stick cells) at higher")
    assert (ic["lo"], ic["hi"], ic["evaluations"]) == (75.0, 90.0, 3)
    assert table.loc["analytic", "status"].startswith("unsupported: no closed-form")


@pytest.mark.fem
def test_fem_threshold_on_a_coarse_grid(tmp_path, capsys):
    """The FEM path, on the quick case's mesh coarsened by 1.5 and a 0.1 bracket
    (3 FEM runs of ~4 s): its threshold matches the half-space solver's on the quick
    grids (0.355 ± 0.004 on every grid of both, see reports/README.md)."""
    out = tmp_path / "res"
    assert main([*SLIDING, "--solver", "fem", "--range", "0.3", "0.4", "--resolution",
                 "0.05", "--grids", "1/1.5", "--out", str(out)]) == 0
    fem = read_result(out / "thresholds.csv", read_thresholds).iloc[0]
    assert fem["grid"] == "fem.h=0.1875" and fem["evaluations"] == 3
    assert (fem["lo"], fem["hi"]) == (0.35, 0.4)


@pytest.mark.parametrize(("extra", "needle"), [
    (["--param", "friction.foo"], "--param 'friction.foo': not a case key"),
    (["--param", "grid.nx"], "--param 'grid.nx': not a real-valued case key"),
    (["--param", "load.P"], "--param load.P: no default bracket; give --range"),
    (["--event", "vm_nowhere"], "--event 'vm_nowhere': unknown event"),
    (["--event", "gross_to_partial_slip"],
     "event gross_to_partial_slip does not apply to case sliding_friction (kind 'static'"),
    (["--range", "0", "0.1"], "--param friction.mu: event vm_max_on_surface does not "
     "change over [0, 0.1] (ic 41x41: max σ_VM below the surface at both ends"),
    (["--range", "-1", "1"], "--param friction.mu = -1: friction.mu1 = -1.0"),
    (["--resolution", "0"], "--resolution 0: needs 0 < R"),
    (["--grids", "1,zero"], "--grids '1,zero': 'zero' is not a number"),
    (["--at", "cycle=x"], "--at 'cycle=x': 'x' is not a number"),
    (["--at", "5"], "--at 5: case sliding_friction has no output step at step = 5"),
    (["--set", "friction.mu=0.3"], "--set friction.mu: the key is the one --param bisects"),
    (["--surface-depth", "-1"], "--surface-depth must be a finite number >= 0"),
])
def test_bad_input_is_named(tmp_path, capsys, extra, needle):
    argv = [*SLIDING, "--solver", "ic", "--out", str(tmp_path / "res")]
    if extra[0] in argv:  # --param, --event: replace the value
        argv[argv.index(extra[0]) + 1] = extra[1]
    else:
        argv += extra
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("contact-vv: error: ") and needle in err, err
    assert not (tmp_path / "res" / "thresholds.csv").exists()


def test_damaged_thresholds_file_is_not_overwritten(tmp_path, capsys):
    out = tmp_path / "res"
    out.mkdir()
    (out / "thresholds.csv").write_text("not,a\nthresholds,table\n")
    assert main([*SLIDING, "--solver", "analytic", "--range", "0.2", "0.4", "--resolution",
                 "0.1", "--grids", "1", "--out", str(out)]) == 2
    assert "thresholds.csv: missing column(s)" in capsys.readouterr().err
    assert (out / "thresholds.csv").read_text() == "not,a\nthresholds,table\n"
    assert pd.read_csv(out / "thresholds.csv").shape == (1, 2)


def test_solver_failures(tmp_path, monkeypatch, capsys):
    """A solver that does not converge: a ``failed`` row, written, exit 1; one that
    rejects the case (the contact reaches the grid edge): exit 2 naming where."""
    out = tmp_path / "res"
    fakes.use(monkeypatch, ic="solve_diverging")
    assert main([*SLIDING, "--solver", "ic", "--grids", "1", "--out", str(out)]) == 1
    assert "contact-vv: error: ic 41x41: failed: Uzawa iteration did not converge" in \
        capsys.readouterr().err
    row = read_result(out / "thresholds.csv", read_thresholds).iloc[0]
    assert row["status"].startswith("failed: ") and pd.isna(row["threshold"])
    fakes.use(monkeypatch, ic="solve_edge")
    assert main([*SLIDING, "--solver", "ic", "--grids", "1", "--out", str(out)]) == 2
    assert ("contact-vv: error: solver ic at friction.mu = 0 on 41x41: the contact area "
            "reaches the edge") in capsys.readouterr().err


@pytest.mark.parametrize("resolution", ["1e-300", "5e-324", "1e-17"])
def test_a_resolution_below_the_float_spacing_ends(tmp_path, capsys, resolution):
    """The bisection stops at two adjacent floats: about 54 halvings of [0.2, 0.4], not
    an endless loop."""
    out = tmp_path / "res"
    assert main([*SLIDING, "--solver", "analytic", "--grids", "1", "--range", "0.2", "0.4",
                 "--resolution", resolution, "--out", str(out)]) == 0
    row = read_result(out / "thresholds.csv", read_thresholds).iloc[-1]
    assert row["status"].startswith("bisected")
    assert float(row["hi"]) == np.nextafter(float(row["lo"]), 1.0)
    assert row["evaluations"] <= 2 + 60


def test_no_named_solver_can_say_is_refused(tmp_path, capsys):
    """Named solvers none of which can locate the event on the case (a closed form with
    scalars only, for a σ_VM event): exit 2 naming each one's reason and nothing written,
    as ``run`` refuses a case none of its solvers runs (at bf2adeb: exit 0, a table of
    ``n/a``)."""
    out = tmp_path / "res"
    assert main(["threshold", "spence", "--param", "friction.mu", "--event",
                 "vm_max_on_surface", "--range", "0.1", "0.6", "--quick", "--no-progress",
                 "--solver", "analytic", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert "none of the solvers analytic can locate vm_max_on_surface" in err
    assert "analytic: n/a: the result has no σ_VM plane" in err
    assert not (out / "thresholds.csv").exists()
