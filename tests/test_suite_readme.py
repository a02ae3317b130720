"""The README as a front door: its Python example runs (a doctest), its "Two commands"
section stays short, and it restates no measured time — those live, dated, in
``benchmarks/README.md`` (issue 48), so that a figure cannot drift between two places."""

from __future__ import annotations

import doctest
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
README = (ROOT / "README.md").read_text()


def _section(title: str) -> str:
    start = README.index(f"## {title}")
    end = README.find("\n## ", start + 1)
    return README[start:end if end > 0 else None]


def test_the_python_example_runs():
    (block,) = re.findall(r"```python\n(.*?)```", README, re.S)
    test = doctest.DocTestParser().get_doctest(block, {}, "README", "README.md", 0)
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
    runner.run(test)
    assert runner.failures == 0 and runner.tries >= 8


def test_two_commands_in_under_250_words():
    words = len(re.sub(r"```.*?```", "", _section("Two commands"), flags=re.S).split())
    assert words < 250, words


def test_no_measured_time_is_restated():
    """A duration (``4 min 57 s``, ``19 minutes``, ``0.2 s``) in the README is a figure
    that drifts from the dated tables of benchmarks/README.md."""
    found = re.findall(r"\b\d+(?:\.\d+)?\s?(?:min|minutes|hours|s|seconds)\b", README)
    assert not found, found
