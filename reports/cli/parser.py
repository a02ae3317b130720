"""The ``contact-vv`` argument parser and the options every command parses the same way
(``--solver``, ``--set``, the limits), each parsed by one function here."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from reports.registry import solvers
from reports.registry.errors import UserError

PROG = "contact-vv"


class _Parser(argparse.ArgumentParser):
    def error(self, message: str):  # argparse's usage + "prog: error: msg", exit 2
        self.print_usage(sys.stderr)
        raise SystemExit(fail(message))


def fail(message: str) -> int:
    """Print ``contact-vv: error: message``; the exit status of a user error."""
    print(f"{PROG}: error: {message}", file=sys.stderr)
    return 2


def parse_solvers(text: str | None) -> list[str] | None:
    """The solver names of ``--solver`` (None: not given)."""
    if text is None:
        return None
    names = [s.strip() for s in text.split(",") if s.strip()]
    if not names:
        raise UserError("--solver needs at least one solver name")
    return names


def parse_overrides(items: Sequence[str] | None) -> dict[str, Any]:
    """The dotted case keys of ``--set KEY=VALUE``."""
    from reports.run.sweep import parse_value

    out: dict[str, Any] = {}
    for item in items or ():
        key, eq, value = item.partition("=")
        if not eq or not key.strip():
            raise UserError(f"--set {item!r}: expected KEY=VALUE (a dotted case key)")
        out[key.strip()] = parse_value(value)
    return out


def limits_of(args: argparse.Namespace):
    """The memory, time and deadline limits of ``--max-memory``, ``--max-hours``,
    ``--time-factor``."""
    from reports.run.plan import Limits

    return Limits.from_flags(args.max_memory, args.max_hours, args.time_factor)


def cluster_options(p: argparse.ArgumentParser, *, workers: int) -> None:
    """``--workers`` and ``--scheduler``: the units as tasks on a Dask cluster
    (:mod:`reports.run.cluster`)."""
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="run the units on this Dask scheduler (e.g. tcp://host:8786)")
    p.add_argument("--workers", type=int, default=None,
                   help="run the units on a LocalCluster of this many single-threaded "
                   "worker processes, at most one per core and as many as the memory "
                   "holds; 0 runs them in this process (default "
                   f"{workers}{', or the cores if fewer' if workers > 1 else ''})")
    p.set_defaults(default_workers=workers)


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
            p.add_argument("--solver", help="comma-separated solvers of "
                           f"{','.join(solvers.names())} (default: the built-in ones that "
                           "run on the case by default, with their exact relations at "
                           "--quick; a plugin only when named: contact-vv list), or "
                           "external:NAME for the result files of the case's "
                           "[external.NAME] table")
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
                           help="this processor's slowness against the estimates' "
                           "(scales --max-hours checks and each run's CPU-time budget; "
                           "a busy machine needs none; default 1)")

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
    cluster_options(run, workers=0)
    common(run, solving=True)

    def results_dir(p: argparse.ArgumentParser) -> None:
        p.add_argument("dir", nargs="?", type=Path, metavar="DIR",
                       help="results directory (the same as --out; default ./results)")
        common(p, solving=False)

    report = sub.add_parser("report", help="write DIR/index.html from the results in DIR")
    results_dir(report)
    report.add_argument("--workers", type=int, default=None,
                        help="draw the case pages in this many processes (default: the "
                        "cores; 1 draws them in this one)")

    _gate_parser(sub, results_dir)

    sweep = sub.add_parser("sweep", help="run a parameter sweep on Dask")
    sweep.add_argument("case", metavar="CASE")
    sweep.add_argument("--param", action="append", required=True,
                       metavar="KEY=START:STOP:STEP|V1,V2",
                       help="swept dotted key; repeat to zip several keys")
    cluster_options(sweep, workers=2)
    sweep.add_argument("--check-serial", action="store_true",
                       help="re-run serially, check the numbers are identical and report "
                       "both wall times (DIR/<case>__sweep_*/sweep_check.json)")
    common(sweep, solving=True)

    _threshold_parser(sub, common)
    _article_parser(sub, common)
    return parser


def _gate_parser(sub: Any, results_dir: Any) -> None:
    """``contact-vv gate``: the verdict on the results in DIR."""
    gate = sub.add_parser("gate", help="print the verdict, the failures and a line per "
                          "case of the results in DIR; exit 1 on any failure")
    results_dir(gate)
    gate.add_argument("--verbose", action="store_true",
                      help="also every metric row, not-gated row and study note")
    gate.add_argument("--junit", type=Path, metavar="FILE",
                      help="also write the verdict as JUnit XML (one test case per row)")
    gate.add_argument("--baseline", type=Path, metavar="DIR",
                      help="also fail on key numbers drifting from the baselines in DIR")
    gate.add_argument("--drift", type=float, default=None, metavar="REL",
                      help="allowed relative drift from the baseline (default 1e-6)")
    gate.add_argument("--update-baseline", type=Path, metavar="DIR",
                      help="write the baselines of the current results to DIR (explicit)")


def _article_parser(sub: Any, common: Any) -> None:
    """``contact-vv article``: the source article's claims judged
    (reports/run/article_sources.py)."""
    art = sub.add_parser("article", help="judge the source article's claims from the results "
                         "in DIR (running what is missing) and write DIR/article.html")
    art.add_argument("--claims", metavar="N,M-K", help="the claims to judge (default: all)")
    cluster_options(art, workers=0)
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
    cluster_options(thr, workers=0)
    common(thr, solving=True)
