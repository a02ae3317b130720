"""Another code's correct results pass the gate on cases nobody bundled (issue 49): the
half-space solver's own surface tractions and contact states, exported as a CSV table at
its cell centres with its resultants stated (as a boundary-element code would hand them
over), read back as ``external:bem`` on generated static cases (tests/case_generator.py:
other R, P, materials, ν, friction, rectangular cells, the load or the approach held,
partial slip, full sliding).  The reader triangulates the points (no cells), so its
fields at the cell centres are the table's values: every row of ``external:bem``
against the closed forms equals the half-space solver's to round-off, and none fails
where the half-space solver's passes (no false alarm from the reader)."""

from __future__ import annotations

import numpy as np
import pandas as pd
from case_generator import user_case
from hypothesis import HealthCheck, given, settings

import halfspace
from cases import load_case
from reports.cli import main
from reports.registry import solvers, tolerances

FIELDS = ("p_n", "p_x", "p_y", "state")
STATED = ("P", "Qx", "Qy")
ROWS = ("p_n", "p_x", "p_y", "P", "p_max", "a_x", "a_y", "contact_area", "stick_area")


def grid_budget_table() -> str:
    """The half-space solver's budgets, stated as a user would whose code is as good."""
    return "\n".join(["default = 0.03"] + [
        f"{q}_{m} = {solvers.grid_budget(q, m)!r}"
        for q, metrics in tolerances.QUANTITY_METRICS.items() for m in metrics])


@settings(max_examples=8, derandomize=True, deadline=None, database=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])
@given(text=user_case(kinds=("hertz", "dissimilar", "partial_slip", "sliding")))
def test_a_correct_table_passes_where_its_code_passes(text, tmp_path_factory):
    tmp = tmp_path_factory.mktemp("case")
    (tmp / "user.toml").write_text(text)
    step = halfspace.solve(load_case(tmp / "user.toml")[0]).steps[-1]
    X, Y = np.meshgrid(step.x, step.y, indexing="ij")
    table = {"x": X.ravel(), "y": Y.ravel(), "z": np.zeros(X.size)}
    table |= {f: step.surface[f].ravel() for f in FIELDS}
    table |= {q: np.full(X.size, step.scalars[q]) for q in STATED}
    pd.DataFrame(table).to_csv(tmp / "bem.csv", index=False)
    number = step.number(0)
    (tmp / "user.toml").write_text(
        text + f'\n[external.bem]\nfiles = "bem.csv"\nsteps = [{number}]\n'
        + "scalars = { " + ", ".join(f'{q} = "{q}"' for q in STATED) + " }\n"
        + "[external.bem.fields]\n" + "".join(f'{f} = "{f}"\n' for f in FIELDS)
        + "[external.bem.budget]\n" + grid_budget_table() + "\n")
    out = tmp / "res"
    assert main(["run", str(tmp / "user.toml"), "--no-progress", "--solver",
                 "external:bem,ic,analytic", "--out", str(out)]) == 0
    m = pd.read_csv(out / "user" / "metrics.csv")
    m = m[m["quantity"].isin(ROWS)]
    ext = m[m["pair"] == "external:bem-analytic"].set_index(["step", "quantity", "metric"])
    ic = m[m["pair"] == "ic-analytic"].set_index(["step", "quantity", "metric"])
    assert len(ext) and set(ext.index) == set(ic.index), text
    both = ext.add_suffix("_ext").join(ic.add_suffix("_ic"))
    assert np.allclose(both["value_ext"], both["value_ic"], rtol=1e-9, atol=1e-12), text
    gated = both[both["status_ext"] == "gated"]
    wrong = gated[~gated["passed_ext"].astype(bool) & gated["passed_ic"].astype(bool)]
    assert wrong.empty, (text, wrong)
