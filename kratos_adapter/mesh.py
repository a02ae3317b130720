"""The two bodies of a sphere-on-plane case as quarter models meshed by gmsh with linear
tetrahedra (Kratos' mortar contact conditions are linear triangles).

Body b (the plane) is the block [0, L] x [0, L] x [-H, 0]; body a (the sphere) the block
[0, L] x [0, L] x [0, H] whose lower face is carried onto the sphere's profile
z = r² / 2R by the map z -> z + (r² / 2R)(1 - z / H) (the profile of the closed forms and
of the half-space solver; the map moves the nodes by at most r²/2R, 0.2 % of L at the
block's corner for the bundled Hertz case, and leaves the top face flat).  Global z
points into body a (README, Conventions).  The element size is ``h`` within
:data:`FINE_RADIUS` a0 of the contact centre and grows linearly to :data:`COARSE` L at
the distance L; both bodies have the same sizes, so the two contact faces' nodes nearly
coincide where they touch.

No code is shared with ``fem_reference`` (whose agreement with this model is the
evidence); only gmsh itself is common to both.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: the refined zone: a ball of this many a0 around the contact centre, on both sides
FINE_RADIUS = 2.5
#: the largest element, a fraction of the block's side L
COARSE = 0.25


@dataclass(frozen=True)
class Body:
    """One meshed quarter body: node coordinates (n, 3), tetrahedra (m, 4) as indices into
    them, the contact face's triangles (k, 3), and the node indices of its faces by name
    (``x0``, ``y0``: the symmetry planes; ``far``: the face opposite the contact)."""

    nodes: np.ndarray
    tets: np.ndarray
    contact: np.ndarray
    faces: dict[str, np.ndarray]


def _box(z0: float, side: float, height: float, h: float, fine: float) -> Body:
    import gmsh

    gmsh.model.add("kratos_body")
    gmsh.model.occ.addBox(0.0, 0.0, z0, side, side, height)
    gmsh.model.occ.synchronize()
    origin = gmsh.model.occ.addPoint(0.0, 0.0, 0.0)
    gmsh.model.occ.synchronize()
    fields = gmsh.model.mesh.field
    dist = fields.add("Distance")
    fields.setNumbers(dist, "PointsList", [origin])
    thr = fields.add("Threshold")
    fields.setNumber(thr, "InField", dist)
    fields.setNumber(thr, "SizeMin", h)
    fields.setNumber(thr, "SizeMax", COARSE * side)
    fields.setNumber(thr, "DistMin", fine)
    fields.setNumber(thr, "DistMax", side)
    fields.setAsBackgroundMesh(thr)
    gmsh.model.mesh.generate(3)
    tags, coords, _ = gmsh.model.mesh.getNodes()
    index = np.full(int(tags.max()) + 1, -1, dtype=np.int64)
    index[tags.astype(np.int64)] = np.arange(tags.size)
    nodes = coords.reshape(-1, 3)
    _, conn = gmsh.model.mesh.getElementsByType(4)  # 4-node tetrahedra
    tets = index[conn.astype(np.int64)].reshape(-1, 4)
    used = np.unique(tets)
    # the surfaces of the box, found by their position
    top = z0 + height
    contact_z = top if z0 < 0 else z0  # the face at z = 0
    faces, contact = {}, None
    for dim, tag in gmsh.model.getEntities(2):
        c = gmsh.model.occ.getCenterOfMass(dim, tag)
        ntags, _, _ = gmsh.model.mesh.getNodes(dim, tag, includeBoundary=True)
        ids = index[ntags.astype(np.int64)]
        if abs(c[0]) < 1e-12 * side:
            faces["x0"] = ids
        elif abs(c[1]) < 1e-12 * side:
            faces["y0"] = ids
        elif abs(c[2] - contact_z) < 1e-9 * side:
            _, tri = gmsh.model.mesh.getElementsByType(2, tag)
            contact = index[tri.astype(np.int64)].reshape(-1, 3)
            faces["contact"] = ids
        elif abs(c[2] - (z0 if z0 < 0 else top)) < 1e-9 * side:
            faces["far"] = ids
    gmsh.model.remove()
    # the contact face's triangles turned to its outward normal (+z on body b, -z on a):
    # Kratos' mortar conditions take their normals from the node order
    tri = nodes[contact]
    nz = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])[:, 2]
    outward = 1.0 if z0 < 0 else -1.0
    flip = nz * outward < 0
    contact[flip] = contact[flip][:, ::-1]
    # keep only the nodes of the volume mesh (gmsh's stray points are not used)
    renum = np.full(nodes.shape[0], -1, dtype=np.int64)
    renum[used] = np.arange(used.size)
    return Body(nodes=nodes[used].copy(), tets=renum[tets], contact=renum[contact],
                faces={k: np.unique(renum[v]) for k, v in faces.items()})


def mesh_bodies(a0: float, R: float, h: float, side: float, height: float,
                master: float = 1.0) -> tuple[Body, Body]:
    """(body a, body b): the quarter sphere cap and the quarter block (module doc), with
    element size ``h`` [mm] near the contact, side L = ``side`` and height H = ``height``."""
    import gmsh

    started = gmsh.isInitialized()
    if not started:
        gmsh.initialize(interruptible=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", 1)
        gmsh.option.setNumber("Mesh.MaxNumThreads3D", 1)
        gmsh.option.setNumber("Mesh.RandomSeed", 1)
        gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
        gmsh.option.setNumber("Mesh.Algorithm", 6)
        gmsh.option.setNumber("Mesh.Algorithm3D", 1)
        gmsh.option.setNumber("Mesh.Optimize", 1)
        fine = FINE_RADIUS * a0
        b = _box(-height, side, height, h, fine)
        a = _box(0.0, side, height, master * h, fine)
    finally:
        if not started:
            gmsh.finalize()
    x, y, z = a.nodes.T
    a.nodes[:, 2] = z + (x**2 + y**2) / (2.0 * R) * (1.0 - z / height)
    return a, b
