"""Tolerances from the combined numerical uncertainty of grid studies (reports.studies.uncertainty):
each kind of study gives its documented u, the terms combine in quadrature (Eq. U1), and
the result can only tighten a tolerance."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from reports.compare.verdict import EXTRA_COLUMNS, METRICS_COLUMNS, Uncertainty, decide
from reports.registry import solvers
from reports.registry import tolerances as tol
from reports.studies import three_level, uncertainty

H = (0.01, 0.015, 0.0225)


def study_row(solver: str, quantity: str, f: tuple[float, float, float],
              param: str = "", step: int = 0) -> dict:
    """A convergence-table row as reports.studies.gridstudy writes it, from three values."""
    st = three_level.study(f, H)
    status, _ = three_level.classify(st)
    gci = 0.0 if status == three_level.EXACT else st.gci_fine
    return {"solver": solver, "param": param, "step": step, "quantity": quantity,
            "h1": H[0], "h2": H[1], "h3": H[2], "f1": f[0], "f2": f[1], "f3": f[2],
            "order": st.p, "f_extrapolated": st.f_ext, "gci_fine": gci, "status": status,
            "gci_coarse": st.gci_coarse, "asymptotic": st.asymptotic, "note": ""}


def metric_row(pair: str, quantity: str, value: float, tolerance: float,
               key: str | None = None, metric: str = "rel") -> dict:
    key = key or f"default:{quantity}"
    return {"quantity": quantity, "pair": pair, "metric": metric, "value": value,
            "tolerance": tolerance, "passed": True, "case": "c", "param": "", "step": 0,
            "s": math.nan, "cycle": math.nan, "tolerance_key": key, "status": "gated",
            "note": "", "tolerance_kind": tol.kind_of(key), "budget": tolerance,
            "uncertainty": math.nan}


def metrics(*rows: dict) -> pd.DataFrame:
    columns = METRICS_COLUMNS + EXTRA_COLUMNS + tol.TOLERANCE_COLUMNS
    return decide(pd.DataFrame.from_records(rows, columns=columns))


def apply(m: pd.DataFrame, frame: pd.DataFrame) -> pd.DataFrame:
    """The verdict on ``m`` with the combined uncertainty of the grid studies ``frame``."""
    u = uncertainty.values(m, frame)
    return decide(m, [] if u is None else [Uncertainty(u)])


def order_two(f0: float, c: float) -> tuple[float, float, float]:
    return tuple(f0 * (1 + c * h**2 / H[0] ** 2) for h in H)


def test_each_study_status_gives_its_documented_uncertainty():
    conv = study_row("ic", "p_max", order_two(100.0, 0.004))  # exact order 2
    assert conv["status"] == "converged"
    # Richardson is exact for a pure power: the GCI is 1.25 times the true error of f1
    assert uncertainty.solver_uncertainty(pd.Series(conv)) == pytest.approx(
        1.25 * 0.004 / 1.004, rel=1e-9)
    exact = study_row("ic", "P", (10.2, 10.2, 10.2))
    assert uncertainty.solver_uncertainty(pd.Series(exact)) == 0.0
    osc = study_row("ic", "vm_max", (100.0, 100.4, 99.9))
    assert osc["status"] == "oscillating"
    assert uncertainty.solver_uncertainty(pd.Series(osc)) == pytest.approx(3 * 0.5 / 100.0)
    grow = study_row("ic", "vm_max", (1.0, 0.9, 0.85))  # differences grow: no number
    assert grow["status"] == "unsettled"
    assert math.isnan(uncertainty.solver_uncertainty(pd.Series(grow)))
    assert math.isnan(uncertainty.solver_uncertainty(None))


def test_combined_uncertainty_sets_the_tolerance_only_where_it_is_tighter():
    ic = study_row("ic", "p_max", order_two(100.0, 0.004))
    fem = study_row("fem", "p_max", order_two(100.2, -0.003))
    frame = pd.DataFrame([ic, fem, study_row("ic", "vm_max", (1.0, 0.9, 0.85))])
    m = metrics(metric_row("ic-analytic", "p_max", 0.004, 0.035),
                metric_row("ic-fem", "p_max", 0.002, 0.06),
                metric_row("ic-fem", "vm_max", 0.01, 0.04),  # not converged in ic
                metric_row("ic-fem", "p_n", 0.01, 0.1, metric="l2"),  # a field norm
                metric_row("ic-analytic", "p_max", 0.004, 0.001, key="ic-analytic.p_max"))
    out = apply(m, frame)
    u_ic, u_fem = 1.25 * 0.004 / 1.004, 1.25 * 0.003 / 0.997
    want_a = math.hypot(u_ic, solvers.closed_form_budget("p_max", "rel"))
    want_f = math.sqrt(u_ic**2 + u_fem**2 + solvers.fem_model_form("p_max", "rel") ** 2)
    assert out["uncertainty"].iloc[:2].to_numpy() == pytest.approx([want_a, want_f],
                                                                   rel=1e-9)
    assert out["tolerance"].iloc[:2].to_numpy() == pytest.approx([want_a, want_f], rel=1e-9)
    assert list(out["tolerance_kind"]) == ["uncertainty", "uncertainty", "budget", "budget",
                                           "case"]
    assert list(out["budget"]) == [0.035, 0.06, 0.04, 0.1, 0.001]
    assert np.isnan(out["uncertainty"].iloc[2:4]).all()
    # a case key tighter than U stays (U never widens), with U shown beside it
    assert out["tolerance"].iloc[4] == 0.001
    assert out["uncertainty"].iloc[4] == pytest.approx(want_a, rel=1e-9)
    assert not out["passed"].iloc[4]


def test_a_defect_inside_the_budget_fails_against_the_uncertainty():
    """A solver 1 % off on every grid has the same differences between its grids as a
    correct one: its GCI is the correct one's, and the error is judged against it."""
    frame = pd.DataFrame([study_row("ic", "p_max", order_two(101.0, 0.0008))])
    right = 0.0008 / 1.0008
    wrong = (101.0 * 1.0008 - 100.0) / 100.0
    out = apply(metrics(metric_row("ic-analytic", "p_max", right, 0.035),
                                    metric_row("ic-analytic", "p_max", wrong, 0.035)), frame)
    assert list(out["passed"]) == [True, False]
    assert (out["budget"] > [right, wrong]).all()  # the budget would have passed both


