"""The table of thresholds: ``DIR/thresholds.csv`` merged with earlier threshold runs under
a lock, and the text table ``contact-vv threshold`` prints (:mod:`reports.run.threshold`)."""

from __future__ import annotations

import math
import sys
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import pandas as pd

from reports.registry.errors import UserError
from reports.run.threshold import COLUMNS, Request
from reports.store.layout import THRESHOLDS
from reports.store.readers import MERGE_KEYS, DamagedResult, read_result, read_thresholds
from reports.store.staging import held
from reports.store.write import write_csv


def _num(v: Any, fmt: str) -> str:
    return "" if not isinstance(v, int | float) or not math.isfinite(v) else format(v, fmt)


def format_table(request: Request, rows: list[dict[str, Any]]) -> str:
    """The rows as a text table, with one grid-dependence line per (point, solver)."""
    r = request
    head = (f"threshold of {r.event} in {r.param} for {r.case}"
            + (" (quick)" if r.quick else "") + f": bracket [{r.lo:g}, {r.hi:g}], "
            f"resolution {r.resolution:g}" + (f", at {at}" if (at := next(
                (row["at"] for row in rows if row["at"]), "")) else ""))
    lines = [head, f"{'solver':9s} {'point':10s} {'grid':14s} {'cell [mm]':>9s} "
             f"{'threshold':>10s} {'±':>9s} {'evals':>5s} {'grid shift':>10s} "
             f"{'wall [s]':>8s}  status"]
    for row in rows:
        status = row["status"].split(":")[0] if row["status"].startswith(
            ("bisected", "exact")) else row["status"]
        lines.append(
            f"{row['solver']:9s} {row['point'] or '-':10s} {row['grid']:14s} "
            f"{_num(row['cell_size'], '9.4g'):>9s} {_num(row['threshold'], '10.5g'):>10s} "
            f"{_num(row['uncertainty'], '9.2g'):>9s} {row['evaluations']:>5} "
            f"{_num(row['grid_shift'], '+10.3g'):>10s} {_num(row['wall_s'], '8.1f'):>8s}  "
            f"{status}")
    lines += grid_dependence(rows)
    return "\n".join(lines)


def grid_dependence(rows: list[dict[str, Any]]) -> list[str]:
    """One line per (point, solver) with thresholds on several grids."""
    groups: dict[tuple[str, str], list[dict[str, Any]]] = {}
    for row in rows:
        if row["grid"] != "exact" and math.isfinite(row["threshold"]):
            groups.setdefault((row["point"], row["solver"]), []).append(row)
    return [f"grid dependence {solver}" + (f" [{point}]" if point else "") + ": "
            + ", ".join(f"{g['threshold']:.5g} on {g['grid']}" for g in group)
            + f"; spread {max(t) - min(t):.3g} (resolution {group[0]['resolution']:g})"
            for (point, solver), group in groups.items()
            if len(t := [g["threshold"] for g in group]) > 1]


def stderr_log(message: str) -> None:
    """One progress line, written whole (the bisections of a cluster log from several
    threads)."""
    sys.stderr.write(f"threshold: {message}\n")
    sys.stderr.flush()


@contextmanager
def _locked(path: Path) -> Iterator[None]:
    """Hold an exclusive OS lock on ``path`` (waiting for another threshold run); the
    lock file is removed at the end (:func:`reports.store.staging.held`)."""
    with held(path):
        yield


def _lock_path(out: Path) -> Path:
    return Path(out) / f".{THRESHOLDS}.lock"


def existing(out: Path) -> pd.DataFrame | None:
    """The rows of ``out/thresholds.csv`` (None if absent); UserError if it is damaged
    or not a regular file (a link would be replaced by the table)."""
    path = Path(out) / THRESHOLDS
    for p in (path, _lock_path(out)):
        if p.is_symlink() or p.exists() and not p.is_file():
            raise UserError(f"{p} is not a regular file; refusing to replace it (move it "
                            "away)")
    if not path.exists():
        return None
    try:
        return read_result(Path(out) / THRESHOLDS, read_thresholds)
    except DamagedResult as exc:
        raise UserError(f"{exc}; move it away to start a new table") from None


def write_rows(out: Path, rows: list[dict[str, Any]]) -> Path:
    """Merge ``rows`` into ``out/thresholds.csv`` (rows of the same case, point, event,
    param, step, tier, solver and grid replaced) and write it atomically."""
    new = pd.DataFrame.from_records(rows, columns=COLUMNS)
    with _locked(_lock_path(out)):
        old = existing(out)
        if old is not None:
            key = set(new[MERGE_KEYS].astype(str).agg("|".join, axis=1))
            kept = old[~old[MERGE_KEYS].astype(str).agg("|".join, axis=1).isin(key)]
            new = pd.concat([kept, new], ignore_index=True) if len(kept) else new
        write_csv(Path(out) / THRESHOLDS, new)
    return Path(out) / THRESHOLDS
