"""The commands that run cases: ``list``, ``run`` and ``sweep``."""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from cases.loader import BUNDLED, CASES_DIR, load_case
from cases.model import CaseError
from reports.cli.parser import PROG, limits_of, parse_overrides, parse_solvers
from reports.registry import solvers
from reports.registry.errors import UserError


def cmd_list(args: argparse.Namespace) -> int:
    for name in BUNDLED:
        if not (CASES_DIR / f"{name}.toml").is_file():
            print(f"{name:26s} (case file missing)")
            continue
        try:
            points, quick = load_case(name), load_case(name, quick=True)
        except CaseError as exc:
            print(f"{name:26s} INVALID: {exc}")
            continue
        first = points[0]
        sweep = f"{len(points)}|{len(quick)} pt"
        print(f"{name:26s} {first.kind:13s} {sweep:9s} {first.description}")
    print("(pt: sweep points at article size | with --quick)\n")
    for s in solvers.names():
        ok, reason = solvers.available(s)
        kind = " (plugin: runs only when named)" if s in solvers.PLUGINS else ""
        print(f"solver {s:9s} {'available' if ok else 'unavailable: ' + reason}{kind}")
        if scope := solvers.record(s).scope:
            print(f"       {'':9s} models {scope}")
    return 0


def report_runs(runs, out: Path) -> int:
    """Print where each run wrote its results, or its failures; the exit status."""
    from reports.store.layout import staging_dir

    failed, user = [], False
    for r in runs:
        if r.failures:
            failed.append(r)
            user = user or r.user_error
        else:
            print(f"{r.name}: {r.path} ({r.wall_s:.1f} s)")
    for r in failed:
        for line in r.failures:
            print(f"{PROG}: error: {line}", file=sys.stderr)
        if r.staging_left:
            print(f"{PROG}: {r.name}: incomplete results left in {staging_dir(out, r.name)}"
                  " (not reported as complete)", file=sys.stderr)
        else:
            print(f"{PROG}: {r.name}: nothing written (its partial results removed)",
                  file=sys.stderr)
    if failed:
        return 2 if user else 1
    return 0


def cmd_run(args: argparse.Namespace) -> int:
    from reports.run.plan import plan_case, select_solvers
    from reports.run.runner import execute

    names = list(args.cases)
    if args.all:
        missing = [n for n in BUNDLED if not (CASES_DIR / f"{n}.toml").is_file()]
        for n in missing:
            print(f"{PROG}: warning: bundled case {n} has no case file yet; skipped",
                  file=sys.stderr)
        names += [n for n in BUNDLED if n not in missing and n not in names]
    if not names:
        raise UserError("run needs at least one CASE or --all")
    requested = parse_solvers(args.solver)
    chosen, skipped = select_solvers(requested, relations=args.quick)
    overrides = parse_overrides(args.overrides)
    limits = limits_of(args)
    plans = [plan_case(n, chosen, quick=args.quick, overrides=overrides, skipped=skipped,
                       limits=limits, explicit=bool(requested))
             for n in names]  # validate every case before running
    plans = _requested(args, plans)
    seen: dict[str, str] = {}
    for n, p in zip(names, plans, strict=True):
        if p.dir_name in seen:
            raise UserError(f"cases {seen[p.dir_name]} and {n} both write {p.dir_name}/")
        seen[p.dir_name] = n
    for p in plans:
        for w in p.warnings:
            print(f"{PROG}: warning: {w}", file=sys.stderr)
    check_workers(args, plans)
    progress = False if args.no_progress else None
    estimated = _announce(plans)
    t0 = time.perf_counter()
    with cluster(args) as dask:
        if dask is None:
            codes = [report_runs([execute(p, args.out, progress=progress)], args.out)
                     for p in plans]  # each case reported as soon as it is done
        else:
            from reports.run.cluster import execute_cases

            codes = [report_runs([r], args.out)
                     for r in execute_cases(plans, args.out, dask, progress)]
    print(f"run: {len(plans)} case(s) in {_duration(time.perf_counter() - t0)} (estimated "
          f"{_duration(estimated)})")
    return 2 if 2 in codes else max(codes)


@contextmanager
def cluster(args: argparse.Namespace) -> Iterator[Any]:
    """The Dask cluster of ``--workers`` / ``--scheduler`` for the command, or None
    (serial)."""
    if _serial(args):
        yield None
        return
    check_workers(args, [])
    from reports.run.cluster import DaskExecutor

    with DaskExecutor(args.scheduler, args.workers) as dask:
        yield dask


def _serial(args: argparse.Namespace) -> bool:
    """Whether the units run in this process (``--workers 0`` and no ``--scheduler``);
    ``--workers`` not given is the command's default, at most the cores."""
    if args.workers is None:
        from reports.run.cluster import cores

        args.workers, args.workers_defaulted = min(args.default_workers, cores()), True
    if args.workers < 0:
        raise UserError("--workers must be >= 0")
    return args.workers == 0 and not args.scheduler


