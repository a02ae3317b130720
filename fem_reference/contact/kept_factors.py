"""Kept LU factors of the semi-smooth Newton systems (:mod:`fem_reference.contact.semismooth`),
preconditioning GMRES on the next systems."""

from __future__ import annotations

import numpy as np
import scipy.linalg as la
from scipy.sparse.linalg import LinearOperator, gmres

from .row_system import RowSystem

#: a Newton system on the unknowns of the kept factors is solved by GMRES preconditioned
#: with them, in at most this many iterations (else the factors are renewed) ...
KRYLOV_MAX = 30
#: ... to this relative residual (checked on the system): an inexact Newton step that
#: contracts the residual by about this factor per iteration near the solution
KRYLOV_RTOL = 1e-6


class KeptFactors:
    """The LU factors of one Newton system
    (:func:`fem_reference.contact.semismooth.semismooth`), kept across iterations and solves. A
    later system differs in the rows of the nodes whose state or slip direction changed
    and in the few nodes that came into or out of contact: GMRES, preconditioned by the
    kept factors (on the unknowns both systems share; a new unknown by its diagonal),
    solves it in a few iterations of O(N²) instead of a new O(N³) factorisation. Counts
    ``factorisations`` and ``krylov`` solves."""

    def __init__(self) -> None:
        self.cols: np.ndarray | None = None
        self.extra = -1
        self.lu = None
        self.factorisations = 0
        self.krylov = 0
        self._parts: dict[str, KeptFactors] = {}

    def part(self, key: str) -> KeptFactors:
        """The kept factors of the diagonal block ``key`` of block-triangular systems,
        kept across solves like these."""
        return self._parts.setdefault(key, KeptFactors())

    def solve(self, J: RowSystem, cols: np.ndarray) -> np.ndarray:
        """The solution of ``J x = J.b``, ``cols`` the traction unknowns of ``J``: by
        GMRES with the kept factors, else by new ones (``J`` formed dense only then)."""
        b = J.b
        extra = J.shape[0] - cols.size
        if self.lu is not None and extra == self.extra:
            x = self._krylov(J, b, cols)
            if x is not None:
                self.krylov += 1
                return x
        self.lu = la.lu_factor(J.dense(), overwrite_a=True, check_finite=False)
        self.cols, self.extra = cols.copy(), extra
        self.factorisations += 1
        return la.lu_solve(self.lu, b, check_finite=False)

    def _krylov(self, J: RowSystem, b: np.ndarray, cols: np.ndarray) -> np.ndarray | None:
        old, n_old = self.cols, self.lu[0].shape[0]
        pos = np.searchsorted(old, cols)  # cols and old are sorted within their blocks
        pos = np.minimum(pos, old.size - 1)
        shared = old[pos] == cols
        if not np.array_equal(np.sort(old), old) or shared.sum() < 0.9 * max(cols.size, old.size):
            return None
        i_new = np.concatenate([np.flatnonzero(shared), cols.size + np.arange(self.extra)])
        i_old = np.concatenate([pos[shared], old.size + np.arange(self.extra)])
        alone = np.flatnonzero(~shared)
        diag = J.diagonal()[alone]
        if np.any(diag == 0):
            return None

        def prec(v: np.ndarray) -> np.ndarray:
            w = np.zeros(n_old)
            w[i_old] = v[i_new]
            z = la.lu_solve(self.lu, w, check_finite=False)
            out = np.empty_like(v)
            out[i_new] = z[i_old]
            out[alone] = v[alone] / diag
            return out

        M = LinearOperator(J.shape, matvec=prec, dtype=float)
        A = LinearOperator(J.shape, matvec=J.matvec, dtype=float)
        x, info = gmres(A, b, x0=prec(b), rtol=KRYLOV_RTOL, restart=KRYLOV_MAX, maxiter=1,
                        M=M)
        if info != 0 or not np.isfinite(x).all() or np.linalg.norm(J.matvec(x) - b) \
                > 10 * KRYLOV_RTOL * max(float(np.linalg.norm(b)), 1e-300):
            return None
        return x
