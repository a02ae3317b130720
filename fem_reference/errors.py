"""The FEM reference's errors."""

from __future__ import annotations

from cases.model import CaseError


class FemError(RuntimeError):
    """The FEM reference failed on this case (the message names the cause)."""


class FemUnsupported(FemError, CaseError):
    """The case needs a feature the FEM reference does not have (also a CaseError)."""