def check_workers(args: argparse.Namespace, plans: list[Any]) -> None:
    """UserError, before any worker starts, when ``--workers`` asks for more workers than
    the machine allows for ``plans`` (:func:`reports.run.cluster.worker_cap`, in 90 % of
    the memory available now: ``--max-memory`` bounds one run), saying how many it
    would; the command's default (``--workers`` not given) is lowered to the cap."""
    if _serial(args) or args.scheduler or args.workers <= 1:
        return
    from reports.run.cluster import worker_cap
    from reports.run.plan import available_memory

    cap, why = worker_cap(plans, 0.9 * available_memory())
    if args.workers > cap and getattr(args, "workers_defaulted", False):  # as many as fit
        args.workers = cap
    if args.workers > cap:
        raise UserError(f"--workers {args.workers}: this machine allows at most {cap} "
                        f"({why})")


#: a unit whose estimate is longer is announced before the run starts
LONG_UNIT_S = 60.0


def _duration(seconds: float) -> str:
    return f"{seconds:.0f} s" if seconds < 120 else f"{seconds / 60:.1f} min"


def _announce(plans) -> float:
    """Print the planner's estimate of every long unit (time and memory) and the total;
    the total estimated seconds (units without an estimate count 0)."""
    total = 0.0
    for p in plans:
        extra = [(g.case, g.solver) for g in p.study_runs()]  # the studies' runs
        for case, s in [(p.points[i], s) for i, s in p.units()] + extra:
            cost = solvers.estimate(s, case)
            if cost is None:
                continue
            total += cost.seconds
            if cost.seconds >= LONG_UNIT_S:
                where = p.name + (f" [{case.param}]" if case.param else "")
                print(f"estimate: {where} {s}: {_duration(cost.seconds)}, "
                      f"{cost.memory / 2**30:.1f} GiB")
    extra = sum(len(p.study_runs()) for p in plans)
    print(f"run: {sum(len(p.units()) for p in plans)} solver run(s)"
          + (f" and {extra} run(s) of studies" if extra else "")
          + f" in {len(plans)} case(s), estimated {_duration(total)}")
    return total


def cmd_sweep(args: argparse.Namespace) -> int:
    from reports.run.cluster import DaskExecutor
    from reports.run.plan import select_solvers
    from reports.run.runner import execute
    from reports.run.sweep import parse_param, plan_sweep
    from reports.run.units import serial_executor

    params = [parse_param(p) for p in args.param]
    serial = _serial(args)
    requested = parse_solvers(args.solver)
    chosen, skipped = select_solvers(requested, relations=args.quick)
    plan = plan_sweep(args.case, params, chosen, quick=args.quick,
                      overrides=parse_overrides(args.overrides), skipped=skipped,
                      limits=limits_of(args), explicit=bool(requested))
    for w in plan.warnings:
        print(f"{PROG}: warning: {w}", file=sys.stderr)
    check_workers(args, [plan])
    progress = False if args.no_progress else None
    t0 = time.perf_counter()
    if serial:
        run = execute(plan, args.out, executor=serial_executor, progress=progress,
                      extra_manifest={"executor": {"scheduler": "serial", "workers": 1}})
    else:
        with DaskExecutor(args.scheduler, args.workers) as dask:
            run = execute(plan, args.out, executor=dask, progress=progress,
                          extra_manifest={"executor": dask.info})
    wall = time.perf_counter() - t0
    code = report_runs([run], args.out)
    if code != 0:
        return code
    from reports.render.plots import write_sweep_plot

    write_sweep_plot(run.path)
    print(f"sweep: {len(plan.units())} task(s) in {wall:.1f} s wall "
          f"(sum of task times {run.unit_wall_s:.1f} s)")
    if args.check_serial:
        return _check_serial(plan, run.path, wall)
    return 0


def _check_serial(plan, path: Path, wall: float) -> int:
    """Re-run a sweep serially; compare its numbers and wall time with the sweep's."""
    from reports.run.sweep import check_serial

    check = check_serial(plan, path, wall)
    print(f"sweep: serial re-run {check['serial_wall_s']:.1f} s vs parallel {wall:.1f} s "
          f"(speed-up {check['speedup']:.2f}x); numbers "
          + ("identical" if check["identical"] else "DIFFER"))
    return 0 if check["identical"] else 1


def _requested(args: argparse.Namespace, plans: list[Any]) -> list[Any]:
    """The plans with the studies their flags ask for (``Study.option``,
    :func:`reports.run.plan.request_study`), their notes said."""
    from reports.run.plan import request_study
    from reports.studies.registry import STUDIES

    for study in STUDIES:
        if study.option and getattr(args, study.option.lstrip("-").replace("-", "_"), False):
            plans, notes = request_study(plans, study.name)
            for note in notes:
                print(f"{PROG}: note: {study.option}: {note}", file=sys.stderr)
    return plans
