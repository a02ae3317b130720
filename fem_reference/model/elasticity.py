"""Quadratic (P2) tetrahedral elasticity: DOF numbering, vectorised stiffness, solver.

Scalar P2 nodes follow scikit-fem's ``ElementTetP2`` numbering: the mesh vertices first,
then one node per edge (``nverts + edge index``); the local order inside a tetrahedron
is the 4 vertices and the edges (0,1), (1,2), (0,2), (0,3), (1,3), (2,3), the VTK
``tetra10`` order.  The vector field has the DOFs ``3 * node + component``.

The stiffness ``K = ∫ ε(v) : D ε(u) dV`` of isotropic elasticity (Young's modulus 1,
Poisson's ratio ν; scale by E) is assembled element by element with numpy (a 4-point
degree-2 rule is exact for the P2 gradient products on straight tetrahedra) — about
an order of magnitude faster than scikit-fem's form-based ``linear_elasticity`` for P2,
which it reproduces to round-off (``tests/test_fem_elasticity.py``).
"""

from __future__ import annotations

import ctypes

import numpy as np
import scipy.sparse as sp
from skfem import MeshTet

from ..errors import FemError

# local edges of a tetrahedron, scikit-fem / VTK tetra10 order
TET_EDGES = np.array([[0, 1], [1, 2], [0, 2], [0, 3], [1, 3], [2, 3]])

# 4-point rule on the tetrahedron, exact for degree 2 (barycentric coordinates)
_QA = (5.0 + 3.0 * np.sqrt(5.0)) / 20.0
_QB = (5.0 - np.sqrt(5.0)) / 20.0
TET_QUAD = np.full((4, 4), _QB) + np.eye(4) * (_QA - _QB)  # rows: points, cols: λ0..λ3
TET_QUAD_W = np.full(4, 0.25)  # fractions of the element volume


def lame(nu: float, E: float = 1.0) -> tuple[float, float]:
    """Lamé constants (λ, μ) of an isotropic material."""
    return E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), E / (2.0 * (1.0 + nu))


class P2Space:
    """The P2 nodes of a tetrahedral mesh and the geometry of its elements."""

    def __init__(self, mesh: MeshTet):
        self.mesh = mesh
        self.nverts = mesh.p.shape[1]
        self.nel = mesh.t.shape[1]
        edges = mesh.edges  # (2, nedges), sorted vertex pairs
        self.nnodes = self.nverts + edges.shape[1]
        self.ndofs = 3 * self.nnodes
        self.nodes = np.hstack([mesh.p, 0.5 * (mesh.p[:, edges[0]] + mesh.p[:, edges[1]])])
        self.element_nodes = np.vstack([mesh.t, self.nverts + mesh.t2e])  # (10, nel)
        self._edge_keys = edges[0].astype(np.int64) * self.nverts + edges[1]
        order = np.argsort(self._edge_keys)
        self._edge_sorted = self._edge_keys[order]
        self._edge_order = order
        P = mesh.p[:, mesh.t]  # (3, 4, nel)
        J = np.stack([P[:, 1] - P[:, 0], P[:, 2] - P[:, 0], P[:, 3] - P[:, 0]], axis=-1)
        J = np.moveaxis(J, 1, 0)  # (nel, 3, 3): columns p_k - p_0
        det = np.linalg.det(J)
        if (np.abs(det) <= 0).any():
            raise ValueError("degenerate tetrahedra in the mesh")
        invJ = np.linalg.inv(J)  # rows k: gradient of λ_{k+1}
        grad = np.empty((self.nel, 4, 3))
        grad[:, 1:, :] = invJ
        grad[:, 0, :] = -invJ.sum(axis=1)
        self.grad_lambda = grad  # (nel, 4, 3)
        self.volume = np.abs(det) / 6.0
        self.origin = P[:, 0, :].T.copy()  # (nel, 3)
        self.invJ = invJ

    def edge_node(self, i: np.ndarray, j: np.ndarray) -> np.ndarray:
        """P2 node index of the edge between vertices ``i`` and ``j`` (arrays)."""
        a, b = np.minimum(i, j), np.maximum(i, j)
        keys = a.astype(np.int64) * self.nverts + b
        pos = np.searchsorted(self._edge_sorted, keys)
        pos = np.clip(pos, 0, self._edge_sorted.size - 1)
        if not np.array_equal(self._edge_sorted[pos], keys):
            raise KeyError("some vertex pairs are not mesh edges")
        return self.nverts + self._edge_order[pos]

    def barycentric(self, points: np.ndarray, elements: np.ndarray) -> np.ndarray:
        """Barycentric coordinates (n, 4) of ``points`` (n, 3) in ``elements`` (n,)."""
        rel = points - self.origin[elements]
        lam = np.einsum("nij,nj->ni", self.invJ[elements], rel)
        return np.hstack([1.0 - lam.sum(axis=1, keepdims=True), lam])


