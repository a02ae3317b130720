"""What ``contact-vv gate`` prints and writes (reports/render/gate.py, reports/render/junit.py):
the verdict first, a failure in the first lines, one line per case, every row with
``--verbose``; JUnit XML read back by a JUnit reader (junitparser) with one test case
per metric row, its failures and skips those of metrics.csv; the results directory as
the positional argument of ``gate`` and ``report``."""

from __future__ import annotations

import pandas as pd
import pytest
from junitparser import Failure, JUnitXml, Skipped

from reports.cli import main
from reports.store import layout


def _run(out, *extra: str) -> None:
    assert main(["run", "hertz", "cattaneo_mindlin", "--quick", "--solver", "ic,analytic",
                 "--no-progress", "--out", str(out), *extra]) == 0


@pytest.fixture(scope="module")
def green(tmp_path_factory):
    out = tmp_path_factory.mktemp("gate") / "res"
    _run(out)
    return out


@pytest.fixture(scope="module")
def failing(tmp_path_factory):
    """The same runs with the peak pressure's tolerance far below its error."""
    out = tmp_path_factory.mktemp("gate") / "res"
    _run(out, "--set", "tolerances.p_max=1e-9")
    return out


def _metrics(out) -> pd.DataFrame:
    return pd.concat([pd.read_csv(out / c / layout.METRICS) for c in ("hertz", "cattaneo_mindlin")],
                     ignore_index=True)


def test_a_green_gate_is_short(green, capsys):
    assert main(["gate", str(green)]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].startswith("gate: 2 case(s), ") and lines[0].endswith("PASSED")
    assert len(lines) <= 2 + 2 + 2  # the verdict, a line per case, the notes' hint
    assert sorted(x.split(":")[0].strip() for x in lines[1:3]) == ["cattaneo_mindlin", "hertz"]


def test_a_failure_comes_first(failing, capsys):
    assert main(["gate", str(failing)]) == 1
    out = capsys.readouterr().out.splitlines()
    assert out[0].endswith("FAILED")
    fails = [k for k, x in enumerate(out) if x.startswith("FAIL ")]
    assert fails and max(fails) < 10
    assert any("p_max rel" in out[k] and "tolerance 1e-09" in out[k] for k in fails)


def test_verbose_prints_every_row(green, capsys):
    assert main(["gate", str(green), "--verbose"]) == 0
    out = capsys.readouterr().out
    m = _metrics(green)
    assert len(out.splitlines()) > len(m)  # the table, one line a row, and the notes
    assert "NOT GATED" in out or (m["status"] == "gated").all()


def test_junit_is_read_back_with_the_rows_of_metrics(failing, tmp_path, capsys):
    path = tmp_path / "gate.xml"
    assert main(["gate", str(failing), "--junit", str(path)]) == 1
    assert f"junit: {path}" in capsys.readouterr().out
    xml = JUnitXml.fromfile(str(path))
    suites = {s.name: s for s in xml}
    assert set(suites) == {"hertz", "cattaneo_mindlin"}
    m = _metrics(failing)
    gated = m["status"] == "gated"
    cases = [c for s in xml for c in s]
    assert len(cases) == len(m) == xml.tests
    failed = [c for c in cases if any(isinstance(r, Failure) for r in c.result)]
    skipped = [c for c in cases if any(isinstance(r, Skipped) for r in c.result)]
    assert len(failed) == int((gated & ~m["passed"].astype(bool)).sum()) >= 1
    assert len(skipped) == int((~gated).sum())
    assert all("p_max rel" in c.name for c in failed)
    assert "> tolerance 1e-09" in failed[0].result[0].message


def test_the_results_directory_is_the_positional_argument(green, tmp_path, capsys):
    assert main(["report", str(green)]) == 0
    assert (green / "index.html").exists()
    assert main(["gate", str(green), "--out", str(tmp_path)]) == 2
    assert "name two results directories" in capsys.readouterr().err
