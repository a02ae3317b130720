"""`contact-vv run --jump-study`: the fretting runs again at J/2 and J/4, the change when
the jump is halved, order and extrapolation per output cycle (reports/studies/jumpstudy.py)."""

from __future__ import annotations

import io
import json
import math
from dataclasses import replace

import pandas as pd
import pytest

import halfspace
from cases.loader import load_case
from reports.cli import main
from reports.compare.verdict import decide
from reports.render.gate import run_gate
from reports.render.pages import report_text
from reports.store import study_tables
from reports.store.readers import Malformed
from reports.studies import jumpstudy
from reports.studies.jumpstudy import JUMP_STUDY
from reports.studies.study import Levels, Own, StudyTable


def late(metrics: pd.DataFrame, table: pd.DataFrame) -> list:
    """The jump study's evidence on ``metrics`` from ``table``."""
    return JUMP_STUDY.evidence(metrics, StudyTable(table), Own([], [], lambda c: []))

BETA0 = ("--set", "friction.beta=0")  # quick fretting_orthotropic, gross slip, J = 500


def _w_max(jump: float, cycle: float) -> float:
    """w_max of the quick β = 0 point at ``cycle`` from the half-space solver run
    directly with the cycle jump ``jump``."""
    case = load_case("fretting_orthotropic", quick=True,
                     overrides={"friction.beta": 0.0, "fretting.jump": jump})[0]
    rows = halfspace.solve(case).summary_rows()
    return float(next(r["w_max"] for r in rows if math.isclose(r["cycle"], cycle)))


@pytest.fixture(scope="module")
def studied(tmp_path_factory):
    out = tmp_path_factory.mktemp("jump") / "res"
    assert main(["run", "fretting_orthotropic", "--quick", "--solver", "ic", "--no-progress",
                 "--jump-study", *BETA0, "--out", str(out)]) == 0
    return out / "fretting_orthotropic"


def test_the_table_holds_the_runs_at_j_j2_j4(studied):
    js = study_tables.read_jump_study(studied / "jump_study.csv")
    assert list(js.columns) == study_tables.JUMP_COLUMNS
    assert set(js["solver"]) == {"ic"} and set(js["cycle"]) == {1000.0, 2000.0}
    assert (js[["h1", "h2", "h3"]].to_numpy() == [125.0, 250.0, 500.0]).all()
    # f(J) is the run's own value: the study leaves the run's results unchanged
    summary = pd.read_csv(studied / "summary.csv", keep_default_na=False)
    assert summary.columns[-1] == jumpstudy.FLAG_COLUMN
    own = summary[summary["solver"] == "ic"].set_index("cycle")  # its relations aside
    w = js[js["quantity"] == "w_max"].set_index("cycle")
    for cycle in (1000.0, 2000.0):
        assert w.loc[cycle, "f3"] == own.loc[cycle, "w_max"]
        assert w.loc[cycle, "change_halved"] == pytest.approx(
            (w.loc[cycle, "f2"] - w.loc[cycle, "f3"]) / w.loc[cycle, "f3"], rel=1e-12)
    # f(J/2) is what the half-space solver gives when run at J/2 itself
    assert w.loc[2000.0, "f2"] == pytest.approx(_w_max(250.0, 2000.0), rel=1e-12)
    mf = json.loads((studied / "manifest.json").read_text())
    assert [u for u in mf["jump_study"]["units"] if u["solver"] == "ic"] == [
        {"solver": "ic", "param": "beta=0", "jumps": [500.0, 250.0, 125.0]}]
    assert all(u["not_studied"].startswith("a metamorphic relation")
               for u in mf["jump_study"]["units"] if u["solver"] != "ic")
    assert [(u.get("level"), u.get("jump")) for u in mf["units"] if u["solver"] == "ic"] == \
        [(None, None), (2, 250.0), (3, 125.0)]
    assert "jump_study.csv" in mf["files"]


def test_the_cycle_jump_converges_at_first_order(studied):
    """The jump is an explicit (forward) integration of the wear history: halving J
    halves the error of w_max (order 1, measured 0.995 at 2000 cycles), and the power
    law fitted to J/4, J/2, J predicts an independent run at J/8 to within a tenth of
    what J/8 changes from J/4 (measured: 1e-7 mm of 5.8e-6 mm)."""
    w = study_tables.read_jump_study(studied / "jump_study.csv")
    row = w[(w["quantity"] == "w_max") & (w["cycle"] == 2000.0)].iloc[0]
    print(f"w_max at 2000 cycles: {row['f1']:.6g} {row['f2']:.6g} {row['f3']:.6g}, "
          f"order {row['order']:.4f}, change when halved {row['change_halved']:.4%}")
    assert row["status"] == "converged"
    assert row["order"] == pytest.approx(1.0, abs=0.05)
    w8 = _w_max(62.5, 2000.0)
    predicted = row["f_extrapolated"] - (row["f_extrapolated"] - row["f1"]) / 2 ** row["order"]
    print(f"J/8: {w8:.6g}, predicted {predicted:.6g}")
    assert abs(predicted - w8) < 0.1 * abs(w8 - row["f1"])


