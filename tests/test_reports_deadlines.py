"""A deadline stops a hung run, never a slow one (issues 31, 59 and 62,
reports/run/deadline.py): a solver that spends more CPU time than its calibrated budget,
or that makes no progress, is stopped and its run fails naming the reason, in ``run``
(serially or in a Dask worker), ``sweep --workers 0`` and ``threshold``; a run that a
busy machine stretches over many times its budget in wall time, while computing,
finishes; ``--time-factor`` scales the budget for a slower processor; the real solvers'
estimates are calibrated (finite deadlines), the closed form's are not.
"""

from __future__ import annotations

import math
import threading
import time
from dataclasses import replace

import numpy as np
import pytest
import test_cli_fakes as fakes
from test_cli_hostile_inputs import TINY, _answer

from cases.loader import load_case
from reports.registry import solvers
from reports.run import deadline
from reports.run.plan import Limits

STOPPED = "was stopped: the run ran past its deadline of"
HUNG = "the run made no progress"
CASE = TINY.replace("nx = 11\nny = 11", "nx = 21\nny = 21")  # coarsened twice by 1.5


def _fake(monkeypatch, ic: str, allowance: float = 0.3) -> None:
    """ic: the fake ``ic`` with an estimate of 0.01 s, factor 1; every run may spend
    ``allowance`` seconds of CPU time beyond it; the watchdog looks every 0.05 s and
    calls a run hung after 1 s under 1 % of a core."""
    fakes.use(monkeypatch, ic=ic, analytic="solve_exact")
    monkeypatch.setitem(solvers.REGISTRY, "ic", replace(solvers.REGISTRY["ic"],
                                                        estimate_attr="estimate_tiny"))
    monkeypatch.setattr(deadline, "ALLOWANCE_S", allowance)
    monkeypatch.setattr(deadline, "TICK_S", 0.05)
    monkeypatch.setattr(deadline, "STALL_S", 1.0)


@pytest.fixture
def slow(monkeypatch):
    """A fake ic that computes for FAKE_SLEEP = 30 s of CPU time."""
    _fake(monkeypatch, "solve_busy")
    monkeypatch.setenv("FAKE_SLEEP", "30")


@pytest.mark.parametrize("command", [
    ["run", "{case}"],
    ["sweep", "{case}", "--param", "grid.nx=21,23", "--workers", "0"],
    ["run", "{case}", "--convergence"],
    ["run", "{case}", "--workers", "2"],  # in a Dask worker's thread (reports/run/cluster.py)
])
def test_a_run_past_its_deadline_is_stopped(tmp_path, capsys, slow, command):
    (tmp_path / "c.toml").write_text(CASE)
    argv = [a.replace("{case}", str(tmp_path / "c.toml")) for a in command]
    t0 = time.perf_counter()
    code, err = _answer([*argv, "--solver", "ic,analytic", "--no-progress", "--out",
                         str(tmp_path / "o")], capsys)
    assert time.perf_counter() - t0 < 10.0  # stopped, not slept out (30 s per run)
    assert code == 1, err
    budget = deadline.seconds(0.01, 1.0)  # 0.3 s + 0.01 s x max(cores, 2)
    assert STOPPED in err and f"{budget:.3g} s of CPU time" in err, err


@pytest.mark.parametrize("command", [
    ["run", "{case}"],
    ["sweep", "{case}", "--param", "grid.nx=21,23", "--workers", "0"],
])
def test_a_hung_run_is_stopped_and_says_so(tmp_path, capsys, monkeypatch, command):
    """A solver that sleeps forever spends no CPU time: the watchdog stops it all the
    same, after STALL_S of no progress."""
    _fake(monkeypatch, "solve_slow")
    monkeypatch.setenv("FAKE_SLEEP", "1e6")
    (tmp_path / "c.toml").write_text(CASE)
    argv = [a.replace("{case}", str(tmp_path / "c.toml")) for a in command]
    t0 = time.perf_counter()
    code, err = _answer([*argv, "--solver", "ic,analytic", "--no-progress", "--out",
                         str(tmp_path / "o")], capsys)
    assert time.perf_counter() - t0 < 20.0
    assert code == 1, err
    assert HUNG in err and "stopped as hung" in err, err


def test_a_slow_run_on_a_busy_machine_finishes(tmp_path, capsys, monkeypatch):
    """Issue 59: a run that gets one part in eight of a core (a busy machine) takes eight
    times its CPU time in wall time: past a wall-clock deadline, within its CPU budget,
    and never mistaken for a hung one."""
    _fake(monkeypatch, "solve_crowded", allowance=1.5)
    monkeypatch.setenv("FAKE_SLEEP", "0.4")
    monkeypatch.setenv("FAKE_STRETCH", "8")
    (tmp_path / "c.toml").write_text(TINY)
    t0 = time.perf_counter()
    code, err = _answer(["run", str(tmp_path / "c.toml"), "--solver", "ic,analytic",
                         "--no-progress", "--out", str(tmp_path / "o")], capsys)
    wall = time.perf_counter() - t0
    assert code == 0, err
    assert wall > deadline.seconds(0.01, 1.0)  # a wall-clock deadline would have stopped it


