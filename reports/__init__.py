"""Running, comparing, reporting and gating: the machinery of the ``contact-vv`` command.

Public API (these names; the sub-packages' modules are the implementation and may
change):

- :func:`run_case` ``(case, solvers=None, *, out="results", quick=False,
  overrides=None) -> CaseRun``: ``contact-vv run CASE`` from Python;
- :func:`compare_point` ``(case, results) -> DataFrame``: the metric rows of one sweep
  point (the rows of ``metrics.csv``) from ``{solver: RunResult}``;
- :func:`write_report` ``(out) -> Path``: ``contact-vv report``;
- :func:`run_gate` ``(out, ...) -> int``: ``contact-vv gate``, its exit status;
- :func:`traction_profiles` ``(steps, a0, p0) -> Figure``: the report's profile plot;
- :class:`SolverRecord`: what a solver plugin declares (``reports/README.md``);
- :func:`main` ``(argv) -> int``: the command line itself;
- :class:`UserError`, :class:`RunFailed`: a bad request, a run or gate that failed.

The names are imported when first used, so ``import reports`` loads nothing else.
"""

from __future__ import annotations

from importlib import import_module
from typing import Any

#: public name -> the module that defines it
_HOMES = {
    "run_case": "reports.run.runner",
    "CaseRun": "reports.run.runner",
    "compare_point": "reports.compare.point",
    "write_report": "reports.render.pages",
    "run_gate": "reports.render.gate",
    "traction_profiles": "reports.render.plots",
    "SolverRecord": "reports.registry.record",
    "main": "reports.cli",
    "UserError": "reports.registry.errors",
    "RunFailed": "reports.registry.errors",
}

__all__ = sorted(_HOMES)


def __getattr__(name: str) -> Any:
    if name not in _HOMES:
        raise AttributeError(f"module 'reports' has no attribute {name!r}")
    value = getattr(import_module(_HOMES[name]), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
