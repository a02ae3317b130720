"""Hostile ``gate --junit`` and ``report DIR`` arguments (issue 59, point 5): each is
refused with one error line naming the argument (exit 2) before anything is written, or
does what it says; nothing in the results directory is replaced.  Found by these probes:
``--junit`` naming a result file wrote the JUnit XML over it (the case then read as
damaged)."""

from __future__ import annotations

from pathlib import Path

import pytest
from test_cli_hostile_inputs import TINY, _answer

from reports.cli import main


@pytest.fixture(scope="module")
def results(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("hg") / "out"
    case = out.parent / "t.toml"
    case.write_text(TINY)
    assert main(["run", str(case), "--solver", "ic,analytic", "--no-progress", "--out",
                 str(out)]) == 0
    return out


def _files(out: Path) -> dict[Path, bytes]:
    return {p: p.read_bytes() for p in out.rglob("*") if p.is_file()}


# (id, the --junit path (from the results directory out and a scratch folder tmp),
#  the needle of the error line)
JUNIT = [
    ("over-a-result-file", "{out}/t/summary.csv", "lies in a case directory"),
    ("new-file-in-a-case", "{out}/t/junit.xml", "lies in a case directory"),
    ("hidden-in-results", "{out}/.t.lock", "lies in a case directory"),
    ("a-directory", "{tmp}", "is a directory"),
    ("empty", "", "--junit .: is a directory"),
    ("not-a-junit-file", "{tmp}/notes.txt", "not a JUnit report"),
    ("a-system-file", "/proc/version", "not a JUnit report"),
]


@pytest.mark.parametrize(("target", "needle"), [j[1:] for j in JUNIT],
                         ids=[j[0] for j in JUNIT])
def test_a_junit_path_that_would_replace_something_is_refused(results, tmp_path, capsys,
                                                              target, needle):
    (tmp_path / "notes.txt").write_text("mine")
    before, notes = _files(results), (tmp_path / "notes.txt").read_bytes()
    path = target.format(out=results, tmp=tmp_path)
    code, err = _answer(["gate", "--out", str(results), "--junit", path], capsys)
    assert code == 2, err
    lines = [x for x in err.splitlines() if x.startswith("contact-vv: error:")]
    assert len(lines) == 1 and needle in lines[0], err
    assert _files(results) == before
    assert (tmp_path / "notes.txt").read_bytes() == notes


def test_a_junit_report_is_written_and_replaced(results, tmp_path, capsys):
    """A new file (its folders made) and an earlier JUnit report are written; the
    verdict's exit status is the gate's."""
    before = _files(results)
    path = tmp_path / "ci" / "reports" / "junit.xml"
    code, _ = _answer(["gate", "--out", str(results), "--junit", str(path)], capsys)
    assert code in (0, 1) and path.read_text().startswith("<?xml")
    again, _ = _answer(["gate", "--out", str(results), "--junit", str(path)], capsys)
    assert again == code and "<testsuites" in path.read_text()
    assert _files(results) == before


@pytest.mark.parametrize(("argv", "needle"), [
    (["report", "{out}/t"], "is a case directory, not a results directory"),
    (["gate", "{out}/t"], "is a case directory, not a results directory"),
    (["report", "{out}/t/summary.csv"], "is a file, not a directory"),
    (["gate", "--out", "{out}/t/summary.csv"], "is a file, not a directory"),
], ids=["report-a-case", "gate-a-case", "report-a-file", "gate-a-file"])
def test_report_and_gate_of_the_wrong_directory(results, capsys, argv, needle):
    before = _files(results)
    code, err = _answer([a.format(out=results) for a in argv], capsys)
    assert code == 2 and needle in err, err
    assert _files(results) == before
