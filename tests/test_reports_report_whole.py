"""A report that is whole or absent (issue 77, point 6): two ``report``s of one directory
at once write one after the other (the index links only pages that exist); a report
stopped before its pages are in place leaves the previous report as it was and ``gate``
passing; what a killed report left (``._report.partial``, ``._report.old-<pid>``) is the
report's own, never a case, and the next report removes it.  Found by these probes: the
next ``gate`` failed with "INCOMPLETE _report", and two reports at once left an index
linking case pages never written (1 of 3 present)."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest
from test_cli_hostile_inputs import TINY

from reports.cli import main
from reports.render import coverage, pages
from reports.store.results import scan

NAMES = ("c1", "c2", "c3")


@pytest.fixture(scope="module")
def results(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("whole") / "out"
    for name in NAMES:
        case = out.parent / f"{name}.toml"
        case.write_text(f'name = "{name}"\n' + TINY)
        assert main(["run", str(case), "--solver", "ic,analytic", "--no-progress", "--out",
                     str(out)]) == 0
    return out


def _links(out: Path) -> list[str]:
    return re.findall(r'href="(_report/[^"]+\.html)"', (out / "index.html").read_text())


def _whole(out: Path) -> None:
    links = _links(out)
    assert sorted(links) == sorted([*(f"_report/{n}.html" for n in NAMES),
                                    f"_report/{coverage.PAGE}"])
    assert all((out / link).is_file() for link in links)
    assert not list(out.glob("._report*"))


def test_two_reports_at_once_write_one_after_the_other(results):
    cli = [sys.executable, "-m", "reports", "report", str(results)]
    for _ in range(2):
        both = [subprocess.Popen(cli, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
                for _ in range(2)]
        errs = [p.communicate(timeout=600)[1] for p in both]
        assert [p.returncode for p in both] == [0, 0], errs
        _whole(results)


def test_a_report_stopped_before_its_pages_are_in_place(results, monkeypatch, capsys):
    assert main(["report", str(results)]) == 0
    capsys.readouterr()
    verdict = main(["gate", str(results)])  # (TINY's coarse grid fails some rows)
    said = capsys.readouterr().out
    before = {p: p.read_bytes() for p in [results / "index.html",
                                          *(results / "_report").rglob("*")] if p.is_file()}
    def killed(staging, final):
        staged = len(list(staging.glob("*.html")))
        assert staging.name == "._report.partial" and staged == len(NAMES) + 1  # coverage
        raise KeyboardInterrupt  # as a kill there would: the pages all staged

    monkeypatch.setattr(pages, "replace_dir", killed)
    assert main(["report", str(results)]) == 130
    monkeypatch.undo()
    assert (results / "._report.partial").is_dir()  # what a killed report leaves
    after = {p: p.read_bytes() for p in before}
    assert after == before
    (results / "._report.old-999999").mkdir()  # and a killed replacement's trash
    (results / "._report.old-999999" / "c1.html").write_text("<html></html>")
    capsys.readouterr()
    assert main(["gate", str(results)]) == verdict
    assert capsys.readouterr().out == said and "INCOMPLETE" not in said
    assert main(["report", str(results)]) == 0
    _whole(results)


def test_a_staging_folder_that_is_not_the_reports_is_kept(results, capsys):
    foreign = results / "._report.partial"
    foreign.mkdir()
    (foreign / "notes.txt").write_text("mine")
    try:
        assert main(["report", str(results)]) == 2
        assert "not a contact-vv report" in capsys.readouterr().err
        assert (foreign / "notes.txt").read_text() == "mine"
    finally:
        (foreign / "notes.txt").unlink()
        foreign.rmdir()


@pytest.mark.parametrize("swap", [True, False], ids=["exchange", "rename-away"])
def test_replace_dir_puts_the_new_folder_in_place(tmp_path, monkeypatch, swap):
    from reports.store import staging

    if not swap:
        monkeypatch.setattr(staging, "_exchange", lambda a, b: False)
    new, final = tmp_path / ".new", tmp_path / "final"
    for folder, text in ((new, "new"), (final, "old")):
        folder.mkdir()
        (folder / "page.html").write_text(text)
    staging.replace_dir(new, final)
    assert (final / "page.html").read_text() == "new"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["final"]


def test_the_exchange_swaps_in_one_step_where_the_system_can(tmp_path):
    from reports.store import staging

    a, b = tmp_path / "a", tmp_path / "b"
    a.mkdir(), b.mkdir()
    (a / "x").write_text("a")
    if not staging._exchange(a, b):
        pytest.skip("this file system cannot swap two paths (renameat2)")
    assert (b / "x").read_text() == "a" and not (a / "x").exists()


def test_pages_drawn_by_two_processes_are_those_drawn_by_one(results, tmp_path):
    """The case pages drawn by two forked processes (a CLI process has no other thread)
    are, byte for byte, those this process draws alone, figures included."""
    def files(out: Path) -> dict[str, bytes]:
        return {str(p.relative_to(out)): p.read_bytes()
                for p in [out / "index.html", *(out / "_report").rglob("*")] if p.is_file()}

    subprocess.run([sys.executable, "-m", "reports", "report", str(results), "--workers",
                    "2"], check=True, stdout=subprocess.DEVNULL, timeout=600)
    two = files(results)
    assert main(["report", str(results), "--workers", "1"]) == 0
    one = files(results)
    assert len([f for f in one if f.endswith(".png")]) >= 3 * len(NAMES)
    drop = re.compile(rb"generated [^<]*")  # the index's time of writing
    assert {k: drop.sub(b"", v) for k, v in two.items()} == \
        {k: drop.sub(b"", v) for k, v in one.items()}


def test_workers_below_one_is_refused(results, capsys):
    assert main(["report", str(results), "--workers", "0"]) == 2
    assert "--workers must be >= 1" in capsys.readouterr().err


def test_the_index_summarises_the_coverage_whose_page_holds_it_whole(results):
    """The index's coverage is one row per regime, its counts those of the full table,
    which is on its own page (issue 76, point 8)."""
    assert main(["report", str(results), "--workers", "1"]) == 0
    cov = coverage.table(scan(results))
    assert not cov.empty

    def section(page: Path) -> str:
        return re.search(r'<div class="coverage">(.*?)</div>', page.read_text(), re.S)[1]

    def cells(html: str) -> list[list[str]]:
        return [re.findall(r"<td[^>]*>([^<]*)</td>", r) for r in html.split("<tr")[2:]]

    index = cells(section(results / "index.html"))
    full = cells(section(results / "_report" / coverage.PAGE))
    regimes = list(dict.fromkeys(cov["regime"]))
    assert [r[0] for r in index] == regimes
    assert [sum(int(r[k]) for r in index) for k in (1, 2, 3, 4)] == [
        len(cov), len(coverage.holes(cov)), cov["rows"].sum(), cov["gated"].sum()]
    assert len(full) == len(coverage.pivot(cov)) >= len(index)
