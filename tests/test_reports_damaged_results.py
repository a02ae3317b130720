"""`report` and `gate` on damaged result directories and baselines: one
``contact-vv: error:`` line naming the file or case, the documented exit status (2 a user
error, 1 a damaged or incomplete case or a failed metric), never a traceback.

A real results directory (hertz, quick grids, ic + analytic) is made once per module;
every test damages a copy of it.  Damage "rehashed" is written into the manifest as a run
would have (so the files match their hashes and the damage must be found by reading
them); damage without it is caught by the hash check.
"""

from __future__ import annotations

import json
import shutil
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest
from damage_kit import (
    bad_crc,
    edit_csv,
    edit_manifest,
    edit_npz,
    huge_array,
    metric_edit,
    npz,
    rehash,
    to_dir,
    truncated,
    wrong_shape,
)

from reports.cli import main
from reports.render.pages import report_text

ERROR = "contact-vv: error:"


@pytest.fixture(scope="module")
def pristine(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("damaged") / "res"
    assert main(["run", "hertz", "--quick", "--solver", "ic,analytic", "--no-progress",
                 "--out", str(out)]) == 0
    return out


@pytest.fixture
def res(pristine, tmp_path) -> Path:
    out = tmp_path / "res"
    shutil.copytree(pristine, out)
    return out


def call(capsys, *argv: str) -> tuple[int, str, str]:
    """``main(argv)`` in-process; (exit status, stdout, stderr).  Nothing may escape."""
    capsys.readouterr()
    try:
        code = main(list(argv))
    except BaseException as exc:  # noqa: BLE001 - the point of the test
        pytest.fail(f"contact-vv {' '.join(argv)} raised {type(exc).__name__}: {exc}")
    out, err = capsys.readouterr()
    assert "Traceback" not in out + err
    assert "internal error" not in err  # the CLI's net for bugs must not be needed
    return code, out, err


def assert_error(err: str, needle: str) -> None:
    lines = [ln for ln in err.splitlines() if ln.startswith(ERROR)]
    assert any(needle in ln for ln in lines), err


def assert_gate_problems(out: str, err: str, *needles: str) -> None:
    """The gate's problems: each on standard output once, the error one line counting
    them (issue 76, point 6: they were printed twice, the error repeating each)."""
    problems = [ln for ln in out.splitlines()
                if ln.split(" ", 1)[0].isupper() and not ln.startswith("(")]
    for needle in needles:
        assert sum(needle in ln for ln in problems) == 1, out
    errors = [ln for ln in err.splitlines() if ln.startswith(ERROR)]
    assert errors == [f"{ERROR} the gate found {len(problems)} problem(s), each listed "
                      "above"], err


SWEEP_CHECK = {"parallel_wall_s": 1.0, "serial_wall_s": 2.0, "speedup": 2.0,
               "identical": True}
BINARY = bytes(range(256)) * 8
PNG = b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR" + BINARY

# (id, damage of DIR/hertz, rehash, report status, gate status, text of an error line)
DAMAGE: list[tuple[str, Callable[[Path], object], bool, int, int, str]] = [
    ("manifest-list", lambda c: (c / "manifest.json").write_text("[1, 2, 3]"), False,
     1, 1, "manifest.json: not a run manifest: not a JSON object (a list)"),
    ("manifest-number", lambda c: (c / "manifest.json").write_text("42"), False,
     1, 1, "manifest.json: not a run manifest: not a JSON object (a number)"),
    ("manifest-not-json", lambda c: (c / "manifest.json").write_text("{'complete': yes"),
     False, 1, 1, "manifest.json: not valid JSON"),
    ("manifest-not-utf8", lambda c: (c / "manifest.json").write_bytes(b'{"a": "\xff\xfe"}'),
     False, 1, 1, "manifest.json: not UTF-8 text"),
    ("manifest-empty", lambda c: (c / "manifest.json").write_bytes(b""), False,
     1, 1, "manifest.json: empty file"),
    ("manifest-binary", lambda c: (c / "manifest.json").write_bytes(PNG), False,
     1, 1, "manifest.json: not UTF-8 text"),
    ("manifest-deeply-nested", lambda c: (c / "manifest.json").write_text("[" * 200000),
     False, 1, 1, "manifest.json: nested too deeply"),
    ("manifest-is-a-directory", lambda c: to_dir(c / "manifest.json"), False,
     1, 1, "manifest.json: not a regular file"),
    ("manifest-wrong-types", lambda c: edit_manifest(c, lambda m: m.update(
        points="abc", skipped=["ic"], units=[{"solver": 1}], wall_s="fast")), False,
     1, 1, "manifest.json: not a run manifest: points is not a list"),
    ("manifest-point-scales-not-numbers", lambda c: edit_manifest(
        c, lambda m: m["points"][0].update(hertz_a0="wide")), False,
     1, 1, "points[0].hertz_a0 is not a number"),
    ("manifest-zero-scale", lambda c: edit_manifest(
        c, lambda m: m["points"][0].update(hertz_p0=0.0)), False,
     1, 1, "points[0].hertz_p0 is 0.0, not a positive number"),
    ("manifest-provenance-list", lambda c: edit_manifest(
        c, lambda m: m.update(provenance=[1])), False, 1, 1, "provenance is not an object"),
    ("manifest-without-files", lambda c: edit_manifest(c, lambda m: m.pop("files")), False,
     1, 1, "manifest.json: not a run manifest: no files"),
    ("manifest-lists-a-file-outside", lambda c: edit_manifest(
        c, lambda m: m["files"].update({"../../etc/passwd": "0" * 64})), False,
     1, 1, "a path outside the case directory"),
    ("manifest-not-complete", lambda c: edit_manifest(c, lambda m: m.update(complete=False)),
     False, 1, 1, "INCOMPLETE hertz"),
    ("metrics-empty", lambda c: (c / "metrics.csv").write_bytes(b""), True,
     1, 1, "metrics.csv: empty file (0 bytes)"),
    ("metrics-empty-hash-mismatch", lambda c: (c / "metrics.csv").write_bytes(b""), False,
     1, 1, "metrics.csv changed after the run"),
    ("metrics-binary", lambda c: (c / "metrics.csv").write_bytes(PNG), True,
     1, 1, "metrics.csv: not UTF-8 text"),
    ("metrics-missing-columns", lambda c: edit_csv(
        c / "metrics.csv", lambda f: f.drop(columns=["value", "tolerance"])),
     True, 1, 1, "metrics.csv: missing column(s) value, tolerance"),
    ("metrics-non-numeric-value", metric_edit("p_max", value="abc"), True,
     1, 1, "metrics.csv: column 'value' holds 'abc'"),
    ("metrics-passed-not-boolean", metric_edit("p_max", passed="maybe"), True,
     1, 1, "metrics.csv: column 'passed' holds 'maybe'"),
    ("metrics-zero-tolerance", metric_edit("vm_max_loc", tolerance="0"), True,
     1, 1, "metrics.csv: column 'tolerance' holds 0.0 (data row 10), not a positive"),
    ("metrics-ragged-rows", lambda c: (c / "metrics.csv").write_text(
        (c / "metrics.csv").read_text() + ",".join(map(str, range(1, 31))) + "\n"), True,
     1, 1, "metrics.csv: not a valid CSV table"),
    ("summary-binary", lambda c: (c / "summary.csv").write_bytes(BINARY), True,
     1, 1, "summary.csv: not a valid CSV table"),
    ("summary-without-step-and-param", lambda c: edit_csv(
        c / "summary.csv", lambda f: f.drop(columns=["step", "param"])), True,
     1, 1, "summary.csv: missing column(s) param, step"),
    ("summary-non-numeric", lambda c: edit_csv(
        c / "summary.csv", lambda f: f.__setitem__("p_max", "high")), True,
     1, 1, "summary.csv: column 'p_max' holds 'high'"),
    ("summary-fractional-step", lambda c: edit_csv(
        c / "summary.csv", lambda f: f.__setitem__("step", "0.5")), True,
     1, 1, "summary.csv: column 'step' holds 0.5"),
    ("summary-is-a-directory", lambda c: to_dir(c / "summary.csv"), False,
     1, 1, "summary.csv listed in the manifest is not a regular file"),
    ("summary-is-a-directory-rehashed", lambda c: to_dir(c / "summary.csv"), True,
     1, 1, "summary.csv: not a regular file"),
    ("npz-random-bytes", lambda c: npz(c).write_bytes(BINARY), True,
     1, 1, "step_0000.npz: corrupt or truncated archive"),
    ("npz-truncated", lambda c: truncated(npz(c)), True,
     1, 1, "step_0000.npz: corrupt or truncated archive"),
    ("npz-bad-crc", lambda c: bad_crc(npz(c, "analytic")), True,
     1, 1, "analytic/base/step_0000.npz: corrupt or truncated archive"),
    ("npz-empty", lambda c: npz(c).write_bytes(b""), True,
     1, 1, "step_0000.npz: empty file"),
    ("npz-inconsistent-shapes", lambda c: wrong_shape(npz(c)), True,
     1, 1, "step_0000.npz: surface field p_n has shape"),
    ("npz-coordinates-not-monotonic", lambda c: edit_npz(
        npz(c), lambda a: a["x"].__setitem__(slice(None), 0.0)), True,
     1, 1, "step_0000.npz: x is not a strictly monotonic sequence of finite numbers"),
    ("npz-scalars-not-an-object", lambda c: edit_npz(
        npz(c), lambda a: a.__setitem__("scalars", np.array("[1, 2]"))), True,
     1, 1, "step_0000.npz: its scalars are not a JSON object"),
    ("npz-claims-terabytes", lambda c: huge_array(npz(c)), True,
     1, 1, "step_0000.npz: cannot be read (MemoryError"),
    ("npz-damaged-hash-mismatch", lambda c: truncated(npz(c)), False,
     1, 1, "step_0000.npz changed after the run"),
    ("npz-added-after-the-run", lambda c: (npz(c).parent / "step_0001.npz").write_bytes(
        BINARY), False, 1, 1, "fields/ic/base/step_0001.npz is not listed in the manifest"),
    ("npz-badly-named", lambda c: shutil.copy(npz(c), npz(c).parent / "step_x.npz"), True,
     1, 1, "step_x.npz: not named step_NNNN.npz"),
    ("fields-is-a-file", lambda c: (shutil.rmtree(c / "fields"), (c / "fields").write_text(
        "x")), False, 1, 1, "listed in the manifest is missing"),
    ("table-binary", lambda c: (npz(c).parent / "fretting_loop.csv").write_bytes(PNG), True,
     1, 1, "fretting_loop.csv: not UTF-8 text"),
    ("table-not-numbers", lambda c: (npz(c).parent / "fretting_loop.csv").write_text(
        "displacement,Qx\n0.1,abc\n"), True, 1, 1, "fretting_loop.csv: column 'Qx'"),
    ("sweep-check-not-json", lambda c: (c / "sweep_check.json").write_text("{identical"),
     False, 1, 1, "sweep_check.json: not valid JSON"),
    ("sweep-check-list", lambda c: (c / "sweep_check.json").write_text("[]"), False,
     1, 1, "sweep_check.json: not a JSON object (a list)"),
    ("sweep-check-missing-keys", lambda c: (c / "sweep_check.json").write_text(
        '{"identical": true}'), False, 1, 1, "sweep_check.json: parallel_wall_s is None"),
    ("sweep-check-is-a-directory", lambda c: to_dir(c / "sweep_check.json", filled=False),
     False,
     1, 1, "sweep_check.json: not a regular file"),
    # metrics the gate must not trust: report shows them (exit 0), gate fails (exit 1)
    ("metric-nan-marked-passed", metric_edit("p_max", value="", passed="True"), True,
     0, 1, "FAIL hertz step 0 ic-analytic p_max rel = nan (not a finite number"),
    ("metric-over-tolerance-marked-passed", metric_edit("p_max", value="0.5", passed="True"),
     True, 0, 1, "FAIL hertz step 0 ic-analytic p_max rel = 0.5 > tolerance"),
    ("metric-infinite-tolerance-marked-passed", metric_edit("p_max", tolerance="inf"), True,
     0, 1, "against tolerance inf (not a finite number)"),
    ("metric-passing-marked-failed", metric_edit("p_max", passed="False"), True,
     0, 1, "INCONSISTENT hertz step 0 ic-analytic p_max rel"),
]


@pytest.mark.parametrize(("damage", "rehashed", "report_code", "gate_code", "needle"),
                         [d[1:] for d in DAMAGE], ids=[d[0] for d in DAMAGE])
def test_damaged_case(res, capsys, damage, rehashed, report_code, gate_code, needle):
    case = res / "hertz"
    damage(case)
    if rehashed:
        rehash(case)
    code, _, err = call(capsys, "report", "--out", str(res))
    assert code == report_code, err
    assert (res / "index.html").is_file()  # written with what could be shown
    if report_code:
        assert_error(err, needle)
        assert_error(err, "hertz")
        assert "damaged" in report_text(res) or \
            "INCOMPLETE" in err or "incomplete" in err
    else:
        assert err == ""
        assert "Gate: 2 problem(s)" in report_text(res) or \
            "Gate: 1 problem(s)" in report_text(res)
    code, out, err = call(capsys, "gate", "--out", str(res))
    assert code == gate_code, err
    assert_gate_problems(out, err, needle)


def test_marked_passed_metric_reports_the_contradiction(res, capsys):
    metric_edit("p_max", value="nan", passed="True")(res / "hertz")
    rehash(res / "hertz")
    code, out, err = call(capsys, "gate", "--out", str(res))
    assert code == 1
    assert_gate_problems(out, err, "INCONSISTENT hertz step 0 ic-analytic p_max rel: ",
                         "records passed = True, but value nan against tolerance 0.01 fails")
    assert "13/14 metric(s) passed" in out


def test_undamaged_results_pass(res, capsys):
    (res / "hertz" / "sweep_check.json").write_text(json.dumps(SWEEP_CHECK))
    code, out, err = call(capsys, "report", "--out", str(res))
    assert (code, err) == (0, ""), err
    assert "report:" in out and "Sweep on Dask" in report_text(res)
    code, out, err = call(capsys, "gate", "--out", str(res))
    assert (code, err) == (0, ""), err
    assert "14/14 metric(s) passed, 2 shown and not gated, 0 problem(s)" in out


def test_the_other_cases_are_still_reported(res, capsys):
    other = res / "other"
    shutil.copytree(res / "hertz", other)
    edit_manifest(other, lambda m: m.update(dir="other", case="other"))
    (res / "hertz" / "metrics.csv").write_bytes(b"")
    rehash(res / "hertz")
    staging = res / ".third.partial"
    staging.mkdir()
    (staging / "failed.json").write_text('["not", "an", "object"]')
    code, _, err = call(capsys, "report", "--out", str(res))
    assert code == 1
    errors = [ln for ln in err.splitlines() if ln.startswith(ERROR)]
    assert len(errors) == 3, err  # one per problem, and where the report is
    assert_error(err, "DAMAGED hertz: ")
    assert_error(err, "INCOMPLETE third: run failed (its failure record ")
    assert_error(err, "failed.json: not a JSON object (a list))")
    page = report_text(res)
    assert 'id="case-other"' in page and 'id="case-hertz"' not in page
    assert "metrics.csv: empty file (0 bytes)" in page
    code, out, err = call(capsys, "gate", "--out", str(res))
    assert code == 1
    assert ("gate: 1 case(s), 14/14 metric(s) passed, 2 shown and not gated, "
            "2 problem(s)") in out
    assert_gate_problems(out, err, "DAMAGED hertz: ")


# ------------------------------------------------------------------ user errors (2)


@pytest.mark.parametrize("command", ["report", "gate"])
@pytest.mark.parametrize(("where", "needle"), [
    (lambda r: r / "missing", "does not exist"),
    (lambda r: (r / "file.txt", (r / "file.txt").write_text("x"))[0],
     "is a file, not a directory"),
    (lambda r: r / "hertz", "is a case directory, not a results directory"),
    (lambda r: (r / "empty", (r / "empty").mkdir())[0], "no results in"),
], ids=["missing", "a-file", "a-case-directory", "empty"])
def test_out_that_is_not_a_results_directory(res, capsys, command, where, needle):
    code, _, err = call(capsys, command, "--out", str(where(res)))
    assert code == 2
    assert_error(err, needle)


def test_report_that_cannot_be_written(res, capsys):
    to_dir(res / "index.html")
    code, _, err = call(capsys, "report", "--out", str(res))
    assert code == 2
    assert_error(err, "index.html")


@pytest.fixture
def baseline(res, capsys) -> Path:
    base = res.parent / "baselines"
    assert call(capsys, "gate", "--out", str(res), "--update-baseline", str(base))[0] == 0
    assert call(capsys, "gate", "--out", str(res), "--baseline", str(base))[0] == 0
    return base


@pytest.mark.parametrize(("damage", "needle"), [
    (lambda b: (b / "hertz.csv").write_bytes(PNG), "hertz.csv: not UTF-8 text"),
    (lambda b: (b / "hertz.csv").write_bytes(b""), "hertz.csv: empty file"),
    (lambda b: (b / "hertz.csv").write_bytes(b"\xff\xfecase,solver\n"), "not UTF-8"),
    (lambda b: edit_csv(b / "hertz.csv", lambda f: f.drop(columns=["solver"])),
     "hertz.csv: missing column(s) solver"),
    (lambda b: edit_csv(b / "hertz.csv", lambda f: f.__setitem__("p_max", "x")),
     "hertz.csv: column 'p_max' holds 'x'"),
    (lambda b: edit_csv(b / "hertz.csv", lambda f: f.__setitem__("solver", "ic")),
     "hertz.csv: two rows for solver ic"),
    (lambda b: to_dir(b / "other.csv"), "other.csv: not a regular file"),
    (lambda b: (b / "hertz.csv").unlink(), "holds no <case>.csv baselines"),
    (lambda b: (shutil.rmtree(b), b.write_text("x")), "is not a directory"),
], ids=["binary", "empty", "not-utf8", "missing-column", "non-numeric", "duplicate-rows",
        "a-directory", "no-baselines", "a-file"])
def test_damaged_baseline_is_a_user_error(res, baseline, capsys, damage, needle):
    damage(baseline)
    code, out, err = call(capsys, "gate", "--out", str(res), "--baseline", str(baseline))
    assert code == 2
    assert_error(err, needle)
    assert out == ""  # refused before printing anything


def test_baselines_are_not_updated_from_damaged_results(res, capsys):
    (res / "hertz" / "summary.csv").write_bytes(BINARY)
    rehash(res / "hertz")
    base = res.parent / "baselines"
    code, _, err = call(capsys, "gate", "--out", str(res), "--update-baseline", str(base))
    assert code == 2
    assert_error(err, "refusing to update baselines from incomplete or damaged results: "
                      "hertz")
    assert not list(base.glob("*.csv")) if base.exists() else True


def test_a_file_damaged_after_the_scan_moves_its_case_to_damaged(res):
    """The report draws from files read lazily; one that fails then is named too."""
    from reports.render import pages
    from reports.store.results import scan

    results = scan(res)
    truncated(npz(res / "hertz"))
    drawn = pages.write_pages(results, res)
    page = pages.render_index(results, res, drawn)
    assert not results.complete and list(results.damaged) == ["hertz"]
    assert "step_0000.npz: corrupt or truncated archive" in results.damaged["hertz"]
    assert 'id="incomplete"' in page and drawn.rows == []
    assert not (res / pages.PAGES / "hertz.html").exists()
