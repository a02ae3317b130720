"""Units run as tasks on a Dask cluster: ``run``, ``article``, ``threshold`` and ``sweep``
with ``--workers N`` (a LocalCluster of N single-threaded worker processes) or ``--scheduler
ADDRESS`` (a running cluster).  Every unit is a task that runs under its own deadline and
returns its outcome; the client writes the results exactly as a serial run writes them,
so the numbers are identical (the workers compute with this process's thread settings).
"""

from __future__ import annotations

import math
import uuid
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from cases.model import Case
from reports.registry import solvers
from reports.registry.errors import UserError
from reports.run.plan import CasePlan
from reports.run.units import UnitOutcome, run_unit


def _thread_env() -> dict[str, str | None]:
    """The thread-count variables of this process (None where unset)."""
    import os

    from reports.store.manifest import THREAD_VARS

    return {var: os.environ.get(var) for var in THREAD_VARS}


#: the thread-count variable of each threading library threadpoolctl reports
LIBRARY_VARS = {"openblas": "OPENBLAS_NUM_THREADS", "mkl": "MKL_NUM_THREADS",
                "openmp": "OMP_NUM_THREADS"}


def worker_environ() -> dict[str, Any]:
    """Dask's pre-spawn environment for worker processes, with the thread counts of this
    process instead of Dask's default of one thread: its thread-count variables, and the
    count of a library this process limits at run time (threadpoolctl) where no variable
    sets it.  A worker then computes with the same BLAS/OpenMP threading as a serial run
    in this process, so the floating-point results are bit-identical (a solver's
    reductions may depend on the thread count)."""
    import os

    import dask

    from reports.store.manifest import THREAD_VARS

    environ = dict(dask.config.get("distributed.nanny.pre-spawn-environ", {}) or {})
    for var in THREAD_VARS:
        if var in os.environ:
            environ[var] = os.environ[var]
        else:
            environ.pop(var, None)
    try:
        from threadpoolctl import threadpool_info
    except ImportError:  # pragma: no cover - a dependency
        return environ
    for pool in threadpool_info():
        var = LIBRARY_VARS.get(pool.get("internal_api", ""))
        count = pool.get("num_threads")
        if var and var not in os.environ and count and count < (os.cpu_count() or count):
            environ[var] = str(min(count, int(environ.get(var, count))))
    return environ


#: the memory a worker process is counted for before its units [bytes]: Python, numpy,
#: Dask and the solvers' imports
WORKER_BASE = 256 * 2**20


def cores() -> int:
    """The processor cores this process may run on."""
    import os

    try:
        return len(os.sched_getaffinity(0))
    except (AttributeError, OSError):  # not Linux
        return os.cpu_count() or 1


