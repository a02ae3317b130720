"""Per-cycle metrics of fretting runs from the solvers' tables: the loop Q(δ) of a cycle
and the energy it dissipates (tables ``loops`` and ``cycles`` of a RunResult), compared
pairwise like the steps (:mod:`reports.compare.metrics`)."""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

from cases.model import Case
from reports.registry import tolerances as tol

_TINY = 1e-12


def friction_scale(case: Case) -> float:
    """μP of a case: P its Hertz load (2π a0² p0 / 3, the held load or the load of the
    held approach) and μ the friction coefficient along ``load.slide_angle``
    (:attr:`cases.model.Case.sliding_friction`)."""
    a0, p0 = case.hertz_scales
    return case.sliding_friction * 2.0 * math.pi * a0 * a0 * p0 / 3.0


def _cycle_rows(table: Mapping[str, object] | None, cycle: float) -> np.ndarray | None:
    """Indices of the rows of ``table`` that belong to ``cycle`` (None: no such rows)."""
    if not table or "cycle" not in table:
        return None
    col = np.asarray(table["cycle"], dtype=float)
    k = np.flatnonzero(np.isclose(col, cycle, rtol=0.0, atol=1e-9 * max(1.0, abs(cycle))))
    return k if k.size else None


def _column(table: Mapping[str, object], name: str, rows: np.ndarray) -> np.ndarray | None:
    if name not in table:
        return None
    return np.asarray(table[name], dtype=float)[rows]


def compare_tables(ta: Mapping[str, Mapping], tb: Mapping[str, Mapping], cycle: float,
                   mu_P: float) -> list[tuple[str, str, float]]:
    """Metric rows (quantity, metric, value) of cycle ``cycle`` from the tables of solver
    A (``ta``) against reference B (``tb``):

    - ``loop_q`` (max): max |Q_A − Q_B| / ``mu_P`` over the cycle's points of table
      ``loops``, Q = (Qx, Qy); only when both loops pass through the same displacements
      (same path and steps), matched in order;
    - ``q_ends`` (max): the same over the loop's extremes only, the points where |δ| is
      the amplitude (the largest |δ| of B's loop): the global tangential load the
      contact carries at ±A;
    - ``energy`` (rel): |E_A − E_B| / |E_B| of column ``energy`` of table ``cycles``.

    A cycle missing from either table, or a column missing from either, is skipped;
    energies zero in both (below 1e-12 μP × the amplitude) too."""
    rows: list[tuple[str, str, float]] = []
    la, lb = ta.get("loops"), tb.get("loops")
    ka, kb = _cycle_rows(la, cycle), _cycle_rows(lb, cycle)
    scale_d = 0.0
    if ka is not None and kb is not None and mu_P > 0:
        cols = [(_column(la, c, ka), _column(lb, c, kb)) for c in
                ("displacement", "Qx", "Qy")]
        if all(x is not None and y is not None for x, y in cols):
            (da, db), (qxa, qxb), (qya, qyb) = cols
            scale_d = float(np.max(np.abs(db))) if db.size else 0.0
            if da.size == db.size and np.allclose(da, db, rtol=0.0,
                                                  atol=1e-9 * max(scale_d, _TINY)):
                diff = np.hypot(qxa - qxb, qya - qyb)
                ends = np.abs(db) >= (1.0 - 1e-9) * scale_d
                rows.append(("loop_q", tol.TABLE_QUANTITIES["loop_q"][1],
                             float(np.max(diff)) / mu_P))
                rows.append(("q_ends", tol.TABLE_QUANTITIES["q_ends"][1],
                             float(np.max(diff[ends])) / mu_P))
    ca, cb = ta.get("cycles"), tb.get("cycles")
    ja, jb = _cycle_rows(ca, cycle), _cycle_rows(cb, cycle)
    if ja is not None and jb is not None:
        ea, eb = _column(ca, "energy", ja[-1:]), _column(cb, "energy", jb[-1:])
        if ea is not None and eb is not None and np.isfinite(ea[0]) and np.isfinite(eb[0]):
            a, b = float(ea[0]), float(eb[0])
            tiny = _TINY * mu_P * max(scale_d, 1.0)
            if not (abs(a) <= tiny and abs(b) <= tiny):
                rows.append(("energy", tol.TABLE_QUANTITIES["energy"][1],
                             abs(a - b) / abs(b) if abs(b) > tiny else math.inf))
    return rows
