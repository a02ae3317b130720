"""Finite-element contact reference (scikit-fem on gmsh meshes): P2 elasticity of finite
blocks, condensed onto the contact surface, and a semi-smooth Newton contact solve.

Shares nothing with ``halfspace`` but the case model and the result container.

Rooms, in their order of dependence (``tests/test_suite_architecture.py``): :mod:`.contact`
(laws and solves on the condensed surface) < :mod:`.model` (mesh, elasticity, block,
surface, shape) < :mod:`.fields` (sampling, contact zone, stresses, planes, VTU); on top
the run (:mod:`.run`), its load paths (:mod:`.loading`, :mod:`.fretting`), the common
result (:mod:`.output`), the entry (:mod:`.solver`) and the cost estimate
(:mod:`.cost`). :mod:`.errors` is below every room.

Public API:

- :func:`solve` ``(case, *, progress=False, on_output=None, vtu=True, log=None)`` with
  solver name ``"fem"`` (see :mod:`fem_reference.solver`: the load path is in
  :mod:`fem_reference.loading`, the fields in :mod:`fem_reference.output`);
- :func:`write_vtu` ``(path, mesh)`` writes one of the ``RunResult.meta["vtu"]``
  ``(step, meshio.Mesh)`` meshes for ParaView; :func:`read_vtu` reads it back;
- :func:`estimate` ``(case) -> cases.result.Cost``: peak memory and wall time of a run,
  before any meshing (:mod:`fem_reference.cost`);
- :class:`FemUnsupported` (a ``CaseError``: the case needs a feature the model does not
  have, e.g. P1), :class:`FemError` (a failure such as the contact leaving
  the FE contact zone), :class:`MeshError` (gmsh failed) and
  :class:`ContactNotConverged` (contact iteration failed; message has the residual).
"""

from collections.abc import Callable

from cases.model import Case, one_case
from cases.result import Cost, RunResult, StepResult

from .errors import ContactNotConverged, FemError, FemUnsupported, MeshError
from .fields.vtu import read_vtu, write_vtu
from .solver import solve as _solve


def solve(case: Case, *, progress: bool = False,
          on_output: Callable[[StepResult], None] | None = None, vtu: bool = True,
          log=None) -> RunResult:
    """Run the FEM reference on ``case`` (:func:`fem_reference.solver.solve`);
    ``on_output`` receives each output step as soon as it is computed."""
    return _solve(one_case(case, "fem_reference"), progress, vtu=vtu, log=log,
                  on_output=on_output)


def supports(case: Case) -> str | None:
    """None when the FE model implements the case (P2 elements; static, sliding-wear and
    fretting cases), else why not."""
    if case.kind not in ("static", "sliding_wear", "fretting"):
        return f"kind {case.kind!r} is not implemented by the FEM reference"
    if case.fem.order != 2:
        return f"fem.order = {case.fem.order}: the FEM reference implements P2 only"
    if case.solver.wear_spread > 0 and case.kind in ("sliding_wear", "fretting"):
        return (f"solver.wear_spread = {case.solver.wear_spread:g} mm is the half-space "
                "solver's resolution probe (its wear increments spread over a length); "
                "the FEM's wear is its own nodes'")
    if case.fretting is not None and case.fretting.transverse == "free":
        from .model.shape import choose_shape

        if choose_shape(case) != "half":
            return ("fretting.transverse = 'free' with the friction axes oblique to the "
                    "motion: the FEM's mixed control (Qy = 0) does not converge in gross "
                    "slip (docs/fem-notes.md, part 5); along the axes it is the held "
                    "reading, which the FEM runs")
    return None


def estimate(case: Case) -> Cost:
    """Peak memory [bytes] and wall time [s] the FEM reference expects ``case`` to take,
    with the case keys that drive each, before any meshing (:mod:`fem_reference.cost`)."""
    from .cost import estimate as _estimate

    return _estimate(case)


__all__ = [
    "supports", "estimate",
    "solve", "write_vtu", "read_vtu", "FemError", "FemUnsupported", "MeshError",
    "ContactNotConverged",
]
