"""Read what runs left in a results directory: complete cases and incomplete ones."""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from cases.result import StepResult, load_step

from . import layout, manifest
from .errors import UserError


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

    def steps(self, solver: str, param: str) -> dict[int, StepResult]:
        """Output steps of one solver at one sweep point, by step number."""
        folder = layout.unit_dir(self.path, solver, param)
        out = {}
        for f in sorted(folder.glob("step_*.npz")):
            out[int(f.stem.split("_")[1])] = load_step(f)
        return out

    def tables(self, solver: str, param: str) -> dict[str, pd.DataFrame]:
        folder = layout.unit_dir(self.path, solver, param)
        return {f.stem: pd.read_csv(f) for f in sorted(folder.glob("*.csv"))}

    def point(self, param: str) -> dict[str, Any]:
        """The case parameters (as recorded) of one sweep point."""
        for p in self.manifest.get("points", []):
            if p.get("param", "") == param:
                return p
        return {}


@dataclass
class Scan:
    """All cases in a results directory."""

    complete: list[CaseResults] = field(default_factory=list)
    incomplete: dict[str, str] = field(default_factory=dict)  # case -> reason


def _read_csv(path: Path) -> pd.DataFrame:
    frame = pd.read_csv(path, dtype={"param": object})
    if "param" in frame.columns:
        frame["param"] = frame["param"].fillna("").astype(str)
    return frame


def _failure_reason(staging: Path) -> str:
    failed = staging / layout.FAILED
    if failed.is_file():
        try:
            return "run failed: " + "; ".join(json.loads(failed.read_text())["failures"])
        except (OSError, ValueError, KeyError):
            pass
    return "run interrupted or still in progress (no manifest)"


def scan(out: Path, *, verify: bool = True) -> Scan:
    """Every case directory under ``out``; :class:`UserError` if ``out`` is not one."""
    out = Path(out)
    if not out.is_dir():
        raise UserError(f"results directory {out} does not exist (run `contact-vv run` first)")
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
            mf = manifest.read(path, verify=verify)
        except manifest.IncompleteRun as exc:
            result.incomplete[path.name] = str(exc)
            continue
        result.complete.append(CaseResults(
            path=path, manifest=mf, summary=_read_csv(path / layout.SUMMARY),
            metrics=_read_csv(path / layout.METRICS)))
    return result


def not_converged(summary: pd.DataFrame) -> pd.DataFrame:
    """Rows of a summary whose ``converged`` is false (blank means not applicable)."""
    if summary.empty or "converged" not in summary.columns:
        return summary.iloc[0:0]
    col = summary["converged"]
    text = col.astype(str).str.strip().str.lower()
    bad = text.isin(["false", "0", "0.0", "no"]) & col.notna()
    return summary[np.asarray(bad)]
