"""Node-wise contact on the P2 surface (fem_reference/model/nodal_basis.py): the modified basis, its
dual weights and the sub-triangle interpolation, checked against element-by-element
quadrature of the dual functions built independently here."""

from __future__ import annotations

import numpy as np
import pytest
from skfem.quadrature import get_quadrature
from skfem.refdom import RefTri

from fem_reference.model.elasticity import P2Space
from fem_reference.model.mesh import MeshSpec, block_mesh
from fem_reference.model.nodal_basis import ALPHA, coefficients, dual_weights, modified_basis
from fem_reference.model.surface import ContactSurface, p2_triangle_values, sub_triangle_values


@pytest.fixture(scope="module")
def surf():
    mesh = block_mesh(MeshSpec("half", 4.0, 4.0, 0.3, 1.5, 1.0, h_max=1.0), 1.0)
    space = P2Space(mesh)
    return ContactSurface(space, 1.5, (2,), np.zeros(space.ndofs, bool))


def _local_modification(alpha: float) -> np.ndarray:
    """φ̃ = T φ on one triangle (order v0 v1 v2 e01 e12 e02), written out by hand."""
    T = np.eye(6)
    T[3:, 3:] *= 1.0 - 2.0 * alpha
    for v, edges in ((0, (3, 5)), (1, (3, 4)), (2, (4, 5))):
        T[v, list(edges)] = alpha
    return T


def test_dual_weights_are_positive_and_integrate_the_zone(surf):
    B, _ = modified_basis(surf)
    d = dual_weights(surf, B)
    assert d.min() > 0.0
    assert np.isclose(d.sum(), surf.area.sum(), rtol=1e-12)
    # per facet: 2 alpha A / 3 at each vertex, (1 - 2 alpha) A / 3 at each edge node
    ref = np.zeros(surf.nnodes)
    for k in range(3):
        np.add.at(ref, surf.facets[:, k], 2 * ALPHA * surf.area / 3)
        np.add.at(ref, surf.facets[:, 3 + k], (1 - 2 * ALPHA) * surf.area / 3)
    assert np.allclose(d, ref, rtol=1e-12)


def test_weighted_gap_is_the_modified_coefficient(surf):
    """∫ ψ_k f dA = d_k (B⁻ᵀ f)_k for a field f of the P2 space, with the dual functions
    ψ = D M̃⁻¹ φ̃ of each facet assembled here; and a uniform multiplier gives the
    consistent P2 load B⁻¹ d = ∫ φ dA."""
    B, Binv = modified_basis(surf)
    d = dual_weights(surf, B)
    f_nodal = 1.0 + surf.xy[:, 0] ** 2 - 0.7 * surf.xy[:, 0] * surf.xy[:, 1] + 0.3 * surf.xy[:, 1]
    X, W = get_quadrature(RefTri, 6)
    lam = np.vstack([1 - X[0] - X[1], X[0], X[1]]).T
    phi = p2_triangle_values(lam)  # (nq, 6)
    T = _local_modification(ALPHA)
    phit = phi @ T.T  # modified functions at the points
    Mt = (phit * W[:, None]).T @ phit  # ∫ φ̃ φ̃ over the reference triangle
    Dt = phit.T @ W
    psi = phit @ np.linalg.solve(Mt, np.diag(Dt))  # (nq, 6): ψ = D M̃⁻¹ φ̃
    assert np.allclose((psi * W[:, None]).T @ phit, np.diag(Dt), atol=1e-14)  # biorthogonal
    weighted = np.zeros(surf.nnodes)
    f_q = phi @ f_nodal[surf.facets].T  # (nq, nf)
    local = 2 * surf.area[:, None] * ((W[:, None] * f_q).T @ psi)  # (nf, 6): ∫ ψ_j f
    np.add.at(weighted, surf.facets, local)
    assert np.allclose(weighted, d * coefficients(Binv, f_nodal), rtol=1e-11, atol=1e-14)
    m = surf.Nq.T @ surf.quad_w
    assert np.allclose(Binv @ d, m, atol=1e-14)
    assert np.allclose((B @ Binv).toarray(), np.eye(surf.nnodes), atol=1e-14)


def test_sub_triangle_interpolation(surf):
    rng = np.random.default_rng(5)
    lam = rng.dirichlet([1.0, 1.0, 1.0], size=5000)
    w = sub_triangle_values(lam)
    assert np.allclose(w.sum(-1), 1.0) and w.min() >= 0.0
    nodes = np.vstack([np.eye(3), [[0.5, 0.5, 0], [0, 0.5, 0.5], [0.5, 0, 0.5]]])
    assert np.allclose(sub_triangle_values(nodes), np.eye(6))
    # reproduces linear fields and never leaves the range of the nodal values
    pts = rng.uniform(-1.0, 1.0, size=(300, 2)) * np.array([1.0, 0.5]) + [0, 0.5]
    N, found = surf.sub_interpolation(pts)
    lin = 2.0 - 0.7 * surf.xy[:, 0] + 1.3 * surf.xy[:, 1]
    assert np.allclose((N @ lin)[found], (2.0 - 0.7 * pts[:, 0] + 1.3 * pts[:, 1])[found])
    step = (surf.xy[:, 0] > 0.2).astype(float)
    assert (N @ step).min() >= 0.0 and (N @ step).max() <= 1.0 + 1e-15
