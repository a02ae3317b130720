"""``gate --junit`` into what a shell or a CI system hands over (issue 77, point 2): ``-``,
``/dev/stdout`` on a pipe or a file, a named pipe, ``/dev/null`` — written once, the XML
alone on standard output, the gate's exit status — and a target that cannot be written
(``/dev/full``, a parent that is a file, a read-only or full file system) refused at once,
exit 2, naming it.  Found by these probes: ``--junit /dev/stdout | cat`` hung (the
target was read before it was replaced) and ``--junit /dev/full`` read until memory ran
out."""

from __future__ import annotations

import os
import subprocess
import sys
import threading
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from test_cli_hostile_gate import _files, results  # noqa: F401 (the fixture)
from test_cli_hostile_inputs import _answer

from reports.cli import main
from reports.store import targets

GATE = [sys.executable, "-m", "reports", "gate"]


def _xml(text: str) -> ET.Element:
    root = ET.fromstring(text)
    assert root.tag == "testsuites" and int(root.get("tests")) > 0
    return root


def test_junit_to_stdout_as_dash_is_the_xml_alone(results, capsys):  # noqa: F811
    code, _ = _answer(["gate", "--out", str(results)], capsys)
    assert main(["gate", "--out", str(results), "--junit", "-"]) == code
    got = capsys.readouterr()
    _xml(got.out)
    assert "gate:" in got.err


def test_junit_to_dev_stdout_through_a_pipe(results):  # noqa: F811
    plain = subprocess.run([*GATE, str(results)], capture_output=True, timeout=120)
    piped = subprocess.run([*GATE, str(results), "--junit", "/dev/stdout"],
                           capture_output=True, timeout=120)
    assert piped.returncode == plain.returncode
    _xml(piped.stdout.decode())
    assert b"gate:" in piped.stderr


def test_junit_to_dev_stdout_redirected_to_a_file(results, tmp_path):  # noqa: F811
    path = tmp_path / "out.xml"
    with open(path, "wb") as fh:
        done = subprocess.run([*GATE, str(results), "--junit", "/dev/stdout"], stdout=fh,
                              stderr=subprocess.PIPE, timeout=120)
    assert done.returncode in (0, 1)
    _xml(path.read_text())


def test_junit_to_a_named_pipe(results, tmp_path, capsys):  # noqa: F811
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    got: list[bytes] = []
    reader = threading.Thread(target=lambda: got.append(fifo.read_bytes()), daemon=True)
    reader.start()
    code, _ = _answer(["gate", "--out", str(results), "--junit", str(fifo)], capsys)
    reader.join(60)
    assert code in (0, 1) and not reader.is_alive()
    _xml(got[0].decode())


def test_junit_to_dev_null(results, capsys):  # noqa: F811
    code, err = _answer(["gate", "--out", str(results), "--junit", os.devnull], capsys)
    assert code in (0, 1), err


@pytest.mark.skipif(not Path("/dev/full").exists(), reason="a system without /dev/full")
def test_junit_to_a_full_device_is_refused_at_once(results, capsys):  # noqa: F811
    before = _files(results)
    code, err = _answer(["gate", "--out", str(results), "--junit", "/dev/full"], capsys)
    assert code == 2 and "--junit /dev/full: cannot be written (No space left" in err, err
    assert "gate:" not in err and _files(results) == before


def _refused(results, capsys, path) -> str:  # noqa: F811
    before = _files(results)
    code, err = _answer(["gate", "--out", str(results), "--junit", str(path)], capsys)
    lines = [x for x in err.splitlines() if x.startswith("contact-vv: error:")]
    assert code == 2 and len(lines) == 1 and f"--junit {path}" in lines[0], err
    assert _files(results) == before
    return lines[0]


def test_junit_under_a_file_is_refused(results, tmp_path, capsys):  # noqa: F811
    (tmp_path / "a").write_text("mine")
    assert "is a file, not a directory" in _refused(results, capsys, tmp_path / "a" / "j.xml")
    assert (tmp_path / "a").read_text() == "mine"


def test_junit_on_a_read_only_or_full_file_system_is_refused(results, tmp_path, capsys,  # noqa: F811
                                                             monkeypatch):
    path = tmp_path / "ci" / "j.xml"
    monkeypatch.setattr(targets.os, "access", lambda *a, **k: False)
    assert "cannot be written (read-only" in _refused(results, capsys, path)
    monkeypatch.undo()
    full = os.statvfs_result((4096, 4096, 100, 0, 0, 10, 0, 0, 0, 255))
    monkeypatch.setattr(targets.os, "statvfs", lambda *a: full)
    assert "no space left" in _refused(results, capsys, path)
    assert not path.exists() and not path.parent.exists()


def test_a_stream_is_never_read():
    assert targets.head(Path("/dev/zero")) == b""
    assert targets.is_stream(Path("-")) and not targets.is_stream(Path("missing.xml"))


@pytest.mark.parametrize(("argv", "needle"), [
    (["run", "/dev/zero"], "case file /dev/zero is not a regular file"),
    (["gate", "{out}", "--baseline", "/dev/zero"], "/dev/zero is not a directory"),
], ids=["case-file", "baseline"])
def test_an_input_that_is_a_device_is_refused_unread(results, capsys, argv, needle):  # noqa: F811
    if not Path("/dev/zero").exists():
        pytest.skip("a system without /dev/zero")
    code, err = _answer([a.format(out=results) for a in argv], capsys)
    assert code == 2 and needle in err, err
