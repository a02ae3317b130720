"""The directories of a case run: a per-case lock held for the whole run, the staging
directory the run writes into, and removal by renaming away first.

The lock (an OS file lock on ``DIR/.<case>.lock``, :func:`case_lock`) is held from before
the staging directory is claimed until after it is renamed onto ``DIR/<case>``, so two
runs of one case never share or remove each other's directories: the second one is
refused with the first one's pid.  Holding the lock, a staging directory found on disk
can only be an interrupted run's: it is discarded with a note (runs do not resume), but
only if it holds nothing a run does not write.  The lock file is removed when the run
ends (:func:`held`: while still held, so that no second holder can appear).
"""

from __future__ import annotations

import errno
import fcntl
import os
import re
import shutil
import stat
import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import TextIO

from reports.registry.errors import UserError
from reports.store import layout

#: what a staging directory may hold besides the result files (layout.OWN_NAMES)
_STAGING_EXTRA = frozenset({layout.FAILED, ".pid"})


@contextmanager
def held(path: Path, *, wait: bool = True,
         busy: Callable[[str], Exception] | None = None) -> Iterator[TextIO]:
    """Hold an exclusive OS lock on the file ``path`` (created if absent, :func:`open_lock`)
    and remove the file at the end, while still holding it, if it holds nothing but what
    a run writes (its pid, or nothing).  A process that waited on the removed file finds,
    once it holds it, that the path no longer names it and locks the file that replaced
    it, so two holders never coexist.  ``wait=False``: ``busy(holder's pid)`` is raised
    if another process holds it."""
    while True:
        fh = open_lock(path)
        try:
            fcntl.flock(fh, fcntl.LOCK_EX | (0 if wait else fcntl.LOCK_NB))
        except BlockingIOError:
            fh.seek(0)
            holder = fh.read().strip() or "?"
            fh.close()
            raise (busy or UserError)(holder) from None
        if _names(path, fh):
            break
        fh.close()  # removed by its last holder: lock the file that replaced it
    try:
        yield fh
    finally:
        try:
            fh.seek(0)
            if _names(path, fh) and re.fullmatch(r"\d*", fh.read().strip()):
                path.unlink()
        finally:
            fh.close()  # closing releases the lock


def _names(path: Path, fh: TextIO) -> bool:
    """Whether ``path`` still names the open file ``fh``."""
    try:
        st = os.stat(path, follow_symlinks=False)
    except FileNotFoundError:
        return False
    mine = os.fstat(fh.fileno())
    return (st.st_ino, st.st_dev) == (mine.st_ino, mine.st_dev)


@contextmanager
def case_lock(out: Path, name: str) -> Iterator[Path]:
    """Hold the lock of case ``name`` in ``out`` (UserError if another run holds it);
    the lock file is removed when the run ends (:func:`held`)."""
    path = layout.lock_file(out, name)

    def busy(holder: str) -> UserError:
        return UserError(f"another contact-vv run (pid {holder}) is writing case {name} in "
                         f"{out}; wait for it to end or choose another --out")

    with held(path, wait=False, busy=busy) as fh:
        fh.seek(0)
        if re.fullmatch(r"\d*", fh.read().strip()):  # a run's (a pid) or new: ours now
            fh.seek(0)
            fh.truncate()
            fh.write(str(os.getpid()))
            fh.flush()
        yield path


