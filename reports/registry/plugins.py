"""Solver plugins: the records installed packages register under the entry-point group
:data:`GROUP` (the protocol and an example: ``reports/README.md``, "Solver plugins").

An entry point ``NAME = "package.module:attr"`` names a
:class:`reports.registry.record.SolverRecord` called NAME, or a function of no argument
that returns one (or None: the plugin has nothing to offer here, e.g. its peer code is
not installed).  NAME is lower-case letters, digits and ``_`` (``-`` joins the two
solvers of a pair, ``+`` names a metamorphic relation, ``,`` separates ``--solver``
names) and no built-in solver's name.  A plugin is compared with every other solver as
the first of each pair: the built-in solvers are its references.

A plugin that cannot load, or loads as something else, is left out with one line naming
it and why (:data:`reports.registry.solvers.PLUGIN_ERRORS`, printed by the CLI); the
built-in solvers never depend on it.
"""

from __future__ import annotations

import contextlib
import os
import re
import sys
import tempfile
from collections.abc import Collection, Iterator
from importlib import metadata

from reports.registry.record import SolverRecord

GROUP = "contact_vv.solvers"
NAME = re.compile(r"[a-z][a-z0-9_]*")


def _where(ep: metadata.EntryPoint) -> str:
    dist = getattr(ep, "dist", None)
    origin = f" of {dist.name} {dist.version}" if dist is not None else ""
    return f"solver plugin {ep.name!r} ({ep.value}{origin})"


def _record(ep: metadata.EntryPoint, taken: Collection[str]) -> SolverRecord | None:
    """The record entry point ``ep`` registers (None: nothing to offer); ValueError with
    the reason when it cannot be used."""
    if not NAME.fullmatch(ep.name):
        raise ValueError("a solver name is lower-case letters, digits and '_', starting "
                         "with a letter")
    if ep.name in taken:
        raise ValueError("the name is taken by a built-in solver or an earlier plugin")
    try:
        obj = ep.load()
        if callable(obj) and not isinstance(obj, SolverRecord):
            obj = obj()
    except Exception as exc:  # anything a foreign package raises
        raise ValueError(f"cannot load it: {type(exc).__name__}: {exc}") from None
    if obj is None:
        return None
    if not isinstance(obj, SolverRecord):
        raise ValueError(f"it gives a {type(obj).__name__}, not a "
                         "reports.registry.record.SolverRecord")
    if obj.name != ep.name:
        raise ValueError(f"its record is named {obj.name!r}")
    if obj.relation is not None or obj.base:
        raise ValueError("a plugin cannot be a metamorphic relation of another solver")
    return obj


def load(builtin: Collection[str], group: str = GROUP
         ) -> tuple[dict[str, SolverRecord], list[str]]:
    """(the installed plugins' records by name, in the order found; one line per plugin
    left out, naming it and why)."""
    records: dict[str, SolverRecord] = {}
    errors: list[str] = []
    for ep in metadata.entry_points(group=group):
        try:
            rec = _record(ep, set(builtin) | set(records))
        except ValueError as exc:
            errors.append(f"{_where(ep)} left out: {exc}")
            continue
        if rec is not None:
            records[ep.name] = rec
    return records, errors


@contextlib.contextmanager
def silenced() -> Iterator[None]:
    """Keep what a plugin's peer code writes to file descriptors 1 and 2 (a banner, a log
    line per iteration) out of the run's output: both point at a scratch file while the
    block runs, and back after it, also when it raises."""
    sys.stdout.flush()
    sys.stderr.flush()
    saved = [os.dup(fd) for fd in (1, 2)]
    with tempfile.TemporaryFile() as sink:
        for fd in (1, 2):
            os.dup2(sink.fileno(), fd)
        try:
            yield
        finally:
            for fd, old in zip((1, 2), saved, strict=True):
                os.dup2(old, fd)
                os.close(old)
