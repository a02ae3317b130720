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

from .relative import RelativeCompliance

#: rows of G C Gᵀ formed at a time by :meth:`NodalCompliance.build`
BLOCK = 512


@dataclass(frozen=True)
class NodalCompliance:
    """``HW = G C Gᵀ W``: the relative nodal displacements [x; y; z] per nodal traction
    [x; y; z] of the points ``G``, ``w``, kept with the nodes of each component in the
    touch ``order`` (module doc) as its diagonal ``blocks`` ``(first row, block)``: the
    whole matrix, or, ``decoupled``, its tangential and normal blocks alone (the
    coupling blocks are zero, and not kept; nor the block of components with no
    condensed DOF, a normal contact's tangential one); and ``C`` for the condensed
    displacements ``u = C Gᵀ W λ``.  Flat indices (``c n + node``) of the methods are in
    the nodes' own order."""

    C: np.ndarray | RelativeCompliance
    G: sp.csr_matrix
    w: np.ndarray
    blocks: tuple[tuple[int, np.ndarray], ...]
    order: np.ndarray  # (n,): the nodes in touch order
    decoupled: bool = False  # the normal–tangential blocks of H vanish (see build)
    _kept: tuple = ()  # ((cols, HW[cols][:, cols]), ...) of the last blocks, newest first

    @classmethod
    def build(cls, C: np.ndarray | RelativeCompliance, G: sp.csr_matrix, w: np.ndarray,
              h: np.ndarray | None = None) -> NodalCompliance:
        """From the condensed compliance ``C``, the points' ``G`` and weights ``w``;
        ``h`` the indenter profile at the points (the touch order; none: their order)."""
        n = w.size
        order = np.arange(n) if h is None else np.argsort(h, kind="stable")
        flat = np.concatenate([order + c * n for c in range(3)])
        Gt = G[flat]  # the points' rows in touch order
        # identical materials (Dundurs' β = 0): the mirrored blocks' normal–tangential
        # compliances cancel in C_rel to the last bit, so H's coupling blocks are zero
        blocks = _decoupled(Gt, C, n)
        decoupled = blocks is not None
        if blocks is None:
            blocks = _whole(Gt, C)
        for first, B in blocks:
            B *= np.tile(w[order], 3)[None, first:first + B.shape[1]]
        return cls(C=C, G=G, w=w, blocks=tuple(blocks), order=order, decoupled=decoupled)

    def _touch(self, idx: np.ndarray) -> np.ndarray:
        """Flat indices in the nodes' order -> flat indices in touch order."""
        n = self.w.size
        rank = np.empty(n, dtype=np.intp)
        rank[self.order] = np.arange(n)
        idx = np.asarray(idx)
        return (idx // n) * n + rank[idx % n]

    def diagonal(self) -> np.ndarray:
        """The self-compliance of each node and component (3, n) [mm/MPa·mm²]."""
        d = np.zeros(3 * self.w.size)
        for first, B in self.blocks:
            d[first:first + B.shape[0]] = np.diag(B)
        out = np.empty((3, self.w.size))
        out[:, self.order] = d.reshape(3, -1)
        return out

    def apply(self, lam: np.ndarray) -> np.ndarray:
        """``HW λ`` (3, n) of the tractions ``lam`` (3, n), reading only the columns up
        to the last loaded node in touch order; decoupled: the normal and tangential
        blocks alone."""
        n = self.w.size
        lt = lam[:, self.order]
        loaded = np.flatnonzero(lt.any(axis=0))
        d = np.zeros(3 * n)
        if loaded.size:
            k = int(loaded[-1]) + 1
            for first, B in self.blocks:
                comps = range(first // n, first // n + B.shape[1] // n)
                rows = slice(first, first + B.shape[0])
                for j, c in enumerate(comps):
                    d[rows] += B[:, j * n:j * n + k] @ lt[c, :k]
        out = np.empty((3, n))
        out[:, self.order] = d.reshape(3, n)
        return out

    def cross(self, rows: np.ndarray, cols: np.ndarray) -> np.ndarray:
        """``HW[rows][:, cols]`` (flat indices in the nodes' order)."""
        return self._gather(self._touch(rows), self._touch(cols))

    def block(self, cols: np.ndarray) -> np.ndarray:
        """``HW[cols][:, cols]`` (``cols`` sorted), the last two kept for the next calls
        with the same ``cols`` (the gather from the large matrix costs more than the
        Newton system's copy; a block-triangular system asks for two blocks)."""
        for kept_cols, B in self._kept:
            if np.array_equal(kept_cols, cols):
                return B
        t = self._touch(cols)
        B = self._gather(t, t)
        object.__setattr__(self, "_kept", ((cols.copy(), B), *self._kept[:1]))
        return B

    def _gather(self, tr: np.ndarray, tc: np.ndarray) -> np.ndarray:
        """``HW[tr][:, tc]`` of flat indices in touch order (zero off the blocks)."""
        if len(self.blocks) == 1 and self.blocks[0][1].shape[0] == 3 * self.w.size:
            return self.blocks[0][1][np.ix_(tr, tc)]
        out = np.zeros((tr.size, tc.size))
        for first, B in self.blocks:
            size = B.shape[0]
            r = np.flatnonzero((tr >= first) & (tr < first + size))
            c = np.flatnonzero((tc >= first) & (tc < first + size))
            out[np.ix_(r, c)] = B[np.ix_(tr[r] - first, tc[c] - first)]
        return out

    def u(self, lam: np.ndarray) -> np.ndarray:
        """Condensed displacements of the tractions ``lam`` (3, n)."""
        return self.C @ (self.G.T @ (np.tile(self.w, 3) * lam.ravel()))


def _rows(Gt: sp.csr_matrix, C, start: int, stop: int) -> np.ndarray:
    """Rows ``start:stop`` of ``G C Gᵀ`` (G's rows ``Gt`` in touch order), BLOCK at a
    time: the dense product G C is never whole (one more matrix of the compliance's
    size)."""
    out = np.empty((stop - start, Gt.shape[0]))
    for first in range(start, stop, BLOCK):
        last = min(first + BLOCK, stop)
        out[first - start:last - start] = np.asarray(Gt @ _left(Gt[first:last], C).T).T
    return out


def _whole(Gt: sp.csr_matrix, C) -> list[tuple[int, np.ndarray]]:
    """``G C Gᵀ`` whole, column-major, as one diagonal block."""
    H = np.empty((Gt.shape[0], Gt.shape[0]), order="F")
    for first in range(0, Gt.shape[0], BLOCK):
        H[first:first + BLOCK] = _rows(Gt, C, first, min(first + BLOCK, Gt.shape[0]))
    return [(0, H)]


def _decoupled(Gt: sp.csr_matrix, C, n: int) -> list[tuple[int, np.ndarray]] | None:
    """The tangential and normal diagonal blocks of ``G C Gᵀ`` (column-major), where
    every entry of its coupling blocks is zero (None at the first that is not); a block
    whose rows of G are empty (no condensed DOF of its components) is left out."""
    blocks = []
    for lo, hi in ((0, 2 * n), (2 * n, 3 * n)):
        if Gt[lo:hi].nnz == 0:
            continue
        B = np.empty((hi - lo, hi - lo), order="F")
        for first in range(lo, hi, BLOCK):
            last = min(first + BLOCK, hi)
            R = _rows(Gt, C, first, last)
            if R[:, :lo].any() or R[:, hi:].any():
                return None
            B[first - lo:last - lo] = R[:, lo:hi]
        blocks.append((lo, B))
    return blocks


def _left(S: sp.csr_matrix, C) -> np.ndarray:
    """``S C`` for sparse rows ``S`` and the exactly symmetric compliance ``C``: a dense
    array (a Fortran-ordered one read as its C-ordered transpose: a sparse product would
    copy it), or a :class:`~fem_reference.contact.relative.RelativeCompliance` (the rows
    of C that S reads, formed for them alone; the same sums in the same order)."""
    if isinstance(C, np.ndarray):
        return np.asarray(S @ (C.T if C.flags.f_contiguous and not C.flags.c_contiguous
                               else C))
    S = S.tocsr()
    K = np.unique(S.indices)
    return np.asarray(S[:, K] @ C.rows(K))
