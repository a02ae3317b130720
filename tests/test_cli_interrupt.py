"""Interrupted runs (SIGKILL, SIGINT) never leave results that look complete, and a
re-run restarts cleanly without mixing files of two runs."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from test_cli_run import SWEEP, write_case

from reports.cli import main
from reports.store import layout, manifest
from reports.store.results import scan

TESTS = Path(__file__).resolve().parent
ROOT = TESTS.parent
DRIVER = f"""
import signal, sys
# Ctrl-C as in a terminal, whatever this test runs under: a shell that started it in the
# background leaves SIGINT ignored, and that disposition is inherited across exec
signal.signal(signal.SIGINT, signal.default_int_handler)
sys.path[:0] = [{str(ROOT)!r}, {str(TESTS)!r}]
from reports.registry import solvers
import test_cli_fakes
solvers.REGISTRY = test_cli_fakes.registry(ic="IC_SOLVER", analytic="solve_exact")
from reports.cli import main
sys.exit(main(sys.argv[1:]))
"""


def start(case: Path, out: Path, sleep: float, ic: str = "solve_slow") -> subprocess.Popen:
    env = dict(os.environ, FAKE_SLEEP=str(sleep))
    return subprocess.Popen([sys.executable, "-c", DRIVER.replace("IC_SOLVER", ic), "run",
                             "--no-progress", str(case), "--out", str(out)], env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def wait_for(path: Path, proc: subprocess.Popen, timeout: float = 60.0) -> None:
    t0 = time.monotonic()
    while not path.exists():
        assert proc.poll() is None, proc.communicate()
        assert time.monotonic() - t0 < timeout, f"{path} never appeared"
        time.sleep(0.05)


@pytest.mark.parametrize("sig", [signal.SIGKILL, signal.SIGINT])
def test_killed_run_restarts_cleanly(tmp_path, sig, monkeypatch):
    import test_cli_fakes as fakes

    fakes.use(monkeypatch, ic="solve_ic", analytic="solve_exact")
    case = write_case(tmp_path, SWEEP)
    out = tmp_path / "res"
    # a complete earlier run
    assert main(["run", "--no-progress", str(case), "--out", str(out)]) == 0
    old_id = manifest.read(out / "small")["provenance"]["date"]

    # a second run, killed after its first unit was written
    proc = start(case, out, 1.5)
    staging = layout.staging_dir(out, "small")
    wait_for(staging / "fields" / "ic" / "mu=0.25" / "step_0000.npz", proc)
    proc.send_signal(sig)
    code = proc.wait(60)
    _, err = proc.communicate()
    if sig == signal.SIGINT:
        assert code == 130 and "interrupted" in err and "Traceback" not in err
    else:
        assert code == -signal.SIGKILL
    # nothing looks complete: the old result was withdrawn when the new run started
    assert not (out / "small").exists()
    found = scan(out)
    assert not found.complete and "interrupted" in found.incomplete["small"]
    assert main(["gate", "--out", str(out)]) == 1

    # the re-run (stale staging area of a dead process) restarts and completes
    assert main(["run", "--no-progress", str(case), "--out", str(out)]) == 0
    assert not staging.exists()
    mf = manifest.read(out / "small")
    assert mf["provenance"]["date"] >= old_id
    files = {p.relative_to(out / "small").as_posix()
             for p in (out / "small").rglob("*") if p.is_file()}
    assert files == set(mf["files"]) | {"manifest.json"}  # no stray file of another run
    assert main(["gate", "--out", str(out)]) == 0


LOCK_HOLDER = """
import fcntl, os, sys, time
fh = open(sys.argv[1], "a+")
fcntl.flock(fh, fcntl.LOCK_EX)
fh.seek(0); fh.truncate(); fh.write(str(os.getpid())); fh.flush()
print("locked", flush=True)
time.sleep(30)
"""


def test_a_live_run_is_not_disturbed(tmp_path, monkeypatch, capsys):
    """A process holding the case's lock is a live run: a second run of the same case is
    refused with its pid and touches neither its staging directory nor its result."""
    import test_cli_fakes as fakes

    fakes.use(monkeypatch, ic="solve_ic")
    out = tmp_path / "res"
    staging = layout.staging_dir(out, "small")
    (staging / "fields").mkdir(parents=True)
    (out / "small").mkdir()
    (out / "small" / "summary.csv").write_text("kept")
    holder = subprocess.Popen([sys.executable, "-c", LOCK_HOLDER,
                               str(layout.lock_file(out, "small"))], stdout=subprocess.PIPE,
                              text=True)
    try:
        assert holder.stdout.readline().strip() == "locked"
        assert main(["run", "--no-progress", str(write_case(tmp_path)), "--out",
                     str(out)]) == 2
        assert f"another contact-vv run (pid {holder.pid}) is writing case small" in \
            capsys.readouterr().err
        assert (staging / "fields").is_dir()
        assert (out / "small" / "summary.csv").read_text() == "kept"
    finally:
        holder.kill()
        holder.wait()
    # the lock dies with its holder: the next run takes over, completes and removes the
    # lock file it held (the holder wrote nothing else into it)
    assert main(["run", "--no-progress", str(write_case(tmp_path)), "--out", str(out)]) == 0
    assert not staging.exists()
    assert not layout.lock_file(out, "small").exists()


def test_a_lock_file_a_run_did_not_write_is_kept(tmp_path, monkeypatch):
    """A file at the lock's name holding anything but a pid is not a run's: kept."""
    import test_cli_fakes as fakes

    fakes.use(monkeypatch, ic="solve_ic")
    out = tmp_path / "res"
    out.mkdir()
    lock = layout.lock_file(out, "small")
    lock.write_text("my notes")
    assert main(["run", "--no-progress", str(write_case(tmp_path)), "--out", str(out)]) == 0
    assert lock.exists()


def test_finished_output_steps_are_kept_and_the_rerun_says_it_restarts(tmp_path, monkeypatch,
                                                                       capsys):
    """Issue 3 item 5: a solver that hands over its output steps as it goes (on_output)
    has each one written into the staging directory at once; a killed run keeps them
    there, and the re-run says that it discards them and restarts."""
    import test_cli_fakes as fakes

    from cases.result import load_step

    case = write_case(tmp_path, SWEEP)
    out = tmp_path / "res"
    proc = start(case, out, 0.7, ic="solve_streaming")
    staging = layout.staging_dir(out, "small")
    unit = layout.unit_dir(staging, "ic", "mu=0.25")
    wait_for(unit / "step_0001.npz", proc)
    proc.send_signal(signal.SIGKILL)
    proc.wait(60)
    proc.communicate()
    kept = sorted(p.name for p in unit.glob("step_*.npz"))
    assert kept[:2] == ["step_0000.npz", "step_0001.npz"]
    assert not (staging / layout.SUMMARY).exists()  # the unit never finished
    step = load_step(unit / "step_0001.npz")
    assert step.scalars["step"] == 1 and step.scalars["p_max"] > 0

    fakes.use(monkeypatch, ic="solve_ic", analytic="solve_exact")
    assert main(["run", "--no-progress", str(case), "--out", str(out)]) == 0
    err = capsys.readouterr().err
    assert "holds an interrupted run of small" in err
    assert f"({len(kept)} output step file(s) kept)" in err
    assert "restarting small from the beginning" in err
    assert not staging.exists() and (out / "small" / layout.SUMMARY).exists()


@pytest.mark.parametrize("stagger", [0.0, 0.3])
def test_two_runs_of_one_case_started_together(tmp_path, stagger):
    """Two runs of one case at once: each ends with a complete, consistent case directory
    or with one clear refusal, never with files of both or a result deleted under it."""
    case = write_case(tmp_path, SWEEP)
    out = tmp_path / "res"
    first = start(case, out, 0.4)
    time.sleep(stagger)
    second = start(case, out, 0.4)
    outcomes = [p.communicate(timeout=120) + (p.returncode,) for p in (first, second)]
    codes = sorted(code for _, _, code in outcomes)
    assert codes in ([0, 0], [0, 2]), outcomes
    for _, err, code in outcomes:
        assert "Traceback" not in err
        if code == 2:
            assert "another contact-vv run (pid" in err and "is writing case small" in err
    mf = manifest.read(out / "small")  # verifies every file's hash against the manifest
    files = {p.relative_to(out / "small").as_posix()
             for p in (out / "small").rglob("*") if p.is_file()}
    assert files == set(mf["files"]) | {"manifest.json"}
    assert not layout.staging_dir(out, "small").exists()
    assert main(["gate", "--out", str(out)]) == 0
