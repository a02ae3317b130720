"""The terminal a user or a CI runner has (issue 77, point 5): an output encoding that
cannot show a path (``PYTHONIOENCODING=ascii``, some runners and old terminals) prints it
escaped, exit 0; a reader that goes away (``contact-vv list | head``) ends the command
silently with the SIGPIPE status 141.  Found by these probes: "internal error:
UnicodeEncodeError" after the result was written, and "error: Broken pipe", exit 2."""

from __future__ import annotations

import os
import subprocess
import sys

from reports.cli import PIPE_CLOSED

CLI = [sys.executable, "-m", "reports"]


def test_an_ascii_terminal_and_a_non_ascii_results_directory(tmp_path):
    out = tmp_path / "r\u2603"
    env = {**os.environ, "PYTHONIOENCODING": "ascii"}
    done = subprocess.run([*CLI, "run", "hertz", "--quick", "--solver", "analytic",
                           "--no-progress", "--out", str(out)], capture_output=True,
                          env=env, timeout=300)
    assert done.returncode == 0, done.stderr.decode()
    assert b"r\\u2603" in done.stdout and b"Error" not in done.stderr
    assert (out / "hertz" / "summary.csv").is_file()
    gate = subprocess.run([*CLI, "gate", str(out)], capture_output=True, env=env,
                          timeout=300)
    assert b"internal error" not in gate.stderr and b"r\\u2603" in gate.stdout + gate.stderr


def test_a_reader_that_goes_away_ends_the_command_silently():
    read, write = os.pipe()
    os.close(read)  # as head does after its lines: every write meets a closed pipe
    try:
        done = subprocess.run([*CLI, "list"], stdout=write, stderr=subprocess.PIPE,
                              timeout=300)
    finally:
        os.close(write)
    assert done.returncode == PIPE_CLOSED
    assert done.stderr == b"", done.stderr.decode()
