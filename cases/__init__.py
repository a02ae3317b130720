"""Case definitions (TOML), their loader and validation, and the result container every
solver returns.

Public API: :func:`load_case` (every sweep point of a case file or bundled name),
:func:`load_point` (one), :data:`BUNDLED` (the bundled cases' names), :class:`Case` and
:class:`CaseError` (bad input, naming the key), :func:`one_case`; the result container
:class:`RunResult` of :class:`StepResult` steps with their stress :class:`Plane` fields,
and a solver's :class:`Cost` estimate."""

from .loader import BUNDLED, load_case, load_point
from .model import Case, CaseError, one_case
from .result import Cost, Plane, RunResult, StepResult

__all__ = ["BUNDLED", "Case", "CaseError", "Cost", "Plane", "RunResult", "StepResult",
           "load_case", "load_point", "one_case"]
