"""Read what runs left in a results directory: complete cases, incomplete ones and damaged
ones.

Every result file (manifest, summary, metrics, output steps, solver tables, the Dask
check of a sweep, failure records, baselines) is read through :func:`read_result`, the
one place where a file that cannot be decoded, or that does not hold what a run writes,
becomes a :class:`DamagedResult` naming the file and the cause.  :func:`scan` reads and
checks every file of a case once, so a case is either fully readable (``complete``) or
listed, with the reason, as ``incomplete`` (no manifest, a failed or interrupted run,
files changed after the run) or ``damaged`` (a file that cannot be read).
"""

from __future__ import annotations

import json
import math
import struct
import zipfile
import zlib
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, TypeVar

import numpy as np
import pandas as pd

from cases.result import SUMMARY_COLUMNS, StepResult, load_step

from . import layout, manifest
from .errors import UserError

T = TypeVar("T")

#: what decoding a hostile file can raise (bad bytes, bad text, bad JSON/CSV/zip/npy,
#: missing keys, wrong types, absurd sizes, deep nesting); nothing else is caught
DECODE_ERRORS = (OSError, ValueError, LookupError, TypeError, EOFError, RuntimeError,
                 MemoryError, OverflowError, zipfile.BadZipFile, zlib.error, struct.error)


class DamagedResult(manifest.IncompleteRun):
    """A result file that cannot be read, or does not hold what a run writes."""

    def __init__(self, path: Path | str, cause: str):
        self.path, self.cause = Path(path), cause
        super().__init__(f"{path}: {cause}")


class Malformed(ValueError):
    """Raised by a file's parser: the file decodes but its content is not a result's."""


def _describe(exc: BaseException) -> str:
    text = " ".join(str(exc).split())[:300]
    if isinstance(exc, Malformed):
        return text
    if isinstance(exc, UnicodeDecodeError):
        return f"not UTF-8 text ({text})"
    if isinstance(exc, json.JSONDecodeError):
        return f"not valid JSON ({text})"
    if isinstance(exc, pd.errors.ParserError | pd.errors.EmptyDataError):
        return f"not a valid CSV table ({text})"
    if isinstance(exc, zipfile.BadZipFile | zlib.error | EOFError | struct.error):
        return f"corrupt or truncated archive ({text or type(exc).__name__})"
    if isinstance(exc, RecursionError):
        return "nested too deeply to read"
    if isinstance(exc, OSError):
        return f"cannot be read ({exc.strerror or text})"
    return f"cannot be read ({type(exc).__name__}: {text})"


def read_result(path: Path | str, parse: Callable[[Path], T]) -> T:
    """``parse(path)``; any decoding or parsing failure becomes :class:`DamagedResult`.

    The one place a result file is read.  ``parse`` raises :class:`Malformed` for a file
    that decodes but does not hold what a run writes.  A path that is not a regular file
    (a directory, a dangling link) or an empty file is damaged too.
    """
    path = Path(path)
    try:
        if not path.is_file():
            raise Malformed("missing" if not path.exists() and not path.is_symlink()
                            else "not a regular file")
        if path.stat().st_size == 0:
            raise Malformed("empty file (0 bytes)")
        return parse(path)
    except DamagedResult:
        raise
    except DECODE_ERRORS as exc:
        raise DamagedResult(path, _describe(exc)) from None


# --------------------------------------------------------------------- parsers


def read_json(path: Path) -> Any:
    """A JSON file (strict UTF-8)."""
    return json.loads(path.read_bytes().decode("utf-8"))


def read_json_object(path: Path) -> dict[str, Any]:
    value = read_json(path)
    if not isinstance(value, dict):
        raise Malformed(f"not a JSON object ({manifest.json_kind(value)})")
    return value


def _text_column(frame: pd.DataFrame, col: str) -> None:
    frame[col] = frame[col].fillna("").astype(str)


