"""The deadline of one solver run: no run goes on past its cost estimate by more than the
estimate's calibration factor (:attr:`cases.result.Cost.time_factor`).

A run of solver S on case C may take ``ALLOWANCE_S + slowdown · f · t`` seconds, t the
solver's own estimate, f its calibration and ``slowdown`` the ``--time-factor`` of a
slower or busier machine; past that it is stopped with :class:`Overrun`, a failure of
that run naming the estimate.  The stop is an alarm signal, so it holds where runs are
made in the main thread (``run``, ``sweep --workers 0``, ``threshold``); a Dask sweep
waits on its tasks for the sum of their deadlines.
"""

from __future__ import annotations

import math
import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager

#: what every run may take beyond its estimate: imports, start-up, writing
ALLOWANCE_S = 30.0


class Overrun(RuntimeError):
    """A run went on past its deadline."""


def seconds(estimate_s: float, time_factor: float, slowdown: float = 1.0) -> float:
    """The deadline [s] of a run estimated at ``estimate_s`` (inf when not calibrated)."""
    limit = ALLOWANCE_S + slowdown * time_factor * estimate_s
    return limit if math.isfinite(limit) else math.inf


@contextmanager
def deadline(limit_s: float, what: str) -> Iterator[None]:
    """Raise :class:`Overrun` in the block once it has run ``limit_s`` seconds (no limit
    when infinite, or outside the main thread, where no alarm can be delivered)."""
    if not math.isfinite(limit_s) or threading.current_thread() is not threading.main_thread():
        yield
        return

    def alarm(signum: int, frame: object) -> None:
        raise Overrun(f"{what} ran past its deadline of {limit_s:.3g} s (its cost estimate "
                      "times the estimate's calibration factor, plus "
                      f"{ALLOWANCE_S:g} s); stopped (on a slower or busier machine, "
                      "raise --time-factor)")

    old = signal.signal(signal.SIGALRM, alarm)
    signal.setitimer(signal.ITIMER_REAL, limit_s)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0.0)
        signal.signal(signal.SIGALRM, old)
