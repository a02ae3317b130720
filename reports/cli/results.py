"""The commands that read a results directory: ``report`` and ``gate``."""

from __future__ import annotations

import argparse
import math
from pathlib import Path

from reports.registry.errors import RunFailed, UserError


def results_dir(args: argparse.Namespace) -> Path:
    """The results directory: DIR, or --out (UserError if both name different ones)."""
    if args.dir is not None and args.out != Path("results") and \
            Path(args.dir).resolve() != Path(args.out).resolve():
        raise UserError(f"DIR {args.dir} and --out {args.out} name two results directories; "
                        "give one")
    return Path(args.dir) if args.dir is not None else Path(args.out)


def cmd_report(args: argparse.Namespace) -> int:
    from reports.render.pages import write_report
    from reports.run.cluster import cores

    out = results_dir(args)
    workers = cores() if args.workers is None else args.workers
    if workers < 1:
        raise UserError("--workers must be >= 1 (1 draws the pages in this process)")
    try:
        path = write_report(out, workers)
    except RunFailed:  # written, showing incomplete or damaged cases: say where, exit 1
        print(f"report: {out / 'index.html'}")
        raise
    print(f"report: {path}")
    return 0


def cmd_gate(args: argparse.Namespace) -> int:
    from reports.render.gate import run_gate

    if args.drift is not None and not (math.isfinite(args.drift) and args.drift > 0):
        raise UserError("--drift must be a finite positive number")
    return run_gate(results_dir(args), baseline=args.baseline,
                    update_baseline=args.update_baseline, drift_tol=args.drift,
                    verbose=args.verbose, junit=args.junit)
