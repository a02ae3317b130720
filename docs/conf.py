"""Sphinx configuration of the documentation site: the Markdown files of ``docs/`` and of
the repository (README, case files, commands, benchmarks) read with MyST, the public API
from the packages' docstrings, the equations rendered by MathJax served from the site
itself (no network at build or view time).

    pip install -e ".[docs]"
    sphinx-build -W --keep-going -b html docs build/site    # then open build/site/index.html
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
# document this checkout's packages, whatever else is installed
sys.path.insert(0, str(ROOT))

project = "contact-vv"
author = "contact-vv"
copyright = "contact-vv authors"

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx-mathjax-offline",  # MathJax 3 copied into _static/mathjax
]
source_suffix = {".md": "markdown"}
root_doc = "index"
# the examples' READMEs are pages through the page that includes them with their files
exclude_patterns = ["_build", "examples/**/README.md"]

myst_enable_extensions = ["dollarmath", "amsmath"]
# GitHub-style anchors, as the Markdown files link them (e.g. "#errata")
myst_heading_anchors = 4

autodoc_member_order = "bysource"  # a package's __all__ order
autodoc_typehints = "signature"

html_theme = "alabaster"
html_title = "contact-vv"
html_theme_options = {"page_width": "1100px", "sidebar_width": "260px"}
html_static_path = ["_static"]
html_css_files = ["site.css"]

# Repository files outside docs/ that the site renders as pages (by an {include}): a
# Markdown link to one of them becomes a link to its page.
PAGES = {
    ROOT / "README.md": "index",
    ROOT / "cases" / "README.md": "case-files",
    ROOT / "reports" / "README.md": "commands",
    ROOT / "benchmarks" / "README.md": "benchmarks",
    ROOT / "benchmarks" / "coverage.md": "benchmarks-coverage",
    DOCS / "examples" / "external_results" / "README.md": "example-external-results",
}
LINK = re.compile(r"\]\(([^()\s#:]+)(#[^()\s]*)?\)")


def _site_links(text: str, folder: Path) -> str:
    """``text`` (read from a file in ``folder``) with its relative Markdown links resolved
    against that folder, so that they hold wherever the text is included: a link to a
    file of ``PAGES`` points at its page, one to a file under ``docs/`` at that file."""

    def target(match: re.Match) -> str:
        path = (folder / match.group(1)).resolve()
        anchor = match.group(2) or ""
        if path in PAGES:
            return f"](/{PAGES[path]}.md{anchor})"
        if path.is_file() and path.is_relative_to(DOCS):
            return f"](/{path.relative_to(DOCS).as_posix()}{anchor})"
        return match.group(0)

    return LINK.sub(target, text)


def _source_read(app, docname: str, source: list[str]) -> None:
    source[0] = _site_links(source[0], (DOCS / docname).parent)


def _include_read(app, relative_path: Path, parent_docname: str, content: list[str]) -> None:
    content[0] = _site_links(content[0], (DOCS / relative_path).resolve().parent)


def setup(app) -> None:
    app.connect("source-read", _source_read)
    app.connect("include-read", _include_read)
