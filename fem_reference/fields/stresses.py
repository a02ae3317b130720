"""Stress recovery from the P2 displacement field.

Stresses are evaluated exactly from the P2 displacement gradient inside the element
that contains a sample point; a point on an element face, edge or vertex (the surface,
planes that coincide with mesh faces) gets the average over every element containing
it, so the value does not depend on which neighbour a search returns.  For the
``.vtu`` output the element values at the P2 nodes are volume-averaged.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

from ..model.elasticity import P2Space, p2_gradients, stress_from_gradient

COMPONENTS = ("sxx", "syy", "szz", "sxy", "sxz", "syz")
_PAIRS = ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2))

# barycentric coordinates of the 10 P2 nodes of a tetrahedron
_NODE_LAMBDA = np.vstack(
    [np.eye(4)]
    + [0.5 * (np.eye(4)[i] + np.eye(4)[j]) for i, j in ((0, 1), (1, 2), (0, 2), (0, 3), (1, 3),
                                                       (2, 3))]
)


class PointLocator:
    """Finds the tetrahedra containing sample points (KD-tree on element centroids)."""

    def __init__(self, space: P2Space):
        self.space = space
        centroids = space.mesh.p[:, space.mesh.t].mean(axis=1).T
        self._tree = cKDTree(centroids)

    def locate(self, points: np.ndarray, *, tol: float = 1e-9
               ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """All (point index, element, barycentric) triples with the point inside.

        Raises ``ValueError`` naming a point that lies outside the mesh.
        """
        points = np.atleast_2d(points)
        n = points.shape[0]
        hits_p, hits_e, hits_l = [], [], []
        todo = np.arange(n)
        for k in (24, 96, 384):
            if todo.size == 0:
                break
            k = min(k, self.space.nel)
            _, cand = self._tree.query(points[todo], k=k)
            cand = cand.reshape(todo.size, k)
            pidx = np.repeat(todo, k)
            lam = self.space.barycentric(points[pidx], cand.ravel())
            inside = lam.min(axis=1) >= -tol
            hits_p.append(pidx[inside])
            hits_e.append(cand.ravel()[inside])
            hits_l.append(lam[inside])
            found = np.zeros(n, bool)
            found[pidx[inside]] = True
            todo = todo[~found[todo]]
        if todo.size:
            raise ValueError(f"sample point {points[todo[0]]} lies outside the FE mesh")
        return np.concatenate(hits_p), np.concatenate(hits_e), np.concatenate(hits_l)


def displacement_gradient(space: P2Space, u: np.ndarray, elements: np.ndarray,
                          lam: np.ndarray) -> np.ndarray:
    """∂u_i/∂x_j (n, 3, 3) of the P2 field ``u`` (3 * nnodes,) at barycentric points."""
    U = u.reshape(-1, 3)[space.element_nodes[:, elements].T]  # (n, 10, 3)
    grads = p2_gradients(lam, space.grad_lambda[elements])  # (n, 10, 3)
    return np.einsum("nai,naj->nij", U, grads)


def sample_stresses(space: P2Space, locator: PointLocator, u: np.ndarray, nu: float, E: float,
                    points: np.ndarray) -> dict[str, np.ndarray]:
    """Stress components (mesh frame) at ``points`` (n, 3), averaged over containing elements."""
    points = np.atleast_2d(points)
    pidx, elems, lam = locator.locate(points)
    sig = stress_from_gradient(displacement_gradient(space, u, elems, lam), nu, E)
    count = np.bincount(pidx, minlength=points.shape[0]).astype(float)
    out = {}
    for name, (i, j) in zip(COMPONENTS, _PAIRS, strict=True):
        out[name] = np.bincount(pidx, weights=sig[:, i, j], minlength=points.shape[0]) / count
    return out


def sample_displacement(space: P2Space, locator: PointLocator, u: np.ndarray,
                        points: np.ndarray) -> np.ndarray:
    """P2 displacement (n, 3) at ``points``."""
    from ..model.elasticity import p2_values

    points = np.atleast_2d(points)
    pidx, elems, lam = locator.locate(points)
    first = np.unique(pidx, return_index=True)[1]
    U = u.reshape(-1, 3)[space.element_nodes[:, elems[first]].T]  # (n, 10, 3)
    return np.einsum("na,nai->ni", p2_values(lam[first]), U)


def nodal_stresses(space: P2Space, u: np.ndarray, nu: float, E: float) -> np.ndarray:
    """Volume-averaged stress tensors (nnodes, 3, 3) at the P2 nodes."""
    nel = space.nel
    acc = np.zeros((space.nnodes, 3, 3))
    wsum = np.zeros(space.nnodes)
    for a in range(10):
        lam = np.broadcast_to(_NODE_LAMBDA[a], (nel, 4))
        sig = stress_from_gradient(
            displacement_gradient(space, u, np.arange(nel), lam), nu, E
        )
        nodes = space.element_nodes[a]
        np.add.at(acc, nodes, sig * space.volume[:, None, None])
        np.add.at(wsum, nodes, space.volume)
    return acc / wsum[:, None, None]
