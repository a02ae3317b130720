"""The candidate contact zone of the block's top surface: P2 triangles, quadrature, probes.

The contact zone is the set of top-surface facets (``Z = 0``) whose centroid lies within
the radius ``r_c`` of the load axis.  The traces of the P2 field on those facets are P2
triangles (3 vertex nodes and 3 edge nodes, order v0 v1 v2 e01 e12 e02).  Everything
the contact solver needs is linear in the surface nodal values and is expressed by
sparse interpolation matrices ``N`` (points x surface nodes): at the quadrature points
(where the penalty tractions are integrated) and at arbitrary probe points (the case
grid, lines through the centre).
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

    # ------------------------------------------------------------------ probes

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

    def interpolation(self, xy: np.ndarray, *, p1: bool = False
                      ) -> tuple[sp.csr_matrix, np.ndarray]:
        """Interpolation matrix (n x nnodes) at points ``xy`` and the mask of points found.

        P2 on each facet, or with ``p1`` linear in the facet's vertex values.  Rows of
        points outside the contact zone are empty.
        """
        facet, bary = self.locate(xy)
        found = facet >= 0
        idx = np.nonzero(found)[0]
        phi = bary[idx] if p1 else p2_triangle_values(bary[idx])
        rows = np.repeat(idx, phi.shape[1])
        cols = self.facets[facet[idx], :phi.shape[1]].ravel()
        N = sp.csr_matrix((phi.ravel(), (rows, cols)), shape=(facet.size, self.nnodes))
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

    def node_ranges(self, values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Range (min, max) per surface node of quadrature-point ``values`` over the facets
        that contain the node (its patch)."""
        v = np.asarray(values, dtype=float).reshape(self.facets.shape[0], -1)
        fmin, fmax = v.min(axis=1), v.max(axis=1)
        lo = np.full(self.nnodes, np.inf)
        hi = np.full(self.nnodes, -np.inf)
        for k in range(self.facets.shape[1]):
            np.minimum.at(lo, self.facets[:, k], fmin)
            np.maximum.at(hi, self.facets[:, k], fmax)
        return lo, hi

    def p1_projection(self) -> tuple[sp.csr_matrix, sp.csr_matrix, sp.csr_matrix]:
        """(F, M, E) of the L2 projection of quadrature-point values on continuous P1.

        ``F`` (nnodes x nquad): values -> ``∫ λ_i v`` at the vertex nodes (zero rows at
        the edge nodes); ``M`` (nnodes x nnodes): the P1 mass matrix ``∫ λ_i λ_j`` with
        unit diagonal at the edge nodes; ``E``: vertex values -> edge-node values (the
        mean of the edge's two vertices).  Nodal values: ``E'`` applied to ``M⁻¹ F v``.
        """
        nf, nq = self.facets.shape[0], self.quad_lam.shape[0]
        vert = self.facets[:, :3]
        rows = np.repeat(np.arange(nf * nq), 3)
        cols = np.repeat(vert, nq, axis=0).ravel()  # the facet's vertex nodes per point
        Nv = sp.csr_matrix((np.tile(self.quad_lam, (nf, 1)).ravel(), (rows, cols)),
                           shape=(nf * nq, self.nnodes))  # P1 values at the points
        F = (Nv.T @ sp.diags(self.quad_w)).tocsr()
        M = (F @ Nv).tocsr()
        is_vert = np.zeros(self.nnodes, dtype=bool)
        is_vert[vert.ravel()] = True
        M = (M + sp.diags((~is_vert).astype(float))).tocsr()
        ends = vert[:, TRI_EDGES]  # (nf, 3, 2)
        mid = self.facets[:, 3:].ravel()
        E = sp.csr_matrix((np.full(2 * mid.size, 0.5), (np.repeat(mid, 2), ends.reshape(-1))),
                          shape=(self.nnodes, self.nnodes))
        count = np.bincount(mid, minlength=self.nnodes).astype(float)
        E = sp.diags(np.where(count > 0, 1.0 / np.maximum(count, 1.0), 0.0)) @ E
        E = (E + sp.diags(is_vert.astype(float))).tocsr()
        return F, M, E

    def mass(self) -> sp.csr_matrix:
        """Surface mass matrix ``∫ φ_i φ_j dA`` over the contact zone (exact for P2)."""
        return (self.Nq.T @ sp.diags(self.quad_w) @ self.Nq).tocsr()
