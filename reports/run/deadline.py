"""The deadline of one solver run: it stops a hung run, never a slow one.

A run is stopped for one of two reasons, both measured on the process's own CPU time
(all its threads, and its child processes), which a busier machine does not inflate the
way it inflates wall time:

- **past its budget**: its CPU time exceeds ``ALLOWANCE_S + slowdown · f · t · c`` seconds,
  t the solver's own estimate of the wall time on the calibration machine, f the estimate's
  calibration (:attr:`cases.result.Cost.time_factor`), c = max(the cores this process may
  use, ``CALIBRATION_CORES``) the threads that wall time may have been spent on, and
  ``slowdown`` the ``--time-factor`` of a slower processor.  This stops a run that loops;
- **no progress**: over ``STALL_S`` seconds of wall time it used less than
  ``STALL_FRACTION`` of one core (a machine a hundred times busier still gives a runnable
  process more).  This stops a run that waits forever (a deadlock, a sleep, a lost
  sub-process), which spends no CPU time and so would never reach its budget.

A watchdog thread measures both once a second and, when one is met, stops the block: in
the main thread (``run``, ``sweep --workers 0``, ``threshold``) by one alarm signal, whose
handler raises :class:`Overrun` naming the reason; in another thread (a Dask worker's task,
``--workers``) by an asynchronous exception raised in that thread at its next Python
instruction, turned into the same :class:`Overrun` (a long call into compiled code is
stopped when it returns).  In the main thread both reasons read the process's CPU time
and its children's.  In another thread the budget reads the thread's own CPU time (a
worker's other tasks are not the run's, and never stop it), and the progress the
process's (the run's helper threads compute for it: a thread waiting on them is not
hung).  A run blocked inside a system call is stopped in the main thread (the signal
interrupts the call) but not in another thread, where the stop waits for the call to
return.
"""

from __future__ import annotations

import ctypes
import math
import os
import signal
import threading
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager

#: CPU time every run may take beyond its estimate: imports, start-up, writing
ALLOWANCE_S = 30.0
#: the cores of the machine the cost estimates were calibrated on (benchmarks/README.md)
CALIBRATION_CORES = 2
#: the wall-time window [s] over which a run must use at least STALL_FRACTION of a core
STALL_S = 120.0
STALL_FRACTION = 0.01
#: how often [s] the watchdog looks
TICK_S = 1.0


class Overrun(RuntimeError):
    """A run went on past its deadline, or made no progress."""


def cores() -> int:
    """The cores this process may run on."""
    try:
        return len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        return os.cpu_count() or 1


def seconds(estimate_s: float, time_factor: float, slowdown: float = 1.0) -> float:
    """The CPU-time budget [s] of a run estimated at ``estimate_s`` of wall time (inf when
    not calibrated)."""
    limit = ALLOWANCE_S + slowdown * time_factor * estimate_s * max(cores(), CALIBRATION_CORES)
    return limit if math.isfinite(limit) else math.inf


def cpu_seconds() -> float:
    """CPU time [s] of this process (all threads) and of its child processes: the live
    ones', and the ended ones' (``os.times``: a program a solver ran, e.g. the calculix
    plugin's ccx, whose time would otherwise drop out of the count as it ends, a fall the
    progress window would read as a hung run)."""
    ended = os.times()
    spent = time.process_time() + ended.children_user + ended.children_system
    try:
        import psutil

        for child in psutil.Process().children(recursive=True):
            try:
                t = child.cpu_times()
                spent += t.user + t.system
            except psutil.Error:
                pass
    except ImportError:  # pragma: no cover - psutil comes with dask.distributed
        pass
    return spent


def _thread_clock(ident: int) -> Callable[[], float]:
    """The CPU time [s] of the thread ``ident`` (this process), read from any thread."""
    clock = time.pthread_getcpuclockid(ident)
    return lambda: time.clock_gettime(clock)


class _AsyncStop(Exception):
    """Raised in a non-main thread by its watchdog; the block turns it into Overrun."""


def _process_clock() -> float:
    """The process's CPU time and its children's, but the calling (watchdog) thread's."""
    return cpu_seconds() - time.thread_time()


