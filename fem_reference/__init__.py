"""Finite-element penalty-contact reference (scikit-fem on gmsh meshes).

Shares nothing with ``halfspace`` but the case model and the result container.

Public API:

- :func:`solve` ``(case, progress=False, *, vtu=True, log=None) -> RunResult`` with
  solver name ``"fem"`` (see :mod:`fem_reference.solver` for the fields and load path);
- :func:`write_vtu` ``(path, mesh)`` writes one of the ``RunResult.meta["vtu"]``
  ``(step, meshio.Mesh)`` meshes for ParaView; :func:`read_vtu` reads it back;
- :class:`FemUnsupported` (a ``CaseError``: the case needs a feature the model does not
  have, e.g. fretting or P1), :class:`FemError` (a failure such as the contact leaving
  the FE contact zone), :class:`MeshError` (gmsh failed) and
  :class:`ContactConvergenceError` (contact iteration failed; message has the residual).
"""

from cases.model import Case

from .contact import ContactConvergenceError
from .mesh import MeshError
from .model import FemError, FemUnsupported
from .solver import solve
from .vtu import read_vtu, write_vtu


def supports(case: Case) -> bool:
    """Whether the FE model implements the case: P2 elements, static and sliding-wear
    cases (fretting is not implemented; the runner skips it with a note)."""
    return case.kind in ("static", "sliding_wear") and case.fem.order == 2


__all__ = [
    "supports",
    "solve", "write_vtu", "read_vtu", "FemError", "FemUnsupported", "MeshError",
    "ContactConvergenceError",
]
