"""A semi-smooth Newton system held as rows of the nodal compliance block.

Every row of the systems of :mod:`.newton_system` and :mod:`.block_system` is a row of
the compliance block ``B = HW[cols][:, cols]`` (a gap or a stick condition: Δd of the
kept unknowns), a combination of two or three of its rows (a slip node's rows,
:mod:`.newton_rows`), or none (a control equation, a component a symmetry plane holds),
plus a few entries of its own.  So

    J = R [B 0] + E,

with ``R`` (N × nk) sparse — one entry per mapped row, two or three per slip row — and
``E`` (N × N) sparse.  A Krylov solve needs only products ``J x = R (B x) + E x``, so a
Newton step that the kept factors precondition (:mod:`.kept_factors`) neither copies
``B`` nor writes the slip rows; the dense ``J`` is formed only for a new factorisation,
the same numbers as written row by row (each slip row's sum in the order of its terms).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp


@dataclass(frozen=True)
class RowSystem:
    """``J = R [B 0] + E`` (module doc) and its right-hand side ``b``."""

    B: np.ndarray  # (nk, nk), the compliance block, not copied
    R: sp.csr_matrix  # (N, nk)
    E: sp.csr_matrix  # (N, N)
    b: np.ndarray  # (N,)

    @property
    def shape(self) -> tuple[int, int]:
        return self.E.shape

    def matvec(self, x: np.ndarray) -> np.ndarray:
        """``J x``."""
        return self.R @ (self.B @ x[:self.B.shape[0]]) + self.E @ x

    def dense(self) -> np.ndarray:
        """``J`` as a dense array."""
        nk = self.B.shape[0]
        J = np.zeros(self.shape)
        J[:, :nk] = self.R @ self.B
        e = self.E.tocoo()
        J[e.row, e.col] += e.data
        return J

    def diagonal(self) -> np.ndarray:
        """The diagonal of ``J``."""
        r = self.R.tocoo()
        on = r.row < self.B.shape[0]
        d = np.bincount(r.row[on], r.data[on] * self.B[r.col[on], r.row[on]],
                        minlength=self.shape[0])
        return d + self.E.diagonal()


class Rows:
    """A :class:`RowSystem` under construction: every row of ``B`` mapped as it is, until
    :meth:`combine` replaces it, :meth:`clear` empties it, or it is an extra row (index
    ``nk`` and beyond: no row of ``B``); :meth:`add` adds entries of ``E``."""

    def __init__(self, B: np.ndarray, n_extra: int):
        self.B, self.nk = B, B.shape[0]
        self.N = self.nk + n_extra
        self.b = np.zeros(self.N)
        self._mapped = np.zeros(self.N, dtype=bool)
        self._mapped[:self.nk] = True
        self._r: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []
        self._e: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []

    def combine(self, rows: np.ndarray, terms: list[tuple[np.ndarray, np.ndarray]]) -> None:
        """Rows ``rows`` become Σ ``coef`` × (row ``col`` of B) over ``terms`` (``(col,
        coef)`` arrays, one entry per row each), summed in that order."""
        self._mapped[rows] = False
        for col, coef in terms:
            self._r.append(_entries(rows, col, coef))

    def add(self, rows, cols, values) -> None:
        """Entries of ``E`` (added where an entry is there already)."""
        self._e.append(_entries(rows, cols, values))

    def clear(self, rows: np.ndarray) -> None:
        """Rows ``rows`` hold nothing so far (the entries added later stay)."""
        self._mapped[rows] = False
        self._r = [_drop(e, rows) for e in self._r]
        self._e = [_drop(e, rows) for e in self._e]

    def system(self) -> RowSystem:
        mapped = np.flatnonzero(self._mapped)
        r = [(mapped, mapped, np.ones(mapped.size)), *self._r]
        R = _csr(r, (self.N, self.nk))
        E = _csr(self._e, (self.N, self.N))
        return RowSystem(B=self.B, R=R, E=E, b=self.b)


def _entries(rows, cols, values) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    rows = np.atleast_1d(np.asarray(rows, dtype=np.intp))
    cols = np.broadcast_to(np.asarray(cols, dtype=np.intp), rows.shape)
    values = np.broadcast_to(np.asarray(values, dtype=float), rows.shape)
    return rows, cols.copy(), values.copy()


def _drop(e: tuple[np.ndarray, np.ndarray, np.ndarray], rows: np.ndarray
          ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    keep = ~np.isin(e[0], rows)
    return e[0][keep], e[1][keep], e[2][keep]


def _csr(parts: list, shape: tuple[int, int]) -> sp.csr_matrix:
    """The entries ``parts`` as CSR, duplicates summed in the order given (a stable sort
    by row, then column, keeps each sum in the order of its terms)."""
    if not parts:
        return sp.csr_matrix(shape)
    rows, cols, vals = (np.concatenate(x) for x in zip(*parts, strict=True))
    order = np.lexsort((cols, rows))
    rows, cols, vals = rows[order], cols[order], vals[order]
    first = np.ones(rows.size, dtype=bool)
    first[1:] = (rows[1:] != rows[:-1]) | (cols[1:] != cols[:-1])
    starts = np.flatnonzero(first)
    summed = np.add.reduceat(vals, starts) if vals.size else vals
    indptr = np.zeros(shape[0] + 1, dtype=np.intp)
    np.add.at(indptr, rows[starts] + 1, 1)
    return sp.csr_matrix((summed, cols[starts], np.cumsum(indptr)), shape=shape)
