"""Influence-coefficient (boundary-element) solver on the elastic half-space.

Implements docs/formulation.md: kernels (Eq. 5, 41), FFT influence products,
orthotropic frictional contact (Eq. 7-17, §3.4), orthotropic Archard wear (Eq. 18-23)
and subsurface stresses (Eq. 32-34, Appendices A and C).

The solver protocol (:mod:`reports.registry.solvers`): :func:`solve` and :func:`supports`.
"""

from __future__ import annotations

from collections.abc import Callable

from cases.model import Case, one_case
from cases.result import Cost, RunResult, StepResult

KINDS = ("static", "sliding_wear", "fretting")


def solve(case: Case, *, progress: bool = False,
          on_output: Callable[[StepResult], None] | None = None) -> RunResult:
    """Solve a case (see :func:`halfspace.solver.solve`); solver name "ic".  ``on_output``
    receives each output step as soon as it is computed."""
    from .solver import solve as _solve

    return _solve(one_case(case, "halfspace"), progress=progress, on_output=on_output)


def estimate(case: Case) -> Cost:
    """Peak memory and wall time of :func:`solve` on ``case``, before any work
    (:mod:`halfspace.cost`)."""
    from .cost import estimate as _estimate

    return _estimate(case)


def supports(case: Case) -> str | None:
    """None: the half-space solver handles every kind of case."""
    return None if case.kind in KINDS else f"kind {case.kind!r} is not implemented"


__all__ = ["estimate", "solve", "supports"]
