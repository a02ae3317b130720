"""The report's pairs side by side (reports/render/cross_check.py; issue 60, point 4): each
cell is the worst row the metrics table shows for that pair, failures and ungated rows are
marked, a relation of one solver with itself is left out, and neither the order of the
rows nor the order in which the solvers ran changes the table."""

from __future__ import annotations

import pandas as pd

from reports.render.cross_check import pairs_side_by_side


def rows() -> pd.DataFrame:
    def row(pair, oracle, quantity, metric, value, tolerance, passed=True, status="gated",
            param="", step=0):
        return dict(pair=pair, oracle=oracle, quantity=quantity, metric=metric, value=value,
                    tolerance=tolerance, passed=passed, status=status, param=param, step=step)

    return pd.DataFrame([
        row("kratos-analytic", "closed form", "p_max", "rel", 6e-5, 0.01),
        row("fem-analytic", "closed form", "p_max", "rel", 1.7e-3, 0.01),
        row("kratos-fem", "other solver", "p_max", "rel", 1.6e-3, 0.01),
        # two points: the worst is the larger value over tolerance, not the last row
        row("kratos-fem", "other solver", "vm_xz", "max", 0.3, 0.21, passed=False, param="a"),
        row("kratos-fem", "other solver", "vm_xz", "max", 0.1, 0.21, param="b"),
        row("fem-analytic", "closed form", "vm_xz", "max", 9.4e-3, 0.065),
        row("kratos-analytic", "closed form", "p_n", "l2", 8e-3, 0.04, status="below floor"),
        # a metamorphic relation compares one solver with itself: not a pair of solvers
        row("fem~mirror", "metamorphic relation", "p_max", "rel", 1e-9, 1e-6),
    ])


def test_each_cell_is_the_pairs_worst_row_marked():
    t = pairs_side_by_side(rows()).set_index(["quantity", "metric"])
    assert t.columns.tolist() == ["kratos-fem", "fem-analytic", "kratos-analytic"]
    assert t.loc[("p_max", "rel"), "kratos-analytic"] == "6e-05"
    assert t.loc[("p_max", "rel"), "fem-analytic"] == "0.0017"
    assert t.loc[("vm_xz", "max"), "kratos-fem"] == "0.3 ✗"
    assert t.loc[("vm_xz", "max"), "kratos-analytic"] == ""  # no such row
    assert t.loc[("p_n", "l2"), "kratos-analytic"] == "0.008 (ng)"
    assert "fem~mirror" not in t.columns


def test_the_table_does_not_depend_on_the_order_of_the_rows():
    m = rows()
    first = pairs_side_by_side(m)
    for seed in range(5):
        assert pairs_side_by_side(m.sample(frac=1.0, random_state=seed)).equals(first)


def test_one_pair_is_no_cross_check():
    m = rows()
    assert pairs_side_by_side(m[m["pair"] == "kratos-fem"]).empty
    assert pairs_side_by_side(m.iloc[0:0]).empty


def test_a_quantity_gated_at_some_rows_shows_its_gated_worst():
    m = rows()
    extra = m.iloc[[0]].assign(value=0.5, status="below floor", param="c")
    t = pairs_side_by_side(pd.concat([m, extra], ignore_index=True))
    t = t.set_index(["quantity", "metric"])
    assert t.loc[("p_max", "rel"), "kratos-analytic"] == "6e-05"
