"""Regression baselines: key numbers of a results directory stored as CSV, and the drift
of new results from them.

``contact-vv gate --update-baseline DIR`` writes ``DIR/<case>.csv`` (one row per case,
solver, sweep point and output step; the columns of :data:`KEYS`) and
``DIR/gated/<case>.csv`` (one row per metric row: :data:`ROW_INDEX`, whether it is gated
and, when it is not, its reason in words,
:func:`reports.registry.tolerances.reason_words`) from the
results; ``contact-vv gate --baseline DIR`` fails on any key number that drifted from its
baseline by more than ``--drift`` (relative, default 1e-6), on a baseline row missing
from the results, on a result row or case missing from the baselines, and on a metric
row gated in the baseline that the results no longer gate or no longer hold (a change
that takes rows out of the gate is a regression like a drifted number; a row gated
anew is not).  A baseline without rows
or with an infinite number is refused (blank is a number a solver does not give).
Updating is always explicit, and never into the results directory or over a file that
is not a baseline.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd

from reports.registry.errors import UserError
from reports.registry.tolerances import reason_words
from reports.store.readers import DamagedResult, Malformed, gated, read_csv, read_result
from reports.store.results import Scan

INDEX = ["case", "solver", "param", "step"]
KEYS = ["P", "p_max", "a_x", "a_y", "contact_area", "stick_area", "w_max", "wear_volume",
        "vm_max", "vm_max_x", "vm_max_z", "vm_max_below"]
DEFAULT_DRIFT = 1e-6
#: the sub-folder of a baseline directory holding each case's gated rows, and their index
GATED_DIR = "gated"
ROW_INDEX = ["param", "step", "pair", "quantity", "metric"]


def key_numbers(results: Scan) -> dict[str, pd.DataFrame]:
    """Per case directory: the baseline columns of its summary."""
    out = {}
    for case in results.complete:
        s = case.summary.copy()
        s["case"] = case.name
        cols = INDEX + [k for k in KEYS if k in s.columns]
        out[case.name] = s[cols].sort_values(INDEX, kind="stable").reset_index(drop=True)
    return out


def gated_rows(results: Scan) -> dict[str, pd.DataFrame]:
    """Per case directory: each metric row's :data:`ROW_INDEX`, ``gated`` and, for a row
    that is not, its ``reason``."""
    out = {}
    for case in results.complete:
        m = case.metrics
        on = gated(m).to_numpy(bool)
        frame = m[ROW_INDEX].assign(
            param=m["param"].fillna("").astype(str), gated=on,
            reason=["" if g else reason_words(r) for g, r in zip(on, m["reason"],
                                                                  strict=True)])
        out[case.name] = frame.sort_values(ROW_INDEX, kind="stable").reset_index(drop=True)
    return out


def write(results: Scan, folder: Path, out: Path) -> list[Path]:
    """Write (replace) the baselines of every complete case of ``results`` (read from
    the results directory ``out``).  :class:`UserError`, before writing anything, if
    ``folder`` is inside ``out`` (a case directory would fail its manifest check, the
    results directory would hold files no run wrote) or if a file it would replace is
    not a baseline."""
    from reports.store.write import write_csv

    folder = Path(folder)
    inside = Path(out).resolve()
    if folder.resolve() == inside or inside in folder.resolve().parents:
        raise UserError(f"--update-baseline {folder}: inside the results directory {out}; "
                        "choose a folder outside it")
    files = {folder / f"{name}.csv": (frame, read_baseline)
             for name, frame in key_numbers(results).items()}
    files.update({folder / GATED_DIR / f"{name}.csv": (frame, read_gated)
                  for name, frame in gated_rows(results).items()})
    for path, (_, parse) in files.items():
        if path.is_symlink() or path.exists() and not path.is_file():
            raise UserError(f"{path} is not a regular file; refusing to replace it")
        if path.exists():
            try:
                read_result(path, parse)
            except DamagedResult as exc:
                raise UserError(f"{path} exists and is not a baseline ({exc}); refusing "
                                "to replace it") from None
    for path, (frame, _) in files.items():
        path.parent.mkdir(parents=True, exist_ok=True)
        write_csv(path, frame)
    return list(files)


def read_baseline(path: Path) -> pd.DataFrame:
    """One baseline CSV: the :data:`INDEX` columns, numbers in the :data:`KEYS` columns
    it has, one row per (case, solver, param, step)."""
    frame = read_csv(path, required=INDEX, text=("case", "solver", "param"), numeric=KEYS,
                     integer=["step"])
    if frame.empty:
        raise Malformed("no rows (a baseline with nothing in it would pass anything)")
    for col in [k for k in KEYS if k in frame.columns]:
        values = frame[col].to_numpy(float)
        if np.isinf(values).any():  # blank (NaN) is a number a solver does not give
            r = frame.iloc[int(np.flatnonzero(np.isinf(values))[0])]
            raise Malformed(f"column {col}: {r[col]} for solver {r['solver']} [{r['param']}] "
                            f"step {r['step']} is not a finite number (it would hide every "
                            "drift of the column)")
    dup = frame.duplicated(INDEX)
    if dup.any():
        r = frame[dup].iloc[0]
        raise Malformed(f"two rows for solver {r['solver']} [{r['param']}] step {r['step']}")
    return frame


def read_gated(path: Path) -> pd.DataFrame:
    """One baseline of gated rows: :data:`ROW_INDEX`, ``gated`` (True/False) and
    ``reason``, one row per metric row."""
    frame = read_csv(path, required=[*ROW_INDEX, "gated", "reason"],
                     text=("param", "pair", "quantity", "metric", "reason"),
                     integer=["step"], boolean=["gated"])
    if frame.empty:
        raise Malformed("no rows (a baseline with nothing in it would pass anything)")
    dup = frame.duplicated(ROW_INDEX)
    if dup.any():
        r = frame[dup].iloc[0]
        raise Malformed(f"two rows for [{r['param']}] step {r['step']} {r['pair']} "
                        f"{r['quantity']} {r['metric']}")
    return frame


def ungated_since(results: Scan, folder: Path) -> list[str]:
    """One line per metric row gated in the baselines of gated rows in ``folder`` that
    the results no longer gate (with its reason now) or no longer hold, and per case of
    the results without such a baseline."""
    folder = Path(folder)
    lines = []
    for name, current in gated_rows(results).items():
        path = folder / GATED_DIR / f"{name}.csv"
        if not path.is_file():
            lines.append(f"DRIFT {name}: no baseline of its gated rows {path} (write it "
                         "with `contact-vv gate --update-baseline DIR`)")
            continue
        try:
            base = read_result(path, read_gated)
        except DamagedResult as exc:
            raise UserError(f"baseline {exc}") from None
        was = base[base["gated"].astype(bool)]
        merged = was.merge(current, on=ROW_INDEX, how="left", suffixes=("", "_now"),
                           indicator="found")
        for r in merged.itertuples(index=False):
            where = (f"DRIFT {name}" + (f" [{r.param}]" if r.param else "")
                     + f" step {r.step} {r.pair} {r.quantity} {r.metric}: gated in the "
                     f"baseline {path}, ")
            if r.found == "left_only":
                lines.append(where + "missing from the results")
            elif not bool(r.gated_now):
                lines.append(where + f"not gated now ({r.reason_now})")
    return lines


def read(folder: Path) -> dict[str, pd.DataFrame]:
    """The baselines in ``folder`` by case; :class:`UserError` if it is not a baseline
    directory (missing, no ``<case>.csv``, or a file that cannot be read as a baseline)."""
    folder = Path(folder)
    if not folder.is_dir():
        raise UserError(f"baseline directory {folder} " + (
            "is not a directory" if folder.exists() else "does not exist")
            + " (create it with `contact-vv gate --update-baseline DIR`)")
    paths = sorted(folder.glob("*.csv"))
    if not paths:
        raise UserError(f"baseline directory {folder} holds no <case>.csv baselines "
                        "(create them with `contact-vv gate --update-baseline DIR`)")
    try:
        return {path.stem: read_result(path, read_baseline) for path in paths}
    except DamagedResult as exc:
        raise UserError(f"baseline {exc}") from None


def drift(results: Scan, folder: Path, tol: float = DEFAULT_DRIFT) -> list[str]:
    """One line per key number that drifted beyond ``tol``, per missing result row and
    per metric row gated in the baseline and not now (:func:`ungated_since`).

    Drift of a number x against its baseline b: |x − b| / max(|b|, 1e-12 m), m the largest
    |b| of that column in the case (so numbers that should be zero are compared on the
    scale of the column).  NaN matches NaN only.
    """
    folder = Path(folder)
    baselines = read(folder)
    current = key_numbers(results)
    lines = ungated_since(results, folder)
    for name in sorted(set(current) - set(baselines)):
        lines.append(f"DRIFT {name}: in the results but no baseline {folder / name}.csv")
    for name, base in baselines.items():
        path = folder / f"{name}.csv"
        if name not in current:
            lines.append(f"DRIFT {name}: in the baseline {path} but not in the results")
            continue
        cur = current[name]
        merged = base.merge(cur, on=INDEX, how="outer", suffixes=("", "_new"), indicator=True)
        for r in merged[merged["_merge"] == "left_only"].itertuples(index=False):
            lines.append(f"DRIFT {name} {r.solver} [{r.param}] step {r.step}: "
                         "baseline row missing from the results")
        for r in merged[merged["_merge"] == "right_only"].itertuples(index=False):
            lines.append(f"DRIFT {name} {r.solver} [{r.param}] step {r.step}: "
                         f"result row missing from the baseline {path}")
        both = merged[merged["_merge"] == "both"]
        for col in [k for k in KEYS if k in base.columns]:
            if f"{col}_new" not in both.columns:
                lines.append(f"DRIFT {name}: column {col} missing from the results")
                continue
            b = both[col].to_numpy(float)
            x = both[f"{col}_new"].to_numpy(float)
            scale = np.nanmax(np.abs(b)) if np.isfinite(b).any() else 0.0
            denom = np.maximum(np.abs(b), 1e-12 * scale if scale > 0 else 1e-300)
            with np.errstate(invalid="ignore", divide="ignore"):
                rel = np.abs(x - b) / denom
            bad = np.where(np.isnan(b) != np.isnan(x), True,
                           np.nan_to_num(rel, nan=0.0) > tol)
            for i in np.flatnonzero(bad):
                r = both.iloc[i]
                value = rel[i] if math.isfinite(rel[i]) else float("nan")
                lines.append(
                    f"DRIFT {name} {r['solver']} [{r['param']}] step {r['step']} {col}: "
                    f"{x[i]:.10g} vs baseline {b[i]:.10g} (relative {value:.3g} > {tol:g})")
    return lines