def p2_values(lam: np.ndarray) -> np.ndarray:
    """P2 shape functions (..., 10) at barycentric coordinates ``lam`` (..., 4)."""
    vert = lam * (2.0 * lam - 1.0)
    edge = 4.0 * lam[..., TET_EDGES[:, 0]] * lam[..., TET_EDGES[:, 1]]
    return np.concatenate([vert, edge], axis=-1)


def p2_gradients(lam: np.ndarray, grad_lambda: np.ndarray) -> np.ndarray:
    """Gradients (..., 10, 3) of the P2 shape functions.

    ``lam`` (..., 4) barycentric coordinates, ``grad_lambda`` (..., 4, 3) their
    (constant) gradients in the element.
    """
    gv = (4.0 * lam - 1.0)[..., None] * grad_lambda
    i, j = TET_EDGES[:, 0], TET_EDGES[:, 1]
    ge = 4.0 * (lam[..., i, None] * grad_lambda[..., j, :]
                + lam[..., j, None] * grad_lambda[..., i, :])
    return np.concatenate([gv, ge], axis=-2)


def stiffness(space: P2Space, nu: float, *, elements: np.ndarray | None = None,
              chunk: int = 20000) -> sp.csr_matrix:
    """Global stiffness matrix (E = 1, Poisson's ratio ``nu``), CSR, DOFs 3*node+comp;
    of the ``elements`` alone where given (their rows are whole at the nodes no other
    element touches)."""
    lam_, mu_ = lame(nu)
    rows, cols, vals = [], [], []
    eye3 = np.eye(3)
    el = np.arange(space.nel) if elements is None else np.asarray(elements)
    for start in range(0, el.size, chunk):
        sl = el[start:start + chunk]
        gl = space.grad_lambda[sl]  # (n, 4, 3)
        vol = space.volume[sl]
        n = gl.shape[0]
        Ke = np.zeros((n, 10, 3, 10, 3))
        for q in range(TET_QUAD.shape[0]):
            G = p2_gradients(np.broadcast_to(TET_QUAD[q], (n, 4)), gl)  # (n, 10, 3)
            wq = TET_QUAD_W[q] * vol
            T = np.einsum("nai,nbj,n->naibj", G, G, wq)  # ∂_i φ_a ∂_j φ_b
            S = np.einsum("naibi->nab", T)  # ∇φ_a · ∇φ_b
            Ke += lam_ * T + mu_ * (
                np.einsum("nab,ij->naibj", S, eye3) + T.transpose(0, 1, 4, 3, 2)
            )
        dofs = 3 * space.element_nodes[:, sl].T[:, :, None] + np.arange(3)  # (n, 10, 3)
        dofs = dofs.reshape(n, 30)
        rows.append(np.repeat(dofs, 30, axis=1).ravel())
        cols.append(np.tile(dofs, (1, 30)).ravel())
        vals.append(Ke.reshape(n, 900).ravel())
    K = sp.coo_matrix(
        (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
        shape=(space.ndofs, space.ndofs),
    ).tocsr()
    K.sum_duplicates()
    return K


def stress_from_gradient(grad_u: np.ndarray, nu: float, E: float = 1.0) -> np.ndarray:
    """Stress tensors (..., 3, 3) from displacement gradients (..., 3, 3) [i, j] = ∂u_i/∂x_j."""
    lam_, mu_ = lame(nu, E)
    eps = 0.5 * (grad_u + np.swapaxes(grad_u, -1, -2))
    tr = np.trace(eps, axis1=-2, axis2=-1)
    return 2.0 * mu_ * eps + lam_ * tr[..., None, None] * np.eye(3)


#: PARDISO's thread count, fixed: MKL's default (dynamic) picks fewer threads when the
#: machine is busy, and the factors then differ in the last digits (measured: σ_VM,max
#: of the quick dissimilar case 2.6e-12 apart between 1 and 2 threads)
PARDISO_THREADS = 2
#: MKL's conditional numerical reproducibility (``MKL_CBWR``) unless the environment sets
#: it: without it MKL's code path depends on the alignment of the arrays it is given, so
#: the same run in another process (a Dask worker) differed in the last bit of a few values
CBWR = "AUTO"


def _pardiso_solver():
    """A new symmetric positive-definite PARDISO solver on :data:`PARDISO_THREADS`, with
    MKL in its reproducible mode (:data:`CBWR`).

    pypardiso searches the whole Python prefix for MKL's ``mkl_rt`` on every instance
    (seconds) unless ``PYPARDISO_MKL_RT`` names it; the first instance records the
    library it found there for the later ones.
    """
    import os

    os.environ.setdefault("MKL_CBWR", CBWR)  # read when MKL loads, below
    import pypardiso

    solver = pypardiso.PyPardisoSolver(mtype=2)
    if not os.environ.get("PYPARDISO_MKL_RT"):
        name = getattr(solver.libmkl, "_name", None)
        if name and os.path.isabs(name):
            os.environ["PYPARDISO_MKL_RT"] = name
    mkl = solver.libmkl
    for fn, value in ((mkl.MKL_Set_Dynamic, 0), (mkl.MKL_Set_Num_Threads, PARDISO_THREADS)):
        fn.argtypes, fn.restype = [ctypes.c_int], None
        fn(value)
    return solver


class Factorization:
    """A sparse SPD matrix factorised once with PARDISO (pypardiso, MKL), reused for solves.

    PARDISO's symmetric positive-definite mode (mtype 2) on the upper triangle takes
    about half the time of the unsymmetric mode.  With ``partial`` (a boolean mask or
    index array of unknowns s, the others i) the factorisation is PARDISO's Schur
    complement one (``iparm[35] = 2``): the unknowns i are factorised and the Schur
    complement ``S = A_ss − A_si A_ii⁻¹ A_is`` is returned dense, within about the time of
    the plain factorisation.  Its inverse is the condensation ``C = Sᵀ A⁻¹ S = S⁻¹`` onto
    the unknowns s (:meth:`schur_inverse`; block inversion of A), formed once by LAPACK's
    Cholesky inverse instead of one partial solve per unknown s; a solve with A is then
    PARDISO's forward substitution (phase 331), ``x_s = C y_s`` and its backward
    substitution (phase 333).
    """

    def __init__(self, A: sp.spmatrix, partial: np.ndarray | None = None):
        self.n = A.shape[0]
        self._A = sp.triu(A, format="csr")
        self._A.sort_indices()
        self._ia = (self._A.indptr + 1).astype(np.int32)  # PARDISO's 1-based CSR
        self._ja = (self._A.indices + 1).astype(np.int32)
        s = _pardiso_solver()
        # explicit parameters (iparm[0] = 1); the others are PARDISO's SPD defaults
        s.set_iparm(1, 1)
        s.set_iparm(2, 2)  # nested-dissection ordering (METIS)
        s.set_iparm(10, 8)  # pivot perturbation 1e-8
        s.set_iparm(11, 0)
        s.set_iparm(13, 0)
        self._solver = s
        self.partial_index: np.ndarray | None = None
        self._C: np.ndarray | None = None
        self.columns = 0  # right-hand sides solved (a work count)
        if partial is None:
            s.factorize(self._A)
            return
        idx = np.asarray(partial)
        idx = np.nonzero(idx)[0] if idx.dtype == bool else np.unique(idx)
        s.perm = np.zeros(self.n, dtype=np.int32)
        s.perm[idx] = 1
        s.set_iparm(36, 2)  # Schur complement with the partial factorisation
        S = np.zeros((idx.size, idx.size), order="F")
        self._call(12, np.zeros(self.n), S.reshape(-1, order="F"))
        self.partial_index = idx
        self._C = _spd_inverse(S)

    def solve(self, b: np.ndarray, *, block: int = 256) -> np.ndarray:
        """Solve for one right-hand side (n,) or many (n, m), ``block`` columns at a time."""
        b = np.asarray(b, dtype=float)
        self.columns += 1 if b.ndim == 1 else b.shape[1]
        if self._C is None:
            if b.ndim == 1:
                return self._solver.solve(self._A, b)
            out = np.empty_like(b)
            for start in range(0, b.shape[1], block):
                sl = slice(start, start + block)
                out[:, sl] = self._solver.solve(self._A, np.asfortranarray(b[:, sl]))
            return out
        B = np.asfortranarray(b.reshape(self.n, -1))
        Y = np.zeros_like(B)
        self._call(331, B, Y)
        idx = self.partial_index
        Y[idx] = self._C @ Y[idx]
        X = np.zeros_like(Y)
        self._call(333, Y, X)
        return X.reshape(b.shape)

    def schur_inverse(self) -> np.ndarray:
        """``C = Sᵀ A⁻¹ S`` for the unit vectors S of the ``partial`` unknowns (dense)."""
        if self._C is None:
            raise ValueError("factorisation was built without partial unknowns")
        return self._C

    def _call(self, phase: int, B: np.ndarray, X: np.ndarray) -> None:
        """PARDISO phase ``phase`` on the kept handle with the Fortran-ordered right-hand
        sides ``B`` (n, k) into ``X`` (for the Schur factorisation, X holds S)."""
        s = self._solver
        error = ctypes.c_int32(0)
        i32, f64 = ctypes.POINTER(ctypes.c_int32), ctypes.POINTER(ctypes.c_double)
        one = ctypes.c_int32(1)
        nrhs = 1 if B.ndim == 1 else B.shape[1]
        s._mkl_pardiso(s.pt.ctypes.data_as(ctypes.POINTER(s._pt_type[0])), ctypes.byref(one),
                       ctypes.byref(one), ctypes.byref(ctypes.c_int32(s.mtype)),
                       ctypes.byref(ctypes.c_int32(phase)), ctypes.byref(ctypes.c_int32(self.n)),
                       self._A.data.ctypes.data_as(f64), self._ia.ctypes.data_as(i32),
                       self._ja.ctypes.data_as(i32), s.perm.ctypes.data_as(i32),
                       ctypes.byref(ctypes.c_int32(nrhs)), s.iparm.ctypes.data_as(i32),
                       ctypes.byref(ctypes.c_int32(s.msglvl)), B.ctypes.data_as(f64),
                       X.ctypes.data_as(f64), ctypes.byref(error))
        if error.value != 0:
            raise FemError(f"PARDISO's phase {phase} failed with error {error.value}")

    def free(self) -> None:
        if self._C is None:
            self._solver.free_memory(everything=True)
        else:
            self._call(-1, np.zeros(self.n), np.zeros(self.n))
            self._C = None


def _spd_inverse(S: np.ndarray) -> np.ndarray:
    """The inverse of the SPD matrix ``S`` (Fortran order, overwritten) by LAPACK's
    Cholesky factorisation and inverse (potrf, potri), symmetric."""
    from scipy.linalg import lapack

    c, info = lapack.dpotrf(S, lower=1, overwrite_a=1, clean=0)
    if info != 0:
        raise FemError(f"the condensed stiffness is not positive definite (potrf {info})")
    C, info = lapack.dpotri(c, lower=1, overwrite_c=1)
    if info != 0:
        raise FemError(f"the condensed stiffness is singular (potri {info})")
    m, b = C.shape[0], 512
    for j0 in range(0, m, b):  # the upper triangle from the lower, a block at a time
        j1 = min(j0 + b, m)
        D = C[j0:j1, j0:j1]
        C[j0:j1, j0:j1] = np.tril(D) + np.tril(D, -1).T
        C[j0:j1, j1:] = C[j1:, j0:j1].T
    return C
