"""Node-wise contact on the quadratic surface: the modified basis and its dual weights.

The contact conditions are imposed once per surface node, not at quadrature points.  A
penalty at the Gauss points of a P2 facet constrains more points than the facet has
nodes: in a stick zone the points then trade traction with their neighbours and the
traction oscillates (docs/fem-notes.md, part 4).  One condition per node removes the
over-constraint; the weights of the nodes come from a dual (biorthogonal) basis.

The vertex functions of the P2 triangle integrate to zero, so a dual basis of the plain
P2 basis does not exist.  The *modified* basis (docs/fem-notes.md, part 4)

    φ̃_v = φ_v + α Σ_{e ∋ v} φ_e,        φ̃_e = (1 − 2α) φ_e,        α = 1/5,

spans the same space, is a partition of unity, and has positive integrals
``d_k = ∫ φ̃_k dA`` (2αA/3 per facet at a vertex, (1 − 2α)A/3 at an edge node).  With
the dual functions ψ_k (``∫ ψ_k φ̃_m dA = δ_km d_k``) as the multiplier basis,
``λ = Σ λ_k ψ_k``, the weighted gap and the nodal forces decouple node by node:

    g̃_k = ∫ ψ_k g dA / d_k = coefficient k of g in the modified basis,
    f = B⁻¹ (d λ)   (forces on the plain P2 DOFs),   u = Bᵀ ũ,

where ``φ̃ = B φ``.  So a contact point per node carries the weight ``d_k``, reads the
modified coefficient ``ũ_k = (B⁻ᵀ u)_k`` of the displacement, and its traction λ_k acts
through ``Gᵀ W λ`` with ``G = B⁻ᵀ`` — the same algebra as the quadrature points, with
``B⁻ᵀ`` in place of the interpolation matrix.  For an indenter profile that is
quadratic on each facet (the sphere's r²/2R is) the weighted profile equals its
modified coefficients, ``h̃ = B⁻ᵀ h(x_nodes)``.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from .surface import TRI_EDGES, ContactSurface

ALPHA = 0.2  # the modification of the vertex functions (α = 1/5)


def vertex_edge_pairs(surface: ContactSurface) -> tuple[np.ndarray, np.ndarray]:
    """(vertex node, edge node) pairs of the zone, each pair once: the edge node lies on
    an edge that ends at the vertex."""
    v = surface.facets[:, TRI_EDGES]  # (nf, 3, 2): the end vertices of edge nodes 3..5
    e = surface.facets[:, 3:]  # (nf, 3)
    pairs = np.concatenate([np.stack([v[..., 0], e], -1).reshape(-1, 2),
                            np.stack([v[..., 1], e], -1).reshape(-1, 2)])
    return tuple(np.unique(pairs, axis=0).T)


def modified_basis(surface: ContactSurface, alpha: float = ALPHA
                   ) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """(B, B⁻¹) with ``φ̃ = B φ`` on the surface nodes of the contact zone."""
    n = surface.nnodes
    is_edge = np.zeros(n, dtype=bool)
    is_edge[surface.facets[:, 3:].ravel()] = True
    vv, ee = vertex_edge_pairs(surface)
    diag = np.where(is_edge, 1.0 - 2.0 * alpha, 1.0)
    B = sp.csr_matrix((np.concatenate([diag, np.full(vv.size, alpha)]),
                       (np.concatenate([np.arange(n), vv]), np.concatenate([np.arange(n), ee]))),
                      shape=(n, n))
    # B = [[I, αE], [0, (1 − 2α) I]] in (vertex, edge) order: its inverse in closed form
    off = -alpha / (1.0 - 2.0 * alpha)
    Binv = sp.csr_matrix((np.concatenate([1.0 / diag, np.full(vv.size, off)]),
                          (np.concatenate([np.arange(n), vv]), np.concatenate([np.arange(n), ee]))),
                         shape=(n, n))
    return B, Binv


def dual_weights(surface: ContactSurface, B: sp.csr_matrix) -> np.ndarray:
    """``d_k = ∫ φ̃_k dA``: B applied to the integrals of the plain P2 functions."""
    m = surface.Nq.T @ surface.quad_w
    return B @ m


def coefficients(Binv: sp.csr_matrix, values: np.ndarray) -> np.ndarray:
    """Modified coefficients ``B⁻ᵀ v`` of a P2 field with nodal values ``v``."""
    return Binv.T @ values
