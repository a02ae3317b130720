"""The verdict on a case's metric rows: status, tolerance and ``passed``, decided once.

The comparisons (:mod:`reports.compare.metrics`) give every row its value, its status
from what they see themselves (a quantity the case declares not converged, a ``kink``
row, a σ_VM maximum whose location is not determined) and the tolerance of its key
(:func:`reports.registry.tolerances.tolerance`).  The studies of a run
(:mod:`reports.studies.study`) add evidence (:data:`Evidence`), folded in this
order, each group in the order of the studies' list:

1. the grid study (``run --convergence``): rows of a quantity that the grids do not
   settle beyond the solver's budget become "not gated" (:class:`Flags`,
   :func:`reports.studies.gridstudy.flags`);
   the resolution probe of worn points (:func:`reports.studies.probe.flags`): rows of a
   quantity that a step spread over the FEM's element moves by more than half their
   tolerance likewise;
2. the combined numerical uncertainty U of the pair (Eq. U1): the tolerance of a row
   still gated becomes min(U, tolerance) (:func:`reports.studies.uncertainty.values`);
3. the cycle-jump study (``run --jump-study``): as 1, with the jump's levels
   (:class:`Flags` with ``late``: its levels are not part of U).

Then, and only here, ``passed`` follows from value and tolerance by the one pass rule
:func:`reports.registry.tolerances.passes`.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from reports.registry import tolerances as tol

#: the contract columns of metrics.csv, then those the comparisons add
METRICS_COLUMNS = ["quantity", "pair", "metric", "value", "tolerance", "passed"]
EXTRA_COLUMNS = ["case", "param", "step", "s", "cycle", "tolerance_key", "status", "note",
                 "reason", "oracle"]


@dataclass(frozen=True)
class Flags:
    """A study's findings on metric rows (by position): notes of the solvers whose study
    drops the row (not settled beyond their budget) and of those whose study keeps it."""

    dropped: Mapping[int, Sequence[str]] = field(default_factory=dict)
    kept: Mapping[int, Sequence[str]] = field(default_factory=dict)
    late: bool = False  # applied after the uncertainty (step 3 of the module doc)
    #: the ``reason`` of a row it drops (a code of reports.registry.tolerances.REASONS)
    reason: str = "study"


@dataclass(frozen=True)
class Uncertainty:
    """The combined numerical uncertainty U of every row (by position; NaN: none), which
    tightens the tolerance of a row still gated to min(U, tolerance)."""

    values: np.ndarray


#: what a study tells the verdict about the metric rows
Evidence = Flags | Uncertainty


def _flag(out: pd.DataFrame, flags: Flags) -> None:
    """Apply a study's :class:`Flags` in place: a dropped row is not gated, and every
    flagged row's note names the study's findings after any earlier reason."""
    status, note = out.columns.get_loc("status"), out.columns.get_loc("note")
    reason = out.columns.get_loc("reason")
    for k in sorted(set(flags.dropped) | set(flags.kept)):
        dropped, kept = list(flags.dropped.get(k, ())), list(flags.kept.get(k, ()))
        if not (dropped or kept):
            continue
        old = str(out.iat[k, note]) if out.iat[k, status] == tol.NOT_GATED else ""
        if dropped:
            if out.iat[k, status] != tol.NOT_GATED:  # the first reason stays
                out.iat[k, reason] = flags.reason
            out.iat[k, status] = tol.NOT_GATED
        out.iat[k, note] = "; ".join([n for n in [old] if n] + dropped
                                     + [t + " (gated)" for t in kept])


def _tighten(out: pd.DataFrame, found: Uncertainty) -> None:
    """Apply U in place: the tolerance of a row still gated becomes min(U, budget)."""
    if out.empty:
        return
    u = np.where(out["status"].to_numpy() == tol.GATED, np.asarray(found.values, float),
                 np.nan)
    tighter = np.isfinite(u) & (u < out["budget"].to_numpy(float))
    out["uncertainty"] = u
    out.loc[tighter, "tolerance"] = u[tighter]
    out.loc[tighter, "tolerance_kind"] = tol.UNCERTAINTY


def decide(rows: pd.DataFrame, evidence: Sequence[Evidence | None] = ()) -> pd.DataFrame:
    """metrics.csv from the comparisons' ``rows`` and a run's study ``evidence`` (module
    doc; None: none): status, tolerance, ``tolerance_kind``, ``budget``, ``uncertainty``
    and ``passed``."""
    out = tol.with_tolerance_columns(rows).reset_index(drop=True)
    if "reason" not in out.columns:  # rows built without it: the codes of their status
        out["reason"] = np.where(out["status"] == tol.GATED, "", tol.UNRECORDED)
    for f in evidence:
        if isinstance(f, Flags) and not f.late:
            _flag(out, f)
    for f in evidence:
        if isinstance(f, Uncertainty):
            _tighten(out, f)
    for f in evidence:
        if isinstance(f, Flags) and f.late:
            _flag(out, f)
    out["passed"] = tol.passes(out["value"], out["tolerance"]).astype(bool)
    extra = [c for c in out.columns if c not in METRICS_COLUMNS]
    return out[METRICS_COLUMNS + extra]
