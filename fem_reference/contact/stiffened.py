"""The linear solve of the contact Newton iteration: ``(K + B) x = r`` with ``K = C⁻¹``.

``C`` is the dense condensed compliance of the surface DOFs (symmetric), ``B`` the sparse
tangent of the contact laws (:func:`fem_reference.contact.laws.evaluate`), nonzero only on the
DOFs ``A`` touched by points in contact.  The push-through (Woodbury) identity

    (K + B)⁻¹ = C − C_{:A} M⁻¹ B_AA C_{A:},        M = I + B_AA C_AA,

shrinks the dense factorisation from all condensed DOFs to those of ``A``; it holds for
any set ``A`` that contains the support of ``B`` (the extra rows of ``B_AA`` are zero).

Between two Newton iterations, or two passes of the augmented Lagrangian, the tangent
changes at the few points whose state changed (stick → slip, open → contact).  A
:class:`StiffenedSolver` keeps the LU factors of one matrix ``M₀ = I + B₀ C`` on a set
``A₀`` and solves with a later ``M = M₀' + ΔB C`` by the Woodbury identity for the
low-rank change ``ΔB`` (its nonzero rows S):

    M⁻¹ = M₀'⁻¹ − W (I_S + V W)⁻¹ V M₀'⁻¹,     W = M₀'⁻¹ E_S,  V = ΔB_S: C,

where ``M₀'`` is ``M₀`` bordered by the DOFs ``X = A \\ A₀`` that came into contact
since (``B₀`` is zero there, so ``M₀' = [[M₀, B₀ C_{A₀X}], [0, I]]`` is block upper
triangular and solved by ``M₀``'s factors alone).  The columns of ``W`` depend only on the
DOF, not on ``ΔB``, and are kept.  When S grows beyond a fraction of ``A`` (the update
would cost more than a new factorisation) the solver factorises the current ``M``.  The
result is the solve of the current ``B`` to round-off either way: the factors are an
economy, not an approximation.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp

#: refactorise when the rank of the change exceeds this fraction of |A| (the update's
#: solves cost about 2 |S| |A|² flops against (2/3) |A|³ for new LU factors)
RANK_FRACTION = 1.0 / 6.0
MIN_RANK = 48  # ... or this many DOFs, below which an update is always cheaper


def _rank_limit(size: int) -> int:
    """The largest rank of a change the kept factors of a block of ``size`` DOFs take."""
    return max(MIN_RANK, int(RANK_FRACTION * size))


def support(B: sp.csr_matrix) -> np.ndarray:
    """The DOFs of B's nonzero rows and columns (sorted): a point's tangent need not be
    symmetric (slip couples t to u_n, not p_n to u_t), and a row without its column
    would be lost by B_AA."""
    return np.unique(np.concatenate(B.nonzero()))


class StiffenedSolver:
    """Solves ``(C⁻¹ + B) x = rhs`` for a sequence of contact tangents B (module doc)."""

    def __init__(self, C: np.ndarray):
        self.C = C
        self.A0: np.ndarray | None = None  # DOFs of the factorised M₀
        self.B0: sp.csr_matrix | None = None  # B₀ on A₀ × A₀ (local indices)
        self.lu = None
        self.cols: dict[int, np.ndarray] = {}  # DOF -> the A₀ part of M₀'⁻¹ e_DOF
        self._rows: tuple[np.ndarray, np.ndarray] | None = None  # (A', C[A']), the last
        self.factorisations = 0
        self.updates = 0

    # ------------------------------------------------------------------ factors

    def _factorise(self, A: np.ndarray, BAA: sp.csr_matrix, C_A: np.ndarray) -> None:
        M = BAA @ C_A[:, A]
        M[np.diag_indices_from(M)] += 1.0
        self.lu = la.lu_factor(M, overwrite_a=True, check_finite=False)
        self.A0, self.B0 = A, BAA
        self.cols = {}
        self.factorisations += 1

    def _m0_solve(self, b: np.ndarray, n0: int, Y: np.ndarray | None) -> np.ndarray:
        """``M₀'⁻¹ b`` for b (|A'|, k) ordered (A₀, X): x_X = b_X, x₀ = M₀⁻¹(b₀ − Y b_X)."""
        x = b.copy()
        rhs0 = b[:n0] if Y is None else b[:n0] - Y @ b[n0:]
        x[:n0] = la.lu_solve(self.lu, rhs0, check_finite=False)
        return x

    # ------------------------------------------------------------------ solve

    def solve(self, B: sp.spmatrix, rhs: np.ndarray) -> np.ndarray:
        """x with ``(C⁻¹ + B) x = rhs`` (rhs (n,) or (n, k))."""
        C = self.C
        y = C @ rhs
        B = sp.csr_matrix(B)
        B.eliminate_zeros()
        B.sort_indices()
        A = support(B)
        if A.size == 0:
            return y
        two_d = y.ndim == 2
        Y2 = y if two_d else y[:, None]
        X = None if self.lu is None else np.setdiff1d(A, self.A0, assume_unique=True)
        if X is None or X.size > _rank_limit(self.A0.size + X.size):
            out = self._fresh(A, B, Y2)
        else:
            out = self._solve_updated(A, X, B, Y2)
        return out if two_d else out[:, 0]

    def _c_rows(self, Ap: np.ndarray) -> np.ndarray:
        """``C[A']``, the rows A' (= the columns A' transposed: C is symmetric), kept
        for the next solve on the same set (the gather costs more than the solve)."""
        if self._rows is None or not np.array_equal(self._rows[0], Ap):
            self._rows = (Ap, self.C[Ap])
        return self._rows[1]

    def _fresh(self, A: np.ndarray, B: sp.csr_matrix, Y2: np.ndarray) -> np.ndarray:
        """New factors of M on A, and the solve with them."""
        C_A = self._c_rows(A)
        BAA = B[A][:, A]
        self._factorise(A, BAA, C_A)
        z = la.lu_solve(self.lu, BAA @ Y2[A], check_finite=False)
        return Y2 - C_A.T @ z

    def _solve_updated(self, A: np.ndarray, X: np.ndarray, B: sp.csr_matrix,
                       Y2: np.ndarray) -> np.ndarray:
        """The solve with M₀'s factors and the Woodbury update of ΔB (module doc); X:
        the DOFs of A not in A₀."""
        A0 = self.A0
        n0 = A0.size
        Ap = np.concatenate([A0, X])  # A' in the order (A₀, X)
        C_A = self._c_rows(Ap)
        Bn = B[Ap][:, Ap].tocsr()
        B0p = sp.block_diag([self.B0, sp.csr_matrix((X.size, X.size))], format="csr")
        dB = (Bn - B0p).tocsr()
        dB.eliminate_zeros()
        S = np.unique(dB.nonzero()[0])
        if S.size > _rank_limit(Ap.size):  # cheaper to factorise the current M
            return self._fresh(A, B, Y2)
        Yb = None
        if X.size:
            Yb = self.B0 @ C_A[:n0][:, X]  # B₀ C_{A₀X}: (|A₀|, |X|)
        b = Bn @ Y2[Ap]
        z0 = self._m0_solve(b, n0, Yb)
        if S.size:
            W = self._columns(S, Ap, n0, Yb)  # (|A'|, |S|)
            V = (dB[S] @ C_A)[:, Ap]  # ΔB_S: C_{A'A'} (C_A: the rows A')
            cap = V @ W
            cap[np.diag_indices_from(cap)] += 1.0
            z0 = z0 - W @ la.solve(cap, V @ z0, check_finite=False)
            self.updates += 1
        return Y2 - C_A.T @ z0

    def _columns(self, S: np.ndarray, Ap: np.ndarray, n0: int, Yb: np.ndarray | None
                 ) -> np.ndarray:
        """``W = M₀'⁻¹ E_S`` (|A'|, |S|): the A₀ part from the kept columns, solving the
        missing ones together; an X DOF's column is e_x in X and −M₀⁻¹(Y e_x) in A₀."""
        dofs = Ap[S]
        missing = [k for k, d in enumerate(dofs) if int(d) not in self.cols]
        if missing:
            R = np.zeros((n0, len(missing)))
            for j, k in enumerate(missing):
                s = S[k]
                if s < n0:
                    R[s, j] = 1.0
                else:
                    R[:, j] = -Yb[:, s - n0]
            sol = la.lu_solve(self.lu, R, check_finite=False)
            for j, k in enumerate(missing):
                self.cols[int(dofs[k])] = sol[:, j]
        W = np.zeros((Ap.size, S.size))
        W[:n0] = np.column_stack([self.cols[int(d)] for d in dofs])
        x_rows = S >= n0
        W[S[x_rows], np.nonzero(x_rows)[0]] = 1.0
        return W
