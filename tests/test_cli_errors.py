"""User errors: a clear `contact-vv: error: <message>` naming the problem, exit 2, no
traceback; run in a subprocess to see exactly what a user sees."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest
import test_cli_fakes as fakes
from test_cli_run import HERTZ, write_case

from reports.cli import main

ROOT = Path(__file__).resolve().parent.parent


def cli(*argv: str, cwd: Path | None = None) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "reports", *argv], capture_output=True,
                          text=True, cwd=cwd or ROOT, timeout=120,
                          env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"})


@pytest.mark.parametrize(("edit", "needle"), [
    (lambda t: t.replace("[geometry]", "[geometry]\nRadius = 5.0"),
     "unknown key 'geometry.Radius'"),
    (lambda t: t.replace("nu = 0.3", "nu = 0.5", 1), "materials.a.nu = 0.5"),
    (lambda t: t.replace("P = 10.2", "P = -10.2"), "load.P = -10.2"),
    (lambda t: t.replace("Lx = 1.6", "Lx = 0.2"), "grid.Lx = 0.2 mm: the expected contact"),
    (lambda t: t + "[tolerances]\np_maxx = 0.1\n", "unknown tolerance key 'p_maxx'"),
    (lambda t: t + '[tolerances]\n"ic-fm.p_max" = 0.1\n', "'ic-fm' is not a compared pair"),
    (lambda t: t.replace("nx = 21", "nx = 21.5"), "grid.nx = 21.5: must be an integer"),
    (lambda t: t.replace("[load]", "[load"), "malformed TOML"),
])
def test_invalid_case_file_is_named(tmp_path, edit, needle):
    case = write_case(tmp_path, edit(HERTZ), name="bad")
    proc = cli("run", str(case), "--out", str(tmp_path / "r"), "--solver", "ic")
    # the solver may not have landed: validation comes first either way
    assert proc.returncode == 2, proc.stderr
    assert proc.stderr.startswith("contact-vv: error: "), proc.stderr
    assert needle in proc.stderr
    assert "Traceback" not in proc.stderr
    assert not (tmp_path / "r" / "bad").exists()


def test_grid_edge_detected_by_the_solver_is_a_user_error(tmp_path, monkeypatch, capsys):
    fakes.use(monkeypatch, ic="solve_edge")
    assert main(["run", "--no-progress", str(write_case(tmp_path)), "--out",
                 str(tmp_path / "r")]) == 2
    err = capsys.readouterr().err
    assert "solver ic rejected the case: the contact area reaches the edge" in err


@pytest.mark.parametrize(("argv", "needle"), [
    (["run", "no_such_case"], "unknown case 'no_such_case'; bundled cases:"),
    (["run", "hertzz"], "unknown case 'hertzz' (did you mean 'hertz'?); bundled cases:"),
    (["run"], "run needs at least one CASE or --all"),
    (["run", "hertz", "--solver", "icc"], "unknown solver(s) icc"),
    (["run", "hertz", "--set", "grid.nx"], "--set 'grid.nx': expected KEY=VALUE"),
    (["frobnicate"], "argument COMMAND: invalid choice: 'frobnicate'"),
    (["run", "hertz", "--bogus"], "unrecognized arguments: --bogus"),
    (["gate", "--out", "/nonexistent/results"], "results directory /nonexistent/results "
                                                 "does not exist"),
    (["report", "--out", "/nonexistent/results"], "results directory /nonexistent/results "
                                                   "does not exist"),
    (["sweep", "hertz", "--param", "friction.mu"],
     "--param 'friction.mu': expected KEY=START:STOP:STEP"),
    (["sweep", "hertz", "--param", "friction.mu=0:1:0"],
     "--param 'friction.mu=0:1:0': STEP must be non-zero"),
])
def test_usage_errors(argv, needle, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert f"contact-vv: error: {needle}" in err


def test_unwritable_output_is_a_clear_error(tmp_path, monkeypatch, capsys):
    fakes.use(monkeypatch, ic="solve_ic")
    blocker = tmp_path / "file"
    blocker.write_text("not a directory")
    assert main(["run", "--no-progress", str(write_case(tmp_path)), "--out",
                 str(blocker / "res")]) == 2
    assert f"contact-vv: error: Not a directory: {blocker / 'res'}" in capsys.readouterr().err


def test_unavailable_solver_is_reported_clearly(tmp_path, monkeypatch, capsys):
    fakes.use(monkeypatch, analytic="solve_exact")  # ic and fem "not landed"
    assert main(["run", str(write_case(tmp_path)), "--solver", "ic,analytic"]) == 2
    err = capsys.readouterr().err
    assert "contact-vv: error: solver 'ic' is not available: cannot import no_such_module_xyz" \
        in err


def test_no_traceback_from_the_console_entry_for_an_unknown_case(tmp_path):
    proc = cli("run", "nope", cwd=tmp_path)
    assert proc.returncode == 2 and "Traceback" not in proc.stderr
    assert "unknown case 'nope'" in proc.stderr


def test_list_shows_cases_and_solvers(capsys):
    assert main(["list"]) == 0
    out = capsys.readouterr().out
    assert "hertz" in out and "static" in out
    # the sweep points at both sizes: sliding_friction's six, and two with --quick
    assert "sliding_friction" in out and "6|2 pt" in out.split("sliding_friction", 1)[1][:40]
    assert "solver ic" in out and "solver analytic" in out


def test_a_results_directory_that_is_a_file_is_named(tmp_path, capsys):
    path = tmp_path / "afile"
    path.write_text("mine")
    assert main(["run", "hertz", "--quick", "--out", str(path)]) == 2
    assert f"results directory {path} is a file, not a directory" in capsys.readouterr().err
    assert path.read_text() == "mine"