class _Watch:
    """The watchdog's state: the budget, the progress window, and why it stopped;
    ``clock`` the CPU time the budget reads (as the watchdog thread reads it, from
    ``start``), the progress window the process's (module doc)."""

    def __init__(self, limit_s: float, what: str, clock: Callable[[], float],
                 start: float) -> None:
        self.limit_s, self.what, self.clock, self.start = limit_s, what, clock, start
        self.cpu = cpu_seconds()  # the last reading (the watchdog's own thread starts at 0)
        self.done = 0.0  # the progress so far: the rises of the readings, summed
        self.window = [(time.monotonic(), self.done)]
        self.reason: str | None = None

    def look(self) -> str | None:
        """The reason to stop now, if any (called from the watchdog thread)."""
        now = time.monotonic()
        if self.clock() - self.start > self.limit_s:
            return (f"{self.what} ran past its deadline of {self.limit_s:.3g} s of CPU time "
                    f"(its cost estimate times the estimate's calibration factor and the "
                    f"cores, plus {ALLOWANCE_S:g} s); stopped (on a slower processor, "
                    "raise --time-factor)")
        # a child process that has ended but is not yet reaped is in neither psutil's
        # list nor os.times for a moment: the reading falls, and a fall is no work undone
        cpu = _process_clock()
        self.done += max(cpu - self.cpu, 0.0)
        self.cpu = cpu
        self.window.append((now, self.done))
        while len(self.window) > 1 and now - self.window[1][0] >= STALL_S:
            self.window.pop(0)
        t0, done0 = self.window[0]
        spent = self.done - done0
        if now - t0 >= STALL_S and spent < STALL_FRACTION * (now - t0):
            return (f"{self.what} made no progress: {spent:.3g} s of CPU time in the "
                    f"last {now - t0:.3g} s (less than {STALL_FRACTION:.0%} of a core); "
                    "stopped as hung")
        return None


@contextmanager
def deadline(limit_s: float, what: str) -> Iterator[None]:
    """Raise :class:`Overrun` in the block once it has spent ``limit_s`` seconds of CPU
    time or made no progress for ``STALL_S`` seconds (the budget is unlimited when
    infinite), in the main thread or in any other (module doc)."""
    if threading.current_thread() is not threading.main_thread():
        with _in_thread(limit_s, what):
            yield
        return
    watch = _Watch(limit_s, what, _process_clock, cpu_seconds())
    done = threading.Event()
    main = threading.main_thread().ident

    def alarm(signum: int, frame: object) -> None:
        if watch.reason is not None and not done.is_set():
            raise Overrun(watch.reason)
        if callable(old):  # an enclosing deadline's alarm
            old(signum, frame)

    old = signal.signal(signal.SIGALRM, alarm)
    try:
        with _watchdog(watch, done, lambda: signal.pthread_kill(main, signal.SIGALRM)):
            yield
    finally:
        signal.signal(signal.SIGALRM, old)


@contextmanager
def _in_thread(limit_s: float, what: str) -> Iterator[None]:
    """The deadline in a thread other than the main one: a budget of the thread's own CPU
    time, and an asynchronous exception of this block's own class to stop it (an
    enclosing block's passes through to that block)."""
    ident = threading.get_ident()
    clock = _thread_clock(ident)
    watch = _Watch(limit_s, what, clock, clock())
    done = threading.Event()
    lock = threading.Lock()  # the stop is raised only while the block runs
    mine = type("_AsyncStop", (_AsyncStop,), {})

    def stop() -> None:
        with lock:
            if not done.is_set():
                ctypes.pythonapi.PyThreadState_SetAsyncExc(ctypes.c_ulong(ident),
                                                           ctypes.py_object(mine))

    try:
        with _watchdog(watch, done, stop, lock):
            yield
    except mine:
        raise Overrun(watch.reason) from None
    finally:
        if watch.reason is not None:  # a stop not yet raised when the block ended
            ctypes.pythonapi.PyThreadState_SetAsyncExc(ctypes.c_ulong(ident), None)


@contextmanager
def _watchdog(watch: _Watch, done: threading.Event, stop: Callable[[], None],
              lock: threading.Lock | None = None) -> Iterator[None]:
    """A watchdog thread that calls ``stop`` once when ``watch`` finds a reason, until
    the block ends (``done``, set under ``lock``)."""

    def look() -> None:
        while not done.wait(TICK_S):
            reason = watch.look()
            if reason is not None:
                watch.reason = reason
                stop()
                return

    thread = threading.Thread(target=look, name="deadline", daemon=True)
    thread.start()
    try:
        yield
    finally:
        if lock is None:
            done.set()
        else:
            with lock:
                done.set()
        thread.join()
