"""``contact-vv report``: the report in pages.

- ``DIR/index.html``: the verdict first, then the gate's problems (failures first), then
  one row per case with its counts and a link to its page, failing cases first; the
  thresholds table; the gate's coverage by regime (:mod:`reports.render.coverage`).  No
  image: it stays small whatever the results hold.
- ``DIR/_report/_coverage.html``: the coverage's full table.
- ``DIR/_report/<case>.html``: one page per case, the section of
  :func:`reports.render.html.case_section`; its figures are PNG files beside it,
  ``DIR/_report/<case>/fig_NNN.png``, loaded lazily.

The pages come from Jinja2 templates (``reports/render/templates``).  ``_report`` cannot
be a case's directory (a case name starts with a letter or digit).  A report holds the
OS lock of ``DIR/._report.lock`` from start to end, so two reports of one directory
write one after the other.  The pages are written into the staging directory
``DIR/._report.partial`` (the report's own: never a case to ``gate``; what a killed
report left there, and its ``._report.old-<pid>``, the next report removes), renamed
onto ``_report``, and the index is then replaced atomically: a report killed before that
rename leaves the previous report as it was.  An existing ``_report`` is replaced only
if it holds nothing but pages and figures, and ``index.html`` only if it is a report
(its title).
"""

from __future__ import annotations

import base64
import multiprocessing
import re
import shutil
import sys
import threading
from collections.abc import Iterator
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass
from pathlib import Path

import jinja2

from cases.result import atomic_write_text
from reports.registry.errors import UserError
from reports.render import coverage
from reports.render.gate import metrics_table, problems
from reports.render.html import case_section
from reports.render.html_blocks import CSS
from reports.render.html_sections import thresholds_html
from reports.render.threshold_gate import threshold_gate
from reports.store import layout
from reports.store.readers import gated
from reports.store.results import CaseResults, Scan, not_converged, scan
from reports.store.staging import held, replace_dir
from reports.studies import gridstudy
from reports.studies.gridstudy import GRID_STUDY
from reports.studies.jumpstudy import JUMP_STUDY

PAGES = layout.REPORT_PAGES  # the case pages' directory under DIR
_STAGING = f".{PAGES}.partial"
_STAGING_OLD = f".{PAGES}.old-"  # replaced pages on their way out (staging.remove_dir)
#: the title every report index has: an ``index.html`` without it is not one (kept)
TITLE = "<title>contact-vv report</title>"
_DATA_URI = re.compile(r'<img alt="([^"]*)" src="data:image/png;base64,([^"]+)">')
_ENV = jinja2.Environment(loader=jinja2.PackageLoader("reports.render", "templates"),
                          autoescape=jinja2.select_autoescape(["j2"]))


@dataclass(frozen=True)
class CaseRow:
    """A case's row in the index."""

    name: str
    href: str
    failed: int
    passed: int
    gated: int
    not_gated: int
    not_converged: int
    unsettled: str
    not_run: str

    @property
    def cls(self) -> str:
        return "fail" if self.failed or self.not_converged else "pass"


def case_row(case: CaseResults) -> CaseRow:
    m = case.metrics
    on = gated(m)
    n_on = int(on.sum())
    n_ok = int((on & m["passed"].astype(bool)).sum()) if n_on else 0
    unsettled = [f"{len(gridstudy.unsettled(t))} {what}"
                 for t, what in ((case.study(GRID_STUDY.name), "unsettled on the grids"),
                                 (case.study(JUMP_STUDY.name),
                                  "unsettled in the cycle jump"))
                 if len(gridstudy.unsettled(t))]
    return CaseRow(case.name, f"{PAGES}/{case.name}.html", n_on - n_ok, n_ok, n_on,
                   len(m) - n_on, len(not_converged(case.summary)), ", ".join(unsettled),
                   ", ".join(case.not_run))


def externalise(page: str, folder: Path, prefix: str) -> str:
    """``page`` with every inlined PNG written to ``folder/fig_NNN.png`` and referred to
    as ``prefix/fig_NNN.png``, loaded lazily."""
    count = 0

    def put(match: re.Match) -> str:
        nonlocal count
        count += 1
        name = f"fig_{count:03d}.png"
        folder.mkdir(parents=True, exist_ok=True)
        (folder / name).write_bytes(base64.b64decode(match.group(2)))
        return f'<img alt="{match.group(1)}" loading="lazy" src="{prefix}/{name}">'

    return _DATA_URI.sub(put, page)


def _ours(folder: Path) -> bool:
    """Whether ``folder`` holds only what this module writes (pages, figure folders)."""
    for entry in folder.iterdir():
        if entry.is_symlink():
            return False
        if entry.is_file() and entry.suffix == ".html":
            continue
        if entry.is_dir() and all(f.is_file() and not f.is_symlink()
                                  and re.fullmatch(r"fig_\d{3,}\.png", f.name)
                                  for f in entry.iterdir()):
            continue
        return False
    return True


def _replaceable(path: Path, what: str) -> None:
    """UserError if ``path`` exists and is not something a report wrote."""
    if not (path.exists() or path.is_symlink()):
        return
    if what == "index":
        ok = path.is_file() and not path.is_symlink()
        if ok:
            with open(path, "rb") as fh:
                ok = TITLE.encode() in fh.read(4096)
    else:
        ok = path.is_dir() and not path.is_symlink() and _ours(path)
    if not ok:
        raise UserError(f"{path} exists and is not a contact-vv report; refusing to "
                        "replace it (remove it or report another directory)")


