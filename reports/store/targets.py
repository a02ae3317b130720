"""The files a user names on the command line (``--junit FILE``): a path, ``-`` (standard
output), or what a shell or CI system hands over — ``/dev/stdout``, a pipe, a device.

A regular file is written atomically (:func:`cases.result.atomic_write_text`); anything
else is a stream, written once and never read (reading ``/dev/stdout`` on a pipe blocks,
reading ``/dev/full`` never ends).  :func:`check` refuses, before any work, a target that
cannot be written: a directory, a parent that is a file, a read-only or full file
system, a device that refuses data (``/dev/full``).
"""

from __future__ import annotations

import os
import stat
import sys
from pathlib import Path

from cases.result import atomic_write_text
from reports.registry.errors import UserError

#: the name of standard output
STDOUT = "-"


def _mode(path: Path) -> int | None:
    try:
        return os.stat(path).st_mode
    except OSError:
        return None


def is_stdout(path: Path) -> bool:
    """Whether ``path`` is this process's standard output (``-``, ``/dev/stdout``, …)."""
    if str(path) == STDOUT:
        return True
    try:
        mine, its = os.fstat(sys.stdout.fileno()), os.stat(path)
    except (OSError, ValueError, AttributeError):  # no stdout file descriptor, no path
        return False
    return (mine.st_dev, mine.st_ino) == (its.st_dev, its.st_ino)


def is_stream(path: Path) -> bool:
    """Whether ``path`` is written as a stream: standard output (:func:`is_stdout`, even
    when it is a regular file: replacing it would cut the shell's file), or an existing
    file that is not a regular one (a pipe, a device, a socket)."""
    if is_stdout(path):
        return True
    mode = _mode(path)
    return mode is not None and not stat.S_ISREG(mode) and not stat.S_ISDIR(mode)


def _probe(path: Path, option: str) -> None:
    """A zero-length write: a device that refuses data (``/dev/full``) fails it."""
    try:
        fd = os.open(path, os.O_WRONLY | os.O_NONBLOCK)
    except OSError as exc:
        raise UserError(f"{option} {path}: cannot be written ({exc.strerror})") from None
    try:
        os.write(fd, b"")
    except OSError as exc:
        raise UserError(f"{option} {path}: cannot be written ({exc.strerror})") from None
    finally:
        os.close(fd)


def check(path: Path, option: str) -> None:
    """UserError, naming ``option`` and ``path``, unless a text can be written there."""
    path = Path(path)
    if str(path) == STDOUT:
        return
    mode = _mode(path)
    if mode is not None and stat.S_ISDIR(mode):
        raise UserError(f"{option} {path}: is a directory; name a file in it")
    if is_stream(path):
        if mode is not None and stat.S_ISCHR(mode):  # never a pipe: its reader sees EOF
            _probe(path, option)
        return
    parent = path.absolute().parent
    while not parent.exists() and parent != parent.parent:
        parent = parent.parent
    if not parent.is_dir():
        raise UserError(f"{option} {path}: {parent} is a file, not a directory")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise UserError(f"{option} {path}: {parent} cannot be written (read-only or "
                        "not permitted)")
    room = os.statvfs(parent)
    if room.f_blocks and not room.f_bavail:  # (a pseudo file system has no blocks)
        raise UserError(f"{option} {path}: no space left on the device of {parent}")


def head(path: Path, size: int = 4096) -> bytes:
    """The first ``size`` bytes of the regular file ``path`` (b"" for a stream or none)."""
    if is_stream(path) or _mode(path) is None:
        return b""
    try:
        with open(path, "rb") as fh:
            return fh.read(size)
    except OSError:
        return b""


def write_text(path: Path, text: str, option: str) -> None:
    """Write ``text`` to ``path``: atomically for a file, once for a stream."""
    path = Path(path)
    try:
        if is_stdout(path):
            sys.stdout.write(text)
            sys.stdout.flush()
        elif is_stream(path):
            with open(path, "w", encoding="utf-8") as fh:
                fh.write(text)
        else:
            atomic_write_text(path, text)
    except OSError as exc:
        raise UserError(f"{option} {path}: cannot be written ({exc.strerror or exc})") \
            from None
