"""The gate's verdict as JUnit XML (``contact-vv gate --junit FILE``), the report format
CI systems display (GitLab, GitHub, Jenkins); FILE may be ``-``, ``/dev/stdout`` or a
pipe (:mod:`reports.store.targets`).

One ``testsuite`` per complete case, one ``testcase`` per metric row — classname the
case and its sweep point, name ``step N pair quantity metric`` — failed where the gate
fails it (the message: value and tolerance), skipped where the row is shown and not
gated (the message: why), passed otherwise; a case's own problems (no gated metric, a
solver that did not converge) are failing test cases of that suite.  The problems of
no case (incomplete or damaged results, drifted baselines) are the failing test cases
of a suite ``contact-vv``.  Written atomically to a file.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from pathlib import Path

import pandas as pd

from reports.registry.errors import UserError
from reports.store import targets
from reports.store.readers import gated
from reports.store.results import CaseResults, Scan

OPTION = "--junit"

#: the words a gate's problem line starts with, before the case it is about
KINDS = ("FAIL", "INCONSISTENT", "NO METRICS", "NOT CONVERGED", "INCOMPLETE", "DAMAGED",
         "DRIFT")


def owner(line: str, names: set[str]) -> str | None:
    """The case a gate's problem line is about (one of ``names``), None if none."""
    kind = next((k for k in KINDS if line.startswith(k + " ")), None)
    if kind is None:
        return None
    rest = line[len(kind) + 1:]
    token = rest.split(" ", 1)[0].split(":", 1)[0]
    return token if token in names else None


def _point(case: str, param: object) -> str:
    return case if pd.isna(param) or not str(param) else f"{case}[{param}]"


def _suite(root: ET.Element, name: str) -> ET.Element:
    return ET.SubElement(root, "testsuite", name=name)


def _case(suite: ET.Element, classname: str, name: str) -> ET.Element:
    return ET.SubElement(suite, "testcase", classname=classname, name=name, time="0")


def _fail(testcase: ET.Element, message: str) -> None:
    ET.SubElement(testcase, "failure", message=message, type="gate").text = message


def _case_suite(root: ET.Element, case: CaseResults, problems: list[str]) -> None:
    suite = _suite(root, case.name)
    m = case.metrics
    on = gated(m).to_numpy() if len(m) else []
    for k, r in enumerate(m.itertuples(index=False)):
        step = "" if pd.isna(r.step) else f"step {int(r.step)} "
        tc = _case(suite, _point(case.name, r.param), f"{step}{r.pair} {r.quantity} {r.metric}")
        value, tol = float(r.value), float(r.tolerance)
        if not on[k]:
            ET.SubElement(tc, "skipped", message=f"not gated: {r.note}")
        elif not r.passed:
            finite = math.isfinite(value) and math.isfinite(tol)
            _fail(tc, f"{value:.4g} > tolerance {tol:.4g} ({r.tolerance_key})" if finite
                  else f"value {value} against tolerance {tol} (not finite)")
    mine = [p for p in problems if owner(p, {case.name}) == case.name
            and not p.startswith("FAIL ")]
    for line in mine:
        kind = next(k for k in KINDS if line.startswith(k))
        _fail(_case(suite, case.name, kind.lower()), line)


def junit_tree(results: Scan, problems: list[str]) -> ET.ElementTree:
    """The XML tree of a gate's verdict (module doc); ``problems`` the gate's lines."""
    root = ET.Element("testsuites", name="contact-vv gate")
    names = {c.name for c in results.complete}
    for case in results.complete:
        _case_suite(root, case, problems)
    rest = [p for p in problems if owner(p, names) is None]
    if rest:
        suite = _suite(root, "contact-vv")
        for line in rest:
            _fail(_case(suite, "contact-vv", line.split(":", 1)[0]), line)
    for suite in root:
        cases = list(suite)
        suite.set("tests", str(len(cases)))
        suite.set("failures", str(sum(c.find("failure") is not None for c in cases)))
        suite.set("skipped", str(sum(c.find("skipped") is not None for c in cases)))
        suite.set("errors", "0")
    for key in ("tests", "failures", "skipped", "errors"):
        root.set(key, str(sum(int(s.get(key)) for s in root)))
    return ET.ElementTree(root)


def check_path(path: Path, out: Path) -> None:
    """UserError unless ``--junit`` may write ``path``: a target that can be written
    (:func:`reports.store.targets.check`: also ``-``, a pipe, a device), not inside a case
    directory of the results directory ``out`` (the run's files only live there), and, if
    it is an existing file, a JUnit report already (nothing else is replaced)."""
    path = Path(path)  # an empty name is the current directory
    targets.check(path, OPTION)
    if targets.is_stream(path):
        return
    parent, root = path.resolve().parent, Path(out).resolve()
    if parent != root and root in parent.parents or parent == root and path.name.startswith("."):
        raise UserError(f"{OPTION} {path}: lies in a case directory of {out}, which holds "
                        "the run's own files only; write it elsewhere")
    if path.exists():
        try:
            head = targets.head(path).decode("utf-8")
        except UnicodeDecodeError:
            head = ""
        if not (head.startswith("<?xml") and "<testsuites" in head):
            raise UserError(f"{OPTION} {path}: exists and is not a JUnit report; not "
                            "replaced (name another file)")


def write_junit(path: Path, results: Scan, problems: list[str]) -> Path:
    """Write :func:`junit_tree` to ``path`` (atomically, or once to a stream); the path."""
    tree = junit_tree(results, problems)
    ET.indent(tree)
    text = ET.tostring(tree.getroot(), encoding="unicode", xml_declaration=True)
    targets.write_text(Path(path), text + "\n", OPTION)
    return Path(path)
