"""The one reader of result files: every file a run writes (manifest, summary, metrics,
output steps, solver tables, the Dask check of a sweep, failure records, baselines) is
read through :func:`read_result`, where a file that cannot be decoded, or that does not
hold what a run writes, becomes a :class:`DamagedResult` naming the file and the cause."""

from __future__ import annotations

import json
import math
import struct
import zipfile
import zlib
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import Any, TypeVar

import numpy as np
import pandas as pd

from cases.result import SUMMARY_COLUMNS, StepResult, load_step
from reports.registry import solvers
from reports.registry.errors import IncompleteRun
from reports.registry.tolerances import (
    GATED,
    KINDS,
    NOT_GATED,
    OLD_STATUS,
    REASONS,
    UNRECORDED,
    passes,
    with_tolerance_columns,
)

T = TypeVar("T")

JSON_NAMES = {dict: "an object", list: "a list", str: "a string", int: "a number",
               float: "a number", bool: "true or false", type(None): "null"}


def json_kind(value: Any) -> str:
    """What a decoded JSON value is, in JSON's words ("a list", "a number", ...)."""
    return JSON_NAMES.get(type(value), type(value).__name__)


#: what decoding a hostile file can raise (bad bytes, bad text, bad JSON/CSV/zip/npy,
#: missing keys, wrong types, absurd sizes, deep nesting); nothing else is caught
DECODE_ERRORS = (OSError, ValueError, LookupError, TypeError, EOFError, RuntimeError,
                 MemoryError, OverflowError, zipfile.BadZipFile, zlib.error, struct.error)


class DamagedResult(IncompleteRun):
    """A result file that cannot be read, or does not hold what a run writes."""

    def __init__(self, path: Path | str, cause: str):
        self.path, self.cause = Path(path), cause
        super().__init__(f"{path}: {cause}")


class Malformed(ValueError):
    """Raised by a file's parser: the file decodes but its content is not a result's."""


def describe(exc: BaseException) -> str:
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
        raise DamagedResult(path, describe(exc)) from None


# --------------------------------------------------------------------- parsers


def read_json(path: Path) -> Any:
    """A JSON file (strict UTF-8)."""
    return json.loads(path.read_bytes().decode("utf-8"))


def read_json_object(path: Path) -> dict[str, Any]:
    value = read_json(path)
    if not isinstance(value, dict):
        raise Malformed(f"not a JSON object ({json_kind(value)})")
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
             numeric: Iterable[str] = (), integer: Iterable[str] = (),
             boolean: Iterable[str] = ()) -> pd.DataFrame:
    """A CSV table with the ``required`` columns; ``text`` columns as str (blank ''),
    ``numeric`` (present ones) as float, ``integer`` (present ones) as int, ``boolean``
    (present ones) True/False, none blank."""
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
    for c in boolean:
        if c in frame.columns:
            _bool_column(frame, c, blank=False)
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


def read_metrics(path: Path) -> pd.DataFrame:
    """``metrics.csv`` with ``passed`` recomputed from value and tolerance by the pass rule
    (:func:`reports.registry.tolerances.passes`); what the file recorded is kept as
    ``passed_recorded``."""
    frame = read_csv(path, required=METRICS_REQUIRED,
                     text=("quantity", "pair", "metric", "param", "case", "tolerance_key",
                           "status", "note", "reason", "tolerance_kind"),
                     numeric=("value", "tolerance", "s", "cycle", "budget", "uncertainty"),
                     integer=["step"])
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
    status = frame["status"].fillna("").replace("", GATED) if "status" in frame.columns \
        else pd.Series(GATED, index=frame.index, dtype=object)
    status = status.replace(OLD_STATUS)  # as an earlier release wrote it
    bad = ~status.isin([GATED, NOT_GATED])
    if bad.any():
        i = int(np.flatnonzero(bad.to_numpy())[0])
        raise Malformed(f"column 'status' holds {str(status.iloc[i])[:40]!r} (data row "
                        f"{i + 1}), not {GATED!r} or {NOT_GATED!r}")
    frame["status"] = status
    frame["note"] = frame["note"].fillna("") if "note" in frame.columns else ""
    _reason_column(frame)
    if "oracle" not in frame.columns:  # a file an older run wrote: from its pairs
        frame["oracle"] = [solvers.oracle(str(p)) for p in frame["pair"]]
    frame = with_tolerance_columns(frame)
    bad = ~frame["tolerance_kind"].isin(KINDS)
    if bad.any():
        i = int(np.flatnonzero(bad.to_numpy())[0])
        raise Malformed(f"column 'tolerance_kind' holds "
                        f"{str(frame['tolerance_kind'].iloc[i])[:40]!r} (data row {i + 1}), "
                        f"not one of {', '.join(KINDS)}")
    return frame


