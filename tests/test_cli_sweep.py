"""`contact-vv sweep`: parameter parsing, points, and Dask results identical to serial."""

from __future__ import annotations

import pandas as pd
import pytest
import test_cli_fakes as fakes
from test_cli_run import SWEEP, write_case

from reports.cli import main
from reports.registry.errors import UserError
from reports.run.sweep import dump_toml, parse_param, sweep_points


def test_parse_ranges_and_lists():
    assert parse_param("friction.beta=0:90:30") == ("friction.beta", [0, 30, 60, 90])
    key, vals = parse_param("friction.mu=0.1:0.3:0.1")
    assert vals == [0.1, 0.2, 0.3]  # rounded, stop included despite 0.1 + 2·0.1 ≠ 0.3
    assert parse_param("friction.beta=90:0:-45")[1] == [90, 45, 0]
    assert parse_param("solver.method=cg,uzawa")[1] == ["cg", "uzawa"]
    assert parse_param("grid.nx=21, 41")[1] == [21, 41]
    for bad in ("beta", "beta=", "beta=0:1", "beta=0:10:-1", "beta=a:b:c"):
        with pytest.raises(UserError):
            parse_param(bad)


def test_dump_toml_round_trips():
    import tomllib

    data = {"kind": "static", "materials": {"a": {"E": 1.0, "nu": 0.3}},
            "quick": {"grid.nx": 41}, "tolerances": {"ic-fem.p_max": 0.02},
            "sweep_values": [0.1, 0.2], "flag": True, "name": 'a"b'}
    assert tomllib.loads(dump_toml(data)) == data


def test_sweep_points_replace_the_file_sweep(tmp_path):
    case = write_case(tmp_path, SWEEP)  # the file sweeps friction.mu over [0.25, 0.6]
    points, info = sweep_points(case, [parse_param("friction.mu=0.1,0.2,0.3")])
    assert [p.param for p in points] == ["mu=0.1", "mu=0.2", "mu=0.3"]
    assert [p.friction.mu1 for p in points] == [0.1, 0.2, 0.3]
    assert all(p.source == str(case) and p.name == "small" for p in points)
    zipped, _ = sweep_points(case, [parse_param("grid.nx=20,40"), parse_param("grid.ny=20,40")])
    assert [(p.grid.nx, p.grid.ny, p.param) for p in zipped] == [
        (20, 20, "nx=20,ny=20"), (40, 40, "nx=40,ny=40")]
    with pytest.raises(UserError, match="same number of values"):
        sweep_points(case, [parse_param("grid.nx=20,40"), parse_param("grid.ny=20")])


def test_workers_get_this_process_thread_settings(monkeypatch):
    """The thread-count variables of this process, and the counts it limits at run time
    where no variable sets them, are the workers'; nothing else of Dask's is changed."""
    pytest.importorskip("distributed")
    import os

    from threadpoolctl import threadpool_limits

    from reports.run.cluster import worker_environ

    cores = os.cpu_count() or 1
    monkeypatch.setenv("OPENBLAS_NUM_THREADS", "3")
    monkeypatch.delenv("OMP_NUM_THREADS", raising=False)
    with threadpool_limits(cores):  # as a process nothing limits (the tests limit BLAS)
        env = worker_environ()
    assert env["OPENBLAS_NUM_THREADS"] == "3"
    assert "OMP_NUM_THREADS" not in env  # Dask's default of 1 removed: library default
    assert "MALLOC_TRIM_THRESHOLD_" in env  # Dask's other settings kept
    monkeypatch.delenv("OPENBLAS_NUM_THREADS")
    if cores > 1:
        with threadpool_limits(1, user_api="blas"):
            assert worker_environ()["OPENBLAS_NUM_THREADS"] == "1"


def test_dask_sweep_matches_serial(tmp_path, monkeypatch, capsys):
    pytest.importorskip("distributed")
    fakes.use(monkeypatch, ic="solve_ic", analytic="solve_exact")
    case = write_case(tmp_path, SWEEP)
    args = ["sweep", "--no-progress", str(case), "--param", "friction.mu=0.1:0.4:0.1"]
    assert main([*args, "--workers", "0", "--out", str(tmp_path / "serial")]) == 0
    assert main([*args, "--workers", "2", "--check-serial", "--out",
                 str(tmp_path / "dask")]) == 0
    out = capsys.readouterr().out
    assert "sweep: 8 task(s)" in out and "speed-up" in out and "numbers identical" in out
    name = "small__sweep_mu"
    a = pd.read_csv(tmp_path / "serial" / name / "summary.csv")
    b = pd.read_csv(tmp_path / "dask" / name / "summary.csv")
    assert list(b["param"].unique()) == ["mu=0.1", "mu=0.2", "mu=0.3", "mu=0.4"]
    pd.testing.assert_frame_equal(a.drop(columns="wall_s"), b.drop(columns="wall_s"),
                                  check_exact=True)
    assert (tmp_path / "serial" / name / "metrics.csv").read_bytes() == \
        (tmp_path / "dask" / name / "metrics.csv").read_bytes()
    import json

    mf = json.loads((tmp_path / "dask" / name / "manifest.json").read_text())
    assert mf["executor"]["workers"] == 2 and mf["executor"]["threads"] == 2
    # the workers compute with this process's BLAS/OpenMP thread settings
    from reports.run.cluster import _thread_env

    assert list(mf["executor"]["worker_thread_env"].values()) == [_thread_env()] * 2
    assert mf["sweep"]["keys"] == ["friction.mu"]
    assert (tmp_path / "dask" / name / "sweep.png").is_file()
    check = json.loads((tmp_path / "dask" / name / "sweep_check.json").read_text())
    assert check["identical"] is True and check["serial_wall_s"] > 0