def _section(case: CaseResults) -> str | tuple[str]:
    """The case's section, or (why,) when its files turn out to be damaged while drawn."""
    from reports.store.readers import DamagedResult

    try:
        return case_section(case)
    except DamagedResult as exc:
        return (str(exc),)


def _forkable() -> bool:
    """Whether a process may fork copies of itself here: on Linux, with no other thread
    (a copy of a process with threads may hold their locks)."""
    return sys.platform == "linux" and threading.active_count() == 1


def sections(cases: list[CaseResults], workers: int) -> Iterator[str | tuple[str]]:
    """:func:`_section` of every case, in order; drawn by ``workers`` forked copies of
    this process where it may fork (:func:`_forkable`), so each draws exactly as this
    one would (the same registry, styles and plugins), else here one after the other."""
    workers = min(workers, len(cases))
    if workers < 2 or not _forkable():
        yield from map(_section, cases)
        return
    pool = ProcessPoolExecutor(workers, mp_context=multiprocessing.get_context("fork"))
    try:
        yield from pool.map(_section, cases)
    finally:  # a report stopped here waits for no case it will not write
        pool.shutdown(cancel_futures=True)


@dataclass(frozen=True)
class Drawn:
    """What :func:`write_pages` drew: the index's rows, failing cases first, and its
    coverage section (:func:`reports.render.coverage.html`)."""

    rows: list[CaseRow]
    coverage: str


def write_pages(results: Scan, out: Path, workers: int = 1) -> Drawn:
    """Every complete case's page into ``out/_report`` (module doc), the cases drawn by
    ``workers`` processes (:func:`sections`); a case whose files turn out to be damaged
    while drawn moves to ``results.damaged``; the coverage's page beside them."""
    final, staging = out / PAGES, out / _STAGING
    _replaceable(final, "pages")
    for left in [staging, *out.glob(f"{_STAGING_OLD}*")]:  # a killed report's
        if left.exists() or left.is_symlink():
            _replaceable(left, "pages")
            shutil.rmtree(left)
    staging.mkdir()
    rows = []
    template = _ENV.get_template("case.html.j2")
    cases = list(results.complete)
    for case, section in zip(cases, sections(cases, workers), strict=True):
        if isinstance(section, tuple):
            results.complete.remove(case)
            results.damaged[case.path.name] = section[0]
            continue
        row = case_row(case)
        verdict = (f"{row.passed}/{row.gated} gated metrics passed"
                   + (f", {row.failed} failed" if row.failed else ""))
        page = template.render(name=case.name, css=CSS, verdict=verdict, cls=row.cls,
                               section=externalise(section, staging / case.name, case.name))
        (staging / f"{case.name}.html").write_text(page, encoding="utf-8")
        rows.append(row)
    index, table = coverage.html(results)
    if table:
        (staging / coverage.PAGE).write_text(template.render(
            name="coverage", css=CSS, verdict="", cls="", section=table), encoding="utf-8")
    replace_dir(staging, final)
    return Drawn(sorted(rows, key=lambda r: (r.cls != "fail", r.name)), index)


def render_index(results: Scan, out: Path, drawn: Drawn) -> str:
    """The index page (module doc)."""
    from reports.store.manifest import provenance

    found = problems(results) + threshold_gate(out)[0]
    table = metrics_table(results)
    n_on = int(gated(table).sum()) if not table.empty else 0
    off = f", {len(table) - n_on} shown and not gated" if n_on < len(table) else ""
    unreported = [*results.incomplete.items(),
                  *((k, f"damaged: {v}") for k, v in results.damaged.items())]
    return _ENV.get_template("index.html.j2").render(
        css=CSS, out=str(out), when=provenance()["date"], problems=found, n_gated=n_on,
        off=off, unreported=unreported, cases=drawn.rows, thresholds=thresholds_html(out),
        coverage=drawn.coverage)


def _thresholds_problem(out: Path) -> list[str]:
    """One line if ``out/thresholds.csv`` exists and cannot be read."""
    return [line for line in threshold_gate(out)[0] if line.startswith("DAMAGED")]


def write_report(out: Path, workers: int = 1) -> Path:
    """Write the report of whatever complete results ``out`` holds: the case pages, then
    ``out/index.html`` atomically.  Incomplete or damaged cases are listed in the index,
    then raised as :class:`RunFailed` (one line each, the pages written: the CLI exits 1).
    The case pages are drawn by ``workers`` processes (:func:`sections`).
    """
    from reports.registry.errors import RunFailed
    from reports.render.gate import case_problems

    out = Path(out)
    results = scan(out)
    if results.empty and not (out / layout.THRESHOLDS).exists():
        raise UserError(f"no results in {out} (run `contact-vv run` first)")
    path = out / layout.REPORT
    with held(layout.lock_file(out, PAGES)):  # one report of a directory at a time
        _replaceable(path, "index")
        atomic_write_text(path, render_index(results, out, write_pages(results, out, workers)))
    lines = case_problems(results) + _thresholds_problem(out)
    if lines:
        raise RunFailed([*lines, f"report {path} written without the {len(lines)} "
                         "incomplete or damaged result(s) above"])
    return path


def report_text(out: Path) -> str:
    """The index and every case page of the report in ``out``, one text (for reading
    the report whole, e.g. in tests)."""
    pages = sorted((Path(out) / PAGES).glob("*.html"))
    return "\n".join(p.read_text(encoding="utf-8")
                     for p in [Path(out) / layout.REPORT, *pages] if p.exists())

