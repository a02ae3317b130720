"""The ``contact-vv`` command line: list, run, report, gate, sweep and threshold.

Exit status: 0 success; 1 a solver failed (did not converge, crashed) or the gate found
a failed metric, non-converged run or incomplete case; 2 a user error (bad case file,
unknown case or solver, bad flag, missing results directory), printed as
``contact-vv: error: <message>`` without a traceback; 130 interrupted.
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from cases.loader import BUNDLED, CASES_DIR, load_case
from cases.model import CaseError
from reports.registry import solvers
from reports.registry.errors import RunFailed, UserError

PROG = "contact-vv"


class _Parser(argparse.ArgumentParser):
    def error(self, message: str):  # argparse's usage + "prog: error: msg", exit 2
        self.print_usage(sys.stderr)
        raise SystemExit(_fail(message))


def _fail(message: str) -> int:
    print(f"{PROG}: error: {message}", file=sys.stderr)
    return 2


def _solver_list(text: str | None) -> list[str] | None:
    if text is None:
        return None
    names = [s.strip() for s in text.split(",") if s.strip()]
    if not names:
        raise UserError("--solver needs at least one solver name")
    return names


def _overrides(items: Sequence[str] | None) -> dict[str, Any]:
    from reports.run.sweep import parse_value

    out: dict[str, Any] = {}
    for item in items or ():
        key, eq, value = item.partition("=")
        if not eq or not key.strip():
            raise UserError(f"--set {item!r}: expected KEY=VALUE (a dotted case key)")
        out[key.strip()] = parse_value(value)
    return out


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog=PROG, description="Verification of the half-space contact solver "
                     "against FEM and analytical references.")
    parser.add_argument("--debug", action="store_true",
                        help="show the traceback of an unexpected error")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    sub.required = True

    sub.add_parser("list", help="list the bundled cases and the solvers")

    def common(p: argparse.ArgumentParser, *, solving: bool) -> None:
        p.add_argument("--out", type=Path, default=Path("results"),
                       help="results directory (default: ./results)")
        if solving:
            p.add_argument("--solver", help="comma-separated solvers (default: every "
                           f"available one of {','.join(solvers.names())})")
            p.add_argument("--quick", action="store_true",
                           help="coarse grids of the case's [quick] table (CI)")
            p.add_argument("--set", action="append", metavar="KEY=VALUE", dest="overrides",
                           help="override a dotted case key, e.g. tolerances.p_max=0.02")
            p.add_argument("--no-progress", action="store_true", help="no progress bars")
            p.add_argument("--max-memory", type=float, metavar="GiB",
                           help="memory one solver run may take by its estimate (default: "
                           "90 %% of the available memory)")
            p.add_argument("--max-hours", type=float, default=48.0, metavar="H",
                           help="wall time one solver run may take by its estimate "
                           "(default: 48)")
            p.add_argument("--time-factor", type=float, default=1.0, metavar="X",
                           help="this machine's slowness against the estimates' (scales "
                           "--max-hours checks and each run's deadline; default 1)")

    run = sub.add_parser("run", help="run cases through the solvers")
    run.add_argument("cases", nargs="*", metavar="CASE", help="bundled case name or TOML path")
    run.add_argument("--all", action="store_true", help="every bundled case")
    run.add_argument("--convergence", action="store_true",
                     help="grid studies: also run every numerical solver on two grids "
                     "coarser by 1.5 and 1.5² and write DIR/<case>/convergence.csv "
                     "(observed order, Richardson extrapolation, GCI)")
    run.add_argument("--jump-study", action="store_true",
                     help="cycle-jump studies of fretting cases: also run every numerical "
                     "solver at half and a quarter of fretting.jump and write "
                     "DIR/<case>/jump_study.csv (change when J is halved, order, GCI)")
    common(run, solving=True)

    report = sub.add_parser("report", help="write DIR/index.html from the results in DIR")
    common(report, solving=False)

    gate = sub.add_parser("gate", help="print the metrics; exit 1 on any failure")
    common(gate, solving=False)
    gate.add_argument("--baseline", type=Path, metavar="DIR",
                      help="also fail on key numbers drifting from the baselines in DIR")
    gate.add_argument("--drift", type=float, default=None, metavar="REL",
                      help="allowed relative drift from the baseline (default 1e-6)")
    gate.add_argument("--update-baseline", type=Path, metavar="DIR",
                      help="write the baselines of the current results to DIR (explicit)")

    sweep = sub.add_parser("sweep", help="run a parameter sweep on Dask")
    sweep.add_argument("case", metavar="CASE")
    sweep.add_argument("--param", action="append", required=True,
                       metavar="KEY=START:STOP:STEP|V1,V2",
                       help="swept dotted key; repeat to zip several keys")
    sweep.add_argument("--scheduler", metavar="ADDRESS",
                       help="existing Dask scheduler (default: a LocalCluster)")
    sweep.add_argument("--workers", type=int, default=2,
                       help="LocalCluster worker processes; 0 runs serially (default 2)")
    sweep.add_argument("--check-serial", action="store_true",
                       help="re-run serially, check the numbers are identical and report "
                       "both wall times (DIR/<case>__sweep_*/sweep_check.json)")
    common(sweep, solving=True)

    _threshold_parser(sub, common)
    _article_parser(sub, common)
    return parser


def _article_parser(sub: Any, common: Any) -> None:
    """``contact-vv article``: the source article's claims judged
    (reports/run/article_sources.py)."""
    art = sub.add_parser("article", help="judge the source article's claims from the results "
                         "in DIR (running what is missing) and write DIR/article.html")
    art.add_argument("--claims", metavar="N,M-K", help="the claims to judge (default: all)")
    common(art, solving=True)


def _threshold_parser(sub: Any, common: Any) -> None:
    """The ``threshold`` sub-command (reports/run/threshold.py)."""
    thr = sub.add_parser("threshold", help="bisect a case key for the value at which an "
                         "event changes, per solver and grid (DIR/thresholds.csv)")
    thr.add_argument("case", metavar="CASE")
    thr.add_argument("--param", required=True, metavar="KEY", help="dotted case key bisected")
    thr.add_argument("--event", required=True, metavar="EVENT",
                     help="vm_max_on_surface or gross_to_partial_slip")
    thr.add_argument("--range", nargs=2, type=float, metavar=("LO", "HI"),
                     help="bracket (default: 0 1 for friction.mu*, 0 90 for friction.beta)")
    thr.add_argument("--resolution", type=float, metavar="R",
                     help="final bracket width (default: 0.01 for mu, 1 for beta)")
    thr.add_argument("--grids", metavar="F1,F2",
                     help="grid refinement factors: 1 the case grid, 2 finer by 2, 1/1.5 "
                     "coarser by 1.5 (default: 1,1/1.5)")
    thr.add_argument("--at", default="", metavar="VALUE",
                     help="output step: sliding distance s [mm] (sliding wear), cycle "
                     "(fretting), or s=V, cycle=N, step=N (default: the last)")
    thr.add_argument("--surface-depth", type=float, default=0.0, metavar="MM",
                     help="vm_max_on_surface: depth counted as the surface (default 0)")
    common(thr, solving=True)


# ------------------------------------------------------------------ commands


def cmd_list(args: argparse.Namespace) -> int:
    for name in BUNDLED:
        if not (CASES_DIR / f"{name}.toml").is_file():
            print(f"{name:26s} (case file missing)")
            continue
        try:
            points = load_case(name)
        except CaseError as exc:
            print(f"{name:26s} INVALID: {exc}")
            continue
        first = points[0]
        sweep = f"{len(points)} points" if len(points) > 1 else "1 point"
        print(f"{name:26s} {first.kind:13s} {sweep:10s} {first.description}")
    print()
    for s in solvers.names():
        ok, reason = solvers.available(s)
        kind = " (plugin)" if s in solvers.PLUGINS else ""
        print(f"solver {s:9s} {'available' if ok else 'unavailable: ' + reason}{kind}")
    return 0


def _report_runs(runs, out: Path) -> int:
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
        print(f"{PROG}: {r.name}: incomplete results left in {staging_dir(out, r.name)} "
              "(not reported as complete)", file=sys.stderr)
    if failed:
        return 2 if user else 1
    return 0


def _limits(args: argparse.Namespace):
    from reports.run.plan import Limits

    return Limits.from_flags(args.max_memory, args.max_hours, args.time_factor)


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
    chosen, skipped = select_solvers(_solver_list(args.solver), relations=args.quick)
    overrides = _overrides(args.overrides)
    limits = _limits(args)
    plans = [plan_case(n, chosen, quick=args.quick, overrides=overrides, skipped=skipped,
                       limits=limits, explicit=bool(_solver_list(args.solver)))
             for n in names]  # validate every case before running
    if args.convergence:
        from reports.run.study_runs import add_grid_studies

        plans = add_grid_studies(plans, limits)
    if args.jump_study:
        plans = _add_jumps(plans, limits)
    seen: dict[str, str] = {}
    for n, p in zip(names, plans, strict=True):
        if p.dir_name in seen:
            raise UserError(f"cases {seen[p.dir_name]} and {n} both write {p.dir_name}/")
        seen[p.dir_name] = n
    for p in plans:
        for w in p.warnings:
            print(f"{PROG}: warning: {w}", file=sys.stderr)
    progress = False if args.no_progress else None
    codes = [_report_runs([execute(p, args.out, progress=progress)], args.out)
             for p in plans]  # each case reported as soon as it is done
    return 2 if 2 in codes else max(codes)


def cmd_sweep(args: argparse.Namespace) -> int:
    from reports.run.plan import select_solvers
    from reports.run.runner import execute
    from reports.run.sweep import DaskExecutor, parse_param, plan_sweep
    from reports.run.units import serial_executor

    params = [parse_param(p) for p in args.param]
    if args.workers < 0:
        raise UserError("--workers must be >= 0")
    chosen, skipped = select_solvers(_solver_list(args.solver), relations=args.quick)
    plan = plan_sweep(args.case, params, chosen, quick=args.quick,
                      overrides=_overrides(args.overrides), skipped=skipped,
                      limits=_limits(args), explicit=bool(_solver_list(args.solver)))
    for w in plan.warnings:
        print(f"{PROG}: warning: {w}", file=sys.stderr)
    progress = False if args.no_progress else None
    t0 = time.perf_counter()
    if args.workers == 0 and not args.scheduler:
        run = execute(plan, args.out, executor=serial_executor, progress=progress,
                      extra_manifest={"executor": {"scheduler": "serial", "workers": 1}})
    else:
        with DaskExecutor(args.scheduler, args.workers) as dask:
            run = execute(plan, args.out, executor=dask, progress=progress,
                          extra_manifest={"executor": dask.info})
    wall = time.perf_counter() - t0
    code = _report_runs([run], args.out)
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


def _add_jumps(plans: list[Any], limits: Any) -> list[Any]:
    """The plans with their cycle-jump studies (:func:`reports.run.study_runs.add_jump_studies`)."""
    from reports.run.study_runs import add_jump_studies

    plans, notes = add_jump_studies(plans, limits)
    for note in notes:
        print(f"{PROG}: note: --jump-study: {note}", file=sys.stderr)
    return plans


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
    overrides = _overrides(args.overrides)
    if args.param in overrides:
        raise UserError(f"--set {args.param}: the key is the one --param bisects")
    chosen, skipped = select_solvers(_solver_list(args.solver))
    for name, reason in skipped.items():
        print(f"{PROG}: note: solver {name} skipped: {reason}", file=sys.stderr)
    request = th.Request(case=args.case, param=args.param, event=args.event, lo=lo, hi=hi,
                         resolution=res, grids=th.parse_grids(args.grids),
                         solvers=tuple(chosen), quick=args.quick, overrides=overrides,
                         options=options, limits=_limits(args),
                         explicit=bool(_solver_list(args.solver)))
    table.existing(args.out)  # a damaged table is refused before any work
    t0 = time.perf_counter()
    rows = th.run(request, log=None if args.no_progress else table.stderr_log)
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
    requested = _solver_list(args.solver)
    work = article.plan(args.out, args.quick, select_solvers(requested, relations=False)[0],
                        _limits(args), claims, bool(requested))
    print(work.describe())
    code = article.execute(work, args.out, progress=False if args.no_progress else None,
                           report=lambda runs: _report_runs(runs, args.out),
                           log=None if args.no_progress else stderr_log)
    path, findings = judge_and_write(args.out, args.quick, claims)
    for n, f in findings.items():
        print(f"claim {n:2d}: {f.verdict} — {f.why}")
    print(f"article: {path}")
    return code


def cmd_report(args: argparse.Namespace) -> int:
    from reports.render.html import write_report

    try:
        path = write_report(args.out)
    except RunFailed:  # written, showing incomplete or damaged cases: say where, exit 1
        print(f"report: {Path(args.out) / 'index.html'}")
        raise
    print(f"report: {path}")
    return 0


def cmd_gate(args: argparse.Namespace) -> int:
    from reports.render.gate import run_gate

    if args.drift is not None and not args.drift > 0:
        raise UserError("--drift must be a positive number")
    return run_gate(args.out, baseline=args.baseline, update_baseline=args.update_baseline,
                    drift_tol=args.drift)


COMMANDS = {"list": cmd_list, "run": cmd_run, "report": cmd_report, "gate": cmd_gate,
            "sweep": cmd_sweep, "threshold": cmd_threshold, "article": cmd_article}


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``contact-vv`` console script; returns the exit status.

    The one error boundary of the command line: every failure is one line
    ``contact-vv: error: …`` and an exit status (module doc); an unexpected exception
    shows its traceback only with ``--debug``."""
    try:
        args = build_parser().parse_args(argv)
    except SystemExit as exc:  # --help (0) or a bad flag (2)
        return int(exc.code or 0)
    for line in solvers.PLUGIN_ERRORS:  # a plugin left out: one line, the others run on
        print(f"{PROG}: warning: {line}", file=sys.stderr)
    try:
        return COMMANDS[args.command](args)
    except (UserError, CaseError) as exc:
        return _fail(str(exc))
    except OSError as exc:  # an unwritable --out, a full disk: the environment, not a bug
        where = f": {exc.filename}" if exc.filename else ""
        return _fail(f"{exc.strerror or exc}{where}")
    except RunFailed as exc:
        for line in exc.failures:
            print(f"{PROG}: error: {line}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print(f"{PROG}: interrupted; nothing incomplete is presented as complete",
              file=sys.stderr)
        return 130
    except MemoryError:
        print(f"{PROG}: error: out of memory (reduce the grid, stress.nz or the FEM mesh, "
              "or raise --max-memory only if the machine has it)", file=sys.stderr)
        return 1
    except Exception as exc:  # a bug: say so in one line, the traceback on request
        if args.debug:
            raise
        print(f"{PROG}: error: internal error: {type(exc).__name__}: {exc} (run with "
              "--debug for the traceback)", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
