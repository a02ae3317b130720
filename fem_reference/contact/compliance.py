"""The nodal compliance of the contact points: the condensed compliance seen from the
nodes, the elastic operator of the semi-smooth contact solve
(:mod:`fem_reference.contact.semismooth`).

Only the nodes in contact carry tractions, and they are a fraction of the condensed
surface.  The compliance is kept with its nodes in *touch order* (the indenter profile
``h`` rising: the nodes an approach reaches first come first), so that the tractions of
a contact zone lie in a leading range of each component and a product reads only those
columns of the dense matrix (:meth:`NodalCompliance.apply`), not all of them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

#: rows of G C Gᵀ formed at a time by :meth:`NodalCompliance.build`
BLOCK = 512


@dataclass(frozen=True)
class NodalCompliance:
    """``HW = G C Gᵀ W``: the relative nodal displacements [x; y; z] per nodal traction
    [x; y; z] of the points ``G``, ``w``, kept as ``HW_touch`` with the nodes of each
    component in the touch ``order`` (module doc); and ``C`` for the condensed
    displacements ``u = C Gᵀ W λ``.  Flat indices (``c n + node``) of the methods are in
    the nodes' own order."""

    C: np.ndarray
    G: sp.csr_matrix
    w: np.ndarray
    HW_touch: np.ndarray
    order: np.ndarray  # (n,): the nodes in touch order
    decoupled: bool = False  # the normal–tangential blocks of H vanish (see build)
    _kept: tuple = ()  # ((cols, HW[cols][:, cols]), ...) of the last blocks, newest first

    @classmethod
    def build(cls, C: np.ndarray, G: sp.csr_matrix, w: np.ndarray,
              h: np.ndarray | None = None) -> NodalCompliance:
        """From the condensed compliance ``C``, the points' ``G`` and weights ``w``;
        ``h`` the indenter profile at the points (the touch order; none: their order)."""
        n = w.size
        order = np.arange(n) if h is None else np.argsort(h, kind="stable")
        flat = np.concatenate([order + c * n for c in range(3)])
        Gt = G[flat]  # the points' rows in touch order
        # G C Gᵀ in touch order, column-major, its rows formed BLOCK at a time: the
        # dense product G C is never whole (one more matrix of the compliance's size);
        # C is exactly symmetric, so a Fortran-ordered C is read as its C-ordered
        # transpose (a sparse product would copy it at every block)
        Cc = C.T if C.flags.f_contiguous and not C.flags.c_contiguous else C
        H = np.empty((Gt.shape[0], Gt.shape[0]), order="F")
        for start in range(0, Gt.shape[0], BLOCK):
            rows = slice(start, start + BLOCK)
            H[rows] = np.asarray(Gt @ np.asarray(Gt[rows] @ Cc).T).T
        # identical materials (Dundurs' β = 0): the mirrored blocks' normal–tangential
        # compliances cancel in C_rel to the last bit, so H's coupling blocks are zero
        decoupled = H.shape[0] == 3 * n and not (H[2 * n:, :2 * n].any()
                                                 or H[:2 * n, 2 * n:].any())
        H *= np.tile(w[order], 3)[None, :]
        return cls(C=C, G=G, w=w, HW_touch=H, order=order, decoupled=decoupled)

    def _touch(self, idx: np.ndarray) -> np.ndarray:
        """Flat indices in the nodes' order -> flat indices in touch order."""
        n = self.w.size
        rank = np.empty(n, dtype=np.intp)
        rank[self.order] = np.arange(n)
        idx = np.asarray(idx)
        return (idx // n) * n + rank[idx % n]

    def diagonal(self) -> np.ndarray:
        """The self-compliance of each node and component (3, n) [mm/MPa·mm²]."""
        out = np.empty((3, self.w.size))
        out[:, self.order] = np.diag(self.HW_touch).reshape(3, -1)
        return out

    def apply(self, lam: np.ndarray) -> np.ndarray:
        """``HW λ`` (3, n) of the tractions ``lam`` (3, n), reading only the columns up
        to the last loaded node in touch order; decoupled: the normal and tangential
        blocks alone."""
        n, H = self.w.size, self.HW_touch
        lt = lam[:, self.order]
        loaded = np.flatnonzero(lt.any(axis=0))
        d = np.zeros((3, n))
        if loaded.size:
            k = int(loaded[-1]) + 1
            rows = slice(0, 2 * n) if self.decoupled else slice(0, 3 * n)
            flat = H[rows, :k] @ lt[0, :k] + H[rows, n:n + k] @ lt[1, :k]
            if self.decoupled:
                d[:2] = flat.reshape(2, n)
                d[2] = H[2 * n:, 2 * n:2 * n + k] @ lt[2, :k]
            else:
                d = (flat + H[:, 2 * n:2 * n + k] @ lt[2, :k]).reshape(3, n)
        out = np.empty_like(d)
        out[:, self.order] = d
        return out

    def cross(self, rows: np.ndarray, cols: np.ndarray) -> np.ndarray:
        """``HW[rows][:, cols]`` (flat indices in the nodes' order)."""
        return self.HW_touch[np.ix_(self._touch(rows), self._touch(cols))]

    def block(self, cols: np.ndarray) -> np.ndarray:
        """``HW[cols][:, cols]`` (``cols`` sorted), the last two kept for the next calls
        with the same ``cols`` (the gather from the large matrix costs more than the
        Newton system's copy; a block-triangular system asks for two blocks)."""
        for kept_cols, B in self._kept:
            if np.array_equal(kept_cols, cols):
                return B
        t = self._touch(cols)
        if self.decoupled:  # the normal–tangential blocks are zero: not gathered
            k = int(np.searchsorted(cols, 2 * self.w.size))  # cols sorted
            B = np.zeros((cols.size, cols.size))
            B[:k, :k] = self.HW_touch[np.ix_(t[:k], t[:k])]
            B[k:, k:] = self.HW_touch[np.ix_(t[k:], t[k:])]
        else:
            B = self.HW_touch[np.ix_(t, t)]
        object.__setattr__(self, "_kept", ((cols.copy(), B), *self._kept[:1]))
        return B

    def u(self, lam: np.ndarray) -> np.ndarray:
        """Condensed displacements of the tractions ``lam`` (3, n)."""
        return self.C @ (self.G.T @ (np.tile(self.w, 3) * lam.ravel()))
