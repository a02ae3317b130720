"""No run goes on past its cost estimate by more than the estimate's calibration factor
(issue 31, reports/run/deadline.py): a solver that runs past its deadline is stopped and
its run fails naming the deadline, in ``run``, ``sweep --workers 0`` and ``threshold``;
``--time-factor`` scales the deadline for a slower machine; the real solvers' estimates
are calibrated (finite deadlines), the closed form's are not.
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
CASE = TINY.replace("nx = 11\nny = 11", "nx = 21\nny = 21")  # coarsened twice by 1.5


@pytest.fixture
def slow(monkeypatch):
    """ic: a fake that sleeps FAKE_SLEEP seconds with an estimate of 0.01 s, factor 1;
    every run may take 0.3 s beyond its estimate."""
    fakes.use(monkeypatch, ic="solve_slow", analytic="solve_exact")
    monkeypatch.setitem(solvers.REGISTRY, "ic", replace(solvers.REGISTRY["ic"],
                                                        estimate_attr="estimate_tiny"))
    monkeypatch.setattr(deadline, "ALLOWANCE_S", 0.3)
    monkeypatch.setenv("FAKE_SLEEP", "30")


@pytest.mark.parametrize("command", [
    ["run", "{case}"],
    ["sweep", "{case}", "--param", "grid.nx=21,23", "--workers", "0"],
    ["run", "{case}", "--convergence"],
])
def test_a_run_past_its_deadline_is_stopped(tmp_path, capsys, slow, command):
    (tmp_path / "c.toml").write_text(CASE)
    argv = [a.replace("{case}", str(tmp_path / "c.toml")) for a in command]
    t0 = time.perf_counter()
    code, err = _answer([*argv, "--solver", "ic,analytic", "--no-progress", "--out",
                         str(tmp_path / "o")], capsys)
    assert time.perf_counter() - t0 < 10.0  # stopped, not slept out (30 s per run)
    assert code == 1, err
    assert STOPPED in err and "0.31 s" in err, err


def test_a_threshold_past_its_deadline_is_a_failed_row(tmp_path, capsys, slow):
    t0 = time.perf_counter()
    code, err = _answer(["threshold", "sliding_friction", "--param", "friction.mu", "--event",
                         "vm_max_on_surface", "--quick", "--solver", "ic", "--grids", "1",
                         "--range", "0.2", "0.4", "--resolution", "0.1", "--no-progress",
                         "--out", str(tmp_path / "o")], capsys)
    assert time.perf_counter() - t0 < 10.0
    assert code == 1 and "ran past its deadline" in err, err


def test_the_time_factor_scales_the_deadline(tmp_path, capsys, slow, monkeypatch):
    monkeypatch.setenv("FAKE_SLEEP", "0.5")
    (tmp_path / "c.toml").write_text(TINY)
    argv = ["run", str(tmp_path / "c.toml"), "--solver", "ic,analytic", "--no-progress"]
    code, err = _answer([*argv, "--out", str(tmp_path / "o1")], capsys)
    assert code == 1 and STOPPED in err, err
    code, err = _answer([*argv, "--out", str(tmp_path / "o2"), "--time-factor", "100"], capsys)
    assert code == 0, err  # 0.3 s + 100 x 0.01 s
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


def test_no_alarm_outside_the_main_thread():
    errors = []

    def work():
        try:
            with deadline.deadline(0.05, "thread"):
                time.sleep(0.2)
        except BaseException as exc:  # noqa: BLE001
            errors.append(exc)

    t = threading.Thread(target=work)
    t.start()
    t.join()
    assert errors == []


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
