"""``run --workers`` / ``--scheduler`` (issue 62, reports/run/cluster.py): the units of
every case as tasks on a Dask cluster, the results identical to a serial run's (every
CSV and field, wall times aside), and a worker killed mid-run losing no unit."""

from __future__ import annotations

import json
import os
import signal
import threading
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import test_cli_fakes as fakes
from test_cli_hostile_inputs import SWEEP

from reports.cli import main

pytest.importorskip("distributed")


def _same_results(a: Path, b: Path) -> None:
    """Every file of the two results directories the same (CSV and fields exactly; the
    wall times and the manifests, which record them and the executor, aside)."""
    files = sorted(p.relative_to(a) for p in a.rglob("*") if p.is_file())
    assert files == sorted(p.relative_to(b) for p in b.rglob("*") if p.is_file())
    assert any(f.suffix == ".npz" for f in files) and any(f.suffix == ".csv" for f in files)
    for f in files:
        if f.suffix == ".csv":
            x, y = (pd.read_csv(d / f) for d in (a, b))
            pd.testing.assert_frame_equal(x.drop(columns="wall_s", errors="ignore"),
                                          y.drop(columns="wall_s", errors="ignore"),
                                          check_exact=True, obj=str(f))
        elif f.suffix == ".npz":
            x, y = (np.load(d / f) for d in (a, b))
            assert sorted(x.files) == sorted(y.files), f
            for k in x.files:
                if k == "scalars":  # JSON; the step's wall time aside
                    u, v = (json.loads(str(s[k])) for s in (x, y))
                    u.pop("wall_s"), v.pop("wall_s")
                    assert u == v or json.dumps(u) == json.dumps(v), (f, k)
                else:
                    assert np.array_equal(x[k], y[k], equal_nan=x[k].dtype.kind in "fc"), \
                        (f, k)
        elif f.name != "manifest.json":
            assert (a / f).read_bytes() == (b / f).read_bytes(), f


def test_run_on_workers_matches_the_serial_run(tmp_path, capsys):
    """The bundled Hertz case at quick size through ic, fem and the closed form."""
    args = ["run", "hertz", "--quick", "--no-progress"]
    assert main([*args, "--out", str(tmp_path / "serial")]) == 0
    assert main([*args, "--workers", "2", "--out", str(tmp_path / "dask")]) == 0
    _same_results(tmp_path / "serial", tmp_path / "dask")
    mf = json.loads((tmp_path / "dask" / "hertz" / "manifest.json").read_text())
    assert mf["executor"]["scheduler"] == "LocalCluster" and mf["executor"]["workers"] == 2
    assert "executor" not in json.loads(
        (tmp_path / "serial" / "hertz" / "manifest.json").read_text())


def test_bad_worker_counts_are_refused(tmp_path, capsys):
    assert main(["run", "hertz", "--quick", "--workers", "-1", "--out", str(tmp_path)]) == 2
    assert "--workers must be >= 0" in capsys.readouterr().err


def test_a_worker_killed_mid_run_loses_no_unit(tmp_path, monkeypatch):
    """Two cases at once on two workers; the worker running a unit is killed while it
    computes: the scheduler runs the unit again on a live worker, and both cases are
    complete and identical to the serial run."""
    from reports.run.cluster import DaskExecutor, execute_cases
    from reports.run.plan import plan_case

    fakes.use(monkeypatch, ic="solve_busy", analytic="solve_exact")
    monkeypatch.setenv("FAKE_SLEEP", "2")  # seconds of CPU time of each ic unit
    cases = []
    for name in ("one", "two"):
        (tmp_path / f"{name}.toml").write_text(SWEEP)
        cases.append(tmp_path / f"{name}.toml")
    plans = [plan_case(c, ["ic", "analytic"]) for c in cases]
    assert main(["run", "--no-progress", *map(str, cases), "--solver", "ic,analytic",
                 "--out", str(tmp_path / "serial")]) == 0
    killed = []
    with DaskExecutor(None, 2) as dask:
        client = dask.client
        pids = client.run(os.getpid)

        def kill_a_busy_worker() -> None:
            deadline = time.monotonic() + 60
            while time.monotonic() < deadline and not killed:
                for addr, keys in client.processing().items():
                    if any("-ic-" in str(k) for k in keys):
                        time.sleep(0.5)  # well inside its 2 s of computing
                        os.kill(pids[addr], signal.SIGKILL)
                        killed.append(addr)
                        return
                time.sleep(0.05)

        killer = threading.Thread(target=kill_a_busy_worker)
        killer.start()
        runs = list(execute_cases(plans, tmp_path / "dask", dask))
        killer.join()
    assert killed, "no ic unit was seen running"
    assert sorted(r.name for r in runs) == ["one", "two"]
    assert all(not r.failures and r.path is not None for r in runs), \
        [r.failures for r in runs]
    _same_results(tmp_path / "serial", tmp_path / "dask")


