"""The project's documentation resolves every reference the code makes to it (no solver runs).

Scanned: the ``*.py``, ``*.md`` and ``*.toml`` files at the top level and under
halfspace, fem_reference, analytic, cases, reports, tests, benchmarks and docs (hidden
and cache directories and ``tests/baselines`` excepted; ``docs/formulation.md`` is the
target, not a source).

Collected references, each resolved against ``docs/formulation.md`` unless noted:

- equations: "Eq." or "Eqs." followed by numbers joined by ``,``, ``/``, ``and``, ``&``,
  or ranges with ``-``, an en dash or ``to`` (every number of a range); a number resolves
  when the file holds its bold label, e.g. ``**(13)**``;
- "erratum"/"errata" with numbers -> a ``**Erratum N.**`` entry;
- "Appendix"/"Appendices" with capital letters -> a heading such as ``Appendix C``;
- "§" with a section number, or "section(s)" with a dotted one ("section 2.4") -> a
  heading that starts with ``§N.N``;
- the solution steps of §3.4 ("step (III)", "steps I-VI", "step a.1", "3.4 (III)") ->
  ``**Step (III)**``;
- "Correction CN" -> a ``**Correction CN`` entry;
- case numbers of the benchmark document ("cases.md, case 4", "cases 4 and 5 of
  cases.md") -> a heading ``## 4.`` in ``docs/cases.md``;
- paths ``docs/<name>.md`` -> an existing file;
- in ``docs/*.md`` and the top-level ``README.md``: ``tests/<file>.py::<test>`` -> a test
  function of that name in that file.

References to another book are skipped.  The rule:

1. an equation number with a decimal part (a book's chapter.equation, e.g. Johnson's
   "eq. 3.45"): the article numbers its equations with integers only;
2. any reference with the name of a cited author or book (``BOOK_MARKERS``) within the
   ``WINDOW`` characters before it (line breaks included, so wrapped docstrings count),
   unless "formulation" or "docs/" stands between that name and the reference;
3. a "§"/"section" reference in a module whose first line cites a book section (an
   author name followed by "§" on that line, e.g. analytic/hertz.py): such modules
   implement textbook solutions, and they cite the article as "formulation Eq. N" or
   "Appendix A", which rules 1-2 still check.

Second test: no file of the repository outside ``docs/`` refers to material that lives
outside the repository (``FOREIGN``).

Third test: a quoted title of ``benchmarks/README.md`` (``benchmarks/README.md, "Escapes"``,
the quote possibly wrapped, in a comment too) starts one of its headings or the first line
of one of its paragraphs (bold or not), so that a moved or renamed section leaves no
quote dangling.
"""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
FORMULATION = DOCS / "formulation.md"
CASES_DOC = DOCS / "cases.md"
THIS = Path(__file__).resolve()

SCAN_DIRS = ("halfspace", "fem_reference", "analytic", "cases", "reports", "external_results",
             "tests", "benchmarks", "docs")
SUFFIXES = (".py", ".md", ".toml")
SKIP_DIRS = {"__pycache__", "baselines"}
BENCHMARKS = ROOT / "benchmarks" / "README.md"
BENCH_QUOTE_RE = re.compile(r'benchmarks/README\.md`{0,2},?\s*\(?"([^"]{1,120})"')

WINDOW = 40
BOOK_MARKERS = (
    "Johnson", "Contact Mechanics", "Hamilton", "Goodman", "Hills", "Argatov", "Hegadekatte",
    "Mindlin", "Deresiewicz", "Cattaneo", "Love", "Polonsky", "Keer", "Kalker", "Roache",
    "Celik", "Hüeber", "Hueber", "Alart", "Curnier", "Archard", "Masing", "Teboulle",
    "Candès", "Candes", "Vingsbo", "Timoshenko", "Barber",
)
ARTICLE_MARKERS = ("formulation", "docs/")

# paths of the source material that is not part of the repository
FOREIGN = ("shared/", "DESIGN.md", "paper/formulation.md", "paper/cases.md",
           "notes/fem-feasibility.md")

