"""A study is one base class (reports.studies.study.Study): a fourth study, registered by one line
in reports.studies.registry.STUDIES, runs, writes its table, adds its summary column,
folds its evidence into the verdict, records its manifest entry, speaks in the gate and
is read back by name, with no other file touched; a study implements only what it does
(the base's defaults for the rest); the three bundled studies keep their order whatever
order a run asks for them in."""

from __future__ import annotations

from typing import Any

import pandas as pd
import pytest
import test_cli_fakes as fakes
from test_cli_run import HERTZ, write_case

from reports.cli import main
from reports.compare.verdict import Evidence, Flags
from reports.run.plan import plan_case, request_study
from reports.store.results import read_case
from reports.studies import registry
from reports.studies.study import Check, Levels, Own, Study, StudyRun, StudyTable


class Repeat(Study):
    """A trivial study: every ``ic`` unit runs once more, unchanged; its table holds the
    change of P between the two runs (zero for a deterministic solver), and its evidence
    drops the P rows of the pairs with ``ic`` (to see the fold)."""

    name, label = "repeat", "repeat"

    def plan(self, own: Own, check: Check) -> list[StudyRun]:
        runs = [StudyRun(i, s, 0, own.points[i]) for i, s in own.units if s == "ic"]
        for r in runs:
            check(r.case, r.solver)
        return runs

    def describe(self, run: StudyRun) -> dict[str, Any]:
        return {"study": self.label}

    def table(self, own: Own, runs: list[StudyRun], levels: Levels) -> StudyTable:
        rows = []
        for g in runs:
            again = levels.rows[(g.point, g.solver, g.level)]
            for first, second in zip(own.rows[(g.point, g.solver)], again, strict=True):
                rows.append({"param": own.points[g.point].param, "step": first["step"],
                             "change": second["P"] - first["P"]})
        return StudyTable(pd.DataFrame(rows, columns=["param", "step", "change"]))

    def summary(self, summary: pd.DataFrame, table: pd.DataFrame) -> pd.DataFrame:
        return summary.assign(repeat_seen=len(table))

    def evidence(self, rows: pd.DataFrame, table: StudyTable, own: Own) -> list[Evidence]:
        on = [k for k in range(len(rows))
              if rows["quantity"].iat[k] == "P" and "ic" in str(rows["pair"].iat[k]).split("-")]
        return [Flags(dropped={k: ["repeat study: dropped"] for k in on})]

    def manifest(self, own: Own, runs: list[StudyRun]) -> dict[str, Any]:
        return {"runs": len(runs)}

    def notes(self, case: str, table: pd.DataFrame) -> list[str]:
        return [f"REPEAT {case}: {len(table)} row(s), largest change "
                f"{table['change'].abs().max():g}"]

    def nothing_planned(self, owns: list[Own]) -> str:
        return "no ic run"


class Bare(Study):
    """A study with only the four methods the base leaves to it: no runs, an empty table,
    no evidence."""

    name, label = "bare", "bare"

    def plan(self, own: Own, check: Check) -> list[StudyRun]:
        return []

    def table(self, own: Own, runs: list[StudyRun], levels: Levels) -> StudyTable:
        return StudyTable(pd.DataFrame())

    def evidence(self, rows: pd.DataFrame, table: StudyTable, own: Own) -> list[Evidence]:
        return []

    def nothing_planned(self, owns: list[Own]) -> str:
        return "nothing to do"


@pytest.fixture
def fourth():
    """The study registered by one line in the list, as a new module would be (the list
    itself, which every module that imported it sees)."""
    study = Repeat()
    registry.STUDIES.append(study)
    try:
        yield study
    finally:
        registry.STUDIES.remove(study)


def test_a_fourth_study_is_one_module_and_one_line(tmp_path, monkeypatch, fourth, capsys):
    import reports.render.gate  # noqa: F401  imported before the run, as in a long session

    fakes.use(monkeypatch, ic="solve_ic", analytic="solve_exact")
    out = tmp_path / "res"
    case = write_case(tmp_path, HERTZ, "static")
    for _ in range(2):  # the second run replaces the first: its table is the run's own
        assert main(["run", "--no-progress", str(case), "--out", str(out)]) == 0
    folder = out / "static"
    table = pd.read_csv(folder / "repeat.csv")
    assert len(table) == 1 and (table["change"] == 0.0).all()  # the fake is deterministic
    result = read_case(folder)
    pd.testing.assert_frame_equal(result.study("repeat"), table, check_dtype=False)
    assert result.manifest["repeat"] == {"runs": 1}
    assert [u.get("study") for u in result.manifest["units"]] == [None, None, "repeat"]
    assert (result.summary["repeat_seen"] == 1).all()
    m = result.metrics
    p_rows = m[(m["quantity"] == "P") & (m["pair"] == "ic-analytic")]
    assert len(p_rows) > 0 and (p_rows["status"] == "not gated").all()
    assert p_rows["note"].str.contains("repeat study: dropped").all()
    others = m[(m["quantity"] != "P") & (m["pair"] == "ic-analytic")]
    assert (others["status"] == "gated").any()
    capsys.readouterr()
    main(["gate", str(out), "--verbose"])
    assert "REPEAT static: 1 row(s), largest change 0" in capsys.readouterr().out


def test_the_studies_keep_the_registrys_order():
    """The verdict folds the studies in the registry's order, so the order a run asks for
    them in changes nothing."""
    plan = plan_case("fretting_orthotropic", ["ic"], quick=True)
    a, _ = request_study([plan], "jump_study")
    a, _ = request_study(a, "convergence")
    b, _ = request_study([plan], "convergence")
    b, _ = request_study(b, "jump_study")
    names = [p.study.name for p in a[0].studies]
    assert names == [p.study.name for p in b[0].studies] == ["convergence", "jump_study"]
    assert a[0].study_runs() == b[0].study_runs()


def test_a_study_implements_only_what_it_does():
    """The base's defaults: no manifest keys per run, summary unchanged, no manifest
    entry, no gate notes, no idle note, asked for by no flag; a study that leaves out one
    of the four methods it must implement cannot be made."""
    study = Bare()
    summary = pd.DataFrame({"step": [0, 1]})
    own = Own(points=[], units=[], applicable=lambda case: [])
    assert study.describe(StudyRun(0, "ic", 0, None)) == {}
    assert study.summary(summary, pd.DataFrame()) is summary
    assert study.manifest(own, []) is None
    assert study.notes("c", pd.DataFrame()) == []
    assert study.idle_note(own) is None
    assert (study.option, study.keeps_results, study.table_without_runs) == (None, False, False)

    class NoEvidence(Study):
        name, label = "partial", "partial"
        plan, table, nothing_planned = Bare.plan, Bare.table, Bare.nothing_planned

    with pytest.raises(TypeError, match="evidence"):
        NoEvidence()