def test_a_threshold_on_workers_matches_the_serial_one():
    """The quick sliding case's threshold in μ, ic and the closed form on two grids each:
    the two solvers' bisections at once on two workers, every row as the serial run's."""
    from reports.run import threshold as th
    from reports.run.cluster import DaskExecutor

    request = th.Request(case="sliding_friction", param="friction.mu",
                         event="vm_max_on_surface", lo=0.2, hi=0.5, resolution=0.02,
                         solvers=("ic", "analytic"), quick=True)
    serial = th.run(request)
    with DaskExecutor(None, 2) as dask:
        parallel = th.run(request, cluster=dask)
    assert [(r["solver"], r["grid"], r["status"].split(":")[0]) for r in serial] == [
        ("ic", "41x41", "bisected"), ("ic", "27x27", "bisected"),
        ("analytic", "exact", "exact"), ("analytic", "41x41", "bisected"),
        ("analytic", "27x27", "bisected")]
    for a, b in zip(serial, parallel, strict=True):  # the coarser grid from the first's guess
        assert pd.Series(a).drop("wall_s").equals(pd.Series(b).drop("wall_s")), (a, b)


def test_a_unit_waiting_in_the_queue_is_not_stopped(tmp_path, monkeypatch):
    """Three cases at once on one worker: the last case's units wait behind the others'
    for longer than their budgets; each budget counts the unit's own CPU time, so none is
    stopped (a wall-time limit from the submission stopped a correct chain)."""
    from dataclasses import replace

    from reports.registry import solvers
    from reports.run import deadline
    from reports.run.cluster import DaskExecutor, execute_cases
    from reports.run.plan import plan_case

    fakes.use(monkeypatch, ic="solve_busy", analytic="solve_exact")
    monkeypatch.setitem(solvers.REGISTRY, "ic", replace(solvers.REGISTRY["ic"],
                                                        estimate_attr="estimate_tiny"))
    monkeypatch.setattr(deadline, "ALLOWANCE_S", 0.6)  # each unit's budget: 0.6 s + 0.02 s
    monkeypatch.setenv("FAKE_SLEEP", "0.3")  # seconds of CPU time of each unit
    plans = []
    for name in ("one", "two", "three"):
        (tmp_path / f"{name}.toml").write_text(SWEEP)
        plans.append(plan_case(tmp_path / f"{name}.toml", ["ic"]))
    with DaskExecutor(None, 1) as dask:
        runs = list(execute_cases(plans, tmp_path / "out", dask))
    assert all(not r.failures for r in runs), [r.failures for r in runs]
    assert sorted(r.name for r in runs) == ["one", "three", "two"]


def test_units_are_placed_by_their_cost_estimates():
    """A unit's Dask priority is its estimated seconds (the longest first); its memory
    estimate is a resource request only where the workers declare MEMORY, capped at the
    largest worker's."""
    from cases.loader import load_case
    from reports.registry import solvers
    from reports.run.cluster import MEMORY, DaskExecutor

    ex = DaskExecutor(None, 2)  # not started: placement needs no cluster
    worn = load_case("fretting_orthotropic", quick=True)[2]
    small = load_case("hertz", quick=True)[0]
    ex.memory = None
    long, short = ex._placement(worn, "fem"), ex._placement(small, "fem")
    assert long["priority"] > short["priority"] > 0 and "resources" not in long
    assert long["priority"] == int(solvers.estimate("fem", worn).seconds)
    assert ex._placement(small, "analytic") == {"priority": 0}  # no estimate
    need = solvers.estimate("fem", worn).memory
    ex.memory = 64e9
    assert ex._placement(worn, "fem")["resources"] == {MEMORY: need}
    ex.memory = need / 2  # no worker has it: the largest one, alone
    assert ex._placement(worn, "fem")["resources"] == {MEMORY: need / 2}
