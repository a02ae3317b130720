"""The verdict on a case's metric rows: status, tolerance and ``passed``, decided once.

The comparisons (:mod:`reports.compare.metrics`) give every row its value, its status
from what they see themselves (a quantity the case declares not converged, a ``kink``
row, a σ_VM maximum whose location is not determined) and the tolerance of its key
(:func:`reports.registry.tolerances.tolerance`).  The studies of a run add evidence, in
this order:

1. the grid study (``run --convergence``): rows of a quantity that the grids do not
   settle beyond the solver's budget become "not converged" (:class:`Flags`,
   :func:`reports.studies.gridstudy.flags`);
   the resolution probe of worn points (:func:`reports.studies.probe.flags`): rows of a
   quantity that a step spread over the FEM's element moves by more than half their
   tolerance likewise;
2. the combined numerical uncertainty U of the pair (Eq. U1): the tolerance of a row
   still gated becomes min(U, tolerance) (:func:`reports.studies.uncertainty.values`);
3. the cycle-jump study (``run --jump-study``): as 1, with the jump's levels.

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
                 "oracle"]


@dataclass(frozen=True)
class Flags:
    """A study's findings on metric rows (by position): notes of the solvers whose study
    drops the row (not settled beyond their budget) and of those whose study keeps it."""

    dropped: Mapping[int, Sequence[str]] = field(default_factory=dict)
    kept: Mapping[int, Sequence[str]] = field(default_factory=dict)


def _flag(out: pd.DataFrame, flags: Flags | None) -> None:
    """Apply a study's :class:`Flags` in place: a dropped row is not gated, and every
    flagged row's note names the study's findings after any earlier reason."""
    if flags is None:
        return
    status, note = out.columns.get_loc("status"), out.columns.get_loc("note")
    for k in sorted(set(flags.dropped) | set(flags.kept)):
        dropped, kept = list(flags.dropped.get(k, ())), list(flags.kept.get(k, ()))
        if not (dropped or kept):
            continue
        old = str(out.iat[k, note]) if out.iat[k, status] == tol.NOT_CONVERGED else ""
        if dropped:
            out.iat[k, status] = tol.NOT_CONVERGED
        out.iat[k, note] = "; ".join([n for n in [old] if n] + dropped
                                     + [t + " (gated)" for t in kept])


def decide(rows: pd.DataFrame, *, grid: Flags | None = None,
           uncertainty: np.ndarray | None = None, jump: Flags | None = None,
           probe: Flags | None = None) -> pd.DataFrame:
    """metrics.csv from the comparisons' ``rows`` and a run's study evidence (module doc):
    status, tolerance, ``tolerance_kind``, ``budget``, ``uncertainty`` and ``passed``."""
    out = tol.with_tolerance_columns(rows).reset_index(drop=True)
    _flag(out, grid)
    _flag(out, probe)
    if uncertainty is not None and not out.empty:
        u = np.where(out["status"].to_numpy() == tol.GATED,
                     np.asarray(uncertainty, float), np.nan)
        tighter = np.isfinite(u) & (u < out["budget"].to_numpy(float))
        out["uncertainty"] = u
        out.loc[tighter, "tolerance"] = u[tighter]
        out.loc[tighter, "tolerance_kind"] = tol.UNCERTAINTY
    _flag(out, jump)
    out["passed"] = tol.passes(out["value"], out["tolerance"]).astype(bool)
    extra = [c for c in out.columns if c not in METRICS_COLUMNS]
    return out[METRICS_COLUMNS + extra]
