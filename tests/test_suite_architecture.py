"""The layers of ``reports/`` (reports/README.md) and of ``fem_reference/`` (its package
docstring): each sub-package imports only those its row allows, nothing imports the CLI,
only the registry knows the solver packages, and no import circle exists between the
project's modules."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("halfspace", "fem_reference", "analytic", "cases", "reports", "external_results")
SOLVERS = ("halfspace", "fem_reference", "analytic", "external_results")

#: sub-package of reports -> the sub-packages it may import (besides itself)
ALLOWED = {
    "registry": set(),
    "store": {"registry"},
    "compare": {"registry"},
    "studies": {"registry", "store", "compare"},
    "run": {"registry", "store", "compare", "studies"},
    "render": {"registry", "store", "compare", "studies"},
    # the plugins' face (reports.plugin): the registry's names a plugin uses, lazily
    "plugin": {"registry"},
    # the command line, on top: parses, dispatches, and calls run/ and render/
    "cli": {"registry", "store", "compare", "studies", "run", "render"},
}

#: rooms of fem_reference, lowest first: a room imports only the rooms before it (and
#: fem_reference.errors, below every room); the modules on top (run, loading, fretting,
#: output, solver, cost) may import any room, and no room imports them
FEM_ROOMS = ("contact", "model", "fields")


def modules() -> dict[str, Path]:
    """Dotted name -> file of every module of the five packages."""
    out = {}
    for pkg in PACKAGES:
        for path in sorted((ROOT / pkg).rglob("*.py")):
            parts = path.relative_to(ROOT).with_suffix("").parts
            if parts[-1] == "__init__":
                parts = parts[:-1]
            out[".".join(parts)] = path
    return out


def imports(name: str, path: Path) -> set[str]:
    """The project modules ``name`` imports (absolute names; a package's ``from pkg import
    mod`` resolved to the module)."""
    known = modules()
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            targets = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                up = package.split(".")[: len(package.split(".")) - node.level + 1]
                base = ".".join(up + ([base] if base else []))
            targets = [f"{base}.{a.name}" if f"{base}.{a.name}" in known else base
                       for a in node.names]
        else:
            continue
        for t in targets:
            while t and t not in known:
                t = t.rpartition(".")[0]
            if t and t.split(".")[0] in PACKAGES and t != name:
                found.add(t)
    return found


GRAPH = {name: imports(name, path) for name, path in modules().items()}


def room(name: str) -> str | None:
    """The sub-package of reports a module belongs to (None: the package's own files);
    the CLI package's face is the CLI too."""
    parts = name.split(".")
    if name == "reports.cli":
        return "cli"
    return parts[1] if parts[0] == "reports" and len(parts) > 2 else None


def test_every_module_of_reports_lives_in_a_sub_package():
    loose = [n for n in GRAPH if n.startswith("reports.") and room(n) is None
             and n != "reports.__main__"
             and n.rpartition(".")[2] not in ALLOWED]
    assert loose == []


@pytest.mark.parametrize("name", sorted(n for n in GRAPH if room(n)))
def test_layers_of_reports(name):
    here = room(name)
    bad = sorted(t for t in GRAPH[name] if t.startswith("reports")
                 and room(t) != here and room(t) not in ALLOWED[here])
    assert bad == [], f"{name} ({here}/) may import only {sorted(ALLOWED[here])}"


def test_nothing_imports_the_cli():
    assert sorted(n for n, deps in GRAPH.items()
                  if any(d == "reports.cli" or d.startswith("reports.cli.") for d in deps)
                  and n != "reports.__main__" and room(n) != "cli") == []


def test_only_the_registry_knows_the_solver_packages():
    bad = sorted(f"{n} -> {t}" for n, deps in GRAPH.items() for t in deps
                 if room(n) not in (None, "registry") and n.startswith("reports")
                 and t.split(".")[0] in SOLVERS)
    assert bad == []


def test_solver_packages_are_independent():
    """halfspace and fem_reference share no code (their agreement is the evidence), and no
    solver imports reports."""
    bad = sorted(f"{n} -> {t}" for n, deps in GRAPH.items() for t in deps
                 if (n.startswith("halfspace") and t.startswith("fem_reference"))
                 or (n.startswith("fem_reference") and t.startswith("halfspace"))
                 or (n.split(".")[0] in SOLVERS + ("cases",) and t.startswith("reports")))
    assert bad == []


def test_external_results_read_files_with_the_cases_package_only():
    """A reader of another code's files shares nothing with the solvers it is compared
    with (external_results)."""
    bad = sorted(f"{n} -> {t}" for n, deps in GRAPH.items() for t in deps
                 if n.startswith("external_results")
                 and t.split(".")[0] not in ("external_results", "cases"))
    assert bad == []


def absolute_imports(folder: Path) -> list[tuple[Path, str]]:
    """(file, module) of every absolute import of the Python files under ``folder``."""
    out = []
    for path in sorted(folder.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            names = ([a.name for a in node.names] if isinstance(node, ast.Import) else
                     [node.module or ""] if isinstance(node, ast.ImportFrom) and not node.level
                     else [])
            out += [(path, n) for n in names]
    return out


@pytest.mark.parametrize("package", ["kratos_adapter", "calculix_adapter"])
def test_the_finite_element_plugins_share_no_solver_code(package):
    """kratos_adapter and calculix_adapter are second FEM references (issues 60, 74):
    their agreement with fem_reference is evidence only if they share no mesh, contact,
    kernel or stress code with fem_reference, halfspace or analytic (the case model, the
    result container and the registry's record are the shared pieces)."""
    bad = [f"{path.name}: {n}" for path, n in absolute_imports(ROOT / package)
           if n.split(".")[0] in ("fem_reference", "halfspace", "analytic")]
    assert bad == []


def test_no_import_circle():
    """Depth-first search for a back edge over the project's module graph."""
    state: dict[str, int] = {}
    cycle: list[str] = []

    def visit(n: str, path: list[str]) -> bool:
        state[n] = 1
        for t in sorted(GRAPH.get(n, ())):
            if state.get(t) == 1:
                cycle.extend(path[path.index(t):] + [n, t] if t in path else [n, t])
                return True
            if t not in state and visit(t, path + [n]):
                return True
        state[n] = 2
        return False

    for n in sorted(GRAPH):
        if n not in state and visit(n, []):
            break
    assert cycle == []


def test_reading_results_loads_no_running_machinery():
    """``report`` and ``gate`` (render/) reach nothing of run/, not even through another
    module."""
    seen, todo = set(), [n for n in GRAPH if room(n) == "render"]
    while todo:
        n = todo.pop()
        if n not in seen:
            seen.add(n)
            todo += GRAPH.get(n, ())
    assert sorted(n for n in seen if room(n) == "run") == []


def fem_room(name: str) -> str | None:
    """The room of fem_reference a module belongs to (None: a module on top)."""
    parts = name.split(".")
    return parts[1] if parts[0] == "fem_reference" and len(parts) > 2 else None


def test_every_module_of_fem_reference_below_the_top_lives_in_a_room():
    assert sorted({fem_room(n) for n in GRAPH} - {None}) == sorted(FEM_ROOMS)


@pytest.mark.parametrize("name", sorted(n for n in GRAPH if fem_room(n)))
def test_layers_of_fem_reference(name):
    here = FEM_ROOMS.index(fem_room(name))
    allowed = {f"fem_reference.{r}" for r in FEM_ROOMS[: here + 1]}
    bad = sorted(t for t in GRAPH[name] if t.startswith("fem_reference")
                 and t != "fem_reference.errors"
                 and not any(t == a or t.startswith(a + ".") for a in allowed))
    assert bad == [], f"{name} may import only {sorted(allowed)} and fem_reference.errors"


#: what a test module's name starts with: the package (room) it holds, or ``suite`` for
#: the product as a whole (the chain, the gate's error rates, the docs, determinism)
TEST_ROOMS = ("analytic", "cases", "fem", "halfspace", "reports", "cli", "tamaas",
              "benchmarks", "suite", "external", "contactmechanics", "kratos",
              "calculix")


def test_every_test_module_names_its_room():
    """tests/ reads by room (issue 50): ``test_<room>_<what>.py``."""
    from pathlib import Path

    here = Path(__file__).resolve().parent
    stray = [p.name for p in here.glob("test_*.py")
             if p.name.removeprefix("test_").split("_")[0] not in TEST_ROOMS]
    assert stray == []


def test_no_module_over_400_lines_no_function_over_80():
    """Small modules, short functions (issue 50): the packages' modules hold at most 400
    lines, their functions at most 80."""
    import ast
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]
    long = []
    for package in ("halfspace", "fem_reference", "analytic", "cases", "reports",
                    "tamaas_adapter", "external_results", "contactmechanics_adapter",
                    "kratos_adapter", "calculix_adapter"):
        for path in sorted((root / package).rglob("*.py")):
            text = path.read_text()
            if text.count("\n") > 400:
                long.append(f"{path.relative_to(root)}: {text.count(chr(10))} lines")
            long += [f"{path.relative_to(root)}:{node.lineno} {node.name}: "
                     f"{node.end_lineno - node.lineno + 1} lines"
                     for node in ast.walk(ast.parse(text))
                     if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef)
                     and node.end_lineno - node.lineno + 1 > 80]
    assert long == []