NUM = r"\(?\d+(?:\.\d+)?\)?"
EQ_RE = re.compile(rf"\b[Ee]qs?\.\s*{NUM}(?:\s*(?:,|/|&|\band\b|\bto\b|-|–)\s*{NUM})*")
ERRATUM_RE = re.compile(r"\b[Ee]rrat(?:um|a)\s+\d+(?:\s*(?:,|-|–|\band\b)\s*\d+)*")
APPENDIX_RE = re.compile(r"\bAppendi(?:x|ces)\s+[A-Z]\b(?:\s*(?:,|/|&|\band\b)\s*[A-Z]\b)*")
SECTION_RE = re.compile(
    r"(?:§\s?\d+(?:\.\d+)?|\b[Ss]ections?\s+\d+\.\d+)(?:\s*(?:,|&|\band\b)\s*\d+\.\d+)*")
ROMAN = ("I", "II", "III", "IV", "V", "VI")
_STEP = r"(?:VI|V|IV|I{1,3}|a\.[12])"
STEP_RE = re.compile(
    rf"\bsteps?\s+\(?({_STEP})\)?(?:\s*(?:-|–|\bto\b)\s*\(?({_STEP})\)?)?(?![\w])"
    rf"|\b3\.4\s+\(({_STEP})\)")
CORRECTION_RE = re.compile(r"\bCorrection\s+C(\d+)")
CASE_RE = re.compile(
    r"cases\.md,?\s+(?:case\s+|§\s?)(\d+)"
    r"|\bcases?\s+(\d+(?:\s*(?:,|\band\b|&)\s*\d+)*)\s+of\s+(?:the\s+)?(?:docs/)?cases\.md")
DOC_PATH_RE = re.compile(r"\bdocs/([\w.-]+\.md)")
TEST_REF_RE = re.compile(r"\btests/(test_\w+\.py)::(test_\w+)")


def project_files() -> list[Path]:
    """Files whose references are checked (see the module docstring)."""
    files = [p for p in sorted(ROOT.iterdir()) if p.is_file() and p.suffix in SUFFIXES]
    for name in SCAN_DIRS:
        for p in sorted((ROOT / name).rglob("*")):
            parts = p.relative_to(ROOT).parts
            if (p.is_file() and p.suffix in SUFFIXES
                    and not any(part.startswith(".") or part in SKIP_DIRS for part in parts)):
                files.append(p)
    return files


def _text(path: Path) -> str:
    return path.read_text(encoding="utf-8", errors="replace")


def _line(text: str, pos: int) -> int:
    return text.count("\n", 0, pos) + 1


def _numbers(ref: str) -> list[str]:
    """Numbers of a reference, ranges expanded ("9-14" -> 9 .. 14).  Decimal numbers are
    kept as strings with their point (rule 1 drops them)."""
    tokens = re.findall(r"\d+(?:\.\d+)?|-|–|\bto\b", ref)
    out: list[str] = []
    pending_range = False
    for tok in tokens:
        if tok in ("-", "–", "to"):
            pending_range = bool(out)
            continue
        if pending_range and "." not in tok and "." not in out[-1]:
            out.extend(str(n) for n in range(int(out[-1]) + 1, int(tok) + 1))
        else:
            out.append(tok)
        pending_range = False
    return out


def _book_window(text: str, start: int) -> bool:
    """Rule 2: a book author's name shortly before ``start``, with no article marker
    between the name and the reference."""
    window = text[max(0, start - WINDOW):start]
    last = max((window.rfind(m) + len(m) for m in BOOK_MARKERS if m in window), default=-1)
    if last < 0:
        return False
    return not any(m in window[last:] for m in ARTICLE_MARKERS)


def _book_module(text: str) -> bool:
    """Rule 3: the file's first line cites a section of a book."""
    first = text.lstrip().split("\n", 1)[0]
    if "§" not in first:
        return False
    cut = first.index("§")
    return any(m in first[:cut] for m in BOOK_MARKERS)


