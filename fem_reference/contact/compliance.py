"""The nodal compliance of the contact points: the condensed compliance seen from the
nodes, the elastic operator of the semi-smooth contact solve
(:mod:`fem_reference.contact.semismooth`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp


@dataclass(frozen=True)
class NodalCompliance:
    """``HW = G C Gᵀ W``: the relative nodal displacements [x; y; z] per nodal traction
    [x; y; z] of the points ``G``, ``w``; and ``C`` for the condensed displacements
    ``u = C Gᵀ W λ``."""

    C: np.ndarray
    G: sp.csr_matrix
    w: np.ndarray
    HW: np.ndarray
    decoupled: bool = False  # the normal–tangential blocks of H vanish (see build)
    _last: tuple | None = None  # (cols, HW[cols][:, cols]) of the last block

    @classmethod
    def build(cls, C: np.ndarray, G: sp.csr_matrix, w: np.ndarray) -> NodalCompliance:
        GC = np.asarray(G @ C)  # (3n, m)
        H = np.asarray(G @ GC.T).T  # G C Gᵀ
        n = w.size
        # identical materials (Dundurs' β = 0): the mirrored blocks' normal–tangential
        # compliances cancel in C_rel to the last bit, so H's coupling blocks are zero
        decoupled = H.shape[0] == 3 * n and not (H[2 * n:, :2 * n].any()
                                                 or H[:2 * n, 2 * n:].any())
        return cls(C=C, G=G, w=w, HW=H * np.tile(w, 3)[None, :], decoupled=decoupled)

    def block(self, cols: np.ndarray) -> np.ndarray:
        """``HW[cols][:, cols]`` (``cols`` sorted), kept for the next call with the same
        ``cols`` (the gather from the large matrix costs more than the Newton system's
        copy)."""
        last = self._last
        if last is None or not np.array_equal(last[0], cols):
            if self.decoupled:  # the normal–tangential blocks are zero: not gathered
                k = int(np.searchsorted(cols, 2 * self.w.size))  # cols sorted
                B = np.zeros((cols.size, cols.size))
                B[:k, :k] = self.HW[np.ix_(cols[:k], cols[:k])]
                B[k:, k:] = self.HW[np.ix_(cols[k:], cols[k:])]
            else:
                B = self.HW[np.ix_(cols, cols)]
            last = (cols.copy(), B)
            object.__setattr__(self, "_last", last)
        return last[1]

    def u(self, lam: np.ndarray) -> np.ndarray:
        """Condensed displacements of the tractions ``lam`` (3, n)."""
        return self.C @ (self.G.T @ (np.tile(self.w, 3) * lam.ravel()))
