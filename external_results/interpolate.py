"""Interpolation of nodal values at the comparisons' sample points: on the contact
surface (triangles) and inside the body (tetrahedra).

- Surface: the facets of the file's cells that lie on the contact surface (depth 0):
  triangles; six-node triangles (and the faces of ten-node tetrahedra) split into their
  four sub-triangles, values linear on each — the monotone reconstruction of nodal
  tractions, which does not ring where a traction drops to zero inside a facet;
  quadrilaterals (faces of hexahedra) split in two.  Without such facets (a CSV table,
  a point cloud) the surface points' Delaunay triangulation.
- Volume: ten-node tetrahedra with their quadratic shape functions (a P2 field is
  reproduced exactly), four-node ones linearly; other cells or none: the points'
  Delaunay tetrahedra, linearly.

A point is located by the barycentric coordinates of the simplices whose centroids lie
nearest (a k-d tree), then among all simplices if none of those holds it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import Delaunay, cKDTree

#: sub-triangles of a six-node triangle (meshio/VTK order: vertices, then the edges
#: 01, 12, 20)
TRI6_SUB = np.array([[0, 3, 5], [3, 1, 4], [5, 4, 2], [3, 4, 5]])
#: faces of a ten-node tetrahedron as six-node triangles (edges 01, 12, 02, 03, 13, 23
#: are nodes 4..9)
TET10_FACES = np.array([[0, 1, 2, 4, 5, 6], [0, 1, 3, 4, 8, 7], [0, 2, 3, 6, 9, 7],
                        [1, 2, 3, 5, 9, 8]])
TET_FACES = TET10_FACES[:, :3]
HEX_FACES = np.array([[0, 1, 2, 3], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5],
                      [2, 3, 7, 6], [3, 0, 4, 7]])
#: the edges of the ten-node tetrahedron's nodes 4..9
TET10_EDGES = ((0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3))
CANDIDATES = 24  # simplices tried per point before all of them
INSIDE = 1e-9  # barycentric tolerance
SNAP = 1e-10  # barycentric coordinates below this are zero


@dataclass(frozen=True)
class Simplices:
    """Simplices (m, d + 1) over points (n, d), with the inverse of each one's edge
    matrix and a tree of their centroids."""

    points: np.ndarray
    index: np.ndarray
    inverse: np.ndarray
    tree: cKDTree

    @classmethod
    def of(cls, points: np.ndarray, index: np.ndarray) -> Simplices:
        v = points[index]
        edges = np.swapaxes(v[:, 1:] - v[:, :1], 1, 2)  # (m, d, d): columns v_k - v_0
        keep = np.abs(np.linalg.det(edges)) > 1e-14 * np.ptp(points, axis=0).prod()
        index, edges = index[keep], edges[keep]
        return cls(points, index, np.linalg.inv(edges), cKDTree(points[index].mean(axis=1)))

    def _bary(self, cand: np.ndarray, q: np.ndarray) -> np.ndarray:
        """Barycentric coordinates (n, k, d + 1) of points q (n, d) in simplices cand (n, k)."""
        rel = q[:, None, :] - self.points[self.index[cand, 0]]
        lam = np.einsum("nkij,nkj->nki", self.inverse[cand], rel)
        return np.concatenate([1.0 - lam.sum(axis=2, keepdims=True), lam], axis=2)

    def locate(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(simplex of each point, -1 outside; barycentric coordinates (n, d + 1))."""
        m = len(self.index)
        k = min(CANDIDATES, m)
        _, cand = self.tree.query(q, k=k)
        cand = cand.reshape(len(q), k)
        lam = self._bary(cand, q)
        worst = lam.min(axis=2)
        best = worst.argmax(axis=1)
        rows = np.arange(len(q))
        found = np.where(worst[rows, best] >= -INSIDE, cand[rows, best], -1)
        bary = lam[rows, best]
        for i in np.flatnonzero(found < 0):  # all simplices, in chunks
            for start in range(0, m, 20000):
                c = np.arange(start, min(start + 20000, m))[None, :]
                lam_i = self._bary(c, q[i:i + 1])[0]
                j = int(lam_i.min(axis=1).argmax())
                if lam_i[j].min() >= -INSIDE:
                    found[i], bary[i] = c[0, j], lam_i[j]
                    break
        # a point on a vertex or an edge takes the values there exactly: round-off in
        # the coordinates of the others would otherwise leak their values in (a
        # pressure of 1e-17 where the table holds 0 is a contact cell)
        bary = np.where(np.abs(bary) < SNAP, 0.0, bary)
        return found, bary / bary.sum(axis=1, keepdims=True)