def numeric_columns(frame: pd.DataFrame, cols: Iterable[str]) -> None:
    """Convert ``cols`` of ``frame`` to float in place; :class:`Malformed` on any entry
    that is neither blank nor a number (blank is NaN)."""
    for col in cols:
        values = frame[col]
        if pd.api.types.is_bool_dtype(values):
            values = values.astype(float)
        elif not pd.api.types.is_numeric_dtype(values):
            converted = pd.to_numeric(values, errors="coerce")
            bad = converted.isna() & values.notna() & (values.astype(str).str.strip() != "")
            if bad.any():
                i = int(np.flatnonzero(bad.to_numpy())[0])
                raise Malformed(f"column {col!r} holds {str(values.iloc[i])[:40]!r} "
                                f"(data row {i + 1}), not a number")
            values = converted
        frame[col] = values.astype(float)


def _integer_column(frame: pd.DataFrame, col: str) -> None:
    numeric_columns(frame, [col])
    v = frame[col].to_numpy()
    bad = ~np.isfinite(v) | (v != np.round(v))
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise Malformed(f"column {col!r} holds {float(v[i])!r} (data row {i + 1}), "
                        "not a whole number")
    frame[col] = v.astype(np.int64)


def _bool_column(frame: pd.DataFrame, col: str, *, blank: bool) -> None:
    """Parse True/False (1/0) in place; blank (NaN) allowed only if ``blank``."""
    text = frame[col].astype(str).str.strip().str.lower()
    missing = frame[col].isna() | (text == "")
    true = text.isin(["true", "1", "1.0"])
    false = text.isin(["false", "0", "0.0"])
    bad = ~(true | false | (missing if blank else False))
    if bad.any():
        i = int(np.flatnonzero(bad.to_numpy())[0])
        raise Malformed(f"column {col!r} holds {str(frame[col].iloc[i])[:40]!r} "
                        f"(data row {i + 1}), not True or False")
    frame[col] = pd.Series([math.nan if m else bool(t) for m, t in zip(missing, true,
                                                                       strict=True)],
                           index=frame.index, dtype=object)


def read_csv(path: Path, *, required: Iterable[str] = (), text: Iterable[str] = (),
             numeric: Iterable[str] = (), integer: Iterable[str] = ()) -> pd.DataFrame:
    """A CSV table with the ``required`` columns; ``text`` columns as str (blank ''),
    ``numeric`` (present ones) as float, ``integer`` (present ones) as int."""
    frame = pd.read_csv(path, dtype={c: object for c in text}, encoding="utf-8")
    missing = [c for c in required if c not in frame.columns]
    if missing:
        raise Malformed(f"missing column(s) {', '.join(missing)}")
    for c in text:
        if c in frame.columns:
            _text_column(frame, c)
    numeric_columns(frame, [c for c in numeric if c in frame.columns])
    for c in integer:
        if c in frame.columns:
            _integer_column(frame, c)
    return frame


_SUMMARY_TEXT = ("case", "solver", "param")


def read_summary(path: Path) -> pd.DataFrame:
    """``summary.csv``: the columns of :data:`cases.result.SUMMARY_COLUMNS`, numbers where
    a run writes numbers, ``converged`` True/False/blank."""
    numeric = [c for c in SUMMARY_COLUMNS if c not in (*_SUMMARY_TEXT, "converged", "step")]
    numeric.append("cell_size")  # read by the grid-convergence table
    frame = read_csv(path, required=SUMMARY_COLUMNS, text=_SUMMARY_TEXT, numeric=numeric,
                     integer=["step"])
    _bool_column(frame, "converged", blank=True)
    return frame


#: the columns of ``metrics.csv`` (``param`` and ``step`` only in a table with rows: a
#: run with a single solver writes the header of the first six)
METRICS_REQUIRED = ["quantity", "pair", "metric", "value", "tolerance", "passed"]


def passes(value: Any, tolerance: Any) -> Any:
    """A metric passes iff value and tolerance are finite numbers and value <= tolerance
    (works elementwise on arrays)."""
    v, t = np.asarray(value, float), np.asarray(tolerance, float)
    with np.errstate(invalid="ignore"):
        return np.isfinite(v) & np.isfinite(t) & (v <= t)


