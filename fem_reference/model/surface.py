"""The candidate contact zone of the block's top surface: P2 triangles, quadrature, samples.

The contact zone is the set of top-surface facets (``Z = 0``) whose centroid lies within
the radius ``r_c`` of the load axis.  The traces of the P2 field on those facets are P2
triangles (3 vertex nodes and 3 edge nodes, order v0 v1 v2 e01 e12 e02).  Everything
the contact solver needs is linear in the surface nodal values and is expressed by
sparse interpolation matrices ``N`` (points x surface nodes): at the quadrature points
(the integrals of the surface functions, :mod:`fem_reference.model.nodal_basis`) and at arbitrary
surface sample points (the case grid, lines through the centre), P2 or linear on the four
sub-triangles of a facet.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from scipy.spatial import cKDTree
from skfem.quadrature import get_quadrature
from skfem.refdom import RefTri

from .elasticity import P2Space

TRI_EDGES = np.array([[0, 1], [1, 2], [0, 2]])


def p2_triangle_values(lam: np.ndarray) -> np.ndarray:
    """P2 triangle shape functions (..., 6) at barycentric coordinates (..., 3)."""
    vert = lam * (2.0 * lam - 1.0)
    edge = 4.0 * lam[..., TRI_EDGES[:, 0]] * lam[..., TRI_EDGES[:, 1]]
    return np.concatenate([vert, edge], axis=-1)


def sub_triangle_values(lam: np.ndarray) -> np.ndarray:
    """Weights (..., 6) of the piecewise-linear interpolation of the six P2 nodes on the
    four sub-triangles of a triangle (v0 e01 e02, v1 e12 e01, v2 e02 e12, e01 e12 e02),
    at barycentric coordinates (..., 3)."""
    l0, l1, l2 = lam[..., 0], lam[..., 1], lam[..., 2]
    out = np.zeros(lam.shape[:-1] + (6,))
    corner = np.argmax(lam, axis=-1)
    big = np.take_along_axis(lam, corner[..., None], -1)[..., 0] >= 0.5
    centre = ~big
    out[..., 3] = np.where(centre, 1.0 - 2.0 * l2, 0.0)
    out[..., 4] = np.where(centre, 1.0 - 2.0 * l0, 0.0)
    out[..., 5] = np.where(centre, 1.0 - 2.0 * l1, 0.0)
    for k, (ea, eb, la, lb) in enumerate(((3, 5, l1, l2), (4, 3, l2, l0), (5, 4, l0, l1))):
        sel = big & (corner == k)
        out[..., k] = np.where(sel, 2.0 * lam[..., k] - 1.0, out[..., k])
        out[..., ea] = np.where(sel, 2.0 * la, out[..., ea])
        out[..., eb] = np.where(sel, 2.0 * lb, out[..., eb])
    return out


class ContactSurface:
    """Top-surface P2 facets within radius ``r_c`` and the condensed surface DOFs.

    ``comps`` are the displacement components kept in the condensed system
    (``(2,)`` for frictionless contact, ``(0, 1, 2)`` with friction); DOFs fixed by a
    symmetry condition (``fixed`` mask over all DOFs) are left out.
    """

    def __init__(self, space: P2Space, r_c: float, comps: tuple[int, ...],
                 fixed: np.ndarray, *, quad_order: int = 5):
        mesh = space.mesh
        self.r_c = r_c
        scale = np.abs(mesh.p).max()
        bf = mesh.boundary_facets()
        fz = mesh.p[2, mesh.facets[:, bf]]  # (3, nbf)
        top = bf[np.all(np.abs(fz) <= 1e-9 * scale, axis=0)]
        verts = mesh.facets[:, top]  # (3, ntop)
        centroid = mesh.p[:2, verts].mean(axis=1)
        sel = np.hypot(centroid[0], centroid[1]) < r_c
        if not sel.any():
            raise ValueError(f"no top-surface facets within r_c = {r_c}")
        verts = verts[:, sel]
        self.top_facets = top[sel]
        e01 = space.edge_node(verts[0], verts[1])
        e12 = space.edge_node(verts[1], verts[2])
        e02 = space.edge_node(verts[0], verts[2])
        gnodes = np.vstack([verts, e01, e12, e02])  # (6, nf) global P2 nodes
        self.nodes, inv = np.unique(gnodes, return_inverse=True)
        self.facets = inv.reshape(gnodes.shape).T  # (nf, 6) local surface nodes
        self.nnodes = self.nodes.size
        self.xy = space.nodes[:2, self.nodes].T.copy()  # (nnodes, 2)
        self.vert_xy = np.moveaxis(mesh.p[:2, verts], 0, -1).transpose(1, 0, 2)  # (nf, 3, 2)
        v = self.vert_xy
        d1, d2 = v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]
        self.area = 0.5 * np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
        T = np.stack([d1, d2], axis=-1)  # (nf, 2, 2) columns
        self._invT = np.linalg.inv(T)
        self.centroid = v.mean(axis=1)
        self.facet_radius = np.hypot(self.centroid[:, 0], self.centroid[:, 1])
        self._tree = cKDTree(self.centroid)
        # quadrature points
        X, W = get_quadrature(RefTri, quad_order)  # reference (ξ, η), weights sum 1/2
        lam = np.vstack([1.0 - X[0] - X[1], X[0], X[1]]).T  # (nq, 3)
        self.quad_lam = lam
        nf, nq = self.facets.shape[0], lam.shape[0]
        phi = p2_triangle_values(lam)  # (nq, 6)
        self.quad_xy = np.einsum("qk,fkd->fqd", lam, v).reshape(-1, 2)
        self.quad_w = (2.0 * self.area[:, None] * W[None, :]).ravel()
        self.quad_facet = np.repeat(np.arange(nf), nq)
        rows = np.repeat(np.arange(nf * nq), 6)
        cols = np.repeat(self.facets, nq, axis=0).ravel()
        vals = np.tile(phi, (nf, 1)).ravel()
        self.Nq = sp.csr_matrix((vals, (rows, cols)), shape=(nf * nq, self.nnodes))
        # condensed DOFs: (node, comp) pairs not fixed by symmetry
        dof = (3 * self.nodes[:, None] + np.asarray(comps)[None, :]).ravel()
        keep = ~fixed[dof]
        self.dofs = dof[keep]  # global DOF numbers
        self.dof_node = np.repeat(np.arange(self.nnodes), len(comps))[keep]
        self.dof_comp = np.tile(np.asarray(comps), self.nnodes)[keep]
        self.ndofs = self.dofs.size

    # ------------------------------------------------------------------ samples

    def locate(self, xy: np.ndarray, *, k: int = 12) -> tuple[np.ndarray, np.ndarray]:
        """(facet index or -1, barycentric coordinates (n, 3)) of points ``xy`` (n, 2)."""
        xy = np.atleast_2d(np.asarray(xy, dtype=float))
        n = xy.shape[0]
        k = min(k, self.centroid.shape[0])
        _, cand = self._tree.query(xy, k=k)
        cand = cand.reshape(n, k)
        rel = xy[:, None, :] - self.vert_xy[cand, 0]  # (n, k, 2)
        l12 = np.einsum("nkij,nkj->nki", self._invT[cand], rel)
        lam = np.concatenate([1.0 - l12.sum(-1, keepdims=True), l12], axis=-1)
        inside = lam.min(axis=-1) >= -1e-10
        found = inside.any(axis=1)
        first = np.argmax(inside, axis=1)
        facet = np.where(found, cand[np.arange(n), first], -1)
        bary = lam[np.arange(n), first]
        return facet, bary

    def interpolation(self, xy: np.ndarray) -> tuple[sp.csr_matrix, np.ndarray]:
        """P2 interpolation matrix (n x nnodes) at points ``xy`` and the mask of points
        found.  Rows of points outside the contact zone are empty."""
        facet, bary = self.locate(xy)
        found = facet >= 0
        idx = np.nonzero(found)[0]
        phi = p2_triangle_values(bary[idx])
        rows = np.repeat(idx, phi.shape[1])
        cols = self.facets[facet[idx], :phi.shape[1]].ravel()
        N = sp.csr_matrix((phi.ravel(), (rows, cols)), shape=(facet.size, self.nnodes))
        return N, found

    def sub_interpolation(self, xy: np.ndarray) -> tuple[sp.csr_matrix, np.ndarray]:
        """Interpolation matrix (n x nnodes) linear on the four sub-triangles of each facet
        (corners and edge nodes: ``sub_triangle_values``), and the mask of points found.

        A monotone reconstruction of nodal values: it never leaves their range, so a
        nodal field that drops to zero within a facet does not ring.
        """
        facet, bary = self.locate(xy)
        found = facet >= 0
        idx = np.nonzero(found)[0]
        phi = sub_triangle_values(bary[idx])
        rows = np.repeat(idx, 6)
        cols = self.facets[facet[idx]].ravel()
        N = sp.csr_matrix((phi.ravel(), (rows, cols)), shape=(facet.size, self.nnodes))
        N.eliminate_zeros()
        return N, found

    def operator(self, N: sp.csr_matrix) -> sp.csr_matrix:
        """``G`` (3n x ndofs): condensed DOFs -> [u_x; u_y; u_z] at the points of ``N``."""
        blocks = []
        for c in range(3):
            sel = np.nonzero(self.dof_comp == c)[0]
            P = sp.csr_matrix(
                (np.ones(sel.size), (self.dof_node[sel], sel)), shape=(self.nnodes, self.ndofs)
            )
            blocks.append(N @ P)
        return sp.vstack(blocks, format="csr")
