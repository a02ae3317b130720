"""The Kratos solution on the case's grid and planes, mirrored from the quarter model.

- Surface pressure: the slave face's nodal pressures (the sphere's face, body a)
  interpolated linearly on its facets (each quadrilateral split in two triangles) at
  the cell centres (x, y) of the case grid, each centre taken to the quarter (|x|, |y|)
  (the frictionless contact is symmetric about both planes); 0 outside the face.
- Stresses: each element's stresses at its nodes (a hexahedron's Gauss-point values
  extrapolated to its corners, :func:`kratos_adapter.model.extrapolate`) averaged at
  every node over the elements that share it, weighted by their volumes, and
  interpolated linearly inside the element (split in six tetrahedra) that contains each
  sample point of the planes (xz through y0, yz through x0, the depths ``stress.z``
  into the reported body).  Mirroring x -> -x changes the sign of σ_xy and σ_xz,
  y -> -y that of σ_xy and σ_yz.
"""

from __future__ import annotations

import numpy as np

from cases.result import Plane, von_mises

COMPONENTS = ("sxx", "syy", "szz", "sxy", "sxz", "syz")
#: the sign of each component when x (first) or y (second) is mirrored
MIRROR = {"sxx": (1, 1), "syy": (1, 1), "szz": (1, 1), "sxy": (-1, -1), "sxz": (-1, 1),
          "syz": (1, -1)}


def surface(nodes: np.ndarray, triangles: np.ndarray, values: np.ndarray,
            x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """``values`` at ``nodes`` interpolated linearly on ``triangles`` (their x, y; a
    quadrilateral face split in two) at the points (x[i], y[j]) taken to the quarter,
    (nx, ny); 0 outside the face."""
    import matplotlib.tri as mtri

    if triangles.shape[1] == 4:
        triangles = np.concatenate([triangles[:, [0, 1, 2]], triangles[:, [0, 2, 3]]])
    used = np.unique(triangles)
    renum = np.full(nodes.shape[0], -1, dtype=np.int64)
    renum[used] = np.arange(used.size)
    tri = mtri.Triangulation(nodes[used, 0], nodes[used, 1], renum[triangles])
    interp = mtri.LinearTriInterpolator(tri, values[used])
    X, Y = np.meshgrid(np.abs(x), np.abs(y), indexing="ij")
    out = interp(X.ravel(), Y.ravel())
    return np.ma.filled(out, 0.0).reshape(X.shape)


#: a hexahedron (Kratos' node order) as six tetrahedra around its diagonal 0-6
HEX_TETS = np.array([[0, 1, 2, 6], [0, 2, 3, 6], [0, 3, 7, 6], [0, 7, 4, 6], [0, 4, 5, 6],
                     [0, 5, 1, 6]])


def as_tets(cells: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(tetrahedra, the cell each comes from): tetrahedra as they are, hexahedra split
    into :data:`HEX_TETS`."""
    if cells.shape[1] == 4:
        return cells, np.arange(cells.shape[0])
    tets = cells[:, HEX_TETS].reshape(-1, 4)
    return tets, np.repeat(np.arange(cells.shape[0]), HEX_TETS.shape[0])


def nodal_stresses(nodes: np.ndarray, cells: np.ndarray, stress: np.ndarray) -> np.ndarray:
    """The cells' stresses at their nodes (m, nodes per cell, 6) averaged at each node
    (n, 6) over the cells that share it, weighted by their volumes."""
    tets, parent = as_tets(cells)
    p = nodes[tets]
    vol = np.abs(np.einsum("ij,ij->i", np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]),
                           p[:, 3] - p[:, 0])) / 6.0
    vol = np.bincount(parent, weights=vol, minlength=cells.shape[0])
    acc = np.zeros((nodes.shape[0], 6))
    wsum = np.zeros(nodes.shape[0])
    for k in range(cells.shape[1]):
        np.add.at(acc, cells[:, k], stress[:, k] * vol[:, None])
        np.add.at(wsum, cells[:, k], vol)
    return acc / np.where(wsum > 0, wsum, 1.0)[:, None]


def locate(nodes: np.ndarray, tets: np.ndarray, points: np.ndarray, candidates: int = 24
           ) -> tuple[np.ndarray, np.ndarray]:
    """(element, barycentric coordinates (k, 4)) of each point: the element among the
    ``candidates`` nearest by centroid whose smallest barycentric coordinate is largest
    (inside, or the nearest to inside for a point on the boundary)."""
    from scipy.spatial import cKDTree

    p = nodes[tets]
    centroids = p.mean(axis=1)
    _, near = cKDTree(centroids).query(points, k=min(candidates, len(tets)))
    T = np.stack([p[:, 1] - p[:, 0], p[:, 2] - p[:, 0], p[:, 3] - p[:, 0]], axis=-1)
    Tinv = np.linalg.inv(T)  # (m, 3, 3)
    rel = points[:, None, :] - p[near, 0]  # (k, c, 3)
    lam = np.einsum("kcij,kcj->kci", Tinv[near], rel)
    bary = np.concatenate([1.0 - lam.sum(axis=-1, keepdims=True), lam], axis=-1)
    best = np.argmax(bary.min(axis=-1), axis=1)
    rows = np.arange(points.shape[0])
    return near[rows, best], bary[rows, best]


def planes(nodes: np.ndarray, cells: np.ndarray, stress: np.ndarray, *, x: np.ndarray,
           y: np.ndarray, z: np.ndarray, x0: float, y0: float, sign_z: float
           ) -> dict[str, Plane]:
    """The xz plane (at y = ``y0``, along ``x``) and the yz plane (at x = ``x0``, along
    ``y``) at the depths ``z`` into the reported body (global z = ``sign_z`` · depth),
    with σ_VM, from the stresses at the nodes of each cell (m, nodes per cell, 6) of
    that body's quarter mesh (:func:`nodal_stresses`)."""
    nodal = nodal_stresses(nodes, cells, stress)
    tets, _ = as_tets(cells)
    out = {}
    for name, s in (("xz", x), ("yz", y)):
        S, Z = np.meshgrid(s, z, indexing="ij")
        px = S if name == "xz" else np.full_like(S, x0)
        py = np.full_like(S, y0) if name == "xz" else S
        pts = np.stack([np.abs(px).ravel(), np.abs(py).ravel(), sign_z * Z.ravel()], axis=1)
        elem, bary = locate(nodes, tets, pts)
        values = np.einsum("kn,knc->kc", bary, nodal[tets[elem]])
        fields = {}
        for c, name_c in enumerate(COMPONENTS):
            sx, sy = MIRROR[name_c]
            sign = np.where(px.ravel() < 0, sx, 1) * np.where(py.ravel() < 0, sy, 1)
            fields[name_c] = (sign * values[:, c]).reshape(S.shape)
        fields["vm"] = von_mises(*(fields[c] for c in COMPONENTS))
        out[name] = Plane(s=np.asarray(s, float).copy(), z=np.asarray(z, float).copy(),
                          fields=fields)
    return out
