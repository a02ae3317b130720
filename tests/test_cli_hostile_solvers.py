"""Solvers that raise or return nonsense (issue 59, point 5): a plugin's result is not
trusted.  Each probe runs the tiny case with a fake solver in the place of ``ic`` beside
the closed form; its expectation: the run exits 1 with one line naming the solver and
the cause (never a traceback, never the process ended by the solver), the results of
the run's other case directories untouched, and nothing reported as complete.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
import test_cli_fakes as fakes
from test_cli_hostile_inputs import TINY, _answer, hang_guard  # noqa: F401 (a fixture)

from cases.model import Case
from cases.result import RunResult


def _good(case: Case) -> RunResult:
    return fakes.solve_ic(case)


def returns_none(case, **kw):
    return None


def returns_text(case, **kw):
    return "converged"


def returns_no_steps(case, **kw):
    return replace(_good(case), steps=[])


supports_all = fakes.supports_all


def raises_runtime(case, **kw):
    raise RuntimeError("the plugin's own solver stalled at 1e-3")


def raises_value(case, **kw):
    raise ValueError("shapes (3,) and (4,) not aligned")


def exits(case, **kw):
    raise SystemExit(3)


def raises_memory(case, **kw):
    raise MemoryError("cannot allocate 80 GiB")


def nan_pressure(case, **kw):
    r = _good(case)
    r.steps[0].surface["p_n"][0, 0] = math.nan
    return r


def inf_load(case, **kw):
    r = _good(case)
    r.steps[0].scalars["P"] = math.inf
    return r


def nan_load(case, **kw):
    r = _good(case)
    r.steps[0].scalars["P"] = math.nan
    return r


def wrong_field_shape(case, **kw):
    r = _good(case)
    r.steps[0].surface["p_n"] = np.ones((3, 4))
    return r


def nan_stress(case, **kw):
    r = _good(case)
    plane = next(iter(r.steps[0].planes.values()))
    plane.fields["vm"] = np.full_like(plane.fields["vm"], np.nan)
    return r


def text_scalar(case, **kw):
    r = _good(case)
    r.steps[0].scalars["P"] = "ten"
    return r


# (id, the fake, the needle of its error line)
PROBES = [
    ("returns-none", "returns_none", "returned NoneType without output steps"),
    ("returns-text", "returns_text", "returned str without output steps"),
    ("returns-no-steps", "returns_no_steps", "without output steps"),
    ("raises-runtime", "raises_runtime", "stalled at 1e-3"),
    ("raises-value", "raises_value", "ValueError: shapes (3,) and (4,) not aligned"),
    ("exits", "exits", "SystemExit"),
    ("raises-memory", "raises_memory", "MemoryError"),
    ("nan-pressure", "nan_pressure", "non-finite values in surface p_n"),
    ("inf-load", "inf_load", "non-finite scalar P = inf"),
    ("nan-load", "nan_load", "non-finite scalar P = nan"),
    ("wrong-field-shape", "wrong_field_shape", "surface p_n"),
    ("nan-stress", "nan_stress", "non-finite values in plane"),
    ("text-scalar", "text_scalar", "scalar P"),
]


@pytest.mark.parametrize(("fake", "needle"), [p[1:] for p in PROBES],
                         ids=[p[0] for p in PROBES])
def test_a_solver_that_raises_or_returns_nonsense(tmp_path, capsys, monkeypatch, hang_guard,  # noqa: F811
                                                  fake, needle):
    registry = fakes.registry(ic="solve_ic", analytic="solve_exact")
    registry["ic"] = replace(registry["ic"], package=__name__, solve_attr=fake)
    from reports.registry import solvers

    monkeypatch.setattr(solvers, "REGISTRY", registry)
    (tmp_path / "c.toml").write_text(TINY)
    out = tmp_path / "out"
    out.mkdir()
    (out / "kept.txt").write_text("kept")
    code, err = _answer(["run", str(tmp_path / "c.toml"), "--solver", "ic,analytic",
                         "--no-progress", "--out", str(out)], capsys)
    assert code == 1, err
    lines = [line for line in err.splitlines() if line.startswith("contact-vv: error:")]
    assert len(lines) == 1 and "solver ic" in lines[0] and needle in lines[0], err
    assert (out / "kept.txt").read_text() == "kept"
    assert not (out / "c" / "summary.csv").exists()  # nothing reported as complete
