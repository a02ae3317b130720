"""FE fields as VTK unstructured grids (``.vtu``) for ParaView, through meshio.

The mesh is written with its quadratic tetrahedra (``tetra10``; the P2 node order of
:mod:`fem_reference.model.elasticity` is VTK's) in the block frame of the reported body:
x and y the global axes, Z = −depth (the body lies below its contact surface Z = 0).
Point data: ``displacement`` (3 components, mm), the stress components ``sxx, syy,
szz, sxy, sxz, syz`` in that frame and ``von_mises`` (MPa), volume-averaged at the
nodes from the exact element stresses; ``p_n, p_x, p_y`` (MPa) the nodal tractions of
the contact solve on body a at the contact surface's nodes (zero at the others), the
values the output's surface fields interpolate linearly on each facet's
sub-triangles.  A quarter or half model holds the modelled part only (ParaView's
Reflect filter restores the rest).  Written and read by the run's one .vtu writer,
:func:`cases.result.write_vtu` / :func:`cases.result.read_vtu` (re-exported here).
"""

from __future__ import annotations

import meshio
import numpy as np

from cases.result import read_vtu, von_mises, write_vtu

from ..model.elasticity import P2Space
from .stresses import COMPONENTS, nodal_stresses

__all__ = ["add_tractions", "fields_mesh", "read_vtu", "write_vtu"]

_PAIRS = ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2))


def fields_mesh(space: P2Space, u: np.ndarray, nu: float, E: float) -> meshio.Mesh:
    """A meshio mesh with the displacement ``u`` (3 * nnodes,) of a body (ν, E), its stresses."""
    sig = nodal_stresses(space, u, nu, E)
    point_data = {"displacement": u.reshape(-1, 3).copy()}
    comps = {}
    for name, (i, j) in zip(COMPONENTS, _PAIRS, strict=True):
        comps[name] = sig[:, i, j].copy()
    point_data.update(comps)
    point_data["von_mises"] = von_mises(*(comps[c] for c in COMPONENTS))
    return meshio.Mesh(
        points=space.nodes.T.copy(),
        cells=[("tetra10", space.element_nodes.T.astype(np.int64).copy())],
        point_data=point_data,
    )


def add_tractions(mesh: meshio.Mesh, nodes: np.ndarray, p_n: np.ndarray,
                  t: np.ndarray) -> meshio.Mesh:
    """``mesh`` with the point data ``p_n, p_x, p_y``: the nodal tractions ``p_n`` (k,)
    and ``t`` (k, 2) at its points ``nodes`` (k,), zero at the others."""
    n = len(mesh.points)
    for name, values in (("p_n", p_n), ("p_x", t[:, 0]), ("p_y", t[:, 1])):
        field = np.zeros(n)
        field[nodes] = values
        mesh.point_data[name] = field
    return mesh