def test_a_threshold_past_its_deadline_is_a_failed_row(tmp_path, capsys, slow):
    t0 = time.perf_counter()
    code, err = _answer(["threshold", "sliding_friction", "--param", "friction.mu", "--event",
                         "vm_max_on_surface", "--quick", "--solver", "ic", "--grids", "1",
                         "--range", "0.2", "0.4", "--resolution", "0.1", "--no-progress",
                         "--out", str(tmp_path / "o")], capsys)
    assert time.perf_counter() - t0 < 10.0
    assert code == 1 and "ran past its deadline" in err, err


def test_the_time_factor_scales_the_deadline(tmp_path, capsys, slow, monkeypatch):
    monkeypatch.setenv("FAKE_SLEEP", "2")
    (tmp_path / "c.toml").write_text(TINY)
    argv = ["run", str(tmp_path / "c.toml"), "--solver", "ic,analytic", "--no-progress"]
    code, err = _answer([*argv, "--out", str(tmp_path / "o1")], capsys)
    assert code == 1 and STOPPED in err, err
    code, err = _answer([*argv, "--out", str(tmp_path / "o2"), "--time-factor", "1000"], capsys)
    assert code == 0, err  # 0.3 s + 1000 x 0.01 s x max(cores, 2)
    code, err = _answer([*argv, "--out", str(tmp_path / "o3"), "--time-factor", "0"], capsys)
    assert code == 2 and "--time-factor must be a positive number" in err, err


def test_the_alarm_stops_a_computation_and_is_then_cleared():
    with pytest.raises(deadline.Overrun, match="busy ran past its deadline of 0.2 s"):
        with deadline.deadline(0.2, "busy"):
            x = np.ones(1000)
            while True:
                x = np.sqrt(x * x)
    with deadline.deadline(0.2, "quick"):
        pass
    time.sleep(0.3)  # no alarm left behind
    with deadline.deadline(math.inf, "unlimited"):
        time.sleep(0.05)


def test_a_block_without_progress_is_stopped(monkeypatch):
    monkeypatch.setattr(deadline, "TICK_S", 0.05)
    monkeypatch.setattr(deadline, "STALL_S", 0.5)
    t0 = time.perf_counter()
    with pytest.raises(deadline.Overrun, match="waiting made no progress: .* stopped as hung"):
        with deadline.deadline(math.inf, "waiting"):
            time.sleep(60)
    assert time.perf_counter() - t0 < 5.0
    with deadline.deadline(math.inf, "working"):  # computing is progress
        x = np.ones(1000)
        t0 = time.perf_counter()
        while time.perf_counter() - t0 < 1.5:
            x = np.sqrt(x * x)


def test_the_budget_counts_cpu_time_not_wall_time(monkeypatch):
    """Sleeping spends no budget; the budget is CPU time over the cores the estimate's
    wall time may have used."""
    monkeypatch.setattr(deadline, "TICK_S", 0.05)
    with deadline.deadline(0.3, "sleeping"):
        time.sleep(0.8)
    d = deadline.seconds(1.0, 2.0, 3.0)
    assert d == pytest.approx(deadline.ALLOWANCE_S
                              + 6.0 * max(deadline.cores(), deadline.CALIBRATION_CORES))


def test_an_enclosing_deadline_still_stops_the_block(monkeypatch):
    """The inner deadline's alarm hands an alarm that is not its own to the enclosing
    one, so a nested run cannot swallow its caller's stop."""
    monkeypatch.setattr(deadline, "TICK_S", 0.05)
    with pytest.raises(deadline.Overrun, match="outer ran past its deadline"):
        with deadline.deadline(0.2, "outer"), deadline.deadline(math.inf, "inner"):
            x, t0 = np.ones(1000), time.perf_counter()
            while time.perf_counter() - t0 < 20.0:  # swallowed: the block ends unstopped
                x = np.sqrt(x * x)


def _in_thread(fn) -> list:
    """What ``fn`` returned or raised in a thread of its own."""
    out = []

    def work():
        try:
            out.append(fn())
        except BaseException as exc:  # noqa: BLE001
            out.append(exc)

    t = threading.Thread(target=work)
    t.start()
    t.join(timeout=30)
    assert not t.is_alive()
    return out


def _spin(seconds: float) -> float:
    x, t0 = np.ones(1000), time.perf_counter()
    while time.perf_counter() - t0 < seconds:
        x = np.sqrt(x * x)
    return time.perf_counter() - t0


def test_a_deadline_stops_a_block_in_another_thread(monkeypatch):
    """A Dask worker runs a unit in a thread of its own: its deadline stops it there with
    the same Overrun, and a thread that sleeps within its budget finishes."""
    monkeypatch.setattr(deadline, "TICK_S", 0.05)

    def busy():
        with deadline.deadline(0.2, "threaded"):
            return _spin(20.0)

    (out,) = _in_thread(busy)
    assert isinstance(out, deadline.Overrun), out
    assert "threaded ran past its deadline of 0.2 s" in str(out)

    def sleeping():
        with deadline.deadline(0.05, "sleeping"):
            time.sleep(0.4)
        return "done"

    assert _in_thread(sleeping) == ["done"]
    time.sleep(0.2)  # no stop left pending for the thread's next code