def test_unmeasured_model_form_and_ungated_rows_keep_their_tolerance():
    frame = pd.DataFrame([study_row("ic", "w_max", order_two(1e-3, 0.002)),
                          study_row("fem", "w_max", order_two(1e-3, 0.003))])
    m = metrics(metric_row("ic-fem", "w_max", 0.001, 0.08))
    m.loc[0, "status"] = "not gated"
    out = apply(m, frame)
    assert math.isnan(out["uncertainty"].iloc[0])  # ungated: no tolerance to set
    out = apply(metrics(metric_row("ic-fem", "w_max", 0.001, 0.08)), frame)
    # the FEM's block term is not measured for wear: no U, the budget stays
    assert math.isnan(solvers.fem_model_form("w_max", "rel"))
    assert out["tolerance_kind"].iloc[0] == "budget" and out["tolerance"].iloc[0] == 0.08


def test_metrics_without_the_new_columns_read_as_budget_or_case():
    old = metrics(metric_row("ic-fem", "p_max", 0.001, 0.06),
                  metric_row("ic-fem", "p_max", 0.001, 0.05, key="p_max"))
    old = old.drop(columns=["tolerance_kind", "budget", "uncertainty"])
    got = tol.with_tolerance_columns(old)
    assert list(got["tolerance_kind"]) == ["budget", "case"]
    assert list(got["budget"]) == [0.06, 0.05] and got["uncertainty"].isna().all()


def test_read_metrics_refuses_an_unknown_tolerance_kind(tmp_path):
    from reports.store.readers import Malformed, read_metrics

    m = metrics(metric_row("ic-fem", "p_max", 0.001, 0.06))
    path = tmp_path / "metrics.csv"
    m.to_csv(path, index=False)
    assert read_metrics(path)["tolerance_kind"].iloc[0] == "budget"
    m.assign(tolerance_kind="guess").to_csv(path, index=False)
    with pytest.raises(Malformed, match="column 'tolerance_kind' holds 'guess'"):
        read_metrics(path)


def test_an_asymptotic_closed_form_states_its_deficit():
    """Argatov's worn-pin depth is an asymptotic limit: the half-space solver's depth,
    converged in space (41², 81², 121² agree to 0.03 %), is 1.3 % below it at 14
    transition distances (benchmarks/README.md).  The combined uncertainty carries the
    closed form's case term, so the converged solver passes; a solver 4 % off fails."""
    from cases.loader import load_case

    case = load_case("pin_on_disk", quick=True)[0]
    frame = pd.DataFrame([study_row("ic", "w_max", (1.6405e-3, 1.6402e-3, 1.6423e-3))])
    rows = metrics(metric_row("ic-analytic", "w_max", 0.013, 0.035),
                   metric_row("ic-analytic", "w_max", 0.040, 0.035))
    stated = decide(rows, [Uncertainty(uncertainty.values(rows, frame, {"": case}))])
    assert list(stated["passed"]) == [True, False]
    assert (stated["uncertainty"] >= solvers.ARGATOV_W_MAX).all()
    bare = apply(rows, frame)  # without the case: the closed form's sampling budget only
    assert list(bare["passed"]) == [False, False]


def test_the_worn_pin_passes_its_grid_study(tmp_path, capsys):
    """End to end: the quick worn pin through ic and the closed forms with
    ``--convergence`` passes the gate (it failed its w_max rows before the case term)."""
    from reports.cli import main

    out = tmp_path / "res"
    assert main(["run", "pin_on_disk", "--quick", "--solver", "ic,analytic",
                 "--convergence", "--no-progress", "--out", str(out)]) == 0
    m = pd.read_csv(out / "pin_on_disk" / "metrics.csv")
    depth = m[(m["pair"] == "ic-analytic") & (m["quantity"] == "w_max")]
    assert len(depth) and (depth["tolerance_kind"] == "uncertainty").all()
    assert main(["gate", "--out", str(out)]) == 0