class Targets:
    """What docs/formulation.md and docs/cases.md define."""

    def __init__(self) -> None:
        f = _text(FORMULATION)
        self.equations = set(re.findall(r"\*\*\((\d+)\)\*\*", f))
        self.errata = set(re.findall(r"\*\*Erratum (\d+)\.\*\*", f))
        self.corrections = set(re.findall(r"\*\*Correction C(\d+)", f))
        self.appendices = set(re.findall(r"(?m)^#{1,6} Appendix ([A-Z])\b", f))
        self.sections = set(re.findall(r"(?m)^#{1,6} §(\d+(?:\.\d+)?)\b", f))
        self.steps = set(re.findall(r"\*\*Step \(([^)]+)\)\*\*", f))
        self.cases = set(re.findall(r"(?m)^## (\d+)\.", _text(CASES_DOC)))


def _equations(m: re.Match, text: str) -> list[str]:
    return [n for n in _numbers(m.group(0)[m.group(0).index(".") + 1:])
            if "." not in n]  # rule 1


def _steps(m: re.Match, text: str) -> list[str]:
    first, last, alone = m.group(1), m.group(2), m.group(3)
    if last and first in ROMAN and last in ROMAN:
        return list(ROMAN[ROMAN.index(first):ROMAN.index(last) + 1])
    return [alone or first]


def _in_window(m: re.Match, text: str) -> bool:
    return _book_window(text, m.start())


def _section_skipped(m: re.Match, text: str) -> bool:
    """Another book's section (rules 2, 3), or a case number of docs/cases.md."""
    return (_book_module(text) or _book_window(text, m.start())
            or "cases.md" in text[max(0, m.start() - 12):m.start()])


def _never(m: re.Match, text: str) -> bool:
    return False


def _rules(t: Targets) -> list[tuple]:
    """(pattern, skip(match, text), cited(match, text), defined, what is missing)."""
    return [
        (EQ_RE, _in_window, _equations, t.equations,
         "no label **(N)** in docs/formulation.md for N ="),
        (ERRATUM_RE, _in_window, lambda m, _: _numbers(m.group(0)), t.errata,
         "no **Erratum N.** for N ="),
        (APPENDIX_RE, _in_window, lambda m, _: re.findall(r"\b[A-Z]\b", m.group(0)),
         t.appendices, "no appendix heading in docs/formulation.md for"),
        (SECTION_RE, _section_skipped, lambda m, _: re.findall(r"\d+(?:\.\d+)?", m.group(0)),
         t.sections, "no heading '§N' for N ="),
        (STEP_RE, _in_window, _steps, t.steps, "no **Step (X)** for X ="),
        (CORRECTION_RE, _never, lambda m, _: [m.group(1)], t.corrections,
         "no such correction in docs/formulation.md: C"),
        (CASE_RE, _never, lambda m, _: re.findall(r"\d+", m.group(1) or m.group(2)), t.cases,
         "no heading '## N.' in docs/cases.md for N ="),
    ]


def _test_refs(text: str) -> list[tuple[re.Match, str]]:
    """(match, what is missing) for ``tests/file.py::test_name`` references without
    their test."""
    out = []
    for m in TEST_REF_RE.finditer(text):
        test_file = ROOT / "tests" / m.group(1)
        if not test_file.is_file():
            out.append((m, "no such test file"))
        elif not re.search(rf"(?m)^\s*(?:async\s+)?def {m.group(2)}\(", _text(test_file)):
            out.append((m, "no such test function"))
    return out


