"""The FEM reference's errors (below every room: any module may raise them)."""

from __future__ import annotations

from cases.model import CaseError


class FemError(RuntimeError):
    """The FEM reference failed on this case (the message names the cause)."""


class FemUnsupported(FemError, CaseError):
    """The case needs a feature the FEM reference does not have (also a CaseError)."""


class MeshError(RuntimeError):
    """The block mesh could not be built."""


class ContactNotConverged(RuntimeError):
    """The contact iteration did not converge; the message gives the residual."""
