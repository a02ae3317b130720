"""The report renders in headless Chromium (runs only where `chromium` is installed; see
reports/README.md for the manual check)."""

from __future__ import annotations

import shutil
import subprocess

import pytest
import test_cli_fakes as fakes
from test_cli_run import HERTZ, write_case

from reports.cli import main

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
pytestmark = pytest.mark.skipif(CHROMIUM is None, reason="headless Chromium is not installed")


def chromium(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", *args],
                          check=True, capture_output=True, text=True, timeout=120)


def test_renders_in_headless_chromium(tmp_path, monkeypatch):
    fakes.use(monkeypatch, ic="solve_ic", analytic="solve_exact")
    out = tmp_path / "res"
    assert main(["run", "--no-progress", str(write_case(tmp_path, HERTZ, "static")),
                 "--out", str(out)]) == 0
    assert main(["report", "--out", str(out)]) == 0
    url = (out / "index.html").resolve().as_uri()
    shot = tmp_path / "shot.png"
    chromium(f"--screenshot={shot}", "--window-size=1280,2000", url)
    assert shot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and shot.stat().st_size > 10_000
    dom = chromium("--dump-dom", url).stdout
    for needle in ('id="case-static"', 'class="profiles"', 'class="vm-planes"',
                   'class="metrics"', 'class="convergence"', 'class="provenance"'):
        assert dom.count(needle) == 1, needle
    assert dom.count("<img") >= 3