def unresolved_references() -> list[str]:
    """``path:line: reference -> what is missing`` for every reference without target."""
    rules = _rules(Targets())
    problems: list[str] = []
    for path in project_files():
        if path == FORMULATION:
            continue
        text = _text(path)
        found: list[tuple[re.Match, str]] = []
        for pattern, skip, cited, defined, what in rules:
            for m in pattern.finditer(text):
                missing = [] if skip(m, text) else [n for n in cited(m, text)
                                                     if n not in defined]
                if missing:
                    found.append((m, f"{what} {', '.join(missing)}"))
        found += [(m, "no such file") for m in DOC_PATH_RE.finditer(text)
                  if not (DOCS / m.group(1)).is_file()]
        if path.suffix == ".md" and path.parent in (DOCS, ROOT):
            found += _test_refs(text)
        problems += [f"{path.relative_to(ROOT)}:{_line(text, m.start())}: "
                     f"'{' '.join(m.group(0).split())}' -> {missing}" for m, missing in found]
    return problems


def test_every_formulation_reference_resolves():
    problems = unresolved_references()
    assert not problems, (
        f"{len(problems)} reference(s) without a target in docs/ (see tests/test_suite_docs.py "
        "for the rules):\n" + "\n".join(problems))


def test_formulation_defines_the_whole_numbering():
    """Eqs. 1-48, errata 1-12, Appendices A-C and the steps of §3.4 are all labelled, so
    a reference the code adds later finds its target."""
    t = Targets()
    assert {str(n) for n in range(1, 49)} <= t.equations, \
        sorted(set(map(str, range(1, 49))) - t.equations, key=int)
    assert {str(n) for n in range(1, 13)} <= t.errata
    assert set("ABC") <= t.appendices
    assert {"2.1", "2.2", "2.3", "2.4", "2.5", "3.1", "3.2", "3.3", "3.4"} <= t.sections
    assert set(ROMAN) | {"a.1", "a.2"} <= t.steps
    assert {str(n) for n in range(1, 8)} <= t.cases


def test_no_reference_to_material_outside_the_repository():
    problems = []
    for path in project_files():
        rel = path.relative_to(ROOT)
        if path == THIS or rel.parts[0] == "docs":
            continue
        for n, line in enumerate(_text(path).splitlines(), 1):
            for needle in FOREIGN:
                if needle in line:
                    problems.append(f"{rel}:{n}: '{needle}' in: {line.strip()}")
    assert not problems, (
        "references to files outside the repository (point them to docs/):\n"
        + "\n".join(problems))


def test_every_quoted_benchmarks_title_resolves():
    lines = _text(BENCHMARKS).splitlines()
    starts = [line.lstrip("#").strip() if line.startswith("#") else line.removeprefix("**")
              for line in lines]
    files = project_files() + [p for d in ("tamaas_adapter", "contactmechanics_adapter",
                                           "kratos_adapter", "calculix_adapter")
                               for p in sorted((ROOT / d).rglob("*.py"))]
    quotes, problems = 0, []
    for path in files:
        text = _text(path)
        for m in BENCH_QUOTE_RE.finditer(text):
            title = re.sub(r"\s*\n\s*(?:#:?\s*)?", " ", m.group(1)).strip()
            quotes += 1
            if not any(start.startswith(title) for start in starts):
                problems.append(f"{path.relative_to(ROOT)}:{_line(text, m.start())}: {title!r}")
    assert quotes >= 30 and not problems, (
        f"{quotes} quote(s); titles not in benchmarks/README.md:\n" + "\n".join(problems))


def test_the_reference_rules_on_examples():
    """The collection and book rules on a few literal cases."""
    assert _numbers(" 9-14") == [str(n) for n in range(9, 15)]
    assert _numbers(" 13/38") == ["13", "38"]
    assert _numbers(" 26, 41-42") == ["26", "41", "42"]
    assert _numbers(" 7.33/7.37") == ["7.33", "7.37"]
    text = "Hertz (Johnson 1985 §4.2)"
    assert _book_window(text, text.index("§"))
    text = "the projected update of the contact solver, §3.4"
    assert not _book_window(text, text.index("§"))
    text = "Argatov's law, see the formulation Eq. 19"
    assert not _book_window(text, text.index("Eq."))
    assert _book_module('"""Hertz contact (Johnson 1985, §4.2).\n')
    assert not _book_module('"""One contact step of section 3.4.\n')