def test_a_threads_budget_is_its_own_cpu_time(monkeypatch):
    """Another thread's computing does not spend a thread's budget: the thread's block,
    which sleeps, is not stopped while the main thread computes."""
    monkeypatch.setattr(deadline, "TICK_S", 0.05)
    got = []

    def sleeping():
        with deadline.deadline(0.2, "sleeping"):
            time.sleep(1.0)
        got.append("done")

    t = threading.Thread(target=sleeping)
    t.start()
    _spin(1.0)
    t.join(timeout=30)
    assert got == ["done"]


def test_a_thread_waiting_on_its_computing_helpers_is_not_hung(monkeypatch):
    """A run that hands its work to a pool (the half-space solver's stress layers) and
    waits: the process computes, so the run progresses, though its own thread does not."""
    from concurrent.futures import ThreadPoolExecutor

    monkeypatch.setattr(deadline, "TICK_S", 0.05)
    monkeypatch.setattr(deadline, "STALL_S", 0.5)

    def waiting():
        with deadline.deadline(math.inf, "waiting"), ThreadPoolExecutor(1) as pool:
            return pool.submit(_spin, 1.5).result() > 1.0

    assert _in_thread(waiting) == [True]


def test_an_enclosing_deadline_stops_a_thread_with_its_own_reason(monkeypatch):
    monkeypatch.setattr(deadline, "TICK_S", 0.05)

    def nested():
        with deadline.deadline(0.2, "outer"), deadline.deadline(math.inf, "inner"):
            return _spin(20.0)

    (out,) = _in_thread(nested)
    assert isinstance(out, deadline.Overrun) and "outer ran past its deadline" in str(out)


@pytest.mark.parametrize("name", ["hertz", "pin_on_disk", "fretting_orthotropic"])
def test_the_solvers_deadlines(name):
    """ic and fem estimates are calibrated: finite deadlines, scaled by --time-factor; the
    closed form makes no estimate: no deadline."""
    case = load_case(name, quick=True)[0]
    one, ten = Limits(), Limits(slowdown=10.0)
    for solver in ("ic", "fem"):
        d1, d10 = one.deadline(case, solver), ten.deadline(case, solver)
        assert deadline.ALLOWANCE_S < d1 < math.inf
        assert d10 - deadline.ALLOWANCE_S == pytest.approx(10 * (d1 - deadline.ALLOWANCE_S))
    assert one.deadline(case, "analytic") == math.inf


def test_a_reading_that_falls_is_no_work_undone(monkeypatch):
    """The process's CPU reading falls for a moment when a child has ended and is not yet
    reaped (in neither psutil's list nor os.times; found as "-0.61 s of CPU time in the
    last 1.01 s" on the test below, on a busy machine): the progress window sums the
    readings' rises, so the fall is not read as a hung run, and a run that stops
    computing is still stopped."""
    import types

    monkeypatch.setattr(deadline, "STALL_S", 1.0)
    clock = {"t": 0.0, "cpu": 1.5}  # a child's 1.5 s counted from the start
    monkeypatch.setattr(deadline, "time", types.SimpleNamespace(monotonic=lambda: clock["t"]))
    monkeypatch.setattr(deadline, "cpu_seconds", lambda: clock["cpu"])
    monkeypatch.setattr(deadline, "_process_clock", lambda: clock["cpu"])
    watch = deadline._Watch(math.inf, "the run", lambda: 0.0, 0.0)
    # the parent computes one core; at t = 1 the child drops out, at t = 1.5 it is back
    for t, cpu in ((0.5, 2.0), (1.0, 1.0), (1.5, 3.0), (2.0, 3.5)):
        clock.update(t=t, cpu=cpu)
        assert watch.look() is None, (t, watch.look())
    for t in (2.5, 3.0):  # it stops computing: no rise for STALL_S
        clock["t"] = t
        reason = watch.look()
    assert reason is not None and "made no progress: 0 s of CPU time" in reason, reason


def test_a_child_process_that_ends_keeps_its_progress(monkeypatch):
    """A block that runs a program in a child process (the calculix plugin's ccx): when
    the child ends, its CPU time stays counted (the ended children's, ``os.times``), so
    the progress window does not see the process's CPU time fall and call the block hung
    (found on a 318 s ccx run, stopped as "-211 s of CPU time in the last 120 s")."""
    import subprocess
    import sys

    monkeypatch.setattr(deadline, "TICK_S", 0.05)
    monkeypatch.setattr(deadline, "STALL_S", 1.0)
    burn = "import time\nt = time.process_time()\nwhile time.process_time() - t < {}: pass"
    with deadline.deadline(math.inf, "the run"):
        subprocess.run([sys.executable, "-c", burn.format(1.5)], check=True)
        t = time.process_time()
        while time.process_time() - t < 1.5:  # the parent computes on
            pass
