"""The documentation site (``docs/conf.py``) builds with warnings as errors, as ``.ci/run``
builds it, and every package's public names (its ``__all__``) have their entry in the API
reference.  In headless Chromium (only where ``chromium`` is installed) the formulation
page renders its equations: MathJax, served from the site itself, has replaced every
equation of the page and reported no TeX error.  Its screenshot is kept as a test
artefact, ``formulation.png`` in ``$CONTACT_VV_ARTEFACTS/chromium`` (default
``artefacts/chromium`` in the repository, not tracked), beside the report's."""

from __future__ import annotations

import importlib
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
ARTEFACTS = Path(os.environ.get("CONTACT_VV_ARTEFACTS", ROOT / "artefacts")) / "chromium"
PNG = b"\x89PNG\r\n\x1a\n"
PACKAGES = ("cases", "halfspace", "fem_reference", "analytic", "external_results", "reports")
PAGES = ("index", "getting-started", "case-files", "cases", "verifying-a-solver",
         "external-results", "example-external-results", "commands", "scale-out",
         "formulation", "fem-notes", "overview", "README", "api/index", "benchmarks",
         "benchmarks-coverage", "changelog", *(f"api/{p}" for p in PACKAGES))
#: an equation as Sphinx writes it for MathJax: inline \( \), display \[ \]
MATH = 'class="math notranslate nohighlight"'
needs_chromium = pytest.mark.skipif(CHROMIUM is None, reason="headless Chromium is not installed")


@pytest.fixture(scope="module")
def site(tmp_path_factory) -> Path:
    """The site as ``.ci/run`` builds it: ``sphinx-build -W --keep-going``."""
    out = tmp_path_factory.mktemp("site")
    built = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q",
                            "-b", "html", str(ROOT / "docs"), str(out)],
                           cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert built.returncode == 0, built.stdout[-3000:] + built.stderr[-5000:]
    return out


def chromium(*args: str) -> subprocess.CompletedProcess:
    """Headless Chromium with ten seconds of virtual time: the scripts have run."""
    return subprocess.run([CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu",
                           "--virtual-time-budget=10000", *args],
                          check=True, capture_output=True, text=True, timeout=120)


def test_the_site_builds_with_warnings_as_errors(site):
    missing = [p for p in PAGES if not (site / f"{p}.html").is_file()]
    assert not missing, missing
    assert (site / "_static" / "mathjax" / "tex-chtml.js").is_file()
    index = (site / "index.html").read_text()
    assert 'href="getting-started.html"' in index and 'href="api/index.html"' in index
    start = (site / "getting-started.html").read_text()
    for section in ("two-commands", "what-you-get", "verify-your-own"):  # the README's
        assert f'id="{section}"' in start, section


def test_every_public_name_has_its_entry(site):
    missing = []
    for package in PACKAGES:
        page = (site / "api" / f"{package}.html").read_text()
        missing += [f"{package}.{name}" for name in importlib.import_module(package).__all__
                    if f'id="{package}.{name}"' not in page]
    assert not missing, missing


@needs_chromium
def test_the_formulation_renders_its_equations(site):
    page = site / "formulation.html"
    equations = page.read_text().count(MATH)
    assert equations > 300, equations
    ARTEFACTS.mkdir(parents=True, exist_ok=True)
    shot = ARTEFACTS / "formulation.png"
    chromium(f"--screenshot={shot}", "--window-size=1280,1600", page.as_uri())
    assert shot.read_bytes()[:8] == PNG and shot.stat().st_size > 50_000
    dom = chromium("--dump-dom", page.as_uri()).stdout
    assert dom.count("<mjx-container") == equations
    assert "<mjx-merror" not in dom and "data-mjx-error" not in dom
    body = re.sub(r"<(style|script)\b.*?</\1>", "", dom[dom.index("<body"):], flags=re.S)
    text = re.sub(r"<[^>]+>", " ", body)
    assert "$$" not in text and "\\(" not in text and "\\[" not in text
    assert "Kernels are always evaluated at" in text