def read_metrics(path: Path) -> pd.DataFrame:
    """``metrics.csv`` with ``passed`` recomputed from value and tolerance
    (:func:`passes`); what the file recorded is kept as ``passed_recorded``."""
    frame = read_csv(path, required=METRICS_REQUIRED,
                     text=("quantity", "pair", "metric", "param", "case", "tolerance_key"),
                     numeric=("value", "tolerance", "s", "cycle"), integer=["step"])
    missing = [c for c in ("param", "step") if c not in frame.columns]
    if missing and not frame.empty:
        raise Malformed(f"missing column(s) {', '.join(missing)}")
    for c in missing:
        frame[c] = pd.Series(dtype=object if c == "param" else np.int64)
    _bool_column(frame, "passed", blank=False)
    tol = frame["tolerance"].to_numpy()
    bad = ~(tol > 0)  # a run's tolerances are positive (NaN is not)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise Malformed(f"column 'tolerance' holds {float(tol[i])!r} (data row {i + 1}), "
                        "not a positive number")
    frame["passed_recorded"] = frame["passed"].astype(bool)
    frame["passed"] = passes(frame["value"], frame["tolerance"])
    return frame


def read_table(path: Path) -> pd.DataFrame:
    """A solver table (``fields/<solver>/<param>/<name>.csv``): numeric columns."""
    frame = pd.read_csv(path, encoding="utf-8")
    numeric_columns(frame, frame.columns)
    return frame


def _axis(name: str, a: np.ndarray) -> None:
    """Sample coordinates: a 1-D array of finite numbers, strictly monotonic."""
    if a.ndim != 1 or not np.issubdtype(a.dtype, np.number):
        raise Malformed(f"{name} is not a 1-D numeric array")
    d = np.diff(a)
    if not np.isfinite(a).all() or not (np.all(d > 0) or np.all(d < 0)):
        raise Malformed(f"{name} is not a strictly monotonic sequence of finite numbers")


def read_step(path: Path) -> StepResult:
    """An output step (``.npz``) whose arrays have consistent shapes."""
    if not zipfile.is_zipfile(path):
        raise Malformed("corrupt or truncated archive (not a zip file)")
    step = load_step(path)
    if not isinstance(step.scalars, dict):
        raise Malformed("its scalars are not a JSON object")
    x, y = np.asarray(step.x), np.asarray(step.y)
    _axis("x", x)
    _axis("y", y)
    for key, arr in step.surface.items():
        if np.shape(arr) != (x.size, y.size) or not np.issubdtype(arr.dtype, np.number):
            raise Malformed(f"surface field {key} has shape {np.shape(arr)}, "
                            f"not ({x.size}, {y.size}) numbers")
    for name, plane in step.planes.items():
        s, z = np.asarray(plane.s), np.asarray(plane.z)
        _axis(f"plane {name} s", s)
        _axis(f"plane {name} z", z)
        for comp, arr in plane.fields.items():
            if np.shape(arr) != (s.size, z.size) or not np.issubdtype(arr.dtype, np.number):
                raise Malformed(f"plane {name} field {comp} has shape {np.shape(arr)}, "
                                f"not ({s.size}, {z.size}) numbers")
    return step


SWEEP_CHECK = "sweep_check.json"


def read_sweep_check(path: Path) -> dict[str, Any]:
    """``sweep_check.json`` (written by ``sweep --check-serial``)."""
    check = read_json_object(path)
    for key in ("parallel_wall_s", "serial_wall_s", "speedup"):
        v = check.get(key)
        if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
            raise Malformed(f"{key} is {v!r}, not a finite number")
    if not isinstance(check.get("identical"), bool):
        raise Malformed(f"identical is {check.get('identical')!r}, not true or false")
    return check


# --------------------------------------------------------------------- results


def _step_number(path: Path) -> int:
    _, _, digits = path.stem.partition("_")
    if not digits.isdigit():
        raise DamagedResult(path, "not named step_NNNN.npz")
    return int(digits)