def worker_cap(plans: list[CasePlan], memory: float) -> tuple[int, str]:
    """The most LocalCluster workers the machine allows for ``plans``, and why: one per
    core, and no more than ``memory`` [bytes] holds if every worker runs the largest
    unit by its estimate (:data:`WORKER_BASE` each besides)."""
    n_cores = cores()
    largest, what = 0.0, ""
    for plan in plans:
        runs = [(plan.points[i], s) for i, s in plan.units()]
        runs += [(g.case, g.solver) for g in plan.study_runs()]
        for case, solver in runs:
            cost = solvers.estimate(solver, case)
            if cost is not None and math.isfinite(cost.memory) and cost.memory > largest:
                largest, what = float(cost.memory), f"{solver} on {plan.name}"
    by_memory = max(1, int(memory // (largest + WORKER_BASE)))
    if by_memory < n_cores:
        return by_memory, (f"{memory / 2**30:.3g} GiB of memory holds {by_memory} worker(s) "
                           f"running the largest unit, {what}, "
                           f"{(largest + WORKER_BASE) / 2**30:.3g} GiB each")
    return n_cores, f"{n_cores} core(s), one single-threaded worker each"


#: the seconds a scheduler has to connect and send its handshake
HANDSHAKE_S = 10.0
#: the largest handshake frame accepted [bytes] (a Dask scheduler's is a few hundred)
HANDSHAKE_MAX = 1 << 20


def probe_scheduler(address: str, seconds: float = HANDSHAKE_S) -> None:
    """UserError, naming ``address``, unless a TCP peer there opens with a Dask
    handshake within ``seconds``: a scheduler writes its handshake first (an 8-byte
    length, then that many bytes).  A peer that says nothing (an HTTP server waits for
    its request) or talks first in another protocol is refused before Dask waits on it
    without a bound or reads its first bytes as a frame's length.  Other protocols
    (tls://, ucx://, …) are left to Dask."""
    import socket
    import struct
    import time

    from distributed.comm.addressing import parse_address, parse_host_port

    try:
        protocol, location = parse_address(address)
        if protocol != "tcp":
            return
        host, port = parse_host_port(location)
    except (ValueError, TypeError) as exc:
        raise UserError(f"--scheduler {address!r}: not a Dask scheduler address, e.g. "
                        f"tcp://127.0.0.1:8786 ({exc})") from None
    deadline = time.monotonic() + seconds

    def read(sock: socket.socket, n: int) -> bytes:
        data = b""
        while len(data) < n:
            sock.settimeout(max(deadline - time.monotonic(), 1e-3))
            chunk = sock.recv(min(n - len(data), 65536))
            if not chunk:
                raise UserError(f"--scheduler {address}: closed the connection without a "
                                "Dask handshake; not a Dask scheduler")
            data += chunk
        return data

    try:
        with socket.create_connection((host, port), timeout=seconds) as sock:
            (size,) = struct.unpack("Q", read(sock, 8))  # as Dask packs it
            if not 0 < size <= HANDSHAKE_MAX:
                raise UserError(f"--scheduler {address}: answered in another protocol "
                                "(its first message is not a Dask handshake); not a Dask "
                                "scheduler")
            read(sock, size)
    except TimeoutError:
        raise UserError(f"--scheduler {address}: sent no Dask handshake within "
                        f"{seconds:g} s; not a Dask scheduler (or not reachable)") from None
    except OSError as exc:
        raise UserError(f"cannot reach the Dask scheduler {address}: "
                        f"{exc.strerror or exc}") from None


#: the Dask worker resource a unit's memory estimate [bytes] is requested from, where the
#: workers declare it (``dask worker ... --resources MEMORY=32e9``)
MEMORY = "MEMORY"


class DaskExecutor:
    """Run the units of a plan as tasks on a dask.distributed cluster, each under its
    deadline (:mod:`reports.run.deadline`) and placed by its cost estimate
    (:meth:`_placement`).

    With ``scheduler`` None a LocalCluster of ``workers`` single-threaded worker
    processes is started for the duration of the ``with`` block.
    """

    def __init__(self, scheduler: str | None = None, workers: int = 2):
        try:
            import distributed  # noqa: F401
        except ImportError:
            raise UserError("--workers and --scheduler need dask.distributed (pip install "
                            "'dask[distributed]'); without them the units run serially") \
                from None
        self.scheduler, self.workers = scheduler, workers
        self.cluster = self.client = None
        self.info: dict[str, Any] = {}
        self.memory: float | None = None
        self._live: set = set()  # the futures submitted and not yet read
        self._stopping = False

    def __enter__(self) -> DaskExecutor:
        from distributed import Client, LocalCluster

        if self.scheduler:
            probe_scheduler(self.scheduler)
            try:
                self.client = Client(self.scheduler, timeout="20s")
            except OSError as exc:
                raise UserError(f"cannot reach the Dask scheduler {self.scheduler}: {exc}") \
                    from None
            except (ValueError, TypeError) as exc:  # Dask's parse of the address
                raise UserError(f"--scheduler {self.scheduler!r}: not a Dask scheduler "
                                f"address, e.g. tcp://127.0.0.1:8786 ({exc})") from None
        else:
            import dask

            with dask.config.set({"distributed.nanny.pre-spawn-environ": worker_environ()}):
                self.cluster = LocalCluster(n_workers=self.workers, threads_per_worker=1,
                                            processes=True, dashboard_address=None)
            self.client = Client(self.cluster)
        workers = self.client.scheduler_info().get("workers", {})
        self.info = {"scheduler": self.scheduler or "LocalCluster", "workers": len(workers),
                     "threads": sum(w.get("nthreads", 0) for w in workers.values()),
                     "worker_thread_env": self.client.run(_thread_env)}
        declared = [w.get("resources", {}).get(MEMORY) for w in workers.values()]
        self.memory = max((float(m) for m in declared if m), default=None)
        return self

    def __exit__(self, *exc: object) -> None:
        import logging

        # a worker's last heartbeat to a scheduler that has just closed is logged as an
        # error with its traceback; the run is over by then, and the report is quiet
        quiet = logging.getLogger("distributed")
        level = quiet.level
        quiet.setLevel(logging.CRITICAL)
        try:
            if self.client is not None:
                self.client.close()
            if self.cluster is not None:
                self.cluster.close()
        finally:
            quiet.setLevel(level)

    def _placement(self, case: Case, solver: str) -> dict[str, Any]:
        """A unit's Dask priority, its estimated seconds (the longest first, so that the
        cluster does not wait on the last long run), and, where the workers declare a
        :data:`MEMORY` resource, its estimated memory (at most the largest worker's), so
        that two large runs do not share a worker's memory."""
        cost = solvers.estimate(solver, case)
        if cost is None:
            return {"priority": 0}
        out: dict[str, Any] = {"priority": int(min(cost.seconds, 1e9))}
        if self.memory is not None and math.isfinite(cost.memory):
            out["resources"] = {MEMORY: min(float(cost.memory), self.memory)}
        return out

    def _submit(self, case: Case, solver: str, *args: Any, **kwargs: Any) -> Any:
        """A task of :func:`~reports.run.units.run_unit`, placed by its estimates."""
        if self._stopping:
            raise _Stopped("the run is being stopped")
        future = self.client.submit(run_unit, *args, pure=False, **kwargs,
                                    **self._placement(case, solver))
        self._live.add(future)
        return future

    def _read(self, future: Any, index: int, solver: str, case: Case) -> UnitOutcome:
        """The outcome of a finished task, or a failed unit where the cluster lost it
        (its worker died too often, it was cancelled); the future is let go."""
        self._live.discard(future)
        try:
            return future.result()
        except Exception as exc:  # noqa: BLE001 - KilledWorker, CancelledError, ...
            return UnitOutcome(index, solver, case.param, None, 0.0, kind="internal",
                               error=f"the cluster lost the run: {type(exc).__name__}: {exc}")

    def stop(self) -> None:
        """Cancel every task not yet read and submit no more (an error or an interrupt in
        one of the client's threads ends the others' waits at once)."""
        self._stopping = True
        for future in list(self._live):
            future.cancel()

    def evaluate(self, fn: Any, case: Case, solver: str, index: int, progress: bool = False,
                 on_output: Any = None, limit_s: float = math.inf) -> UnitOutcome:
        """:func:`~reports.run.units.run_unit` as one task, waited for (a threshold's
        evaluation: :func:`reports.run.threshold.run`); its output steps are not
        streamed (``on_output`` must be None)."""
        if on_output is not None:
            raise ValueError("a cluster's evaluation streams no output steps")
        future = self._submit(case, solver, fn, case, solver, index, False, None, limit_s)
        return self._read(future, index, solver, case)

    def map(self, fn: Any, items: list[Any]) -> list[Any]:
        """``[fn(x) for x in items]``, each call in a client thread of its own, so that
        the tasks they submit run at once; the first exception stops the others' tasks
        (:meth:`stop`) and is raised."""
        from concurrent.futures import ThreadPoolExecutor

        if len(items) <= 1:
            return [fn(x) for x in items]
        with ThreadPoolExecutor(max_workers=len(items), thread_name_prefix="group") as pool:
            try:
                return list(pool.map(fn, items))
            except BaseException:
                self.stop()
                raise

    def __call__(self, plan: CasePlan, units: list[tuple[int, str]],
                 progress: bool) -> Iterator[UnitOutcome]:
        """The outcomes as the tasks finish.  Each task runs under its own deadline, on
        the CPU time of the worker thread that runs it (:mod:`reports.run.deadline`);
        the client sets none in wall time, which would count the time a task waits in
        the queue behind longer ones (it stopped a correct chain that way) and a busy
        machine's slowness.  The tasks not yet done when the caller stops are
        cancelled."""
        from distributed import as_completed

        fns = {s: solvers.resolve(s) for s in {s for _, s in units}}
        tag = uuid.uuid4().hex[:8]
        unit = {}
        for i, s in units:
            case = plan.points[i]
            future = self._submit(case, s, fns[s], case, s, i, False, None,
                                  plan.limits.deadline(case, s),
                                  key=f"{plan.dir_name}-{i}-{s}-{tag}")
            unit[future.key] = (future, i, s)
        try:
            for future in as_completed([f for f, _, _ in unit.values()]):
                _, i, s = unit.pop(future.key)  # let the result go once read
                yield self._read(future, i, s, plan.points[i])
        finally:
            for future, _, _ in unit.values():
                self._live.discard(future)
                future.cancel()


def execute_cases(plans: list[CasePlan], out: Path, executor: DaskExecutor,
                  progress: bool | None = None) -> Iterator[Any]:
    """Run the cases of ``plans`` at once through ``executor``: each case's units and
    studies are submitted as soon as its previous stage is done (one client thread per
    case), so the cluster holds the units of every case and runs the longest first;
    yields each case's :class:`~reports.run.runner.CaseRun` as it completes.  Each
    case's directory is written by the client as a serial run writes it.  ``progress``
    (None: on a terminal) shows one bar of the units done, naming the last."""
    from concurrent.futures import ThreadPoolExecutor, as_completed

    from tqdm.auto import tqdm

    from reports.run.runner import execute

    extra = {"executor": executor.info}
    total = sum(len(p.units()) + len(p.study_runs()) for p in plans)
    with tqdm(total=total, desc="units", unit="run", leave=False,
              disable=None if progress is None else not progress) as bar, \
            ThreadPoolExecutor(max_workers=max(len(plans), 1),
                               thread_name_prefix="case") as pool:
        counted = _Counted(executor, bar)
        futures = [pool.submit(execute, p, out, executor=counted, progress=False,
                               extra_manifest=extra) for p in plans]
        try:
            for future in as_completed(futures):
                yield future.result()
        except BaseException:  # an interrupt, or a case that raised: stop the others
            executor.stop()
            raise


class _Stopped(RuntimeError):
    """A unit not submitted: the run is being stopped (:meth:`DaskExecutor.stop`)."""


class _Counted:
    """An executor that counts the outcomes of another on a progress bar."""

    def __init__(self, executor: DaskExecutor, bar: Any):
        import threading

        self.executor, self.bar, self.lock = executor, bar, threading.Lock()

    def __call__(self, plan: CasePlan, units: list[tuple[int, str]],
                 progress: bool) -> Iterator[UnitOutcome]:
        for outcome in self.executor(plan, units, progress):
            with self.lock:
                if self.bar.total is not None and self.bar.n >= self.bar.total:
                    self.bar.total = self.bar.n + 1  # a study's runs beyond the plan's
                self.bar.update(1)
                self.bar.set_postfix_str(f"last {plan.name} {outcome.param} "
                                         f"{outcome.solver}".replace("  ", " "))
            yield outcome
