"""The report in pages renders in headless Chromium (runs only where `chromium` is
installed; see reports/README.md for the manual check): a green run's index and case
page, and a failing run whose failure is in the first screen of the index.  The
screenshots are kept as test artefacts in ``$CONTACT_VV_ARTEFACTS/chromium`` (default
``artefacts/chromium`` in the repository, not tracked)."""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import pytest
import test_cli_fakes as fakes
from test_cli_run import HERTZ, write_case

from reports.cli import main
from reports.render.pages import PAGES

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
pytestmark = pytest.mark.skipif(CHROMIUM is None, reason="headless Chromium is not installed")
ARTEFACTS = Path(os.environ.get("CONTACT_VV_ARTEFACTS",
                                Path(__file__).resolve().parents[1] / "artefacts")) / "chromium"
PNG = b"\x89PNG\r\n\x1a\n"


def chromium(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", *args],
                          check=True, capture_output=True, text=True, timeout=120)


def shoot(page: Path, name: str, size: str) -> Path:
    """A screenshot of ``page`` kept as ``ARTEFACTS/name``."""
    ARTEFACTS.mkdir(parents=True, exist_ok=True)
    shot = ARTEFACTS / name
    chromium(f"--screenshot={shot}", f"--window-size={size}", page.resolve().as_uri())
    assert shot.read_bytes()[:8] == PNG
    return shot


def run(tmp_path: Path, monkeypatch) -> Path:
    fakes.use(monkeypatch, ic="solve_ic", analytic="solve_exact")
    out = tmp_path / "res"
    assert main(["run", "--no-progress", str(write_case(tmp_path, HERTZ, "static")),
                 "--out", str(out)]) == 0
    main(["report", str(out)])
    return out


def test_a_green_run_renders_in_pages(tmp_path, monkeypatch):
    out = run(tmp_path, monkeypatch)
    index, page = out / "index.html", out / PAGES / "static.html"
    assert shoot(index, "green_index.png", "1280,800").stat().st_size > 5_000
    assert shoot(page, "green_case.png", "1280,2000").stat().st_size > 10_000
    dom = chromium("--dump-dom", index.resolve().as_uri()).stdout
    assert 'id="verdict"' in dom and "Gate: pass" in dom and "<img" not in dom
    assert f'href="{PAGES}/static.html"' in dom
    dom = chromium("--dump-dom", page.resolve().as_uri()).stdout
    for needle in ('id="case-static"', 'class="profiles"', 'class="vm-planes"',
                   'class="metrics"', 'class="convergence"', 'class="provenance"'):
        assert dom.count(needle) == 1, needle
    assert dom.count('loading="lazy"') >= 3 and "data:image" not in dom


def test_a_failure_is_in_the_first_screen(tmp_path, monkeypatch):
    """ic 20 % off the closed form: the index opens with the verdict and the failures,
    before the table of cases (the first screen, 1280 x 800, kept as an artefact)."""
    monkeypatch.setattr(fakes, "ERROR", 0.2)
    out = run(tmp_path, monkeypatch)
    index = out / "index.html"
    shoot(index, "failing_index.png", "1280,800")
    dom = chromium("--dump-dom", index.resolve().as_uri()).stdout
    body = dom[dom.index("<body>"):]
    first = body.index("<li>FAIL")
    assert "Gate: " in body[:first] and "problem(s)" in body[:first]
    assert first < body.index("<h2>Cases</h2>") and first < 1000, body[:first]
