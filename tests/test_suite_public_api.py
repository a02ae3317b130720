"""The packages' public faces (issue 61, point 2): each package lists its public names in
``__all__``, they resolve, they stay what this test says (a change to them is a change
of the API, made here on purpose), a room's face is exactly the modules the other rooms
import, and the README's and the examples' code imports public names only."""

from __future__ import annotations

import ast
import importlib
import re
from pathlib import Path

import pytest
from test_suite_architecture import GRAPH

ROOT = Path(__file__).resolve().parents[1]

#: package -> its public names
FACES = {
    "halfspace": ["estimate", "solve", "supports"],
    "analytic": None,  # checked for resolving only (its closed forms are many)
    "cases": ["BUNDLED", "Case", "CaseError", "Cost", "Plane", "RunResult", "StepResult",
              "load_case", "load_point", "one_case"],
    "fem_reference": ["ContactNotConverged", "FemError", "FemUnsupported", "MeshError",
                      "estimate", "read_vtu", "solve", "supports", "write_vtu"],
    "reports": ["CaseRun", "RunFailed", "SolverRecord", "UserError", "compare_point", "main",
                "run_case", "run_gate", "traction_profiles", "write_report"],
    # the face of a solver plugin (issue 76, point 3)
    "reports.plugin": ["Case", "CaseError", "Cost", "Plane", "RunResult", "SolverRecord",
                       "SolverUnavailable", "StepResult", "UserError", "grid_budget",
                       "refine_fem", "refine_grid", "silenced"],
}
#: the rooms, whose faces are their modules that other rooms import
ROOMS = ["reports.registry", "reports.store", "reports.compare", "reports.studies",
         "reports.run", "reports.render", "fem_reference.contact", "fem_reference.model",
         "fem_reference.fields"]


@pytest.mark.parametrize("name", sorted(FACES))
def test_every_public_name_resolves_and_stays(name):
    module = importlib.import_module(name)
    assert module.__doc__ and len(module.__doc__.strip()) > 40
    assert all(getattr(module, n, None) is not None for n in module.__all__), name
    if FACES[name] is not None:
        assert sorted(module.__all__) == sorted(FACES[name])


@pytest.mark.parametrize("room", ROOMS)
def test_a_rooms_face_is_what_the_other_rooms_import(room):
    used = sorted({t.split(".")[2] for n, targets in GRAPH.items()
                   if not n.startswith(room + ".") and n != room
                   for t in targets if t.startswith(room + ".")})
    module = importlib.import_module(room)
    assert sorted(module.__all__) == used, f"{room}: list what other rooms import"
    for name in module.__all__:
        importlib.import_module(f"{room}.{name}")


def test_reports_imports_nothing_until_asked():
    import subprocess
    import sys

    code = ("import sys, reports; print(sorted(m for m in sys.modules "
            "if m.startswith('reports.')))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, cwd=ROOT).stdout
    assert out.strip() == "[]"


def _imports(source: str) -> list[tuple[str, str]]:
    """(module, name) of every ``from module import name`` and ``import module``."""
    out = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.ImportFrom) and node.module and not node.level:
            out += [(node.module, a.name) for a in node.names]
        elif isinstance(node, ast.Import):
            out += [(a.name, "") for a in node.names]
    return out


def _markdown_code(path: Path) -> str:
    """The Python of a Markdown file's ``python`` blocks: a doctest block's input lines, a
    plain block whole."""
    blocks = re.findall(r"```python\n(.*?)```", path.read_text(encoding="utf-8"), flags=re.S)
    out = []
    for b in blocks:
        lines = b.splitlines()
        if any(line.startswith(">>> ") for line in lines):
            lines = [line[4:] for line in lines if line.startswith((">>> ", "... "))]
        out += lines
    return "\n".join(out)


@pytest.mark.parametrize("where", ["README.md", "reports/README.md",
                                   "docs/examples/solver_plugin",
                                   "docs/examples/external_results"])
def test_the_documentation_imports_public_names_only(where):
    path = ROOT / where
    if path.is_file():
        sources = [_markdown_code(path)]
    else:
        sources = [p.read_text(encoding="utf-8") for p in sorted(path.rglob("*.py"))]
    found = [i for s in sources for i in _imports(s)
             if i[0].split(".")[0] in FACES]
    assert found, where
    for module, name in found:
        assert module in FACES, f"{where} imports {module}.{name}: not a package's face"
        if name:
            assert name in importlib.import_module(module).__all__, (where, module, name)
