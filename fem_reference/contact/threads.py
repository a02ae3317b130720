"""Temporarily single-threaded OpenBLAS for the many mid-size dense solves of the contact loop.

On a small shared machine, OpenBLAS's thread hand-off made a 300 x 300 LU take 0.14 s
with 2 threads against 1 ms with one (measured under load); the contact iteration does
hundreds of such solves, so it runs them single-threaded.  The OpenBLAS copies loaded
by numpy and scipy are found in ``/proc/self/maps`` (Linux) and driven through their
exported ``*openblas_set_num_threads*`` functions; elsewhere this is a no-op.
"""

from __future__ import annotations

import ctypes
from collections.abc import Iterator
from contextlib import contextmanager
from functools import lru_cache

_SUFFIXES = ("", "64_", "_64_", "_")
_PREFIXES = ("openblas", "scipy_openblas")


@lru_cache(maxsize=1)
def _controls() -> tuple[tuple, ...]:
    try:
        with open("/proc/self/maps") as fh:
            paths = {line.split()[-1] for line in fh if "openblas" in line.lower()}
    except OSError:
        return ()
    found = []
    for path in sorted(p for p in paths if p.startswith("/")):
        try:
            lib = ctypes.CDLL(path)
        except OSError:
            continue
        for prefix in _PREFIXES:
            pair = None
            for suffix in _SUFFIXES:
                try:
                    setter = getattr(lib, f"{prefix}_set_num_threads{suffix}")
                    getter = getattr(lib, f"{prefix}_get_num_threads{suffix}")
                except AttributeError:
                    continue
                setter.argtypes, setter.restype = [ctypes.c_int], None
                getter.argtypes, getter.restype = [], ctypes.c_int
                pair = (getter, setter)
                break
            if pair:
                found.append(pair)
                break
    return tuple(found)


@contextmanager
def blas_threads(n: int = 1) -> Iterator[None]:
    """Run the block with at most ``n`` OpenBLAS threads, then restore the previous counts."""
    saved = []
    for getter, setter in _controls():
        try:
            saved.append((setter, int(getter())))
            setter(n)
        except (OSError, ValueError):
            continue
    try:
        yield
    finally:
        for setter, count in saved:
            setter(count)