def _reason_column(frame: pd.DataFrame) -> None:
    """Check ``reason`` in place: a code of :data:`REASONS` on every row not gated, empty
    on the gated ones; a file written before the column gets :data:`UNRECORDED`."""
    on = (frame["status"] == GATED).to_numpy()
    if "reason" not in frame.columns:
        frame["reason"] = np.where(on, "", UNRECORDED)
        return
    reason = frame["reason"].fillna("").astype(str)
    bad = np.where(on, reason != "", ~reason.isin(list(REASONS)))
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise Malformed(f"column 'reason' holds {reason.iloc[i][:40]!r} (data row {i + 1}) "
                        "on a row " + ("gated: it must be empty" if on[i] else
                                       f"not gated: not one of {', '.join(REASONS)}"))
    frame["reason"] = reason


def gated(metrics: pd.DataFrame) -> pd.Series:
    """Which metric rows are gated (``status`` "gated", as :func:`read_metrics` and the
    comparisons write it; not those shown and not gated, with their ``reason``,
    :mod:`reports.registry.tolerances`)."""
    if "status" not in metrics.columns:
        return pd.Series(True, index=metrics.index)
    return metrics["status"] == GATED


def worst(metrics: pd.DataFrame) -> pd.DataFrame:
    """Per (pair, quantity, metric): the row of the largest value over its tolerance (a
    value or a tolerance that is not a number counts as the largest), the worst the
    report shows of a gated quantity."""
    margin = _largest_first(metrics["value"] / metrics["tolerance"])
    idx = margin.groupby([metrics["pair"], metrics["quantity"], metrics["metric"]],
                         sort=False).idxmax()
    return metrics.loc[idx]


def ungated(metrics: pd.DataFrame) -> pd.DataFrame:
    """Per (pair, quantity, metric) of the rows that are not gated: the row of the
    largest value (one that is not a number counts as the largest), with ``rows`` (how
    many there are) and its ``note`` (why)."""
    off = metrics[~gated(metrics)]
    if off.empty:
        return off.assign(rows=pd.Series(dtype=int))
    keys = ["pair", "quantity", "metric"]
    value = _largest_first(off["value"])
    worst = off.loc[value.groupby([off[k] for k in keys], sort=False).idxmax()]
    return worst.assign(rows=off.groupby(keys, sort=False)["value"].transform("size")
                        .loc[worst.index])


def _largest_first(values: pd.Series) -> pd.Series:
    """``values`` as floats with NaN as +inf: the order in which a worst row is picked,
    where a value that is not a number is the worst a row can have."""
    return values.astype(float).fillna(math.inf)


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


#: the columns that name a threshold (``contact-vv threshold`` replaces rows that match)
MERGE_KEYS = ["case", "point", "event", "param", "at", "quick", "solver", "grid"]
_THRESHOLD_TEXT = ("case", "point", "event", "param", "at", "quick", "solver", "grid",
                   "status")


def read_thresholds(path: Path) -> pd.DataFrame:
    """``DIR/thresholds.csv`` (written by ``contact-vv threshold``, reports/run/threshold.py)."""
    return read_csv(path, required=[*MERGE_KEYS, "threshold", "uncertainty", "status"],
                    text=_THRESHOLD_TEXT,
                    numeric=("refine", "cell_size", "threshold", "uncertainty", "resolution",
                             "lo", "hi", "range_lo", "range_hi", "evaluations", "grid_shift",
                             "wall_s"))
