"""The solver protocol: adding a solver is one registry record and one package, and the
reports know solvers only through the registry."""

from __future__ import annotations

import ast
import sys
import textwrap
from dataclasses import replace
from pathlib import Path

import pandas as pd
import pytest

from reports.cli import main
from reports.registry import solvers, tolerances

ROOT = Path(__file__).resolve().parent.parent

TOY = '''
"""A toy fourth solver: the analytic reference with the peak pressure 0.5 % high."""
import analytic


def solve(case, *, progress=False, on_output=None):
    result = analytic.solve(case)
    for step in result.steps:
        step.scalars["p_max"] *= 1.005
        if on_output is not None:
            on_output(step)
    return result


def supports(case):
    return analytic.supports(case)
'''


def toy_budget(quantity: str, metric: str) -> float:
    return 0.02


@pytest.fixture
def toy(tmp_path, monkeypatch):
    (tmp_path / "toy_solver").mkdir()
    (tmp_path / "toy_solver" / "__init__.py").write_text(textwrap.dedent(TOY))
    monkeypatch.syspath_prepend(str(tmp_path))
    registry = dict(solvers.REGISTRY)
    registry = {"ic": registry["ic"],
                "toy": solvers.SolverRecord("toy", "toy_solver", budget=toy_budget,
                                            style={"color": "C2", "ls": "-."},
                                            cell_size=solvers.no_cell),
                "analytic": registry["analytic"]}
    monkeypatch.setattr(solvers, "REGISTRY", registry)
    yield
    sys.modules.pop("toy_solver", None)


def test_a_fourth_solver_is_one_record_and_one_package(tmp_path, toy):
    out = tmp_path / "res"
    assert main(["run", "hertz", "--quick", "--no-progress", "--solver", "ic,toy,analytic",
                 "--out", str(out)]) == 0
    summary = pd.read_csv(out / "hertz" / "summary.csv")
    assert list(summary["solver"]) == ["ic", "toy", "analytic"]
    m = pd.read_csv(out / "hertz" / "metrics.csv")
    assert set(m["pair"]) == {"ic-toy", "ic-analytic", "toy-analytic"}
    row = m[(m.pair == "toy-analytic") & (m.quantity == "p_max")].iloc[0]
    assert row["value"] == pytest.approx(0.005, rel=1e-9)
    # the default tolerance is the sum of the two records' budgets (hertz.toml sets its
    # own p_max tolerance, so look at a quantity it leaves to the defaults)
    row = m[(m.pair == "toy-analytic") & (m.quantity == "p_n") & (m.metric == "l2")].iloc[0]
    assert row["value"] == 0.0
    assert row["tolerance"] == pytest.approx(0.02 + 0.01, rel=1e-12)
    assert row["tolerance_key"] == "default:p_n_l2"
    assert tolerances.default_tolerance("ic-toy", "vm_max", "rel") == pytest.approx(0.015 + 0.02)
    assert main(["report", "--out", str(out)]) == 0
    assert main(["gate", "--out", str(out)]) == 0


def test_a_solver_without_the_protocol_is_unavailable(monkeypatch):
    broken = replace(solvers.REGISTRY["ic"], supports_attr="no_such_function")
    monkeypatch.setitem(solvers.REGISTRY, "ic", broken)
    ok, reason = solvers.available("ic")
    assert not ok and "halfspace has no entry point no_such_function()" in reason


@pytest.mark.parametrize("name", ["ic", "fem", "analytic"])
def test_every_package_follows_the_protocol(name):
    rec = solvers.REGISTRY[name]
    assert solvers.available(name) == (True, "")
    import inspect

    params = inspect.signature(rec.entry("solve")).parameters
    assert params["progress"].kind is inspect.Parameter.KEYWORD_ONLY
    assert params["on_output"].kind is inspect.Parameter.KEYWORD_ONLY


def _literals(path: Path) -> list[tuple[int, str]]:
    tree = ast.parse(path.read_text())
    return [(node.lineno, node.value) for node in ast.walk(tree)
            if isinstance(node, ast.Constant) and isinstance(node.value, str)]


def test_reports_name_no_solver_outside_the_registry():
    names = set(solvers.REGISTRY)
    pairs = {f"{a}-{b}" for a in names for b in names if a != b}
    found = [f"{p.name}:{line} {value!r}"
             for p in sorted((ROOT / "reports").glob("*.py")) if p.name != "solvers.py"
             for line, value in _literals(p) if value in names | pairs]
    assert not found, "solver names outside reports/registry/solvers.py: " + ", ".join(found)
