"""Parameter sweeps from the command line, run on Dask (or serially).

``--param key=start:stop:step`` or ``--param key=v1,v2,...`` sets one dotted case key
(``friction.beta``, ``grid.nx``) per sweep point; several ``--param`` options are zipped
(same number of values), e.g. a grid study ``--param grid.nx=21,41,81 --param
grid.ny=21,41,81``.  The sweep replaces any ``[sweep]`` table of the case file, and its
results go to ``DIR/<case>__sweep_<labels>/`` in the layout of a run.

Every (sweep point, solver) is an independent task.  On a ``dask.distributed`` cluster
(a LocalCluster of ``--workers`` single-threaded processes by default, or the scheduler
at ``--scheduler``) the tasks run in parallel and their results are written by the
client exactly as a serial run writes them, so the numbers are identical.
"""

from __future__ import annotations

import json
import math
import tempfile
import time
import tomllib
import uuid
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from cases.loader import case_path, load_case, read_toml, value_label
from cases.model import Case, CaseError
from reports.registry import solvers
from reports.registry.errors import RunFailed, UserError
from reports.run.plan import CasePlan, Limits, plan_case
from reports.run.units import UnitOutcome, run_unit, serial_executor
from reports.store import layout


def parse_value(text: str) -> Any:
    """A TOML scalar (``45``, ``0.25``, ``true``, ``"cg"``), else the bare string."""
    try:
        return tomllib.loads(f"v = {text.strip()}")["v"]
    except tomllib.TOMLDecodeError:
        return text.strip()


def parse_param(spec: str) -> tuple[str, list[Any]]:
    """``key=start:stop:step`` (stop included) or ``key=v1,v2`` -> (key, values)."""
    key, eq, rhs = spec.partition("=")
    key = key.strip()
    if not eq or not key or not rhs.strip():
        raise UserError(f"--param {spec!r}: expected KEY=START:STOP:STEP or KEY=V1,V2,...")
    if ":" in rhs:
        parts = rhs.split(":")
        nums = [parse_value(p) for p in parts]
        if len(parts) != 3 or not all(isinstance(n, int | float) and not isinstance(n, bool)
                                      for n in nums):
            raise UserError(f"--param {spec!r}: a range is START:STOP:STEP with numbers")
        start, stop, step = nums
        if step == 0 or (stop - start) / step < 0:
            raise UserError(f"--param {spec!r}: STEP must be non-zero and move towards STOP")
        count = int(math.floor((stop - start) / step + 1e-9)) + 1
        if count > 10_000:
            raise UserError(f"--param {spec!r}: {count} values (limit 10000)")
        as_int = all(isinstance(n, int) for n in nums)
        values = [start + k * step if as_int else round(start + k * step, 12)
                  for k in range(count)]
    else:
        values = [parse_value(v) for v in rhs.split(",") if v.strip()]
    if not values:
        raise UserError(f"--param {spec!r}: no values")
    return key, values


def _toml_value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int | float):
        return repr(value)
    if isinstance(value, str):  # a JSON string is a TOML basic string, but for U+007F
        return json.dumps(value, ensure_ascii=False).replace("\x7f", "\\u007f")
    if isinstance(value, list | tuple):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    raise CaseError(f"cannot write {value!r} to TOML")


def dump_toml(data: dict[str, Any]) -> str:
    """A minimal TOML writer for case files (scalars, arrays, nested tables)."""
    lines: list[str] = []

    def table(prefix: str, node: dict[str, Any]) -> None:
        scalars = {k: v for k, v in node.items() if not isinstance(v, dict)}
        tables = {k: v for k, v in node.items() if isinstance(v, dict)}
        if prefix and scalars:
            lines.append(f"[{prefix}]")
        for k, v in scalars.items():
            lines.append(f"{_toml_value(k) if not k.isidentifier() else k} = {_toml_value(v)}")
        for k, v in tables.items():
            name = k if k.replace("_", "a").isalnum() else _toml_value(k)
            table(f"{prefix}.{name}" if prefix else name, v)

    table("", data)
    return "\n".join(lines) + "\n"


def sweep_points(ref: str | Path, params: list[tuple[str, list[Any]]], *,
                 quick: bool = False, overrides: dict[str, Any] | None = None
                 ) -> tuple[list[Case], dict[str, Any]]:
    """The validated cases of a command-line sweep and its description for the manifest."""
    lengths = {len(v) for _, v in params}
    if len(lengths) != 1:
        raise UserError("zipped --param options need the same number of values")
    source = case_path(ref)
    raw = read_toml(source)
    raw.pop("sweep", None)
    if "quick" in raw:
        raw["quick"] = {k: v for k, v in raw["quick"].items() if not k.startswith("sweep.")}
    raw.setdefault("name", source.stem)
    labels = [key.split(".")[-1] for key, _ in params]
    cases = []
    with tempfile.TemporaryDirectory(prefix="contact-vv-sweep-") as tmp:
        path = Path(tmp) / source.name
        path.write_text(dump_toml(raw))
        for k in range(lengths.pop()):
            point = dict(overrides or {})
            point.update({key: values[k] for key, values in params})
            (case,) = load_case(path, quick=quick, overrides=point)
            label = ",".join(f"{lab}={value_label(values[k])}"
                             for lab, (_, values) in zip(labels, params, strict=True))
            if any(c.param == label for c in cases):
                raise UserError(f"--param: repeated sweep point {label}")
            cases.append(case.with_changes(param=label, source=str(source)))
    return cases, {"keys": [key for key, _ in params], "labels": labels,
                   "values": [values for _, values in params]}


