"""The solver registry: names -> lazily imported entry points ``solve(case, progress)``.

Solvers are resolved only when used, so a solver whose package has not landed (or fails
to import) is reported as unavailable without breaking the others.  Each entry point
takes a :class:`cases.model.Case` and returns a :class:`cases.result.RunResult`.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable

from cases.model import Case
from cases.result import RunResult

from .errors import SolverUnavailable

SolveFn = Callable[..., RunResult]

#: solver name -> "module:function"; the order is the order of columns, rows and pairs.
REGISTRY: dict[str, str] = {
    "ic": "halfspace:solve",
    "fem": "fem_reference:solve",
    "analytic": "cases.analytic.solver:solve",
}

#: solver name -> "module:function" deciding whether the solver applies to a case.
#: ``has_solution`` is required of the analytic references (a case without one is not
#: theirs); ``supports`` is optional for the numerical solvers (without it they claim
#: every case, and a case they cannot handle fails loudly).
APPLICABLE: dict[str, str] = {
    "ic": "halfspace:supports",
    "fem": "fem_reference:supports",
    "analytic": "cases.analytic.solver:has_solution",
}
REQUIRED_APPLICABILITY = frozenset({"analytic"})


def _import(target: str) -> Callable:
    module_name, _, attr = target.partition(":")
    try:
        module = importlib.import_module(module_name)
    except ImportError as exc:
        raise SolverUnavailable(f"cannot import {module_name} ({exc})") from None
    fn = getattr(module, attr, None)
    if not callable(fn):
        raise SolverUnavailable(f"{module_name} has no entry point {attr}()")
    return fn


def names() -> list[str]:
    """All registered solver names, in registry order."""
    return list(REGISTRY)


def resolve(name: str) -> SolveFn:
    """The entry point of solver ``name``; :class:`SolverUnavailable` if it cannot load."""
    if name not in REGISTRY:
        raise SolverUnavailable(
            f"unknown solver {name!r} (known: {', '.join(REGISTRY)})"
        )
    try:
        return _import(REGISTRY[name])
    except SolverUnavailable as exc:
        raise SolverUnavailable(f"solver {name!r} is not available: {exc}") from None


def available(name: str) -> tuple[bool, str]:
    """(True, '') if solver ``name`` loads, else (False, reason)."""
    try:
        resolve(name)
    except SolverUnavailable as exc:
        return False, str(exc)
    return True, ""


def applies(name: str, case: Case) -> bool:
    """Whether solver ``name`` has anything to say about ``case`` (e.g. an analytic solution).

    A solver without an applicability test applies to every case, unless the test is
    required of it (:data:`REQUIRED_APPLICABILITY`) and cannot be imported.
    """
    target = APPLICABLE.get(name)
    if target is None:
        return True
    try:
        fn = _import(target)
    except SolverUnavailable:
        return name not in REQUIRED_APPLICABILITY
    return bool(fn(case))
