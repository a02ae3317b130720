"""The commands that read a results directory: ``report`` and ``gate``."""

from __future__ import annotations

import argparse
from pathlib import Path

from reports.registry.errors import RunFailed, UserError


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