@dataclass
class CaseResults:
    """One complete case directory."""

    path: Path
    manifest: dict[str, Any]
    summary: pd.DataFrame
    metrics: pd.DataFrame

    @property
    def name(self) -> str:
        return str(self.manifest.get("dir") or self.manifest.get("case") or self.path.name)

    def _step_files(self, solver: str, param: str) -> dict[int, Path]:
        folder = layout.unit_dir(self.path, solver, param)
        return {_step_number(f): f for f in sorted(folder.glob("step_*.npz"))}

    def steps(self, solver: str, param: str) -> dict[int, StepResult]:
        """Output steps of one solver at one sweep point, by step number."""
        return {n: read_result(f, read_step) for n, f in self._step_files(solver, param).items()}

    def tables(self, solver: str, param: str) -> dict[str, pd.DataFrame]:
        folder = layout.unit_dir(self.path, solver, param)
        return {f.stem: read_result(f, read_table) for f in sorted(folder.glob("*.csv"))}

    def point(self, param: str) -> dict[str, Any]:
        """The case parameters (as recorded) of one sweep point."""
        for p in self.manifest.get("points", []):
            if p.get("param", "") == param:
                return p
        return {}

    def check_files(self) -> None:
        """Read every output step, solver table and the sweep check once
        (:class:`DamagedResult` on the first that cannot be read)."""
        for solver in self.manifest.get("solvers", []):
            for param in dict.fromkeys(self.manifest.get("params", [""])):
                for f in self._step_files(solver, param).values():
                    read_result(f, read_step)  # one at a time: a long run has many
                self.tables(solver, param)
        if (self.path / SWEEP_CHECK).exists():
            read_result(self.path / SWEEP_CHECK, read_sweep_check)


@dataclass
class Scan:
    """All cases in a results directory."""

    complete: list[CaseResults] = field(default_factory=list)
    incomplete: dict[str, str] = field(default_factory=dict)  # case -> reason
    damaged: dict[str, str] = field(default_factory=dict)  # case -> file and cause

    @property
    def empty(self) -> bool:
        return not (self.complete or self.incomplete or self.damaged)


def _read_failure(path: Path) -> list[str]:
    failures = read_json_object(path).get("failures")
    if not isinstance(failures, list) or not all(isinstance(f, str) for f in failures):
        raise Malformed("failures is not a list of strings")
    return failures


def _failure_reason(staging: Path) -> str:
    failed = staging / layout.FAILED
    if failed.exists():
        try:
            return "run failed: " + "; ".join(read_result(failed, _read_failure))
        except DamagedResult as exc:
            return f"run failed (its failure record {exc})"
    return "run interrupted or still in progress (no manifest)"


def load_case(path: Path, *, verify: bool = True) -> CaseResults:
    """One case directory, every file read (with ``verify``, also the output steps and
    tables); :class:`manifest.IncompleteRun` or :class:`DamagedResult` otherwise."""
    mf = manifest.read(path, verify=verify)
    case = CaseResults(path=path, manifest=mf,
                       summary=read_result(path / layout.SUMMARY, read_summary),
                       metrics=read_result(path / layout.METRICS, read_metrics))
    if verify:
        case.check_files()
    return case


def scan(out: Path, *, verify: bool = True) -> Scan:
    """Every case directory under ``out``; :class:`UserError` if ``out`` is not one."""
    out = Path(out)
    if not out.is_dir():
        raise UserError(f"results directory {out} does not exist (run `contact-vv run` first)")
    if (out / layout.MANIFEST).exists():
        raise UserError(f"{out} is a case directory, not a results directory "
                        f"(use --out {out.parent})")
    result = Scan()
    for path in sorted(out.iterdir()):
        if not path.is_dir():
            continue
        partial = layout.partial_case_name(path)
        if partial is not None:
            result.incomplete[partial] = _failure_reason(path)
            continue
        if path.name.startswith(".") or not layout.looks_like_result(path):
            continue  # not something a run wrote
        try:
            result.complete.append(load_case(path, verify=verify))
        except DamagedResult as exc:
            result.damaged[path.name] = str(exc)
        except manifest.IncompleteRun as exc:
            result.incomplete[path.name] = str(exc)
        except OSError as exc:  # e.g. a file listed in the manifest that cannot be opened
            result.damaged[path.name] = f"{exc.filename or path}: {_describe(exc)}"
    return result


def not_converged(summary: pd.DataFrame) -> pd.DataFrame:
    """Rows of a summary whose ``converged`` is false (blank means not applicable)."""
    if summary.empty or "converged" not in summary.columns:
        return summary.iloc[0:0]
    col = summary["converged"]
    text = col.astype(str).str.strip().str.lower()
    bad = text.isin(["false", "0", "0.0", "no"]) & col.notna()
    return summary[np.asarray(bad)]
