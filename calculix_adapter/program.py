"""Running the ``ccx`` program: one job in a scratch directory, on one thread, killed
when the call is interrupted; what its log and status file say.
"""

from __future__ import annotations

import math
import os
import shutil
import subprocess
from pathlib import Path

from .support import PROGRAM


class CalculixFailed(RuntimeError):
    """ccx stopped with an error, or did not converge."""


def ccx(deck: str, workdir: Path) -> tuple[str, float]:
    """Run ``ccx`` on ``deck`` in ``workdir`` (one thread); (its log, CPU seconds).  The
    process is killed if this call is interrupted (a deadline, ^C)."""
    (workdir / "job.inp").write_text(deck)
    env = {**os.environ, "OMP_NUM_THREADS": "1", "CCX_NPROC_EQUATION_SOLVER": "1",
           "CCX_NPROC_STIFFNESS": "1", "CCX_NPROC_RESULTS": "1"}
    log = workdir / "ccx.log"
    with open(log, "wb") as out:
        proc = subprocess.Popen([shutil.which(PROGRAM) or PROGRAM, "-i", "job"],
                                cwd=workdir, stdout=out, stderr=subprocess.STDOUT,
                                stdin=subprocess.DEVNULL, env=env)
        try:
            while True:  # in short waits: a deadline's stop reaches a worker thread
                try:
                    rc = proc.wait(timeout=1.0)
                    break
                except subprocess.TimeoutExpired:
                    continue
        finally:
            if proc.poll() is None:
                proc.kill()
                proc.wait()
    text = log.read_text(errors="replace")
    if rc != 0 or "Job finished" not in text:
        lines = [line.strip() for line in text.splitlines() if line.strip()]
        said = [line for line in lines if "*ERROR" in line] or lines[-4:]
        raise CalculixFailed(f"ccx stopped (exit {rc}): {'; '.join(said[:4])}")
    return text, _total_time(text)


def _total_time(log: str) -> float:
    for line in log.splitlines()[::-1]:
        if "Total CalculiX Time" in line:
            return float(line.split(":")[1])
    return math.nan


def increments(workdir: Path) -> tuple[int, int]:
    """(converged increments, Newton iterations of every attempt) of the run, from its
    ``.sta`` file (a row per attempt; ``U`` marks one that did not converge and was cut
    back)."""
    rows = [line.split() for line in (workdir / "job.sta").read_text().splitlines()[2:]]
    rows = [r for r in rows if len(r) >= 4 and r[0].isdigit()]
    return sum(not r[2].endswith("U") for r in rows), sum(int(r[3]) for r in rows)


def version() -> str:
    """The ``ccx`` version (its ``-v``)."""
    try:
        out = subprocess.run([PROGRAM, "-v"], capture_output=True, text=True, timeout=30,
                             stdin=subprocess.DEVNULL).stdout
    except (OSError, subprocess.SubprocessError):
        return "unknown"
    words = out.split()
    return words[-1] if words else "unknown"