def plan_sweep(ref: str | Path, params: list[tuple[str, list[Any]]], solver_names: list[str],
               *, quick: bool = False, overrides: dict[str, Any] | None = None,
               skipped: dict[str, str] | None = None, limits: Limits | None = None,
               explicit: bool = True) -> CasePlan:
    cases, sweep = sweep_points(ref, params, quick=quick, overrides=overrides)
    return plan_case(ref, solver_names, quick=quick, overrides=overrides, skipped=skipped,
                     points=cases, sweep=sweep,
                     dir_name=layout.sweep_dir_name(cases[0].name, [k for k, _ in params]),
                     limits=limits, explicit=explicit)


def _thread_env() -> dict[str, str | None]:
    """The thread-count variables of this process (None where unset)."""
    import os

    from reports.store.manifest import THREAD_VARS

    return {var: os.environ.get(var) for var in THREAD_VARS}


def worker_environ() -> dict[str, Any]:
    """Dask's pre-spawn environment for worker processes, with the thread-count variables
    of this process instead of Dask's default of one thread: a worker then computes with
    the same BLAS/OpenMP threading as a serial run in this process, so the floating-point
    results are bit-identical (a solver's reductions may depend on the thread count)."""
    import os

    import dask

    from reports.store.manifest import THREAD_VARS

    environ = dict(dask.config.get("distributed.nanny.pre-spawn-environ", {}) or {})
    for var in THREAD_VARS:
        if var in os.environ:
            environ[var] = os.environ[var]
        else:
            environ.pop(var, None)
    return environ


class DaskExecutor:
    """Run the units of a plan as tasks on a dask.distributed cluster.

    With ``scheduler`` None a LocalCluster of ``workers`` single-threaded worker
    processes is started for the duration of the ``with`` block.
    """

    def __init__(self, scheduler: str | None = None, workers: int = 2):
        try:
            import distributed  # noqa: F401
        except ImportError:
            raise UserError("sweeps on Dask need dask.distributed: "
                            "pip install 'contact-vv[dask]' (or --workers 0 for serial)") from None
        self.scheduler, self.workers = scheduler, workers
        self.cluster = self.client = None
        self.info: dict[str, Any] = {}

    def __enter__(self) -> DaskExecutor:
        from distributed import Client, LocalCluster

        if self.scheduler:
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
        return self

    def __exit__(self, *exc: object) -> None:
        if self.client is not None:
            self.client.close()
        if self.cluster is not None:
            self.cluster.close()

    def __call__(self, plan: CasePlan, units: list[tuple[int, str]],
                 progress: bool) -> Iterator[UnitOutcome]:
        """The outcomes as the tasks finish; the tasks not done by the sum of their
        deadlines (:mod:`reports.run.deadline`, as if run one after the other) are
        cancelled and reported as stopped."""
        from distributed import TimeoutError as DaskTimeout
        from distributed import as_completed

        fns = {s: solvers.resolve(s) for s in {s for _, s in units}}
        tag = uuid.uuid4().hex[:8]
        futures = [self.client.submit(run_unit, fns[s], plan.points[i], s, i, False,
                                      pure=False, key=f"{plan.dir_name}-{i}-{s}-{tag}")
                   for i, s in units]
        limit = sum(plan.limits.deadline(plan.points[i], s) for i, s in units)
        done: set[tuple[int, str]] = set()
        try:
            for future in as_completed(futures, timeout=limit if math.isfinite(limit)
                                       else None):
                outcome = future.result()
                done.add((outcome.index, outcome.solver))
                yield outcome
        except DaskTimeout:
            for i, s in units:
                if (i, s) not in done:
                    yield UnitOutcome(i, s, plan.points[i].param, None, limit, kind="overrun",
                                      error=f"the sweep's tasks ran past their deadline of "
                                      f"{limit:.3g} s (the sum of their cost estimates times "
                                      "their calibration factors); stopped")
        finally:
            for future in futures:
                future.cancel()


def check_serial(plan: CasePlan, path: Path, wall: float) -> dict[str, Any]:
    """Re-run a sweep serially into a scratch directory: its wall time against the
    sweep's ``wall``, and whether its summary (but the wall times) and metrics are the
    sweep's; written as ``sweep_check.json`` beside the sweep's results."""
    import json

    import pandas as pd

    from cases.result import atomic_write_text
    from reports.run.runner import execute
    from reports.store import layout

    with tempfile.TemporaryDirectory(prefix="contact-vv-serial-") as tmp:
        t0 = time.perf_counter()
        ref = execute(plan, Path(tmp), executor=serial_executor, progress=False)
        serial = time.perf_counter() - t0
        if ref.failures:
            raise RunFailed(ref.failures)
        a = pd.read_csv(path / layout.SUMMARY).drop(columns="wall_s")
        b = pd.read_csv(ref.path / layout.SUMMARY).drop(columns="wall_s")
        same = a.equals(b) and \
            (path / layout.METRICS).read_bytes() == (ref.path / layout.METRICS).read_bytes()
    check = {"parallel_wall_s": wall, "serial_wall_s": serial, "speedup": serial / wall,
             "identical": bool(same)}
    atomic_write_text(path / layout.SWEEP_CHECK, json.dumps(check, indent=1))
    return check