def surface_triangles(xyz: np.ndarray, cells: dict[str, np.ndarray], on: np.ndarray
                      ) -> np.ndarray:
    """Linear triangles (m, 3) of the facets whose nodes all lie on the surface (``on``,
    a mask of the points), by the module doc's rules; empty if there are none."""
    tris = []

    def add(facets: np.ndarray, sub: np.ndarray) -> None:
        facets = facets[on[facets].all(axis=1)]
        if len(facets):
            tris.append(facets[:, sub].reshape(-1, 3))

    for kind, conn in cells.items():
        if kind == "triangle":
            add(conn, np.array([[0, 1, 2]]))
        elif kind == "triangle6":
            add(conn, TRI6_SUB)
        elif kind == "quad":
            add(conn, np.array([[0, 1, 2], [0, 2, 3]]))
        elif kind == "tetra":
            add(conn[:, TET_FACES].reshape(-1, 3), np.array([[0, 1, 2]]))
        elif kind == "tetra10":
            add(conn[:, TET10_FACES].reshape(-1, 6), TRI6_SUB)
        elif kind == "hexahedron":
            add(conn[:, HEX_FACES].reshape(-1, 4), np.array([[0, 1, 2], [0, 2, 3]]))
    if not tris:
        return np.empty((0, 3), dtype=np.int64)
    return np.unique(np.sort(np.vstack(tris), axis=1), axis=0)


@dataclass(frozen=True)
class Surface:
    """Linear interpolation on the contact surface's triangles (module doc)."""

    simplices: Simplices
    nodes: np.ndarray  # the surface points' indices in the file

    @classmethod
    def of(cls, xyz: np.ndarray, cells: dict[str, np.ndarray], tol: float) -> Surface:
        on = np.abs(xyz[:, 2]) <= tol
        nodes = np.flatnonzero(on)
        if len(nodes) < 3:
            raise ValueError("fewer than three points lie on the contact surface "
                             "(depth 0): check axes and origin")
        tris = surface_triangles(xyz, cells, on)
        local = np.full(len(xyz), -1)
        local[nodes] = np.arange(len(nodes))
        xy = xyz[nodes, :2]
        tris = local[tris] if len(tris) else Delaunay(xy).simplices
        return cls(Simplices.of(xy, tris), nodes)

    def weights(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(inside mask, file point indices (n, 3), weights (n, 3)) at points q (n, 2)."""
        found, bary = self.simplices.locate(q)
        inside = found >= 0
        idx = self.nodes[self.simplices.index[np.maximum(found, 0)]]
        return inside, idx, np.where(inside[:, None], bary, 0.0)

    def integral(self, values: np.ndarray) -> float:
        """∫ of the linear interpolant of ``values`` (at every file point) over the
        triangles: area times the mean of the vertex values."""
        s = self.simplices
        v = s.points[s.index]
        a, b = v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]
        area = 0.5 * np.abs(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0])
        return float(np.sum(area * values[self.nodes[s.index]].mean(axis=1)))


@dataclass(frozen=True)
class Volume:
    """Interpolation inside the body (module doc): shape functions of ten-node or
    four-node tetrahedra, else linear on the points' Delaunay tetrahedra."""

    simplices: Simplices
    quadratic: np.ndarray | None  # (m, 10) node indices of the ten-node tetrahedra

    @classmethod
    def of(cls, xyz: np.ndarray, cells: dict[str, np.ndarray]) -> Volume:
        if "tetra10" in cells:
            conn = cells["tetra10"]
            s = Simplices.of(xyz, conn[:, :4])
            keep = cls._kept(conn[:, :4], s.index)
            return cls(s, conn[keep])
        if "tetra" in cells:
            return cls(Simplices.of(xyz, cells["tetra"]), None)
        return cls(Simplices.of(xyz, Delaunay(xyz).simplices), None)

    @staticmethod
    def _kept(all_index: np.ndarray, kept: np.ndarray) -> np.ndarray:
        """Rows of ``all_index`` that :meth:`Simplices.of` kept (non-degenerate)."""
        if len(kept) == len(all_index):
            return np.arange(len(all_index))
        rows = {tuple(r): i for i, r in enumerate(all_index)}
        return np.array([rows[tuple(r)] for r in kept])

    def weights(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(inside mask, file point indices (n, k), weights (n, k)) at points q (n, 3)."""
        found, lam = self.simplices.locate(q)
        inside = found >= 0
        f = np.maximum(found, 0)
        if self.quadratic is None:
            return inside, self.simplices.index[f], lam
        w = [lam[:, i] * (2.0 * lam[:, i] - 1.0) for i in range(4)]
        w += [4.0 * lam[:, i] * lam[:, j] for i, j in TET10_EDGES]
        return inside, self.quadratic[f], np.column_stack(w)
