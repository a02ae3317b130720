"""Fretting with the normal load held (cases/examples/fretting_orthotropic_load.toml) and
the early estimate of the worn contact's size (cases.model.Case.worn_radius_estimate,
reports.run.plan.grid_warning)."""

from __future__ import annotations

import math
from pathlib import Path

import pandas as pd
import pytest

from cases.loader import load_case
from reports.cli import main
from reports.run.plan import grid_warning, plan_case

EXAMPLE = Path(__file__).resolve().parent.parent / "cases" / "examples" / \
    "fretting_orthotropic_load.toml"


def test_the_held_approach_estimate_is_the_rigid_overlap():
    for case in load_case("fretting_orthotropic"):
        assert case.worn_radius_estimate == pytest.approx(
            math.sqrt(2 * case.R * case.load.approach), rel=1e-15)
        assert grid_warning(case) is None  # the bundled 2 mm grid holds the overlap


def test_the_grid_warning_comes_before_any_work(tmp_path, capsys):
    """On a 5 mm grid the held-load sweep may outgrow the grid from β = 30 on (measured:
    β = 60 reaches the edge near 1e5 cycles, β = 0 stays at r = 2.0 mm); the warning
    names each point and the grid that keeps the estimate inside.  The 8 mm grid of the
    example is quiet.  (ic alone also gets its exact mirror relation, with a warning of
    its own.)"""
    def grid_warnings(plan):
        return [w for w in plan.warnings if "no other solver compares" not in w]

    assert grid_warnings(plan_case(EXAMPLE, ["ic"])) == []
    small = {"grid.Lx": 5.0, "grid.Ly": 5.0, "grid.nx": 61, "grid.ny": 61}
    warned = grid_warnings(plan_case(EXAMPLE, ["ic"], overrides=small))
    assert [w.split(":")[0] for w in warned] == [
        f"fretting_orthotropic_load [beta={b}]" for b in (30, 60, 70, 80, 90)]
    assert "may reach r = 3.08 mm by cycle 100000" in warned[1]
    assert "grid.Lx = grid.Ly = 6.48 mm keeps it inside" in warned[1]
    # printed by `run` before the runs: a 2 mm grid against r = 1.01 mm at 1000 cycles
    # (the contact measures 0.74 mm there, so the run completes)
    sets = ["--set", "grid.Lx=2", "--set", "grid.Ly=2", "--set", "grid.nx=21", "--set",
            "grid.ny=21", "--set", "friction.beta=60", "--set", "fretting.cycles=1000",
            "--set", "fretting.output_cycles=[1000]"]
    assert main(["run", str(EXAMPLE), "--solver", "ic", *sets, "--no-progress", "--out",
                 str(tmp_path)]) == 0
    err = capsys.readouterr().err
    assert err.startswith("contact-vv: warning: fretting_orthotropic_load [beta=60]: grid.Lx "
                          "x grid.Ly = 2 x 2 mm: ") and "may reach r = 1.01 mm" in err


def test_the_held_load_runs_and_the_estimate_holds_in_gross_slip(tmp_path):
    """The quick example through the half-space solver: P stays 778.41 N; in gross slip
    (β = 0) the semi-width a_x of the worn contact at 2000 cycles is the Archard estimate
    to within one cell (the grid's quantisation of a_x; measured 0.823 against 0.831 mm);
    with a stick zone (β = 90) it is smaller (0.823 against 1.22 mm)."""
    out = tmp_path / "res"
    assert main(["run", str(EXAMPLE), "--quick", "--solver", "ic", "--no-progress",
                 "--out", str(out)]) == 0
    summary = pd.read_csv(out / "fretting_orthotropic_load" / "summary.csv")
    cases = {c.param: c for c in load_case(EXAMPLE, quick=True)}
    last = summary[(summary["cycle"] == 2000) & (summary["solver"] == "ic")].set_index("param")
    assert last["P"].to_numpy() == pytest.approx(778.41, rel=1e-9)
    est = {p: c.worn_radius_estimate for p, c in cases.items()}
    dx = cases["beta=0"].grid.dx
    print(f"a_x at 2000 cycles: {last['a_x'].to_dict()}, estimate {est}, cell {dx:.4g}")
    assert last.loc["beta=0", "stick_area"] == 0.0
    assert abs(last.loc["beta=0", "a_x"] - est["beta=0"]) <= dx
    assert last.loc["beta=90", "stick_area"] > 0.0
    assert last.loc["beta=90", "a_x"] < est["beta=90"] - dx