def test_report_and_gate(studied):
    out = studied.parent
    stream = io.StringIO()
    assert run_gate(out, stream=stream) == 0
    assert "UNSETTLED (jump)" not in stream.getvalue()  # gross slip: all converged
    assert main(["report", "--out", str(out)]) == 0
    html = report_text(out)
    sec = html.split('id="jump-fretting_orthotropic"')[1].split("</div>")[0]
    assert "Cycle-jump convergence" in sec and "halving J [%]" in sec
    n = len(study_tables.read_jump_study(studied / "jump_study.csv"))
    assert f"{n} / {n} quantities converged or exact" in sec


def test_a_damaged_table_is_refused(studied, tmp_path):
    bad = tmp_path / "jump_study.csv"
    bad.write_text((studied / "jump_study.csv").read_text().replace("converged", "fine", 1))
    with pytest.raises(Malformed, match="column 'status' holds 'fine'"):
        study_tables.read_jump_study(bad)


def test_not_converged_in_j_is_flagged_not_gated(studied):
    """A metric whose study (either solver) is unsettled and spreads by more than the
    budget is not gated, with the three jumps and values in its note."""
    js = study_tables.read_jump_study(studied / "jump_study.csv")
    row = js[(js["quantity"] == "w_max") & (js["cycle"] == 2000.0)].iloc[[0]].copy()
    row["status"], row["f1"] = "unsettled", 2 * row["f3"].iloc[0]
    metrics = pd.DataFrame([{"param": "beta=0", "step": int(row["step"].iloc[0]),
                             "pair": "ic-fem", "quantity": "w_max", "metric": "rel",
                             "value": 0.01, "tolerance": 0.1, "status": "gated",
                             "note": ""}])
    flagged = decide(metrics, late(metrics, row))
    assert flagged["status"].iat[0] == "not gated"
    assert flagged["note"].iat[0].startswith("jump study: ic unsettled, f = ")
    assert "on J = 125, 250, 500 cycles" in flagged["note"].iat[0]
    assert decide(metrics, late(metrics, js))["status"].iat[0] == "gated"


@pytest.mark.parametrize(("case", "needle"), [
    ("hertz", "hertz: a static case has no cycle jump"),
    ("fretting_isotropic", "fretting.jump = 1: every cycle is simulated"),
])
def test_no_cycle_jump_is_an_error(tmp_path, capsys, case, needle):
    assert main(["run", case, "--quick", "--solver", "ic", "--jump-study", "--no-progress",
                 "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert "--jump-study: no run has a cycle jump to halve" in err and needle in err
    assert not (tmp_path / case).exists()  # refused before any work


def test_a_failed_level_leaves_the_quantity_not_converged():
    """A run at J/2 or J/4 that fails (contact at the grid edge, no convergence) is no
    evidence: the rows say which level failed and why, and are unsettled."""
    from reports.run.plan import plan_case

    plan = plan_case("fretting_orthotropic", ["ic"], quick=True,
                     overrides={"friction.beta": 0.0}).with_study(JUMP_STUDY)
    runs = list(plan.planned(JUMP_STUDY).runs)
    assert [(g.level, g.case.fretting.jump) for g in runs] == [(2, 250.0), (3, 125.0)]
    own = [{"step": 2, "cycle": 1000.0, "w_max": 1e-3}, {"step": 4, "cycle": 2000.0,
                                                          "w_max": 2e-3}]
    half = [{**r, "w_max": 1.1 * r["w_max"]} for r in own]
    levels = Levels(rows={(0, "ic", 2): half}, errors={(0, "ic", 3): "failed: edge"})
    mine = replace(plan.own(), rows={(0, "ic"): own})
    table = JUMP_STUDY.table(mine, runs, levels).table.set_index("cycle")
    assert list(table["quantity"]) == ["w_max", "w_max"]
    assert table.loc[2000.0, "change_halved"] == pytest.approx(0.1, rel=1e-12)
    assert (table["status"] == "unsettled").all()
    assert (table["note"] == "J/4 failed (failed: edge)").all()
