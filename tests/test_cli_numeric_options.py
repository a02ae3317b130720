"""Options checked as they are parsed (issue 77, point 4): every numeric option and range
refuses inf, NaN and negative values, exit 2 naming it, before any work; ``--claims`` is
checked before it is expanded; ``--workers`` is capped by the cores and the memory of the
largest unit, refused above the cap with the number it would allow, before any worker
starts.  Found by these probes: ``sweep --param load.P=1:inf:1`` ended in "internal
error: OverflowError", ``article --claims 1-999999999999`` ran out of memory, and
``--workers 1000`` started 345 worker processes."""

from __future__ import annotations

import itertools
import multiprocessing
import time

import pytest
from test_cli_hostile_inputs import TINY, _answer

from cases.loader import load_case
from reports.cli import main
from reports.run import cluster
from reports.run.plan import plan_case

BAD = ("inf", "-inf", "nan", "-1")

#: (command line, the option given a bad value)
OPTIONS = [
    (["run", "{case}"], "--max-memory"),
    (["run", "{case}"], "--max-hours"),
    (["run", "{case}"], "--time-factor"),
    (["run", "{case}"], "--workers"),
    (["sweep", "{case}", "--param", "grid.nx=11,13"], "--workers"),
    (["sweep", "{case}", "--param", "grid.nx=11,13"], "--max-hours"),
    (["gate", "--out", "{tmp}"], "--drift"),
    (["report", "--out", "{tmp}"], "--workers"),
    (["threshold", "{case}", "--param", "friction.mu", "--event", "vm_max_on_surface"],
     "--resolution"),
    (["threshold", "{case}", "--param", "friction.mu", "--event", "vm_max_on_surface"],
     "--surface-depth"),
    (["threshold", "{case}", "--param", "friction.mu", "--event", "vm_max_on_surface"],
     "--grids"),
    (["article", "--quick"], "--time-factor"),
]


@pytest.fixture
def case(tmp_path):
    path = tmp_path / "case.toml"
    path.write_text(TINY + "[friction]\nmu = 0.2\n")
    return path


@pytest.mark.parametrize(("argv", "option", "bad"),
                         [(a, o, b) for (a, o), b in itertools.product(OPTIONS, BAD)],
                         ids=[f"{a[0]}{o}={b}" for (a, o), b in itertools.product(OPTIONS, BAD)])
def test_a_bad_number_is_refused_naming_the_option(tmp_path, case, capsys, argv, option,
                                                   bad):
    argv = [a.format(case=case, tmp=tmp_path) for a in argv]
    t0 = time.perf_counter()
    code, err = _answer([*argv, f"{option}={bad}", "--out", str(tmp_path / "o")]
                        if argv[0] not in ("gate", "report") else [*argv, f"{option}={bad}"],
                        capsys)
    if option == "--workers" and bad == "-1":
        least = 1 if argv[0] == "report" else 0  # report draws in at least this process
        assert code == 2 and f"--workers must be >= {least}" in err, err
    else:
        assert code == 2 and option in err, err
    assert time.perf_counter() - t0 < 60 and not (tmp_path / "o").exists()


@pytest.mark.parametrize("bad", ["1:inf:1", "1:nan:1", "nan:2:1", "1:2:inf", "1:2:nan",
                                 "-inf:0:1", "1:1e308:1e-308", "1:2:1e-300", "0:1e9:1"])
def test_a_range_of_infinities_or_too_many_values_is_refused(tmp_path, case, capsys, bad):
    code, err = _answer(["sweep", str(case), "--param", f"load.P={bad}", "--workers", "0",
                         "--no-progress", "--out", str(tmp_path / "o")], capsys)
    assert code == 2 and f"load.P={bad}" in err and "internal error" not in err, err
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("claims", ["1-999999999999", "0-999999999999", "999999999999",
                                    "5-3", "1-", "x"])
def test_a_claims_range_is_checked_before_it_is_expanded(tmp_path, capsys, claims):
    t0 = time.perf_counter()
    code, err = _answer(["article", "--quick", "--claims", claims, "--out",
                         str(tmp_path / "o")], capsys)
    assert code == 2 and "--claims" in err, err
    assert time.perf_counter() - t0 < 30 and not (tmp_path / "o").exists()


def test_workers_above_the_cores_are_refused_before_any_starts(tmp_path, case, capsys,
                                                              monkeypatch):
    import distributed

    def started(*args, **kwargs):
        raise AssertionError("a LocalCluster was started")

    monkeypatch.setattr(distributed, "LocalCluster", started)
    monkeypatch.setattr(cluster, "cores", lambda: 3)
    for argv in (["run", str(case)], ["sweep", str(case), "--param", "grid.nx=11,13"]):
        code, err = _answer([*argv, "--workers", "1000", "--no-progress", "--out",
                             str(tmp_path / "o")], capsys)
        assert code == 2 and "--workers 1000: this machine allows at most 3 (3 core" in err
    assert not multiprocessing.active_children() and not (tmp_path / "o").exists()


def test_workers_are_capped_by_the_memory_of_the_largest_unit(monkeypatch):
    plans = [plan_case(load_case("hertz", quick=True)[0].name, ["ic", "analytic"],
                       quick=True)]
    monkeypatch.setattr(cluster, "cores", lambda: 64)
    from reports.registry import solvers

    unit = max(solvers.estimate(s, plans[0].points[i]).memory
               for i, s in plans[0].units() if solvers.estimate(s, plans[0].points[i]))
    each = unit + cluster.WORKER_BASE
    cap, why = cluster.worker_cap(plans, 5.5 * each)
    assert cap == 5 and "holds 5 worker(s)" in why and "hertz" in why
    cap, why = cluster.worker_cap(plans, 1e3 * each)
    assert cap == 64 and "64 core(s)" in why
    assert cluster.worker_cap(plans, 0.1 * each)[0] == 1  # one worker always runs


def test_the_default_workers_are_at_most_the_cores(tmp_path, case, capsys, monkeypatch):
    """sweep's default of two workers on a one-core machine is one, not a refusal."""
    seen = []

    class Executor:
        def __init__(self, scheduler, workers):
            seen.append(workers)
            raise KeyboardInterrupt  # stop there: the count is what is tested

    monkeypatch.setattr(cluster, "cores", lambda: 1)
    monkeypatch.setattr(cluster, "DaskExecutor", Executor)
    main(["sweep", str(case), "--param", "grid.nx=11,13", "--no-progress", "--out",
          str(tmp_path / "o")])
    capsys.readouterr()
    assert seen == [1]
