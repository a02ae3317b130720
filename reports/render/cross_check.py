"""Every pair of solvers side by side: for each quantity and metric of a case, the worst
value of each pair (``fem-analytic``, ``kratos-analytic``, ``kratos-fem``, …) in one row,
so that a reader sees whether two references agree with each other where they differ
from a third solver (issue 60, point 4).  A view of the metrics rows, nothing computed
anew: each cell is the value of the row the metrics tables show as that pair's worst
(:func:`reports.store.readers.worst` for a gated quantity,
:func:`reports.store.readers.ungated` for one that is not), marked ``✗`` where that row
failed its gate and ``(ng)`` where the quantity is not gated.

The columns are ordered by the pair's oracle (another solver first, then a closed form),
then by name, so the table does not depend on the order in which the solvers ran.
"""

from __future__ import annotations

import math

import pandas as pd

from reports.store import readers

#: the oracles whose pairs compare two solvers' fields (a metamorphic relation compares
#: one solver with itself and has no place among the pairs)
ORACLES = ("other solver", "closed form")


def _cell(row: pd.Series) -> str:
    value = row["value"]
    text = "—" if not math.isfinite(value) else f"{value:.3g}"
    if not row["on"]:
        return f"{text} (ng)"
    return text if bool(row["passed"]) else f"{text} ✗"


def pairs_side_by_side(metrics: pd.DataFrame) -> pd.DataFrame:
    """One row per (quantity, metric), one column per pair of solvers (module doc); empty
    when fewer than two pairs compare solvers."""
    if metrics.empty or "oracle" not in metrics.columns:
        return pd.DataFrame()
    m = metrics[metrics["oracle"].isin(ORACLES)]
    if m["pair"].nunique() < 2:
        return pd.DataFrame()
    on = readers.gated(m)
    keys = ["pair", "quantity", "metric"]
    worst = pd.concat([readers.worst(m[on]).assign(on=True),
                       readers.ungated(m).assign(on=False)])
    worst = worst.drop_duplicates(keys)  # a quantity gated at some rows: its gated worst
    rank = {o: k for k, o in enumerate(ORACLES)}
    pairs = sorted(worst["pair"].unique(),
                   key=lambda p: (rank[worst.loc[worst["pair"] == p, "oracle"].iloc[0]], p))
    cells = worst.assign(cell=[_cell(r) for _, r in worst.iterrows()])
    table = cells.pivot(index=["quantity", "metric"], columns="pair", values="cell")
    table = table.reindex(columns=pairs).fillna("")
    return table.sort_index().reset_index().rename_axis(columns=None)
