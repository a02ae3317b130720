"""The commands that study the cases: ``threshold`` and ``article``."""

from __future__ import annotations

import argparse
import sys
import time

from reports.cli.parser import PROG, limits_of, parse_overrides, parse_solvers
from reports.cli.runs import cluster, report_runs
from reports.registry.errors import RunFailed, UserError


def cmd_threshold(args: argparse.Namespace) -> int:
    from reports.run import threshold as th
    from reports.run import threshold_table as table
    from reports.run.plan import select_solvers
    from reports.studies.events import EventOptions, event

    th.check_param(args.param)
    event(args.event)
    lo, hi, res = th.bracket(args.param, tuple(args.range) if args.range else None,
                             args.resolution)
    options = EventOptions(args.at.strip(), args.surface_depth)
    overrides = parse_overrides(args.overrides)
    if args.param in overrides:
        raise UserError(f"--set {args.param}: the key is the one --param bisects")
    requested = parse_solvers(args.solver)
    chosen, skipped = select_solvers(requested)
    for name, reason in skipped.items():
        print(f"{PROG}: note: solver {name} skipped: {reason}", file=sys.stderr)
    request = th.Request(case=args.case, param=args.param, event=args.event, lo=lo, hi=hi,
                         resolution=res, grids=th.parse_grids(args.grids),
                         solvers=tuple(chosen), quick=args.quick, overrides=overrides,
                         options=options, limits=limits_of(args),
                         explicit=bool(requested))
    table.existing(args.out)  # a damaged table is refused before any work
    t0 = time.perf_counter()
    with cluster(args) as dask:
        rows = th.run(request, log=None if args.no_progress else table.stderr_log,
                      cluster=dask)
    print(table.format_table(request, rows))
    path = table.write_rows(args.out, rows)
    print(f"threshold: {path} ({time.perf_counter() - t0:.1f} s)")
    failed = [f"{r['solver']} {r['grid']}: {r['status']}" for r in rows
              if r["status"].startswith("failed")]
    if failed:
        raise RunFailed(failed)
    return 0


def cmd_article(args: argparse.Namespace) -> int:
    from reports.render.article_page import judge_and_write
    from reports.run import article_sources as article
    from reports.run.plan import select_solvers
    from reports.run.threshold_table import stderr_log
    from reports.studies.claims import numbers

    claims = numbers(args.claims)
    if args.overrides:
        raise UserError("--set: article runs the article's cases as the case files hold them")
    requested = parse_solvers(args.solver)
    work = article.plan(args.out, args.quick, select_solvers(requested, relations=False)[0],
                        limits_of(args), claims, bool(requested))
    print(work.describe())
    with cluster(args) as dask:
        code = article.execute(work, args.out, progress=False if args.no_progress else None,
                               report=lambda runs: report_runs(runs, args.out),
                               log=None if args.no_progress else stderr_log, cluster=dask)
    path, findings = judge_and_write(args.out, args.quick, claims)
    for n, f in findings.items():
        print(f"claim {n:2d}: {f.verdict} — {f.why}")
    print(f"article: {path}")
    return code
