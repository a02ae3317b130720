"""Exceptions the CLI turns into messages and exit codes (never tracebacks)."""

from __future__ import annotations


class UserError(Exception):
    """A mistake in what the user asked for (bad flag, missing results, unknown solver).

    The CLI prints ``contact-vv: error: <message>`` and exits with status 2.
    """


class SolverUnavailable(UserError):
    """A solver's entry point cannot be imported (its package has not landed or is broken)."""


class RunFailed(Exception):
    """One or more solver runs failed (did not converge or raised); exit status 1.

    ``failures`` holds one human-readable line per failed (case, solver, param).
    """

    def __init__(self, failures: list[str]):
        self.failures = list(failures)
        super().__init__("; ".join(self.failures))


class IncompleteRun(Exception):
    """A case directory whose manifest is missing, incomplete or contradicted by its files
    (a result problem: exit status 1)."""
