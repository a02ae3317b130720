"""The resolution probe's verdict (reports/studies/probe.py): which rows it admits, which
it shows, and why, on made-up metric rows and probe tables whose answer is known."""

from __future__ import annotations

import pandas as pd
import pytest

from reports.compare.verdict import decide
from reports.registry import tolerances as tol
from reports.store.study_tables import PROBE_COLUMNS
from reports.studies import probe


def _rows(*rows: tuple[str, str, str, float, float]) -> pd.DataFrame:
    """Metric rows (pair, quantity, metric, value, tolerance) of param ``beta=90``, step 2."""
    return pd.DataFrame([{
        "quantity": q, "pair": pair, "metric": m, "value": v, "tolerance": t,
        "passed": False, "case": "c", "param": "beta=90", "step": 2, "s": float("nan"),
        "cycle": 1000.0, "tolerance_key": f"default:{q}", "status": tol.GATED, "note": "",
        "oracle": "other solver"} for pair, q, m, v, t in rows])


def _table(*rows: tuple[str, str, str, float]) -> pd.DataFrame:
    return pd.DataFrame([{
        "param": "beta=90", "pair": pair, "step": 2, "cycle": 1000.0, "quantity": q,
        "metric": m, "sensitivity": s, "width": 0.08, "spread": 0.04}
        for pair, q, m, s in rows], columns=PROBE_COLUMNS)


def test_a_row_is_gated_only_where_the_probe_moves_it_by_at_most_half_its_tolerance():
    rows = _rows(("ic-fem", "w_max", "rel", 0.02, 0.08),
                 ("ic-fem", "energy", "rel", 0.02, 0.06),
                 ("ic-fem", "P", "rel", 0.001, 0.06),
                 ("ic-ic+mirror", "energy", "rel", 1e-12, 1e-9))  # not a probed pair
    table = _table(("ic-fem", "w_max", "rel", 0.04),        # exactly half: admitted
                   ("ic-fem", "energy", "rel", 0.0301),     # beyond half: shown
                   ("ic-fem", "P", "rel", float("nan")))    # not formed: shown
    out = decide(rows, [probe.flags(rows, table)])
    assert list(out["status"]) == [tol.GATED, tol.NOT_GATED, tol.NOT_GATED,
                                   tol.GATED]
    note = out["note"].iat[1]
    assert note.startswith("resolution probe: ") and "0.0301" in note and "0.06" in note
    # the element that would resolve it at first order: 0.08 mm × 0.03 / 0.0301
    assert "0.08 mm" in note and "about 0.08 mm would" in note
    assert out["passed"].iat[0] and out["passed"].iat[3]


def test_rows_the_probe_did_not_measure_or_whose_probe_failed_are_not_gated():
    rows = _rows(("ic-fem", "w_max", "rel", 0.02, 0.08), ("fem-analytic", "p_max", "rel",
                                                         0.001, 0.02))
    missing = probe.flags(rows, _table(("ic-fem", "w_max", "rel", 0.0)))
    assert sorted(missing.dropped) == [1]
    assert "not measured" in missing.dropped[1][0]
    failed = probe.flags(rows, _table(), {"beta=90": "solver: did not converge"})
    assert sorted(failed.dropped) == [0, 1]
    assert "resolution probe failed (solver: did not converge)" in failed.dropped[0]
    # another point's rows are not the probe's business
    other = rows.assign(param="beta=0")
    assert probe.flags(other, _table(("ic-fem", "w_max", "rel", 1.0))).dropped == {}


def test_the_report_table_says_which_rows_the_probe_admits():
    rows = _rows(("ic-fem", "w_max", "rel", 0.02, 0.08), ("ic-fem", "energy", "rel", 0.02,
                                                          0.06))
    table = probe.admitted(rows, _table(("ic-fem", "w_max", "rel", 0.01),
                                        ("ic-fem", "energy", "rel", 0.05)))
    assert list(table["admitted"]) == [True, False]
    assert list(table["tolerance"]) == pytest.approx([0.08, 0.06])
