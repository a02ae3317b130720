"""The ``contact-vv`` command line: list, run, report, gate, sweep, threshold and article
(:mod:`.parser` parses, :mod:`.runs`, :mod:`.studies` and :mod:`.results` hold the
commands).

Exit status: 0 success; 1 a solver failed (did not converge, crashed) or the gate found
a failed metric, non-converged run or incomplete case; 2 a user error (bad case file,
unknown case or solver, bad flag, missing results directory), printed as
``contact-vv: error: <message>`` without a traceback; 130 interrupted.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence

from cases.model import CaseError
from reports.cli.parser import PROG, build_parser, fail
from reports.cli.results import cmd_gate, cmd_report
from reports.cli.runs import cmd_list, cmd_run, cmd_sweep
from reports.cli.studies import cmd_article, cmd_threshold
from reports.registry import solvers
from reports.registry.errors import RunFailed, UserError

COMMANDS = {"list": cmd_list, "run": cmd_run, "report": cmd_report, "gate": cmd_gate,
            "sweep": cmd_sweep, "threshold": cmd_threshold, "article": cmd_article}


def _check_out(args) -> None:
    """A results directory that names an existing file is refused, naming it."""
    for out in (getattr(args, "dir", None), getattr(args, "out", None)):
        if out is not None and out.exists() and not out.is_dir():
            raise UserError(f"results directory {out} is a file, not a directory; choose "
                            "another --out")


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
        _check_out(args)
        return COMMANDS[args.command](args)
    except (UserError, CaseError) as exc:
        return fail(str(exc))
    except OSError as exc:  # an unwritable --out, a full disk: the environment, not a bug
        where = f": {exc.filename}" if exc.filename else ""
        return fail(f"{exc.strerror or exc}{where}")
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
