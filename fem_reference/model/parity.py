"""The mirror-parity split of the block: the full block's solves and condensed compliance
from four problems on its quarter.

The block, its supports and its material are symmetric about the planes X = 0 and Y = 0
whatever the load.  A displacement field splits into four parts of definite parity
``p = (p_x, p_y)``, each ``+1`` or ``−1``: under the mirror ``M_x: (X, Y, Z) → (−X, Y, Z)``
a part with ``p_x = +1`` satisfies ``u(M_x X) = M_x u(X)`` (u_x odd in X, u_y and u_z
even) and one with ``p_x = −1`` satisfies ``u(M_x X) = −M_x u(X)``; the same about Y.
On a full mesh made of a quarter mesh and its three mirror images (:func:`mirrored`),
the stiffness K commutes with the mirrors, the four parts are K-orthogonal and

    K⁻¹ = ¼ Σ_p T_p K_p⁻¹ T_pᵀ,

where ``K_p`` is the quarter's stiffness with the conditions of parity p on its cut
planes — a component that the plane's mirror turns over is zero there: u_x on X = 0
where ``p_x = +1``, u_y and u_z where ``p_x = −1``, likewise u_y, or u_x and u_z, on
Y = 0 — and ``T_p`` extends a quarter field of parity p to the full mesh (each node the
value of its quarter image, each component times ``σ_x(c)^{r_x} σ_y(c)^{r_y}``, ``r`` the
reflections that carry the image to the node, :func:`parity_signs`).  ``T_pᵀ K T_p = 4
K_p``: a field of definite parity has four times the quarter's energy.  The condensed
compliance of the contact DOFs ``S`` is then

    C = S K⁻¹ Sᵀ = ¼ Σ_p Q_pᵀ C_p Q_p,

``C_p`` the quarter's condensed compliance of parity p on the quarter images of the
contact DOFs and ``Q_p = (S T_p)ᵀ`` restricted to them, one ``±1`` per contact DOF
(:class:`ParityCompliance`).  The quarter's factorisations are four of a quarter of the
unknowns, its dense blocks four of a quarter of the size.

The half block (Y ≥ 0, its load even about Y = 0 and held there by rollers) is the
quarter and its image about X = 0 alone: the same sums over the two parities of its
own ``p_y`` (+1; −1 for a companion's antisymmetric load), weighted ½.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..errors import FemError
from .elasticity import Factorization, P2Space

#: the four parities (p_x, p_y), in the order every sum over them is taken
PARITIES = ((1, 1), (1, -1), (-1, 1), (-1, -1))


def parities(axes: tuple[int, ...], p_y: int = 1) -> tuple[tuple[int, int], ...]:
    """The parities of a block mirrored about ``axes``: all four for the full block;
    for the half block (X = 0 alone) the two of its own parity ``p_y`` about Y = 0
    (+1 its load, −1 a companion's)."""
    return PARITIES if tuple(axes) == (0, 1) else tuple(p for p in PARITIES if p[1] == p_y)


def mirrored(points: np.ndarray, tets: np.ndarray, tol: float, axes: tuple[int, ...] = (0, 1)
             ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The mesh (points (3, N), tets (4, 2^k M)) of a quarter mesh (X, Y ≥ 0) and its
    mirror images about the planes X_axis = 0 of ``axes`` (both: the full block; X = 0
    alone: the half block Y ≥ 0), and each vertex's quarter vertex (N,).

    Coordinates within ``tol`` of a cut plane are put on it; a mirrored point is the
    exact negation of its image, a mirrored tetrahedron keeps the orientation."""
    P = np.array(points, dtype=float, copy=True)
    P[:2][np.abs(P[:2]) <= tol] = 0.0
    T = np.asarray(tets)
    image = np.arange(P.shape[1])
    for axis in axes:
        off = np.flatnonzero(P[axis] != 0.0)
        index = np.arange(P.shape[1])
        index[off] = P.shape[1] + np.arange(off.size)
        Q = P[:, off]
        Q[axis] = -Q[axis]
        P = np.hstack([P, Q])
        image = np.concatenate([image, image[off]])
        T = np.hstack([T, index[T][[0, 2, 1, 3]]])
    return P, T, image


def parity_signs(parity: tuple[int, int]) -> np.ndarray:
    """``σ`` (2, 3): the factor of component c (columns x, y, z) of a field of
    ``parity`` under the mirror about X = 0 (row 0) and Y = 0 (row 1) (module doc)."""
    px, py = parity
    return np.array([[-px, px, px], [py, -py, py]], dtype=float)


class ParitySplit:
    """A mirrored P2 space's nodes (:func:`mirrored` about ``axes``) as images of the
    quarter's: each node's quarter node ``q`` and reflections ``r`` (2, N) (``r[0]``:
    X < 0, ``r[1]``: Y < 0); ``images`` the quarter's copies, 2^len(axes)."""

    def __init__(self, quarter: P2Space, full: P2Space, image: np.ndarray,
                 axes: tuple[int, ...] = (0, 1)):
        edges = full.mesh.edges
        self.quarter, self.full, self.axes = quarter, full, tuple(axes)
        self.images = 2 ** len(self.axes)
        self.q = np.concatenate([image, quarter.edge_node(image[edges[0]],
                                                          image[edges[1]])])
        nodes = full.nodes
        self.r = np.zeros((2, nodes.shape[1]), dtype=bool)
        want = nodes.copy()
        for axis in self.axes:
            self.r[axis] = nodes[axis] < 0.0
            want[axis] = np.abs(nodes[axis])
        if not np.array_equal(quarter.nodes[:, self.q], want):
            raise FemError("internal error: the mesh is not the quarter's mirror images")
        self.on_plane = quarter.nodes[:2] == 0.0  # (2, nq): X = 0, Y = 0

    def signs(self, parity: tuple[int, int]) -> np.ndarray:
        """The factor (3 N,) of each full DOF ``3 i + c`` on its quarter DOF ``3 q + c``
        in a field of ``parity``."""
        s = parity_signs(parity)
        out = np.where(self.r[0][:, None], s[0][None, :], 1.0)
        out = out * np.where(self.r[1][:, None], s[1][None, :], 1.0)
        return out.ravel()

    def quarter_dofs(self) -> np.ndarray:
        """Each full DOF's quarter DOF (3 N,)."""
        return (3 * self.q[:, None] + np.arange(3)).ravel()

    def held(self, parity: tuple[int, int]) -> np.ndarray:
        """The quarter DOFs (mask, 3 nq) a field of ``parity`` holds on the cut planes."""
        return held({0: self.on_plane[0], 1: self.on_plane[1]}, parity)


def held(planes: dict[int, np.ndarray], parity: tuple[int, int]) -> np.ndarray:
    """The DOFs (mask, 3 n) that a field of ``parity`` holds at zero on the mirror planes
    ``planes`` (axis: the mask of the nodes on the plane X_axis = 0): the components the
    plane's mirror turns over (module doc)."""
    s = parity_signs(parity)
    mask = np.zeros((next(iter(planes.values())).size, 3), dtype=bool)
    for axis, on in planes.items():
        mask |= on[:, None] & (s[axis] < 0)[None, :]
    return mask.ravel()


def extension(split: ParitySplit, parity: tuple[int, int], rows: np.ndarray,
              cols: np.ndarray) -> sp.csr_matrix:
    """``T_p`` (module doc) from the quarter's DOFs ``cols`` (its unknowns of ``parity``)
    to the full DOFs ``rows``, sparse: one ``±1`` per row whose quarter DOF is a column."""
    qd = split.quarter_dofs()[rows]
    pos = np.searchsorted(cols, qd)
    pos = np.minimum(pos, cols.size - 1)
    hit = cols[pos] == qd
    return sp.csr_matrix((split.signs(parity)[rows][hit], (np.flatnonzero(hit), pos[hit])),
                         shape=(rows.size, cols.size))


class ParityFactorization:
    """``K⁻¹`` of the mirrored block as the quarter's factorisations ``F_p`` and their
    extensions ``T_p`` (module doc; ``images`` the quarter's copies, the weight of the
    sum ¼ for the full block, ½ for the half): :meth:`solve` as :class:`Factorization`'s."""

    def __init__(self, parts: list[tuple[sp.csr_matrix, Factorization]], images: int):
        self.parts, self.images = parts, images
        self.n = parts[0][0].shape[0]

    def solve(self, b: np.ndarray) -> np.ndarray:
        """``K⁻¹ b`` for one right-hand side (n,) or many (n, m)."""
        b = np.asarray(b, dtype=float)
        out = np.zeros(b.shape)
        for T, F in self.parts:
            out += T @ F.solve(T.T @ b)
        return out / self.images

    def free(self) -> None:
        for _, F in self.parts:
            F.free()


@dataclass(frozen=True)
class ParityCompliance:
    """``C = ¼ Σ_p Q_pᵀ C_p Q_p`` (module doc; ½ for the half block's two parities) of
    m contact DOFs, held as the quarter's dense ``C_p`` with each contact DOF's row
    ``index[p]`` in it and factor ``sign[p]`` (0 where the parity holds the DOF):
    products and rows, never whole but on request.  Exactly symmetric: an entry and its
    transpose are the same products summed in the same order."""

    blocks: tuple[np.ndarray, ...]
    index: np.ndarray  # (parities, m) int
    sign: np.ndarray  # (parities, m) float: ±1, 0
    images: int  # the quarter's copies: the sum's weight 1 / images

    @property
    def shape(self) -> tuple[int, int]:
        m = self.index.shape[1]
        return m, m

    def rows(self, K: np.ndarray) -> np.ndarray:
        """``C[K]`` (|K|, m)."""
        K = np.asarray(K)
        out = np.zeros((K.size, self.shape[0]))
        for C_p, j, s in zip(self.blocks, self.index, self.sign, strict=True):
            out += (s[K, None] * s[None, :]) * C_p[np.ix_(j[K], j)]
        return out / self.images

    def dense(self) -> np.ndarray:
        return self.rows(np.arange(self.shape[0]))

    def __matmul__(self, v: np.ndarray) -> np.ndarray:
        """``C v`` (v (m,) or (m, k))."""
        V = np.asarray(v, dtype=float).reshape(self.shape[0], -1)
        out = np.zeros(V.shape)
        for C_p, j, s in zip(self.blocks, self.index, self.sign, strict=True):
            y = np.zeros((C_p.shape[0], V.shape[1]))
            np.add.at(y, j, s[:, None] * V)
            out += s[:, None] * (C_p @ y)[j]
        return (out / self.images).reshape(np.shape(v))


def condensed(split: ParitySplit, parity: tuple[int, int], cdofs: np.ndarray,
              free_p: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The quarter's condensed unknowns of ``parity`` for the full contact DOFs ``cdofs``:
    (their positions in the quarter's unknowns ``free_p``, each contact DOF's row among
    them, its factor ``±1`` or 0 where the parity holds it)."""
    qd = split.quarter_dofs()[cdofs]
    s = split.signs(parity)[cdofs]
    pos = np.minimum(np.searchsorted(free_p, qd), free_p.size - 1)
    s = np.where(free_p[pos] == qd, s, 0.0)
    kept = np.unique(pos[s != 0.0])
    row = np.minimum(np.searchsorted(kept, pos), max(kept.size - 1, 0))
    return kept, row, s
