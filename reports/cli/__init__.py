"""The ``contact-vv`` command line: list, run, report, gate, sweep, threshold and article
(:mod:`.parser` parses, :mod:`.runs`, :mod:`.studies` and :mod:`.results` hold the
commands).

Exit status: 0 success; 1 a solver failed (did not converge, crashed) or the gate found
a failed metric, non-converged run or incomplete case; 2 a user error (bad case file,
unknown case or solver, bad flag, missing results directory), printed as
``contact-vv: error: <message>`` without a traceback; 130 interrupted; 141 the reader of
the output went away (``contact-vv list | head``), silently, as a tool that SIGPIPE ends.

Output the terminal's encoding cannot show (a non-ASCII path under ``LANG=C`` or
``PYTHONIOENCODING=ascii``) is printed with backslash escapes, never an error.
"""

from __future__ import annotations

import os
import select
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


#: the exit status of a command whose standard output was closed by its reader
PIPE_CLOSED = 141


def _escape_unencodable() -> None:
    """Standard output and error escape what their encoding cannot show."""
    for stream in (sys.stdout, sys.stderr):
        if hasattr(stream, "reconfigure"):
            stream.reconfigure(errors="backslashreplace")


def _stdout_closed() -> bool:
    """Whether standard output is a pipe its reader has closed (poll reports an error)."""
    try:
        poll = select.poll()
        poll.register(sys.stdout.fileno(), select.POLLOUT)
        return any(ev & select.POLLERR for _, ev in poll.poll(0))
    except (OSError, ValueError, AttributeError):
        return False


def _silence_stdout() -> None:
    """Send what is left to print to /dev/null: nothing more reaches the closed pipe, and
    the interpreter's last flush raises nothing."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, ValueError, AttributeError):
        pass


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``contact-vv`` console script; returns the exit status.

    The one error boundary of the command line: every failure is one line
    ``contact-vv: error: …`` and an exit status (module doc); an unexpected exception
    shows its traceback only with ``--debug``."""
    _escape_unencodable()
    try:
        args = build_parser().parse_args(argv)
    except SystemExit as exc:  # --help (0) or a bad flag (2)
        return int(exc.code or 0)
    for line in solvers.PLUGIN_ERRORS:  # a plugin left out: one line, the others run on
        print(f"{PROG}: warning: {line}", file=sys.stderr)
    try:
        _check_out(args)
        code = COMMANDS[args.command](args)
        sys.stdout.flush()  # a closed reader is met here, not at the interpreter's exit
        return code
    except (UserError, CaseError) as exc:
        return fail(str(exc))
    except BrokenPipeError as exc:
        if _stdout_closed():
            _silence_stdout()
            return PIPE_CLOSED
        return fail(f"{exc.strerror or exc}")
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
