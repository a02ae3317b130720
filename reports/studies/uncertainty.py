"""Tolerances from measured numerical uncertainty (``run --convergence``).

A grid study (:mod:`reports.studies.gridstudy`) gives each numerical solver's scalar a measured
numerical uncertainty.  Following ASME V&V 20 (2009) and Roache (1998), two solutions
agree when their difference lies within the *combined* uncertainty of the pair
(docs/formulation.md §4.2, Eq. U1):

    U = √(u_A² + u_B² + m_A² + m_B²)

- u_s, the numerical uncertainty of solver s for this quantity at this sweep point and
  step, relative to its finest value f1 (the metric ``rel`` is relative too):

  - study ``converged``: Roache's GCI of the finest grid (``gci_fine``);
  - study ``exact`` (a load the solver imposes, a zero on every grid): 0;
  - study ``oscillating`` (differences change sign; still gated only when the three
    values spread by less than the solver's budget, :func:`reports.studies.gridstudy.flags`):
    Eça & Hoekstra's estimate for anomalous behaviour, three times the data range,
    3 (max f − min f) / |f1| (J. Comput. Phys. 262 (2014) 104–130), since no order and
    no Richardson extrapolation can be trusted;
  - ``unsettled``, or no study of that solver: none — the row keeps its budget;
  - a closed form (no grid): its stated accuracy, the budget of its registry record plus
    what it states for the kind of case (``case_term``: an asymptotic limit's deficit);

- m_s, the model-form term of solver s: what it models differently from the half-space
  problem (the FEM's finite block, measured by enlarging it), its record's
  ``model_form(quantity, metric)`` in :mod:`reports.registry.solvers`, with the measurement.

The tolerance of a gated row becomes min(U, the tolerance it had)
(:func:`reports.compare.verdict.decide`; this module gives U, :func:`values`): the uncertainty may
only tighten a gate, never widen a budget or a case key (a U above the budget says the
grids are too coarse to resolve that budget, and the row keeps the budget).  Every
metric row says which kind of tolerance it used (``tolerance_kind``): ``budget`` (the
pair's default, the sum of the two budgets), ``case`` (a key of the case file) or
``uncertainty``, with the tolerance it had before in ``budget`` and U in
``uncertainty`` (NaN where no U could be formed).  Only the scalars compared with the
metric ``rel`` get a U: the other metrics (field norms, lengths in cells) keep their
budgets.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np
import pandas as pd

from cases.model import Case
from reports.registry import solvers
from reports.studies import three_level

#: Eça & Hoekstra's factor on the data range of an anomalous (oscillating) study
RANGE_FACTOR = 3.0
#: metrics whose tolerance a grid study can set
STUDIED_METRICS = ("rel",)


def solver_uncertainty(row: Any) -> float:
    """u of one solver from its convergence-table row (module doc); NaN: none."""
    if row is None:
        return math.nan
    status = row.status
    if status == three_level.EXACT:
        return 0.0
    if status == three_level.CONVERGED:
        u = float(row.gci_fine)
        return u if math.isfinite(u) and u >= 0 else math.nan
    if status == three_level.OSCILLATING:
        f = np.array([row.f1, row.f2, row.f3], float)
        if not np.isfinite(f).all() or f[0] == 0:
            return math.nan
        return RANGE_FACTOR * float(f.max() - f.min()) / abs(float(f[0]))
    return math.nan


def combined(terms: list[float]) -> float:
    """√(Σ t²) of the terms (Eq. U1); NaN if any is NaN."""
    t = np.asarray(terms, dtype=float)
    return float(np.sqrt(np.sum(t * t))) if np.isfinite(t).all() else math.nan


def pair_uncertainty(pair: str, param: str, step: int, quantity: str, metric: str,
                     rows: dict[tuple[str, str, int, str], object],
                     case: Case | None = None) -> float:
    """U of one metric row (Eq. U1); NaN when a numerical solver of the pair has no
    usable study for it.  A closed form's accuracy is its budget plus what it states for
    the kind of case (its record's ``case_term``, e.g. an asymptotic limit)."""
    terms = []
    for solver in pair.split("-"):
        rec = solvers.record(solver)
        if rec.closed_form:
            terms.append(rec.budget(quantity, metric)
                         + (rec.case_term(case, quantity, metric) if case else 0.0))
        else:
            terms.append(solver_uncertainty(rows.get((solver, param, step, quantity))))
        terms.append(rec.model_form(quantity, metric))
    return combined(terms)


def values(metrics: pd.DataFrame, frame: pd.DataFrame | None,
           cases: Mapping[str, Case] | None = None) -> np.ndarray | None:
    """U of every ``rel`` row of ``metrics`` from the grid-study table ``frame`` (Eq. U1;
    NaN where none can be formed), for :func:`reports.compare.verdict.decide`, which
    tightens the tolerance of a row still gated to min(U, tolerance); None without a
    study."""
    if frame is None or frame.empty or metrics.empty:
        return None
    rows = {(str(r.solver), "" if pd.isna(r.param) else str(r.param), int(r.step),
             str(r.quantity)): r for r in frame.itertuples(index=False)}
    param = metrics["param"].fillna("").astype(str)
    u = np.full(len(metrics), math.nan)
    for k in range(len(metrics)):
        metric = str(metrics["metric"].iat[k])
        if metric in STUDIED_METRICS:
            u[k] = pair_uncertainty(str(metrics["pair"].iat[k]), param.iat[k],
                                    int(metrics["step"].iat[k]),
                                    str(metrics["quantity"].iat[k]), metric, rows,
                                    (cases or {}).get(param.iat[k]))
    return u
