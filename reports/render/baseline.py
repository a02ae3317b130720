"""Regression baselines: key numbers of a results directory stored as CSV, and the drift
of new results from them.

``contact-vv gate --update-baseline DIR`` writes ``DIR/<case>.csv`` (one row per case,
solver, sweep point and output step; the columns of :data:`KEYS`) from the results;
``contact-vv gate --baseline DIR`` fails on any key number that drifted from its baseline
by more than ``--drift`` (relative, default 1e-6) or on a baseline row missing from the
results.  Updating is always explicit.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd

from reports.registry.errors import UserError
from reports.store.readers import DamagedResult, Malformed, read_csv, read_result
from reports.store.results import Scan

INDEX = ["case", "solver", "param", "step"]
KEYS = ["P", "p_max", "a_x", "a_y", "contact_area", "stick_area", "w_max", "wear_volume",
        "vm_max", "vm_max_x", "vm_max_z", "vm_max_below"]
DEFAULT_DRIFT = 1e-6


def key_numbers(results: Scan) -> dict[str, pd.DataFrame]:
    """Per case directory: the baseline columns of its summary."""
    out = {}
    for case in results.complete:
        s = case.summary.copy()
        s["case"] = case.name
        cols = INDEX + [k for k in KEYS if k in s.columns]
        out[case.name] = s[cols].sort_values(INDEX, kind="stable").reset_index(drop=True)
    return out


def write(results: Scan, folder: Path) -> list[Path]:
    """Write (replace) the baselines of every complete case of ``results``."""
    from reports.store.write import write_csv

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    paths = []
    for name, frame in key_numbers(results).items():
        path = folder / f"{name}.csv"
        write_csv(path, frame)
        paths.append(path)
    return paths


def read_baseline(path: Path) -> pd.DataFrame:
    """One baseline CSV: the :data:`INDEX` columns, numbers in the :data:`KEYS` columns
    it has, one row per (case, solver, param, step)."""
    frame = read_csv(path, required=INDEX, text=("case", "solver", "param"), numeric=KEYS,
                     integer=["step"])
    dup = frame.duplicated(INDEX)
    if dup.any():
        r = frame[dup].iloc[0]
        raise Malformed(f"two rows for solver {r['solver']} [{r['param']}] step {r['step']}")
    return frame


def read(folder: Path) -> dict[str, pd.DataFrame]:
    """The baselines in ``folder`` by case; :class:`UserError` if it is not a baseline
    directory (missing, no ``<case>.csv``, or a file that cannot be read as a baseline)."""
    folder = Path(folder)
    if not folder.is_dir():
        raise UserError(f"baseline directory {folder} does not exist "
                        "(create it with `contact-vv gate --update-baseline DIR`)")
    paths = sorted(folder.glob("*.csv"))
    if not paths:
        raise UserError(f"baseline directory {folder} holds no <case>.csv baselines "
                        "(create them with `contact-vv gate --update-baseline DIR`)")
    try:
        return {path.stem: read_result(path, read_baseline) for path in paths}
    except DamagedResult as exc:
        raise UserError(f"baseline {exc}") from None


def drift(results: Scan, folder: Path, tol: float = DEFAULT_DRIFT) -> list[str]:
    """One line per key number that drifted beyond ``tol`` and per missing result row.

    Drift of a number x against its baseline b: |x − b| / max(|b|, 1e-12 m), m the largest
    |b| of that column in the case (so numbers that should be zero are compared on the
    scale of the column).  NaN matches NaN only.
    """
    folder = Path(folder)
    baselines = read(folder)
    current = key_numbers(results)
    lines = []
    for name, base in baselines.items():
        path = folder / f"{name}.csv"
        if name not in current:
            lines.append(f"DRIFT {name}: in the baseline {path} but not in the results")
            continue
        cur = current[name]
        merged = base.merge(cur, on=INDEX, how="left", suffixes=("", "_new"), indicator=True)
        for r in merged[merged["_merge"] == "left_only"].itertuples(index=False):
            lines.append(f"DRIFT {name} {r.solver} [{r.param}] step {r.step}: "
                         "baseline row missing from the results")
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