def open_lock(path: Path):
    """A lock file opened for reading and writing, created if absent, never through a
    symbolic link (UserError naming it: the run would write its pid into the target)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    try:
        fd = os.open(path, os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW, 0o666)
    except OSError as exc:
        raise UserError(f"{path}: cannot be used as a lock file ({exc.strerror}"
                        + ("; it is a symbolic link" if path.is_symlink() else "")
                        + "); remove it or choose another --out") from None
    if not stat.S_ISREG(os.fstat(fd).st_mode):
        os.close(fd)
        raise UserError(f"{path}: not a regular file; remove it or choose another --out")
    return os.fdopen(fd, "r+")


def _ours(path: Path, extra: frozenset[str]) -> bool:
    """Whether a staging directory holds only what a run writes into one, at any depth
    (:func:`reports.store.layout.foreign`; ``extra``: more names a run writes at the top)."""
    return layout.foreign(path, _STAGING_EXTRA | extra) is None


def claim_staging(out: Path, name: str, extra: frozenset[str] = frozenset()) -> Path:
    """Create a fresh staging directory for ``name`` (the caller holds the case's lock);
    ``extra``: names beyond :data:`reports.store.layout.OWN_NAMES` a run writes at the top
    (the studies' tables)."""
    staging = layout.staging_dir(out, name)
    _remove_leftovers(out, name, extra)
    if staging.exists() or staging.is_symlink():
        if staging.is_symlink() or not (staging.is_dir() and _ours(staging, extra)):
            raise UserError(f"{staging} exists and is not a contact-vv staging directory; "
                            "refusing to remove it (choose another --out)")
        kept = sum(1 for _ in staging.rglob("step_*.npz"))
        print(f"contact-vv: {staging} holds an interrupted run of {name} ({kept} output "
              "step file(s) kept); runs do not resume: discarding it and restarting "
              f"{name} from the beginning", file=sys.stderr)
        remove_dir(staging)
    staging.mkdir(parents=True)
    return staging


#: renameat2's flag that swaps two paths in one step (Linux 3.15; ext4, xfs, btrfs, tmpfs)
_RENAME_EXCHANGE = 2
_AT_FDCWD = -100


def _exchange(a: Path, b: Path) -> bool:
    """Swap the entries ``a`` and ``b`` in one step; False where the system cannot."""
    import ctypes
    import ctypes.util

    try:
        libc = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6", use_errno=True)
        renameat2 = libc.renameat2
    except (OSError, AttributeError):  # not glibc 2.28+, not Linux
        return False
    renameat2.argtypes = [ctypes.c_int, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p,
                          ctypes.c_uint]
    done = renameat2(_AT_FDCWD, os.fsencode(a), _AT_FDCWD, os.fsencode(b), _RENAME_EXCHANGE)
    if done == 0:
        return True
    err = ctypes.get_errno()
    if err in (errno.EINVAL, errno.ENOSYS, errno.ENOTSUP):  # a file system without it
        return False
    raise OSError(err, os.strerror(err), str(a))


def replace_dir(staging: Path, final: Path) -> None:
    """Put the directory ``staging`` in place of ``final`` and remove the old one: in one
    step where the system can swap two paths (:func:`_exchange`), so that ``final`` is
    never absent; else by renaming the old one away first."""
    if final.exists() and _exchange(staging, final):
        shutil.rmtree(staging)  # the old one, swapped out
        return
    remove_dir(final)
    os.replace(staging, final)


def _remove_leftovers(out: Path, name: str, extra: frozenset[str]) -> None:
    """Remove what a killed removal of ``name``'s directories left (:func:`remove_dir`'s
    ``.<case>.old-<pid>`` and ``..<case>.partial.old-<pid>``) where it holds only a run's
    files; the caller holds the case's lock, so no live run owns them."""
    final, staging = layout.case_dir(out, name), layout.staging_dir(out, name)
    olds = re.compile("|".join(re.escape(f".{p.name}.old-") + r"\d+" for p in (final, staging)))
    for left in Path(out).iterdir():
        if olds.fullmatch(left.name) and left.is_dir() and not left.is_symlink() \
                and _ours(left, extra):
            shutil.rmtree(left, ignore_errors=True)


def _old(path: Path, pid: int) -> Path:
    """Where :func:`remove_dir` renames ``path`` before removing it."""
    return path.with_name(f".{path.name}.old-{pid}")


def remove_dir(path: Path) -> None:
    """Remove a directory by first renaming it away (the removal itself is not atomic)."""
    if path.exists():
        trash = _old(path, os.getpid())
        if trash.exists():
            shutil.rmtree(trash)
        os.replace(path, trash)
        shutil.rmtree(trash, ignore_errors=True)
