"""The contact tractions of a CalculiX solution as the nodal forces of body b's
elements at its face, over the nodes' tributary areas.

``ccx`` writes the surface-to-surface contact stresses to the ``.frd`` file at the nodes
by extrapolating each slave face's integration-point values and averaging them: a
combination with negative weights, which at the contact edge gives a node shear beyond
μ times its pressure (six times, on the quick Cattaneo–Mindlin contact) although every
integration point obeys the friction law.  The nodal forces do not: at a node k of the
face, equilibrium of body b says the contact force equals the internal force of the
elements around it,

    F_k = Σ_e ∫_e Bₖᵀ σ(u) dV = ∫_face N_k t dA,

a combination of the contact tractions t with the positive weights N_k, so
‖F_t,k‖ ≤ μ F_n,k wherever ‖t_t‖ ≤ μ t_n, and Σ_k F_k is the total contact force
(``*CONTACT PRINT``'s, a check of the whole chain).  The contact's normal is z (the
bodies share the gap so that the deformed interface is flat:
:mod:`calculix_adapter.mesh`), so F's z component is the normal force and its x and y
components the friction force.  σ(u) is the C3D8 element's (isoparametric trilinear,
linear elasticity, 2 × 2 × 2 Gauss points) from the displacements ``ccx`` prints to the
``.dat`` file (seven digits) at the nodes of the face's element layer; the traction at
the node is F_k over ∫ N_k dA (the horizontal tributary area,
:func:`calculix_adapter.fields.tributary`), the traction on body a being −F_k / A_k
(README, Conventions).
"""

from __future__ import annotations

import numpy as np

from .mesh import Body

#: the corners of a hexahedron in its natural coordinates, CalculiX's order
CORNERS = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                    [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], dtype=float)
GAUSS = CORNERS / np.sqrt(3.0)


def elasticity(E: float, nu: float) -> np.ndarray:
    """The isotropic elasticity matrix (6, 6) in the order xx, yy, zz, xy, yz, xz
    (engineering shear strains)."""
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    G = E / (2 * (1 + nu))
    D = np.zeros((6, 6))
    D[:3, :3] = lam
    D[np.arange(3), np.arange(3)] += 2 * G
    D[np.arange(3, 6), np.arange(3, 6)] = G
    return D


def gradients(coords: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(dN_a/dx_j (m, gauss 8, node 8, 3), the Jacobian's determinant (m, 8)) of the
    trilinear hexahedra whose corners are ``coords`` (m, 8, 3), at their Gauss points."""
    g = GAUSS[:, None, :]  # (8, 1, 3)
    c = CORNERS[None, :, :]  # (1, 8, 3)
    f = 1.0 + g * c  # (8, 8, 3): the three factors of N_a at each point
    d = np.empty((8, 8, 3))
    d[..., 0] = c[..., 0] * f[..., 1] * f[..., 2]
    d[..., 1] = c[..., 1] * f[..., 0] * f[..., 2]
    d[..., 2] = c[..., 2] * f[..., 0] * f[..., 1]
    d /= 8.0  # dN_a/dξ_i
    J = np.einsum("gai,maj->mgij", d, coords)  # ∂x_j/∂ξ_i
    return np.einsum("mgji,gai->mgaj", np.linalg.inv(J), d), np.linalg.det(J)


def nodal_forces(body: Body, u: np.ndarray, E: float, nu: float) -> np.ndarray:
    """The internal forces (nx, ny, 3) [N] at the nodes of body b's face (its top,
    z = 0) of the element layer under it, from the displacements ``u`` (n, 3) of the
    body's nodes (those of the layer must be given)."""
    nx, ny, nz = body.shape
    idx = np.arange(body.nodes.shape[0]).reshape(nx, ny, nz)
    layer = body.cells.reshape(nx - 1, ny - 1, nz - 1, 8)[:, :, -1].reshape(-1, 8)
    dN, det = gradients(body.nodes[layer])  # (m, 8, 8, 3), (m, 8)
    ue = u[layer]  # (m, 8, 3)
    grad = np.einsum("mgai,maj->mgij", dN, ue)  # du_j/dx_i
    eps = np.stack([grad[..., 0, 0], grad[..., 1, 1], grad[..., 2, 2],
                    grad[..., 0, 1] + grad[..., 1, 0], grad[..., 1, 2] + grad[..., 2, 1],
                    grad[..., 0, 2] + grad[..., 2, 0]], axis=-1)
    s = eps @ elasticity(E, nu).T  # (m, 8, 6)
    sig = np.empty(s.shape[:2] + (3, 3))
    sig[..., 0, 0], sig[..., 1, 1], sig[..., 2, 2] = s[..., 0], s[..., 1], s[..., 2]
    sig[..., 0, 1] = sig[..., 1, 0] = s[..., 3]
    sig[..., 1, 2] = sig[..., 2, 1] = s[..., 4]
    sig[..., 0, 2] = sig[..., 2, 0] = s[..., 5]
    fe = np.einsum("mgai,mgij,mg->maj", dN, sig, det)  # (m, 8, 3), unit weights
    out = np.zeros((body.nodes.shape[0], 3))
    np.add.at(out, layer[:, 4:].ravel(), fe[:, 4:].reshape(-1, 3))
    return out[idx[:, :, -1]]

